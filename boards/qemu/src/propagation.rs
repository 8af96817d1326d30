//! A bound on how far two runs of a linear(ised) filter drift apart when the
//! gains change from step to step: the self-test's fallback where the
//! library's error budget ([`abtrack::budget`]) refuses (its small-gain
//! argument cannot certify gain schedules that sweep a wide range, see its
//! module docs, step 3) or does not apply (the range–azimuth filter).
//!
//! # What it bounds
//!
//! The difference `d` between a run in `S` and its `f64` twin obeys, exactly,
//! `d_{k+1} = A_k d_k + w_k` (the budget's module docs, step 1: the update is
//! affine in the state, `A_k` is the closed-loop matrix of step k with the
//! f64 run's gains, `w_k` what both runs' rounding injects at step k, and any
//! difference between the two runs' gains times the residual). Given
//! componentwise bounds `|w_k| ≤ η_k` and `|d_0| ≤ Y_0`, the exact solution
//!
//! ```text
//! d_k = Φ(k, j)·d_j + Σ_{i=j}^{k−1} Φ(k, i+1)·w_i,   Φ(k, j) = A_{k−1}···A_j,
//! ```
//!
//! gives, with `j = k − m` and `Y_j` the bound already proved at step `j`,
//!
//! ```text
//! |d_k| ≤ Y_k = |Φ(k, k−m)|·Y_{k−m} + Σ_{l=1}^{m} |Φ(k, k−l+1)|·η_{k−l}
//! ```
//!
//! (entrywise absolute values; `Φ(k, k) = I`), for any `m ≤ k`. The
//! products are exact, so the signs of the error dynamics (the cancellation
//! that makes a stable filter forget old errors) are kept over a window of
//! `M` steps; only at lag `M` are absolute values taken. The classic running
//! bound `Y_{k+1} = |A_k|·Y_k + η_k` is the case `M = 1`, and it grows without
//! limit for underdamped or slow gains (e.g. α = 0.5, β = 0.3 gives
//! ρ(|Ā|) = 1), which is why the window is needed.
//!
//! Cost: `M` products of `N×N` matrices per step and `M·(N² + 2N)` f64 of
//! memory (6 KB for `N = 4`, `M = 32`), so it is sized per use.
//!
//! The bound's own `f64` arithmetic is covered by [`OWN_ROUNDING`]: the sums
//! of nonnegative terms are off by at most M·N·2⁻⁵³ relative, and a product
//! of l ≤ M matrices by at most l·N·2⁻⁵³ times the product of their absolute
//! values. For the windows and gains used here (M ≤ 32, |A| with spectral
//! radius close to 1, so the product of absolute values stays within a few
//! hundred) that is of order 10⁻¹² absolute against entries of order
//! 10⁻²–10: not proved for every possible gain sequence, but six orders of
//! magnitude inside the allowance.

/// Relative allowance for the bound's own rounding (module docs): four
/// orders of magnitude above what it covers.
pub const OWN_ROUNDING: f64 = 1e-6;

/// Square matrices of dimension `N`, row-major.
pub type Matrix<const N: usize> = [[f64; N]; N];

pub fn identity<const N: usize>() -> Matrix<N> {
    let mut m = [[0.0; N]; N];
    for (i, row) in m.iter_mut().enumerate() {
        if let Some(v) = row.get_mut(i) {
            *v = 1.0;
        }
    }
    m
}

fn product<const N: usize>(a: &Matrix<N>, b: &Matrix<N>) -> Matrix<N> {
    let mut c = [[0.0; N]; N];
    for (c_row, a_row) in c.iter_mut().zip(a.iter()) {
        for (j, c_ij) in c_row.iter_mut().enumerate() {
            let mut s = 0.0;
            for (a_ik, b_row) in a_row.iter().zip(b.iter()) {
                s += a_ik * b_row.get(j).copied().unwrap_or(0.0);
            }
            *c_ij = s;
        }
    }
    c
}

/// `acc += |m|·v`.
fn add_abs_product<const N: usize>(acc: &mut [f64; N], m: &Matrix<N>, v: &[f64; N]) {
    for (a, row) in acc.iter_mut().zip(m.iter()) {
        let mut s = 0.0;
        for (m_ij, v_j) in row.iter().zip(v.iter()) {
            s += libm::fabs(*m_ij) * v_j;
        }
        *a += s;
    }
}

/// One slot of the window: for lag `l` (steps back from now), the product
/// `Φ(now, now − l)`, the injection bound `η_{now−l}` and the bound
/// `Y_{now−l}`.
#[derive(Clone, Copy)]
pub struct Lag<const N: usize> {
    product: Matrix<N>,
    injection: [f64; N],
    bound: [f64; N],
}

impl<const N: usize> Lag<N> {
    pub const EMPTY: Self = Lag {
        product: [[0.0; N]; N],
        injection: [0.0; N],
        bound: [0.0; N],
    };
}

