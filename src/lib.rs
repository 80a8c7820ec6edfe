//! **mbd** — multibody dynamics for Rust, generated at compile time.
//!
//! Write a mechanism with [`mechanism!`]; the macro derives its constraints, their Jacobian and
//! the velocity and acceleration right-hand sides symbolically and emits them as straight-line,
//! allocation-free Rust. [`mbd_runtime`]'s solvers (re-exported here) do the analyses.
#![cfg_attr(not(feature = "std"), no_std)]

pub use mbd_macros::mechanism;
pub use mbd_runtime::*;

/// What a user of `mechanism!` writes: `use mbd::prelude::*;` — the macro, the traits whose
/// methods a mechanism is called with, each analysis with its options, results and error, the
/// integrators, the work space and the outputs. Nothing in it has a name nalgebra's prelude or
/// `nalgebra::*` also has, or a generic one (`Point`, `Output`, `System`, `Event`, `Flow`,
/// `Mode`, `Energy`, `Sample`); those, the `DEFAULT_*` constants and the rarer types are at
/// `mbd::` (`mbd::Sample`, `mbd::DEFAULT_TOLERANCE`).
pub mod prelude {
    pub use core::f64::consts::PI;
    pub use mbd_macros::mechanism;
    // The traits of a generated mechanism, for its methods (`m.initial_positions()`, …).
    pub use mbd_runtime::{BodyFrames, Dynamics, ForwardDynamics, Kinematics, Linearize, Mechanism, NewtonMatrix, Real};
    // Kinematics, statics, inverse dynamics and reactions.
    pub use mbd_runtime::{
        joint_reaction, joint_reaction_at, kinetic_energy, InverseDynamics, InverseDynamicsError, InverseDynamicsOptions, JointReaction,
        KinematicError, KinematicOptions, KinematicSolver, Stability, StaticError, StaticOptions, StaticReport, StaticSolver, Workspace,
        Wrench,
    };
    // Simulation and its integrators.
    pub use mbd_runtime::{
        Auto, AutoOptions, Bdf, BdfOptions, Correction, Dop853, Dop853Options, Dopri5, Dopri5Options, DynamicsError, DynamicsOptions,
        ErrorControl, GeneralizedAlpha, GeneralizedAlphaOptions, Integrator, Rk4, Rk4Options, Simulation, SimulationError,
        SimulationOptions, Statistics,
    };
    // Linearization and modes.
    #[cfg(any(feature = "alloc", feature = "std"))]
    pub use mbd_runtime::{LinearStability, Linearization, LinearizeError, LinearizeOptions, Linearizer};
    // Outputs.
    #[cfg(feature = "animation")]
    pub use mbd_runtime::Animation;
    #[cfg(feature = "std")]
    pub use mbd_runtime::CsvWriter;
    #[cfg(feature = "plots")]
    pub use mbd_runtime::Plot;
    #[cfg(feature = "progress")]
    pub use mbd_runtime::Progress;
}
