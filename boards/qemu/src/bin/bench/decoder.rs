//! `parse_byte`: the wire decoder ([`abtrack::wire::Decoder`]) per received
//! byte, on a stream of valid measurement frames. Integer code, the same in
//! every numeric type: its numeric label is `int`.

use core::hint::black_box;

use abtrack::wire::{Decoder, Encoder, MeasurementReport, Message, MAX_FRAME_LEN};

use crate::counter::Bench;
use crate::synth::Lcg;

const OPERATION: &str = "parse_byte";
use crate::numeric::INTEGER as NUMERIC;
/// Frames in the stream the calls cycle through.
const FRAMES: usize = 16;

#[inline(never)]
fn push_byte(decoder: &mut Decoder, byte: u8) -> bool {
    matches!(decoder.push(byte), Some(Ok(_)))
}

/// Measurement frames as a sensor sends them: Cartesian with and without
/// altitude, and polar, alternating; returns the bytes and their number.
fn stream() -> Option<([u8; FRAMES * MAX_FRAME_LEN], usize)> {
    let mut bytes = [0u8; FRAMES * MAX_FRAME_LEN];
    let mut len = 0;
    let mut rng = Lcg::new(7);
    let mut encoder = Encoder::new();
    for i in 0..FRAMES {
        let t = 1000 * i as u32;
        let report = match i % 3 {
            0 => MeasurementReport::cartesian_from_metres(
                t,
                1,
                rng.uniform(-50_000.0, 50_000.0),
                rng.uniform(-50_000.0, 50_000.0),
                Some(rng.uniform(1_000.0, 30_000.0)),
            ),
            1 => MeasurementReport::cartesian_from_metres(
                t,
                1,
                rng.uniform(-50_000.0, 50_000.0),
                rng.uniform(-50_000.0, 50_000.0),
                None,
            ),
            _ => MeasurementReport::polar_from_metres(
                t,
                2,
                rng.uniform(100.0, 50_000.0),
                rng.uniform(0.0, core::f64::consts::TAU),
                Some(rng.uniform(1_000.0, 30_000.0)),
            ),
        }
        .ok()?;
        len += encoder
            .encode(&Message::Measurement(report), bytes.get_mut(len..)?)
            .ok()?;
    }
    Some((bytes, len))
}

#[inline(never)]
pub fn parse_byte(bench: &mut Bench) {
    let Some((bytes, len)) = stream() else {
        bench.fail(NUMERIC, OPERATION, "frames not encodable");
        return;
    };
    let byte = |k: u32| bytes.get(k as usize % len).copied().unwrap_or(0);
    let mut decoder = Decoder::new();
    let mut frames = 0u32;
    bench.per_call(
        NUMERIC,
        OPERATION,
        |k| frames += u32::from(push_byte(&mut decoder, black_box(byte(k)))),
        |k| {
            black_box(black_box(byte(k)));
        },
    );
    let stats = decoder.stats();
    let clean = stats.crc_errors == 0
        && stats.unknown_type == 0
        && stats.bad_length == 0
        && stats.bad_field == 0
        && stats.bytes_skipped == 0;
    // At least every frame of the complete passes over the stream came out.
    let complete_passes = crate::CALLS as usize / len;
    bench.check(
        clean && complete_passes > 0 && frames as usize >= complete_passes * FRAMES,
        NUMERIC,
        OPERATION,
        "frames lost or refused",
    );
}
