//! The number traits: [`Quantity`] (one physical quantity's value and its
//! report to the hot path's guard), [`Real`] (a dimensionless number with
//! ×, ÷, √), [`Numeric`] (a number system: one type per quantity, the
//! operations between them and the track table's few extra operations),
//! [`AddProduct`] (the hot path's `q + a·b`) and [`Scalar`] (one type for
//! every quantity: `f64`, `f32`, Q32.32, [`super::ScaledScalar`]). A fixed
//! point system can give each quantity its own format (see
//! `docs/numerics-fixed-point.md`); a [`Scalar`] implements [`Numeric`]
//! with every quantity the type itself.
//!
//! # The guarded hot path
//!
//! The per-update arithmetic of the filters goes through [`AddProduct`] and
//! [`Quantity::sub_guarded`] with the number system's guard
//! ([`Numeric::Guard`]): `q + a·b` and `a − b`, each rounded once. The guard
//! records what the results need to be trusted, so the filter checks
//! validity once ([`Numeric::passed`]), after computing everything:
//!
//! * floats: NaN and ±∞ are sticky, so checking the outputs checks every
//!   intermediate. `f64` sums the outputs ([`Quantity::check_output`]) and
//!   the guard passes when `s − s == 0`, true exactly when the sum is
//!   finite: it refuses every update with a non-finite output, and accepts
//!   every update whose outputs are all below `MAX/8` (a finite sum of at
//!   most eight of them cannot overflow). `f32` refuses exactly the updates
//!   with a NaN or infinite output, with an integer test of each output's
//!   exponent field on the M0/M3 (where a sum would cost a library call per
//!   output) and `check + 0·output` on the M4F's FPU ([`super::f32_check`]);
//! * Q32.32 ([`crate::Fix`]): a sum of valid values near 2³¹ could
//!   saturate, so its guard keeps zero while every output is valid and a
//!   sentinel otherwise ([`Scalar::accumulate_check`]);
//! * the fast fixed point ([`super::fixed32`]): products and sums are formed
//!   in 64 bits and narrowed once; a result that does not fit its format,
//!   or an input that is a saturation sentinel ([`Quantity::check_input`]),
//!   raises the guard's flag. Nothing is sticky there, which is why every
//!   operation reports to the guard.

use core::fmt;
use core::ops::{Add, Div, Mul, Neg, Sub};

use super::{NumError, Scalar};

/// Not a number trait: the cfg alias that lets the number types carry the
/// bound the derived `defmt::Format` impls need. Private, so not nameable
/// outside the crate (a sealed helper).
pub(crate) mod sealed {
    /// `defmt::Format` when the `defmt` feature is on, nothing otherwise.
    #[cfg(feature = "defmt")]
    pub trait MaybeFormat: defmt::Format {}
    #[cfg(feature = "defmt")]
    impl<T: defmt::Format> MaybeFormat for T {}
    /// See the `defmt` variant.
    #[cfg(not(feature = "defmt"))]
    pub trait MaybeFormat {}
    #[cfg(not(feature = "defmt"))]
    impl<T> MaybeFormat for T {}
}
use sealed::MaybeFormat;

