//! Runtime of **mbd**: the traits generated mechanisms implement and the solvers that use them.
//!
//! `#![no_std]` without the default `std` feature; elementary functions then come from `libm`
//! (f64 `sin` and `cos` always do: [`Real`]).
//! Feature `alloc` (part of `std`) adds [`Linearizer`], which needs a heap but not `std`.
//! No solver allocates: O(N²) work space and the solvers' O(N) vectors are the caller's
//! [`Workspace`] (made once, on the heap with [`Workspace::boxed`] or in a `static`), the rest
//! fixed-size arrays on the stack.
#![cfg_attr(not(feature = "std"), no_std)]
#![warn(missing_docs)]
// No function over 150 lines (`clippy.toml`).
#![warn(clippy::too_many_lines)]

#[cfg(feature = "alloc")]
extern crate alloc;

// The modules form layers, each built only on the layers before it: `real` and `options` (the
// scalar, the options pattern); `linalg`; `model` (the traits generated mechanisms implement,
// bodies, work space); `solvers` (the analyses at a state); `integrate`; `output`. The test
// `layering` below keeps it so.
mod integrate;
mod linalg;
mod model;
mod options;
mod output;
mod real;
mod solvers;
#[cfg(test)]
mod test_support;

pub use model::workspace;
pub use solvers::dense_forward;
#[cfg(feature = "alloc")]
pub use solvers::linearize;
pub use solvers::{redundancy, statics};

pub use integrate::partition::Partition;
pub use integrate::{
    project, Auto, AutoOptions, AutoPhase, Bdf, BdfOptions, Correction, Dop853, Dop853Options, Dopri5, Dopri5Options, Energy, ErrorControl,
    Event, EventHit, GeneralizedAlpha, GeneralizedAlphaOptions, Integrator, NewtonIteration, Point, Radau5, Radau5Options, Rk4, Rk4Options,
    Sample, Simulation, SimulationError, SimulationOptions, SingularPassage, Statistics, StiffnessDetected, System, BDF_MAX_ORDER,
    SINGULAR_SINE,
};
pub use linalg::sparse::SparsePattern;
pub use linalg::LinalgError;

/// The sparse LU factorization of the implicit integrators' Newton matrix (generalized-α, BDF,
/// Radau5: slopes c_v and c_q of their own)
///
/// ```text
/// [ A   −Dᵀ ]      A = M − c_v ∂h/∂v − c_q (∂h/∂q·B + ∂(Dᵀλ)/∂q·B)
/// [ D    0  ]
/// ```
///
/// on a pattern that `mechanism!` plans at compile time ([`SparsePattern`]): the elimination
/// order and every fill-in entry are fixed from the structure of M, of the force and constraint
/// derivatives and of D, so a step stores and touches only the structural non-zeros of the
/// factors — O(bodies) for a chain — and never a dense (NV + NC)² matrix.
///
/// # Why no pivoting is needed
///
/// The order puts each multiplier λ_r after every velocity its row of D touches. Then each
/// leading block of the reordered matrix is itself a saddle matrix [[A₁₁, −D₁ᵀ], [D₁, 0]] whose
/// rows D₁ lie entirely within its own velocities, and it is regular whenever A₁₁ is positive
/// definite (A is M plus O(h) terms) and D₁ has full row rank: Gaussian elimination in that order
/// meets no zero pivot at a regular position. A multiplier's pivot is then the Schur complement
/// D_r A⁻¹ D_rᵀ restricted to what came before, positive, and it is compared with its own scale
/// Σ_c D_rc² / |u_cc| (u_cc the pivots of its velocities): a ratio at most the pivot tolerance means row r is, to that tolerance, a
/// combination of the rows eliminated before it (a singular position or a redundant
/// constraint), and the row is dropped (Δλ_r = 0) or reported — what partial pivoting found
/// before, without moving rows.
///
/// [`factor`](crate::sparse::factor) and [`solve`](crate::sparse::solve) are real;
/// [`factor_complex`](crate::sparse::factor_complex) and
/// [`solve_complex`](crate::sparse::solve_complex) factor Radau5's complex block on the same
/// pattern (`Name::NEWTON_PATTERN`).
pub mod sparse {
    pub use crate::linalg::sparse::{factor, factor_complex, solve, solve_complex, SparsePattern};
}
pub use model::body::{BodyFrames, BodyPose, BodyTwist, BodyWrench, JointLoads};
pub use model::dynamics::{
    kinetic_energy, DynamicsError, DynamicsOptions, ForwardDynamics, DEFAULT_BAUMGARTE, DEFAULT_DYNAMICS_PIVOT_TOLERANCE,
};
pub use model::mechanism::{
    BodyCoordinates, ConstraintForces, CoordinateInfo, CoordinateKind, Dynamics, ForceInfo, Formulation, JointInfo, Kinematics, Linearize,
    Mechanism, NewtonMatrix, OpCount, PositionStep, VelocityInfo, VelocityKind,
};
pub use model::named::{PlanarBody, PlanarPoint, SpatialBody, SpatialPoint, TreeBody, TreePoint};
pub use model::planar::{point_acceleration, point_position, point_velocity};
pub use model::workspace::{DenseArrays, DenseScratch, WorkArrays, Workspace};
/// nalgebra, as the runtime uses it (positions, velocities and rotations of named bodies and
/// points come out as its types).
pub use nalgebra;
#[cfg(feature = "animation")]
pub use output::animation::{Animation, AnimationError, DEFAULT_SVG_FRAMES, DEFAULT_SVG_SHAPES};
#[cfg(feature = "std")]
pub use output::csv::CsvWriter;
#[cfg(feature = "plots")]
pub use output::plot::{Plot, PlotError};
#[cfg(feature = "progress")]
pub use output::progress::Progress;
pub use real::Real;
pub use solvers::error::{ConstraintRows, KinematicError, NonFiniteQuantity};
pub use solvers::finite_differences::FiniteDifferences;
pub use solvers::flow::Flow;
pub use solvers::friction::settle_loads;
pub use solvers::inverse::{
    joint_reaction, joint_reaction_at, InverseDynamics, InverseDynamicsError, InverseDynamicsOptions, JointReaction, Wrench,
};
pub use solvers::kinematics::{
    Convergence, KinematicOptions, KinematicSolver, KinematicState, DEFAULT_MAX_ITERATIONS, DEFAULT_MAX_STEP, DEFAULT_PIVOT_TOLERANCE,
    DEFAULT_PREDICTOR, DEFAULT_RANK_TOLERANCE, DEFAULT_REUSE_SAFETY, DEFAULT_TOLERANCE, RESOLUTION_ULPS,
};
#[cfg(feature = "alloc")]
pub use solvers::linearize::{LinearStability, Linearization, LinearizeError, LinearizeOptions, Linearizer, Mode, Output};
pub use solvers::redundancy::Redundancy;
pub use solvers::statics::{
    Stability, StaticError, StaticOptions, StaticReport, StaticSolver, DEFAULT_STATIC_ASSEMBLY_ITERATIONS, DEFAULT_STATIC_INITIAL_STEP,
    DEFAULT_STATIC_MAX_ITERATIONS, DEFAULT_STATIC_NEUTRAL_TOLERANCE, DEFAULT_STATIC_PIVOT_TOLERANCE, DEFAULT_STATIC_TOLERANCE,
};

