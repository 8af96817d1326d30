//! The `minikalman` 0.8 anchor: a general constant-velocity Kalman filter,
//! state (x, y, vₓ, v_y), position measured, in f32 and in I16F16 (Q16.16,
//! the crate's fixed-point build), on the `ab2d_update` row's data.
//!
//! Its buffers are stack arrays made with the crate's `impl_buffer_*` macros
//! (no `alloc`). One call = `predict` then `correct` with the new
//! measurement, as an αβ update is one predict-and-correct.

use core::hint::black_box;

use minikalman::num_traits::FromPrimitive;
use minikalman::prelude::*;
use minikalman::regular::{RegularKalmanBuilder, RegularObservationBuilder};

use crate::counter::Bench;
use crate::data::{at, PlaneRing, RING};

const STATES: usize = 4;
const OBSERVATIONS: usize = 2;
const OPERATION: &str = "kalman_cv2d_update";

/// Both builds. The f32 label follows the core (hardware or software f32),
/// as for abtrack's own rows.
#[inline(never)]
pub fn run(bench: &mut Bench) {
    cv2d::<f32>(bench, <f32 as crate::numeric::BenchNumber>::LABEL);
    cv2d::<I16F16>(bench, "i16f16");
}

/// Converts an f64 constant; `None` if `T` cannot hold it.
fn constant<T: FromPrimitive>(v: f64) -> Option<T> {
    T::from_f64(v)
}

#[inline(never)]
fn predict_correct<F, M, T>(filter: &mut F, measurement: &mut M, z: [T; 2])
where
    T: MatrixDataType,
    F: KalmanFilterPredict<STATES, T> + KalmanFilterUpdate<STATES, T>,
    M: KalmanFilterObservationCorrectFilter<STATES, T>
        + KalmanFilterObservationVectorMut<OBSERVATIONS, T>,
{
    let v = measurement.measurement_vector_mut();
    v.set_at(0, 0, z[0]);
    v.set_at(1, 0, z[1]);
    filter.predict();
    filter.correct(measurement);
}

/// q = 1 m²/s³ (continuous white-noise acceleration), σ = 25 m, T = 1 s:
/// the hand-written `axis_kalman_cv2d_update`'s model, as one 4-state
/// filter.
#[allow(non_snake_case)] // the crate's matrix names
#[inline(never)]
fn cv2d<T: MatrixDataType + Default>(bench: &mut Bench, numeric: &'static str) {
    let (Some(t), Some(q_pos), Some(q_cross), Some(q_vel), Some(r), Some(p_pos), Some(p_vel)) = (
        constant::<T>(1.0),
        constant::<T>(1.0 / 3.0),
        constant::<T>(0.5),
        constant::<T>(1.0),
        constant::<T>(625.0),
        constant::<T>(625.0),
        constant::<T>(10_000.0),
    ) else {
        bench.fail(numeric, OPERATION, "constants not representable");
        return;
    };
    let lossy = |v: f64| constant::<T>(v).unwrap_or_default();
    // The `ab2d_update` row's target (σ = 25 m), converted.
    let target = PlaneRing::<f64>::new(25.0);
    let xs: [T; RING] = target.xs.map(lossy);
    let ys: [T; RING] = target.ys.map(lossy);

    impl_buffer_x!(mut x, STATES, T, T::zero());
    impl_buffer_A!(mut A, STATES, T, T::zero());
    impl_buffer_P!(mut P, STATES, T, T::zero());
    impl_buffer_Q_direct!(mut Q, STATES, T, T::zero());
    impl_buffer_temp_x!(mut temp_x, STATES, T, T::zero());
    impl_buffer_temp_P!(mut temp_P, STATES, T, T::zero());
    let mut filter = RegularKalmanBuilder::new::<STATES, T>(A, x, P, Q, temp_x, temp_P);

    impl_buffer_z!(mut z, OBSERVATIONS, T, T::zero());
    impl_buffer_H!(mut H, OBSERVATIONS, STATES, T, T::zero());
    impl_buffer_R!(mut R, OBSERVATIONS, T, T::zero());
    impl_buffer_y!(mut y, OBSERVATIONS, T, T::zero());
    impl_buffer_S!(mut S, OBSERVATIONS, T, T::zero());
    impl_buffer_K!(mut K, STATES, OBSERVATIONS, T, T::zero());
    impl_buffer_temp_S_inv!(mut temp_S_inv, OBSERVATIONS, T, T::zero());
    impl_buffer_temp_HP!(mut temp_HP, OBSERVATIONS, STATES, T, T::zero());
    impl_buffer_temp_PHt!(mut temp_PHt, STATES, OBSERVATIONS, T, T::zero());
    impl_buffer_temp_KHP!(mut temp_KHP, STATES, T, T::zero());
    let mut measurement = RegularObservationBuilder::new::<STATES, OBSERVATIONS, T>(
        H, z, R, y, S, K, temp_S_inv, temp_HP, temp_PHt, temp_KHP,
    );

    // State (x, y, vₓ, v_y): x' = x + T·vₓ, y' = y + T·v_y.
    filter.state_transition_mut().apply(|a| {
        a.make_identity();
        a.set_at(0, 2, t);
        a.set_at(1, 3, t);
    });
    filter.state_vector_mut().apply(|s| {
        s.set_at(0, 0, xs[0]);
        s.set_at(1, 0, ys[0]);
    });
    filter.estimate_covariance_mut().apply(|p| {
        p.set_at(0, 0, p_pos);
        p.set_at(1, 1, p_pos);
        p.set_at(2, 2, p_vel);
        p.set_at(3, 3, p_vel);
    });
    filter.direct_process_noise_mut().apply(|q| {
        for (position, velocity) in [(0, 2), (1, 3)] {
            q.set_at(position, position, q_pos);
            q.set_at(position, velocity, q_cross);
            q.set_at(velocity, position, q_cross);
            q.set_at(velocity, velocity, q_vel);
        }
    });
    measurement.observation_matrix_mut().apply(|h| {
        h.set_at(0, 0, T::one());
        h.set_at(1, 1, T::one());
    });
    measurement.measurement_noise_covariance_mut().apply(|m| {
        m.set_at(0, 0, r);
        m.set_at(1, 1, r);
    });

    bench.per_call(
        numeric,
        OPERATION,
        |k| {
            let z = [black_box(xs[at(k)]), black_box(ys[at(k)])];
            predict_correct(&mut filter, &mut measurement, z);
        },
        |k| {
            black_box([black_box(xs[at(k)]), black_box(ys[at(k)])]);
        },
    );
    // It must have followed the target (I16F16 wraps silently on overflow).
    let last = at(crate::CALLS - 1);
    let state = filter.state_vector();
    let near = |estimate: T, z: T| {
        let d = estimate - z;
        let limit = constant::<T>(150.0).unwrap_or_default();
        d < limit && d > -limit
    };
    bench.check(
        near(state.get_at(0, 0), xs[last]) && near(state.get_at(1, 0), ys[last]),
        numeric,
        OPERATION,
        "diverged",
    );
}
