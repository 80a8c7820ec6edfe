//! Coordinate partitioning (Nikravesh 13.6.2) in velocity space: the NV velocity directions
//! split into NV − NC independent ones, kept as integrated, and NC dependent ones. Positions are
//! corrected by Newton on Φ(q, t) = 0 with steps Δv that are zero in the independent entries,
//! D_d Δv_d = −Φ (D_d the square block of D = Φ_q B), applied as q ⊕ Δv
//! ([`Kinematics::integrate_positions`], h = 1; planar: the dependent coordinates move, the
//! others stay); velocities from D_d v_d = ν − D_i v_i.
//!
//! The split is chosen by Gaussian elimination with full pivoting on D: each step takes the
//! largest remaining entry, whose column becomes dependent. It is chosen again when D_d has
//! become ill-conditioned against what the choice achieved (Nikravesh: "when the dependent
//! Jacobian becomes ill-conditioned"): the measure is the smallest pivot of D_d's LU relative
//! to the largest entry of its row of D, which is scale-free per row (N and m rows alike) and
//! sees a dependent velocity whose column has no other entry (a bead on a circle at
//! x = 0, where D_d = 2x alone: a pivot relative to its own column would be 1 there). The
//! partition is chosen anew when that measure falls below 1e-2 of its value at the choice.
//!
//! Dependent rows (a redundant joint such as a Bricard linkage's sixth hinge, or a singular
//! position) are handled as forward dynamics handles them
//! ([`DynamicsOptions::allow_redundant`]): a row whose entries left after the elimination are
//! at most τ (the pivot tolerance, 1e-8) of its largest entry in D — about the sine of its
//! angle to the span of the rows taken — is dropped, so r < NC rows decide r dependent
//! velocities and NV − r stay independent; with `allow_redundant` off it is a
//! [`DynamicsError::DependentConstraint`] naming it. A dropped row is still part of the
//! converged residual ‖Φ‖∞: where it is not implied by the others (an inconsistent singular
//! position) the correction does not converge and says so. Dropping from √τ instead (where
//! forward dynamics' smooth drop takes hold) left a parallelogram chain's dropped rows
//! unconverged at 1.07e-10 near its flat positions with DOPRI5 at rtol 1e-10; from τ it passes
//! them at every rtol (`mbd-long/tests/singular.rs`).

use crate::integrate::SimulationError;
use crate::linalg::{lu_factor, lu_solve_in_place, LinalgError, LuWork};
use crate::model::dynamics::{DynamicsError, DynamicsOptions};
use crate::model::mechanism::{Kinematics, Mechanism};
use crate::model::workspace::{Indices, Vectors, WorkArrays};
use crate::real::Real;
use crate::solvers::kinematics::name;

/// Fraction of the chosen partition's conditioning below which D_d is chosen anew.
const REPARTITION_RATIO: f64 = 1e-2;
/// Pivot ratio below which even a fresh partition is singular.
const SINGULAR_PIVOT: f64 = 1e-12;

/// A choice of dependent velocities (planar: coordinates), and of the constraint rows that
/// decide them: with dependent rows (a redundant joint, a singular position) fewer rows than NC.
///
/// The choice's indices are in the work space it corrects with (so that they do not put two
/// arrays of NC indices on the stack): the dependent velocities, of which the first `rank` are
/// decided by the rows `rows[..rank]`, and the constraint rows in the order of their pivots,
/// the rows past `rank` dropped.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Partition<const NV: usize, const NC: usize> {
    rank: usize,
    chosen: bool,
    /// The conditioning measure (module docs) of D_d when it was chosen.
    chosen_measure: f64,
    /// How many times a partition was chosen.
    pub choices: u32,
}

impl<const NV: usize, const NC: usize> Default for Partition<NV, NC> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const NV: usize, const NC: usize> Partition<NV, NC> {
    /// No partition yet: the first correction chooses one.
    pub fn new() -> Self {
        Self { rank: 0, chosen: false, chosen_measure: 0.0, choices: 0 }
    }

