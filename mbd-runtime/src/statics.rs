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
//!    [[M, Dᵀ], [D, 0]] [Δv; ·] = [0; −Φ], q ← q ⊕ Δv — the same restoration follows every trial
//!    step.
//! 2. **Multipliers by least squares** at every iterate, in the M⁻¹ norm:
//!    [[M, Dᵀ], [D, 0]] [x; −λ] = [h; 0], so that the residual r = h + Dᵀλ = M x is the force
//!    projected onto the motions the joints allow (x is the acceleration the mechanism would
//!    take if released from rest here, and λ its reactions at that instant). The λ passed in is
//!    only an output: its value on entry is ignored. The M⁻¹ norm makes the projection
//!    independent of units (a Euclidean (D Dᵀ)λ = −D h would add N² to (N·m)²); both give the
//!    same λ at an equilibrium. Converged when ‖r‖∞ ≤ tolerance (N, N·m; or the rounding
//!    floor of the forces where that is larger, see [`StaticOptions::tolerance`]) and
//!    ‖Φ‖∞ ≤ tolerance (m, rad).
//! 3. **Modes**: Z, an M-orthonormal basis of the null space of D (the M-orthogonal projections
//!    of the unit velocities onto it, by column-pivoted Gram–Schmidt in the M inner product),
//!    and the reduced stiffness A = −Zᵀ H Z with H = (∂h/∂q)B + K(λ), K = ∂(Dᵀλ)/∂q·B
//!    ([`ConstraintForces`]) — the Hessian of the potential on the manifold (its symmetric part
//!    is used). Its eigenvalues (cyclic Jacobi) are the squared natural frequencies ω² (1/s²)
//!    of small oscillations about the current configuration, the eigenvectors the mode shapes.
//! 4. **Trust-region step** in mode coordinates y (δ = Z y), minimizing the quadratic model of
//!    the energy −fᵀy + ½ yᵀ diag(ω²) y, f = Zᵀ r, within a radius on ‖S y‖, S the largest
//!    velocity-space entry of each unit mode — so the radius is in m or rad, and the first one
//!    is [`StaticOptions::initial_step`]: the Newton step y = f/ω² when every mode that carries
//!    a force is stiff and the step fits the radius, else y_i = f_i / (ω²_i + μ s_i²) with the
//!    shift μ ≥ max(0, −ω²_i/s_i²) that puts the step on the radius (the Levenberg–Marquardt
//!    form of the step: μ = 0 is Newton, large μ a short step along M⁻¹ r). Modes whose force
//!    is below the tolerance are not moved (a compressed spring pushing straight down does
//!    not buckle sideways).
//! 5. **Energy test**: after q ⊕ δ and restoration onto Φ = 0, the work the loads did along the
//!    displacement δ' (velocity space), by Simpson's rule on the chord
//!    (h(q₀) + 4 h(q₀ ⊕ δ'/2) + h(q₁))ᵀ δ' / 6 — for a conservative h that is −ΔV (to fifth
//!    order on a straight chord), it covers actuators and applied forces, which
//!    [`Dynamics::potential_energy`] does not, and its midpoint sees a hill inside a long step
//!    that the trapezoid on the end points would miss (that is how a stiff cylinder's branch
//!    is kept) — is compared with the model's predicted decrease: the step is accepted only if
//!    the energy went down by at least 1 % of the prediction, and the radius grows (×2) or
//!    shrinks (to ¼ of the step) with the agreement, as in any trust-region method.
//! 6. **Stability** from the eigenvalues at the converged point ([`Stability`]). When the
//!    equilibrium reached is unstable (a saddle or a maximum: the upright pendulum started
//!    exactly upright), the solver by default steps off it along the mode of most negative ω²
//!    and continues downhill ([`StaticOptions::leave_unstable`]); with that option off it
//!    returns the unstable equilibrium and says so.
//!
//! Compared with Levenberg–Marquardt on the full KKT matrix (shift ×10 on rejection, ÷10 on
//! acceptance), the eigen-decomposed trust region solves the step problem exactly for any
//! shift and leaves a saddle in a few steps of growing length: an LM shift just above the
//! negative curvature makes steps proportional to the tiny force near the saddle, and the
//! ×10/÷10 rule alternates around that curvature (about a 17 % gain per two iterations for the
//! pendulum near upright). The stability report comes from the same decomposition.
//!
//! **Angles** come back in a documented range: each planar angle coordinate (`"body.phi"`) is
//! wrapped into (−π, π] when the wrap changes neither Φ nor h (the mechanism is 2π-periodic in
//! it: a driver or a torsion spring written linearly in φ is not, and the angle is left as is;
//! angles are wrapped one at a time). Spatial Euler parameters come back unit, with e0 ≥ 0
//! (p and −p are the same rotation).
//!
//! Work space: the caller's [`Workspace`] holds D, the (NV + NC)-square matrix
//! [[M, Dᵀ], [D, 0]] and its factors (then the reduced stiffness), and two NV × NV arrays (H,
//! and the basis Z); the stack holds O(NV + NC) scalars. Nothing allocates.

use crate::kinematics::{first_non_finite, name};
use crate::linalg::{lu_factor, lu_solve_in_place, LinalgError, Permutation};
use crate::redundancy::orthogonalize;
use crate::{ConstraintForces, Dynamics, Mechanism, Real, Workspace};
use core::fmt;