/// The window's storage, kept by the caller (`[Lag::EMPTY; M]` in its own
/// frame): built in place, where a kilobytes-large value returned by a
/// constructor would be copied, and doubled on the stack.
pub type Window<const N: usize, const M: usize> = [Lag<N>; M];

/// The windowed bound of the module docs: `N` state components, a window of
/// `M` steps.
pub struct ErrorPropagation<'w, const N: usize, const M: usize> {
    lags: &'w mut Window<N, M>,
    /// Slot the next step is written to; lag `l` is at `head − l` (mod M).
    head: usize,
    /// Lags stored (≤ M).
    len: usize,
    current: [f64; N],
    steps: u32,
}

impl<'w, const N: usize, const M: usize> ErrorPropagation<'w, N, M> {
    /// Starts from `|d_0| ≤ initial` (componentwise), using `window` (its
    /// previous contents are ignored).
    pub fn new(window: &'w mut Window<N, M>, initial: [f64; N]) -> Self {
        ErrorPropagation {
            lags: window,
            head: 0,
            len: 0,
            current: initial,
            steps: 0,
        }
    }

    /// The bound on `|d|` now.
    pub fn bound(&self) -> [f64; N] {
        self.current
    }

    pub fn steps(&self) -> u32 {
        self.steps
    }

    /// One step `d ← A·d + w` with `|w| ≤ injection`; returns the new bound.
    pub fn step(&mut self, a: &Matrix<N>, injection: [f64; N]) -> [f64; N] {
        if M == 0 {
            return self.current;
        }
        // Every stored lag ages by one step: Φ(now+1, j) = A·Φ(now, j).
        let stored = self.len;
        for l in 1..=stored {
            let i = (self.head + M - l) % M;
            if let Some(slot) = self.lags.get_mut(i) {
                slot.product = product(a, &slot.product);
            }
        }
        // The new lag 1: Φ(now+1, now) = A, injected w_now, bound Y_now. When
        // the window is full this overwrites the slot that just became lag
        // M + 1.
        if let Some(slot) = self.lags.get_mut(self.head) {
            *slot = Lag {
                product: *a,
                injection,
                bound: self.current,
            };
        }
        self.head = (self.head + 1) % M;
        self.len = (self.len + 1).min(M);

        // Y = Σ_{l=1}^{len} |Φ(now, now−l+1)|·η_{now−l} + |Φ(now, now−len)|·Y_{now−len}.
        let mut y = [0.0; N];
        let mut previous: Option<usize> = None; // slot of lag l − 1
        for l in 1..=self.len {
            let i = (self.head + M - l) % M;
            let Some(slot) = self.lags.get(i) else {
                continue;
            };
            match previous.and_then(|p| self.lags.get(p)) {
                None => {
                    // Φ(now, now) = I.
                    for (y_i, w_i) in y.iter_mut().zip(slot.injection.iter()) {
                        *y_i += w_i;
                    }
                }
                Some(p) => add_abs_product(&mut y, &p.product, &slot.injection),
            }
            if l == self.len {
                add_abs_product(&mut y, &slot.product, &slot.bound);
            }
            previous = Some(i);
        }
        for v in y.iter_mut() {
            *v *= 1.0 + OWN_ROUNDING;
        }
        self.current = y;
        self.steps += 1;
        y
    }
}

/// The closed-loop matrix of one αβ(γ) update in physical units
/// (x, v, a), `N` = 2 or 3: `A = (I − K·H)·Φ(T)` with
/// `K = (α, β/T, γ/(2T²))` (Tenne & Singh eqs. 1–5; Al-Wagih eqs. 3–8) and
/// `Φ(T) = [[1, T, T²/2], [0, 1, T], [0, 0, 1]]`.
pub fn kinematic_update<const N: usize>(alpha: f64, beta: f64, gamma: f64, dt: f64) -> Matrix<N> {
    let phi = [[1.0, dt, 0.5 * dt * dt], [0.0, 1.0, dt], [0.0, 0.0, 1.0]];
    let k = [alpha, beta / dt, gamma / (2.0 * dt * dt)];
    let mut a = [[0.0; N]; N];
    for (i, row) in a.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            let (p_ij, p_0j, k_i) = (
                phi.get(i).and_then(|r| r.get(j)).copied().unwrap_or(0.0),
                phi.first().and_then(|r| r.get(j)).copied().unwrap_or(0.0),
                k.get(i).copied().unwrap_or(0.0),
            );
            *v = p_ij - k_i * p_0j;
        }
    }
    a
}

/// The prediction alone (a coast): `Φ(T)` for `N` = 2 or 3.
pub fn kinematic_prediction<const N: usize>(dt: f64) -> Matrix<N> {
    kinematic_update::<N>(0.0, 0.0, 0.0, dt)
}
