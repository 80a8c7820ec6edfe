//! The Newton iteration of the implicit methods on the index-3 equations M v̇ − Dᵀλ = h,
//! Φ = 0 (generalized-α, BDF): each method maps the unknown v̇₊ to its step's end state q₊, v₊
//! ([`StateMap`]) with slopes ∂v₊/∂v̇₊ = c_v and ∂q₊/∂v̇₊ = c_q (in velocity space), and [`solve`]
//! iterates on (v̇₊, λ₊) with the iteration matrix [[M − c_v ∂h/∂v − c_q ((∂h/∂q)B +
//! ∂(Dᵀλ)/∂q·B), −Dᵀ], [D, 0]] (the constraint rows scaled by 1/c_q), built and factored over the
//! sparse pattern `mechanism!` planned ([`NewtonMatrix`]). h includes Coulomb friction at the
//! iterate's λ, its derivatives in q and v enter the matrix with the others
//! ([`Dynamics::friction_derivatives`](crate::Dynamics::friction_derivatives)), and its slope in
//! the loads beside −Dᵀ in the λ columns, −Dᵀ − ∂f/∂λ
//! ([`Dynamics::friction_multiplier_derivatives`](crate::Dynamics::friction_multiplier_derivatives)):
//! without it a bridge whose anchor pins rub converged too slowly for Radau5's simplified
//! Newton (issue 39). Where a full Newton step makes the residual ‖r‖₂ grow — a
//! saturating law such as regularized friction near sticking makes Newton overshoot and cycle —
//! the step is halved, up to six times.

use super::{check_step, Point, SimulationError, System};
use crate::linalg::LinalgError;
use crate::model::dynamics::DynamicsError;
use crate::model::mechanism::{Mechanism, NewtonMatrix};
use crate::model::workspace::{DenseScratch, WorkArrays};
use crate::real::Real;
use crate::solvers::kinematics::name;

/// How an implicit method's step end depends on the unknown v̇₊.
pub(super) trait StateMap<T: Real, M, const NQ: usize, const NV: usize, const NC: usize> {
    /// (c_v, c_q): ∂v₊/∂v̇₊ and ∂q₊/∂v̇₊ (in velocity space, through B(q)).
    fn slopes(&self) -> (T, T);
    /// q₊ and v₊ for v̇₊ = `vd` (`work`: a vector to work in).
    fn state(&self, mechanism: &M, vd: &[T; NV], q: &mut [T; NQ], v: &mut [T; NV], work: &mut [T; NV]);
    /// Where q₊ = q ⊕ Δ on the rotation group ([`crate::model::group`]), Δ for v̇₊ = `vd` into
    /// `out`, and `true`: its tangent operator enters the iteration matrix
    /// ([`NewtonMatrix::newton_matrix`]). `false` (the default): q₊ moves with v̇₊ through B(q₊)
    /// alone.
    fn displacement(&self, vd: &[T; NV], out: &mut [T; NV]) -> bool {
        let _ = (vd, out);
        false
    }
    /// The size of the change of q₊ and v₊ a Newton correction `dvd` of v̇₊ makes, in the
    /// method's own error norm (1: its tolerance), for the rate test of [`solve`]; `None` (the
    /// default): a method without one converges by the absolute tests alone.
    fn error_norm(&self, dvd: &[T; NV]) -> Option<T> {
        let _ = dvd;
        None
    }
}

/// The rate test (DASSL's, Brenan, Campbell & Petzold 5.2.2): with the convergence rate ρ of
/// the iteration (the ratio of successive corrections, kept from step to step), the error left
/// after a correction of size δ in the method's error norm is about ρ/(1 − ρ) δ; where that is
/// below a third of the tolerance the iterate is accepted, even after one iteration.
const RATE_TEST: f64 = 0.33;

