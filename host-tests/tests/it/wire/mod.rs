//! The wire codec: frames, CRC, round trips and the streaming decoder.

mod codec;
