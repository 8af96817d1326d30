//! Writing a tool's output to stdout: a reader that closed the pipe early
//! (`replay … | head`) has taken all it wanted, so the tool ends quietly
//! with status 0; any other write error is reported with status 1.

use std::io::{self, ErrorKind, Write};
use std::process::ExitCode;

/// Writes `bytes` to `out` and flushes; `Ok(false)` when the reader closed
/// the pipe.
pub fn write_all_or_closed(out: &mut dyn Write, bytes: &[u8]) -> io::Result<bool> {
    match out.write_all(bytes).and_then(|()| out.flush()) {
        Ok(()) => Ok(true),
        Err(e) if e.kind() == ErrorKind::BrokenPipe => Ok(false),
        Err(e) => Err(e),
    }
}

/// Writes `bytes` to stdout: status 0 when written or when the pipe was
/// closed, 1 (with `tool: cannot write the output: …` on stderr) on any
/// other error.
pub fn write_stdout(tool: &str, bytes: &[u8]) -> ExitCode {
    match write_all_or_closed(&mut io::stdout().lock(), bytes) {
        Ok(_) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("{tool}: cannot write the output: {e}");
            ExitCode::FAILURE
        }
    }
}