/// The Newton iteration's settings, from the method's options (their documentation there).
#[derive(Clone, Copy, Debug)]
pub(super) struct NewtonSettings<T> {
    pub tolerance: T,
    pub lambda_tolerance: T,
    pub max_iterations: u32,
    pub reuse_factors: bool,
    pub pivot_tolerance: T,
    pub project_velocities: bool,
    /// Take one mass-weighted position step onto Φ = 0 from the converged iterate before the
    /// velocity projection (BDF): Newton stops within its tolerance, or earlier by the rate
    /// test, and one step from there (quadratic) reaches rounding, as the simulation's
    /// projection would — which then has nothing left to do
    /// ([`Integrator::projected_end`](super::Integrator::projected_end)).
    pub end_position_step: bool,
}

/// One implicit step from `from` to t1: Newton on (v̇₊, λ₊) with the planned Newton matrix
/// [[M + c_v C + c_q K, −Dᵀ], [D, 0]] (the constraint rows scaled by 1/c_q), q₊ and v₊ given by
/// `map`, then the velocity projection (and with `end_position_step`, a position step before it,
/// whose starting ‖Φ‖∞ it returns). Writes q₊, v₊, v̇₊ and λ₊ to `to`; counts the Newton
/// iterations in `iterations`. `vd0` is the first guess of v̇₊ (λ₊ starts from `from`'s).
/// Where `map` has an error norm, `rate` carries the convergence rate from step to step and
/// the iterate is also accepted by the rate test ([`RATE_TEST`]).
// `!(x > y)` on purpose: it is also true when either side is NaN.
#[allow(clippy::neg_cmp_op_on_partial_ord, clippy::too_many_arguments)]
pub(super) fn solve<T, M, S, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
    system: &System<'_, M, T>,
    o: &NewtonSettings<T>,
    resolution: T,
    map: &S,
    vd0: &[T; NV],
    from: &Point<T, NQ, NV, NC>,
    t1: T,
    to: &mut Point<T, NQ, NV, NC>,
    iterations: &mut u32,
    rate: &mut Option<T>,
    s: &mut M::NewtonStorage,
    mut scratch: DenseScratch<'_, T, NV, NC>,
) -> Result<Option<T>, SimulationError>
where
    T: Real,
    M: NewtonMatrix<T, NQ, NV, NC>,
    S: StateMap<T, M, NQ, NV, NC>,
{
    let mech = system.mechanism;
    let one = T::ONE;
    let half = T::from_f64(0.5);
    let (c_v, c_q) = map.slopes();
    // Unknowns: v̇₊ (from the first guess) and λ₊ (from λ); the iterate's state, Φ, forces and
    // residual (the work space's vectors). `s`: D's non-zeros, then the Newton matrix and its
    // LU factors over the pattern planned at compile time (`NewtonMatrix`, `crate::sparse`):
    // O(non-zeros), no dense matrix, in the work space.
    // Each is written whole before it is read (the state by `map`, Φ, h and M v̇ by the
    // mechanism, the rest copied), but the last correction, which an error may name at once.
    let vectors = &mut scratch.vectors;
    let [vd, v, force, inertia, base_vd, work] = vectors.rows_written::<NV, 6>();
    let [lambda, phi, base_lambda] = vectors.rows_written::<NC, 3>();
    let [rhs] = vectors.rows_written::<N, 1>();
    let [q] = vectors.rows_written::<NQ, 1>();
    let step = vectors.take::<N>();
    *vd = *vd0;
    *lambda = from.lambda;
    let mut iteration = 0;
    let mut dropped = [false; NC];
    let mut last_change = [T::ZERO; 2];
    // Whether the iteration matrix has been factored, the rounding floor of the force change
    // and whether a kept multiplier's pivot is near singular, from the last factorization;
    // and whether the next iteration must factor again (modified Newton, `reuse_factors`).
    let mut factored = false;
    let (mut rounding_floor, mut near_singular, mut refactor) = (T::ZERO, false, true);
    // Backtracking on ‖r‖₂: the last Newton step's start (`base_vd`, `base_lambda`), direction
    // (`step`), fraction θ taken, the residual it started from and the size of the full
    // correction.
    *base_vd = *vd;
    *base_lambda = *lambda;
    let mut theta = one;
    let mut norm_before = T::ZERO;
    let mut correction = T::ZERO;
    let mut last_size: Option<T> = None;
    loop {
        map.state(mech, vd, q, v, work);
        // Φ and D, with the Newton matrix when this iteration factors it (modified Newton:
        // `reuse_factors` keeps the last factors while the corrections shrink fast enough).
        let factor = refactor || !o.reuse_factors || !factored;
        if factor {
            let displacement = map.displacement(vd, work).then_some(&*work);
            mech.newton_matrix(q, v, vd, t1, lambda, displacement, c_v, c_q, phi, s, scratch.reborrow());
        } else {
            mech.newton_jacobian(q, t1, phi, s, scratch.reborrow());
        }
        mech.forces(q, v, t1, force);
        // Coulomb friction with the iterate's loads (its exact derivatives, in q, v and λ,
        // are in the iteration matrix).
        mech.friction_forces(q, v, t1, lambda, force);
        mech.mass_times(q, vd, inertia);
        let worst = residual::<T, M, NQ, NV, NC, N>(s, force, inertia, lambda, phi, c_q, rhs);
        // A NaN or infinity in a force: name the force element; in Φ or the state: the row
        // it surfaced in.
        if let Some(i) = rhs.iter().position(|x| !x.is_finite()) {
            return Err(non_finite_residual(mech, (q, v, t1, lambda), from.t, i));
        }
        // A saturating force (regularized Coulomb friction, v/√(v² + v_s²)) makes full
        // Newton steps overshoot and cycle; where the step made the residual grow, take half
        // of it instead (at most six times, then go on from there).
        let norm = rhs.iter().fold(T::ZERO, |s, &r| s + r * r);
        if iteration > 0 && correction > o.tolerance && !(norm <= norm_before) && theta > T::from_f64(1.0 / 64.0) {
            theta *= half;
            for i in 0..NV {
                vd[i] = base_vd[i] + theta * step[i];
            }
            for r in 0..NC {
                lambda[r] = base_lambda[r] + theta * step[NV + r];
            }
            continue;
        }
        if iteration >= o.max_iterations {
            return Err(not_converged::<T, M, NV, NC, N>(t1, iteration, worst, step, c_q, o.tolerance));
        }
        if factor {
            (rounding_floor, near_singular) =
                factor_newton::<T, M, NQ, NV, NC>(s, o, system.dynamics.allow_redundant, resolution / (c_q), t1, &mut dropped)?;
            factored = true;
        }
        for r in 0..NC {
            if dropped[r] {
                rhs[NV + r] = T::ZERO;
            }
        }
        M::newton_solve(s, rhs);
        if let Some(i) = rhs.iter().position(|x| !x.is_finite()) {
            return Err(SimulationError::NonFinite { t: from.t.to_f64(), coordinate: row_name::<M>(i, NV) });
        }
        *base_vd = *vd;
        *base_lambda = *lambda;
        *step = *rhs;
        (theta, norm_before) = (one, norm);
        let mut force_scale;
        (correction, force_scale) = apply_correction(vd, lambda, rhs, [force, inertia], c_q);
        // The change of the constraint forces Dᵀλ (N, N·m per velocity), not of λ itself:
        // near a singular position the part of λ along D's (near-)null space is not
        // determined — rounding moves it by ε/σ² — and exerts no force. `force` is free
        // until the next iteration: it takes Dᵀλ.
        let lambda_change = constraint_force_change::<T, M, NQ, NV, NC, N>(s, rhs, lambda, inertia, force);
        // Modified Newton: keep the factors while each correction shrinks at least 4×.
        refactor = iteration > 0 && !(correction < T::from_f64(0.25) * last_change[0]);
        force_scale = force.iter().fold(force_scale, |m, f| m.max(f.abs()));
        iteration += 1;
        *iterations = iteration;
        let changes = [correction, lambda_change];
        let size = map.error_norm(rhs[..NV].try_into().expect("NV rows")).filter(|_| theta == one && !near_singular);
        let rate_met = rate_test(size, &mut last_size, rate);
        if worst.0 <= o.tolerance
            && converged(o, changes, last_change, (o.lambda_tolerance * force_scale).max(rounding_floor), near_singular, iteration > 1)
            || rate_met
        {
            break;
        }
        last_change = changes;
    }
    // The state of the converged iterate (its last correction below tolerance, or passing the
    // rate test).
    map.state(mech, vd, q, v, work);
    let end_residual =
        if o.end_position_step { Some(mech.project_positions_step_in(scratch.reborrow(), q, t1, &system.dynamics)?) } else { None };
    if o.project_velocities {
        mech.project_velocities_in(scratch, q, v, t1, &system.dynamics)?;
    }
    to.t = t1;
    to.q = *q;
    to.v = *v;
    to.vd = *vd;
    to.lambda = *lambda;
    check_step::<T, M, NQ, NV, NC>(from, to)?;
    Ok(end_residual)
}