/// A value of one physical quantity in one number system (a position, a
/// speed, a gain, ...). Arithmetic never panics and never wraps: a result
/// outside the representable range is an invalid value ([`Self::is_valid`]),
/// which propagates through later operators (it is sticky).
pub trait Quantity:
    Copy
    + Default
    + PartialEq
    + PartialOrd
    + fmt::Debug
    + Send
    + Sync
    + 'static
    + MaybeFormat
    + Add<Output = Self>
    + Sub<Output = Self>
    + Neg<Output = Self>
{
    /// Zero of this quantity.
    const ZERO: Self;

    /// Rounding model of this quantity, used by the error budget
    /// ([`crate::budget`]): a result rounded to this quantity errs by at most
    /// `UNIT_ROUNDOFF·|exact| + ABS_RESOLUTION`, a conversion from `f64` by at
    /// most `UNIT_ROUNDOFF·|v| + ABS_RESOLUTION/2`, and a sum of two values of
    /// this quantity by at most `UNIT_ROUNDOFF·|exact|`. Floats: unit
    /// roundoff 2⁻ᵖ (p = significand bits) and the smallest subnormal;
    /// fixed point: exact `+ −`, one step per `× ÷`.
    const UNIT_ROUNDOFF: f64;
    /// See [`Self::UNIT_ROUNDOFF`].
    const ABS_RESOLUTION: f64;
    /// Whether the rounding is relative over a wide range (floats, the
    /// [`super::scaled::Scaled`] formats: `UNIT_ROUNDOFF` > 0), so products
    /// of large quantities neither overflow nor lose resolution and a
    /// reciprocal keeps its digits; false for the fixed formats (Q32.32,
    /// `Fixed32`'s words), whose rounding is absolute. A constant: tests
    /// on it are compiled out.
    const RELATIVE_PRECISION: bool = Self::UNIT_ROUNDOFF > 0.0;

    /// The hot path's validity check of the number system this quantity
    /// belongs to (module docs): [`ScalarGuard`] for a [`Scalar`],
    /// [`super::fixed32::Fixed32Guard`] for the fast fixed point.
    type Guard: Default + fmt::Debug;

    /// Converts an outside value (SI units), refusing NaN, infinities and
    /// values beyond the representable range. Use this at the edges (wire,
    /// CSV, constructors).
    fn try_from_f64(v: f64) -> Result<Self, NumError>;

    /// Converts a constant, rounding to nearest; out-of-range values become
    /// invalid values. Meant for literals such as 0.5 in generic code.
    fn from_f64_lossy(v: f64) -> Self;

    /// A time in milliseconds as seconds, `ms / 1000` rounded to nearest:
    /// by default through `f64`; `f32` divides in `f32` (the same value for
    /// every `ms` ≤ 2²⁴), the [`super::scaled::Scaled`] formats divide
    /// their integers and the `Fixed32` quantities scale and divide theirs,
    /// so no double-precision library call on a core without a
    /// double-precision FPU.
    #[inline]
    fn seconds_from_ms(ms: u32) -> Self {
        Self::from_f64_lossy(f64::from(ms) / 1000.0)
    }

    /// The value in SI units (exact for every format; an invalid value
    /// gives ±∞ or NaN).
    fn to_f64(self) -> f64;

    /// False for NaN, ±∞ and the fixed-point saturation sentinels.
    fn is_valid(self) -> bool;

    /// [`Self::is_valid`] and > 0 (the filters' test of an interval; `f32`
    /// overrides it with one integer compare).
    #[inline]
    fn is_valid_and_positive(self) -> bool {
        self.is_valid() && self > Self::ZERO
    }

    /// Absolute value (invalid stays invalid).
    fn abs(self) -> Self;

    /// Half the value (exact in floating formats, rounded to nearest in
    /// fixed formats).
    fn half(self) -> Self;

    /// The smaller of two valid values.
    #[inline]
    fn min_of(self, other: Self) -> Self {
        if other < self {
            other
        } else {
            self
        }
    }

    /// The larger of two valid values.
    #[inline]
    fn max_of(self, other: Self) -> Self {
        if other > self {
            other
        } else {
            self
        }
    }

    /// Reports an input of the computation (a measurement) to the guard:
    /// fixed point flags a saturation sentinel; floats need nothing (every
    /// input reaches an output, and NaN/∞ are sticky).
    fn check_input(self, guard: &mut Self::Guard);

    /// Reports a result that will be stored or returned: floats fold it
    /// into the guard's check ([`Scalar::accumulate_check`]); fixed point
    /// flags a sentinel (its operations report overflow themselves).
    fn check_output(self, guard: &mut Self::Guard);

    /// `self − b`; marks `guard` if the result does not fit.
    fn sub_guarded(self, b: Self, guard: &mut Self::Guard) -> Self;
}

/// A dimensionless real number with a wide range: gains, ratios, sines.
pub trait Real: Quantity + Mul<Output = Self> + Div<Output = Self> {
    /// One.
    const ONE: Self;

    /// Two: `ONE + ONE`, exact in every format, without the sum (a call
    /// in the software formats).
    const TWO: Self;

