//! Time integration of the equations of motion (Nikravesh ch. 13; Arnold & Brüls 2007 for the
//! generalized-α method), allocation-free: every work array is a fixed-size field.
//!
//! The state is (t, q, v) with q̇ = B(q) v ([`Kinematics::position_rates`]; planar v = q̇); each
//! step ends at a [`Point`] that also holds v̇, λ and, when asked for, the work of
//! non-conservative forces and of constraint forces. Six integrators:
//!
//! * [`Rk4`]: classical Runge–Kutta, fixed step, 4 evaluations of v̇ per step.
//! * [`Dopri5`]: Dormand–Prince 5(4) with error control (mixed absolute/relative tolerance on q
//!   and v), PI step-size control and 4th-order dense output; 6 evaluations per accepted step.
//! * [`Dop853`]: Dormand–Prince 8(5,3), for tight tolerances: 12 evaluations per accepted step,
//!   7th-order dense output (3 more, only in steps holding an output time).
//! * [`GeneralizedAlpha`]: the implicit generalized-α method on the index-3 equations
//!   M v̇ − Dᵀλ = h, Φ = 0, solved by Newton in velocity space with the exact (∂h/∂q)B, ∂h/∂v
//!   and ∂(Dᵀλ)/∂q·B: second-order accurate, numerical damping set by ρ∞, fit for stiff springs
//!   and dampers; fixed steps, or variable ones from a local error estimate ([`ErrorControl`]).
//! * [`Bdf`]: variable-order (1–5), variable-step BDF on the same index-3 equations through the
//!   same Newton iteration, with error control on q and v: the stiff method.
//! * [`Auto`]: DOPRI5 while the model is not stiff, BDF while it is (switching on DOPRI5's
//!   stiffness test and back where the fast mode has slowed tenfold): the one to start with.
//!
//! Each accepted step ends with [`Kinematics::normalize_positions`] (spatial: unit Euler
//! parameters; planar: nothing).
//!
//! [`Kinematics::position_rates`]: crate::Kinematics::position_rates
//! [`Kinematics::normalize_positions`]: crate::Kinematics::normalize_positions
//!
//! [`Simulation`] drives any of them to a list of output times, corrects drift after
//! each step ([`Correction`]: mass-weighted projection or coordinate partitioning) and hands each
//! output [`Sample`] to a callback.
//!
//! This file holds what they share: the [`Point`] a step ends at, its [`Sample`] and [`Energy`],
//! the [`System`] of equations an [`Integrator`] advances, [`SimulationError`], cubic Hermite
//! interpolation and the end-of-step finiteness check. Each integrator has its own file
//! (`rk4.rs`, `dopri5.rs`, `dop853.rs`, `generalized_alpha.rs`, `bdf.rs`, `auto.rs`; the implicit
//! methods' Newton iteration in `implicit.rs`, DOPRI5's and DOP853's stiffness test in
//! `stiffness.rs`), and the driver its own (`simulate.rs`, with `branch.rs` watching for singular
//! passages and `partition.rs` for coordinate partitioning).

mod auto;
mod bdf;
mod branch;
mod dop853;
mod dopri5;
mod generalized_alpha;
mod implicit;
pub(crate) mod partition;
mod radau5;
mod rk4;
mod simulate;
mod stiffness;
#[cfg(test)]
mod tests;

pub use auto::{Auto, AutoOptions, AutoPhase};
pub use bdf::{Bdf, BdfOptions, BDF_MAX_ORDER};
pub use branch::{SingularPassage, SINGULAR_SINE};
pub use dop853::{Dop853, Dop853Options};
pub use dopri5::{Dopri5, Dopri5Options};
pub use generalized_alpha::{ErrorControl, GeneralizedAlpha, GeneralizedAlphaOptions};
pub use radau5::{Radau5, Radau5Options};
pub use rk4::{Rk4, Rk4Options};
pub use simulate::{project, Correction, Event, EventHit, Simulation, SimulationOptions, Statistics};
pub use stiffness::StiffnessDetected;

