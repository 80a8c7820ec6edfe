//! Static equilibrium (Nikravesh, *Planar Multibody Dynamics*, 14.2): at rest (v = 0, v̇ = 0) the
//! equations of motion reduce to
//!
//! h(q, 0, t) + Dᵀ λ = 0,   Φ(q, t) = 0,
//!
//! and of the solutions the solver looks for a **stable** one: a local minimum of the potential
//! energy on the constraint manifold (for conservative loads; for others, a point where the
//! loads do no work along any motion the joints allow). Plain Newton on this saddle-point system
//! cannot tell a minimum from a maximum — it finds the upright pendulum as readily as the hanging
//! one, overshoots into another assembly branch, and from λ = 0 it has no gravity stiffness at
//! all. Instead, at t fixed:
//!
//! 1. **Assembly**: q is brought onto Φ = 0 by Newton steps of least kinetic-energy norm,
//!    [[M, −Dᵀ], [D, 0]] [Δv; ·] = [0; −Φ], q ← q ⊕ Δv — the same restoration follows every
//!    trial step.
//! 2. **Multipliers by least squares** at every iterate, in the M⁻¹ norm:
//!    [[M, −Dᵀ], [D, 0]] [x; λ] = [h; 0], so that the residual r = h + Dᵀλ = M x is the force
//!    projected onto the motions the joints allow (x is the acceleration the mechanism would
//!    take if released from rest here, and λ its reactions at that instant). The λ passed in is
//!    only an output: its value on entry is ignored. The M⁻¹ norm makes the projection
//!    independent of units (a Euclidean (D Dᵀ)λ = −D h would add N² to (N·m)²); both give the
//!    same λ at an equilibrium. Converged when ‖r‖∞ ≤ tolerance (N, N·m; or the rounding
//!    floor of the forces where that is larger, see [`StaticOptions::tolerance`]) and
//!    ‖Φ‖∞ ≤ tolerance (m, rad).
//! 3. **Stiffness**: H = (∂h/∂q)B + K(λ), K = ∂(Dᵀλ)/∂q·B ([`ConstraintForces`]); on the
//!    constraint manifold −H is the Hessian of the potential, and the reduced stiffness
//!    −Zᵀ H Z (Z a basis of the motions the joints allow, D Z = 0) has as eigenvalues, against
//!    the reduced mass Zᵀ M Z, the squared natural frequencies ω² (1/s²) of small oscillations.
//!    Z is never formed. Every system is the saddle-point matrix
//!
//!    ```text
//!    [ μM − H   −Dᵀ ]
//!    [ D          0 ]
//!    ```
//!
//!    for a shift μ ≥ 0 (1/s²), factored over the pattern `mechanism!` plans for
//!    generalized-α's Newton matrix ([`NewtonMatrix`], [`crate::sparse`]): O(non-zeros), no
//!    dense matrix. Whether μM − H is positive definite on the motions the joints allow is read
//!    off the pivots' signs: by Sylvester's law of inertia the symmetric saddle matrix has
//!    then exactly NV positive pivots (velocities' positive, kept multipliers' negative in this
//!    unsymmetric form), whatever the order of elimination.
//! 4. **Trust-region step** (Levenberg–Marquardt in the M norm): (μM − H)δ − Dᵀy = r, Dδ = 0,
//!    the minimizer of the quadratic model of the energy −rᵀδ − ½δᵀHδ plus ½μ δᵀMδ on the
//!    manifold's tangent. Newton's step (μ = 0) when the matrix at the floor shift √ε · s
//!    (s = max |H_ij| / √(M_ii M_jj), the stiffness scale; √ε ≈ 1.5e-8) is definite and the
//!    step's largest motion of a body (`Dynamics::motion_size`: its largest entry in body
//!    coordinates) fits the trust radius (m or rad; the first one is
//!    [`StaticOptions::initial_step`]) — the floor's factors, refined against the unshifted
//!    matrix, give it exactly; else the smallest μ (to 5 %) that is definite and fits: the step
//!    on the radius. Modes whose force is zero are not moved (a compressed spring pushing
//!    straight down does not buckle sideways). The factors eliminate velocities first, which
//!    loses up to log₁₀(s/μ) digits where μM − H is nearly singular on a free direction;
//!    iterative refinement against the matrix regains them.
//! 5. **Energy test**: after q ⊕ δ and restoration onto Φ = 0, the work the loads did along the
//!    displacement δ' (velocity space), by Simpson's rule on the chord
//!    (h(q₀) + 4 h(q₀ ⊕ δ'/2) + h(q₁))ᵀ δ' / 6 — for a conservative h that is −ΔV (to fifth
//!    order on a straight chord), it covers actuators and applied forces, which
//!    [`Dynamics::potential_energy`] does not, and its midpoint sees a hill inside a long step
//!    that the trapezoid on the end points would miss (that is how a stiff cylinder's branch
//!    is kept) — is compared with the model's predicted decrease ½(rᵀδ + μ δᵀMδ): the step is
//!    accepted only if the energy went down by at least 1 % of the prediction, and the radius
//!    grows (×2) or shrinks (to ¼ of the step) with the agreement, as in any trust-region
//!    method.
//! 6. **Stability** at the converged point ([`Stability`]): the lowest mode by inverse
//!    iteration with the factors of the smallest definite shift μ, x ← (μM − H)⁻¹ M x on the
//!    manifold, which converges to the smallest ω² + μ > 0, i.e. to the lowest ω², stable or
//!    not; ω² is the Rayleigh quotient x'ᵀMx / x'ᵀMx' − μ (no product with H). When the
//!    equilibrium reached is unstable (a saddle or a maximum: the upright pendulum started
//!    exactly upright), the solver by default steps off it along that mode and continues
//!    downhill ([`StaticOptions::leave_unstable`]); with that option off it returns the unstable
//!    equilibrium and says so.
//!
//! Compared with Levenberg–Marquardt on a fixed shift schedule (×10 on rejection, ÷10 on
//! acceptance), choosing μ anew at each iterate — Newton's where it is definite, else the
//! step on the trust radius — leaves a saddle in a few steps of growing length: a shift just
//! above the negative curvature makes steps proportional to the tiny force near the saddle,
//! and the ×10/÷10 rule alternates around that curvature.
//!
//! **Angles** come back in a documented range: each angle coordinate ([`CoordinateKind::Angle`]:
//! a planar body's `"body.phi"`) is wrapped into (−π, π] when the wrap changes neither Φ nor h
//! (the mechanism is 2π-periodic in it: a driver or a torsion spring written linearly in φ is
//! not, and the angle is left as is; angles are wrapped one at a time). Quaternions
//! ([`CoordinateKind::Quaternion`]: a spatial body's Euler parameters) come back unit, with
//! e0 ≥ 0 (p and −p are the same rotation).
//!
//! Work space: the two matrices and one set of factors over the planned storage (D's
//! non-zeros and the factors' entries: O(bodies) for a chain) live in the caller's
//! [`Workspace`]'s three Newton slots; the stack holds O(NV + NC) scalars. Of the work space's
//! other arrays only D is written, at the equilibrium, for [`crate::joint_reaction`]. Nothing
//! allocates.

use crate::linalg::LinalgError;
#[cfg(doc)]
use crate::model::mechanism::{ConstraintForces, Dynamics};
use crate::model::mechanism::{CoordinateKind, Mechanism, NewtonMatrix, VelocityKind};
use crate::model::workspace::Workspace;
use crate::real::Real;
use crate::solvers::kinematics::{first_non_finite, name};
use core::fmt;