    /// `numerator / denominator`, rounded once (invalid for a zero
    /// denominator). Used for the gain formulas of integer counts. By
    /// default through `f64`; `f32` divides in `f32` when both are exact
    /// there (≤ 2²⁴), the same value, since `f64` rounding first is
    /// innocuous for a quotient (53 ≥ 2·24 + 2 bits).
    #[inline]
    fn from_ratio(numerator: u64, denominator: u64) -> Self {
        if denominator == 0 {
            return Self::from_f64_lossy(f64::NAN);
        }
        Self::from_f64_lossy(numerator as f64 / denominator as f64)
    }

    /// Square root; invalid for a negative argument.
    fn sqrt(self) -> Self;

    /// √(a² + b²) without forming a² (positions up to 4·10⁵ m would
    /// overflow Q32.32 when squared): the larger magnitude times
    /// √(1 + k²), k ≤ 1. An invalid argument gives an invalid result (the
    /// comparisons are arranged so NaN and the saturation sentinels
    /// propagate). The [`super::scaled::Scaled`] formats override it with
    /// one root of the squared mantissas.
    fn hypot(self, other: Self) -> Self {
        let (a, b) = (self.abs(), other.abs());
        let (large, small) = if a >= b { (a, b) } else { (b, a) };
        if large == Self::ZERO {
            return small; // zero, or an invalid value that propagates
        }
        let k = small / large;
        large * (Self::ONE + k * k).sqrt()
    }

    /// √(a² + b² + c²) with one square root (two hypots would take two):
    /// the largest magnitude times √(1 + k₁² + k₂²), k₁, k₂ ≤ 1, so nothing
    /// is squared beyond 3. Invalid arguments give an invalid result, as in
    /// [`Real::hypot`]; the [`super::scaled::Scaled`] formats override it
    /// with one root of the squared mantissas.
    #[inline]
    fn hypot3(self, b: Self, c: Self) -> Self {
        let (a, b, c) = (self.abs(), b.abs(), c.abs());
        if !(a.is_valid() && b.is_valid() && c.is_valid()) {
            return a + b + c;
        }
        let (large, m1, m2) = if a >= b && a >= c {
            (a, b, c)
        } else if b >= c {
            (b, a, c)
        } else {
            (c, a, b)
        };
        if large == Self::ZERO {
            return large;
        }
        let (k1, k2) = (m1 / large, m2 / large);
        large * (Self::ONE + k1 * k1 + k2 * k2).sqrt()
    }

    /// Whether every value is valid: [`Quantity::is_valid`] of each, or a
    /// format's cheaper running check (a [`Scalar`]'s
    /// [`Scalar::accumulate_check`]).
    #[inline(always)]
    fn all_valid<const K: usize>(values: [Self; K]) -> bool {
        values.iter().all(|v| v.is_valid())
    }
}

/// The corners (min, max) of `center` ± (ρ + ρ/2⁴), ρ = `reach`, the
/// sixteenth formed by four halvings ([`Numeric::circle_bounds`]).
#[inline(always)]
pub(crate) fn circle_box<S: Numeric>(
    center: [S::Length; 2],
    reach: S::Length,
) -> ([S::Length; 2], [S::Length; 2]) {
    let half = reach + reach.half().half().half().half();
    (
        [center[0] - half, center[1] - half],
        [center[0] + half, center[1] + half],
    )
}

/// `self + a·b`, rounded once, with overflow reported to the guard.
pub trait AddProduct<A, B>: Quantity {
    /// `self + a·b`; marks `guard` if the result does not fit.
    fn add_product(self, a: A, b: B, guard: &mut Self::Guard) -> Self;
}