use core::fmt;

use crate::model::dynamics::{DynamicsError, DynamicsOptions, ForwardDynamics};
use crate::model::mechanism::{Kinematics, Mechanism};
use crate::model::workspace::{DenseArrays, DenseScratch, WorkArrays};
use crate::real::Real;
use crate::solvers::kinematics::name;

/// The state of the mechanism at the end of a step: time, coordinates, velocities and their
/// derivatives, multipliers, and the accumulated work.
///
/// `repr(C)` and made only of `T` and arrays of `T`: a [`Workspace`](crate::Workspace) holds a simulation's
/// points in its rows of scalars.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point<T, const NQ: usize, const NV: usize, const NC: usize> {
    /// Time (s).
    pub t: T,
    /// Coordinates q (m, rad; spatial: m and Euler parameters).
    pub q: [T; NQ],
    /// Velocities v (m/s, rad/s; planar v = q̇).
    pub v: [T; NV],
    /// Accelerations v̇ (m/s², rad/s²).
    pub vd: [T; NV],
    /// Lagrange multipliers (N, N·m per constraint row), M v̇ − Dᵀλ = h.
    pub lambda: [T; NC],
    /// Work since the start (J): `[non-conservative forces, constraint forces]`; zero unless
    /// [`SimulationOptions::track_work`].
    pub work: [T; 2],
    /// The rates of `work` (W).
    pub power: [T; 2],
}

impl<T: Copy, const NQ: usize, const NV: usize, const NC: usize> Point<T, NQ, NV, NC> {
    /// Makes this point a copy of `other`, field by field: `*self = *other` builds the copy on
    /// the stack first in a debug build, a frame of O(NQ + NV + NC) scalars for each place it
    /// is written.
    pub(crate) fn copy_from(&mut self, other: &Self) {
        self.t = other.t;
        self.q.copy_from_slice(&other.q);
        self.v.copy_from_slice(&other.v);
        self.vd.copy_from_slice(&other.vd);
        self.lambda.copy_from_slice(&other.lambda);
        self.work = other.work;
        self.power = other.power;
    }
}