    /// The dependent velocities (indices into v; planar: into q), once chosen: one per kept
    /// constraint row. `ws` is the work space the partition corrects with.
    pub fn dependent<'w, T, const N: usize, const NS: usize>(&self, ws: &'w WorkArrays<T, NV, NC, N, NS>) -> Option<&'w [usize]> {
        self.chosen.then_some(&ws.indices.dependent[..self.rank])
    }

    /// The constraint rows dropped as dependent on the others (indices into Φ), once chosen.
    /// `ws` is the work space the partition corrects with.
    pub fn dropped<'w, T, const N: usize, const NS: usize>(&self, ws: &'w WorkArrays<T, NV, NC, N, NS>) -> Option<&'w [usize]> {
        self.chosen.then_some(&ws.indices.rows[self.rank..])
    }

    /// Chooses the dependent coordinates by full pivoting on `d`, into `indices.dependent` and
    /// `indices.rows`. A row whose remaining entries are all at most `drop_below` times its
    /// largest entry in D (about the sine of its angle to the span of the rows already taken)
    /// depends on those rows: it is dropped when `allow_redundant`, and `Err(row)` names it
    /// otherwise. `a` and `scale` are scratch.
    // `!(x > y)` on purpose: it is also true when either side is NaN.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    fn choose<T: Real>(
        &mut self,
        d: &[[T; NV]; NC],
        (a, scale): (&mut [[T; NV]; NC], &mut [T; NC]),
        indices: &mut Indices<NV, NC>,
        drop_below: T,
        allow_redundant: bool,
    ) -> Result<(), usize> {
        let Indices { rows, dependent, .. } = indices;
        // Row by row: `*a = *d` builds the NC × NV copy on the stack first in a debug build
        // (2.4 MB for a 201-body ladder, past a 2 MB thread).
        a.copy_from_slice(d);
        for (s, row) in scale.iter_mut().zip(d) {
            *s = row.iter().fold(T::ZERO, |m, v| m.max(v.abs()));
        }
        let largest = scale.iter().fold(T::ZERO, |m, &v| m.max(v));
        for (i, row) in rows.iter_mut().enumerate() {
            *row = i;
        }
        // A byte a velocity: whether it is dependent already.
        let mut used = [false; NV];
        let mut rank = NC;
        let mut k = 0;
        while k < rank {
            // Rows left with nothing of their own go to the end, dropped.
            let mut i = k;
            while i < rank {
                let remaining = a[i].iter().zip(&used).fold(T::ZERO, |m, (v, &u)| if u { m } else { m.max(v.abs()) });
                let row = rows[i];
                if remaining > drop_below * scale[row] && remaining > T::from_f64(SINGULAR_PIVOT) * largest {
                    i += 1;
                    continue;
                }
                if !allow_redundant {
                    return Err(row);
                }
                rank -= 1;
                a.swap(i, rank);
                rows.swap(i, rank);
            }
            if k == rank {
                break;
            }
            let mut best = (T::ZERO, k, 0);
            for (i, row) in a.iter().enumerate().take(rank).skip(k) {
                for (j, v) in row.iter().enumerate() {
                    if !used[j] && v.abs() > best.0 {
                        best = (v.abs(), i, j);
                    }
                }
            }
            let (value, i, j) = best;
            if !(value > T::ZERO) {
                return Err(rows[i]);
            }
            a.swap(k, i);
            rows.swap(k, i);
            used[j] = true;
            dependent[k] = j;
            let (done, remaining) = a.split_at_mut(k + 1);
            let pivot_row = &done[k];
            for row in remaining.iter_mut().take(rank - k - 1) {
                let factor = row[j] / pivot_row[j];
                for (entry, &p) in row.iter_mut().zip(pivot_row.iter()) {
                    *entry -= factor * p;
                }
            }
            k += 1;
        }
        self.rank = rank;
        self.chosen = true;
        self.choices += 1;
        Ok(())
    }

    /// LU of D_d (the kept rows against the dependent velocities, the identity past `rank`),
    /// choosing the partition anew when it is missing or ill-conditioned: the factors in
    /// `block`, their interchanges in `indices.pivots_c`. `scratch` and `vectors` are scratch.
    fn factor<T: Real, M: Mechanism>(
        &mut self,
        t: T,
        d: &[[T; NV]; NC],
        options: &DynamicsOptions<T>,
        (scratch, block): (&mut [[T; NV]; NC], &mut [[T; NC]; NC]),
        indices: &mut Indices<NV, NC>,
        mut vectors: Vectors<'_, T>,
    ) -> Result<(), SimulationError> {
        if let Some(row) = d.iter().position(|row| row.iter().any(|x| !x.is_finite())) {
            return Err(DynamicsError::NonFinite { t: t.to_f64(), row: name(M::CONSTRAINT_NAMES, row) }.into());
        }
        // Only with `allow_redundant` off (with it on, such a row is dropped).
        let dependent_row = |row| DynamicsError::DependentConstraint { t: t.to_f64(), row: name(M::CONSTRAINT_NAMES, row) }.into();
        let [scale, pivot_scale] = vectors.rows_written::<NC, 2>();
        loop {
            let fresh = !self.chosen;
            if fresh {
                self.choose(d, (scratch, scale), indices, options.pivot_tolerance, options.allow_redundant).map_err(dependent_row)?;
            }
            let Indices { rows, dependent, pivots_c, columns_c, .. } = &mut *indices;
            for (r, row) in block.iter_mut().enumerate() {
                for (k, entry) in row.iter_mut().enumerate() {
                    *entry = match (r < self.rank, k < self.rank) {
                        (true, true) => d[rows[r]][dependent[k]],
                        (false, false) if r == k => T::ONE,
                        _ => T::ZERO,
                    };
                }
            }
            // The largest entry of each kept row of D, in the block's order.
            for (s, &row) in pivot_scale.iter_mut().zip(rows.iter()).take(self.rank) {
                *s = d[row].iter().fold(T::ZERO, |m, x| m.max(x.abs()));
            }
            // A fresh block's elimination pivots are at least √τ of their rows' largest entries
            // (`choose`): it is regular, and its LU takes any non-zero pivot.
            let tolerance = if fresh { T::ZERO } else { T::from_f64(SINGULAR_PIVOT) };
            let work = LuWork { pivots: &mut *pivots_c, columns: columns_c, scale: &mut *scale };
            let kept = match lu_factor(block, tolerance, work) {
                Ok(()) => {
                    // The smallest pivot against the largest entry of its row of D: the
                    // scales interchanged as the LU interchanged the rows (the rows past `rank`,
                    // the identity's, stay in place below them).
                    for (k, &swapped) in pivots_c.iter().enumerate().take(self.rank) {
                        pivot_scale.swap(k, swapped);
                    }
                    let measure = (0..self.rank).fold(f64::INFINITY, |m, k| m.min((block[k][k].abs() / pivot_scale[k]).to_f64()));
                    if fresh {
                        self.chosen_measure = measure;
                    }
                    fresh || measure >= REPARTITION_RATIO * self.chosen_measure
                }
                Err(LinalgError::Singular { candidate_row, .. }) if fresh => {
                    return Err(dependent_row(rows[candidate_row]));
                }
                Err(_) => false,
            };
            if kept {
                return Ok(());
            }
            self.chosen = false;
        }
    }

    /// Solves the dependent directions of q and the dependent velocities for the independent
    /// ones.
    ///
    /// # Errors
    /// [`SimulationError::NotConverged`] naming the worst row, or a dependent-constraint error.
    // The mechanism, its work space, the state and the two tolerances: no grouping reads better.
    #[allow(clippy::too_many_arguments)]
    pub fn correct<T: Real, M: Kinematics<T, NQ, NV, NC>, const NQ: usize, const N: usize, const NS: usize>(
        &mut self,
        mechanism: &M,
        ws: &mut WorkArrays<T, NV, NC, N, NS>,
        t: T,
        q: &mut [T; NQ],
        v: &mut [T; NV],
        options: &DynamicsOptions<T>,
        tolerance: T,
        max_iterations: u32,
    ) -> Result<(), SimulationError> {
        let tolerance = tolerance.max(crate::solvers::kinematics::resolution(q));
        let WorkArrays { jacobian: d, jacobian_scratch: scratch, constraint_square: block, vectors, indices, .. } = ws;
        // Φ, then ν; the kept rows' right-hand side; a step of the positions.
        let mut vectors = Vectors::new(vectors.flat());
        let [phi, b] = vectors.rows::<NC, 2>();
        let step = vectors.take::<NV>();
        let mut iterations = 0;
        loop {
            mechanism.position_eval(q, t, phi, d);
            let worst = phi.iter().enumerate().fold((0, T::ZERO), |w, (i, v)| if v.abs() > w.1 { (i, v.abs()) } else { w });
            if worst.1 <= tolerance {
                break;
            }
            if iterations >= max_iterations || !worst.1.is_finite() {
                return Err(SimulationError::NotConverged {
                    t: t.to_f64(),
                    newton: super::NewtonIteration::Partitioning,
                    iterations,
                    worst_row: name(M::CONSTRAINT_NAMES, worst.0),
                    residual: worst.1.to_f64(),
                });
            }
            self.factor::<T, M>(t, d, options, (scratch, block), indices, vectors.reborrow())?;
            self.kept(&indices.rows, phi, b);
            lu_solve_in_place(block, &indices.pivots_c, b);
            // The partition may have been chosen anew: only this one's entries move.
            step.fill(T::ZERO);
            for (&c, &bk) in indices.dependent[..self.rank].iter().zip(b.iter()) {
                step[c] = -bk;
            }
            mechanism.integrate_positions(q, step, T::ONE);
            iterations += 1;
        }
        // Velocities: D_d v_d = ν − D_i v_i, with D at the corrected q.
        self.factor::<T, M>(t, d, options, (scratch, block), indices, vectors.reborrow())?;
        let nu = phi;
        mechanism.velocity_rhs(q, t, nu);
        for &c in &indices.dependent[..self.rank] {
            v[c] = T::ZERO;
        }
        for (r, row) in d.iter().enumerate() {
            for (entry, &vc) in row.iter().zip(v.iter()) {
                nu[r] -= *entry * vc;
            }
        }
        self.kept(&indices.rows, nu, b);
        lu_solve_in_place(block, &indices.pivots_c, b);
        for (&c, &bk) in indices.dependent[..self.rank].iter().zip(b.iter()) {
            v[c] = bk;
        }
        Ok(())
    }

    /// The kept rows of `x` (one entry per constraint row) in the block's order (`rows`, the
    /// work space's), zeros past `rank` (the identity rows of the dropped ones).
    fn kept<T: Real>(&self, rows: &[usize; NC], x: &[T; NC], into: &mut [T; NC]) {
        for (i, y) in into.iter_mut().enumerate() {
            *y = if i < self.rank { x[rows[i]] } else { T::ZERO };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::workspace::Workspace;
    use crate::test_support::UnitPendulum;

    /// The partition is chosen again when its block's smallest pivot, against its row of D,
    /// falls below 1e-2 of its value at the choice — also when that pivot is alone in its
    /// column (a bead on a circle at x → 0: D_d = 2x, 1 against its own column at any x).
    /// `Partition::factor` on a work space's arrays.
    fn factor(
        partition: &mut Partition<3, 2>,
        ws: &mut Workspace<f64, 3, 2, 5>,
        t: f64,
        d: &[[f64; 3]; 2],
        options: &DynamicsOptions<f64>,
    ) -> Result<(), SimulationError> {
        let WorkArrays { jacobian_scratch, constraint_square, vectors, indices, .. } = &mut **ws;
        partition.factor::<f64, UnitPendulum>(t, d, options, (jacobian_scratch, constraint_square), indices, Vectors::new(vectors.flat()))
    }

    /// The partition is chosen again when its block's smallest pivot, against its row of D,
    /// falls below 1e-2 of its value at the choice — also when that pivot is alone in its
    /// column (a bead on a circle at x → 0: D_d = 2x, 1 against its own column at any x).
    #[test]
    fn an_ill_conditioned_block_is_chosen_again() {
        let mut partition = Partition::<3, 2>::new();
        let mut ws = Workspace::<f64, 3, 2, 5>::new();
        let options = DynamicsOptions::default();
        // D of the bead at (1, 0): rows (2x, 2y, 0) and the held turn (0, 0, 1).
        let at_side = [[2.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
        factor(&mut partition, &mut ws, 0.0, &at_side, &options).unwrap();
        assert_eq!((partition.dependent(&ws), partition.choices), (Some(&[0, 2][..]), 1));
        // Still well conditioned at x = 0.1 (measure 0.1 of 1 at the choice: kept).
        let near = [[0.2, 1.99, 0.0], [0.0, 0.0, 1.0]];
        factor(&mut partition, &mut ws, 0.1, &near, &options).unwrap();
        assert_eq!((partition.dependent(&ws), partition.choices), (Some(&[0, 2][..]), 1));
        // At x = 0.005 (measure 2.5e-3): y becomes dependent.
        let bottom = [[0.01, -2.0, 0.0], [0.0, 0.0, 1.0]];
        factor(&mut partition, &mut ws, 0.2, &bottom, &options).unwrap();
        assert_eq!((partition.dependent(&ws), partition.choices), (Some(&[1, 2][..]), 2));
    }

    /// The measure follows the block's row interchanges. The bead's row with a second one
    /// coupling x and the turn: at the side D_d = [[2, 0], [1, 1]], measure 1. Near the bottom
    /// its LU exchanges the rows, and the bead's pivot is measured against the bead's row of D:
    /// at x = 0.1, 0.2/1.99, kept; at x = 0.008, 0.016/2 = 0.008 < 1e-2, chosen again (measured
    /// against the other row, it would read 0.016 and be kept).
    #[test]
    fn the_measure_follows_the_interchanges() {
        let mut partition = Partition::<3, 2>::new();
        let mut ws = Workspace::<f64, 3, 2, 5>::new();
        let options = DynamicsOptions::default();
        let at_side = [[2.0, 0.0, 0.0], [1.0, 0.0, 1.0]];
        factor(&mut partition, &mut ws, 0.0, &at_side, &options).unwrap();
        assert_eq!((partition.dependent(&ws), partition.choices), (Some(&[0, 2][..]), 1));
        let near = [[0.2, 1.99, 0.0], [1.0, 0.0, 1.0]];
        factor(&mut partition, &mut ws, 0.1, &near, &options).unwrap();
        assert_eq!(ws.indices.pivots_c[0], 1, "the LU exchanged D_d's rows");
        assert_eq!((partition.dependent(&ws), partition.choices), (Some(&[0, 2][..]), 1));
        let bottom = [[0.016, -2.0, 0.0], [1.0, 0.0, 1.0]];
        factor(&mut partition, &mut ws, 0.2, &bottom, &options).unwrap();
        assert_eq!((partition.dependent(&ws), partition.choices), (Some(&[1, 0][..]), 2));
    }

    /// Rows that depend on each other: with `allow_redundant` (the default) one of them is
    /// dropped and the other decides the dependent velocity; without, the error names it.
    #[test]
    fn dependent_rows_are_dropped_or_named() {
        let mut ws = Workspace::<f64, 3, 2, 5>::new();
        // The bead's circle stated twice, the second row scaled by 2 (and off by a rounding).
        let twice = [[2.0, 0.0, 0.0], [4.0, 1e-15, 0.0]];
        let mut partition = Partition::<3, 2>::new();
        factor(&mut partition, &mut ws, 0.3, &twice, &DynamicsOptions::default()).unwrap();
        // Full pivoting takes the larger row first: the first one is dropped.
        assert_eq!((partition.dependent(&ws), partition.dropped(&ws)), (Some(&[0][..]), Some(&[0][..])));
        let mut b = [7.0; 2];
        partition.kept(&ws.indices.rows, &[-0.5, -1.0], &mut b);
        lu_solve_in_place(&ws.constraint_square, &ws.indices.pivots_c, &mut b);
        assert_eq!(b[0], -0.25, "4 Δx = −1 from the kept row; the identity row stays 0");
        assert_eq!(b[1], 0.0);
        let strict = DynamicsOptions::default().with_allow_redundant(false);
        let err = factor(&mut Partition::<3, 2>::new(), &mut ws, 0.3, &twice, &strict).unwrap_err();
        assert!(matches!(err, SimulationError::Dynamics(DynamicsError::DependentConstraint { t, .. }) if t == 0.3), "{err:?}");
    }
}
