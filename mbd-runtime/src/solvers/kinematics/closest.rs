//! Where Newton did not reach Φ(q, t) = 0: the closest configuration a descent finds, to tell a
//! loop that cannot close from a guess that was too far.
//!
//! Newton's step solves the linearized rows exactly and, where the rows cannot all hold, it
//! oscillates or wanders, and its last iterate's worst row may belong to a loop that closes
//! (a new user's impossible loop was reported by a row of another one). A descent on ½‖Φ‖²
//! instead only accepts steps that lower ‖Φ‖, so it ends at a configuration where no step does:
//! Φ = 0, or a local minimum whose violated rows are the loop that does not close. It takes
//! Levenberg–Marquardt's steps first (Newton's where the rows can all hold), then Newton's
//! method on ½‖Φ‖² itself, whose Hessian includes Φ's curvature, to reach a minimum with a
//! residual.

use crate::linalg::{self, LuWork};
use crate::model::mechanism::Kinematics;
use crate::model::workspace::{Indices, Vectors, WorkArrays, Workspace};
use crate::real::Real;
use crate::solvers::error::ConstraintRows;

/// Gauss–Newton steps tried (accepted or not); each is one evaluation of Φ and D and one dense
/// solve of D Dᵀ + μ I. Where the rows can all hold they converge as Newton does; at a minimum
/// with a residual they crawl (on a 1 m rod pinned 2 m apart: 2 % above the minimum after 60
/// steps, Gauss–Newton leaving out Φ's curvature), and Newton's method on ½‖Φ‖² takes over.
const MAX_STEPS: u32 = 30;

/// Newton steps on ½‖Φ‖² after the Gauss–Newton ones, each with its Hessian by differences of
/// the gradient DᵀΦ (NV evaluations of Φ and D): quadratic convergence to the minimum.
const MAX_NEWTON_STEPS: u32 = 20;

/// A step that lowers ½‖Φ‖² by less than this fraction of it ends the descent: a minimum.
const STALL: f64 = 1e-12;

/// A row is named as violated at the minimum where its |Φ| is at least this fraction of ‖Φ‖∞.
const VIOLATED: f64 = 1e-2;

/// Newton's method on ½‖Φ‖² differences its Hessian over every velocity, NV evaluations of Φ
/// and the dense D a step, O(NV² NC) work: above this many velocities it is left out, and the
/// residual reported is where Levenberg–Marquardt stopped (within a few per cent of the
/// minimum's where it crawls, as above).
const MAX_NEWTON_VELOCITIES: usize = 200;

/// What the descent reached: Φ = 0 (`rows` is `None`), or a minimum with ‖Φ‖∞ = `residual` and
/// the rows violated there, largest first.
pub(super) struct Closest {
    pub residual: f64,
    pub steps: u32,
    pub rows: Option<ConstraintRows>,
}