impl<T: Real, const NQ: usize, const NV: usize, const NC: usize> Point<T, NQ, NV, NC> {
    /// A point at rest at t = 0 with all zeros (overwritten before use).
    pub fn zero() -> Self {
        Self {
            t: T::ZERO,
            q: [T::ZERO; NQ],
            v: [T::ZERO; NV],
            vd: [T::ZERO; NV],
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
    /// ½ vᵀ M v.
    pub kinetic: T,
    /// Potential of gravity and springs V(q, t).
    pub potential: T,
    /// ∫ (vᵀh + dV/dt) dt: work of dampers, actuators, applied forces and friction.
    pub nonconservative_work: T,
    /// ∫ λᵀ D v dt: work of drivers (and of the stabilization on drifted states).
    pub constraint_work: T,
}

impl<T: Real> Energy<T> {
    /// T + V − W_nc − W_c: constant for an exact solution when the run tracks work
    /// ([`SimulationOptions::track_work`](crate::SimulationOptions::track_work), off by
    /// default). Without it both works are 0 and this is T + V, which dampers, friction,
    /// actuators and drivers change.
    pub fn balance(&self) -> T {
        self.kinetic + self.potential - self.nonconservative_work - self.constraint_work
    }
}

/// One output of [`Simulation`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample<T, const NQ: usize, const NV: usize, const NC: usize> {
    /// State, accelerations and multipliers at the output time.
    pub point: Point<T, NQ, NV, NC>,
    /// Its energies.
    pub energy: Energy<T>,
    /// `Some` for the extra sample [`Simulation`] delivers at a located event, at its
    /// instant, on its new side: the switching function (or the user's event function) there
    /// has the sign it changed to (within rounding of the instant it is close to zero, so the
    /// sample is taken just past it). `None` at the output times.
    pub event: Option<EventHit>,
}

/// The Newton iteration behind a [`SimulationError::NotConverged`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum NewtonIteration {
    /// The correction after a step, projecting the positions onto Φ = 0
    /// ([`Correction::projection`]).
    Projection,
    /// Coordinate partitioning's solve for the dependent positions
    /// ([`Correction::partitioning`]).
    Partitioning,
    /// An implicit method's step. Only generalized-α at a fixed step reports it: BDF, Radau5
    /// and generalized-α with error control retry a shorter step instead.
    Step,
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
        /// The first non-finite coordinate, or velocity (from
        /// [`Mechanism::VELOCITY_NAMES`]; planar: named as its coordinate), or — from
        /// generalized-α's Newton step — the constraint row whose multiplier became non-finite.
        coordinate: &'static str,
    },
    /// Error control asked for a step below the minimum: a singularity or a discontinuity.
    StepSizeTooSmall {
        /// Time (s).
        t: f64,
        /// The rejected step size (s).
        step: f64,
    },
    /// Variable-step generalized-α bounding its error per unit time
    /// ([`ErrorControl::per_unit_time`]) needed steps whose error allowance, h (atol + rtol),
    /// is below what the positions resolve: a second-order method cannot meet this tolerance in
    /// this scalar type (in f64 it reaches about 1e-8 where the motion is smooth).
    ToleranceBelowResolution {
        /// Time (s).
        t: f64,
        /// The rejected step size (s).
        step: f64,
        /// The relative tolerance asked.
        rtol: f64,
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
        /// Which Newton iteration failed (generalized-α's step: the message says what to change).
        newton: NewtonIteration,
        /// Iterations made.
        iterations: u32,
        /// The constraint with the largest residual; or, when every constraint is met and the
        /// corrections do not settle, the velocity with the largest correction.
        worst_row: &'static str,
        /// That residual or correction (m or rad).
        residual: f64,
    },
    /// An option is out of range (`what` names it and the rule).
    InvalidOptions {
        /// The option and what it must be.
        what: &'static str,
    },
    /// A [`Simulation`] was run without a start or without output times (`missing` says which
    /// and how to give it).
    Incomplete {
        /// What the simulation lacks.
        missing: &'static str,
    },
    /// The output times are not non-decreasing from the initial time.
    TimesNotIncreasing {
        /// Index of the first offending time.
        index: usize,
    },
    /// The generalized-α iteration matrix has no pivot in the column of a velocity: a direction
    /// with neither mass nor stiffness (a massless body, a zero inertia).
    SingularIterationMatrix {
        /// Time (s).
        t: f64,
        /// The velocity, from [`Mechanism::VELOCITY_NAMES`].
        velocity: &'static str,
    },
    /// A generalized-α work space does not have NV + NC rows (use the generated
    /// `Name::generalized_alpha`).
    WorkspaceSize {
        /// Rows the mechanism needs.
        expected: usize,
        /// Rows the work space has.
        found: usize,
    },
    /// A generalized-α work space's Newton slots do not have the mechanism's
    /// `NEWTON_STORAGE` scalars (a `Workspace` made by hand; use the generated
    /// `Name::workspace()`).
    NewtonSlotSize {
        /// Scalars the mechanism's planned Newton matrix needs.
        expected: usize,
        /// Scalars each slot of the work space has (NS).
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
                write!(
                    f,
                    "the step from t = {t} s made `{coordinate}` NaN or infinite (a fixed step too large for the stiffness; \
                     an adaptive method reports this only at its minimum step: a state where the model is undefined)"
                )
            }
            SimulationError::StepSizeTooSmall { t, step } => {
                write!(f, "at t = {t} s error control needed a step of {step} s, below the minimum")
            }
            SimulationError::ToleranceBelowResolution { t, step, rtol } => write!(
                f,
                "at t = {t} s generalized-α bounding its error per unit time at rtol {rtol:e} needed steps of {step:e} s, whose error \
                 allowance the positions' resolution cannot measure: loosen rtol and atol, bound the error per step instead \
                 (ErrorControl::with_per_unit_time(false), which does not deliver the tolerance), or use DOP853"
            ),
            SimulationError::TooManySteps { t, steps } => write!(f, "{steps} steps taken, stopped at t = {t} s"),
            SimulationError::NotConverged { t, newton, iterations, worst_row, residual } => {
                write!(f, "at t = {t} s Newton did not converge in {iterations} iterations: `{worst_row}` has residual {residual}")?;
                match newton {
                    NewtonIteration::Step => write!(
                        f,
                        "; generalized-α at a fixed step has no shorter step to retry: give it error control \
                         (with_error_control), which shortens the step where Newton fails and where the motion asks for it; \
                         or shorten the step, or allow more iterations (GeneralizedAlphaOptions::with_max_iterations, \
                         {iterations} in this run) — these two run on at a fixed step, which can step over a contact or \
                         an input shorter than it"
                    ),
                    NewtonIteration::Projection | NewtonIteration::Partitioning => Ok(()),
                }
            }
            SimulationError::InvalidOptions { what } => write!(f, "invalid option: {what}"),
            SimulationError::Incomplete { missing } => write!(f, "the simulation was run without {missing}"),
            SimulationError::TimesNotIncreasing { index } => {
                write!(f, "output time {index} is before the one before it or before the start")
            }
            SimulationError::SingularIterationMatrix { t, velocity } => {
                write!(
                    f,
                    "at t = {t} s the generalized-α iteration matrix is singular in `{velocity}`: no mass or stiffness in that direction"
                )
            }
            SimulationError::WorkspaceSize { expected, found } => {
                write!(f, "the generalized-α work space has {found} rows; this mechanism needs NV + NC = {expected}; use Name::workspace()")
            }
            SimulationError::NewtonSlotSize { expected, found } => write!(
                f,
                "generalized-α: the work space's Newton slots hold {found} scalars but the mechanism needs NEWTON_STORAGE = {expected}; use Name::workspace()"
            ),
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

    /// v̇ and λ at (t, q, v), and the powers `[P_nc, P_c]` when work is tracked. A mechanism
    /// that needs dense arrays (joint coordinates with closed loops) keeps them on the stack
    /// here; an integrator calls [`derivatives_in`](Self::derivatives_in) with its work space's.
    ///
    /// # Errors
    /// As [`ForwardDynamics::accelerations`].
    #[inline]
    pub fn derivatives<const NQ: usize, const NV: usize, const NC: usize>(
        &self,
        t: T,
        q: &[T; NQ],
        v: &[T; NV],
        vd: &mut [T; NV],
        lambda: &mut [T; NC],
    ) -> Result<[T; 2], DynamicsError>
    where
        M: ForwardDynamics<T, NQ, NV, NC>,
    {
        self.derivatives_in(DenseArrays::new().scratch(), t, q, v, vd, lambda)
    }

    /// [`derivatives`](Self::derivatives) with the dense arrays of a mechanism that needs them in
    /// `scratch` (the work space's, [`Workspace::dense`](crate::WorkArrays::dense); see
    /// [`ForwardDynamics::accelerations_in`]).
    ///
    /// # Errors
    /// As [`ForwardDynamics::accelerations`].
    #[inline]
    pub fn derivatives_in<const NQ: usize, const NV: usize, const NC: usize>(
        &self,
        mut scratch: DenseScratch<'_, T, NV, NC>,
        t: T,
        q: &[T; NQ],
        v: &[T; NV],
        vd: &mut [T; NV],
        lambda: &mut [T; NC],
    ) -> Result<[T; 2], DynamicsError>
    where
        M: ForwardDynamics<T, NQ, NV, NC>,
    {
        // Work tracking's vectors (friction's forces, h and M v̇), taken before forward dynamics
        // gets the rest of the rows.
        let work = if self.track_work { Some(scratch.vectors.rows::<NV, 3>()) } else { None };
        self.mechanism.accelerations_in(scratch, q, v, t, &self.dynamics, vd, lambda)?;
        // No NaN leaves a solve silently: a non-finite v̇ or λ is traced to its source (the cold
        // path names the force element). One independent comparison per velocity: v̇ =
        // M⁻¹(h + Dᵀλ) multiplies every λ_r into the velocities of its row, so a non-finite λ
        // makes v̇ non-finite too.
        if !vd.iter().all(|x| x.is_finite()) {
            return Err(crate::model::dynamics::non_finite(self.mechanism, q, v, t, lambda));
        }
        let Some([friction, h, inertia]) = work else {
            return Ok([T::ZERO; 2]);
        };
        let mut nonconservative = self.mechanism.nonconservative_power(q, v, t);
        // Coulomb friction (absent from the generated power, which is λ-free).
        self.mechanism.friction_forces(q, v, t, lambda, friction);
        for i in 0..NV {
            nonconservative += v[i] * friction[i];
        }
        // λᵀ D v = vᵀ (M v̇ − h − h_friction)
        self.mechanism.forces(q, v, t, h);
        for i in 0..NV {
            h[i] += friction[i];
        }
        self.mechanism.mass_times(q, vd, inertia);
        let mut constraint = T::ZERO;
        for i in 0..NV {
            constraint += v[i] * (inertia[i] - h[i]);
        }
        Ok([nonconservative, constraint])
    }

    /// A point at (t, q, v) with its v̇, λ and powers; `work` as given (dense arrays as in
    /// [`derivatives`](Self::derivatives)).
    ///
    /// # Errors
    /// As [`ForwardDynamics::accelerations`].
    pub fn point<const NQ: usize, const NV: usize, const NC: usize>(
        &self,
        t: T,
        q: [T; NQ],
        v: [T; NV],
        work: [T; 2],
    ) -> Result<Point<T, NQ, NV, NC>, DynamicsError>
    where
        M: ForwardDynamics<T, NQ, NV, NC>,
    {
        self.point_in(DenseArrays::new().scratch(), t, q, v, work)
    }

    /// [`point`](Self::point) with the dense arrays in `scratch`, as
    /// [`derivatives_in`](Self::derivatives_in).
    ///
    /// # Errors
    /// As [`ForwardDynamics::accelerations`].
    pub fn point_in<const NQ: usize, const NV: usize, const NC: usize>(
        &self,
        scratch: DenseScratch<'_, T, NV, NC>,
        t: T,
        q: [T; NQ],
        v: [T; NV],
        work: [T; 2],
    ) -> Result<Point<T, NQ, NV, NC>, DynamicsError>
    where
        M: ForwardDynamics<T, NQ, NV, NC>,
    {
        let mut p = Point { t, q, v, vd: [T::ZERO; NV], lambda: [T::ZERO; NC], work, power: [T::ZERO; 2] };
        self.complete_in(scratch, &mut p)?;
        Ok(p)
    }

    /// Sets the point's v̇, λ and powers from its t, q and v (as [`point_in`](Self::point_in)
    /// makes a point, in place: λ from zero, the first guess of Coulomb friction's loads).
    ///
    /// # Errors
    /// As [`ForwardDynamics::accelerations`].
    pub fn complete_in<const NQ: usize, const NV: usize, const NC: usize>(
        &self,
        scratch: DenseScratch<'_, T, NV, NC>,
        p: &mut Point<T, NQ, NV, NC>,
    ) -> Result<(), DynamicsError>
    where
        M: ForwardDynamics<T, NQ, NV, NC>,
    {
        p.vd.fill(T::ZERO);
        p.lambda.fill(T::ZERO);
        p.power = self.derivatives_in(scratch, p.t, &p.q, &p.v, &mut p.vd, &mut p.lambda)?;
        Ok(())
    }
}