/// Adds the Newton correction `rhs` (Δv̇, then Δλ) to the iterate; returns the size of the
/// position change it makes, ‖c_q Δv̇‖∞ (m, rad), and the force scale of the iterate's applied
/// and inertia forces, max ‖·‖∞ (N, N·m).
fn apply_correction<T: Real, const NV: usize, const NC: usize, const N: usize>(
    vd: &mut [T; NV],
    lambda: &mut [T; NC],
    rhs: &[T; N],
    forces: [&[T; NV]; 2],
    c_q: T,
) -> (T, T) {
    let (mut correction, mut force_scale) = (T::ZERO, T::ZERO);
    for i in 0..NV {
        vd[i] += rhs[i];
        correction = correction.max((rhs[i] * c_q).abs());
        force_scale = force_scale.max(forces[0][i].abs()).max(forces[1][i].abs());
    }
    for r in 0..NC {
        lambda[r] += rhs[NV + r];
    }
    (correction, force_scale)
}

/// The rate test ([`RATE_TEST`]) on a correction of `size` in the method's error norm (`None`:
/// no norm, or a step not to be judged so): the rate is measured on this step's corrections
/// when there are two (`last_size` holds the one before), else the last step's is used.
fn rate_test<T: Real>(size: Option<T>, last_size: &mut Option<T>, rate: &mut Option<T>) -> bool {
    if let (Some(size), Some(before)) = (size, last_size.filter(|&b| b > T::ZERO)) {
        *rate = Some(size / before);
    }
    *last_size = size;
    match (size, rate.filter(|&r| r < T::from_f64(0.9))) {
        (Some(size), Some(r)) => r / (T::ONE - r) * size <= T::from_f64(RATE_TEST),
        _ => false,
    }
}

