//! `Real::TWO` is `ONE + ONE` in every number type that implements `Real`.

use abtrack::num::fixed32::Ratio;
use abtrack::num::Real;
use abtrack::track::FixedVariance;
use abtrack::{Fix, ScaledScalar};

fn two_is_one_plus_one<R: Real>(name: &str) {
    let sum = R::ONE + R::ONE;
    assert!(
        R::TWO == sum,
        "{name}: TWO {:?} != ONE + ONE {:?}",
        R::TWO,
        sum
    );
    assert!(R::TWO.half() == R::ONE, "{name}: TWO / 2 != ONE");
}

#[test]
fn two_is_one_plus_one_in_every_format() {
    two_is_one_plus_one::<f32>("f32");
    two_is_one_plus_one::<f64>("f64");
    two_is_one_plus_one::<Fix>("Fix");
    two_is_one_plus_one::<Ratio>("fixed32::Ratio");
    two_is_one_plus_one::<ScaledScalar>("ScaledScalar");
    two_is_one_plus_one::<FixedVariance>("FixedVariance");
}