/// Default tolerance on max(‖h + Dᵀλ‖∞ (N, N·m), ‖Φ‖∞ (m, rad)).
pub const DEFAULT_STATIC_TOLERANCE: f64 = 1e-9;
/// Default cap on trial steps, accepted and rejected together: a Newton phase takes 3–6, a
/// start on the wrong side of a hill (a pendulum near upright) 10–20 more.
pub const DEFAULT_STATIC_MAX_ITERATIONS: u32 = 100;
/// Default relative pivot tolerance of the factorizations of [[μM − H, −Dᵀ], [D, 0]].
pub const DEFAULT_STATIC_PIVOT_TOLERANCE: f64 = 1e-13;
/// Default cap on the Newton iterations of each assembly onto Φ = 0 (the first one and the
/// restoration after each trial step), as [`crate::DEFAULT_MAX_ITERATIONS`] of the kinematic
/// solver.
pub const DEFAULT_STATIC_ASSEMBLY_ITERATIONS: u32 = 25;
/// Default relative tolerance of the stability verdict: a mode is neutral when
/// |ω²| ≤ 1e-8 · s, s the largest of |ω²|, |H_ij| / √(M_ii M_jj) and the shift of the inverse
/// iteration (1/s²). ω² is computed to about 1e-12 of s (rounding through the refined
/// factorizations), and the equilibrium itself is only found to the tolerance: four orders of
/// margin above both.
pub const DEFAULT_STATIC_NEUTRAL_TOLERANCE: f64 = 1e-8;
/// Default length of the first step along a mode of non-positive stiffness, where Newton gives
/// no length: its largest entry in velocity space is 0.5 (m or rad). The trust region adapts
/// from there (×2 per step that the energy confirms).
pub const DEFAULT_STATIC_INITIAL_STEP: f64 = 0.5;

/// A step is accepted when the work the loads did along it is at least this fraction of the
/// decrease the quadratic model predicted.
const ACCEPT_RATIO: f64 = 0.01;
/// Below this ratio of actual to predicted decrease the trust radius shrinks to a quarter of
/// the step.
const SHRINK_RATIO: f64 = 0.25;
/// Above this ratio (and with the step on the radius) the trust radius doubles.
const GROW_RATIO: f64 = 0.75;
/// A step "on the radius": at least this fraction of it.
const ON_RADIUS: f64 = 0.9;
/// Cap on the iterative refinements of a solve with a shifted matrix
/// ([`Iterate::shifted_solve`]): at the floor shift the factors lose up to half the digits, and
/// the first refinement regains them; toward Newton's μ = 0 each gains log₁₀(ω²_min/μ) more.
const MAX_REFINEMENTS: u32 = 12;
/// Shifts tried, ×10 each from the floor (past 1e24 · s the reduced matrix is μM to rounding,
/// definite where M is) and ×4 each to fit a step in the trust radius.
const SHIFT_TRIALS: u32 = 64;
/// Cap on inverse iterations for the lowest mode; each is one solve with the planned factors
/// and gains a factor (ω²₁ + μ)/(ω²₂ + μ), so a gap of 1 % of the spectrum settles in a few
/// hundred.
const INVERSE_ITERATIONS: u32 = 500;
/// Rejected trial steps off an unstable equilibrium before it is returned as such.
const ESCAPE_ATTEMPTS: u32 = 12;
/// The force residual's rounding floor, in units of ε (‖h‖∞ + max_k Σ_r |D_rk λ_r| +
/// ‖H‖∞ max(1, ‖q‖∞)): a force is a sum of terms of those sizes, and a coordinate known to ε
/// moves it by ‖H‖ ε |q|. Heavy machines on stiff cylinders (10⁵ N, 10⁷ N/m) have a floor of
/// about 1e-7 N, above the default tolerance; there the floor is the tolerance.
const RESIDUAL_ROUNDING: f64 = 16.0;
/// Rounding allowance of the work estimate, in units of ε times the sum of |terms|: the
/// dot product of NV terms rounds by at most NV·ε of that sum; this covers NV up to a few
/// hundred.
const WORK_ROUNDING: f64 = 256.0;

crate::options::options! {
    /// Options of [`StaticSolver`], in the scalar type `T` of the mechanism (default `f64`).
    /// Build from [`Default`] and the `with_*` setters.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct StaticOptions<T> {
        /// Converged when both residuals are at most this (N or N·m for forces, m or rad for Φ)
        /// — the force residual, or its rounding floor 16 ε (‖h‖∞ + ‖Dᵀλ‖ + ‖H‖∞ max(1, ‖q‖∞))
        /// where that is larger (loads of 10⁵ N on 10⁷ N/m cylinders cannot be balanced to
        /// 1e-9 N in f64). Default [`DEFAULT_STATIC_TOLERANCE`].
        tolerance: T = T::from_f64(DEFAULT_STATIC_TOLERANCE) => with_tolerance,
        /// Trial steps (accepted and rejected) before giving up. Default
        /// [`DEFAULT_STATIC_MAX_ITERATIONS`].
        max_iterations: u32 = DEFAULT_STATIC_MAX_ITERATIONS => with_max_iterations,
        /// Relative pivot tolerance of the planned factorization (see [`crate::linalg::sparse::factor`]):
        /// a velocity pivot at most this times its row's largest entry has no pivot, and a
        /// multiplier whose pivot ratio is at most this is dependent. Default
        /// [`DEFAULT_STATIC_PIVOT_TOLERANCE`].
        pivot_tolerance: T = T::from_f64(DEFAULT_STATIC_PIVOT_TOLERANCE) => with_pivot_tolerance,
        /// Newton iterations of each assembly onto Φ = 0. Default
        /// [`DEFAULT_STATIC_ASSEMBLY_ITERATIONS`].
        assembly_iterations: u32 = DEFAULT_STATIC_ASSEMBLY_ITERATIONS => with_assembly_iterations,
        /// Relative tolerance of the neutral verdict (see [`Stability`]). Default
        /// [`DEFAULT_STATIC_NEUTRAL_TOLERANCE`].
        neutral_tolerance: T = T::from_f64(DEFAULT_STATIC_NEUTRAL_TOLERANCE) => with_neutral_tolerance,
        /// Largest motion of a body (m or rad; `Dynamics::motion_size`, a step's largest entry
        /// in body coordinates) of the first step along a mode without stiffness. Default [`DEFAULT_STATIC_INITIAL_STEP`].
        initial_step: T = T::from_f64(DEFAULT_STATIC_INITIAL_STEP) => with_initial_step,
        /// On reaching an unstable equilibrium, step off it along its most unstable mode and keep
        /// going downhill (`true`, the default), or return it with [`Stability::Unstable`].
        leave_unstable: bool = true => with_leave_unstable,
        /// A constraint row whose sine of angle to the rows eliminated before it (in the M⁻¹
        /// metric) is at most this is dropped (redundant, or dependent at a singular pose; its
        /// multiplier is 0). The factorization compares the squared sine, its pivot ratio, so
        /// below √[`pivot_tolerance`](Self::pivot_tolerance) the pivot tolerance decides. Default
        /// [`crate::DEFAULT_RANK_TOLERANCE`], as the kinematic solver's.
        rank_tolerance: T = T::from_f64(crate::solvers::kinematics::DEFAULT_RANK_TOLERANCE) => with_rank_tolerance,
    }
}

/// Whether an equilibrium is stable, from the lowest eigenvalue of the reduced stiffness −Zᵀ H Z
/// against the reduced mass Zᵀ M Z (Z a basis of the motions the joints allow): the squared
/// natural frequencies ω² (1/s²) of small oscillations about the equilibrium. A mode is
/// neutral when |ω²| ≤ [`StaticOptions::neutral_tolerance`] · s, s the largest of |ω²|,
/// |H_ij| / √(M_ii M_jj) and the inverse iteration's shift. The verdict assumes a symmetric
/// stiffness (conservative loads); for non-conservative ones (follower forces) it is that of
/// the lowest real mode of the non-symmetric −H and says nothing about flutter.
///
/// A mode is named by the velocity that carries the largest share of its kinetic energy
/// (the largest |z_i| √M_ii), from [`Mechanism::VELOCITY_NAMES`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Stability {
    /// Every motion the joints allow raises the energy: all ω² above the neutral band.
    Stable {
        /// The lowest ω² (1/s²); infinite when no motion is free (DOF = 0).
        omega_squared: f64,
    },
    /// No mode lowers the energy, but at least one leaves it unchanged to second order (a rod
    /// free to turn without gravity): an equilibrium, not a unique one.
    Neutral {
        /// The velocity that carries the neutral mode.
        direction: &'static str,
        /// Its ω² (1/s²), within the neutral band.
        omega_squared: f64,
    },
    /// Some motion lowers the energy (an upright pendulum): the mechanism falls away from here.
    Unstable {
        /// The velocity that carries the most unstable mode.
        direction: &'static str,
        /// Its ω² (1/s²), negative: the mode grows as e^{√(−ω²) t}.
        omega_squared: f64,
    },
}