/// Levenberg–Marquardt from `q` (moved to the configuration reached): the step
/// Δv = −Dᵀ (D Dᵀ + μ I)⁻¹ Φ, the regularized minimum-norm Newton step (the same as
/// −(DᵀD + μ I)⁻¹ DᵀΦ, over the NC rows), accepted where it lowers ‖Φ‖², μ divided by 3 after
/// an accepted step and multiplied by 4 after a refused one. Uses `ws.jacobian` (D) and
/// `ws.constraint_square` (D Dᵀ + μ I and its LU).
pub(super) fn closest<T, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    m: &M,
    q: &mut [T; NQ],
    t: T,
    tolerance: T,
    ws: &mut Workspace<T, NV, NC, N, NS>,
) -> Closest
where
    T: Real,
    M: Kinematics<T, NQ, NV, NC>,
{
    let WorkArrays { jacobian: d, jacobian_scratch, constraint_square: a, velocity_square, vectors, indices, .. } = &mut **ws;
    let mut vectors = Vectors::new(vectors.flat());
    let [phi, trial_phi, x, lu_scale] = vectors.rows::<NC, 4>();
    let (step, trial) = (vectors.take::<NV>(), vectors.take::<NQ>());
    m.position_eval(q, t, phi, d);
    let mut cost = squared(phi);
    // μ starts at a thousandth of D Dᵀ's largest diagonal entry, and is never below ε of it.
    let scale = d.iter().map(|row| squared(row)).fold(T::ZERO, T::max).max(T::from_f64(f64::MIN_POSITIVE));
    let (mut mu, floor, ceiling) = (T::from_f64(1e-3) * scale, T::EPSILON * scale, T::from_f64(1e12) * scale);
    let mut steps: u32 = 0;
    while steps < MAX_STEPS && max_abs(phi) > tolerance && mu < ceiling && cost.is_finite() {
        steps += 1;
        for (i, row_i) in d.iter().enumerate() {
            for (j, row_j) in d.iter().enumerate() {
                a[i][j] = row_i.iter().zip(row_j).fold(T::ZERO, |s, (&p, &r)| s + p * r);
            }
            a[i][i] += mu;
        }
        // D Dᵀ + μ I is symmetric positive definite: its LU needs no pivot test.
        let work = LuWork { pivots: &mut indices.pivots_c, columns: &mut indices.columns_c, scale: &mut *lu_scale };
        if linalg::lu_factor(a, T::ZERO, work).is_err() {
            mu *= T::from_f64(4.0);
            continue;
        }
        x.copy_from_slice(phi);
        linalg::lu_solve_in_place(a, &indices.pivots_c, x);
        for (k, s) in step.iter_mut().enumerate() {
            *s = T::ZERO - d.iter().zip(x.iter()).fold(T::ZERO, |sum, (row, &xi)| sum + row[k] * xi);
        }
        trial.copy_from_slice(q);
        m.integrate_positions(trial, step, T::ONE);
        m.constraints(trial, t, trial_phi);
        let trial_cost = squared(trial_phi);
        if trial_cost.is_finite() && trial_cost < cost {
            let lowered = cost - trial_cost;
            q.copy_from_slice(trial);
            m.position_eval(q, t, phi, d);
            cost = squared(phi);
            mu = (mu / T::from_f64(3.0)).max(floor);
            if lowered <= T::from_f64(STALL) * (cost + lowered) {
                break;
            }
        } else {
            mu *= T::from_f64(4.0);
        }
    }
    if max_abs(phi) > tolerance && cost.is_finite() && NV <= MAX_NEWTON_VELOCITIES {
        steps += minimize(m, q, t, tolerance, [d, jacobian_scratch], (velocity_square, indices), vectors.reborrow());
        m.constraints(q, t, phi);
    }
    let residual = max_abs(phi);
    if residual <= tolerance {
        return Closest { residual: residual.to_f64(), steps, rows: None };
    }
    let rows = violated_rows(phi, T::from_f64(VIOLATED) * residual);
    Closest { residual: residual.to_f64(), steps, rows: Some(ConstraintRows::new(M::CONSTRAINT_NAMES, rows)) }
}

/// The rows with |Φ| ≥ `threshold`: the largest ones first (as many as [`ConstraintRows`] names,
/// by selection rather than a sorted copy of Φ, which would grow the stack with NC), then the
/// others.
fn violated_rows<T: Real, const NC: usize>(phi: &[T; NC], threshold: T) -> impl Iterator<Item = usize> + '_ {
    let violated = move |i: usize| phi[i].abs() >= threshold;
    let mut largest = [usize::MAX; ConstraintRows::CAPACITY];
    for k in 0..largest.len() {
        let next = (0..NC).filter(|&i| violated(i) && !largest[..k].contains(&i)).fold(None, |best: Option<usize>, i| match best {
            Some(b) if phi[b].abs() >= phi[i].abs() => Some(b),
            _ => Some(i),
        });
        largest[k] = next.unwrap_or(usize::MAX);
    }
    let named = largest.into_iter().take_while(|&i| i != usize::MAX);
    named.chain((0..NC).filter(move |&i| violated(i) && !largest.contains(&i)))
}