/// A one-step method for the equations of motion.
///
/// Every method is required: those that change results between steps (`prepare_interpolation`,
/// `restart`, `after_correction`) have no default, so a wrapper must forward each of them and
/// cannot compile while leaving one out (a forgotten `prepare_interpolation` made DOP853's dense
/// output wrong, a forgotten `after_correction` restarted generalized-α at every step). A
/// wrapper that counts steps:
///
/// ```
/// use mbd_runtime::{ForwardDynamics, Integrator, Point, Real, SimulationError, System, WorkArrays};
///
/// /// Any integrator, counting the steps it takes.
/// struct Counted<I> {
///     inner: I,
///     steps: u64,
/// }
///
/// impl<T: Real, M, I, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>
///     Integrator<T, M, NQ, NV, NC, N, NS> for Counted<I>
/// where
///     I: Integrator<T, M, NQ, NV, NC, N, NS>,
/// {
///     fn step(
///         &mut self,
///         system: &System<'_, M, T>,
///         ws: &mut WorkArrays<T, NV, NC, N, NS>,
///         from: &Point<T, NQ, NV, NC>,
///         t_max: T,
///         to: &mut Point<T, NQ, NV, NC>,
///     ) -> Result<(), SimulationError> {
///         self.steps += 1;
///         self.inner.step(system, ws, from, t_max, to)
///     }
///     fn prepare_interpolation(
///         &mut self,
///         system: &System<'_, M, T>,
///         ws: &mut WorkArrays<T, NV, NC, N, NS>,
///         from: &Point<T, NQ, NV, NC>,
///         to: &Point<T, NQ, NV, NC>,
///     ) -> Result<(), SimulationError> {
///         self.inner.prepare_interpolation(system, ws, from, to)
///     }
///     fn interpolate(&self, m: &M, from: &Point<T, NQ, NV, NC>, to: &Point<T, NQ, NV, NC>, t: T, q: &mut [T; NQ], v: &mut [T; NV]) {
///         self.inner.interpolate(m, from, to, t, q, v)
///     }
///     fn restart(&mut self) {
///         self.steps = 0;
///         self.inner.restart()
///     }
///     fn after_correction(
///         &mut self,
///         system: &System<'_, M, T>,
///         ws: &mut WorkArrays<T, NV, NC, N, NS>,
///         to: &mut Point<T, NQ, NV, NC>,
///     ) -> Result<(), SimulationError>
///     where
///         M: ForwardDynamics<T, NQ, NV, NC>,
///     {
///         self.inner.after_correction(system, ws, to)
///     }
///     fn holds_constraints(&self) -> bool {
///         self.inner.holds_constraints()
///     }
///     fn projected_end(&self) -> Option<T> {
///         self.inner.projected_end()
///     }
///     fn stiffness(&self) -> Option<mbd_runtime::StiffnessDetected> {
///         self.inner.stiffness()
///     }
/// }
/// ```
pub trait Integrator<T: Real, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize = 0> {
    /// Whether each step ends with Φ(q, t) = 0 solved by Newton from the step's prediction (an
    /// index-3 implicit method: generalized-α), which keeps the assembly branch through a
    /// singular position as the projection does, so that a run without a correction need not
    /// be watched for one ([`Statistics::singular`]). Default `false`: watched (a wrapper that
    /// does not forward it has its runs watched, which changes no result).
    fn holds_constraints(&self) -> bool {
        false
    }