/// Default tolerance on max(‖h + Dᵀλ‖∞ (N, N·m), ‖Φ‖∞ (m, rad)).
pub const DEFAULT_STATIC_TOLERANCE: f64 = 1e-9;
/// Default cap on trial steps, accepted and rejected together: a Newton phase takes 3–6, a
/// start on the wrong side of a hill (a pendulum near upright) 10–20 more.
pub const DEFAULT_STATIC_MAX_ITERATIONS: u32 = 100;
/// Default relative pivot tolerance of the factorization of [[M, Dᵀ], [D, 0]].
pub const DEFAULT_STATIC_PIVOT_TOLERANCE: f64 = 1e-13;
/// Default cap on the Newton iterations of each assembly onto Φ = 0 (the first one and the
/// restoration after each trial step), as [`crate::DEFAULT_MAX_ITERATIONS`] of the kinematic
/// solver.
pub const DEFAULT_STATIC_ASSEMBLY_ITERATIONS: u32 = 25;
/// Default relative tolerance of the stability verdict: a mode is neutral when
/// |ω²| ≤ 1e-8 · s, s the largest |ω²| or |H_ij| / √(M_ii M_jj) (1/s²). The stiffness and the
/// basis are computed to about 1e-12 of s (rounding through the factorizations), and the
/// equilibrium itself is only found to the tolerance: four orders of margin above both.
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
/// Cyclic Jacobi sweeps of the reduced stiffness: each sweep squares the off-diagonal norm
/// (quadratic convergence), so 6–10 sweeps reach rounding; 50 is a safe cap.
const JACOBI_MAX_SWEEPS: u32 = 50;
/// Bisection steps for the trust-region shift μ (each halves the bracket; 200 reach any
/// double's resolution from any bracket).
const SHIFT_BISECTIONS: u32 = 200;
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

/// Options of [`StaticSolver`]. Build from [`Default`] and the `with_*` methods.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct StaticOptions {
    /// Converged when both residuals are at most this (N or N·m for forces, m or rad for Φ) —
    /// the force residual, or its rounding floor 16 ε (‖h‖∞ + ‖Dᵀλ‖ + ‖H‖∞ max(1, ‖q‖∞)) where
    /// that is larger (loads of 10⁵ N on 10⁷ N/m cylinders cannot be balanced to 1e-9 N in
    /// f64). Default [`DEFAULT_STATIC_TOLERANCE`].
    pub tolerance: f64,
    /// Trial steps (accepted and rejected) before giving up. Default
    /// [`DEFAULT_STATIC_MAX_ITERATIONS`].
    pub max_iterations: u32,
    /// Relative pivot tolerance of the LU factorization (see [`crate::linalg::lu_factor`]).
    /// Default [`DEFAULT_STATIC_PIVOT_TOLERANCE`].
    pub pivot_tolerance: f64,
    /// Newton iterations of each assembly onto Φ = 0. Default
    /// [`DEFAULT_STATIC_ASSEMBLY_ITERATIONS`].
    pub assembly_iterations: u32,
    /// Relative tolerance of the neutral verdict (see [`Stability`]). Default
    /// [`DEFAULT_STATIC_NEUTRAL_TOLERANCE`].
    pub neutral_tolerance: f64,
    /// Largest velocity-space entry (m or rad) of the first step along a mode without
    /// stiffness. Default [`DEFAULT_STATIC_INITIAL_STEP`].
    pub initial_step: f64,
    /// On reaching an unstable equilibrium, step off it along its most unstable mode and keep
    /// going downhill (`true`, the default), or return it with [`Stability::Unstable`].
    pub leave_unstable: bool,
    /// A constraint row whose sine of angle to the rows declared before it is at most this is
    /// dropped (redundant, or dependent at a singular pose; its multiplier is 0). Default
    /// [`crate::DEFAULT_RANK_TOLERANCE`], as the kinematic solver's.
    pub rank_tolerance: f64,
}

impl Default for StaticOptions {
    fn default() -> Self {
        StaticOptions {
            tolerance: DEFAULT_STATIC_TOLERANCE,
            max_iterations: DEFAULT_STATIC_MAX_ITERATIONS,
            pivot_tolerance: DEFAULT_STATIC_PIVOT_TOLERANCE,
            assembly_iterations: DEFAULT_STATIC_ASSEMBLY_ITERATIONS,
            neutral_tolerance: DEFAULT_STATIC_NEUTRAL_TOLERANCE,
            initial_step: DEFAULT_STATIC_INITIAL_STEP,
            leave_unstable: true,
            rank_tolerance: crate::DEFAULT_RANK_TOLERANCE,
        }
    }
}

impl StaticOptions {
    /// With another residual tolerance.
    pub const fn with_tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = tolerance;
        self
    }
    /// With another cap on trial steps.
    pub const fn with_max_iterations(mut self, max_iterations: u32) -> Self {
        self.max_iterations = max_iterations;
        self
    }
    /// With another relative pivot tolerance.
    pub const fn with_pivot_tolerance(mut self, pivot_tolerance: f64) -> Self {
        self.pivot_tolerance = pivot_tolerance;
        self
    }
    /// With another cap on assembly iterations.
    pub const fn with_assembly_iterations(mut self, assembly_iterations: u32) -> Self {
        self.assembly_iterations = assembly_iterations;
        self
    }
    /// With another relative tolerance of the neutral verdict.
    pub const fn with_neutral_tolerance(mut self, neutral_tolerance: f64) -> Self {
        self.neutral_tolerance = neutral_tolerance;
        self
    }
    /// With another first step along a mode without stiffness (m or rad).
    pub const fn with_initial_step(mut self, initial_step: f64) -> Self {
        self.initial_step = initial_step;
        self
    }
    /// Whether to step off an unstable equilibrium (default) or return it.
    pub const fn with_leave_unstable(mut self, leave_unstable: bool) -> Self {
        self.leave_unstable = leave_unstable;
        self
    }
    /// See [`StaticOptions::rank_tolerance`].
    pub const fn with_rank_tolerance(mut self, rank_tolerance: f64) -> Self {
        self.rank_tolerance = rank_tolerance;
        self
    }
}

/// Whether an equilibrium is stable, from the reduced stiffness A = −Zᵀ H Z in an M-orthonormal
/// basis Z of the motions the joints allow: its eigenvalues are the squared natural frequencies
/// ω² (1/s²) of small oscillations about the equilibrium. A mode is neutral when
/// |ω²| ≤ [`StaticOptions::neutral_tolerance`] · s, s the largest |ω²| or |H_ij| / √(M_ii M_jj).
/// The verdict is on the symmetric part of the stiffness: for non-conservative loads (follower
/// forces) it says nothing about flutter.
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

