//! The host tools' CSV reader (`abtrack_csv_input::read_recording`,
//! what `replay` reads) on arbitrary bytes, with each time order and angle
//! unit the options allow.
//!
//! Properties (beyond "never panics"):
//! - an accepted file: every row's line number lies in the file and never
//!   goes back (a lone carriage return ends a row without a new `\n` line,
//!   so two rows can share one); every value is finite and inside the envelope
//!   (`abtrack::envelope`, the firmware's limits), times too (rows out of
//!   time order are read: the runners skip and count them);
//! - a refusal names a line of the file (1 ..= its line count + 1) and
//!   echoes at most `ECHO_CHARS` characters of a bad field.

use abtrack::envelope;
use abtrack_csv_input::{
    read_recording, AngleUnit, CsvError, ReadOptions, Recording, TimeOrder, ECHO_CHARS,
};

fn check_refusal(e: &CsvError, lines: usize) {
    let line = match e {
        CsvError::Malformed { line, .. } | CsvError::FieldCount { line, .. } => Some(*line),
        CsvError::Field { line, text, .. } => {
            // The echo may end in '…' when it cuts the field.
            assert!(text.chars().count() <= ECHO_CHARS + 1, "echo of {text:?}");
            Some(*line)
        }
        _ => None,
    };
    if let Some(line) = line {
        assert!((1..=lines + 1).contains(&line), "line {line} of {lines}");
    }
}

fn check_times(times: impl Iterator<Item = f64>) {
    for t in times {
        assert!(envelope::TIME_S.contains(t), "t = {t}");
    }
}

fn check_lines(lines_of_rows: impl Iterator<Item = usize>, lines: usize) {
    let mut previous = 0;
    for line in lines_of_rows {
        assert!(
            line >= previous.max(1) && line <= lines + 1,
            "row line {line} after {previous}"
        );
        previous = line;
    }
}

/// One input of the fuzz target.
pub fn check(data: &[u8]) {
    let Some((&selector, bytes)) = data.split_first() else {
        return;
    };
    let options = ReadOptions {
        times: if selector & 1 == 0 {
            TimeOrder::Increasing
        } else {
            TimeOrder::Scans
        },
        azimuth_unit: if selector & 2 == 0 {
            AngleUnit::Radians
        } else {
            AngleUnit::Degrees
        },
    };
    let lines = bytes.iter().filter(|&&b| b == b'\n').count() + 1;
    match read_recording(bytes, options) {
        Err(e) => check_refusal(&e, lines),
        Ok(Recording::Cartesian(m)) => {
            check_lines(m.rows.iter().map(|r| r.line), lines);
            check_times(m.rows.iter().map(|r| r.t));
            for r in &m.rows {
                for &z in r.z.iter().take(m.dims) {
                    assert!(envelope::POSITION_M.contains(z), "position {z}");
                }
                if let Some(alt) = r.alt {
                    assert!(envelope::ALTITUDE_FT.contains(alt), "alt {alt}");
                }
            }
        }
        Ok(Recording::RangeAzimuth(m)) => {
            check_lines(m.rows.iter().map(|r| r.line), lines);
            check_times(m.rows.iter().map(|r| r.t));
            for r in &m.rows {
                assert!(envelope::RANGE_M.contains(r.range), "range {}", r.range);
                assert!(
                    envelope::AZIMUTH_RAD.contains(r.azimuth),
                    "azimuth {}",
                    r.azimuth
                );
                if let Some(alt) = r.alt {
                    assert!(envelope::ALTITUDE_FT.contains(alt), "alt {alt}");
                }
            }
        }
    }
}