    /// `Some(r)` where the method projected the last step's end itself, as [`Simulation`]'s
    /// projection ([`Correction::Projection`]) does: a mass-weighted position step onto Φ = 0
    /// from ‖Φ‖∞ = `r` (the last, if several), then the velocities onto D v = ν (BDF and Radau5
    /// with `project_velocities`). Where `r` meets the projection's tolerance — where its own
    /// Newton loop would stop after that step — the run leaves the point as it is: a second
    /// projection of the same state changes it by rounding only, and cost a tenth of a BDF step.
    /// Default `None`: corrected every step (a wrapper that does not forward it costs that
    /// projection, and changes no result).
    fn projected_end(&self) -> Option<T> {
        None
    }

    /// Stiffness this integrator has seen since it was made (an explicit method whose steps
    /// were held by stability: [`StiffnessDetected`]), for the run's [`Statistics::stiffness`].
    /// Default `None`: not watched (implicit methods, and a wrapper that does not forward it).
    fn stiffness(&self) -> Option<StiffnessDetected> {
        None
    }

    /// One step from `from` (whose v̇, λ and powers are consistent with its state) to at most
    /// `t_max`; writes every field of the end point `to` (its v̇, λ and powers, its q normalized
    /// ([`Kinematics::normalize_positions`](crate::Kinematics::normalize_positions))). `ws` is
    /// the work space's arrays ([`WorkArrays`]): a [`Simulation`] keeps `from` and `to` in the
    /// rest of its [`Workspace`](crate::Workspace).
    ///
    /// # Errors
    /// A [`SimulationError`] naming the time, coordinate or constraint.
    fn step(
        &mut self,
        system: &System<'_, M, T>,
        ws: &mut WorkArrays<T, NV, NC, N, NS>,
        from: &Point<T, NQ, NV, NC>,
        t_max: T,
        to: &mut Point<T, NQ, NV, NC>,
    ) -> Result<(), SimulationError>;

