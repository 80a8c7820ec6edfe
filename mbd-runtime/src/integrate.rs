//! Time integration of the equations of motion (Nikravesh ch. 13; Arnold & Brüls 2007 for the
//! generalized-α method), allocation-free: every work array is a fixed-size field.
//!
//! The state is (t, q, q̇); each step ends at a [`Point`] that also holds q̈, λ and, when asked
//! for, the work of non-conservative forces and of constraint forces. Three integrators:
//!
//! * [`Rk4`]: classical Runge–Kutta, fixed step, 4 evaluations of q̈ per step.
//! * [`Dopri5`]: Dormand–Prince 5(4) with error control (mixed absolute/relative tolerance on q
//!   and q̇), PI step-size control and 4th-order dense output; 6 evaluations per accepted step.
//! * [`GeneralizedAlpha`]: the implicit generalized-α method on the index-3 equations
//!   M q̈ − Φ_qᵀλ = h, Φ = 0, solved by Newton with the exact ∂h/∂q, ∂h/∂q̇ and ∂(Φ_qᵀλ)/∂q:
//!   second-order accurate, numerical damping set by ρ∞, fit for stiff springs and dampers.
//!
//! [`simulate`] drives any of them to a list of output times, corrects drift after each step
//! ([`Correction`]: mass-weighted projection or coordinate partitioning) and hands each output
//! [`Sample`] to a callback.

use core::fmt;

use crate::dynamics::kinetic_energy;
use crate::kinematics::name;
use crate::linalg::{lu_factor, lu_solve_in_place};
use crate::partition::Partition;
use crate::{ConstraintForces, DynamicsError, DynamicsOptions, ForwardDynamics, Mechanism, Real};

/// The state of the mechanism at the end of a step: time, coordinates and their derivatives,
/// multipliers, and the accumulated work.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point<T, const NQ: usize, const NC: usize> {
    /// Time (s).
    pub t: T,
    /// Coordinates (m, rad).
    pub q: [T; NQ],
    /// Velocities (m/s, rad/s).
    pub qd: [T; NQ],
    /// Accelerations (m/s², rad/s²).
    pub qdd: [T; NQ],
    /// Lagrange multipliers (N, N·m per constraint row), M q̈ − Φ_qᵀλ = h.
    pub lambda: [T; NC],
    /// Work since the start (J): `[non-conservative forces, constraint forces]`; zero unless
    /// [`SimulationOptions::track_work`].
    pub work: [T; 2],
    /// The rates of `work` (W).
    pub power: [T; 2],
}

impl<T: Real, const NQ: usize, const NC: usize> Point<T, NQ, NC> {
    /// A point at rest at t = 0 with all zeros (overwritten before use).
    pub fn zero() -> Self {
        Self {
            t: T::ZERO,
            q: [T::ZERO; NQ],
            qd: [T::ZERO; NQ],
            qdd: [T::ZERO; NQ],
            lambda: [T::ZERO; NC],
            work: [T::ZERO; 2],
            power: [T::ZERO; 2],
        }
    }
}

/// Energies at an output time (J): d(T + V)/dt = P_nc + P_c, so `kinetic + potential −
/// nonconservative_work − constraint_work` stays at its initial value up to the integration
/// error (with `track_work`; otherwise both works are zero and T + V is conserved only by
/// conservative mechanisms with scleronomic constraints).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Energy<T> {
    /// ½ q̇ᵀ M q̇.
    pub kinetic: T,
    /// Potential of gravity and springs V(q, t).
    pub potential: T,
    /// ∫ (q̇ᵀh + dV/dt) dt: work of dampers, actuators, applied forces and friction.
    pub nonconservative_work: T,
    /// ∫ λᵀ Φ_q q̇ dt: work of drivers (and of the stabilization on drifted states).
    pub constraint_work: T,
}

impl<T: Real> Energy<T> {
    /// T + V − W_nc − W_c: constant for an exact solution.
    pub fn balance(&self) -> T {
        self.kinetic + self.potential - self.nonconservative_work - self.constraint_work
    }
}

/// One output of [`simulate`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample<T, const NQ: usize, const NC: usize> {
    /// State, accelerations and multipliers at the output time.
    pub point: Point<T, NQ, NC>,
    /// Its energies.
    pub energy: Energy<T>,
}

