//! The wire frame decoder (`abtrack::wire::Decoder`) on arbitrary bytes, as
//! the receive interrupt feeds it, then the line going idle.
//!
//! Properties (beyond "never panics"):
//! - every byte is accounted for: bytes pushed = bytes of the frames
//!   returned + bytes skipped + bytes held (none once the line is idle);
//! - every candidate frame is counted once: frames returned = `accepted`,
//!   each error returned = its counter (CRC, unknown type, bad length, bad
//!   field, out of envelope, truncated), and `frames` = their sum;
//! - a frame returned is well formed: emitted again (with any sequence
//!   number), it is the same message.

use abtrack::wire::{Decoder, Message, WireError, MAX_FRAME_LEN};

#[derive(Default)]
struct Returned {
    frames: u32,
    frame_bytes: u64,
    crc_errors: u32,
    unknown_type: u32,
    bad_length: u32,
    bad_field: u32,
    out_of_envelope: u32,
    truncated: u32,
}

impl Returned {
    fn take(&mut self, result: Result<Message, WireError>) {
        match result {
            Ok(message) => {
                self.frames += 1;
                self.frame_bytes += message.buffer_len() as u64;
                let mut buffer = [0u8; MAX_FRAME_LEN];
                let len = message
                    .emit(0, &mut buffer)
                    .expect("a decoded message emits into a frame buffer");
                let again = Message::parse_bytes(&buffer[..len])
                    .expect("a decoded message, emitted, parses");
                assert_eq!(again, message, "emit/parse round trip");
            }
            Err(WireError::Checksum) => self.crc_errors += 1,
            Err(WireError::UnknownType) => self.unknown_type += 1,
            Err(WireError::BadLength) => self.bad_length += 1,
            Err(WireError::BadField) => self.bad_field += 1,
            Err(WireError::OutOfEnvelope) => self.out_of_envelope += 1,
            Err(WireError::Truncated) => self.truncated += 1,
            Err(e) => panic!("the decoder returned {e:?}, which it never should"),
        }
    }
}

/// One input of the fuzz target.
pub fn check(bytes: &[u8]) {
    let mut decoder = Decoder::new();
    let mut returned = Returned::default();
    for (i, &byte) in bytes.iter().enumerate() {
        if let Some(result) = decoder.push(byte) {
            returned.take(result);
        }
        // Pending results come out with poll, as the interrupt does.
        while let Some(result) = decoder.poll() {
            returned.take(result);
        }
        let s = decoder.stats();
        assert_eq!(
            (i as u64) + 1,
            returned.frame_bytes + u64::from(s.bytes_skipped) + decoder.held() as u64,
            "bytes pushed = frame bytes + skipped + held"
        );
    }
    while let Some(result) = decoder.line_idle() {
        returned.take(result);
    }
    assert_eq!(decoder.held(), 0, "nothing held once the line is idle");
    let s = *decoder.stats();
    assert_eq!(
        bytes.len() as u64,
        returned.frame_bytes + u64::from(s.bytes_skipped),
        "bytes pushed = frame bytes + skipped"
    );
    assert_eq!(s.accepted, returned.frames, "accepted frames");
    assert_eq!(
        s.frames,
        returned.frames
            + returned.crc_errors
            + returned.unknown_type
            + returned.bad_length
            + returned.bad_field
            + returned.out_of_envelope
            + returned.truncated,
        "every candidate decided once"
    );
    assert_eq!(s.crc_errors, returned.crc_errors, "CRC errors");
    assert_eq!(s.unknown_type, returned.unknown_type, "unknown type");
    assert_eq!(s.bad_length, returned.bad_length, "bad length");
    assert_eq!(s.bad_field, returned.bad_field, "bad field");
    assert_eq!(
        s.out_of_envelope, returned.out_of_envelope,
        "out of envelope"
    );
    assert_eq!(s.truncated, returned.truncated, "truncated");
}
