//! Runtime of **mbd**: the traits generated mechanisms implement and the solvers that use them.
//!
//! `#![no_std]` without the default `std` feature; elementary functions then come from `libm`.
//! Feature `alloc` (part of `std`) adds [`Linearizer`], which needs a heap but not `std`.
//! No solver allocates: O(N²) work space is the caller's [`Workspace`] (made once, on the heap
//! with [`Workspace::boxed`] or in a `static`), the rest fixed-size arrays on the stack.
#![cfg_attr(not(feature = "std"), no_std)]
#![warn(missing_docs)]
// No function over 150 lines (`clippy.toml`).
#![warn(clippy::too_many_lines)]

#[cfg(feature = "alloc")]
extern crate alloc;

#[cfg(feature = "animation")]
mod animation;
mod body;
#[cfg(feature = "std")]
mod csv;
#[cfg(feature = "animation")]
mod drawing;
mod dynamics;
mod error;
mod finite_differences;
mod integrate;
mod inverse;
mod kinematics;
pub mod linalg;
#[cfg(feature = "alloc")]
pub mod linearize;
mod mechanism;
mod named;
mod options;
mod partition;
mod planar;
#[cfg(feature = "plots")]
mod plot;
#[cfg(feature = "progress")]
mod progress;
mod real;
pub mod redundancy;
pub mod sparse;
pub mod statics;
#[cfg(test)]
mod test_support;
pub mod workspace;

#[cfg(feature = "animation")]
pub use animation::{Animation, AnimationError, DEFAULT_SVG_FRAMES, DEFAULT_SVG_SHAPES};
pub use body::{BodyFrames, BodyPose, BodyTwist};
#[cfg(feature = "std")]
pub use csv::CsvWriter;
pub use dynamics::{kinetic_energy, DynamicsError, DynamicsOptions, ForwardDynamics, DEFAULT_BAUMGARTE, DEFAULT_DYNAMICS_PIVOT_TOLERANCE};
pub use error::{KinematicError, NonFiniteQuantity};
pub use finite_differences::FiniteDifferences;
pub use integrate::{
    project, Correction, Dop853, Dop853Options, Dopri5, Dopri5Options, Energy, ErrorControl, Event, EventHit, Flow, GeneralizedAlpha,
    GeneralizedAlphaOptions, Integrator, Point, Rk4, Rk4Options, Sample, Simulation, SimulationError, SimulationOptions, Statistics,
    System,
};
pub use inverse::{joint_reaction, InverseDynamics, InverseDynamicsError, InverseDynamicsOptions, JointReaction, Wrench};
pub use kinematics::{
    Convergence, KinematicOptions, KinematicSolver, KinematicState, DEFAULT_MAX_ITERATIONS, DEFAULT_MAX_STEP, DEFAULT_PIVOT_TOLERANCE,
    DEFAULT_PREDICTOR, DEFAULT_RANK_TOLERANCE, DEFAULT_REUSE_SAFETY, DEFAULT_TOLERANCE, RESOLUTION_ULPS,
};
#[cfg(feature = "alloc")]
pub use linearize::{LinearStability, Linearization, LinearizeError, LinearizeOptions, Linearizer, Mode, Output};
pub use mechanism::{
    ConstraintForces, CoordinateInfo, CoordinateKind, Dynamics, ForceInfo, JointInfo, Kinematics, Linearize, Mechanism, NewtonMatrix,
    OpCount, PositionStep, VelocityInfo, VelocityKind,
};
/// nalgebra, as the runtime uses it (positions, velocities and rotations of named bodies and
/// points come out as its types).
pub use nalgebra;
pub use named::{PlanarBody, PlanarPoint, SpatialBody, SpatialPoint};
pub use partition::Partition;
pub use planar::{point_acceleration, point_position, point_velocity};
#[cfg(feature = "plots")]
pub use plot::{Plot, PlotError};
#[cfg(feature = "progress")]
pub use progress::Progress;
pub use real::Real;
pub use redundancy::Redundancy;
pub use sparse::SparsePattern;
pub use workspace::Workspace;

/// Its items when the runtime has `std`, nothing without (the generated code's `workspace()`,
/// which boxes).
#[doc(hidden)]
#[cfg(feature = "std")]
#[macro_export]
macro_rules! __if_std {
    ($($tokens:tt)*) => { $($tokens)* };
}

/// Its items when the runtime has `std`, nothing without.
#[doc(hidden)]
#[cfg(not(feature = "std"))]
#[macro_export]
macro_rules! __if_std {
    ($($tokens:tt)*) => {};
}
pub use statics::{
    Stability, StaticError, StaticOptions, StaticReport, StaticSolver, DEFAULT_STATIC_ASSEMBLY_ITERATIONS, DEFAULT_STATIC_INITIAL_STEP,
    DEFAULT_STATIC_MAX_ITERATIONS, DEFAULT_STATIC_NEUTRAL_TOLERANCE, DEFAULT_STATIC_PIVOT_TOLERANCE, DEFAULT_STATIC_TOLERANCE,
};