/// Why a simulation stopped.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum SimulationError {
    /// Forward dynamics failed (dependent constraints, non-positive mass, NaN).
    Dynamics(DynamicsError),
    /// A coordinate or velocity became NaN or infinite: the step size is too large for the
    /// mechanism's stiffness, or the motion diverged.
    NonFinite {
        /// Time of the step's start (s).
        t: f64,
        /// The first non-finite coordinate (its velocity if the name is of a velocity).
        coordinate: &'static str,
    },
    /// Error control asked for a step below the minimum: a singularity or a discontinuity.
    StepSizeTooSmall {
        /// Time (s).
        t: f64,
        /// The rejected step size (s).
        step: f64,
    },
    /// The step budget ran out before the last output time.
    TooManySteps {
        /// Time reached (s).
        t: f64,
        /// Steps taken.
        steps: u64,
    },
    /// Newton (generalized-α, projection or partitioning) did not converge.
    NotConverged {
        /// Time (s).
        t: f64,
        /// Iterations made.
        iterations: u32,
        /// The constraint with the largest residual; or, when every constraint is met and the
        /// corrections do not settle, the coordinate with the largest correction.
        worst_row: &'static str,
        /// That residual or correction (m or rad).
        residual: f64,
    },
    /// An option is out of range (`what` names it and the rule).
    InvalidOptions {
        /// The option and what it must be.
        what: &'static str,
    },
    /// The output times are not non-decreasing from the initial time.
    TimesNotIncreasing {
        /// Index of the first offending time.
        index: usize,
    },
    /// A generalized-α work space does not have NQ + NC rows (use the generated
    /// `Name::generalized_alpha`).
    WorkspaceSize {
        /// Rows the mechanism needs.
        expected: usize,
        /// Rows the work space has.
        found: usize,
    },
}

impl From<DynamicsError> for SimulationError {
    fn from(e: DynamicsError) -> Self {
        SimulationError::Dynamics(e)
    }
}

impl fmt::Display for SimulationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SimulationError::Dynamics(e) => write!(f, "{e}"),
            SimulationError::NonFinite { t, coordinate } => {
                write!(f, "the step from t = {t} s made `{coordinate}` NaN or infinite (step too large for the stiffness?)")
            }
            SimulationError::StepSizeTooSmall { t, step } => {
                write!(f, "at t = {t} s error control needed a step of {step} s, below the minimum")
            }
            SimulationError::TooManySteps { t, steps } => write!(f, "{steps} steps taken, stopped at t = {t} s"),
            SimulationError::NotConverged { t, iterations, worst_row, residual } => write!(
                f,
                "at t = {t} s Newton did not converge in {iterations} iterations: `{worst_row}` has residual {residual}"
            ),
            SimulationError::InvalidOptions { what } => write!(f, "invalid option: {what}"),
            SimulationError::TimesNotIncreasing { index } => {
                write!(f, "output time {index} is before the one before it or before the start")
            }
            SimulationError::WorkspaceSize { expected, found } => {
                write!(f, "the generalized-α work space has {found} rows; this mechanism needs NQ + NC = {expected}")
            }
        }
    }
}

impl core::error::Error for SimulationError {}

/// The equations of motion an integrator advances: the mechanism, its forward-dynamics options
/// and whether work is accumulated.
#[derive(Clone, Copy, Debug)]
pub struct System<'m, M, T> {
    /// The mechanism.
    pub mechanism: &'m M,
    /// Baumgarte α, β and the pivot rule of the solve.
    pub dynamics: DynamicsOptions<T>,
    /// Accumulate the work of non-conservative and constraint forces (one more evaluation of h
    /// and of the non-conservative power per stage). Default off: what is not asked costs nothing.
    pub track_work: bool,
}

impl<'m, M, T: Real> System<'m, M, T> {
    /// The mechanism with default dynamics options (Baumgarte α = β = 5) and no work tracking.
    pub fn new(mechanism: &'m M) -> Self {
        Self { mechanism, dynamics: DynamicsOptions::default(), track_work: false }
    }

    /// q̈ and λ at (t, q, q̇), and the powers `[P_nc, P_c]` when work is tracked.
    #[inline]
    pub fn derivatives<const NQ: usize, const NC: usize>(
        &self,
        t: T,
        q: &[T; NQ],
        qd: &[T; NQ],
        qdd: &mut [T; NQ],
        lambda: &mut [T; NC],
    ) -> Result<[T; 2], DynamicsError>
    where
        M: ForwardDynamics<T, NQ, NC>,
    {
        self.mechanism.accelerations(q, qd, t, &self.dynamics, qdd, lambda)?;
        if !self.track_work {
            return Ok([T::ZERO; 2]);
        }
        let mut nonconservative = self.mechanism.nonconservative_power(q, qd, t);
        // Coulomb friction (absent from the generated power, which is λ-free).
        let mut friction = [T::ZERO; NQ];
        self.mechanism.friction_forces(q, qd, t, lambda, &mut friction);
        for i in 0..NQ {
            nonconservative += qd[i] * friction[i];
        }
        // λᵀ Φ_q q̇ = q̇ᵀ (M q̈ − h − h_friction)
        let mut h = [T::ZERO; NQ];
        self.mechanism.forces(q, qd, t, &mut h);
        for i in 0..NQ {
            h[i] += friction[i];
        }
        let m = self.mechanism.mass_diagonal();
        let mut constraint = T::ZERO;
        for i in 0..NQ {
            constraint += qd[i] * (m[i] * qdd[i] - h[i]);
        }
        Ok([nonconservative, constraint])
    }

