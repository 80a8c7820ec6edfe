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
use crate::linalg::{lu_factor, lu_solve_in_place, LinalgError};
use crate::model::dynamics::{DynamicsError, DynamicsOptions};
use crate::model::mechanism::{Kinematics, Mechanism};
use crate::model::workspace::{Vectors, WorkArrays};
use crate::real::Real;
use crate::solvers::kinematics::name;

/// Fraction of the chosen partition's conditioning below which D_d is chosen anew.
const REPARTITION_RATIO: f64 = 1e-2;
/// Pivot ratio below which even a fresh partition is singular.
const SINGULAR_PIVOT: f64 = 1e-12;

/// A choice of dependent velocities (planar: coordinates), and of the constraint rows that
/// decide them: with dependent rows (a redundant joint, a singular position) fewer rows than NC.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Partition<const NV: usize, const NC: usize> {
    /// The dependent velocities: the first `rank` are decided by the rows `rows[..rank]`.
    dependent: [usize; NC],
    /// The constraint rows in the order of their pivots; the rows past `rank` are dropped.
    rows: [usize; NC],
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
        Self { dependent: [0; NC], rows: [0; NC], rank: 0, chosen: false, chosen_measure: 0.0, choices: 0 }
    }

    /// The dependent velocities (indices into v; planar: into q), once chosen: one per kept
    /// constraint row.
    pub fn dependent(&self) -> Option<&[usize]> {
        self.chosen.then_some(&self.dependent[..self.rank])
    }

    /// The constraint rows dropped as dependent on the others (indices into Φ), once chosen.
    pub fn dropped(&self) -> Option<&[usize]> {
        self.chosen.then_some(&self.rows[self.rank..])
    }

    /// Chooses the dependent coordinates by full pivoting on `d`. A row whose remaining entries
    /// are all at most `drop_below` times its largest entry in D (about the sine of its angle to
    /// the span of the rows already taken) depends on those rows: it is dropped when
    /// `allow_redundant`, and `Err(row)` names it otherwise.
    // `!(x > y)` on purpose: it is also true when either side is NaN.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    fn choose<T: Real>(&mut self, d: &[[T; NV]; NC], a: &mut [[T; NV]; NC], drop_below: T, allow_redundant: bool) -> Result<(), usize> {
        // Row by row: `*a = *d` builds the NC × NV copy on the stack first in a debug build
        // (2.4 MB for a 201-body ladder, past a 2 MB thread).
        a.copy_from_slice(d);
        let scale: [T; NC] = core::array::from_fn(|r| d[r].iter().fold(T::ZERO, |m, v| m.max(v.abs())));
        let largest = scale.iter().fold(T::ZERO, |m, &v| m.max(v));
        self.rows = core::array::from_fn(|i| i);
        let mut used = [false; NV];
        let mut rank = NC;
        let mut k = 0;
        while k < rank {
            // Rows left with nothing of their own go to the end, dropped.
            let mut i = k;
            while i < rank {
                let remaining = a[i].iter().zip(&used).fold(T::ZERO, |m, (v, &u)| if u { m } else { m.max(v.abs()) });
                let row = self.rows[i];
                if remaining > drop_below * scale[row] && remaining > T::from_f64(SINGULAR_PIVOT) * largest {
                    i += 1;
                    continue;
                }
                if !allow_redundant {
                    return Err(row);
                }
                rank -= 1;
                a.swap(i, rank);
                self.rows.swap(i, rank);
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
                return Err(self.rows[i]);
            }
            a.swap(k, i);
            self.rows.swap(k, i);
            used[j] = true;
            self.dependent[k] = j;
            let pivot_row = a[k];
            for row in a.iter_mut().take(rank).skip(k + 1) {
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
    /// choosing the partition anew when it is missing or ill-conditioned.
    fn factor<T: Real, M: Mechanism>(
        &mut self,
        t: T,
        d: &[[T; NV]; NC],
        options: &DynamicsOptions<T>,
        scratch: &mut [[T; NV]; NC],
        block: &mut [[T; NC]; NC],
    ) -> Result<crate::linalg::Permutation<NC>, SimulationError> {
        if let Some(row) = d.iter().position(|row| row.iter().any(|x| !x.is_finite())) {
            return Err(DynamicsError::NonFinite { t: t.to_f64(), row: name(M::CONSTRAINT_NAMES, row) }.into());
        }
        // Only with `allow_redundant` off (with it on, such a row is dropped).
        let dependent_row = |row| DynamicsError::DependentConstraint { t: t.to_f64(), row: name(M::CONSTRAINT_NAMES, row) }.into();
        loop {
            let fresh = !self.chosen;
            if fresh {
                self.choose(d, scratch, options.pivot_tolerance, options.allow_redundant).map_err(dependent_row)?;
            }
            for (r, row) in block.iter_mut().enumerate() {
                for (k, entry) in row.iter_mut().enumerate() {
                    *entry = match (r < self.rank, k < self.rank) {
                        (true, true) => d[self.rows[r]][self.dependent[k]],
                        (false, false) if r == k => T::ONE,
                        _ => T::ZERO,
                    };
                }
            }
            // A fresh block's elimination pivots are at least √τ of their rows' largest entries
            // (`choose`): it is regular, and its LU takes any non-zero pivot.
            let tolerance = if fresh { T::ZERO } else { T::from_f64(SINGULAR_PIVOT) };
            let kept = match lu_factor(block, tolerance) {
                Ok(p) => {
                    // The smallest pivot against the largest entry of its row of D.
                    let measure = (0..self.rank).fold(f64::INFINITY, |m, k| {
                        let row = self.rows[p.original_rows()[k]];
                        let scale = d[row].iter().fold(T::ZERO, |s, x| s.max(x.abs()));
                        m.min((block[k][k].abs() / scale).to_f64())
                    });
                    if fresh {
                        self.chosen_measure = measure;
                    }
                    (fresh || measure >= REPARTITION_RATIO * self.chosen_measure).then_some(p)
                }
                Err(LinalgError::Singular { candidate_row, .. }) if fresh => {
                    return Err(dependent_row(self.rows[candidate_row]));
                }
                Err(_) => None,
            };
            match kept {
                Some(p) => return Ok(p),
                None => self.chosen = false,
            }
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
        let WorkArrays { jacobian: d, jacobian_scratch: scratch, constraint_square: block, vectors, .. } = ws;
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
                    iterations,
                    worst_row: name(M::CONSTRAINT_NAMES, worst.0),
                    residual: worst.1.to_f64(),
                });
            }
            let permutation = self.factor::<T, M>(t, d, options, scratch, block)?;
            self.kept(phi, b);
            lu_solve_in_place(block, &permutation, b);
            // The partition may have been chosen anew: only this one's entries move.
            step.fill(T::ZERO);
            for (&c, &bk) in self.dependent[..self.rank].iter().zip(b.iter()) {
                step[c] = -bk;
            }
            mechanism.integrate_positions(q, step, T::ONE);
            iterations += 1;
        }
        // Velocities: D_d v_d = ν − D_i v_i, with D at the corrected q.
        let permutation = self.factor::<T, M>(t, d, options, scratch, block)?;
        let nu = phi;
        mechanism.velocity_rhs(q, t, nu);
        for &c in &self.dependent[..self.rank] {
            v[c] = T::ZERO;
        }
        for (r, row) in d.iter().enumerate() {
            for (entry, &vc) in row.iter().zip(v.iter()) {
                nu[r] -= *entry * vc;
            }
        }
        self.kept(nu, b);
        lu_solve_in_place(block, &permutation, b);
        for (&c, &bk) in self.dependent[..self.rank].iter().zip(b.iter()) {
            v[c] = bk;
        }
        Ok(())
    }

    /// The kept rows of `x` (one entry per constraint row) in the block's order, zeros past
    /// `rank` (the identity rows of the dropped ones).
    fn kept<T: Real>(&self, x: &[T; NC], into: &mut [T; NC]) {
        for (i, y) in into.iter_mut().enumerate() {
            *y = if i < self.rank { x[self.rows[i]] } else { T::ZERO };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::UnitPendulum;

    /// The partition is chosen again when its block's smallest pivot, against its row of D,
    /// falls below 1e-2 of its value at the choice — also when that pivot is alone in its
    /// column (a bead on a circle at x → 0: D_d = 2x, 1 against its own column at any x).
    #[test]
    fn an_ill_conditioned_block_is_chosen_again() {
        let mut partition = Partition::<3, 2>::new();
        let (mut scratch, mut block) = ([[0.0; 3]; 2], [[0.0; 2]; 2]);
        // D of the bead at (1, 0): rows (2x, 2y, 0) and the held turn (0, 0, 1).
        let at_side = [[2.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
        partition.factor::<f64, UnitPendulum>(0.0, &at_side, &DynamicsOptions::default(), &mut scratch, &mut block).unwrap();
        assert_eq!((partition.dependent(), partition.choices), (Some(&[0, 2][..]), 1));
        // Still well conditioned at x = 0.1 (measure 0.1 of 1 at the choice: kept).
        let near = [[0.2, 1.99, 0.0], [0.0, 0.0, 1.0]];
        partition.factor::<f64, UnitPendulum>(0.1, &near, &DynamicsOptions::default(), &mut scratch, &mut block).unwrap();
        assert_eq!((partition.dependent(), partition.choices), (Some(&[0, 2][..]), 1));
        // At x = 0.005 (measure 2.5e-3): y becomes dependent.
        let bottom = [[0.01, -2.0, 0.0], [0.0, 0.0, 1.0]];
        partition.factor::<f64, UnitPendulum>(0.2, &bottom, &DynamicsOptions::default(), &mut scratch, &mut block).unwrap();
        assert_eq!((partition.dependent(), partition.choices), (Some(&[1, 2][..]), 2));
    }

    /// Rows that depend on each other: with `allow_redundant` (the default) one of them is
    /// dropped and the other decides the dependent velocity; without, the error names it.
    #[test]
    fn dependent_rows_are_dropped_or_named() {
        let (mut scratch, mut block) = ([[0.0; 3]; 2], [[0.0; 2]; 2]);
        // The bead's circle stated twice, the second row scaled by 2 (and off by a rounding).
        let twice = [[2.0, 0.0, 0.0], [4.0, 1e-15, 0.0]];
        let mut partition = Partition::<3, 2>::new();
        let p = partition.factor::<f64, UnitPendulum>(0.3, &twice, &DynamicsOptions::default(), &mut scratch, &mut block).unwrap();
        // Full pivoting takes the larger row first: the first one is dropped.
        assert_eq!((partition.dependent(), partition.dropped()), (Some(&[0][..]), Some(&[0][..])));
        let mut b = [7.0; 2];
        partition.kept(&[-0.5, -1.0], &mut b);
        lu_solve_in_place(&block, &p, &mut b);
        assert_eq!(b[0], -0.25, "4 Δx = −1 from the kept row; the identity row stays 0");
        assert_eq!(b[1], 0.0);
        let strict = DynamicsOptions::default().with_allow_redundant(false);
        let err = Partition::<3, 2>::new().factor::<f64, UnitPendulum>(0.3, &twice, &strict, &mut scratch, &mut block).unwrap_err();
        assert!(matches!(err, SimulationError::Dynamics(DynamicsError::DependentConstraint { t, .. }) if t == 0.3), "{err:?}");
    }
}