/// What [`StaticSolver::solve`] found.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct StaticReport {
    /// Accepted steps (0 when the assembled start was already an equilibrium).
    pub iterations: u32,
    /// Trial steps rejected by the energy test (or whose restoration onto Φ = 0 failed).
    pub rejected: u32,
    /// max(‖h + Dᵀλ‖∞, ‖Φ‖∞) at the returned q (N, N·m; m, rad).
    pub residual: f64,
    /// Whether the equilibrium is stable.
    pub stability: Stability,
}

/// Why a static equilibrium was not found.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum StaticError {
    /// The workspace does not have NV + NC rows.
    WorkspaceSize {
        /// Rows the mechanism needs.
        expected: usize,
        /// Rows the workspace has.
        found: usize,
    },
    /// The workspace's Newton slots do not have the mechanism's `NEWTON_STORAGE` scalars (a
    /// `Workspace` made by hand with another NS; `Name::workspace()` has the right one).
    NewtonSlotSize {
        /// Scalars the mechanism's planned Newton matrix needs.
        expected: usize,
        /// Scalars each slot of the workspace has (NS).
        found: usize,
    },
    /// The starting q could not be assembled onto Φ = 0.
    NotAssembled {
        /// Time (s).
        t: f64,
        /// Assembly iterations made.
        iterations: u32,
        /// The constraint row with the largest |Φ|.
        worst_row: &'static str,
        /// Its value (m, rad).
        residual: f64,
    },
    /// No equilibrium within the iterations; the worst residual is a force row (a velocity) or
    /// a constraint. A force that no stiffness balances (a free body under a constant load)
    /// ends here too.
    NotConverged {
        /// Time (s).
        t: f64,
        /// Trial steps made.
        iterations: u32,
        /// The row with the largest residual.
        worst_row: &'static str,
        /// Its value.
        residual: f64,
    },
    /// [[M, Dᵀ], [D, 0]] has no pivot: a velocity without mass, constraint rows nearly but not
    /// quite dependent (sine of their angle above [`StaticOptions::rank_tolerance`] yet below
    /// the pivot tolerance), or a singular start pose that cannot be assembled (links lying
    /// collinear, e.g. every angle 0 where `at:` was left out: the row named depends on the
    /// others there and is not met). Consistent redundant rows and singular poses met on the
    /// way are not this error: their dependent rows are dropped.
    Singular {
        /// Time (s).
        t: f64,
        /// The velocity or constraint row without a pivot.
        row: &'static str,
    },
    /// A force element gives a NaN or infinite generalized force (or stiffness) at the iterate:
    /// a law undefined there (a square root of a negative stretch, a division by a zero
    /// length).
    NonFiniteForce {
        /// Time (s).
        t: f64,
        /// The first force element (declaration order, gravity first) reaching that velocity,
        /// from [`crate::Mechanism::FORCE_ELEMENTS`].
        element: &'static str,
        /// How many other elements reach it too (0: `element` is the one).
        others: u16,
        /// The velocity whose generalized force or stiffness is not finite.
        velocity: &'static str,
    },
    /// NaN or infinity in t, the state, the forces, the constraints or their derivatives.
    NonFinite {
        /// Time (s).
        t: f64,
        /// The row where it appeared: `"t"`, a coordinate, a velocity (forces, stiffness) or a
        /// constraint.
        row: &'static str,
    },
}

impl fmt::Display for StaticError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StaticError::WorkspaceSize { expected, found } => {
                write!(f, "static equilibrium: the workspace has {found} rows but the mechanism needs NV + NC = {expected}; use Name::workspace()")
            }
            StaticError::NewtonSlotSize { expected, found } => write!(
                f,
                "static equilibrium: the workspace's Newton slots hold {found} scalars but the mechanism needs NEWTON_STORAGE = {expected}; use Name::workspace()"
            ),
            StaticError::NotAssembled { t, iterations, worst_row, residual } => write!(
                f,
                "static equilibrium at t = {t} s: the start does not assemble after {iterations} iterations: |Φ| = {residual:.3e} in '{worst_row}'"
            ),
            StaticError::NotConverged { t, iterations, worst_row, residual } => write!(
                f,
                "static equilibrium not found at t = {t} s after {iterations} iterations: worst residual {residual:.3e} in '{worst_row}'"
            ),
            StaticError::Singular { t, row } => {
                write!(f, "static equilibrium at t = {t} s: no pivot for '{row}' (a singular start pose such as collinear links — give `at:` angles near the equilibrium —, a velocity without mass, or constraint rows nearly but not quite dependent)")
            }
            StaticError::NonFiniteForce { t, element, others: 0, velocity } => {
                write!(f, "static equilibrium at t = {t} s: the force element `{element}` gives a NaN or infinite force on `{velocity}`")
            }
            StaticError::NonFiniteForce { t, element, others, velocity } => write!(
                f,
                "static equilibrium at t = {t} s: NaN or infinite force on `{velocity}`, from `{element}` or one of {others} other elements acting there"
            ),
            StaticError::NonFinite { t, row } => write!(f, "static equilibrium at t = {t} s: non-finite value in '{row}'"),
        }
    }
}

impl core::error::Error for StaticError {}

/// Static-equilibrium solver that finds stable equilibria (the algorithm: [the `statics`
/// module](crate::statics)).
#[derive(Clone, Copy, Debug)]
pub struct StaticSolver<T = f64> {
    /// Tolerances, iteration caps and the choice at unstable equilibria.
    pub options: StaticOptions<T>,
}

impl<T: Real> Default for StaticSolver<T> {
    fn default() -> Self {
        Self::new(StaticOptions::new())
    }
}

/// A non-finite generalized force or stiffness at velocity `i`: named by the force element that
/// reaches it (else by the velocity: the constraint stiffness K(λ) or a gyroscopic term).
fn non_finite_force<M: Mechanism>(t: f64, i: usize) -> StaticError {
    let velocity = name(M::VELOCITY_NAMES, i);
    match crate::model::dynamics::force_element::<M>(i) {
        Some((element, others)) => StaticError::NonFiniteForce { t, element, others, velocity },
        None => StaticError::NonFinite { t, row: velocity },
    }
}

/// A failed factorization as the solver reports it: a velocity without pivot, or the row
/// (velocity: its force or stiffness; constraint: Φ or D) where a NaN appeared.
fn factor_error<M: Mechanism>(t: f64, nv: usize, e: LinalgError) -> StaticError {
    match e {
        LinalgError::Singular { column, .. } if column < nv => StaticError::Singular { t, row: name(M::VELOCITY_NAMES, column) },
        LinalgError::Singular { column, .. } => StaticError::Singular { t, row: name(M::CONSTRAINT_NAMES, column - nv) },
        LinalgError::NonFinite { row, .. } if row < nv => non_finite_force::<M>(t, row),
        LinalgError::NonFinite { row, .. } => StaticError::NonFinite { t, row: name(M::CONSTRAINT_NAMES, row - nv) },
        LinalgError::NotSquare { .. } | LinalgError::Overdetermined { .. } => StaticError::NonFinite { t, row: "t" },
    }
}

/// (max |v_i|, i), the first index among equals; (0, 0) when empty.
fn max_abs<T: Real>(values: &[T]) -> (T, usize) {
    values.iter().enumerate().fold((T::ZERO, 0), |(best, at), (i, v)| if v.abs() > best { (v.abs(), i) } else { (best, at) })
}

/// aᵀ b over the shorter length.
fn dot<T: Real>(a: &[T], b: &[T]) -> T {
    a.iter().zip(b).fold(T::ZERO, |s, (&x, &y)| s + x * y)
}

/// Each stored entry of the Newton pattern with the unknowns of its row and column (v̇ entries
/// 0..NV, then multipliers), in storage order (after D's non-zeros).
fn entries(pattern: &crate::linalg::sparse::SparsePattern) -> impl Iterator<Item = (usize, usize)> + '_ {
    (0..pattern.size()).flat_map(move |p| {
        let row = pattern.row_start[p] as usize..pattern.row_start[p + 1] as usize;
        pattern.columns[row].iter().map(move |&c| (pattern.unknown[p] as usize, pattern.unknown[c as usize] as usize))
    })
}