/// The saddle-point part of the [`Workspace`]: the (NV + NC)-square matrix and its right-hand
/// side.
struct Saddle<'w, T, const NV: usize, const NC: usize, const N: usize> {
    matrix: &'w mut [[T; N]; N],
    rhs: &'w mut [T; N],
    /// Scratch of the rank-revealing orthogonalization of D's rows.
    rows: &'w mut [[T; NV]; NC],
    gram: &'w mut [[T; NC]; NC],
}

/// Static-equilibrium solver that finds stable equilibria (the algorithm: [the `statics`
/// module](crate::statics)).
#[derive(Clone, Copy, Debug, Default)]
pub struct StaticSolver {
    /// Tolerances, iteration caps and the choice at unstable equilibria.
    pub options: StaticOptions,
}

/// Name of row `i` of the stacked system: a velocity (force balance) or a constraint.
/// A non-finite generalized force or stiffness at velocity `i`: named by the force element that
/// reaches it (else by the velocity: the constraint stiffness K(λ) or a gyroscopic term).
fn non_finite_force<M: Mechanism>(t: f64, i: usize) -> StaticError {
    let velocity = name(M::VELOCITY_NAMES, i);
    match crate::dynamics::force_element::<M>(i) {
        Some((element, others)) => StaticError::NonFiniteForce { t, element, others, velocity },
        None => StaticError::NonFinite { t, row: velocity },
    }
}