    /// A point at (t, q, q̇) with its q̈, λ and powers; `work` as given.
    pub fn point<const NQ: usize, const NC: usize>(
        &self,
        t: T,
        q: [T; NQ],
        qd: [T; NQ],
        work: [T; 2],
    ) -> Result<Point<T, NQ, NC>, DynamicsError>
    where
        M: ForwardDynamics<T, NQ, NC>,
    {
        let mut p = Point { t, q, qd, qdd: [T::ZERO; NQ], lambda: [T::ZERO; NC], work, power: [T::ZERO; 2] };
        p.power = self.derivatives(t, &p.q, &p.qd, &mut p.qdd, &mut p.lambda)?;
        Ok(p)
    }
}

/// A one-step method for the equations of motion.
pub trait Integrator<T: Real, M, const NQ: usize, const NC: usize> {
    /// One step from `from` (whose q̈, λ and powers are consistent with its state) to at most
    /// `t_max`; writes the end point `to` with its q̈, λ and powers.
    ///
    /// # Errors
    /// A [`SimulationError`] naming the time, coordinate or constraint.
    fn step(
        &mut self,
        system: &System<'_, M, T>,
        from: &Point<T, NQ, NC>,
        t_max: T,
        to: &mut Point<T, NQ, NC>,
    ) -> Result<(), SimulationError>;

    /// q and q̇ at `t` within the last step from `from` to `to` (its dense output).
    fn interpolate(&self, from: &Point<T, NQ, NC>, to: &Point<T, NQ, NC>, t: T, q: &mut [T; NQ], qd: &mut [T; NQ]);

    /// Forgets what the method carries from step to step (called by [`simulate`] at its start,
    /// so an integrator can be reused for another run).
    fn restart(&mut self) {}
}

/// Cubic Hermite interpolation of y with derivative yd between two points, at θ ∈ [0, 1] of a
/// step of length h.
#[inline]
fn hermite<T: Real>(y0: T, yd0: T, y1: T, yd1: T, h: T, theta: T) -> T {
    let one = T::ONE;
    let two = T::from_f64(2.0);
    let three = T::from_f64(3.0);
    let t2 = theta * theta;
    let t3 = t2 * theta;
    let h00 = two * t3 - three * t2 + one;
    let h10 = t3 - two * t2 + theta;
    let h01 = three * t2 - two * t3;
    let h11 = t3 - t2;
    h00 * y0 + h10 * h * yd0 + h01 * y1 + h11 * h * yd1
}

/// Hermite interpolation of q (with q̇) and of q̇ (with q̈) between two points.
fn hermite_state<T: Real, const NQ: usize, const NC: usize>(
    from: &Point<T, NQ, NC>,
    to: &Point<T, NQ, NC>,
    t: T,
    q: &mut [T; NQ],
    qd: &mut [T; NQ],
) {
    let h = to.t - from.t;
    let theta = if h > T::ZERO { (t - from.t) / h } else { T::ONE };
    for i in 0..NQ {
        q[i] = hermite(from.q[i], from.qd[i], to.q[i], to.qd[i], h, theta);
        qd[i] = hermite(from.qd[i], from.qdd[i], to.qd[i], to.qdd[i], h, theta);
    }
}

/// The first non-finite entry of q or q̇, by coordinate name.
fn non_finite<T: Real, M: Mechanism, const NQ: usize>(q: &[T; NQ], qd: &[T; NQ]) -> Option<&'static str> {
    let i = q.iter().chain(qd.iter()).position(|v| !v.is_finite())?;
    Some(name(M::COORDINATE_NAMES, i % NQ))
}

fn check_step<T: Real, M: Mechanism, const NQ: usize, const NC: usize>(
    from: &Point<T, NQ, NC>,
    to: &Point<T, NQ, NC>,
) -> Result<(), SimulationError> {
    match non_finite::<T, M, NQ>(&to.q, &to.qd) {
        Some(coordinate) => Err(SimulationError::NonFinite { t: from.t.to_f64(), coordinate }),
        None => Ok(()),
    }
}

/// Classical fourth-order Runge–Kutta with a fixed step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rk4<T> {
    /// Step size h (s); the last step before an end time may be shorter. Default 1e-3 s.
    pub step: T,
}

impl<T: Real> Default for Rk4<T> {
    fn default() -> Self {
        Self { step: T::from_f64(1e-3) }
    }
}

impl<T: Real> Rk4<T> {
    /// RK4 with step `step` (s).
    pub fn new(step: T) -> Self {
        Self { step }
    }
}

