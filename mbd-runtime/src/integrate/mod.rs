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
//! [`simulate`](simulate()) drives any of them to a list of output times, corrects drift after
//! each step ([`Correction`]: mass-weighted projection or coordinate partitioning) and hands each
//! output [`Sample`] to a callback.
//!
//! This file holds what they share: the [`Point`] a step ends at, its [`Sample`] and [`Energy`],
//! the [`System`] of equations an [`Integrator`] advances, [`SimulationError`], cubic Hermite
//! interpolation and the end-of-step finiteness check. Each integrator has its own file
//! (`rk4.rs`, `dopri5.rs`, `generalized_alpha.rs`), and the driver its own (`simulate.rs`).

mod dopri5;
mod generalized_alpha;
mod rk4;
mod simulate;

pub use dopri5::{Dopri5, Dopri5Options};
pub use generalized_alpha::{GeneralizedAlpha, GeneralizedAlphaOptions};
pub use rk4::Rk4;
pub use simulate::{project, simulate, Correction, SimulationOptions, Statistics};

use core::fmt;

use crate::kinematics::name;
use crate::{DynamicsError, DynamicsOptions, ForwardDynamics, Mechanism, Real};

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

/// One output of [`simulate`](simulate()).
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
            SimulationError::NotConverged { t, iterations, worst_row, residual } => {
                write!(f, "at t = {t} s Newton did not converge in {iterations} iterations: `{worst_row}` has residual {residual}")
            }
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

    /// Forgets what the method carries from step to step (called by [`simulate`](simulate()) at
    /// its start, so an integrator can be reused for another run).
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
