//! Forward dynamics (Nikravesh ch. 13): accelerations and Lagrange multipliers from
//!
//! ```text
//! M v̇ − Dᵀ λ = h(q, v, t)
//! D v̇       = γ − 2α (D v − ν) − β² Φ        (Baumgarte stabilization, α, β in 1/s)
//! ```
//!
//! in velocity space (D = Φ_q B; planar v = q̇, D = Φ_q). With M block-diagonal,
//! v̇ = M⁻¹ (h + Dᵀ λ) and λ solves S λ = γ* − D M⁻¹ h with S = D M⁻¹ Dᵀ. `mechanism!` generates
//! this solve as straight-line code over the structural non-zeros of S and of its LDLᵀ factor,
//! whose pattern it computes at compile time ([`ForwardDynamics`]). The same factorization
//! projects positions and velocities back onto the constraint manifold in the metric of M.

use core::fmt;

use crate::model::mechanism::{Dynamics, Mechanism};
use crate::model::workspace::DenseScratch;
use crate::real::Real;

/// Default Baumgarte α and β (1/s): the constraint violation then decays like a critically
/// damped oscillator with a time constant of 0.2 s. Zero turns stabilization off.
pub const DEFAULT_BAUMGARTE: f64 = 5.0;
/// Default relative pivot tolerance τ of the LDLᵀ of S. With [`DynamicsOptions::allow_redundant`]
/// (the default) each 1/d_k becomes w/d_k with w = 1/(1 + ρ⁸), ρ = τ S_kk/d_k: a row within
/// about √τ = 1e-4 rad of the span of the rows before it (a singular position, a redundant
/// constraint) is dropped smoothly; a pivot 100 τ S_kk or more is exact, and one at 20 τ S_kk
/// (a row at 4.5e-4 rad, met in the spatial oracle's mechanisms) changes by 4e-11. Measured on
/// parallelogram chains passing their flat positions (`mbd-long/tests/singular.rs`, 4 loops):
/// τ = 1e-8 held DOPRI5 at rtol 1e-12 to 2.2e-8 rad of the exact motion over 20 s, τ = 1e-10
/// to 3.8e-7.
pub const DEFAULT_DYNAMICS_PIVOT_TOLERANCE: f64 = 1e-8;

crate::options::options! {
    /// Options of one forward-dynamics solve, in the scalar type `T` of the mechanism (default
    /// `f64`). Build from [`Default`] (Baumgarte on), [`DynamicsOptions::without_stabilization`]
    /// (the default of [`Simulation`](crate::Simulation)) or [`DynamicsOptions::baumgarte`], and the
    /// `with_*` setters.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct DynamicsOptions<T> {
        /// Baumgarte α (1/s), the weight 2α of the velocity violation D v − ν. Default 5
        /// ([`DEFAULT_BAUMGARTE`]).
        baumgarte_alpha: T = T::from_f64(DEFAULT_BAUMGARTE) => with_baumgarte_alpha,
        /// Baumgarte β (1/s), the weight β² of the position violation Φ. Default 5
        /// ([`DEFAULT_BAUMGARTE`]).
        baumgarte_beta: T = T::from_f64(DEFAULT_BAUMGARTE) => with_baumgarte_beta,
        /// Relative pivot tolerance τ of the factorization of S: a pivot d_k small against τ S_kk
        /// marks row k as dependent on the rows before it. Default 1e-8
        /// ([`DEFAULT_DYNAMICS_PIVOT_TOLERANCE`]).
        pivot_tolerance: T = T::from_f64(DEFAULT_DYNAMICS_PIVOT_TOLERANCE) => with_pivot_tolerance,
        /// What to do with a dependent constraint row — at a singular position (a parallelogram
        /// lying flat, a slider-crank whose rod is as long as its crank at θ = ±π/2) or a
        /// redundant constraint (a parallelogram's third crank). `true` (default): drop it
        /// smoothly — 1/d_k becomes w/d_k with w = 1/(1 + ρ⁸), ρ = τ S_kk/d_k, so its multiplier
        /// fades to 0 as the row becomes dependent (d_k → 0) and the other rows carry its load:
        /// the right motion where the constraints are consistent, with reactions that are one of
        /// many valid sets. `false`: fail with [`DynamicsError::DependentConstraint`] where
        /// d_k ≤ τ S_kk, and use the exact pivots everywhere else.
        allow_redundant: bool = true => with_allow_redundant,
        /// Coulomb friction only: the loads λ are found by fixed-point iteration, starting from
        /// the `lambda` passed in, until max |Δλ| ≤ `friction_tolerance` · max(1, |λ|∞)
        /// (dimensionless). Default 1e-10.
        friction_tolerance: T = T::from_f64(1e-10) => with_friction_tolerance,
        /// Coulomb friction only: iterations before [`DynamicsError::FrictionNotConverged`].
        /// Default 50.
        friction_iterations: u32 = 50 => with_friction_iterations,
    }
}

