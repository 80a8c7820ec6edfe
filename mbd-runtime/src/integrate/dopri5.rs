//! Dormand–Prince 5(4) with error control, PI step-size control and dense output (Hairer,
//! Nørsett & Wanner, *Solving ODEs I*, II.5 and its `DOPRI5` code): [`Dopri5`] and its
//! [`Dopri5Options`].
//!
//! On y = (q, v), y' = (B(q) v, v̇); each accepted step ends with q normalized. Seven stages
//! (FSAL: the last is the next step's first, so 6 evaluations of v̇ per accepted step); the
//! error of the embedded 4th-order solution, RMS over q and v in the mixed tolerance
//! atol + rtol·|y|, sets the next step by the PI rule h₊ = h · 0.9 · err^−0.17 · err_prev^0.04
//! (the factor clamped to [0.2, 10]). The 4th-order dense output is
//! y(θ) = r1 + θ(r2 + (1−θ)(r3 + θ(r4 + (1−θ) r5))).

use super::stiffness::{StiffnessDetected, StiffnessTest};
use super::{check_step, non_finite, Integrator, Point, SimulationError, System};
use crate::model::dynamics::ForwardDynamics;
use crate::model::workspace::WorkArrays;
use crate::real::Real;

crate::options::options! {
    /// Options of [`Dopri5`], in the scalar type `T` of the mechanism (default `f64`). Build
    /// from [`Default`] and the `with_*` setters.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct Dopri5Options<T> {
        /// Relative tolerance on each coordinate and velocity. Default 1e-8; raised to 16 ε of
        /// the scalar type where it is below (f32: 1.9e-6), since no step resolves less.
        rtol: T = T::from_f64(1e-8) => with_rtol,
        /// Absolute tolerance (m, rad, m/s, rad/s). Default 1e-10; raised likewise to 16 ε.
        atol: T = T::from_f64(1e-10) => with_atol,
        /// First step size (s); 0 chooses one from the initial derivatives (Hairer's rule).
        /// Default 0.
        initial_step: T = T::ZERO => with_initial_step,
        /// Largest step size (s). Default 0.1 s.
        max_step: T = T::from_f64(0.1) => with_max_step,
        /// Smallest step size before failing with [`SimulationError::StepSizeTooSmall`]. Default
        /// 1e-12 s.
        min_step: T = T::from_f64(1e-12) => with_min_step,
    }
}

impl<T: Real> Dopri5Options<T> {
    /// See [`check_step_control`].
    pub(super) fn check(&self) -> Result<(), SimulationError> {
        check_step_control(
            [self.rtol, self.atol, self.max_step, self.min_step],
            [
                "rtol and atol (Dopri5Options) must be non-negative, not both zero",
                "Dopri5Options::max_step must be positive, min_step non-negative",
            ],
        )
    }
}