/// A NaN or infinity in row `row` of a Newton residual at the state (q, v, t, λ), in the step
/// from `t0`: the force element that gave it, or the row (BDF, generalized-α and Radau5's stages).
pub(super) fn non_finite_residual<T, M, const NQ: usize, const NV: usize, const NC: usize>(
    mech: &M,
    (q, v, t, lambda): (&[T; NQ], &[T; NV], T, &[T; NC]),
    t0: T,
    row: usize,
) -> SimulationError
where
    T: Real,
    M: NewtonMatrix<T, NQ, NV, NC>,
{
    match crate::model::dynamics::non_finite(mech, q, v, t, lambda) {
        force @ DynamicsError::NonFiniteForce { .. } => SimulationError::Dynamics(force),
        _ => SimulationError::NonFinite { t: t0.to_f64(), coordinate: row_name::<M>(row, NV) },
    }
}

/// Factors the Newton matrix in `s`; returns the rounding floor of the force change and
/// whether a kept multiplier's pivot is near singular (below 1e-3 of its column).
///
/// The floor is the force change one rounding of the positions makes: q₊ carries v̇₊ times
/// c_q (β'h² for generalized-α), so a position resolved to `resolution` leaves M v̇₊ — and Dᵀλ with it — uncertain by
/// about m · resolution/c_q (`per_mass`; 1e-7 N per kg in f64 at h = 1 ms, but 1e-3 N at
/// 1e-5 s, and 25 N per kg in f32 at 1 ms). No iteration gets below it. A multiplier without a
/// pivot belongs to a row that depends on the others (a singular position, a redundant
/// constraint): with `allow_redundant` its row and column are replaced by Δλ_r = 0 for the
/// rest of the step and the others carry the load, as forward dynamics drops such a row.
fn factor_newton<T, M, const NQ: usize, const NV: usize, const NC: usize>(
    s: &mut M::NewtonStorage,
    o: &NewtonSettings<T>,
    allow_redundant: bool,
    per_mass: T,
    t1: T,
    dropped: &mut [bool; NC],
) -> Result<(T, bool), SimulationError>
where
    T: Real,
    M: NewtonMatrix<T, NQ, NV, NC>,
{
    let pattern = M::NEWTON_PATTERN;
    let lu = &s.as_ref()[M::JACOBIAN_PATTERN.len()..];
    let mass_scale = (0..NV).fold(T::ZERO, |m, i| m.max(lu[pattern.diagonal[pattern.position[i] as usize] as usize].abs()));
    let smallest_ratio =
        M::newton_factor(s, o.pivot_tolerance, allow_redundant, dropped).map_err(|e| factorization_error::<M, T>(e, t1, NV))?;
    Ok((mass_scale * per_mass, smallest_ratio < T::from_f64(1e-3)))
}