impl<T: Real, M: ForwardDynamics<T, NQ, NC>, const NQ: usize, const NC: usize> Integrator<T, M, NQ, NC> for Rk4<T> {
    #[inline]
    fn step(
        &mut self,
        system: &System<'_, M, T>,
        from: &Point<T, NQ, NC>,
        t_max: T,
        to: &mut Point<T, NQ, NC>,
    ) -> Result<(), SimulationError> {
        if !(self.step > T::ZERO) {
            return Err(SimulationError::InvalidOptions { what: "Rk4::step must be positive" });
        }
        let h = if from.t + self.step > t_max { t_max - from.t } else { self.step };
        let half = h * T::from_f64(0.5);
        let sixth = h / T::from_f64(6.0);
        let two = T::from_f64(2.0);
        let t_half = from.t + half;
        // The start's multipliers: the first guess of Coulomb friction loads, if any.
        let mut lambda = from.lambda;
        // k1 = (q̇0, q̈0)
        let mut q = [T::ZERO; NQ];
        let mut qd2 = [T::ZERO; NQ];
        for i in 0..NQ {
            q[i] = from.q[i] + half * from.qd[i];
            qd2[i] = from.qd[i] + half * from.qdd[i];
        }
        let mut qdd2 = [T::ZERO; NQ];
        let p2 = system.derivatives(t_half, &q, &qd2, &mut qdd2, &mut lambda)?;
        let mut qd3 = [T::ZERO; NQ];
        for i in 0..NQ {
            q[i] = from.q[i] + half * qd2[i];
            qd3[i] = from.qd[i] + half * qdd2[i];
        }
        let mut qdd3 = [T::ZERO; NQ];
        let p3 = system.derivatives(t_half, &q, &qd3, &mut qdd3, &mut lambda)?;
        let mut qd4 = [T::ZERO; NQ];
        for i in 0..NQ {
            q[i] = from.q[i] + h * qd3[i];
            qd4[i] = from.qd[i] + h * qdd3[i];
        }
        let mut qdd4 = [T::ZERO; NQ];
        let p4 = system.derivatives(from.t + h, &q, &qd4, &mut qdd4, &mut lambda)?;
        for i in 0..NQ {
            to.q[i] = from.q[i] + sixth * (from.qd[i] + two * (qd2[i] + qd3[i]) + qd4[i]);
            to.qd[i] = from.qd[i] + sixth * (from.qdd[i] + two * (qdd2[i] + qdd3[i]) + qdd4[i]);
        }
        for k in 0..2 {
            to.work[k] = from.work[k] + sixth * (from.power[k] + two * (p2[k] + p3[k]) + p4[k]);
        }
        to.t = from.t + h;
        check_step::<T, M, NQ, NC>(from, to)?;
        to.power = system.derivatives(to.t, &to.q, &to.qd, &mut to.qdd, &mut to.lambda)?;
        Ok(())
    }

    fn interpolate(&self, from: &Point<T, NQ, NC>, to: &Point<T, NQ, NC>, t: T, q: &mut [T; NQ], qd: &mut [T; NQ]) {
        hermite_state(from, to, t, q, qd);
    }
}

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

/// Options of [`GeneralizedAlpha`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GeneralizedAlphaOptions<T> {
    /// Step size h (s). Default 1e-3 s.
    pub step: T,
    /// Spectral radius at infinite frequency ρ∞ ∈ [0, 1]: 1 keeps every mode undamped, 0
    /// annihilates the highest frequencies in one step. Default 0.8.
    pub rho_infinity: T,
    /// Newton tolerance on ‖Φ‖∞ (m, rad) and on the correction ‖Δq‖∞ (m, rad). Default 1e-10.
    pub tolerance: T,
    /// Newton iterations per step before failing. Default 12.
    pub max_iterations: u32,
    /// Relative pivot tolerance of the LU of the iteration matrix. Default 1e-13.
    pub pivot_tolerance: T,
}

impl<T: Real> Default for GeneralizedAlphaOptions<T> {
    fn default() -> Self {
        Self {
            step: T::from_f64(1e-3),
            rho_infinity: T::from_f64(0.8),
            tolerance: T::from_f64(1e-10),
            max_iterations: 12,
            pivot_tolerance: T::from_f64(1e-13),
        }
    }
}

/// The generalized-α method on the index-3 equations of motion (Chung & Hulbert 1993; Arnold &
/// Brüls 2007, as in Chrono and Exudyn): with pseudo-accelerations a,
///
/// ```text
/// (1 − α_m) a₊ + α_m a = (1 − α_f) q̈₊ + α_f q̈
/// q₊ = q + h q̇ + h² (½ − β) a + h² β a₊,     q̇₊ = q̇ + h (1 − γ) a + h γ a₊
/// M q̈₊ − Φ_qᵀ λ₊ = h(q₊, q̇₊, t₊),           Φ(q₊, t₊) = 0
/// ```
///
/// solved for (q̈₊, λ₊) by Newton with the exact iteration matrix
/// [[M − γ'h ∂h/∂q̇ − β'h² (∂h/∂q + ∂(Φ_qᵀλ)/∂q), −Φ_qᵀ], [Φ_q, 0]] (β' = β(1−α_f)/(1−α_m),
/// γ' = γ(1−α_f)/(1−α_m); the constraint rows scaled by 1/(β'h²)). h includes Coulomb friction
/// at the iterate's λ, and ∂h/∂q, ∂h/∂q̇ its exact derivatives at fixed λ
/// ([`Dynamics::friction_derivatives`]; friction's slope in λ, at most μ, is left out). Where a
/// full Newton step makes the residual ‖r‖₂ grow — a saturating law such as regularized friction
/// near sticking makes Newton overshoot and cycle — the step is halved, up to six times.
/// N must be NQ + NC; the generated `Name::generalized_alpha(options)` makes one of the right size.
#[derive(Clone, Copy, Debug)]
pub struct GeneralizedAlpha<T, const N: usize> {
    /// Step size, damping and Newton options.
    pub options: GeneralizedAlphaOptions<T>,
    /// Newton iterations of the last step.
    pub iterations: u32,
    // Pseudo-acceleration a of the last point, and whether it is valid.
    a: [T; N],
    started: bool,
    matrix: [[T; N]; N],
}