/// A number system: one type per quantity the filters use, the operations
/// between them (the bounds below are the whole algebra a generic filter
/// may use), and the few operations a track table needs beyond them.
///
/// Every [`Scalar`] (`f64`, `f32`, Q32.32, [`super::ScaledScalar`])
/// implements it with every quantity the type itself; the fast fixed point
/// ([`super::fixed32::Fixed32`]) with a format per quantity.
///
/// The track table's operations:
///
/// * the gate test of a circle and its cost, the squared distance
///   normalised by the radius, quantised to `u16` (the solver's currency):
///   floats multiply the squared distance by 1/r², Q32.32 the offsets by
///   1/r (its squares of metres would overflow), each formed once per
///   track; `Fixed32` compares the squared offsets with the squared
///   radius exactly in 64-bit integers and divides once per gated pair. A
///   gate given by its squared radius σ²·F ([`Numeric::scaled_circle`])
///   needs no square root in floats: the box around it takes an upper bound
///   of √(σ²·F) from the float's bits (within 6.1 %);
/// * polar geometry (projecting range and azimuth; range/azimuth windows)
///   runs in a [`Scalar`] ([`Numeric::Polar`]): the type itself, or `f32`
///   for `Fixed32`, which has no sine or arctangent (in software on its
///   cores, library calls rather than Q32.32's inlined 128-bit arithmetic,
///   13 KB less flash on the micro:bit; 24 significant bits: 6 mm at
///   100 km);
/// * the covariance that sizes a gate ([`crate::track::ErrorVariance`], in
///   units of σ²) is kept in [`Numeric::Variance`]: the ratio type, except
///   in `Fixed32`, whose ratios (a mantissa and an exponent in software)
///   cost about 100 instructions an operation on the Cortex-M3: there it
///   is [`crate::track::FixedVariance`], a 32-bit I16F16 word (its
///   envelope: intervals of at least 8 ms, `docs/track-table.md`).
pub trait Numeric:
    Copy + Default + fmt::Debug + PartialEq + Send + Sync + 'static + MaybeFormat
{
    /// Short name for reports: "f64", "f32", "q32", "scaled", "fixed".
    const NAME: &'static str;

    /// Whether [`AddProduct`] forms `q + a·b` in a wider word and checks
    /// only the sum (the fast fixed point), rather than rounding and
    /// checking the product on its own (the sticky operators): the error
    /// budget's range checks follow it.
    const FUSED_PRODUCTS: bool = false;

    /// Metres (feet where a tracker works in feet): positions, residuals.
    /// `From<Ratio>` reads a number of metres (invalid beyond the range).
    type Length: Quantity<Guard = Self::Guard>
        + From<Self::Ratio>
        + AddProduct<Self::Speed, Self::Interval>
        + AddProduct<Self::Acceleration, Self::IntervalSquared>
        + AddProduct<Self::Gain, Self::Length>
        + Div<Self::Interval, Output = Self::Speed>
        + Div<Self::Length, Output = Self::Ratio>;
    /// Metres per second. `From<Ratio>` reads a number of m/s (invalid
    /// beyond the range).
    type Speed: Quantity<Guard = Self::Guard>
        + From<Self::Ratio>
        + AddProduct<Self::Acceleration, Self::Interval>
        + AddProduct<Self::Rate, Self::Length>
        + Mul<Self::Interval, Output = Self::Length>;
    /// Metres per second².
    type Acceleration: Quantity<Guard = Self::Guard>
        + AddProduct<Self::RateSquared, Self::Length>
        + Mul<Self::Interval, Output = Self::Speed>
        + Mul<Self::IntervalSquared, Output = Self::Length>;
    /// Seconds: the interval T between updates.
    type Interval: Quantity<Guard = Self::Guard>
        + Mul<Self::Interval, Output = Self::IntervalSquared>;
    /// Seconds², e.g. T²/2 of the αβγ prediction.
    type IntervalSquared: Quantity<Guard = Self::Guard>;
    /// Dimensionless: the gains α, β, γ and ratios. `From<Length>` gives a
    /// length's number of metres (for sums of squares, which would
    /// overflow a length format).
    type Ratio: Real<Guard = Self::Guard>
        + From<Self::Length>
        + From<Self::Interval>
        + Mul<Self::Length, Output = Self::Length>
        + Mul<Self::Speed, Output = Self::Speed>
        + Div<Self::Interval, Output = Self::Rate>
        + Div<Self::IntervalSquared, Output = Self::RateSquared>;
    /// A gain of the per-update path, |g| < 8, where a fixed format is
    /// enough (the smoothing gain α, in (0, 2)); [`Self::gain`] converts.
    type Gain: Quantity<Guard = Self::Guard>;
    /// Per second: the velocity gain β/T. `From<Ratio>` reads a ratio
    /// computed in 1/s (a covariance's velocity gain) as a rate.
    type Rate: Quantity<Guard = Self::Guard>
        + From<Self::Ratio>
        + Mul<Self::Length, Output = Self::Speed>;
    /// Per second²: the acceleration gain γ/(2T²).
    type RateSquared: Quantity<Guard = Self::Guard> + Mul<Self::Length, Output = Self::Acceleration>;
    /// Radians: azimuths.
    type Angle: Quantity<Guard = Self::Guard>;
    /// The hot path's validity check (module docs), the one of every
    /// quantity above.
    type Guard: Default + fmt::Debug;

    /// This number system's one type for every quantity: the type itself
    /// for a [`Scalar`], the wide format [`super::ScaledScalar`] for `Fixed32`.
    type Wide: Scalar;
    /// The scalar type of the track table's polar geometry.
    type Polar: Scalar;
    /// What a circular gate keeps to test measurements (the reciprocal of
    /// its radius, for floats and Q32.32).
    type CircleScale: Copy + fmt::Debug + PartialEq;
    /// The number type of the gate's covariance bookkeeping.
    type Variance: Real<Guard = Self::Guard>;
    /// What the pre-gate's grid keeps per axis to map a coordinate's offset
    /// from the measurements' minimum to its cell.
    type GridScale: Copy + fmt::Debug;
    /// A scale that puts every offset in cell 0.
    const GRID_SCALE_ZERO: Self::GridScale;

    /// True when every value reported to `guard` is valid (module docs).
    fn passed(guard: &Self::Guard) -> bool;

    /// (sin θ, cos θ).
    fn sin_cos(theta: Self::Angle) -> (Self::Ratio, Self::Ratio);

    /// The azimuth of (x, y), clockwise from the y axis, in [0, 2π).
    fn azimuth(x: Self::Length, y: Self::Length) -> Self::Angle;

    /// A [`Self::Ratio`] as a [`Self::Gain`] (invalid beyond the gain's
    /// range).
    fn gain(r: Self::Ratio) -> Self::Gain;

    /// √(a² + b²), never overflowing on the way (invalid arguments give an
    /// invalid result).
    fn hypot(a: Self::Length, b: Self::Length) -> Self::Length;

    /// The circle's scale for `radius` (> 0), or `None` if it cannot be
    /// formed.
    fn circle_scale(radius: Self::Length) -> Option<Self::CircleScale>;

    /// The circle of radius σ·√`factor` (σ = `sigma` > 0, `factor` > 0):
    /// a half-width at least the radius (its reach: the pre-gate's box and
    /// the first test of each offset) and its scale, or `None` if it cannot
    /// be formed. By default the radius itself and [`Self::circle_scale`];
    /// floats form r² and bound √r² without a square root.
    fn scaled_circle(
        sigma: Self::Length,
        factor: Self::Ratio,
    ) -> Option<(Self::Length, Self::CircleScale)> {
        let radius = factor.sqrt() * sigma;
        Some((radius, Self::circle_scale(radius)?))
    }

    /// The corners (min, max) of the box `center` ± ρ·(1 + 2⁻⁴) around a
    /// circle of reach ρ = `reach` ([`crate::track::GateRegion::bounds`]),
    /// the sixteenth formed by four halvings.
    #[inline]
    fn circle_bounds(
        center: [Self::Length; 2],
        reach: Self::Length,
    ) -> ([Self::Length; 2], [Self::Length; 2]) {
        circle_box::<Self>(center, reach)
    }

    /// The radius of a circle of reach `reach` and scale `scale`: by
    /// default the reach itself.
    fn circle_radius(reach: Self::Length, _scale: Self::CircleScale) -> Self::Length {
        reach
    }

    /// The cost `round((dx² + dy²)/r²·MAX_COST)` of a measurement offset
    /// (dx, dy) from the centre of a circle of reach `reach` (at least its
    /// radius r) and scale `scale`, or `None` if it lies outside (or an
    /// operand is invalid).
    fn circle_cost(
        dx: Self::Length,
        dy: Self::Length,
        reach: Self::Length,
        scale: Self::CircleScale,
    ) -> Option<u16>;

    /// [`Self::circle_cost`] of the measurement at `z` in the circle
    /// around `center`: by default of the offsets `z` − `center`.
    #[inline]
    fn circle_cost_at(
        z: [Self::Length; 2],
        center: [Self::Length; 2],
        reach: Self::Length,
        scale: Self::CircleScale,
    ) -> Option<u16> {
        Self::circle_cost(z[0] - center[0], z[1] - center[1], reach, scale)
    }

    /// The scale that spreads `min ..= max` over `cells` cells (about
    /// equal widths); everything in cell 0 if it cannot be formed.
    fn grid_scale(min: Self::Length, max: Self::Length, cells: u16) -> Self::GridScale;

    /// The cell of a valid `v` over `min ..= max` (below `min`, cell 0;
    /// the caller caps the result at the last cell): non-decreasing in `v`,
    /// rounding included, so that a box's cells hold every point inside it.
    fn grid_cell(
        v: Self::Length,
        min: Self::Length,
        max: Self::Length,
        scale: Self::GridScale,
    ) -> u32;

    /// A length in the polar scalar (exact).
    fn length_to_polar(v: Self::Length) -> Self::Polar;
    /// Back, rounded to the length's resolution (invalid if out of range).
    fn length_from_polar(v: Self::Polar) -> Self::Length;
    /// A ratio (an angle in radians) in the polar scalar.
    fn ratio_to_polar(v: Self::Ratio) -> Self::Polar;
    /// Back (invalid if out of range).
    fn ratio_from_polar(v: Self::Polar) -> Self::Ratio;

    /// A ratio as a covariance number (saturating).
    fn to_variance(r: Self::Ratio) -> Self::Variance;
    /// Back.
    fn from_variance(v: Self::Variance) -> Self::Ratio;
}