/// [rtol, atol, max_step, min_step]: the tolerances non-negative and not both zero, `max_step`
/// positive, `min_step` non-negative (NaN fails each), else the error with the first or second
/// of `messages`: the check of every error-controlled integrator's options.
// `!(x >= y)` on purpose: it is also true when either side is NaN.
#[allow(clippy::neg_cmp_op_on_partial_ord)]
pub(super) fn check_step_control<T: Real>(
    [rtol, atol, max_step, min_step]: [T; 4],
    messages: [&'static str; 2],
) -> Result<(), SimulationError> {
    if !(rtol >= T::ZERO && atol >= T::ZERO && rtol + atol > T::ZERO) {
        return Err(SimulationError::InvalidOptions { what: messages[0] });
    }
    if !(max_step > T::ZERO && min_step >= T::ZERO) {
        return Err(SimulationError::InvalidOptions { what: messages[1] });
    }
    Ok(())
}

/// Dormand–Prince 5(4) with error control, PI step-size control and dense output (Hairer,
/// Nørsett & Wanner, *Solving ODEs I*, II.5 and its `DOPRI5` code). The work integrals use the
/// method's 5th-order weights on the stage powers.
#[derive(Clone, Copy, Debug)]
pub struct Dopri5<T, const NQ: usize, const NV: usize> {
    /// Tolerances and step limits.
    pub options: Dopri5Options<T>,
    /// The step size the next step will try (s); 0 before the first.
    pub next_step: T,
    /// Accepted and rejected steps so far.
    pub accepted: u64,
    /// Rejected steps so far.
    pub rejected: u64,
    /// Evaluations of v̇ so far (the stages of every step tried).
    pub evaluations: u64,
    previous_error: T,
    stiffness: StiffnessTest,
    // Dense output of the last step: y(θ) = r1 + θ(r2 + (1−θ)(r3 + θ(r4 + (1−θ) r5))) for q
    // and for v.
    dense_q: [[T; NQ]; 5],
    dense_v: [[T; NV]; 5],
}

impl<T: Real, const NQ: usize, const NV: usize> Dopri5<T, NQ, NV> {
    /// The dense output's coefficients of the step from `from` to `to` (its unnormalized end)
    /// with stage derivatives `kq`, `kv`.
    #[allow(clippy::needless_range_loop)] // i indexes q, v and every stage's derivative alike
    fn store_dense<const NC: usize>(
        &mut self,
        from: &Point<T, NQ, NV, NC>,
        to: &Point<T, NQ, NV, NC>,
        kq: &[[T; NQ]; 7],
        kv: &[[T; NV]; 7],
        h: T,
    ) {
        for i in 0..NQ {
            let r = dense_coefficients(from.q[i], to.q[i], |s| kq[s][i], h);
            for (c, value) in r.into_iter().enumerate() {
                self.dense_q[c][i] = value;
            }
        }
        for i in 0..NV {
            let r = dense_coefficients(from.v[i], to.v[i], |s| kv[s][i], h);
            for (c, value) in r.into_iter().enumerate() {
                self.dense_v[c][i] = value;
            }
        }
    }

    /// A Dormand–Prince integrator with the given options.
    pub fn new(options: Dopri5Options<T>) -> Self {
        Self {
            options,
            next_step: T::ZERO,
            accepted: 0,
            rejected: 0,
            evaluations: 0,
            previous_error: T::from_f64(1e-4),
            stiffness: StiffnessTest::default(),
            dense_q: [[T::ZERO; NQ]; 5],
            dense_v: [[T::ZERO; NV]; 5],
        }
    }
}

impl<T: Real, const NQ: usize, const NV: usize> Dopri5<T, NQ, NV> {
    /// Counts the stiffness test's steps afresh (after another method took steps): a stiff
    /// phase is seen again 15 steps at the bound from here.
    pub(super) fn watch_again(&mut self) {
        self.stiffness.watch_again();
    }
}

impl<T: Real, const NQ: usize, const NV: usize> Default for Dopri5<T, NQ, NV> {
    fn default() -> Self {
        Self::new(Dopri5Options::default())
    }
}

// Dormand–Prince coefficients.
const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
const A: [[f64; 6]; 7] = [
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0, 0.0, 0.0],
    [9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0, 0.0],
    [35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0],
];
/// b − b̂: the embedded error estimate's weights.
const E: [f64; 7] = [71.0 / 57600.0, 0.0, -71.0 / 16695.0, 71.0 / 1920.0, -17253.0 / 339200.0, 22.0 / 525.0, -1.0 / 40.0];
/// Dense-output weights (Hairer's `contd5`).
const D: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

/// Dense-output coefficients r1 … r5 of one component y with stage derivatives k (Hairer's
/// `contd5`): `dense[0..5]` for y0 → y1 over a step h.
#[inline]
fn dense_coefficients<T: Real>(y0: T, y1: T, k: impl Fn(usize) -> T, h: T) -> [T; 5] {
    let r2 = y1 - y0;
    let r3 = h * k(0) - r2;
    let r4 = r2 - h * k(6) - r3;
    let mut r5 = T::ZERO;
    for (s, &d) in D.iter().enumerate() {
        r5 += T::from_f64(d) * k(s);
    }
    [y0, r2, r3, r4, h * r5]
}