impl<T: Real, const N: usize> GeneralizedAlpha<T, N> {
    /// A generalized-α integrator (N = NQ + NC).
    pub fn new(options: GeneralizedAlphaOptions<T>) -> Self {
        Self { options, iterations: 0, a: [T::ZERO; N], started: false, matrix: [[T::ZERO; N]; N] }
    }

    /// Forget the pseudo-accelerations: the next step starts from q̈ of its initial point (call
    /// after changing the state by hand).
    pub fn restart(&mut self) {
        self.started = false;
    }
}

impl<T: Real, M, const NQ: usize, const NC: usize, const N: usize> Integrator<T, M, NQ, NC> for GeneralizedAlpha<T, N>
where
    M: ForwardDynamics<T, NQ, NC> + ConstraintForces<T, NQ, NC>,
{
    fn step(
        &mut self,
        system: &System<'_, M, T>,
        from: &Point<T, NQ, NC>,
        t_max: T,
        to: &mut Point<T, NQ, NC>,
    ) -> Result<(), SimulationError> {
        if N != NQ + NC {
            return Err(SimulationError::WorkspaceSize { expected: NQ + NC, found: N });
        }
        let o = self.options;
        if !(o.step > T::ZERO) {
            return Err(SimulationError::InvalidOptions { what: "GeneralizedAlphaOptions::step must be positive" });
        }
        if !(o.rho_infinity >= T::ZERO && o.rho_infinity <= T::ONE) {
            return Err(SimulationError::InvalidOptions { what: "GeneralizedAlphaOptions::rho_infinity must be in [0, 1]" });
        }
        let mech = system.mechanism;
        let one = T::ONE;
        let half = T::from_f64(0.5);
        let rho = o.rho_infinity;
        let alpha_m = (T::from_f64(2.0) * rho - one) / (rho + one);
        let alpha_f = rho / (rho + one);
        let gamma = half + alpha_f - alpha_m;
        let beta = T::from_f64(0.25) * (gamma + half) * (gamma + half);
        let h = if from.t + o.step > t_max { t_max - from.t } else { o.step };
        if !(h > T::ZERO) {
            *to = *from;
            return Ok(());
        }
        let beta_p = beta * (one - alpha_f) / (one - alpha_m);
        let gamma_p = gamma * (one - alpha_f) / (one - alpha_m);
        let mut a_n = [T::ZERO; NQ];
        if self.started {
            a_n.copy_from_slice(&self.a[..NQ]);
        } else {
            a_n = from.qdd;
        }
        let t1 = from.t + h;
        let m = mech.mass_diagonal();
        // Unknowns: q̈₊ (start from q̈) and λ₊ (start from λ).
        let mut qdd = from.qdd;
        let mut lambda = from.lambda;
        let mut q = [T::ZERO; NQ];
        let mut qd = [T::ZERO; NQ];
        let mut a1 = [T::ZERO; NQ];
        let (mut phi, mut d, mut nu, mut gam) = ([T::ZERO; NC], [[T::ZERO; NQ]; NC], [T::ZERO; NC], [T::ZERO; NC]);
        let mut hq = [[T::ZERO; NQ]; NQ];
        let mut hqd = [[T::ZERO; NQ]; NQ];
        let mut kc = [[T::ZERO; NQ]; NQ];
        let mut force = [T::ZERO; NQ];
        let mut rhs = [T::ZERO; N];
        let mut iteration = 0;
        // Backtracking on ‖r‖₂: the last Newton step's start, direction, fraction θ
        // taken, the residual it started from and the size of the full correction.
        let (mut base_qdd, mut base_lambda) = (qdd, lambda);
        let mut step = [T::ZERO; N];
        let mut theta = one;
        let mut norm_before = T::ZERO;
        let mut correction = T::ZERO;
        loop {
            for i in 0..NQ {
                a1[i] = (alpha_f * from.qdd[i] + (one - alpha_f) * qdd[i] - alpha_m * a_n[i]) / (one - alpha_m);
                q[i] = from.q[i] + h * from.qd[i] + h * h * ((half - beta) * a_n[i] + beta * a1[i]);
                qd[i] = from.qd[i] + h * ((one - gamma) * a_n[i] + gamma * a1[i]);
            }
            mech.full_eval(&q, &qd, t1, &mut phi, &mut d, &mut nu, &mut gam);
            mech.forces(&q, &qd, t1, &mut force);
            // Coulomb friction with the iterate's loads (its exact ∂/∂q and ∂/∂q̇ enter the
            // iteration matrix below; its dependence on λ is left out, a quasi-Newton step of
            // slope ≤ μ).
            mech.friction_forces(&q, &qd, t1, &lambda, &mut force);
            // Residuals: r = M q̈ − Φ_qᵀλ − h, Φ/(β'h²).
            let mut worst = (T::ZERO, 0usize);
            for i in 0..NQ {
                let mut r = m[i] * qdd[i] - force[i];
                for (row, &l) in d.iter().zip(lambda.iter()) {
                    r -= row[i] * l;
                }
                rhs[i] = -r;
            }
            for (r, &p) in phi.iter().enumerate() {
                rhs[NQ + r] = -p / (beta_p * h * h);
                if p.abs() > worst.0 {
                    worst = (p.abs(), r);
                }
            }
            // A saturating force (regularized Coulomb friction, v/√(v² + v_s²)) makes full
            // Newton steps overshoot and cycle; where the step made the residual grow, take half
            // of it instead (at most six times, then go on from there).
            let norm = rhs.iter().fold(T::ZERO, |s, &r| s + r * r);
            if iteration > 0 && correction > o.tolerance && !(norm <= norm_before) && theta > T::from_f64(1.0 / 64.0) {
                theta = theta * half;
                for i in 0..NQ {
                    qdd[i] = base_qdd[i] + theta * step[i];
                }
                for r in 0..NC {
                    lambda[r] = base_lambda[r] + theta * step[NQ + r];
                }
                continue;
            }
            if iteration >= o.max_iterations {
                // Name the violated constraint, or, with every constraint met, the coordinate
                // whose correction would not settle.
                let (worst_row, residual) = if worst.0 > o.tolerance {
                    (name(M::CONSTRAINT_NAMES, worst.1), worst.0)
                } else {
                    let k = (0..NQ).fold(0, |k, i| if step[i].abs() > step[k].abs() { i } else { k });
                    (name(M::COORDINATE_NAMES, k), (step[k] * beta_p * h * h).abs())
                };
                return Err(SimulationError::NotConverged { t: t1.to_f64(), iterations: iteration, worst_row, residual: residual.to_f64() });
            }
            mech.forces_q(&q, &qd, t1, &mut hq);
            mech.forces_qd(&q, &qd, t1, &mut hqd);
            mech.friction_derivatives(&q, &qd, t1, &lambda, &mut hq, &mut hqd);
            mech.constraint_force_q(&q, t1, &lambda, &mut kc);
            let a = &mut self.matrix;
            for i in 0..NQ {
                for j in 0..NQ {
                    a[i][j] = -gamma_p * h * hqd[i][j] - beta_p * h * h * (hq[i][j] + kc[i][j]);
                }
                a[i][i] += m[i];
                for r in 0..NC {
                    a[i][NQ + r] = -d[r][i];
                }
            }
            for r in 0..NC {
                for j in 0..NQ {
                    a[NQ + r][j] = d[r][j];
                }
                for k in 0..NC {
                    a[NQ + r][NQ + k] = T::ZERO;
                }
            }
            let permutation = match lu_factor(a, o.pivot_tolerance) {
                Ok(p) => p,
                Err(_) => {
                    return Err(SimulationError::Dynamics(DynamicsError::DependentConstraint {
                        t: t1.to_f64(),
                        row: name(M::CONSTRAINT_NAMES, worst.1),
                    }))
                }
            };
            lu_solve_in_place(a, &permutation, &mut rhs);
            (base_qdd, base_lambda, step, theta, norm_before) = (qdd, lambda, rhs, one, norm);
            correction = T::ZERO;
            for i in 0..NQ {
                qdd[i] += rhs[i];
                correction = correction.max((rhs[i] * beta_p * h * h).abs());
            }
            for r in 0..NC {
                lambda[r] += rhs[NQ + r];
            }
            iteration += 1;
            if !correction.is_finite() {
                return Err(SimulationError::NonFinite { t: from.t.to_f64(), coordinate: name(M::COORDINATE_NAMES, 0) });
            }
            if correction <= o.tolerance && worst.0 <= o.tolerance {
                break;
            }
        }
        // The state of the converged iterate (the last correction is below tolerance).
        for i in 0..NQ {
            a1[i] = (alpha_f * from.qdd[i] + (one - alpha_f) * qdd[i] - alpha_m * a_n[i]) / (one - alpha_m);
            q[i] = from.q[i] + h * from.qd[i] + h * h * ((half - beta) * a_n[i] + beta * a1[i]);
            qd[i] = from.qd[i] + h * ((one - gamma) * a_n[i] + gamma * a1[i]);
        }
        self.iterations = iteration;
        self.a[..NQ].copy_from_slice(&a1);
        self.started = true;
        to.t = t1;
        to.q = q;
        to.qd = qd;
        to.qdd = qdd;
        to.lambda = lambda;
        check_step::<T, M, NQ, NC>(from, to)?;
        to.power = if system.track_work {
            let mut scratch_qdd = [T::ZERO; NQ];
            let mut scratch_lambda = [T::ZERO; NC];
            system.derivatives(t1, &q, &qd, &mut scratch_qdd, &mut scratch_lambda)?
        } else {
            [T::ZERO; 2]
        };
        // Trapezoidal rule for the work: second order, like the method.
        for k in 0..2 {
            to.work[k] = from.work[k] + half * h * (from.power[k] + to.power[k]);
        }
        Ok(())
    }

    fn interpolate(&self, from: &Point<T, NQ, NC>, to: &Point<T, NQ, NC>, t: T, q: &mut [T; NQ], qd: &mut [T; NQ]) {
        hermite_state(from, to, t, q, qd);
    }

    fn restart(&mut self) {
        self.started = false;
    }
}