/// Whether the position correction and the force change (`now`, against the last iteration's
/// `before`) are below tolerance, Φ being met. A correction or force change that stopped
/// shrinking (not smaller than the last iteration's) counts as met too near a singular position
/// (a multiplier's pivot below 1e-3 of its column: `near_singular`), and a force change within
/// 100× its tolerance anywhere: it is the rounding of an ill-conditioned solve — ε/σ in λ and
/// v̇, and Φ's rounding amplified by the 1/c_q of the constraint rows at small steps — which
/// no further iteration removes. Beyond that band the test stays strict: Coulomb friction's
/// loads converge linearly and not always monotonically. `repeated`: a last iteration exists.
// `!(x < y)` on purpose: it is also true when either side is NaN.
#[allow(clippy::neg_cmp_op_on_partial_ord)]
fn converged<T: Real>(o: &NewtonSettings<T>, now: [T; 2], before: [T; 2], force_tolerance: T, near_singular: bool, repeated: bool) -> bool {
    let stalled = |now: T, before: T, band: bool| (near_singular || band) && repeated && !(now < before);
    let correction_met = now[0] <= o.tolerance || stalled(now[0], before[0], false);
    let force_met = now[1] <= force_tolerance || stalled(now[1], before[1], now[1] <= T::from_f64(100.0) * force_tolerance);
    correction_met && force_met
}

/// The Newton residuals into `rhs`: r = h − M v̇ + Dᵀλ in the momentum rows (D's non-zeros at
/// the front of `s`), −Φ/c_q in the constraint rows; returns the largest |Φ| and its row.
#[allow(clippy::too_many_arguments)]
fn residual<T, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
    s: &M::NewtonStorage,
    force: &[T; NV],
    inertia: &[T; NV],
    lambda: &[T; NC],
    phi: &[T; NC],
    c_q: T,
    rhs: &mut [T; N],
) -> (T, usize)
where
    T: Real,
    M: NewtonMatrix<T, NQ, NV, NC>,
{
    let mut worst = (T::ZERO, 0usize);
    for i in 0..NV {
        rhs[i] = force[i] - inertia[i];
    }
    for (&value, &(r, c)) in s.as_ref().iter().zip(M::JACOBIAN_PATTERN) {
        rhs[c as usize] += value * lambda[r as usize];
    }
    for (r, &p) in phi.iter().enumerate() {
        rhs[NV + r] = -p / c_q;
        if p.abs() > worst.0 {
            worst = (p.abs(), r);
        }
    }
    worst
}