impl<T: Real, M: ForwardDynamics<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>
    Integrator<T, M, NQ, NV, NC, N, NS> for Dopri5<T, NQ, NV>
{
    // `!(x > y)` on purpose: it is also true when either side is NaN.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    // One index runs over q (or v) and its stage derivatives, start and end in step.
    #[allow(clippy::needless_range_loop)]
    fn step(
        &mut self,
        system: &System<'_, M, T>,
        ws: &mut WorkArrays<T, NV, NC, N, NS>,
        from: &Point<T, NQ, NV, NC>,
        t_max: T,
        to: &mut Point<T, NQ, NV, NC>,
    ) -> Result<(), SimulationError> {
        let o = self.options;
        o.check()?;
        let span = t_max - from.t;
        if !(span > T::ZERO) {
            to.copy_from(from);
            return Ok(());
        }
        let mech = system.mechanism;
        // Tolerances below the scalar's rounding cannot be met (f32 with the f64 defaults).
        let floor = T::from_f64(16.0) * T::EPSILON;
        let (rtol, atol) = (o.rtol.max(floor), o.atol.max(floor));
        let scale = |y0: T, y1: T| atol + rtol * y0.abs().max(y1.abs());
        // Stage derivatives: (q̇ = B(q) v, v̇) and powers; the stage state, the sixth stage's
        // (at t + h like the solution: the stiffness test's) and the multipliers.
        let mut dense = ws.dense();
        let (kq, kv) = (dense.vectors.rows::<NQ, 7>(), dense.vectors.rows::<NV, 7>());
        let [q, q5] = dense.vectors.rows::<NQ, 2>();
        let [v, v5] = dense.vectors.rows::<NV, 2>();
        let lambda = dense.vectors.take::<NC>();
        let mut kp = [[T::ZERO; 2]; 7];
        mech.position_rates(&from.q, &from.v, &mut kq[0]);
        kv[0] = from.vd;
        kp[0] = from.power;
        if !(self.next_step > T::ZERO) {
            self.next_step = if o.initial_step > T::ZERO { o.initial_step } else { initial_step(from, &kq[0], &scale, o.max_step) };
        }
        *lambda = from.lambda;
        'attempt: loop {
            let mut h = self.next_step.max(o.min_step);
            if h > o.max_step {
                h = o.max_step;
            }
            // Hairer's rule: a step within 1 % of the end goes all the way, so that a run never
            // ends on a sliver left by rounding (ten steps of 0.1 s sum to 0.9999999999999999).
            let last = from.t + T::from_f64(1.01) * h >= t_max;
            if last {
                h = span;
            }
            for s in 1..7 {
                for i in 0..NQ {
                    let mut dq = T::ZERO;
                    for j in 0..s {
                        dq += T::from_f64(A[s][j]) * kq[j][i];
                    }
                    q[i] = from.q[i] + h * dq;
                }
                for i in 0..NV {
                    let mut dv = T::ZERO;
                    for j in 0..s {
                        dv += T::from_f64(A[s][j]) * kv[j][i];
                    }
                    v[i] = from.v[i] + h * dv;
                }
                mech.position_rates(q, v, &mut kq[s]);
                if s == 5 {
                    *q5 = *q;
                    *v5 = *v;
                }
                let t_s = if s == 6 { from.t + h } else { from.t + T::from_f64(C[s]) * h };
                self.evaluations += 1;
                match system.derivatives_in(dense.reborrow(), t_s, q, v, &mut kv[s], lambda) {
                    Ok(p) => kp[s] = p,
                    // A trial state may be off the manifold far enough to fail the solve:
                    // shrink the step, and report the failure only at the minimum step.
                    Err(e) => {
                        self.rejected += 1;
                        self.next_step = h * T::from_f64(0.25);
                        if self.next_step < o.min_step {
                            return Err(e.into());
                        }
                        continue 'attempt;
                    }
                }
            }
            to.q = *q;
            to.v = *v;
            to.vd = kv[6];
            to.lambda = *lambda;
            to.power = kp[6];
            // Error estimate, RMS over q and v scaled by the tolerances (one pass over both, so
            // that for NQ = NV the sum is accumulated in the same order as q and v pairwise).
            let mut sum = T::ZERO;
            for i in 0..NQ.max(NV) {
                let (mut eq, mut ev) = (T::ZERO, T::ZERO);
                for s in 0..7 {
                    let e = T::from_f64(E[s]);
                    if i < NQ {
                        eq += e * kq[s][i];
                    }
                    if i < NV {
                        ev += e * kv[s][i];
                    }
                }
                let rq = if i < NQ { h * eq / scale(from.q[i], to.q[i]) } else { T::ZERO };
                let rv = if i < NV { h * ev / scale(from.v[i], to.v[i]) } else { T::ZERO };
                sum += rq * rq + rv * rv;
            }
            let error = (sum / T::from_f64((NQ + NV).max(1) as f64)).sqrt();
            // PI step-size control (Hairer: exponents 0.2 − 0.75·0.04 and 0.04, safety 0.9).
            let safe = T::from_f64(0.9);
            if error <= T::ONE {
                let e = error.max(T::from_f64(1e-10));
                let factor = safe * e.powf(T::from_f64(-0.17)) * self.previous_error.powf(T::from_f64(0.04));
                let factor = factor.max(T::from_f64(0.2)).min_(T::from_f64(10.0));
                self.previous_error = e.max(T::from_f64(1e-4));
                if !last || h < self.next_step {
                    self.next_step = h * factor;
                }
                self.accepted += 1;
                self.stiffness.observe("DOPRI5", 3.25, from.t + h, h, [&kq[6], &kv[6], &kq[5], &kv[5]], [q, v, q5, v5]);
                // The 5th-order weights are the last row of A (b₇ = 0).
                #[allow(clippy::needless_range_loop)] // k indexes from.work, to.work and each stage's kp[s]
                for k in 0..2 {
                    let mut w = T::ZERO;
                    for s in 0..6 {
                        w += T::from_f64(A[6][s]) * kp[s][k];
                    }
                    to.work[k] = from.work[k] + h * w;
                }
                to.t = if last { t_max } else { from.t + h };
                // Dense output coefficients, from the step's unnormalized end (the stages' flow).
                self.store_dense(from, to, kq, kv, h);
                mech.normalize_positions(&mut to.q);
                return check_step::<T, M, NQ, NV, NC>(from, to);
            }
            self.rejected += 1;
            let e = if error.is_finite() { error } else { T::from_f64(1e10) };
            let factor = (safe * e.powf(T::from_f64(-0.2))).max(T::from_f64(0.1));
            self.next_step = h * factor;
            if self.next_step < o.min_step {
                if let Some(coordinate) = non_finite::<T, M, NQ, NV>(&to.q, &to.v) {
                    return Err(SimulationError::NonFinite { t: from.t.to_f64(), coordinate });
                }
                return Err(SimulationError::StepSizeTooSmall { t: from.t.to_f64(), step: self.next_step.to_f64() });
            }
        }
    }

    fn interpolate(&self, _mechanism: &M, from: &Point<T, NQ, NV, NC>, to: &Point<T, NQ, NV, NC>, t: T, q: &mut [T; NQ], v: &mut [T; NV]) {
        let h = to.t - from.t;
        let theta = if h > T::ZERO { (t - from.t) / h } else { T::ONE };
        let one_minus = T::ONE - theta;
        let at = |d: [T; 5]| d[0] + theta * (d[1] + one_minus * (d[2] + theta * (d[3] + one_minus * d[4])));
        for (i, out) in q.iter_mut().enumerate() {
            *out = at(core::array::from_fn(|c| self.dense_q[c][i]));
        }
        for (i, out) in v.iter_mut().enumerate() {
            *out = at(core::array::from_fn(|c| self.dense_v[c][i]));
        }
    }
    fn prepare_interpolation(
        &mut self,
        _system: &System<'_, M, T>,
        _ws: &mut WorkArrays<T, NV, NC, N, NS>,
        _from: &Point<T, NQ, NV, NC>,
        _to: &Point<T, NQ, NV, NC>,
    ) -> Result<(), SimulationError> {
        // The step leaves its interpolant ready.
        Ok(())
    }

    /// Hairer's test on the last two stages of each accepted step (module `stiffness`).
    fn stiffness(&self) -> Option<StiffnessDetected> {
        self.stiffness.found()
    }

    fn restart(&mut self) {
        // Its step size and error history stay: `Simulation` restarts at a switch and steps
        // again towards it from the same start, where the step the last one chose lands on the
        // switch (a fresh start's small first step would land short of it, step after step).
        // Its dense output is the last step's, made by `step`.
    }

    fn after_correction(
        &mut self,
        system: &System<'_, M, T>,
        ws: &mut WorkArrays<T, NV, NC, N, NS>,
        to: &mut Point<T, NQ, NV, NC>,
    ) -> Result<(), SimulationError> {
        // An explicit method goes on from forward dynamics at the corrected state.
        Ok(system.complete_in(ws.dense(), to)?)
    }
}