    /// Readies the dense output of the last step from `from` to `to` before the first
    /// [`interpolate`](Integrator::interpolate) inside it: a method whose interpolant needs more
    /// evaluations of v̇ (DOP853's three) makes them here, only for steps that hold an output
    /// time; one whose `step` leaves its interpolant ready returns `Ok(())`.
    ///
    /// # Errors
    /// Those of forward dynamics at the extra stages.
    fn prepare_interpolation(
        &mut self,
        system: &System<'_, M, T>,
        ws: &mut WorkArrays<T, NV, NC, N, NS>,
        from: &Point<T, NQ, NV, NC>,
        to: &Point<T, NQ, NV, NC>,
    ) -> Result<(), SimulationError>;

    /// q and v at `t` within the last step from `from` to `to` (its dense output); `mechanism`
    /// gives the rates q̇ = B(q) v the interpolation of q needs. q is not normalized.
    fn interpolate(&self, mechanism: &M, from: &Point<T, NQ, NV, NC>, to: &Point<T, NQ, NV, NC>, t: T, q: &mut [T; NQ], v: &mut [T; NV]);

    /// Forgets what the method carries from step to step (called by [`Simulation`] at
    /// its start, so an integrator can be reused for another run).
    fn restart(&mut self);

    /// Readies the point to go on from after [`Simulation`] corrected the drift of the step's
    /// end: `to` is that end with its q and v corrected. An explicit method, whose next step
    /// starts from v̇ = f(q, v), sets v̇, λ and the powers of forward dynamics at the corrected
    /// state: `Ok(system.complete_in(ws.dense(), to)?)`. A method whose v̇ and λ are unknowns of
    /// its own equations keeps them (`to` holds them): they are part of its state, and replacing
    /// them by forward dynamics' (with its Baumgarte terms) would restart it every step.
    ///
    /// # Errors
    /// Those of forward dynamics at the corrected state.
    fn after_correction(
        &mut self,
        system: &System<'_, M, T>,
        ws: &mut WorkArrays<T, NV, NC, N, NS>,
        to: &mut Point<T, NQ, NV, NC>,
    ) -> Result<(), SimulationError>
    where
        M: ForwardDynamics<T, NQ, NV, NC>;
}