impl<T: Real> DynamicsOptions<T> {
    /// The defaults without Baumgarte stabilization (α = β = 0): for integrators that project
    /// instead.
    pub fn without_stabilization() -> Self {
        Self::new().with_baumgarte(T::ZERO, T::ZERO)
    }

    /// The defaults with Baumgarte α and β (1/s).
    pub fn baumgarte(alpha: T, beta: T) -> Self {
        Self::new().with_baumgarte(alpha, beta)
    }

    /// Sets both Baumgarte weights, α and β (1/s).
    #[must_use]
    pub fn with_baumgarte(self, alpha: T, beta: T) -> Self {
        self.with_baumgarte_alpha(alpha).with_baumgarte_beta(beta)
    }
}

/// A failed forward-dynamics solve or projection.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum DynamicsError {
    /// The constraint rows are dependent at this configuration: the pivot of `row` in the
    /// factorization of D M⁻¹ Dᵀ (or of D_d in coordinate partitioning) vanished — a singular
    /// position such as a toggle, a missing degree of freedom, or redundant constraints — and
    /// [`DynamicsOptions::allow_redundant`] is off (with it on, such a row is dropped).
    DependentConstraint {
        /// Time of the solve (s).
        t: f64,
        /// The row whose pivot vanished, from [`Mechanism::CONSTRAINT_NAMES`].
        row: &'static str,
    },
    /// The row of D of a constraint is zero at this configuration: it restrains no velocity, so
    /// its acceleration equation 0 = γ cannot be met or dropped (a distance constraint or driver
    /// of zero length, an angle measured about a point that lies on it). No option changes this:
    /// the constraint is degenerate there.
    DegenerateConstraint {
        /// Time of the solve (s).
        t: f64,
        /// The row, from [`Mechanism::CONSTRAINT_NAMES`].
        row: &'static str,
    },
    /// A body's mass or moment of inertia is not positive and finite: M is not invertible.
    NonPositiveMass {
        /// The body, from [`Mechanism::BODY_NAMES`].
        body: &'static str,
        /// The offending value (kg or kg·m²).
        value: f64,
    },
    /// The joint loads of Coulomb friction did not settle: friction so large that it changes
    /// the loads it depends on more than they change it (μ too large, or a wedging geometry).
    FrictionNotConverged {
        /// Time of the solve (s).
        t: f64,
        /// The last change of max |λ|.
        change: f64,
    },
    /// The solve met a NaN or an infinity (in q, v, t, a constraint's γ or the inertia terms).
    NonFinite {
        /// Time of the solve (s).
        t: f64,
        /// The constraint row, or the velocity, where it surfaced.
        row: &'static str,
    },
    /// A force element's generalized force is NaN or infinite at a finite state (a law that
    /// divides by a length that reached 0, the square root of a negative number, ...).
    NonFiniteForce {
        /// Time of the evaluation (s).
        t: f64,
        /// The first force element (in declaration order, gravity first) whose generalized
        /// force reaches that velocity, from [`Mechanism::FORCE_ELEMENTS`].
        element: &'static str,
        /// How many other elements reach it too (0: `element` is the one).
        others: u16,
        /// The velocity whose generalized force is not finite, from
        /// [`Mechanism::VELOCITY_NAMES`].
        velocity: &'static str,
    },
}