/// Why a restoration onto Φ = 0 failed.
enum RestoreFailure {
    NotConverged { iterations: u32, worst: usize, residual: f64 },
    Static(StaticError),
}

/// One iterate, evaluated over the Newton matrix's planned storage: the matrices
/// [[M, −Dᵀ], [D, 0]] (`mass`) and
/// [[M − H, −Dᵀ], [D, 0]] (`stiff`, H = (∂h/∂q)B + K(λ) at the multipliers), the loads, the
/// multipliers and the projected residual r = h + Dᵀλ.
struct Iterate<'a, S, T, const NV: usize, const NC: usize> {
    mass: &'a S,
    stiff: &'a S,
    /// The rows of D dropped as dependent on the rows eliminated before them.
    dropped: [bool; NC],
    h: [T; NV],
    phi: [T; NC],
    lambda: [T; NC],
    r: [T; NV],
    /// M's diagonal.
    mass_diagonal: [T; NV],
    /// max |H_ij| / √(M_ii M_jj) (1/s²): the scale of the stiffness, of the neutral verdict and
    /// of the Levenberg–Marquardt shift.
    scale: T,
    /// ‖H‖∞ and max_k Σ_r |D_rk λ_r|: the sizes entering the residual's rounding floor.
    stiffness_norm: T,
    reaction: T,
    /// max_r |D_ri| and max_r |H_ri| of each column i, for the angle wrap.
    d_columns: [T; NV],
    h_columns: [T; NV],
}

impl<S: Copy + AsRef<[T]> + AsMut<[T]>, T: Real, const NV: usize, const NC: usize> Iterate<'_, S, T, NV, NC> {
    /// Multipliers kept by the factorization of [[M, −Dᵀ], [D, 0]].
    fn kept(&self) -> usize {
        self.dropped.iter().filter(|&&d| !d).count()
    }

    /// Solves [[μM − H, −Dᵀ], [D, 0]] x = b in place (`b`: NV + NC entries) by iterative
    /// refinement against that matrix, with the `factors` of the one at a shift μ_f ≥ μ. For
    /// μ = μ_f this regains the digits the factors lose: the planned order eliminates
    /// velocities first, and where M − H/μ is nearly singular there (a small shift on a free
    /// direction: only the constraints' stiffness holds a pendulum's x) they lose up to
    /// log₁₀(s/μ). For μ below it (Newton's μ = 0 from the floor's factors) each refinement
    /// also gains a factor (μ_f − μ)/(ω²_min + μ_f): the exact Newton step, where the floor is
    /// tiny against the softest mode. Returns whether the corrections fell to rounding
    /// ([`MAX_REFINEMENTS`] at most, each at least halving the last).
    fn shifted_solve<M, const NQ: usize, const N: usize>(&self, factors: &S, mu: T, b: &mut [T; N]) -> bool
    where
        M: NewtonMatrix<T, NQ, NV, NC, NewtonStorage = S>,
    {
        let nnz = M::JACOBIAN_PATTERN.len();
        let rhs = *b;
        M::newton_solve(factors, b);
        let mut last: Option<T> = None;
        for _ in 0..MAX_REFINEMENTS {
            // r = rhs − A x over the stored entries; a dropped multiplier's row is the
            // identity's in the factors, and its unknown stays 0.
            let mut r = rhs;
            let values = self.stiff.as_ref()[nnz..].iter().zip(&self.mass.as_ref()[nnz..]);
            for ((u, w), (&stiff, &mass)) in entries(&M::NEWTON_PATTERN).zip(values) {
                if u >= NV && self.dropped[u - NV] {
                    continue;
                }
                let a = if u < NV && w < NV { stiff + (mu - T::ONE) * mass } else { stiff };
                r[u] -= a * b[w];
            }
            for (r, &dropped) in r[NV..].iter_mut().zip(&self.dropped) {
                if dropped {
                    *r = T::ZERO;
                }
            }
            M::newton_solve(factors, &mut r);
            let change = max_abs(&r).0;
            if !change.is_finite() || last.is_some_and(|last| change > T::from_f64(0.5) * last) {
                return false;
            }
            for (x, dx) in b.iter_mut().zip(r) {
                *x += dx;
            }
            if change <= T::from_f64(16.0) * T::EPSILON * max_abs(b).0 {
                return true;
            }
            last = Some(change);
        }
        false
    }
}

/// The lowest mode of the reduced stiffness: ω² (1/s²) and its shape z (M-normalized,
/// velocity space).
struct Mode<T, const NV: usize> {
    omega_squared: T,
    shape: [T; NV],
    /// The shift of the inverse iteration: ω² is known to about ε times it.
    shift: T,
}

impl<T: Real> StaticSolver<T> {
    /// A solver with the given options.
    pub const fn new(options: StaticOptions<T>) -> Self {
        StaticSolver { options }
    }

