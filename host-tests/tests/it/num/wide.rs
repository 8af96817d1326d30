//! The Cortex-M0's products from 16×16 partial products
//! (`abtrack::num::wide`) against the plain 64-bit product: exact for every
//! pair of words.

use abtrack::num::wide::{wide_mul_by_halves, wide_mul_unsigned_by_halves};
use proptest::prelude::*;

/// The words where a carry or a sign is at its limit.
const EDGES: [u32; 10] = [
    0,
    1,
    0xFFFF,
    0x1_0000,
    0x7FFF_FFFF,
    0x8000_0000,
    0x8000_0001,
    0xFFFF_0000,
    0xFFFF_FFFE,
    0xFFFF_FFFF,
];

#[test]
fn partial_products_are_exact_at_the_edges() {
    for &a in &EDGES {
        for &b in &EDGES {
            assert_eq!(
                wide_mul_unsigned_by_halves(a, b),
                u64::from(a) * u64::from(b),
                "{a:#x} · {b:#x}"
            );
            let (sa, sb) = (a as i32, b as i32);
            assert_eq!(
                wide_mul_by_halves(sa, sb),
                i64::from(sa) * i64::from(sb),
                "{sa} · {sb}"
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4000, ..ProptestConfig::default() })]

    #[test]
    fn partial_products_are_exact(a in any::<u32>(), b in any::<u32>()) {
        prop_assert_eq!(wide_mul_unsigned_by_halves(a, b), u64::from(a) * u64::from(b));
        let (sa, sb) = (a as i32, b as i32);
        prop_assert_eq!(wide_mul_by_halves(sa, sb), i64::from(sa) * i64::from(sb));
    }
}
