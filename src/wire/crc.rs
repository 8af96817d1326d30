/// CRC-32C's polynomial 0x1EDC6F41, bit-reversed (the CRC is computed
/// least significant bit first).
const CRC32C_POLY_REFLECTED: u32 = 0x82F6_3B78;
/// Initial value (and final XOR) of CRC-32C.
pub const CRC_INIT: u32 = 0xFFFF_FFFF;

// Evaluated at compile time only: an index out of range or an overflow
// would fail the build, not the firmware.
#[allow(clippy::indexing_slicing, clippy::arithmetic_side_effects)]
const fn crc_table() -> [u32; 256] {
    let mut table = [0u32; 256];
    let mut i = 0;
    while i < 256 {
        let mut crc = i as u32;
        let mut bit = 0;
        while bit < 8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ CRC32C_POLY_REFLECTED
            } else {
                crc >> 1
            };
            bit += 1;
        }
        table[i] = crc;
        i += 1;
    }
    table
}

/// 1 KiB of flash buys one table lookup per byte instead of eight shifts
/// in the receive interrupt.
static CRC_TABLE: [u32; 256] = crc_table();

/// Continues a CRC-32C over `data` from the running register `crc` (start
/// from [`CRC_INIT`]; the final value is `!crc`, see [`crc32c`]).
pub fn crc32c_update(mut crc: u32, data: &[u8]) -> u32 {
    for &b in data {
        // The index is a u8: always inside the 256-entry table.
        let index = usize::from((crc as u8) ^ b);
        crc = (crc >> 8) ^ CRC_TABLE.get(index).copied().unwrap_or(0);
    }
    crc
}

/// CRC-32C (CRC-32/ISCSI: reflected poly 0x82F63B78, init and final XOR
/// 0xFFFFFFFF) of `data`; 0xE3069283 for `b"123456789"`.
pub fn crc32c(data: &[u8]) -> u32 {
    !crc32c_update(CRC_INIT, data)
}
