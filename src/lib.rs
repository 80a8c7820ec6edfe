//! **mbd** — multibody dynamics for Rust, generated at compile time.
//!
//! Write a mechanism with [`mechanism!`]; the macro derives its constraints, their Jacobian and
//! the velocity and acceleration right-hand sides symbolically and emits them as straight-line,
//! allocation-free Rust. [`mbd_runtime`]'s solvers (re-exported here) do the analyses.
//!
//! The user's guide is [`guide`]: the DSL, each analysis, integrators, numerical stability,
//! performance and embedded use, with programs that run (they are tested by the `mbd-guide`
//! crate of the repository).
#![cfg_attr(not(feature = "std"), no_std)]

/// The user's guide (`guide/*.md` of the repository), one module per chapter, for `cargo doc`
/// and docs.rs. Documentation only: its programs are compiled and run as the `snippets` test
/// of the repository's `mbd-guide` crate, not here (so they are not built twice). Links between
/// chapters point to the Markdown files, as on the repository's pages.
#[cfg(all(doc, not(doctest)))]
pub mod guide {
    #![doc = include_str!("../guide/README.md")]
    macro_rules! chapters {
        ($($name:ident = $file:literal;)*) => {
            $(
                #[doc = include_str!(concat!("../guide/", $file))]
                pub mod $name {}
            )*
        };
    }
    chapters! {
        dsl = "dsl.md";
        joint_coordinates = "joint-coordinates.md";
        spatial = "spatial.md";
        generated_api = "generated-api.md";
        kinematics = "kinematics.md";
        dynamics = "dynamics.md";
        linearization = "linearization.md";
        animation_and_plots = "animation-and-plots.md";
        numerical_stability = "numerical-stability.md";
        performance = "performance.md";
        build_time = "build-time.md";
        embedded = "embedded.md";
        examples = "examples.md";
    }
}

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
        ErrorControl, GeneralizedAlpha, GeneralizedAlphaOptions, Integrator, Radau5, Radau5Options, Rk4, Rk4Options, Simulation,
        SimulationError, SimulationOptions, Statistics,
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