fn row_name<M: Mechanism>(i: usize, nv: usize) -> &'static str {
    if i < nv {
        name(M::VELOCITY_NAMES, i)
    } else {
        name(M::CONSTRAINT_NAMES, i - nv)
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

/// Why a restoration onto Φ = 0 failed.
enum RestoreFailure {
    NotConverged { iterations: u32, worst: usize, residual: f64 },
    Static(StaticError),
}

/// The column `j` of an NV × NV array.
fn column<T: Real, const NV: usize>(a: &[[T; NV]; NV], j: usize) -> [T; NV] {
    core::array::from_fn(|i| a[i][j])
}

/// Writes column `j` of an NV × NV array.
fn set_column<T: Real, const NV: usize>(a: &mut [[T; NV]; NV], j: usize, x: &[T; NV]) {
    for (row, &value) in a.iter_mut().zip(x) {
        row[j] = value;
    }
}

/// Eigen-decomposition of the symmetric leading n × n block of `a` by cyclic Jacobi rotations:
/// on return its diagonal holds the eigenvalues; every rotation is also applied to the first n
/// columns of `basis` (so they become the eigenvectors in its coordinates).
// `!(x > y)` on purpose: it is also true when either side is NaN.
#[allow(clippy::neg_cmp_op_on_partial_ord)]
fn jacobi_eigen<T: Real, const N: usize, const NV: usize>(a: &mut [[T; N]; N], n: usize, basis: &mut [[T; NV]; NV]) {
    let two = T::from_f64(2.0);
    let huge = T::ONE / T::EPSILON;
    for _ in 0..JACOBI_MAX_SWEEPS {
        let (mut off, mut total) = (T::ZERO, T::ZERO);
        for (p, row) in a.iter().enumerate().take(n) {
            for (q, &value) in row.iter().enumerate().take(n) {
                total += value * value;
                if p != q {
                    off += value * value;
                }
            }
        }
        if !(off > T::EPSILON * T::EPSILON * total) {
            return;
        }
        for p in 0..n {
            for q in p + 1..n {
                let apq = a[p][q];
                if apq == T::ZERO {
                    continue;
                }
                let theta = (a[q][q] - a[p][p]) / (two * apq);
                let t = if theta.abs() > huge {
                    T::ONE / (two * theta)
                } else {
                    let magnitude = T::ONE / (theta.abs() + (theta * theta + T::ONE).sqrt());
                    if theta < T::ZERO {
                        -magnitude
                    } else {
                        magnitude
                    }
                };
                let c = T::ONE / (t * t + T::ONE).sqrt();
                let s = t * c;
                for row in a.iter_mut().take(n) {
                    let (akp, akq) = (row[p], row[q]);
                    row[p] = c * akp - s * akq;
                    row[q] = s * akp + c * akq;
                }
                let (upper, lower) = a.split_at_mut(q);
                for (apk, aqk) in upper[p].iter_mut().zip(lower[0].iter_mut()).take(n) {
                    (*apk, *aqk) = (c * *apk - s * *aqk, s * *apk + c * *aqk);
                }
                a[p][q] = T::ZERO;
                a[q][p] = T::ZERO;
                for row in basis.iter_mut() {
                    let (zp, zq) = (row[p], row[q]);
                    row[p] = c * zp - s * zq;
                    row[q] = s * zp + c * zq;
                }
            }
        }
    }
}

/// The trust-region step in mode coordinates, in the scaled norm ‖S y‖ (S = diag(`reach`), the
/// largest velocity-space entry of each unit mode, so ‖S y‖ measures the step in m or rad):
/// y_i = f_i / (ω²_i + μ s_i²) for the `active` modes (0 for the others), with the smallest
/// μ ≥ max(0, max −ω²_i / s_i²) that keeps ‖S y‖ ≤ `radius`, found by bisection on the
/// decreasing ‖S y(μ)‖. Returns ‖S y‖.
fn shifted_step<T: Real>(omega2: &[T], f: &[T], reach: &[T], active: &[bool], radius: T, y: &mut [T]) -> T {
    let modes = || omega2.iter().zip(f).zip(reach).zip(active).map(|(((&w, &fi), &s), &on)| (w, fi, s, on));
    let mut low = T::ZERO;
    let mut force = T::ZERO;
    for (w, fi, s, on) in modes() {
        if on {
            low = low.max(-w / (s * s));
            force += (fi / s) * (fi / s);
        }
    }
    let norm_at = |mu: T| {
        let mut sum = T::ZERO;
        for (w, fi, s, on) in modes() {
            if on {
                let scaled = s * fi / (w + mu * s * s);
                sum += scaled * scaled;
            }
        }
        sum.sqrt()
    };
    // At μ_hi = μ_lo + ‖f/s‖/radius every |s_i y_i| ≤ |f_i/s_i| radius/‖f/s‖, so ‖S y‖ ≤ radius.
    let mut high = low + force.sqrt() / radius;
    let newton = norm_at(T::ZERO);
    let mu = if low == T::ZERO && newton.is_finite() && newton <= radius {
        T::ZERO
    } else {
        let mut lo = low;
        for _ in 0..SHIFT_BISECTIONS {
            let mid = T::from_f64(0.5) * (lo + high);
            if !(mid > lo && mid < high) {
                break;
            }
            if norm_at(mid) > radius {
                lo = mid;
            } else {
                high = mid;
            }
        }
        high
    };
    let mut norm = T::ZERO;
    for (yi, (w, fi, s, on)) in y.iter_mut().zip(modes()) {
        *yi = if on { fi / (w + mu * s * s) } else { T::ZERO };
        norm += (s * *yi) * (s * *yi);
    }
    norm.sqrt()
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

/// The factorization of [[M, Dᵀ], [D, 0]] at one configuration.
struct SaddleFactors<const N: usize, const NC: usize> {
    permutation: Permutation<N>,
    /// The rank of D: NV − rank is the mobility at q, the null space's dimension.
    rank: usize,
    /// The constraint rows dropped as dependent on the rows before them.
    redundant: [bool; NC],
}

impl StaticSolver {
    /// A solver with the given options.
    pub const fn new(options: StaticOptions) -> Self {
        StaticSolver { options }
    }

    /// Finds a stable equilibrium: q and λ with h(q, 0, t) + Dᵀλ = 0 and Φ(q, t) = 0 where the
    /// potential energy is a local minimum on the constraint manifold, starting from `q` — any
    /// rough guess; it is assembled first — and descending in energy (see the module
    /// documentation). `lambda` is an output only (its value on entry is ignored): on success
    /// it holds the multipliers, and the joint reactions follow from them with
    /// [`crate::joint_reaction`]. On success `q` holds the equilibrium, with planar angles in
    /// (−π, π] where the mechanism is periodic in them and unit Euler parameters with e0 ≥ 0;
    /// on error it holds the last accepted iterate.
    ///
    /// # Errors
    /// [`StaticError::WorkspaceSize`]; [`StaticError::NonFinite`] (t, q, Φ, D, h, its
    /// derivatives); [`StaticError::NotAssembled`]; [`StaticError::Singular`] (a velocity
    /// without mass); [`StaticError::NotConverged`], naming the velocity or constraint row with
    /// the largest residual.
    pub fn solve<T, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
        &self,
        m: &M,
        ws: &mut Workspace<T, NV, NC, N>,
        q: &mut [T; NQ],
        t: T,
        lambda: &mut [T; NC],
    ) -> Result<StaticReport, StaticError>
    where
        T: Real,
        M: Dynamics<T, NQ, NV, NC> + ConstraintForces<T, NQ, NV, NC>,
    {
        if N != NV + NC {
            return Err(StaticError::WorkspaceSize { expected: NV + NC, found: N });
        }
        let time = t.to_f64();
        if !t.is_finite() {
            return Err(StaticError::NonFinite { t: time, row: "t" });
        }
        if let Some(i) = first_non_finite(q) {
            return Err(StaticError::NonFinite { t: time, row: name(M::COORDINATE_NAMES, i) });
        }
        let options = &self.options;
        let tol = T::from_f64(options.tolerance);
        let half = T::from_f64(0.5);
        let zero_v = [T::ZERO; NV];
        let mut phi = [T::ZERO; NC];
        // D; H = (∂h/∂q)B + K(λ) and then Z in two NV × NV arrays; the saddle-point system.
        let Workspace { jacobian: d, jacobian_scratch, constraint_square, velocity_squares: [stiffness, basis, _], saddle, saddle_rhs } =
            ws;
        let ws = &mut Saddle { matrix: saddle, rhs: saddle_rhs, rows: jacobian_scratch, gram: constraint_square };
        let (mut h, mut r, mut mass_diagonal) = ([T::ZERO; NV], [T::ZERO; NV], [T::ZERO; NV]);
        // Per mode: ω², the force along it, its largest entry, the largest entry of M z.
        let (mut omega2, mut f, mut reach, mut force_scale) = ([T::ZERO; NV], [T::ZERO; NV], [T::ZERO; NV], [T::ZERO; NV]);
        let (mut y, mut active, mut trial) = ([T::ZERO; NV], [false; NV], *q);
        let mut correction = [T::ZERO; NV];

        self.restore(m, q, t, &mut phi, d, ws, &mut correction).map_err(|e| match e {
            RestoreFailure::NotConverged { iterations, worst, residual } => {
                StaticError::NotAssembled { t: time, iterations, worst_row: name(M::CONSTRAINT_NAMES, worst), residual }
            }
            RestoreFailure::Static(e) => e,
        })?;

        let (mut accepted, mut rejected) = (0u32, 0u32);
        // The trust radius, in the scaled norm of `shifted_step` (m or rad).
        let mut radius = T::from_f64(options.initial_step);
        loop {
            // Forces, constraints, multipliers and the projected residual at the assembled q.
            m.position_eval(q, t, &mut phi, d);
            m.forces(q, &zero_v, t, &mut h);
            if let Some(i) = first_non_finite(&phi) {
                return Err(StaticError::NonFinite { t: time, row: name(M::CONSTRAINT_NAMES, i) });
            }
            if let Some(i) = first_non_finite(&h) {
                return Err(non_finite_force::<M>(time, i));
            }
            let factors = self.factor_saddle(m, q, t, d, ws, &mut mass_diagonal)?;
            // The mobility at q: NV − NC, or more where rows are redundant or the pose singular.
            let dof = NV - factors.rank;
            ws.rhs[..NV].copy_from_slice(&h);
            ws.rhs[NV..].fill(T::ZERO);
            lu_solve_in_place(ws.matrix, &factors.permutation, ws.rhs);
            for (l, &x) in lambda.iter_mut().zip(&ws.rhs[NV..]) {
                *l = -x;
            }
            for (kv, ri) in r.iter_mut().enumerate() {
                *ri = h[kv] + d.iter().zip(lambda.iter()).fold(T::ZERO, |s, (row, &l)| s + row[kv] * l);
            }
            if let Some(i) = first_non_finite(&r) {
                return Err(StaticError::NonFinite { t: time, row: name(M::VELOCITY_NAMES, i) });
            }
            let (force_residual, force_row) = max_abs(&r);
            let (constraint_residual, constraint_row) = max_abs(&phi);
            let (residual, worst_row) = if force_residual >= constraint_residual {
                (force_residual, name(M::VELOCITY_NAMES, force_row))
            } else {
                (constraint_residual, name(M::CONSTRAINT_NAMES, constraint_row))
            };

            // Modes: Z (M-orthonormal null-space basis) and the reduced stiffness's eigenpairs.
            m.forces_q(q, &zero_v, t, stiffness);
            m.constraint_force_q(q, t, lambda, basis);
            for (row, krow) in stiffness.iter_mut().zip(basis.iter()) {
                for (x, &kx) in row.iter_mut().zip(krow) {
                    *x += kx;
                }
            }
            for (i, row) in stiffness.iter().enumerate() {
                if first_non_finite(row).is_some() {
                    return Err(non_finite_force::<M>(time, i));
                }
            }
            self.null_space_basis(m, q, t, &factors, ws, dof, basis)?;
            let scale = reduced_stiffness(stiffness, basis, dof, &mass_diagonal, ws);
            jacobi_eigen(ws.matrix, dof, basis);
            let mut lowest = 0;
            for i in 0..dof {
                omega2[i] = ws.matrix[i][i];
                let z = column(basis, i);
                f[i] = dot(&z, &r);
                reach[i] = max_abs(&z).0;
                let mut mz = [T::ZERO; NV];
                m.mass_times(q, &z, &mut mz);
                force_scale[i] = max_abs(&mz).0;
                if omega2[i] < omega2[lowest] {
                    lowest = i;
                }
            }
            let scale = omega2[..dof].iter().fold(scale, |s, w| s.max(w.abs()));
            let neutral = T::from_f64(options.neutral_tolerance) * scale;

            // The tolerance, or the force residual's rounding floor where that is larger.
            let reaction =
                (0..NV).fold(T::ZERO, |s, kv| s.max(d.iter().zip(lambda.iter()).fold(T::ZERO, |a, (row, &l)| a + (row[kv] * l).abs())));
            let stiffness_norm = stiffness.iter().fold(T::ZERO, |s, row| s.max(row.iter().fold(T::ZERO, |a, x| a + x.abs())));
            let floor =
                T::from_f64(RESIDUAL_ROUNDING) * T::EPSILON * (max_abs(&h).0 + reaction + stiffness_norm * max_abs(q).0.max(T::ONE));
            let tol = tol.max(floor);
            let converged = residual <= tol;
            let unstable = dof > 0 && omega2[lowest] < -neutral;
            if converged && !(unstable && options.leave_unstable) {
                let stability = classify::<T, M, NV>(dof, &omega2, basis, &mass_diagonal, lowest, neutral);
                self.wrap_angles(m, q, t, &phi, d, &h, stiffness);
                return Ok(StaticReport { iterations: accepted, rejected, residual: residual.to_f64(), stability });
            }
            let not_converged = |iterations| StaticError::NotConverged { t: time, iterations, worst_row, residual: residual.to_f64() };
            if accepted + rejected >= options.max_iterations {
                return Err(not_converged(accepted + rejected));
            }

            // Which modes to move: those whose force shows in the residual (r = Σ M z_i f_i, so
            // if each were below tolerance / DOF we would have converged).
            let per_mode = tol / T::from_f64(dof.max(1) as f64);
            for i in 0..dof {
                active[i] = f[i].abs() * force_scale[i] > per_mode;
            }
            let newton = (0..dof).all(|i| !active[i] || omega2[i] > neutral);
            // Off an unstable equilibrium: along its most unstable mode, the first step moving
            // no entry more than `initial_step`.
            let escape = converged;
            if escape {
                radius = T::from_f64(options.initial_step);
            }
            let mut attempts = 0u32;
            loop {
                // The step in mode coordinates and its predicted energy decrease.
                let step_norm = if escape {
                    y[..dof].fill(T::ZERO);
                    // Downhill along the force if it has any, else toward the mode's largest
                    // entry (either way falls off a saddle).
                    let z = column(basis, lowest);
                    let sign = if f[lowest] != T::ZERO { f[lowest] } else { z[max_abs(&z).1] };
                    let size = radius / reach[lowest];
                    y[lowest] = if sign < T::ZERO { -size } else { size };
                    radius
                } else {
                    let mut norm = T::ZERO;
                    if newton {
                        for i in 0..dof {
                            y[i] = if active[i] { f[i] / omega2[i] } else { T::ZERO };
                            norm += (reach[i] * y[i]) * (reach[i] * y[i]);
                        }
                        norm = norm.sqrt();
                    }
                    if newton && norm <= radius {
                        norm
                    } else {
                        shifted_step(&omega2[..dof], &f[..dof], &reach[..dof], &active[..dof], radius, &mut y[..dof])
                    }
                };
                let predicted = (0..dof).fold(T::ZERO, |s, i| s + f[i] * y[i] - half * omega2[i] * y[i] * y[i]);
                let mut delta = [T::ZERO; NV];
                for (di, row) in delta.iter_mut().zip(basis.iter()) {
                    *di = dot(&row[..dof], &y[..dof]);
                }
                let ratio = self.trial(m, q, t, &h, &delta, predicted, &mut trial, &mut phi, d, ws);
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
                if escape && attempts >= ESCAPE_ATTEMPTS {
                    // Every step off it raised the energy: unstable as it looked, but not
                    // leavable at this resolution; report it as it is.
                    m.position_eval(q, t, &mut phi, d);
                    let stability = classify::<T, M, NV>(dof, &omega2, basis, &mass_diagonal, lowest, neutral);
                    self.wrap_angles(m, q, t, &phi, d, &h, stiffness);
                    return Ok(StaticReport { iterations: accepted, rejected, residual: residual.to_f64(), stability });
                }
                if accepted + rejected >= options.max_iterations {
                    return Err(not_converged(accepted + rejected));
                }
            }
        }
    }

    /// One trial step from the equilibrium iterate `q` (forces `h`): `trial` = q ⊕ δ restored
    /// onto Φ = 0, and the work the loads did along the displacement δ' (δ plus the
    /// restoration's steps), by Simpson's rule on the chord: (h₀ + 4 h(q ⊕ δ'/2) + h₁)ᵀ δ' / 6,
    /// −ΔV to fifth order for conservative loads, and alert to a hill inside the step that the
    /// end points alone would miss. Returns the ratio of that work to the `predicted` decrease
    /// if the step is accepted (the work is at least [`ACCEPT_RATIO`] of the prediction, up to
    /// the rounding of the sum), `None` if it is rejected or its restoration failed.
    #[allow(clippy::too_many_arguments)]
    fn trial<T, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
        &self,
        m: &M,
        q: &[T; NQ],
        t: T,
        h: &[T; NV],
        delta: &[T; NV],
        predicted: T,
        trial: &mut [T; NQ],
        phi: &mut [T; NC],
        d: &mut [[T; NV]; NC],
        ws: &mut Saddle<'_, T, NV, NC, N>,
    ) -> Option<T>
    where
        T: Real,
        M: Dynamics<T, NQ, NV, NC>,
    {
        let zero_v = [T::ZERO; NV];
        *trial = *q;
        m.integrate_positions(trial, delta, T::ONE);
        let mut correction = [T::ZERO; NV];
        self.restore(m, trial, t, phi, d, ws, &mut correction).ok()?;
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

    /// [[M, Dᵀ], [D, 0]] into the workspace, factored; M's diagonal into `mass_diagonal`.
    /// A constraint row that depends on the rows declared before it (sine of its angle to
    /// their span ≤ [`StaticOptions::rank_tolerance`], as [`crate::KinematicSolver::redundancy`]
    /// decides: a redundant constraint, or a singular pose) is dropped: its row and column of
    /// the matrix become the identity's, so its multiplier is 0 (the dropped row carries no
    /// load, the rule forward dynamics follows) and what it imposes is met through the others.
    fn factor_saddle<T, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
        &self,
        m: &M,
        q: &[T; NQ],
        t: T,
        d: &[[T; NV]; NC],
        ws: &mut Saddle<'_, T, NV, NC, N>,
        mass_diagonal: &mut [T; NV],
    ) -> Result<SaddleFactors<N, NC>, StaticError>
    where
        T: Real,
        M: Dynamics<T, NQ, NV, NC>,
    {
        let time = t.to_f64();
        for row in ws.matrix.iter_mut() {
            row.fill(T::ZERO);
        }
        let mut unit = [T::ZERO; NV];
        let mut column_j = [T::ZERO; NV];
        for j in 0..NV {
            unit[j] = T::ONE;
            m.mass_times(q, &unit, &mut column_j);
            unit[j] = T::ZERO;
            for (i, &value) in column_j.iter().enumerate() {
                ws.matrix[i][j] = value;
            }
            mass_diagonal[j] = column_j[j];
        }
        let mut redundant = [false; NC];
        let split = orthogonalize(d, T::from_f64(self.options.rank_tolerance), ws.rows, ws.gram, &mut redundant);
        for (r, row) in d.iter().enumerate() {
            if redundant[r] {
                ws.matrix[NV + r][NV + r] = T::ONE;
                continue;
            }
            for (c, &value) in row.iter().enumerate() {
                ws.matrix[c][NV + r] = value;
                ws.matrix[NV + r][c] = value;
            }
        }
        let permutation = lu_factor(ws.matrix, T::from_f64(self.options.pivot_tolerance).max(T::EPSILON)).map_err(|e| match e {
            LinalgError::Singular { column, .. } => StaticError::Singular { t: time, row: row_name::<M>(column, NV) },
            // M is NV × NV, D's entries sit in the rows or columns past NV.
            LinalgError::NonFinite { row, column } => StaticError::NonFinite { t: time, row: row_name::<M>(row.max(column), NV) },
            LinalgError::NotSquare { .. } | LinalgError::Overdetermined { .. } => {
                StaticError::WorkspaceSize { expected: NV + NC, found: N }
            }
        })?;
        Ok(SaddleFactors { permutation, rank: split.rank, redundant })
    }

    /// Newton onto Φ(q, t) = 0 with steps of least kinetic-energy norm,
    /// [[M, Dᵀ], [D, 0]] [Δv; ·] = [0; −Φ], q ← q ⊕ Δv; the steps are added to `correction`.
    /// On success `phi` and `d` hold Φ and D at the returned q.
    #[allow(clippy::too_many_arguments)]
    fn restore<T, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
        &self,
        m: &M,
        q: &mut [T; NQ],
        t: T,
        phi: &mut [T; NC],
        d: &mut [[T; NV]; NC],
        ws: &mut Saddle<'_, T, NV, NC, N>,
        correction: &mut [T; NV],
    ) -> Result<u32, RestoreFailure>
    where
        T: Real,
        M: Dynamics<T, NQ, NV, NC>,
    {
        let time = t.to_f64();
        let tol = T::from_f64(self.options.tolerance);
        let mut diagonal = [T::ZERO; NV];
        let mut iterations = 0;
        let mut dropped = [false; NC];
        loop {
            m.position_eval(q, t, phi, d);
            if let Some(i) = first_non_finite(phi) {
                return Err(RestoreFailure::Static(StaticError::NonFinite { t: time, row: name(M::CONSTRAINT_NAMES, i) }));
            }
            let (norm, worst) = max_abs(phi);
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
            let factors = self.factor_saddle(m, q, t, d, ws, &mut diagonal).map_err(RestoreFailure::Static)?;
            dropped = factors.redundant;
            ws.rhs[..NV].fill(T::ZERO);
            for (x, &p) in ws.rhs[NV..].iter_mut().zip(phi.iter()) {
                *x = -p;
            }
            lu_solve_in_place(ws.matrix, &factors.permutation, ws.rhs);
            let mut step = [T::ZERO; NV];
            step.copy_from_slice(&ws.rhs[..NV]);
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

    /// The first `dof` columns of `basis` become an M-orthonormal basis of the null space of D:
    /// the M-orthogonal projections P e_j of the unit velocities (from the factors of
    /// [[M, Dᵀ], [D, 0]]: [[M, Dᵀ], [D, 0]] [P e_j; ·] = [M e_j; 0]), orthonormalized by
    /// Gram–Schmidt in the M inner product, each step taking the remaining column of largest
    /// M-norm.
    // `!(x > y)` on purpose: it is also true when either side is NaN.
    #[allow(clippy::too_many_arguments, clippy::neg_cmp_op_on_partial_ord)]
    fn null_space_basis<T, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
        &self,
        m: &M,
        q: &[T; NQ],
        t: T,
        factors: &SaddleFactors<N, NC>,
        ws: &mut Saddle<'_, T, NV, NC, N>,
        dof: usize,
        basis: &mut [[T; NV]; NV],
    ) -> Result<(), StaticError>
    where
        T: Real,
        M: Dynamics<T, NQ, NV, NC>,
    {
        let mut unit = [T::ZERO; NV];
        let mut mz = [T::ZERO; NV];
        for j in 0..NV {
            unit[j] = T::ONE;
            m.mass_times(q, &unit, &mut mz);
            unit[j] = T::ZERO;
            ws.rhs[..NV].copy_from_slice(&mz);
            ws.rhs[NV..].fill(T::ZERO);
            lu_solve_in_place(ws.matrix, &factors.permutation, ws.rhs);
            for (row, &value) in basis.iter_mut().zip(ws.rhs.iter()) {
                row[j] = value;
            }
        }
        let m_norm2 = |z: &[T; NV], mz: &mut [T; NV]| {
            m.mass_times(q, z, mz);
            dot(z, mz)
        };
        for s in 0..dof {
            let mut best = (T::ZERO, s);
            for j in s..NV {
                let n2 = m_norm2(&column(basis, j), &mut mz);
                if n2 > best.0 {
                    best = (n2, j);
                }
            }
            if !(best.0 > T::ZERO) || !best.0.is_finite() {
                return Err(StaticError::Singular { t: t.to_f64(), row: name(M::VELOCITY_NAMES, best.1) });
            }
            for row in basis.iter_mut() {
                row.swap(s, best.1);
            }
            let inverse = T::ONE / best.0.sqrt();
            let mut zs = column(basis, s);
            for x in zs.iter_mut() {
                *x *= inverse;
            }
            set_column(basis, s, &zs);
            m.mass_times(q, &zs, &mut mz);
            for j in s + 1..NV {
                let mut zj = column(basis, j);
                let c = dot(&zj, &mz);
                for (x, &z) in zj.iter_mut().zip(&zs) {
                    *x -= c * z;
                }
                set_column(basis, j, &zj);
            }
        }
        Ok(())
    }

    /// Wraps each planar angle into (−π, π] and flips each body's Euler parameters to e0 ≥ 0,
    /// where that leaves Φ and h unchanged (to the tolerance plus the rounding of the shift,
    /// bounded by the shift's size times the largest entry of D's or H's column); then
    /// normalizes. `d` (D at q on entry) is work space.
    #[allow(clippy::too_many_arguments)]
    fn wrap_angles<T, M, const NQ: usize, const NV: usize, const NC: usize>(
        &self,
        m: &M,
        q: &mut [T; NQ],
        t: T,
        phi: &[T; NC],
        d: &mut [[T; NV]; NC],
        h: &[T; NV],
        stiffness: &[[T; NV]; NV],
    ) where
        T: Real,
        M: Dynamics<T, NQ, NV, NC>,
    {
        let tol = T::from_f64(self.options.tolerance);
        let names = M::COORDINATE_NAMES;
        let zero_v = [T::ZERO; NV];
        let d_columns: [T; NV] = core::array::from_fn(|i| d.iter().fold(T::ZERO, |s, row| s.max(row[i].abs())));
        let h_columns: [T; NV] = core::array::from_fn(|i| stiffness.iter().fold(T::ZERO, |s, row| s.max(row[i].abs())));
        let (mut phi1, mut h1) = ([T::ZERO; NC], [T::ZERO; NV]);
        let mut unchanged = |candidate: &[T; NQ], d_scale: T, h_scale: T| {
            m.position_eval(candidate, t, &mut phi1, d);
            m.forces(candidate, &zero_v, t, &mut h1);
            phi.iter().zip(&phi1).all(|(a, b)| (*a - *b).abs() <= tol + d_scale)
                && h.iter().zip(&h1).all(|(a, b)| (*a - *b).abs() <= tol + h_scale)
        };
        let rounding = T::from_f64(16.0) * T::EPSILON;
        for i in 0..NQ {
            let coordinate = name(names, i);
            if M::DIMENSION == 2 && NQ == NV && coordinate.ends_with(".phi") {
                let wrapped = T::from_f64(wrap_angle(q[i].to_f64()));
                if wrapped == q[i] {
                    continue;
                }
                let shift = rounding * (q[i].abs() + T::from_f64(2.0 * core::f64::consts::PI));
                let mut candidate = *q;
                candidate[i] = wrapped;
                if unchanged(&candidate, shift * d_columns[i], shift * h_columns[i]) {
                    *q = candidate;
                }
            } else if M::DIMENSION == 3 && coordinate.ends_with(".e0") && i + 3 < NQ && q[i] < T::ZERO {
                // p and −p are one rotation: Φ and h do not change at all.
                let mut candidate = *q;
                for x in candidate[i..i + 4].iter_mut() {
                    *x = -*x;
                }
                if unchanged(&candidate, rounding * max_abs(phi).0, rounding * max_abs(h).0) {
                    *q = candidate;
                }
            }
        }
        m.normalize_positions(q);
    }
}