/// Relative stretch of a fixed step allowed to land on the end time: a last step of up to
/// `(1 + LAST_STEP_STRETCH) · h` is taken whole. The time of a fixed-step run is a sum of steps
/// that is rarely exact in floating point (ten steps of 0.1 s end at 0.9999999999999999 s):
/// without the stretch the run would end on a sliver of about 1e-16 s, which an implicit method
/// divides by h² (generalized-α scales its constraint rows by 1/(β′h²)). The stretch must
/// exceed the rounding a sum of n steps accumulates: at most ε·h·n²/2 (each addition rounds by
/// ε of the running sum), typically ε·h·n^{3/2} (random signs). 1e-3 covers the worst case up
/// to 3·10⁶ steps in f64 and the typical one up to about 10⁸, and changes a last step's error
/// by 0.1 %.
const LAST_STEP_STRETCH: f64 = 1e-3;

/// The size and end time of a fixed step of nominal size `step` from `t` towards `t_max`: the
/// nominal step, or the rest of the way when that is at most [`LAST_STEP_STRETCH`] longer — then
/// the step ends exactly at `t_max`, not at a rounded sum.
#[inline]
pub(crate) fn fixed_step<T: Real>(t: T, step: T, t_max: T) -> (T, T) {
    let remaining = t_max - t;
    if remaining <= step * (T::ONE + T::from_f64(LAST_STEP_STRETCH)) {
        (remaining, t_max)
    } else {
        (step, t + step)
    }
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

/// Hermite interpolation of q (with q̇ = B(q) v at both ends) and of v (with v̇) between two
/// points.
// One index runs over the values and rates at both ends.
#[allow(clippy::needless_range_loop)]
fn hermite_state<T: Real, M, const NQ: usize, const NV: usize, const NC: usize>(
    mechanism: &M,
    from: &Point<T, NQ, NV, NC>,
    to: &Point<T, NQ, NV, NC>,
    t: T,
    q: &mut [T; NQ],
    v: &mut [T; NV],
) where
    M: Kinematics<T, NQ, NV, NC>,
{
    let h = to.t - from.t;
    let theta = if h > T::ZERO { (t - from.t) / h } else { T::ONE };
    let (mut rates_from, mut rates_to) = ([T::ZERO; NQ], [T::ZERO; NQ]);
    mechanism.position_rates(&from.q, &from.v, &mut rates_from);
    mechanism.position_rates(&to.q, &to.v, &mut rates_to);
    for i in 0..NQ {
        q[i] = hermite(from.q[i], rates_from[i], to.q[i], rates_to[i], h, theta);
    }
    for i in 0..NV {
        v[i] = hermite(from.v[i], from.vd[i], to.v[i], to.vd[i], h, theta);
    }
}

/// The first non-finite entry of q (by coordinate name) or of v (by velocity name).
fn non_finite<T: Real, M: Mechanism, const NQ: usize, const NV: usize>(q: &[T; NQ], v: &[T; NV]) -> Option<&'static str> {
    if let Some(i) = q.iter().position(|x| !x.is_finite()) {
        return Some(name(M::COORDINATE_NAMES, i));
    }
    let i = v.iter().position(|x| !x.is_finite())?;
    Some(name(M::VELOCITY_NAMES, i))
}

fn check_step<T: Real, M: Mechanism, const NQ: usize, const NV: usize, const NC: usize>(
    from: &Point<T, NQ, NV, NC>,
    to: &Point<T, NQ, NV, NC>,
) -> Result<(), SimulationError> {
    match non_finite::<T, M, NQ, NV>(&to.q, &to.v) {
        Some(coordinate) => Err(SimulationError::NonFinite { t: from.t.to_f64(), coordinate }),
        None => Ok(()),
    }
}
