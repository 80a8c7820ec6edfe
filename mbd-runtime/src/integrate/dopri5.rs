//! Dormand–Prince 5(4) with error control, PI step-size control and dense output (Hairer,
//! Nørsett & Wanner, *Solving ODEs I*, II.5 and its `DOPRI5` code): [`Dopri5`] and its
//! [`Dopri5Options`].
//!
//! Seven stages (FSAL: the last is the next step's first, so 6 evaluations of q̈ per accepted
//! step); the error of the embedded 4th-order solution, RMS over q and q̇ in the mixed tolerance
//! atol + rtol·|y|, sets the next step by the PI rule h₊ = h · 0.9 · err^−0.17 · err_prev^0.04
//! (the factor clamped to [0.2, 10]). The 4th-order dense output is
//! y(θ) = r1 + θ(r2 + (1−θ)(r3 + θ(r4 + (1−θ) r5))).

use super::{check_step, non_finite, Integrator, Point, SimulationError, System};
use crate::{ForwardDynamics, Real};

/// Options of [`Dopri5`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dopri5Options<T> {
    /// Relative tolerance on each coordinate and velocity. Default 1e-8.
    pub rtol: T,
    /// Absolute tolerance (m, rad, m/s, rad/s). Default 1e-10.
    pub atol: T,
    /// First step size (s); 0 chooses one from the initial derivatives (Hairer's rule). Default 0.
    pub initial_step: T,
    /// Largest step size (s). Default 0.1 s.
    pub max_step: T,
    /// Smallest step size before failing with [`SimulationError::StepSizeTooSmall`]. Default 1e-12 s.
    pub min_step: T,
}

impl<T: Real> Default for Dopri5Options<T> {
    fn default() -> Self {
        Self {
            rtol: T::from_f64(1e-8),
            atol: T::from_f64(1e-10),
            initial_step: T::ZERO,
            max_step: T::from_f64(0.1),
            min_step: T::from_f64(1e-12),
        }
    }
}

/// Dormand–Prince 5(4) with error control, PI step-size control and dense output (Hairer,
/// Nørsett & Wanner, *Solving ODEs I*, II.5 and its `DOPRI5` code). The work integrals use the
/// method's 5th-order weights on the stage powers.
#[derive(Clone, Copy, Debug)]
pub struct Dopri5<T, const NQ: usize> {
    /// Tolerances and step limits.
    pub options: Dopri5Options<T>,
    /// The step size the next step will try (s); 0 before the first.
    pub next_step: T,
    /// Accepted and rejected steps so far.
    pub accepted: u64,
    /// Rejected steps so far.
    pub rejected: u64,
    previous_error: T,
    // Dense output of the last step: y(θ) = r1 + θ(r2 + (1−θ)(r3 + θ(r4 + (1−θ) r5))) for q, q̇.
    dense: [[[T; NQ]; 2]; 5],
}

impl<T: Real, const NQ: usize> Dopri5<T, NQ> {
    /// A Dormand–Prince integrator with the given options.
    pub fn new(options: Dopri5Options<T>) -> Self {
        Self { options, next_step: T::ZERO, accepted: 0, rejected: 0, previous_error: T::from_f64(1e-4), dense: [[[T::ZERO; NQ]; 2]; 5] }
    }
}