/// The change of the constraint forces Dᵀλ by a Newton correction (its multipliers' part of
/// `rhs`), largest over the velocities; the change into `change` and the forces Dᵀλ themselves
/// into `total`.
fn constraint_force_change<T, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
    s: &M::NewtonStorage,
    rhs: &[T; N],
    lambda: &[T; NC],
    change: &mut [T; NV],
    total: &mut [T; NV],
) -> T
where
    T: Real,
    M: NewtonMatrix<T, NQ, NV, NC>,
{
    change.fill(T::ZERO);
    total.fill(T::ZERO);
    for (&value, &(r, c)) in s.as_ref().iter().zip(M::JACOBIAN_PATTERN) {
        let (r, c) = (r as usize, c as usize);
        change[c] += value * rhs[NV + r];
        total[c] += value * lambda[r];
    }
    change.iter().fold(T::ZERO, |m, c| m.max(c.abs()))
}

/// Newton did not converge: name the violated constraint, or, with every constraint met, the
/// velocity or multiplier whose correction would not settle (`step`: the last correction).
fn not_converged<T: Real, M: Mechanism, const NV: usize, const NC: usize, const N: usize>(
    t1: T,
    iterations: u32,
    worst: (T, usize),
    step: &[T; N],
    c_q: T,
    tolerance: T,
) -> SimulationError {
    let k = (0..NV).fold(0, |k, i| if step[i].abs() > step[k].abs() { i } else { k });
    let (worst_row, residual) = if worst.0 > tolerance {
        (name(M::CONSTRAINT_NAMES, worst.1), worst.0)
    } else if (step[k] * c_q).abs() > tolerance || NC == 0 {
        (name(M::VELOCITY_NAMES, k), (step[k] * c_q).abs())
    } else {
        let r = (0..NC).fold(0, |r, j| if step[NV + j].abs() > step[NV + r].abs() { j } else { r });
        (name(M::CONSTRAINT_NAMES, r), step[NV + r].abs())
    };
    SimulationError::NotConverged {
        t: t1.to_f64(),
        newton: super::NewtonIteration::Step,
        iterations,
        worst_row,
        residual: residual.to_f64(),
    }
}

/// Name of row `i` of the iteration matrix: a velocity (the momentum rows) or a constraint.
pub(super) fn row_name<M: Mechanism>(i: usize, nv: usize) -> &'static str {
    if i < nv {
        name(M::VELOCITY_NAMES, i)
    } else {
        name(M::CONSTRAINT_NAMES, i - nv)
    }
}

/// What a failed factorization of the iteration matrix means: no pivot in a multiplier's
/// column is a constraint row that depends on the others (a singular position or redundant
/// constraints); no pivot in a velocity's column is a direction with neither mass nor
/// stiffness; a NaN or infinity is named by its row.
pub(super) fn factorization_error<M: Mechanism, T: Real>(error: LinalgError, t: T, nv: usize) -> SimulationError {
    match error {
        LinalgError::Singular { column, .. } if column >= nv => {
            SimulationError::Dynamics(DynamicsError::DependentConstraint { t: t.to_f64(), row: name(M::CONSTRAINT_NAMES, column - nv) })
        }
        LinalgError::Singular { column, .. } => {
            SimulationError::SingularIterationMatrix { t: t.to_f64(), velocity: name(M::VELOCITY_NAMES, column) }
        }
        LinalgError::NonFinite { row, .. } => SimulationError::NonFinite { t: t.to_f64(), coordinate: row_name::<M>(row, nv) },
        // Not returned by the sparse factorization.
        LinalgError::NotSquare { rows, columns } | LinalgError::Overdetermined { rows, columns } => {
            SimulationError::WorkspaceSize { expected: rows, found: columns }
        }
    }
}

