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

mod angles;
mod iterate;
mod report;
mod step;

use crate::model::mechanism::NewtonMatrix;
#[cfg(doc)]
use crate::model::mechanism::{ConstraintForces, CoordinateKind, Dynamics};
use crate::model::workspace::Workspace;
use crate::real::Real;
use crate::solvers::kinematics::{first_non_finite, name};

use iterate::{dot, max_abs, IterateVectors, Mode, RestoreFailure};
use report::classify;
pub use report::{Stability, StaticError, StaticReport};

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
        /// Relative pivot tolerance of the planned factorization (see [`crate::sparse::factor`]):
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
        let (newton, mut dense) = ws.newton_and_dense();
        let Some([mass, stiff, scratch]) = crate::model::workspace::newton_slots::<M::NewtonStorage, T, NS>(newton) else {
            return Err(StaticError::NewtonSlotSize { expected: M::JACOBIAN_PATTERN.len() + M::NEWTON_PATTERN.entries(), found: NS });
        };
        let time = t.to_f64();
        if !t.is_finite() {
            return Err(StaticError::NonFinite { t: time, row: "t" });
        }
        if let Err(crate::model::dynamics::DynamicsError::NonPositiveMass { body, value }) = m.check_inertia() {
            return Err(StaticError::NonPositiveMass { body, value });
        }
        if let Some(i) = first_non_finite(q) {
            return Err(StaticError::NonFinite { t: time, row: name(M::COORDINATE_NAMES, i) });
        }
        let options = &self.options;
        let tol = options.tolerance;
        let half = T::from_f64(0.5);
        // The trial point, the restoration's correction, the step, the lowest mode's shape and
        // the iterate's vectors: the work space's.
        let trial = dense.vectors.take::<NQ>();
        let [correction, delta, shape] = dense.vectors.rows::<NV, 3>();
        let mut vectors = IterateVectors::<T, NV, NC, N>::take(&mut dense.vectors);

        self.restore::<M, NQ, NV, NC, N>(m, q, t, correction, scratch, dense.reborrow()).map_err(|e| match e {
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
            let it = self.evaluate::<M, NQ, NV, NC, N>(m, q, t, mass, stiff, scratch, &mut vectors, dense.reborrow())?;
            *lambda = *it.lambda;
            let (force_residual, force_row) = max_abs(it.r);
            let (constraint_residual, constraint_row) = max_abs(it.phi);
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
                * (max_abs(it.h).0 + it.reaction + it.stiffness_norm * max_abs(q).0.max(T::ONE));
            let tol = tol.max(floor);
            let converged = residual <= tol;
            let not_converged = |iterations| StaticError::NotConverged { t: time, iterations, worst_row, residual: residual.to_f64() };
            // At a converged point, its lowest mode tells stable from unstable.
            let mode = if converged && dof > 0 {
                let mode = self.lowest_mode::<M, NQ, NV, NC, N>(m, q, &it, scratch, &mut *shape, dense.vectors.reborrow());
                Some(mode.ok_or_else(|| not_converged(accepted + rejected))?)
            } else {
                None
            };
            // The neutral band: relative to the stiffness scale, and never below what rounding
            // leaves of ω² (about ε times the inverse iteration's shift).
            let neutral = |mode: &Mode<'_, T, NV>| options.neutral_tolerance * it.scale.max(mode.omega_squared.abs()).max(mode.shift);
            let unstable = mode.as_ref().is_some_and(|mode| mode.omega_squared < -neutral(mode));
            if converged && !(unstable && options.leave_unstable) {
                let stability = classify::<T, M, NV>(mode.as_ref(), it.mass_diagonal, neutral);
                self.wrap_angles(m, q, t, &it, scratch, dense.reborrow());
                // D into the work space's (`Workspace::jacobian`), which `dense.y` is.
                m.jacobian(q, t, dense.y);
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
                let predicted = match &escape {
                    Some(mode) => {
                        // Downhill along the force if it has any, else toward the mode's
                        // largest entry (either way falls off a saddle).
                        let z = mode.shape;
                        let f = dot(z, it.r);
                        let sign = if f != T::ZERO { f } else { z[max_abs(z).1] };
                        let size = radius / m.motion_size(q, z);
                        let y = if sign < T::ZERO { -size } else { size };
                        for (d, &zi) in delta.iter_mut().zip(z.iter()) {
                            *d = y * zi;
                        }
                        Some(f * y - half * mode.omega_squared * y * y)
                    }
                    None => self.shifted_step::<M, NQ, NV, NC, N>(m, q, &it, radius, scratch, delta, dense.vectors.reborrow()),
                };
                let Some(predicted) = predicted else {
                    return Err(not_converged(accepted + rejected));
                };
                let step_norm = m.motion_size(q, delta);
                let ratio = self.trial::<M, NQ, NV, NC, N>(m, q, t, it.h, delta, predicted, trial, correction, scratch, dense.reborrow());
                if let Some(ratio) = ratio {
                    *q = *trial;
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
                    let stability = classify::<T, M, NV>(escape.as_ref(), it.mass_diagonal, neutral);
                    self.wrap_angles(m, q, t, &it, scratch, dense.reborrow());
                    m.jacobian(q, t, dense.y);
                    return Ok(StaticReport { iterations: accepted, rejected, residual: residual.to_f64(), stability });
                }
                if accepted + rejected >= options.max_iterations {
                    return Err(not_converged(accepted + rejected));
                }
            }
        }
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
}