/// What brings the state back onto the constraint manifold after each step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Correction<T> {
    /// Nothing (Baumgarte stabilization, if set, still acts through the accelerations).
    None,
    /// Mass-weighted projection (Newton on Φ = 0 with steps −M⁻¹Φ_qᵀS⁻¹Φ, then the exact
    /// velocity projection), to ‖Φ‖∞ ≤ `tolerance`.
    Projection {
        /// On ‖Φ‖∞ (m, rad).
        tolerance: T,
        /// Newton steps before failing.
        max_iterations: u32,
    },
    /// Coordinate partitioning (Nikravesh 13.6.2): the integrated independent coordinates are
    /// kept; the dependent ones are solved from Φ = 0 and Φ_q q̇ = ν. The partition is chosen
    /// by full pivoting on Φ_q at the start and again whenever its pivots degrade.
    Partitioning {
        /// On ‖Φ‖∞ (m, rad).
        tolerance: T,
        /// Newton steps before failing.
        max_iterations: u32,
    },
}

impl<T: Real> Correction<T> {
    /// Projection to 1e-10 in at most 10 Newton steps.
    pub fn projection() -> Self {
        Correction::Projection { tolerance: T::from_f64(1e-10), max_iterations: 10 }
    }
    /// Coordinate partitioning to 1e-10 in at most 10 Newton steps.
    pub fn partitioning() -> Self {
        Correction::Partitioning { tolerance: T::from_f64(1e-10), max_iterations: 10 }
    }
}