/// Newton's method on f = ½‖Φ‖² in velocity space from `q` (moved to where it ends): gradient
/// g = DᵀΦ, Hessian H by forward differences of g along each velocity (h = √ε max(1, ‖q‖∞),
/// symmetrized), the step −(H + μ I)⁻¹ g accepted where f falls, μ (from 0) raised after a
/// refusal. Ends at ‖Φ‖∞ ≤ `tolerance`, where a step lowers f by less than [`STALL`] of it, or
/// after [`MAX_NEWTON_STEPS`]. Returns the steps tried. Uses `ws.jacobian`,
/// `ws.jacobian_scratch`, and `ws.velocity_square` (H) with the index rows of its LU.
fn minimize<T, M, const NQ: usize, const NV: usize, const NC: usize>(
    m: &M,
    q: &mut [T; NQ],
    t: T,
    tolerance: T,
    [d, moved_d]: [&mut [[T; NV]; NC]; 2],
    (hessian, indices): (&mut [[T; NV]; NV], &mut Indices<NV, NC>),
    mut vectors: Vectors<'_, T>,
) -> u32
where
    T: Real,
    M: Kinematics<T, NQ, NV, NC>,
{
    let [phi, moved_phi] = vectors.rows::<NC, 2>();
    let [g, moved_g, step, unit, lu_scale] = vectors.rows::<NV, 5>();
    let [moved, trial] = vectors.rows::<NQ, 2>();
    m.position_eval(q, t, phi, d);
    gradient(d, phi, g);
    let mut cost = squared(phi);
    let mut mu = T::ZERO;
    let mut steps = 0;
    while steps < MAX_NEWTON_STEPS && max_abs(phi) > tolerance {
        steps += 1;
        let h = T::EPSILON.sqrt() * max_abs(q).max(T::ONE);
        for k in 0..NV {
            moved.copy_from_slice(q);
            unit.fill(T::ZERO);
            unit[k] = T::ONE;
            m.integrate_positions(moved, unit, h);
            m.position_eval(moved, t, moved_phi, moved_d);
            gradient(moved_d, moved_phi, moved_g);
            for (row, (&after, &before)) in hessian.iter_mut().zip(moved_g.iter().zip(g.iter())) {
                row[k] = (after - before) / h;
            }
        }
        let scale = (0..NV).fold(T::ZERO, |s, k| s.max(hessian[k][k].abs())).max(T::from_f64(f64::MIN_POSITIVE));
        symmetrize(hessian);
        for (i, row) in hessian.iter_mut().enumerate() {
            row[i] += mu;
        }
        let work = LuWork { pivots: &mut indices.pivots_v, columns: &mut indices.columns_v, scale: &mut *lu_scale };
        let solved = linalg::lu_factor(hessian, T::ZERO, work).is_ok_and(|()| {
            for (s, &gk) in step.iter_mut().zip(g.iter()) {
                *s = T::ZERO - gk;
            }
            linalg::lu_solve_in_place(hessian, &indices.pivots_v, step);
            step.iter().all(|x| x.is_finite())
        });
        trial.copy_from_slice(q);
        if solved {
            m.integrate_positions(trial, step, T::ONE);
            m.constraints(trial, t, moved_phi);
        }
        let trial_cost = squared(moved_phi);
        if solved && trial_cost.is_finite() && trial_cost < cost {
            let lowered = cost - trial_cost;
            q.copy_from_slice(trial);
            m.position_eval(q, t, phi, d);
            gradient(d, phi, g);
            cost = squared(phi);
            mu /= T::from_f64(10.0);
            if lowered <= T::from_f64(STALL) * (cost + lowered) {
                break;
            }
        } else {
            mu = (mu * T::from_f64(10.0)).max(T::from_f64(1e-6) * scale);
        }
    }
    steps
}

/// H made its symmetric part: the differences' H is symmetric only to their rounding.
#[allow(clippy::needless_range_loop)] // entry (i, j) with entry (j, i): both indices are needed
fn symmetrize<T: Real, const NV: usize>(h: &mut [[T; NV]; NV]) {
    for i in 0..NV {
        for j in 0..i {
            let mean = (h[i][j] + h[j][i]) / T::from_f64(2.0);
            (h[i][j], h[j][i]) = (mean, mean);
        }
    }
}

/// g = Dᵀ Φ, the gradient of ½‖Φ‖² in velocity space.
fn gradient<T: Real, const NV: usize, const NC: usize>(d: &[[T; NV]; NC], phi: &[T; NC], g: &mut [T; NV]) {
    for (k, out) in g.iter_mut().enumerate() {
        *out = d.iter().zip(phi).fold(T::ZERO, |s, (row, &p)| s + row[k] * p);
    }
}

fn squared<T: Real, const K: usize>(a: &[T; K]) -> T {
    a.iter().fold(T::ZERO, |s, &x| s + x * x)
}

fn max_abs<T: Real, const K: usize>(a: &[T; K]) -> T {
    a.iter().fold(T::ZERO, |s, &x| s.max(x.abs()))
}