/// A = −Zᵀ H Z (symmetric part) into the leading `dof` block of the workspace; returns
/// s = max |H_ij| / √(M_ii M_jj), the scale of the neutral verdict (1/s²).
fn reduced_stiffness<T: Real, const NV: usize, const NC: usize, const N: usize>(
    stiffness: &[[T; NV]; NV],
    basis: &[[T; NV]; NV],
    dof: usize,
    mass_diagonal: &[T; NV],
    ws: &mut Saddle<'_, T, NV, NC, N>,
) -> T {
    let mut scale = T::ZERO;
    for (i, row) in stiffness.iter().enumerate() {
        for (j, &value) in row.iter().enumerate() {
            let weight = (mass_diagonal[i] * mass_diagonal[j]).sqrt();
            if weight > T::ZERO {
                scale = scale.max(value.abs() / weight);
            }
        }
    }
    for j in 0..dof {
        let z = column(basis, j);
        let hz: [T; NV] = core::array::from_fn(|i| dot(&stiffness[i], &z));
        for (a, row) in ws.matrix.iter_mut().enumerate().take(dof) {
            row[j] = -basis.iter().zip(&hz).fold(T::ZERO, |s, (z, &x)| s + z[a] * x);
        }
    }
    let half = T::from_f64(0.5);
    for a in 0..dof {
        for b in a + 1..dof {
            let mean = half * (ws.matrix[a][b] + ws.matrix[b][a]);
            ws.matrix[a][b] = mean;
            ws.matrix[b][a] = mean;
        }
    }
    scale
}