/// What the code `mechanism!` generates uses and a user does not: kept out of the
/// documentation and the API, as serde keeps its own.
#[doc(hidden)]
pub mod __private {
    pub use crate::linalg::sparse::{max_abs_finite, pivot, refined, schur_pivot, Elements};
    pub use crate::model::dynamics::check_inertia;
    pub use crate::model::group::tangent_operator;
    pub use crate::model::mechanism::KinematicsHooks;
    pub use crate::solvers::newton::{Newton, NewtonNext};
}

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

/// The layers named above (`LAYERS`, in order): every module imports only from its own layer
/// and the layers before it, by the module's path (`crate::model::body::BodyPose`),
/// never through this file's re-exports (`crate::BodyPose`) — so the folders show the
/// architecture and no cycle runs between them. Doc comments, which name items by their public
/// paths, and `$crate` in macros are not imports.
#[cfg(test)]
mod layering {
    const LAYERS: [&[&str]; 6] = [&["options", "real"], &["linalg"], &["model"], &["solvers"], &["integrate"], &["output"]];

    fn layer(module: &str) -> Option<usize> {
        LAYERS.iter().position(|l| l.contains(&module))
    }

    /// Every `crate::name` in the code of `text` (comments left out).
    fn crate_paths(text: &str) -> Vec<String> {
        let mut out = Vec::new();
        for line in text.lines() {
            let code = line.split("//").next().unwrap_or("");
            let mut rest = code;
            while let Some(at) = rest.find("crate::") {
                let before = rest[..at].chars().next_back();
                let after = &rest[at + "crate::".len()..];
                let name: String = after.chars().take_while(|c| c.is_alphanumeric() || *c == '_' || *c == '*' || *c == '{').collect();
                if before != Some('$') && !before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
                    out.push(name);
                }
                rest = after;
            }
        }
        out
    }

    #[test]
    fn each_module_imports_from_its_own_layer_and_those_before_it() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
        let mut files = vec![root.clone()];
        let mut problems = Vec::new();
        let mut checked = 0;
        while let Some(path) = files.pop() {
            if path.is_dir() {
                files.extend(std::fs::read_dir(&path).expect("the sources").map(|e| e.expect("an entry").path()));
                continue;
            }
            let relative = path.strip_prefix(&root).expect("under src").to_string_lossy().replace('\\', "/");
            let top = relative.split('/').next().unwrap_or("").trim_end_matches(".rs").to_string();
            let Some(own) = layer(&top) else {
                // lib.rs (the re-exports) and the test doubles.
                assert!(["lib", "test_support"].contains(&top.as_str()), "{relative}: a module in no layer; add it to LAYERS");
                continue;
            };
            checked += 1;
            let text = std::fs::read_to_string(&path).expect("a source");
            for name in crate_paths(&text) {
                // The API test reads the public surface as a user does.
                if relative == "options.rs" && name == "*" || name == "test_support" {
                    continue;
                }
                match layer(&name) {
                    Some(l) if l <= own => {}
                    Some(_) => problems.push(format!("{relative} imports `crate::{name}`, a layer after its own")),
                    None => problems.push(format!("{relative} imports `crate::{name}` through lib.rs; use the module's path")),
                }
            }
        }
        assert!(checked > 30, "only {checked} files checked");
        assert!(problems.is_empty(), "{}", problems.join("\n"));
    }

    /// The check sees a path through lib.rs and one into a lower layer, and not a `$crate` or a
    /// comment.
    #[test]
    fn the_check_reads_paths_not_comments() {
        let text = "use crate::Mechanism;\nlet x = crate::output::csv::f(); // crate::Real\n$crate::Real\n";
        assert_eq!(crate_paths(text), ["Mechanism", "output"]);
    }
}