    /// Finds a stable equilibrium: q and λ with h(q, 0, t) + Dᵀλ = 0 and Φ(q, t) = 0 where the
    /// potential energy is a local minimum on the constraint manifold, starting from `q` — any
    /// rough guess; it is assembled first — and descending in energy (see the module
    /// documentation). `lambda` is an output only (its value on entry is ignored): on success
    /// it holds the multipliers, and `ws.jacobian()` holds D(q, t) at the equilibrium: the
    /// joint reactions follow with [`crate::joint_reaction`]`(m, q, ws.jacobian(), lambda, …)`.
    /// On success `q` holds the equilibrium, with planar angles in (−π, π] where the mechanism
    /// is periodic in them and unit Euler parameters with e0 ≥ 0; on error it holds the last
    /// accepted iterate.
    ///
    /// The solver works over the factorization `mechanism!` plans for generalized-α
    /// ([`NewtonMatrix`]), in `ws`'s three Newton slots (the mechanism's `NEWTON_STORAGE`
    /// scalars each: `Name::workspace()` has them). Of `ws`'s other arrays it reads nothing; it
    /// writes only D at the equilibrium, on success.
    ///
    /// # Errors
    /// [`StaticError::WorkspaceSize`]; [`StaticError::NewtonSlotSize`]; [`StaticError::NonFinite`] (t, q, Φ, D, h, its
    /// derivatives); [`StaticError::NotAssembled`]; [`StaticError::Singular`] (a velocity
    /// without mass); [`StaticError::NotConverged`], naming the velocity or constraint row with
    /// the largest residual.
    pub fn solve<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
        &self,
        m: &M,
        ws: &mut Workspace<T, NV, NC, N, NS>,
        q: &mut [T; NQ],
        t: T,
        lambda: &mut [T; NC],
    ) -> Result<StaticReport, StaticError>
    where
        M: NewtonMatrix<T, NQ, NV, NC>,
    {
        if N != NV + NC {
            return Err(StaticError::WorkspaceSize { expected: NV + NC, found: N });
        }
        let Some([mass, stiff, scratch]) = crate::model::workspace::newton_slots::<M::NewtonStorage, T, NS>(&mut ws.newton) else {
            return Err(StaticError::NewtonSlotSize { expected: M::JACOBIAN_PATTERN.len() + M::NEWTON_PATTERN.entries(), found: NS });
        };
        let time = t.to_f64();
        if !t.is_finite() {
            return Err(StaticError::NonFinite { t: time, row: "t" });
        }
        if let Some(i) = first_non_finite(q) {
            return Err(StaticError::NonFinite { t: time, row: name(M::COORDINATE_NAMES, i) });
        }
        let options = &self.options;
        let tol = options.tolerance;
        let half = T::from_f64(0.5);
        let mut trial = *q;
        let mut correction = [T::ZERO; NV];

        self.restore::<M, NQ, NV, NC, N>(m, q, t, &mut correction, scratch).map_err(|e| match e {
            RestoreFailure::NotConverged { iterations, worst, residual } => {
                StaticError::NotAssembled { t: time, iterations, worst_row: name(M::CONSTRAINT_NAMES, worst), residual }
            }
            RestoreFailure::Static(e) => e,
        })?;

        let (mut accepted, mut rejected) = (0u32, 0u32);
        // The trust radius: the largest motion of a body under a step (m or rad;
        // `Dynamics::motion_size`: its largest entry in body coordinates).
        let mut radius = options.initial_step;
        loop {
            let it = self.evaluate::<M, NQ, NV, NC, N>(m, q, t, mass, stiff, scratch)?;
            *lambda = it.lambda;
            let (force_residual, force_row) = max_abs(&it.r);
            let (constraint_residual, constraint_row) = max_abs(&it.phi);
            let (residual, worst_row) = if force_residual >= constraint_residual {
                (force_residual, name(M::VELOCITY_NAMES, force_row))
            } else {
                (constraint_residual, name(M::CONSTRAINT_NAMES, constraint_row))
            };
            // The mobility at q: NV − NC, or more where rows are redundant or the pose singular.
            let dof = NV - it.kept();
            // The tolerance, or the force residual's rounding floor where that is larger.
            let floor = T::from_f64(RESIDUAL_ROUNDING)
                * T::EPSILON
                * (max_abs(&it.h).0 + it.reaction + it.stiffness_norm * max_abs(q).0.max(T::ONE));
            let tol = tol.max(floor);
            let converged = residual <= tol;
            let not_converged = |iterations| StaticError::NotConverged { t: time, iterations, worst_row, residual: residual.to_f64() };
            // At a converged point, its lowest mode tells stable from unstable.
            let mode = if converged && dof > 0 {
                Some(self.lowest_mode::<M, NQ, NV, NC, N>(m, q, &it, scratch).ok_or_else(|| not_converged(accepted + rejected))?)
            } else {
                None
            };
            // The neutral band: relative to the stiffness scale, and never below what rounding
            // leaves of ω² (about ε times the inverse iteration's shift).
            let neutral = |mode: &Mode<T, NV>| options.neutral_tolerance * it.scale.max(mode.omega_squared.abs()).max(mode.shift);
            let unstable = mode.as_ref().is_some_and(|mode| mode.omega_squared < -neutral(mode));
            if converged && !(unstable && options.leave_unstable) {
                let stability = classify::<T, M, NV>(mode.as_ref(), &it.mass_diagonal, neutral);
                self.wrap_angles(m, q, t, &it, scratch);
                m.jacobian(q, t, &mut ws.jacobian);
                return Ok(StaticReport { iterations: accepted, rejected, residual: residual.to_f64(), stability });
            }
            if accepted + rejected >= options.max_iterations {
                return Err(not_converged(accepted + rejected));
            }
            // Off an unstable equilibrium: along its most unstable mode, the first step moving
            // no body more than `initial_step`.
            let escape = mode.filter(|_| converged);
            if escape.is_some() {
                radius = options.initial_step;
            }
            let mut attempts = 0u32;
            loop {
                // The step and its predicted energy decrease.
                let step = match &escape {
                    Some(mode) => {
                        // Downhill along the force if it has any, else toward the mode's
                        // largest entry (either way falls off a saddle).
                        let z = &mode.shape;
                        let f = dot(z, &it.r);
                        let sign = if f != T::ZERO { f } else { z[max_abs(z).1] };
                        let size = radius / m.motion_size(q, z);
                        let y = if sign < T::ZERO { -size } else { size };
                        let delta: [T; NV] = core::array::from_fn(|i| y * z[i]);
                        Some((delta, f * y - half * mode.omega_squared * y * y))
                    }
                    None => self.shifted_step::<M, NQ, NV, NC, N>(m, q, &it, radius, scratch),
                };
                let Some((delta, predicted)) = step else {
                    return Err(not_converged(accepted + rejected));
                };
                let step_norm = m.motion_size(q, &delta);
                let ratio = self.trial::<M, NQ, NV, NC, N>(m, q, t, &it.h, &delta, predicted, &mut trial, &mut correction, scratch);
                if let Some(ratio) = ratio {
                    *q = trial;
                    accepted += 1;
                    if ratio < T::from_f64(SHRINK_RATIO) {
                        radius = step_norm / T::from_f64(4.0);
                    } else if ratio > T::from_f64(GROW_RATIO) && step_norm >= T::from_f64(ON_RADIUS) * radius {
                        radius = radius + radius;
                    }
                    break;
                }
                rejected += 1;
                attempts += 1;
                radius = step_norm / T::from_f64(4.0);
                if escape.is_some() && attempts >= ESCAPE_ATTEMPTS {
                    // Every step off it raised the energy: unstable as it looked, but not
                    // leavable at this resolution; report it as it is.
                    let stability = classify::<T, M, NV>(escape.as_ref(), &it.mass_diagonal, neutral);
                    self.wrap_angles(m, q, t, &it, scratch);
                    m.jacobian(q, t, &mut ws.jacobian);
                    return Ok(StaticReport { iterations: accepted, rejected, residual: residual.to_f64(), stability });
                }
                if accepted + rejected >= options.max_iterations {
                    return Err(not_converged(accepted + rejected));
                }
            }
        }
    }

    /// The relative pivot ratio below which a multiplier is dropped as dependent: the ratio is
    /// about the squared sine of the row's angle to the rows eliminated before it (in the M⁻¹
    /// metric), so the square of [`StaticOptions::rank_tolerance`], and never below the pivot
    /// tolerance (rounding).
    fn drop_ratio(&self) -> T {
        let o = &self.options;
        (o.rank_tolerance * o.rank_tolerance).max(o.pivot_tolerance).max(T::from_f64(f64::EPSILON))
    }

    /// Everything the iteration needs at an assembled `q`: the two matrices (in `mass` and
    /// `stiff`), the multipliers by least squares in the M⁻¹ norm ([[M, −Dᵀ], [D, 0]] [x; λ] =
    /// [h; 0], factored in `factors`) and the residual r = h + Dᵀλ = M x.
    #[allow(clippy::too_many_arguments)]
    fn evaluate<'a, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
        &self,
        m: &M,
        q: &[T; NQ],
        t: T,
        mass: &'a mut M::NewtonStorage,
        stiff: &'a mut M::NewtonStorage,
        factors: &mut M::NewtonStorage,
    ) -> Result<Iterate<'a, M::NewtonStorage, T, NV, NC>, StaticError>
    where
        M: NewtonMatrix<T, NQ, NV, NC>,
    {
        let time = t.to_f64();
        let zero_v = [T::ZERO; NV];
        let nnz = M::JACOBIAN_PATTERN.len();
        let (mut phi, mut h) = ([T::ZERO; NC], [T::ZERO; NV]);
        m.newton_matrix(q, &zero_v, &zero_v, t, &[T::ZERO; NC], T::ZERO, T::ZERO, &mut phi, mass);
        m.forces(q, &zero_v, t, &mut h);
        if let Some(i) = first_non_finite(&phi) {
            return Err(StaticError::NonFinite { t: time, row: name(M::CONSTRAINT_NAMES, i) });
        }
        if let Some(i) = first_non_finite(&h) {
            return Err(non_finite_force::<M>(time, i));
        }
        factors.as_mut().copy_from_slice(mass.as_ref());
        let mut dropped = [false; NC];
        M::newton_factor(factors, self.drop_ratio(), true, &mut dropped).map_err(|e| factor_error::<M>(time, NV, e))?;
        let mut b = [T::ZERO; N];
        b[..NV].copy_from_slice(&h);
        M::newton_solve(factors, &mut b);
        let mut lambda = [T::ZERO; NC];
        lambda.copy_from_slice(&b[NV..]);
        let mut r = h;
        let mut reaction_row = [T::ZERO; NV];
        for (&value, &(row, c)) in mass.as_ref().iter().zip(M::JACOBIAN_PATTERN) {
            r[c as usize] += value * lambda[row as usize];
            reaction_row[c as usize] += (value * lambda[row as usize]).abs();
        }
        if let Some(i) = first_non_finite(&r) {
            return Err(StaticError::NonFinite { t: time, row: name(M::VELOCITY_NAMES, i) });
        }
        m.newton_matrix(q, &zero_v, &zero_v, t, &lambda, T::ZERO, T::ONE, &mut phi, stiff);
        let (mass, stiff) = (&*mass, &*stiff);
        // M's diagonal, then H = M − (M − H) entry by entry over the velocity block.
        let mut mass_diagonal = [T::ZERO; NV];
        for ((u, w), &value) in entries(&M::NEWTON_PATTERN).zip(&mass.as_ref()[nnz..]) {
            if u == w && u < NV {
                mass_diagonal[u] = value;
            }
        }
        let (mut scale, mut row_sums, mut h_columns, mut d_columns) = (T::ZERO, [T::ZERO; NV], [T::ZERO; NV], [T::ZERO; NV]);
        for ((u, w), (&m0, &m1)) in entries(&M::NEWTON_PATTERN).zip(mass.as_ref()[nnz..].iter().zip(&stiff.as_ref()[nnz..])) {
            if u < NV && w < NV {
                let hij = m0 - m1;
                if !hij.is_finite() {
                    return Err(non_finite_force::<M>(time, u));
                }
                row_sums[u] += hij.abs();
                h_columns[w] = h_columns[w].max(hij.abs());
                let weight = (mass_diagonal[u] * mass_diagonal[w]).abs().sqrt();
                if weight > T::ZERO {
                    scale = scale.max(hij.abs() / weight);
                }
            }
        }
        for (&value, &(_, c)) in mass.as_ref().iter().zip(M::JACOBIAN_PATTERN) {
            d_columns[c as usize] = d_columns[c as usize].max(value.abs());
        }
        Ok(Iterate {
            mass,
            stiff,
            dropped,
            h,
            phi,
            lambda,
            r,
            mass_diagonal,
            scale,
            stiffness_norm: max_abs(&row_sums).0,
            reaction: max_abs(&reaction_row).0,
            d_columns,
            h_columns,
        })
    }

    /// [[μM − H, −Dᵀ], [D, 0]] factored, if the reduced matrix of that shift μ (1/s²) is
    /// positive definite on the motions the joints allow: the factorization keeps the rows kept
    /// at the iterate, and its pivots' signs (velocity pivots positive, multiplier pivots
    /// negative, NV of them) say so (Sylvester's law of inertia: module documentation).
    fn shifted_factor<M, const NQ: usize, const NV: usize, const NC: usize>(
        &self,
        it: &Iterate<M::NewtonStorage, T, NV, NC>,
        mu: T,
        s: &mut M::NewtonStorage,
    ) -> bool
    where
        M: NewtonMatrix<T, NQ, NV, NC>,
    {
        let nnz = M::JACOBIAN_PATTERN.len();
        let pattern = M::NEWTON_PATTERN;
        s.as_mut().copy_from_slice(it.stiff.as_ref());
        for ((u, w), (x, &m0)) in entries(&pattern).zip(s.as_mut()[nnz..].iter_mut().zip(&it.mass.as_ref()[nnz..])) {
            if u < NV && w < NV {
                *x += (mu - T::ONE) * m0;
            }
        }
        let mut dropped = it.dropped;
        let tolerance = self.options.pivot_tolerance.max(T::EPSILON);
        if M::newton_factor(s, tolerance, true, &mut dropped).is_err() || dropped != it.dropped {
            return false;
        }
        let values = &s.as_ref()[nnz..];
        let positive = (0..pattern.size())
            .filter(|&p| {
                let (u, pivot) = (pattern.unknown[p] as usize, values[pattern.diagonal[p] as usize]);
                if u < NV {
                    pivot > T::ZERO
                } else {
                    !dropped[u - NV] && pivot < T::ZERO
                }
            })
            .count();
        positive == NV
    }

    /// The smallest shift of the ladder μ_k = 10^k · μ₀ (k = 0, 1, …; μ₀ = [`shift_floor`])
    /// whose reduced matrix is positive definite, with its factors in `s`.
    fn definite_shift<M, const NQ: usize, const NV: usize, const NC: usize>(
        &self,
        it: &Iterate<M::NewtonStorage, T, NV, NC>,
        s: &mut M::NewtonStorage,
    ) -> Option<T>
    where
        M: NewtonMatrix<T, NQ, NV, NC>,
    {
        let mut mu = shift_floor(it);
        for _ in 0..SHIFT_TRIALS {
            if self.shifted_factor::<M, NQ, NV, NC>(it, mu, s) {
                return Some(mu);
            }
            mu *= T::from_f64(10.0);
        }
        None
    }

    /// The Levenberg–Marquardt step in the M norm along the motions the joints allow:
    /// (μM − H)δ − Dᵀy = r, Dδ = 0 (the iterate is assembled; the restoration after the step
    /// meets Φ = 0 again), with the smallest shift of the ladder that makes the reduced matrix
    /// positive definite, raised ×4 until δ moves no body more than `radius`. Returns δ and the
    /// decrease the quadratic model predicts, rᵀδ + ½δᵀHδ = ½(rᵀδ + μ δᵀMδ); `None` if no
    /// shift gives a finite step.
    #[allow(clippy::too_many_arguments)]
    fn shifted_step<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
        &self,
        m: &M,
        q: &[T; NQ],
        it: &Iterate<M::NewtonStorage, T, NV, NC>,
        radius: T,
        factors: &mut M::NewtonStorage,
    ) -> Option<([T; NV], T)>
    where
        M: NewtonMatrix<T, NQ, NV, NC>,
    {
        // The step at shift μ: `Err(true)` if the reduced matrix is definite but the step
        // does not fit, `Err(false)` if it is not definite (or the step not finite).
        let floor = shift_floor(it);
        let mut attempt = |mu: T| -> Result<([T; NV], T), bool> {
            if !self.shifted_factor::<M, NQ, NV, NC>(it, mu, factors) {
                return Err(false);
            }
            let factors = &*factors;
            let mut b = [T::ZERO; N];
            b[..NV].copy_from_slice(&it.r);
            // At the floor, Newton's own step (μ = 0) where the refinement converges to it.
            let mut mu = mu;
            if mu == floor && !it.shifted_solve::<M, NQ, N>(factors, T::ZERO, &mut b) {
                b = [T::ZERO; N];
                b[..NV].copy_from_slice(&it.r);
                it.shifted_solve::<M, NQ, N>(factors, mu, &mut b);
            } else if mu == floor {
                mu = T::ZERO;
            } else {
                it.shifted_solve::<M, NQ, N>(factors, mu, &mut b);
            }
            let delta: [T; NV] = core::array::from_fn(|i| b[i]);
            if first_non_finite(&delta).is_some() {
                return Err(false);
            }
            if m.motion_size(q, &delta) > radius {
                return Err(true);
            }
            let mut md = [T::ZERO; NV];
            m.mass_times(q, &delta, &mut md);
            Ok((delta, T::from_f64(0.5) * (dot(&it.r, &delta) + mu * dot(&delta, &md))))
        };
        // Up from the floor (Newton's step where it is definite and fits): ×10 while not
        // definite, ×4 while the step is too long.
        let (mut low, mut mu) = (T::ZERO, floor);
        let (mut high, mut step) = loop {
            match attempt(mu) {
                Ok(step) => break (mu, step),
                Err(definite) => {
                    low = mu;
                    mu *= T::from_f64(if definite { 4.0 } else { 10.0 });
                    if !mu.is_finite() {
                        return None;
                    }
                }
            }
        };
        // Above the floor, the smallest shift that fits (to 5 %): the step on the radius, the
        // trust-region step (step length falls as μ grows past the definite threshold).
        if low > T::ZERO {
            for _ in 0..SHIFT_TRIALS {
                if m.motion_size(q, &step.0) >= T::from_f64(ON_RADIUS) * radius || high <= T::from_f64(1.05) * low {
                    break;
                }
                let middle = (low * high).sqrt();
                match attempt(middle) {
                    Ok(found) => (high, step) = (middle, found),
                    Err(_) => low = middle,
                }
            }
        }
        let _ = high;
        Some(step)
    }

    /// The lowest mode of the reduced stiffness, by inverse iteration on the factors of the
    /// smallest definite shift μ: x ← (μM − H)⁻¹ M x on the motions the joints allow
    /// ([[μM − H, −Dᵀ], [D, 0]] [x'; ·] = [M x; 0]), which converges to the mode of smallest
    /// ω² + μ > 0, i.e. the smallest ω²; ω² from the Rayleigh quotient
    /// x'ᵀ(−H)x' / x'ᵀMx' = x'ᵀMx / x'ᵀMx' − μ, which needs no product with H.
    fn lowest_mode<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
        &self,
        m: &M,
        q: &[T; NQ],
        it: &Iterate<M::NewtonStorage, T, NV, NC>,
        factors: &mut M::NewtonStorage,
    ) -> Option<Mode<T, NV>>
    where
        M: NewtonMatrix<T, NQ, NV, NC>,
    {
        let mu = self.definite_shift::<M, NQ, NV, NC>(it, factors)?;
        let factors = &*factors;
        // Start from M times a vector of unequal entries (fractional parts of multiples of the
        // golden ratio): no mode is missed by a symmetry of the start.
        let mut mx: [T; NV] = core::array::from_fn(|i| {
            let spread = libm::fmod(0.618_033_988_749_895 * (i + 1) as f64, 1.0);
            it.mass_diagonal[i] * T::from_f64(0.5 + spread)
        });
        let mut x = [T::ZERO; NV];
        let mut omega_squared = T::ZERO;
        for k in 0..INVERSE_ITERATIONS {
            let mut b = [T::ZERO; N];
            b[..NV].copy_from_slice(&mx);
            it.shifted_solve::<M, NQ, N>(factors, mu, &mut b);
            let next: [T; NV] = core::array::from_fn(|i| b[i]);
            let mut m_next = [T::ZERO; NV];
            m.mass_times(q, &next, &mut m_next);
            let norm2 = dot(&next, &m_next);
            if !norm2.is_finite() || norm2 <= T::ZERO {
                return None;
            }
            let rayleigh = dot(&next, &mx) / norm2 - mu;
            let inverse = T::ONE / norm2.sqrt();
            x = core::array::from_fn(|i| next[i] * inverse);
            mx = core::array::from_fn(|i| m_next[i] * inverse);
            let settled = (rayleigh - omega_squared).abs() <= T::from_f64(1e-13) * rayleigh.abs().max(it.scale);
            omega_squared = rayleigh;
            if k > 0 && settled {
                break;
            }
        }
        // Without any stiffness (H = 0) every ω² is 0 exactly; the iteration gave the shape.
        if it.scale == T::ZERO {
            omega_squared = T::ZERO;
        }
        Some(Mode { omega_squared, shape: x, shift: mu })
    }

    /// One trial step from the equilibrium iterate `q` (forces `h`): `trial` = q ⊕ δ restored
    /// onto Φ = 0, and the work the loads did along the displacement δ' (δ plus the
    /// restoration's steps), by Simpson's rule on the chord: (h₀ + 4 h(q ⊕ δ'/2) + h₁)ᵀ δ' / 6,
    /// −ΔV to fifth order for conservative loads, and alert to a hill inside the step that the
    /// end points alone would miss. Returns the ratio of that work to the `predicted` decrease
    /// if the step is accepted (the work is at least [`ACCEPT_RATIO`] of the prediction, up to
    /// the rounding of the sum), `None` if it is rejected or its restoration failed.
    #[allow(clippy::too_many_arguments)]
    fn trial<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
        &self,
        m: &M,
        q: &[T; NQ],
        t: T,
        h: &[T; NV],
        delta: &[T; NV],
        predicted: T,
        trial: &mut [T; NQ],
        correction: &mut [T; NV],
        s: &mut M::NewtonStorage,
    ) -> Option<T>
    where
        M: NewtonMatrix<T, NQ, NV, NC>,
    {
        let zero_v = [T::ZERO; NV];
        *trial = *q;
        m.integrate_positions(trial, delta, T::ONE);
        correction.fill(T::ZERO);
        self.restore::<M, NQ, NV, NC, N>(m, trial, t, correction, s).ok()?;
        let displacement: [T; NV] = core::array::from_fn(|i| delta[i] + correction[i]);
        let half_way: [T; NV] = core::array::from_fn(|i| T::from_f64(0.5) * displacement[i]);
        let mut middle = *q;
        m.integrate_positions(&mut middle, &half_way, T::ONE);
        let (mut h_middle, mut h_end) = ([T::ZERO; NV], [T::ZERO; NV]);
        m.forces(&middle, &zero_v, t, &mut h_middle);
        m.forces(trial, &zero_v, t, &mut h_end);
        if first_non_finite(trial).is_some() || first_non_finite(&h_middle).is_some() || first_non_finite(&h_end).is_some() {
            return None;
        }
        let (mut work, mut size) = (T::ZERO, T::ZERO);
        let (four, sixth) = (T::from_f64(4.0), T::ONE / T::from_f64(6.0));
        for i in 0..NV {
            let term = sixth * (h[i] + four * h_middle[i] + h_end[i]) * displacement[i];
            work += term;
            size += term.abs();
        }
        let rounding = T::from_f64(WORK_ROUNDING) * T::EPSILON * size;
        if work + rounding < T::from_f64(ACCEPT_RATIO) * predicted {
            return None;
        }
        Some(if predicted > rounding { (work / predicted).max(T::ZERO) } else { T::ONE })
    }

    /// Newton onto Φ(q, t) = 0 with steps of least kinetic-energy norm,
    /// [[M, −Dᵀ], [D, 0]] [Δv; ·] = [0; −Φ], q ← q ⊕ Δv, over the planned factorization; the
    /// steps are added to `correction`. A constraint row that depends on the rows eliminated
    /// before it (a redundant constraint, or a singular pose) is dropped: its multiplier is 0
    /// and what it imposes is met through the others.
    fn restore<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
        &self,
        m: &M,
        q: &mut [T; NQ],
        t: T,
        correction: &mut [T; NV],
        s: &mut M::NewtonStorage,
    ) -> Result<u32, RestoreFailure>
    where
        M: NewtonMatrix<T, NQ, NV, NC>,
    {
        let time = t.to_f64();
        let tol = self.options.tolerance;
        let zero_v = [T::ZERO; NV];
        let mut phi = [T::ZERO; NC];
        let mut iterations = 0;
        let mut dropped = [false; NC];
        loop {
            m.newton_matrix(q, &zero_v, &zero_v, t, &[T::ZERO; NC], T::ZERO, T::ZERO, &mut phi, s);
            if let Some(i) = first_non_finite(&phi) {
                return Err(RestoreFailure::Static(StaticError::NonFinite { t: time, row: name(M::CONSTRAINT_NAMES, i) }));
            }
            let (norm, worst) = max_abs(&phi);
            if norm <= tol {
                return Ok(iterations);
            }
            if iterations >= self.options.assembly_iterations {
                // The worst row unmet and dependent on the others: a singular pose whose
                // linearization cannot see that row (links lying collinear from `at:` left out).
                if dropped[worst] {
                    return Err(RestoreFailure::Static(StaticError::Singular { t: time, row: name(M::CONSTRAINT_NAMES, worst) }));
                }
                return Err(RestoreFailure::NotConverged { iterations, worst, residual: norm.to_f64() });
            }
            dropped = [false; NC];
            M::newton_factor(s, self.drop_ratio(), true, &mut dropped)
                .map_err(|e| RestoreFailure::Static(factor_error::<M>(time, NV, e)))?;
            let mut b = [T::ZERO; N];
            for (x, &p) in b[NV..].iter_mut().zip(&phi) {
                *x = -p;
            }
            M::newton_solve(s, &mut b);
            let step: [T; NV] = core::array::from_fn(|i| b[i]);
            if let Some(i) = first_non_finite(&step) {
                return Err(RestoreFailure::Static(StaticError::NonFinite { t: time, row: name(M::VELOCITY_NAMES, i) }));
            }
            m.integrate_positions(q, &step, T::ONE);
            for (c, s) in correction.iter_mut().zip(step) {
                *c += s;
            }
            iterations += 1;
        }
    }

    /// Wraps each angle coordinate into (−π, π] and flips each quaternion to e0 ≥ 0,
    /// where that leaves Φ and h unchanged (to the tolerance plus the rounding of the shift,
    /// bounded by the shift's size times the largest entry of D's or H's column); then
    /// normalizes.
    fn wrap_angles<M, const NQ: usize, const NV: usize, const NC: usize>(
        &self,
        m: &M,
        q: &mut [T; NQ],
        t: T,
        it: &Iterate<M::NewtonStorage, T, NV, NC>,
        s: &mut M::NewtonStorage,
    ) where
        M: NewtonMatrix<T, NQ, NV, NC>,
    {
        let tol = self.options.tolerance;
        let zero_v = [T::ZERO; NV];
        let (phi, h) = (&it.phi, &it.h);
        let (mut phi1, mut h1) = ([T::ZERO; NC], [T::ZERO; NV]);
        let mut unchanged = |candidate: &[T; NQ], d_scale: T, h_scale: T| {
            m.newton_jacobian(candidate, t, &mut phi1, s);
            m.forces(candidate, &zero_v, t, &mut h1);
            phi.iter().zip(&phi1).all(|(a, b)| (*a - *b).abs() <= tol + d_scale)
                && h.iter().zip(&h1).all(|(a, b)| (*a - *b).abs() <= tol + h_scale)
        };
        let rounding = T::from_f64(16.0) * T::EPSILON;
        for (i, coordinate) in M::COORDINATES.iter().enumerate().take(NQ) {
            match coordinate.kind {
                CoordinateKind::Angle => {
                    // The column of D and of h that moves this angle: its rate's.
                    let Some(k) = M::VELOCITIES.iter().position(|v| v.kind == VelocityKind::Rate { coordinate: i as u16 }) else {
                        continue;
                    };
                    let wrapped = T::from_f64(wrap_angle(q[i].to_f64()));
                    if wrapped == q[i] {
                        continue;
                    }
                    let shift = rounding * (q[i].abs() + T::from_f64(2.0 * core::f64::consts::PI));
                    let mut candidate = *q;
                    candidate[i] = wrapped;
                    if unchanged(&candidate, shift * it.d_columns[k], shift * it.h_columns[k]) {
                        *q = candidate;
                    }
                }
                CoordinateKind::Quaternion { part: 0 } if i + 3 < NQ && q[i] < T::ZERO => {
                    // p and −p are one rotation: Φ and h do not change at all.
                    let mut candidate = *q;
                    for x in candidate[i..i + 4].iter_mut() {
                        *x = -*x;
                    }
                    if unchanged(&candidate, rounding * max_abs(phi).0, rounding * max_abs(h).0) {
                        *q = candidate;
                    }
                }
                _ => {}
            }
        }
        m.normalize_positions(q);
    }
}