/// The stability verdict from the eigenvalues ω² and mode shapes (columns of `basis`).
fn classify<T: Real, M: Mechanism, const NV: usize>(
    dof: usize,
    omega2: &[T; NV],
    basis: &[[T; NV]; NV],
    mass_diagonal: &[T; NV],
    lowest: usize,
    neutral: T,
) -> Stability {
    if dof == 0 {
        return Stability::Stable { omega_squared: f64::INFINITY };
    }
    let w = omega2[lowest];
    let direction = {
        let z = column(basis, lowest);
        let weighted: [T; NV] = core::array::from_fn(|i| z[i] * mass_diagonal[i].abs().sqrt());
        name(M::VELOCITY_NAMES, max_abs(&weighted).1)
    };
    if w < -neutral {
        Stability::Unstable { direction, omega_squared: w.to_f64() }
    } else if w <= neutral {
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
            let report = StaticSolver::default().solve(&UnitPendulum, &mut Workspace::<f64, 3, 2, 5>::new(), &mut q, 0.0, &mut lambda);
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
    }

    /// Jacobi's eigenvalues of a symmetric 3 × 3 matrix with known spectrum (1, 2, 4 — the
    /// matrix Q diag(1, 2, 4) Qᵀ for a rotation Q), and the rotated basis holds its eigenvectors:
    /// to 1e-12 (a few sweeps reach rounding).
    #[test]
    fn jacobi_finds_eigenpairs() {
        let (c, s) = (0.6, 0.8);
        let qm = [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]];
        let lambda = [1.0, 2.0, 4.0];
        let mut a = [[0.0; 4]; 4];
        for i in 0..3 {
            for j in 0..3 {
                a[i][j] = (0..3).map(|k| qm[i][k] * lambda[k] * qm[j][k]).sum();
            }
        }
        let original = a;
        let mut basis = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        jacobi_eigen(&mut a, 3, &mut basis);
        let mut found = [a[0][0], a[1][1], a[2][2]];
        found.sort_by(f64::total_cmp);
        for (f, e) in found.iter().zip(lambda) {
            assert!((f - e).abs() < 1e-12, "{found:?}");
        }
        for k in 0..3 {
            let v = [basis[0][k], basis[1][k], basis[2][k]];
            for i in 0..3 {
                let av: f64 = (0..3).map(|j| original[i][j] * v[j]).sum();
                assert!((av - a[k][k] * v[i]).abs() < 1e-12, "A v = λ v for mode {k}");
            }
        }
    }

    /// The shifted step: Newton's when it fits, else on the radius with μ > −min ω²; inactive
    /// modes do not move. Tolerances: the bisection resolves μ to rounding, so ‖y‖ = radius to
    /// 1e-12.
    #[test]
    fn shifted_step_stays_in_the_radius() {
        let mut y = [0.0; 3];
        let unscaled = [1.0; 3];
        // Newton fits: μ = 0.
        let n = shifted_step(&[2.0, 4.0, 1.0], &[1.0, 2.0, 0.0], &unscaled, &[true, true, true], 10.0, &mut y);
        assert_eq!(y, [0.5, 0.5, 0.0]);
        assert!((n - 0.5f64.hypot(0.5)).abs() < 1e-15);
        // Negative curvature with a force along it: on the radius, the negative mode dominant.
        let n = shifted_step(&[-3.0, 4.0, 1.0], &[0.1, 2.0, 5.0], &unscaled, &[true, true, false], 0.7, &mut y);
        assert!((n - 0.7).abs() < 1e-12 && y[2] == 0.0 && y[0] > 0.0 && y[0].abs() > y[1].abs(), "{y:?}");
        let mu = 0.1 / y[0] + 3.0;
        assert!(mu > 3.0 && (y[1] - 2.0 / (4.0 + mu)).abs() < 1e-9, "{y:?}");
        // Scaled: a mode whose unit moves an entry by 2 gets half the room.
        let n = shifted_step(&[1.0], &[10.0], &[2.0], &[true], 1.0, &mut y[..1]);
        assert!((n - 1.0).abs() < 1e-12 && (y[0] - 0.5).abs() < 1e-12, "{y:?}");
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