/// Hairer's initial step: h such that an explicit Euler step changes the state by about the
/// tolerance, refined with a second derivative estimate; here the derivatives at hand suffice:
/// h = 0.01 · ‖y‖ / ‖y'‖ in the tolerance's norm (y = (q, v), y' = (q̇, v̇)), capped by
/// `max_step`.
// One index runs over q and v together (see the loop).
#[allow(clippy::needless_range_loop)]
pub(super) fn initial_step<T: Real, const NQ: usize, const NV: usize, const NC: usize>(
    p: &Point<T, NQ, NV, NC>,
    qdot: &[T; NQ],
    scale: &impl Fn(T, T) -> T,
    max_step: T,
) -> T {
    let (mut d0, mut d1) = (T::ZERO, T::ZERO);
    // One pass over both, in the order of q and v pairwise (as for NQ = NV).
    for i in 0..NQ.max(NV) {
        let (mut y, mut dy) = (T::ZERO, T::ZERO);
        if i < NQ {
            let sq = scale(p.q[i], p.q[i]);
            y = (p.q[i] / sq) * (p.q[i] / sq);
            dy = (qdot[i] / sq) * (qdot[i] / sq);
        }
        if i < NV {
            let sv = scale(p.v[i], p.v[i]);
            y += (p.v[i] / sv) * (p.v[i] / sv);
            dy += (p.vd[i] / sv) * (p.vd[i] / sv);
        }
        d0 += y;
        d1 += dy;
    }
    let h = if d0 < T::from_f64(1e-10) || d1 < T::from_f64(1e-10) { T::from_f64(1e-6) } else { T::from_f64(0.01) * (d0 / d1).sqrt() };
    h.min_(max_step)
}

/// The smaller of two values (NaN-propagating like `max`'s twin).
pub(super) trait MinExt {
    fn min_(self, other: Self) -> Self;
}

impl<T: Real> MinExt for T {
    #[inline]
    fn min_(self, other: Self) -> Self {
        if other < self {
            other
        } else {
            self
        }
    }
}