impl<T: Real, const NQ: usize> Default for Dopri5<T, NQ> {
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

impl<T: Real, M: ForwardDynamics<T, NQ, NC>, const NQ: usize, const NC: usize> Integrator<T, M, NQ, NC> for Dopri5<T, NQ> {
    // `!(x > y)` on purpose: it is also true when either side is NaN.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    fn step(
        &mut self,
        system: &System<'_, M, T>,
        from: &Point<T, NQ, NC>,
        t_max: T,
        to: &mut Point<T, NQ, NC>,
    ) -> Result<(), SimulationError> {
        let o = self.options;
        if !(o.rtol >= T::ZERO && o.atol >= T::ZERO && o.rtol + o.atol > T::ZERO) {
            return Err(SimulationError::InvalidOptions { what: "Dopri5 tolerances must be non-negative, not both zero" });
        }
        if !(o.max_step > T::ZERO && o.min_step >= T::ZERO) {
            return Err(SimulationError::InvalidOptions { what: "Dopri5::max_step must be positive, min_step non-negative" });
        }
        let span = t_max - from.t;
        if !(span > T::ZERO) {
            *to = *from;
            return Ok(());
        }
        let scale = |y0: T, y1: T| o.atol + o.rtol * y0.abs().max(y1.abs());
        if !(self.next_step > T::ZERO) {
            self.next_step = if o.initial_step > T::ZERO { o.initial_step } else { initial_step(from, &scale, o.max_step) };
        }
        // Stage derivatives: (q̇, q̈) and powers.
        let mut kq = [[T::ZERO; NQ]; 7];
        let mut kv = [[T::ZERO; NQ]; 7];
        let mut kp = [[T::ZERO; 2]; 7];
        kq[0] = from.qd;
        kv[0] = from.qdd;
        kp[0] = from.power;
        let mut lambda = from.lambda;
        'attempt: loop {
            let mut h = self.next_step.max(o.min_step);
            if h > o.max_step {
                h = o.max_step;
            }
            let last = from.t + h >= t_max;
            if last {
                h = span;
            }
            let mut q = [T::ZERO; NQ];
            let mut qd = [T::ZERO; NQ];
            for s in 1..7 {
                for i in 0..NQ {
                    let (mut dq, mut dv) = (T::ZERO, T::ZERO);
                    for j in 0..s {
                        let a = T::from_f64(A[s][j]);
                        dq += a * kq[j][i];
                        dv += a * kv[j][i];
                    }
                    q[i] = from.q[i] + h * dq;
                    qd[i] = from.qd[i] + h * dv;
                }
                kq[s] = qd;
                let t_s = if s == 6 { from.t + h } else { from.t + T::from_f64(C[s]) * h };
                match system.derivatives(t_s, &q, &qd, &mut kv[s], &mut lambda) {
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
            to.q = q;
            to.qd = qd;
            to.qdd = kv[6];
            to.lambda = lambda;
            to.power = kp[6];
            // Error estimate, RMS over q and q̇ scaled by the tolerances.
            let mut sum = T::ZERO;
            for i in 0..NQ {
                let (mut eq, mut ev) = (T::ZERO, T::ZERO);
                for s in 0..7 {
                    let e = T::from_f64(E[s]);
                    eq += e * kq[s][i];
                    ev += e * kv[s][i];
                }
                let rq = h * eq / scale(from.q[i], to.q[i]);
                let rv = h * ev / scale(from.qd[i], to.qd[i]);
                sum += rq * rq + rv * rv;
            }
            let error = (sum / T::from_f64((2 * NQ).max(1) as f64)).sqrt();
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
                // Dense output coefficients.
                for (c, (y0, y1, k)) in [(&from.q, &to.q, &kq), (&from.qd, &to.qd, &kv)].into_iter().enumerate() {
                    for i in 0..NQ {
                        let r2 = y1[i] - y0[i];
                        let r3 = h * k[0][i] - r2;
                        let r4 = r2 - h * k[6][i] - r3;
                        let mut r5 = T::ZERO;
                        for s in 0..7 {
                            r5 += T::from_f64(D[s]) * k[s][i];
                        }
                        self.dense[0][c][i] = y0[i];
                        self.dense[1][c][i] = r2;
                        self.dense[2][c][i] = r3;
                        self.dense[3][c][i] = r4;
                        self.dense[4][c][i] = h * r5;
                    }
                }
                return check_step::<T, M, NQ, NC>(from, to);
            }
            self.rejected += 1;
            let e = if error.is_finite() { error } else { T::from_f64(1e10) };
            let factor = (safe * e.powf(T::from_f64(-0.2))).max(T::from_f64(0.1));
            self.next_step = h * factor;
            if self.next_step < o.min_step {
                if let Some(coordinate) = non_finite::<T, M, NQ>(&to.q, &to.qd) {
                    return Err(SimulationError::NonFinite { t: from.t.to_f64(), coordinate });
                }
                return Err(SimulationError::StepSizeTooSmall { t: from.t.to_f64(), step: self.next_step.to_f64() });
            }
        }
    }

    fn interpolate(&self, from: &Point<T, NQ, NC>, to: &Point<T, NQ, NC>, t: T, q: &mut [T; NQ], qd: &mut [T; NQ]) {
        let h = to.t - from.t;
        let theta = if h > T::ZERO { (t - from.t) / h } else { T::ONE };
        let one_minus = T::ONE - theta;
        let d = &self.dense;
        for i in 0..NQ {
            for (c, out) in [&mut *q, &mut *qd].into_iter().enumerate() {
                out[i] = d[0][c][i] + theta * (d[1][c][i] + one_minus * (d[2][c][i] + theta * (d[3][c][i] + one_minus * d[4][c][i])));
            }
        }
    }
}

/// Hairer's initial step: h such that an explicit Euler step changes the state by about the
/// tolerance, refined with a second derivative estimate; here the derivatives at hand suffice:
/// h = 0.01 · ‖y‖ / ‖y'‖ in the tolerance's norm, capped by `max_step`.
fn initial_step<T: Real, const NQ: usize, const NC: usize>(p: &Point<T, NQ, NC>, scale: &impl Fn(T, T) -> T, max_step: T) -> T {
    let (mut d0, mut d1) = (T::ZERO, T::ZERO);
    for i in 0..NQ {
        let (sq, sv) = (scale(p.q[i], p.q[i]), scale(p.qd[i], p.qd[i]));
        d0 += (p.q[i] / sq) * (p.q[i] / sq) + (p.qd[i] / sv) * (p.qd[i] / sv);
        d1 += (p.qd[i] / sq) * (p.qd[i] / sq) + (p.qdd[i] / sv) * (p.qdd[i] / sv);
    }
    let h = if d0 < T::from_f64(1e-10) || d1 < T::from_f64(1e-10) { T::from_f64(1e-6) } else { T::from_f64(0.01) * (d0 / d1).sqrt() };
    h.min_(max_step)
}

/// The smaller of two values (NaN-propagating like `max`'s twin).
trait MinExt {
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