/// The work space's three Newton slots, as the mechanism's storage, and its dense arrays: what
/// an implicit method steps with, refused where the work space is not the mechanism's
/// (`Name::workspace()`).
#[allow(clippy::type_complexity)]
pub(super) fn newton_space<T, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    ws: &mut WorkArrays<T, NV, NC, N, NS>,
) -> Result<([&mut M::NewtonStorage; 3], DenseScratch<'_, T, NV, NC>), SimulationError>
where
    T: Real,
    M: NewtonMatrix<T, NQ, NV, NC>,
{
    if N != NV + NC {
        return Err(SimulationError::WorkspaceSize { expected: NV + NC, found: N });
    }
    let (newton, dense) = ws.newton_and_dense();
    let Some(slots) = crate::model::workspace::newton_slots::<M::NewtonStorage, T, NS>(newton) else {
        return Err(SimulationError::NewtonSlotSize { expected: M::JACOBIAN_PATTERN.len() + M::NEWTON_PATTERN.entries(), found: NS });
    };
    Ok((slots, dense))
}

/// The first step of an adaptive implicit method: `initial` where it is positive, else DOPRI5's
/// choice from the initial rates in the mixed tolerance atol + rtol·|y|.
pub(super) fn first_step<T, M, const NQ: usize, const NV: usize, const NC: usize>(
    mech: &M,
    from: &Point<T, NQ, NV, NC>,
    initial: T,
    (rtol, atol): (T, T),
    max_step: T,
) -> T
where
    T: Real,
    M: NewtonMatrix<T, NQ, NV, NC>,
{
    if initial > T::ZERO {
        return initial;
    }
    let mut qdot = [T::ZERO; NQ];
    mech.position_rates(&from.q, &from.v, &mut qdot);
    let scale = |y0: T, y1: T| atol + rtol * y0.abs().max(y1.abs());
    super::dopri5::initial_step(from, &qdot, &scale, max_step)
}

/// The powers at the end point and the work integrals of a step of h.
pub(super) fn finish<T, M, const NQ: usize, const NV: usize, const NC: usize>(
    system: &System<'_, M, T>,
    mut scratch: DenseScratch<'_, T, NV, NC>,
    from: &Point<T, NQ, NV, NC>,
    to: &mut Point<T, NQ, NV, NC>,
    h: T,
) -> Result<(), SimulationError>
where
    T: Real,
    M: NewtonMatrix<T, NQ, NV, NC>,
{
    to.power = if system.track_work {
        let (vd, lambda) = (scratch.vectors.take::<NV>(), scratch.vectors.take::<NC>());
        system.derivatives_in(scratch, to.t, &to.q, &to.v, vd, lambda)?
    } else {
        [T::ZERO; 2]
    };
    accumulate_work(from, to, h);
    Ok(())
}

/// The work integrals of a step of h from the powers at its ends.
pub(super) fn accumulate_work<T: Real, const NQ: usize, const NV: usize, const NC: usize>(
    from: &Point<T, NQ, NV, NC>,
    to: &mut Point<T, NQ, NV, NC>,
    h: T,
) {
    // Trapezoidal rule for the work: second order (generalized-α's order; BDF's and Radau
    // IIA's work is second order where their motion is of higher order).
    for k in 0..2 {
        to.work[k] = from.work[k] + T::from_f64(0.5) * h * (from.power[k] + to.power[k]);
    }
}

/// `ulps` units in the last place of the largest coordinate (m, rad; 1 for Euler parameters).
pub(super) fn position_ulps<T: Real, const NQ: usize>(q: &[T; NQ], ulps: f64) -> T {
    T::from_f64(ulps) * T::EPSILON * q.iter().fold(T::ONE, |m, x| m.max(x.abs()))
}