/// Projects q onto Φ(q, t) = 0 and q̇ onto Φ_q q̇ = ν in the metric of M.
///
/// # Errors
/// [`SimulationError::NotConverged`] if ‖Φ‖∞ stays above `tolerance`; dynamics errors of the solve.
pub fn project<T: Real, M: ForwardDynamics<T, NQ, NC>, const NQ: usize, const NC: usize>(
    mechanism: &M,
    t: T,
    q: &mut [T; NQ],
    qd: &mut [T; NQ],
    options: &DynamicsOptions<T>,
    tolerance: T,
    max_iterations: u32,
) -> Result<(), SimulationError> {
    let mut iterations = 0;
    loop {
        let residual = mechanism.project_positions_step(q, t, options)?;
        if residual <= tolerance {
            // The step just taken was below tolerance too: keep it (it only helps).
            break;
        }
        iterations += 1;
        if iterations > max_iterations {
            let mut phi = [T::ZERO; NC];
            mechanism.constraints(q, t, &mut phi);
            let worst = phi.iter().enumerate().fold((0, T::ZERO), |w, (i, v)| if v.abs() > w.1 { (i, v.abs()) } else { w });
            return Err(SimulationError::NotConverged {
                t: t.to_f64(),
                iterations,
                worst_row: name(M::CONSTRAINT_NAMES, worst.0),
                residual: worst.1.to_f64(),
            });
        }
    }
    mechanism.project_velocities(q, qd, t, options)?;
    Ok(())
}

/// Statistics of a [`simulate`] run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Statistics {
    /// Steps taken (accepted).
    pub steps: u64,
    /// Samples handed to the callback.
    pub samples: u64,
}

/// Options of [`simulate`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SimulationOptions<T> {
    /// Baumgarte α, β and the pivot rule of the forward-dynamics solve.
    pub dynamics: DynamicsOptions<T>,
    /// Drift correction after each step. Default none.
    pub correction: Correction<T>,
    /// Accumulate work for the energy balance. Default off.
    pub track_work: bool,
    /// Step budget. Default 100 million.
    pub max_steps: u64,
}

impl<T: Real> Default for SimulationOptions<T> {
    fn default() -> Self {
        Self { dynamics: DynamicsOptions::default(), correction: Correction::None, track_work: false, max_steps: 100_000_000 }
    }
}

