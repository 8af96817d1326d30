//! Exact 32×32→64 products, the one multiply of the fast fixed point's
//! formats ([`super::fixed32`], [`super::scaled`]) and of the track table's
//! fixed-point gate.
//!
//! On ARMv6-M (Cortex-M0: no `smull`/`umull`; recognised on stable Rust by
//! its lack of 32-bit atomics) LLVM calls the general 64×64 `__aeabi_lmul`
//! for a product of two widened words; four 16×16 partial products inline
//! ([`wide_mul_by_halves`], [`wide_mul_unsigned_by_halves`]) cost about half
//! of it. Elsewhere the plain product is one instruction.

/// Whether this target forms products from 16×16 partial products.
const BY_HALVES: bool = cfg!(all(target_arch = "arm", not(target_has_atomic = "32")));

/// The exact product of two signed words.
#[inline(always)]
pub fn wide_mul(a: i32, b: i32) -> i64 {
    if BY_HALVES {
        wide_mul_by_halves(a, b)
    } else {
        // |a·b| ≤ 2⁶²: exact.
        i64::from(a).wrapping_mul(i64::from(b))
    }
}

/// The exact product of two unsigned words.
#[inline(always)]
pub fn wide_mul_unsigned(a: u32, b: u32) -> u64 {
    if BY_HALVES {
        wide_mul_unsigned_by_halves(a, b)
    } else {
        // Below 2⁶⁴: exact.
        u64::from(a).wrapping_mul(u64::from(b))
    }
}

/// [`wide_mul`] from four 16×16 partial products (what the Cortex-M0
/// runs; public so that the host tests compare it with the plain product).
#[inline(always)]
pub fn wide_mul_by_halves(a: i32, b: i32) -> i64 {
    // a = ah·2¹⁶ + al with ah signed (|ah| ≤ 2¹⁵) and 0 ≤ al < 2¹⁶, so
    // every partial product fits its word: |ah·bh| ≤ 2³⁰, |ah·bl| < 2³¹,
    // al·bl < 2³² (unsigned).
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    let high = ah.wrapping_mul(bh);
    let middle = i64::from(ah.wrapping_mul(bl)).wrapping_add(i64::from(al.wrapping_mul(bh)));
    let low = (al as u32).wrapping_mul(bl as u32);
    (i64::from(high) << 32)
        .wrapping_add(middle << 16)
        .wrapping_add(i64::from(low))
}

/// [`wide_mul_unsigned`] from four 16×16 partial products (as
/// [`wide_mul_by_halves`]).
#[inline(always)]
pub fn wide_mul_unsigned_by_halves(a: u32, b: u32) -> u64 {
    // Each partial product is below 2³², the middle sum below 2³³.
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    let middle = u64::from(ah.wrapping_mul(bl)).wrapping_add(u64::from(al.wrapping_mul(bh)));
    (u64::from(ah.wrapping_mul(bh)) << 32)
        .wrapping_add(middle << 16)
        .wrapping_add(u64::from(al.wrapping_mul(bl)))
}