/// [`Dynamics::check_inertia`]'s check, called by the generated code: `values` holds, per body
/// in [`Mechanism::BODY_NAMES`]' order, `per_body` values — the mass and J (planar, 2), or the
/// mass and the rows of J′ (spatial, 10). Masses and planar J must be positive and finite; J′
/// positive definite (its leading principal minors positive), else its smallest principal
/// moment is reported.
#[doc(hidden)]
pub fn check_inertia<M: Mechanism, T: Real>(values: &[T], per_body: usize) -> Result<(), DynamicsError> {
    let positive = |x: T| x.is_finite() && x > T::ZERO;
    for (b, c) in values.chunks_exact(per_body.max(1)).enumerate() {
        let body = M::BODY_NAMES.get(b).copied().unwrap_or("?");
        let refuse = |value: T| Err(DynamicsError::NonPositiveMass { body, value: value.to_f64() });
        if !positive(c[0]) {
            return refuse(c[0]);
        }
        match c[1..] {
            [j] if !positive(j) => return refuse(j),
            [j11, j12, j13, j21, j22, j23, j31, j32, j33] => {
                let det = j11 * (j22 * j33 - j23 * j32) - j12 * (j21 * j33 - j23 * j31) + j13 * (j21 * j32 - j22 * j31);
                if ![j11, j11 * j22 - j12 * j21, det].into_iter().all(positive) {
                    return refuse(smallest_eigenvalue([[j11, j12, j13], [j21, j22, j23], [j31, j32, j33]]));
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// The smallest eigenvalue of the symmetric part of a 3 × 3 matrix (Smith 1961, by the
/// trigonometric solution of its characteristic cubic).
// `!(p > 0)` on purpose: a NaN entry returns the (NaN) mean.
#[allow(clippy::neg_cmp_op_on_partial_ord)]
fn smallest_eigenvalue<T: Real>(a: [[T; 3]; 3]) -> T {
    let half = T::from_f64(0.5);
    let s = |i: usize, j: usize| half * (a[i][j] + a[j][i]);
    let off = s(0, 1) * s(0, 1) + s(0, 2) * s(0, 2) + s(1, 2) * s(1, 2);
    let mean = (s(0, 0) + s(1, 1) + s(2, 2)) / T::from_f64(3.0);
    let spread = (0..3).fold(T::from_f64(2.0) * off, |sum, i| sum + (s(i, i) - mean) * (s(i, i) - mean));
    let p = (spread / T::from_f64(6.0)).sqrt();
    if !(p > T::ZERO) {
        return mean;
    }
    let b = |i: usize, j: usize| (s(i, j) - if i == j { mean } else { T::ZERO }) / p;
    let det = b(0, 0) * (b(1, 1) * b(2, 2) - b(1, 2) * b(1, 2)) - b(0, 1) * (b(0, 1) * b(2, 2) - b(1, 2) * b(0, 2))
        + b(0, 2) * (b(0, 1) * b(1, 2) - b(1, 1) * b(0, 2));
    let phi = (half * det).max(-T::ONE).min(T::ONE).acos() / T::from_f64(3.0);
    mean + T::from_f64(2.0) * p * (phi + T::from_f64(2.0 * core::f64::consts::PI / 3.0)).cos()
}

impl DynamicsError {
    /// The error for a failed pivot of `row` — called by the generated code on its cold path:
    /// a non-positive mass or a non-finite input is reported as such, a zero row of D (`jv`, in
    /// [`Mechanism::JACOBIAN_PATTERN`]'s order) as a degenerate row, anything else as a dependent
    /// row — which `allow_redundant` would have dropped, so with it on (the pivot then fails only
    /// for a zero row or an overflow) as a non-finite pivot. `mass` is the diagonal of M, one
    /// entry per velocity, and `bodies` the body (an index into [`Mechanism::BODY_NAMES`]) whose
    /// mass or inertia each entry is.
    #[doc(hidden)]
    pub fn from_pivot<M: Mechanism, T: Real>(
        t: T,
        row: usize,
        mass: &[T],
        bodies: &[u16],
        jv: &[T],
        inputs_finite: bool,
        allow_redundant: bool,
    ) -> Self {
        for (&m, &b) in mass.iter().zip(bodies) {
            if !(m.is_finite() && m > T::ZERO) {
                let body = M::BODY_NAMES.get(b as usize).copied().unwrap_or("?");
                return DynamicsError::NonPositiveMass { body, value: m.to_f64() };
            }
        }
        let row_name = M::CONSTRAINT_NAMES.get(row).copied().unwrap_or("?");
        if !inputs_finite || !t.is_finite() {
            return DynamicsError::NonFinite { t: t.to_f64(), row: row_name };
        }
        let zero_row = jv.len() == M::JACOBIAN_PATTERN.len()
            && M::JACOBIAN_PATTERN.iter().zip(jv).all(|(&(r, _), &x)| r as usize != row || x == T::ZERO);
        Self::at_pivot(t.to_f64(), row_name, zero_row, allow_redundant)
    }

    /// A failed pivot of a row with finite inputs: degenerate (`zero_row`: its row of D is zero),
    /// dependent (`allow_redundant` off), or else an overflow of the pivot.
    pub(crate) fn at_pivot(t: f64, row: &'static str, zero_row: bool, allow_redundant: bool) -> Self {
        if zero_row {
            DynamicsError::DegenerateConstraint { t, row }
        } else if allow_redundant {
            DynamicsError::NonFinite { t, row }
        } else {
            DynamicsError::DependentConstraint { t, row }
        }
    }

    /// Time of the failed solve (s), when it has one.
    pub fn time(&self) -> Option<f64> {
        match *self {
            DynamicsError::DependentConstraint { t, .. }
            | DynamicsError::DegenerateConstraint { t, .. }
            | DynamicsError::NonFinite { t, .. }
            | DynamicsError::NonFiniteForce { t, .. }
            | DynamicsError::FrictionNotConverged { t, .. } => Some(t),
            DynamicsError::NonPositiveMass { .. } => None,
        }
    }
}

impl fmt::Display for DynamicsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DynamicsError::DependentConstraint { t, row } => write!(
                f,
                "at t = {t} s the constraint row `{row}` depends on the rows before it \
                 (singular position, missing degree of freedom or redundant constraint: \
                 KinematicSolver::redundancy reports which; DynamicsOptions::allow_redundant, \
                 off in this solve, drops such a row)"
            ),
            DynamicsError::DegenerateConstraint { t, row } => write!(
                f,
                "at t = {t} s the constraint row `{row}` has a zero Jacobian row: it restrains no velocity here \
                 (a distance of zero length, an angle about a point on it), so it can be neither solved nor \
                 dropped as redundant; state the constraint so that it has a direction at this position"
            ),
            DynamicsError::NonPositiveMass { body, value } => {
                write!(f, "body `{body}` has a mass or moment of inertia of {value}: it must be positive")
            }
            DynamicsError::FrictionNotConverged { t, change } => {
                write!(f, "at t = {t} s the Coulomb friction loads did not settle (last change of λ: {change})")
            }
            DynamicsError::NonFinite { t, row } => write!(f, "at t = {t} s a NaN or infinity reached the solve at row `{row}`"),
            DynamicsError::NonFiniteForce { t, element, others, velocity } => {
                if *others == 0 {
                    write!(f, "at t = {t} s the force element `{element}` gives a NaN or infinite generalized force on `{velocity}`")?;
                } else {
                    write!(
                        f,
                        "at t = {t} s the generalized force on `{velocity}` is NaN or infinite: from the force element `{element}` "
                    )?;
                    match others {
                        1 => write!(f, "or the other element acting on it")?,
                        n => write!(f, "or one of the {n} other elements acting on it")?,
                    }
                }
                write!(f, " (a law undefined at this state, or with a fixed step a state blown up by a step too large for the stiffness)")
            }
        }
    }
}

impl core::error::Error for DynamicsError {}

/// Why a solve at a state (t, q, v) gave a NaN or infinite v̇ or λ — the cold path of the
/// finiteness checks: a non-finite t, q or v, then the first velocity whose generalized force
/// (Coulomb friction's included, at `lambda`) is not finite, named by the force elements that
/// reach it, then the first constraint row whose ν or γ is not finite; else the first row
/// whose λ is not finite.
#[cold]
pub fn non_finite<T, M, const NQ: usize, const NV: usize, const NC: usize>(
    mechanism: &M,
    q: &[T; NQ],
    v: &[T; NV],
    t: T,
    lambda: &[T; NC],
) -> DynamicsError
where
    T: Real,
    M: Dynamics<T, NQ, NV, NC>,
{
    let row =
        |names: &'static [&'static str], i: usize| DynamicsError::NonFinite { t: t.to_f64(), row: names.get(i).copied().unwrap_or("?") };
    if !t.is_finite() {
        return row(M::CONSTRAINT_NAMES, 0);
    }
    if let Some(i) = q.iter().position(|x| !x.is_finite()) {
        return row(M::COORDINATE_NAMES, i);
    }
    if let Some(i) = v.iter().position(|x| !x.is_finite()) {
        return row(M::VELOCITY_NAMES, i);
    }
    let mut h = [T::ZERO; NV];
    mechanism.forces(q, v, t, &mut h);
    let finite_lambda = lambda.map(|l| if l.is_finite() { l } else { T::ZERO });
    mechanism.friction_forces(q, v, t, &finite_lambda, &mut h);
    if let Some(i) = h.iter().position(|x| !x.is_finite()) {
        return match force_element::<M>(i) {
            Some((element, others)) => {
                DynamicsError::NonFiniteForce { t: t.to_f64(), element, others, velocity: M::VELOCITY_NAMES.get(i).copied().unwrap_or("?") }
            }
            // No element reaches it: the inertia terms (a spatial body's gyroscopic moment).
            None => row(M::VELOCITY_NAMES, i),
        };
    }
    let (mut nu, mut gamma) = ([T::ZERO; NC], [T::ZERO; NC]);
    mechanism.velocity_rhs(q, t, &mut nu);
    mechanism.gamma(q, v, t, &mut gamma);
    if let Some(r) = nu.iter().zip(gamma.iter()).position(|(n, g)| !(n.is_finite() && g.is_finite())) {
        return row(M::CONSTRAINT_NAMES, r);
    }
    row(M::CONSTRAINT_NAMES, lambda.iter().position(|x| !x.is_finite()).unwrap_or(0))
}

/// The first force element (declaration order, gravity first) whose generalized force reaches
/// velocity `i`, and how many others reach it too; `None` if none does.
pub(crate) fn force_element<M: Mechanism>(i: usize) -> Option<(&'static str, u16)> {
    let mut acting = M::FORCE_ELEMENTS.iter().filter(|e| e.velocities.contains(&(i as u16)));
    acting.next().map(|first| (first.name, acting.count() as u16))
}

/// Forward dynamics of a mechanism, generated by `mechanism!` as straight-line code that
/// exploits the block-diagonal mass matrix and the compile-time sparsity of S = D M⁻¹ Dᵀ.
pub trait ForwardDynamics<T: Real, const NQ: usize, const NV: usize, const NC: usize>: Dynamics<T, NQ, NV, NC> {
    /// v̇ and λ of the equations of motion with Baumgarte stabilization (module docs); λ in N
    /// or N·m per constraint row, with the sign convention M v̇ − Dᵀ λ = h. With Coulomb
    /// friction the `lambda` passed in is the first guess of the joint loads (the previous
    /// step's λ converges fastest).
    ///
    /// # Errors
    /// [`DynamicsError`] naming the dependent row or the body with a non-positive mass.
    fn accelerations(
        &self,
        q: &[T; NQ],
        v: &[T; NV],
        t: T,
        options: &DynamicsOptions<T>,
        vd: &mut [T; NV],
        lambda: &mut [T; NC],
    ) -> Result<(), DynamicsError>;

    /// One Newton step of the mass-weighted projection of q onto Φ(q, t) = 0:
    /// q ← q ⊕ (−M⁻¹ Dᵀ S⁻¹ Φ) (as [`Kinematics::integrate_positions`](crate::Kinematics::integrate_positions)
    /// with h = 1). Returns ‖Φ‖∞ before the step.
    ///
    /// # Errors
    /// As [`ForwardDynamics::accelerations`].
    fn project_positions_step(&self, q: &mut [T; NQ], t: T, options: &DynamicsOptions<T>) -> Result<T, DynamicsError>;

    /// Mass-weighted projection of v onto D v = ν (exact, one step):
    /// v ← v − M⁻¹ Dᵀ S⁻¹ (D v − ν). Returns ‖D v − ν‖∞ before the projection.
    ///
    /// # Errors
    /// As [`ForwardDynamics::accelerations`].
    fn project_velocities(&self, q: &[T; NQ], v: &mut [T; NV], t: T, options: &DynamicsOptions<T>) -> Result<T, DynamicsError>;

    /// [`accelerations`](Self::accelerations) with the dense arrays a mechanism whose M depends
    /// on q needs where it has constraint rows (joint coordinates with closed loops,
    /// [`crate::dense_forward`]) in `scratch` — a work space's ([`Workspace::dense`](crate::WorkArrays::dense)),
    /// on the heap — instead of on the stack. The solvers and integrators call this one; the
    /// generated sparse solve of body coordinates needs no scratch (this provided method).
    ///
    /// # Errors
    /// As [`ForwardDynamics::accelerations`].
    #[allow(clippy::too_many_arguments)]
    fn accelerations_in(
        &self,
        scratch: DenseScratch<'_, T, NV, NC>,
        q: &[T; NQ],
        v: &[T; NV],
        t: T,
        options: &DynamicsOptions<T>,
        vd: &mut [T; NV],
        lambda: &mut [T; NC],
    ) -> Result<(), DynamicsError> {
        let _ = scratch;
        self.accelerations(q, v, t, options, vd, lambda)
    }

    /// [`project_positions_step`](Self::project_positions_step) with its dense arrays in
    /// `scratch`, as [`accelerations_in`](Self::accelerations_in).
    ///
    /// # Errors
    /// As [`ForwardDynamics::accelerations`].
    fn project_positions_step_in(
        &self,
        scratch: DenseScratch<'_, T, NV, NC>,
        q: &mut [T; NQ],
        t: T,
        options: &DynamicsOptions<T>,
    ) -> Result<T, DynamicsError> {
        let _ = scratch;
        self.project_positions_step(q, t, options)
    }

    /// [`project_velocities`](Self::project_velocities) with its dense arrays in `scratch`, as
    /// [`accelerations_in`](Self::accelerations_in).
    ///
    /// # Errors
    /// As [`ForwardDynamics::accelerations`].
    fn project_velocities_in(
        &self,
        scratch: DenseScratch<'_, T, NV, NC>,
        q: &[T; NQ],
        v: &mut [T; NV],
        t: T,
        options: &DynamicsOptions<T>,
    ) -> Result<T, DynamicsError> {
        let _ = scratch;
        self.project_velocities(q, v, t, options)
    }
}

/// Kinetic energy ½ vᵀ M(q) v (J).
pub fn kinetic_energy<T, M, const NQ: usize, const NV: usize, const NC: usize>(mechanism: &M, q: &[T; NQ], v: &[T; NV]) -> T
where
    T: Real,
    M: Dynamics<T, NQ, NV, NC>,
{
    kinetic_energy_in(mechanism, q, v, &mut [T::ZERO; NV])
}

/// [`kinetic_energy`] with the momentum M v written into `momentum`.
pub(crate) fn kinetic_energy_in<T, M, const NQ: usize, const NV: usize, const NC: usize>(
    mechanism: &M,
    q: &[T; NQ],
    v: &[T; NV],
    momentum: &mut [T; NV],
) -> T
where
    T: Real,
    M: Dynamics<T, NQ, NV, NC>,
{
    mechanism.mass_times(q, v, momentum);
    let twice = momentum.iter().zip(v.iter()).fold(T::ZERO, |sum, (&p, &vi)| sum + p * vi);
    twice * T::from_f64(0.5)
}