// ---------------------------------------------------------------------------
// f64, f32, Q32.32 and ScaledScalar: every quantity is the scalar type itself.

/// The guard of a [`Scalar`]: a running check of the outputs, folded
/// by [`Scalar::accumulate_check`] (their sum, or for `f32` the check word
/// of [`super::f32_check`]; module docs).
#[derive(Debug, Clone, Copy, Default)]
pub struct ScalarGuard<S> {
    check: S,
}

impl<S: Scalar> ScalarGuard<S> {
    /// True when every value reported to the guard is valid
    /// ([`Scalar::check_passed`]: for the sum, `s − s == 0` exactly when `s`
    /// is finite; module docs).
    #[inline]
    pub fn passed(&self) -> bool {
        S::check_passed(self.check)
    }
}

impl<S: Scalar> AddProduct<S, S> for S {
    #[inline]
    fn add_product(self, a: S, b: S, _guard: &mut ScalarGuard<S>) -> S {
        self + a * b
    }
}

/// The [`Quantity`] items every [`Scalar`] shares (inside its
/// `impl Quantity` block): its guard, the guard's reports, and `half`.
macro_rules! scalar_quantity_items {
    () => {
        type Guard = $crate::num::numeric::ScalarGuard<Self>;

        #[inline]
        fn half(self) -> Self {
            core::ops::Mul::mul(self, <Self as $crate::num::Quantity>::from_f64_lossy(0.5))
        }
        #[inline]
        fn check_input(self, _guard: &mut Self::Guard) {}
        #[inline]
        fn check_output(self, guard: &mut Self::Guard) {
            guard.fold(self);
        }
        #[inline]
        fn sub_guarded(self, b: Self, _guard: &mut Self::Guard) -> Self {
            core::ops::Sub::sub(self, b)
        }
    };
}
pub(crate) use scalar_quantity_items;