/// The smallest Levenberg–Marquardt shift tried: √ε (1.5e-8 in f64) times the stiffness scale
/// s = max |H_ij| / √(M_ii M_jj). Small enough that the step is Newton's to √ε · s / ω²_min
/// (the iteration converges at least at that rate), large enough that the factors, eliminating
/// velocities first, keep half the digits where μM − H is singular but for μM (two iterative
/// refinements regain them). 1 (1/s²) where there is no stiffness at all (H = 0: every step is
/// then r/μ in the M norm, on the trust radius).
fn shift_floor<S, T: Real, const NV: usize, const NC: usize>(it: &Iterate<S, T, NV, NC>) -> T {
    if it.scale > T::ZERO {
        T::EPSILON.sqrt() * it.scale
    } else {
        T::ONE
    }
}

/// Wraps an angle into (−π, π].
fn wrap_angle(phi: f64) -> f64 {
    let turn = 2.0 * core::f64::consts::PI;
    let mut wrapped = phi - turn * libm::round(phi / turn);
    if wrapped <= -core::f64::consts::PI {
        wrapped += turn;
    } else if wrapped > core::f64::consts::PI {
        wrapped -= turn;
    }
    wrapped
}

/// The stability verdict from the lowest mode (`None`: no motion is free, DOF = 0); `neutral`
/// gives the half-width of the neutral band about its ω².
fn classify<T: Real, M: Mechanism, const NV: usize>(
    mode: Option<&Mode<T, NV>>,
    mass_diagonal: &[T; NV],
    neutral: impl Fn(&Mode<T, NV>) -> T,
) -> Stability {
    let Some(mode) = mode else {
        return Stability::Stable { omega_squared: f64::INFINITY };
    };
    let w = mode.omega_squared;
    let direction = {
        let weighted: [T; NV] = core::array::from_fn(|i| mode.shape[i] * mass_diagonal[i].abs().sqrt());
        name(M::VELOCITY_NAMES, max_abs(&weighted).1)
    };
    let band = neutral(mode);
    if w < -band {
        Stability::Unstable { direction, omega_squared: w.to_f64() }
    } else if w <= band {
        Stability::Neutral { direction, omega_squared: w.to_f64() }
    } else {
        Stability::Stable { omega_squared: w.to_f64() }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::{UnitPendulum, GRAVITY, LENGTH, MASS};

    /// NQ ≠ NV: the solver in velocity space, with q updated through `integrate_positions`,
    /// hangs the unit-complex pendulum straight down from a guess off the unit circle:
    /// q = (0, −L, 0, −1), the pin carrying the weight, λ = (0, m g). The residual tolerance
    /// 1e-9 leaves q within about 1e-9 / (m g L) ≈ 1e-10, checked to 1e-9. The multipliers
    /// passed in are ignored (any value gives the same answer).
    #[test]
    fn velocity_space_newton_finds_the_hanging_pendulum() {
        for start in [[0.2, -0.4, 0.4, -0.95], [LENGTH, 0.0, 1.0, 0.0], [0.0, LENGTH, 0.0, 1.0]] {
            let mut q = start;
            let mut lambda = [123.0, -7.0];
            let report = StaticSolver::default().solve(&UnitPendulum, &mut Workspace::<f64, 3, 2, 5, 29>::new(), &mut q, 0.0, &mut lambda);
            let report = report.expect("equilibrium");
            assert!(report.iterations < 30, "{report:?}");
            let expected = [0.0, -LENGTH, 0.0, -1.0];
            for (x, e) in q.iter().zip(expected) {
                assert!((x - e).abs() < 1e-9, "from {start:?}: q = {q:?}");
            }
            assert!((q[2].hypot(q[3]) - 1.0).abs() < 1e-15, "{q:?}");
            assert!(lambda[0].abs() < 1e-9 && (lambda[1] - MASS * GRAVITY).abs() < 1e-9, "λ = {lambda:?}");
            // ω² = m g L / (J + m L²) about the pin.
            let omega2 = MASS * GRAVITY * LENGTH / (crate::test_support::INERTIA + MASS * LENGTH * LENGTH);
            match report.stability {
                Stability::Stable { omega_squared } => assert!((omega_squared - omega2).abs() < 1e-6 * omega2, "{report:?}"),
                other => panic!("{other:?}"),
            }
        }
        // A work space of NQ + NC rows is the wrong size: it takes NV + NC.
        let mut q = [0.2, -0.4, 0.4, -0.95];
        let err = StaticSolver::default().solve(&UnitPendulum, &mut Workspace::<f64, 3, 2, 6>::new(), &mut q, 0.0, &mut [0.0; 2]);
        assert_eq!(err, Err(StaticError::WorkspaceSize { expected: 5, found: 6 }));
        // Newton slots of another size than the mechanism's storage (4 non-zeros of D, 25
        // entries of the factors): named, not a panic.
        let err = StaticSolver::default().solve(&UnitPendulum, &mut Workspace::<f64, 3, 2, 5>::new(), &mut q, 0.0, &mut [0.0; 2]);
        assert_eq!(err, Err(StaticError::NewtonSlotSize { expected: 29, found: 0 }));
    }

    #[test]
    fn angles_wrap_into_the_half_open_interval() {
        use core::f64::consts::PI;
        assert_eq!(wrap_angle(PI), PI);
        assert_eq!(wrap_angle(-PI), PI);
        assert!((wrap_angle(7.0) - (7.0 - 2.0 * PI)).abs() < 1e-15);
        assert!((wrap_angle(-7.0) - (-7.0 + 2.0 * PI)).abs() < 1e-15);
        assert_eq!(wrap_angle(0.25), 0.25);
    }
}