/// Integrates from `initial` (t, q, q̇) and calls `output` at each of `times` (non-decreasing,
/// not before the initial time) with the interpolated state, its q̈ and λ, and its energies.
///
/// The initial state is corrected first when a [`Correction`] is set (initial-condition
/// correction, Nikravesh 14.3). Nothing allocates: storage for the samples is the caller's.
///
/// # Errors
/// The first [`SimulationError`] met; the samples before it have been delivered.
#[allow(clippy::too_many_arguments)]
pub fn simulate<T, M, I, const NQ: usize, const NC: usize>(
    mechanism: &M,
    integrator: &mut I,
    t0: T,
    q0: &[T; NQ],
    qd0: &[T; NQ],
    times: &[T],
    options: &SimulationOptions<T>,
    mut output: impl FnMut(&Sample<T, NQ, NC>),
) -> Result<Statistics, SimulationError>
where
    T: Real,
    M: ForwardDynamics<T, NQ, NC>,
    I: Integrator<T, M, NQ, NC>,
{
    for (i, &t) in times.iter().enumerate() {
        let before = if i == 0 { t0 } else { times[i - 1] };
        if !(t >= before) {
            return Err(SimulationError::TimesNotIncreasing { index: i });
        }
    }
    let system = System { mechanism, dynamics: options.dynamics, track_work: options.track_work };
    let (mut q, mut qd) = (*q0, *qd0);
    let mut partition = Partition::<NQ, NC>::new();
    correct(mechanism, &mut partition, options, t0, &mut q, &mut qd)?;
    let mut from = system.point(t0, q, qd, [T::ZERO; 2])?;
    let mut to = from;
    integrator.restart();
    let mut stats = Statistics::default();
    let t_end = match times.last() {
        Some(&t) => t,
        None => return Ok(stats),
    };
    let mut next = 0;
    while next < times.len() && times[next] <= from.t {
        output(&sample(mechanism, &from));
        stats.samples += 1;
        next += 1;
    }
    while next < times.len() {
        if stats.steps >= options.max_steps {
            return Err(SimulationError::TooManySteps { t: from.t.to_f64(), steps: stats.steps });
        }
        integrator.step(&system, &from, t_end, &mut to)?;
        stats.steps += 1;
        // The integrator's own end point, for its dense output; `to` becomes the corrected one.
        let end = to;
        if !matches!(options.correction, Correction::None) {
            let (mut q, mut qd) = (to.q, to.qd);
            correct(mechanism, &mut partition, options, to.t, &mut q, &mut qd)?;
            to = system.point(to.t, q, qd, to.work)?;
        }
        while next < times.len() && times[next] <= end.t {
            if times[next] == end.t {
                output(&sample(mechanism, &to));
            } else {
                let (mut q, mut qd) = ([T::ZERO; NQ], [T::ZERO; NQ]);
                integrator.interpolate(&from, &end, times[next], &mut q, &mut qd);
                let work = interpolate_work(&from, &end, times[next]);
                output(&sample(mechanism, &system.point(times[next], q, qd, work)?));
            }
            stats.samples += 1;
            next += 1;
        }
        from = to;
    }
    Ok(stats)
}

fn interpolate_work<T: Real, const NQ: usize, const NC: usize>(from: &Point<T, NQ, NC>, to: &Point<T, NQ, NC>, t: T) -> [T; 2] {
    let h = to.t - from.t;
    let theta = if h > T::ZERO { (t - from.t) / h } else { T::ONE };
    core::array::from_fn(|k| hermite(from.work[k], from.power[k], to.work[k], to.power[k], h, theta))
}

/// A point with its energies.
fn sample<T: Real, M: ForwardDynamics<T, NQ, NC>, const NQ: usize, const NC: usize>(mechanism: &M, p: &Point<T, NQ, NC>) -> Sample<T, NQ, NC> {
    let energy = Energy {
        kinetic: kinetic_energy(mechanism, &p.qd),
        potential: mechanism.potential_energy(&p.q, p.t),
        nonconservative_work: p.work[0],
        constraint_work: p.work[1],
    };
    Sample { point: *p, energy }
}

/// Applies the drift correction of `options` to (q, q̇) at t.
fn correct<T: Real, M: ForwardDynamics<T, NQ, NC>, const NQ: usize, const NC: usize>(
    mechanism: &M,
    partition: &mut Partition<NQ, NC>,
    options: &SimulationOptions<T>,
    t: T,
    q: &mut [T; NQ],
    qd: &mut [T; NQ],
) -> Result<(), SimulationError> {
    match options.correction {
        Correction::None => Ok(()),
        Correction::Projection { tolerance, max_iterations } => {
            project(mechanism, t, q, qd, &options.dynamics, tolerance, max_iterations)
        }
        Correction::Partitioning { tolerance, max_iterations } => partition.correct(mechanism, t, q, qd, tolerance, max_iterations),
    }
}