/// The [`Real`] item every [`Scalar`] shares: [`Real::all_valid`] as one
/// running check over the values ([`Scalar::accumulate_check`]).
macro_rules! scalar_real_items {
    () => {
        #[inline(always)]
        fn all_valid<const K: usize>(values: [Self; K]) -> bool {
            <Self as $crate::num::Scalar>::check_passed(
                values
                    .iter()
                    .fold(<Self as $crate::num::Quantity>::ZERO, |c, &v| {
                        <Self as $crate::num::Scalar>::accumulate_check(c, v)
                    }),
            )
        }
    };
}
pub(crate) use scalar_real_items;

impl<S: Scalar> ScalarGuard<S> {
    /// Folds an output into the running check.
    #[inline]
    pub(crate) fn fold(&mut self, value: S) {
        self.check = S::accumulate_check(self.check, value);
    }
}

/// [`Numeric`] for a [`Scalar`]: every quantity the type itself, its sine
/// and cosine given by `|θ| sin_cos`, the track table's operations from
/// `crate::track::numeric`'s generic scalar forms.
macro_rules! scalar_numeric {
    ($t:ty, $name:literal, |$theta:ident| $sin_cos:expr) => {
        impl Numeric for $t {
            const NAME: &'static str = $name;
            type Length = $t;
            type Speed = $t;
            type Acceleration = $t;
            type Interval = $t;
            type IntervalSquared = $t;
            type Ratio = $t;
            type Gain = $t;
            type Rate = $t;
            type RateSquared = $t;
            type Angle = $t;
            type Guard = ScalarGuard<$t>;
            type Wide = $t;
            type Polar = $t;
            type CircleScale = $t;
            type Variance = $t;
            type GridScale = $t;
            const GRID_SCALE_ZERO: $t = <$t as Quantity>::ZERO;

            #[inline]
            fn passed(guard: &ScalarGuard<$t>) -> bool {
                guard.passed()
            }
            #[inline]
            fn sin_cos($theta: $t) -> ($t, $t) {
                $sin_cos
            }
            #[inline]
            fn azimuth(x: $t, y: $t) -> $t {
                super::azimuth_of(x, y)
            }
            #[inline]
            fn gain(r: $t) -> $t {
                r
            }
            #[inline]
            fn hypot(a: $t, b: $t) -> $t {
                Real::hypot(a, b)
            }
            #[inline]
            fn circle_scale(radius: $t) -> Option<$t> {
                scalar_track::circle_scale(radius)
            }
            #[inline]
            fn scaled_circle(sigma: $t, factor: $t) -> Option<($t, $t)> {
                scalar_track::scaled_circle(sigma, factor)
            }
            #[inline]
            fn circle_radius(reach: $t, scale: $t) -> $t {
                scalar_track::circle_radius(reach, scale)
            }
            #[inline]
            fn circle_cost(dx: $t, dy: $t, reach: $t, scale: $t) -> Option<u16> {
                scalar_track::circle_cost(dx, dy, reach, scale)
            }
            #[inline]
            fn grid_scale(min: $t, max: $t, cells: u16) -> $t {
                scalar_track::grid_scale(min, max, cells)
            }
            #[inline]
            fn grid_cell(v: $t, min: $t, max: $t, scale: $t) -> u32 {
                scalar_track::grid_cell(v, min, max, scale)
            }
            #[inline]
            fn length_to_polar(v: $t) -> $t {
                v
            }
            #[inline]
            fn length_from_polar(v: $t) -> $t {
                v
            }
            #[inline]
            fn ratio_to_polar(v: $t) -> $t {
                v
            }
            #[inline]
            fn ratio_from_polar(v: $t) -> $t {
                v
            }
            #[inline]
            fn to_variance(r: $t) -> $t {
                r
            }
            #[inline]
            fn from_variance(v: $t) -> $t {
                v
            }
        }
    };
}

use crate::track::numeric::scalar as scalar_track;

scalar_numeric!(f64, "f64", |theta| libm::sincos(theta));
// f32: the table sine of the exact binary angle (`sine::sin_cos_f32`):
// no double-precision arithmetic, which libm's `sincosf` uses.
scalar_numeric!(f32, "f32", |theta| super::sine::sin_cos_f32(theta));
scalar_numeric!(super::Fix, "q32", |theta| super::Fix::sin_cos_cordic(theta));
scalar_numeric!(super::ScaledScalar, "scaled", |theta| {
    super::ScaledScalar::sin_cos_table(theta)
});
