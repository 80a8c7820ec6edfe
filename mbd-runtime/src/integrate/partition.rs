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

use crate::integrate::SimulationError;
use crate::linalg::{lu_factor, lu_solve_in_place, LinalgError};
use crate::model::dynamics::DynamicsError;
use crate::model::mechanism::{Kinematics, Mechanism};
use crate::model::workspace::Workspace;
use crate::real::Real;
use crate::solvers::kinematics::name;

/// Fraction of the chosen partition's conditioning below which D_d is chosen anew.
const REPARTITION_RATIO: f64 = 1e-2;
/// Pivot ratio below which even a fresh partition is singular.
const SINGULAR_PIVOT: f64 = 1e-12;

/// A choice of dependent velocities (planar: coordinates).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Partition<const NV: usize, const NC: usize> {
    /// The dependent velocities, one per constraint row.
    dependent: [usize; NC],
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
        Self { dependent: [0; NC], chosen: false, chosen_measure: 0.0, choices: 0 }
    }

    /// The dependent velocities (indices into v; planar: into q), once chosen.
    pub fn dependent(&self) -> Option<&[usize; NC]> {
        self.chosen.then_some(&self.dependent)
    }

    /// Chooses the dependent coordinates by full pivoting on `d`; `Err(row)` names a row with
    /// no acceptable pivot left (dependent constraints).
    // `!(x > y)` on purpose: it is also true when either side is NaN.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    fn choose<T: Real>(&mut self, d: &[[T; NV]; NC], a: &mut [[T; NV]; NC]) -> Result<(), usize> {
        *a = *d;
        let mut rows: [usize; NC] = core::array::from_fn(|i| i);
        let mut used = [false; NV];
        let scale = a.iter().flatten().fold(T::ZERO, |m, v| m.max(v.abs()));
        for k in 0..NC {
            let mut best = (T::ZERO, k, 0);
            for (i, row) in a.iter().enumerate().skip(k) {
                for (j, v) in row.iter().enumerate() {
                    if !used[j] && v.abs() > best.0 {
                        best = (v.abs(), i, j);
                    }
                }
            }
            let (value, i, j) = best;
            if !(value > T::from_f64(SINGULAR_PIVOT) * scale) {
                return Err(rows[k]);
            }
            a.swap(k, i);
            rows.swap(k, i);
            used[j] = true;
            self.dependent[k] = j;
            let pivot_row = a[k];
            for row in a.iter_mut().skip(k + 1) {
                let factor = row[j] / pivot_row[j];
                for (entry, &p) in row.iter_mut().zip(pivot_row.iter()) {
                    *entry -= factor * p;
                }
            }
        }
        self.chosen = true;
        self.choices += 1;
        Ok(())
    }

    /// LU of D_d, choosing the partition anew when it is missing or ill-conditioned.
    fn factor<T: Real, M: Mechanism>(
        &mut self,
        t: T,
        d: &[[T; NV]; NC],
        scratch: &mut [[T; NV]; NC],
        block: &mut [[T; NC]; NC],
    ) -> Result<crate::linalg::Permutation<NC>, SimulationError> {
        for attempt in 0..2 {
            let fresh = !self.chosen || attempt == 1;
            if fresh {
                if let Err(row) = self.choose(d, scratch) {
                    return Err(DynamicsError::DependentConstraint { t: t.to_f64(), row: name(M::CONSTRAINT_NAMES, row) }.into());
                }
            }
            for (r, row) in block.iter_mut().enumerate() {
                for (k, entry) in row.iter_mut().enumerate() {
                    *entry = d[r][self.dependent[k]];
                }
            }
            match lu_factor(block, T::from_f64(SINGULAR_PIVOT)) {
                Ok(p) => {
                    // The smallest pivot against the largest entry of its row of D.
                    let measure = (0..NC).fold(f64::INFINITY, |m, k| {
                        let row = p.original_rows()[k];
                        let scale = d[row].iter().fold(T::ZERO, |s, x| s.max(x.abs()));
                        m.min((block[k][k].abs() / scale).to_f64())
                    });
                    if fresh {
                        self.chosen_measure = measure;
                        return Ok(p);
                    }
                    if measure >= REPARTITION_RATIO * self.chosen_measure {
                        return Ok(p);
                    }
                }
                Err(LinalgError::Singular { candidate_row, .. }) if attempt == 1 => {
                    return Err(DynamicsError::DependentConstraint { t: t.to_f64(), row: name(M::CONSTRAINT_NAMES, candidate_row) }.into())
                }
                Err(LinalgError::NonFinite { row, .. }) => {
                    return Err(DynamicsError::NonFinite { t: t.to_f64(), row: name(M::CONSTRAINT_NAMES, row) }.into())
                }
                Err(_) => {}
            }
        }
        Err(DynamicsError::DependentConstraint { t: t.to_f64(), row: name(M::CONSTRAINT_NAMES, 0) }.into())
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
        ws: &mut Workspace<T, NV, NC, N, NS>,
        t: T,
        q: &mut [T; NQ],
        v: &mut [T; NV],
        tolerance: T,
        max_iterations: u32,
    ) -> Result<(), SimulationError> {
        let mut phi = [T::ZERO; NC];
        let tolerance = tolerance.max(crate::solvers::kinematics::resolution(q));
        let Workspace { jacobian: d, jacobian_scratch: scratch, constraint_square: block, .. } = ws;
        let mut iterations = 0;
        loop {
            mechanism.position_eval(q, t, &mut phi, d);
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
            let permutation = self.factor::<T, M>(t, d, scratch, block)?;
            lu_solve_in_place(block, &permutation, &mut phi);
            // The partition may have been chosen anew: only this one's entries move.
            let mut step = [T::ZERO; NV];
            for (k, &c) in self.dependent.iter().enumerate() {
                step[c] = -phi[k];
            }
            mechanism.integrate_positions(q, &step, T::ONE);
            iterations += 1;
        }
        // Velocities: D_d v_d = ν − D_i v_i, with D at the corrected q.
        let permutation = self.factor::<T, M>(t, d, scratch, block)?;
        let mut rhs = [T::ZERO; NC];
        mechanism.velocity_rhs(q, t, &mut rhs);
        for &c in &self.dependent {
            v[c] = T::ZERO;
        }
        for (r, row) in d.iter().enumerate() {
            for (entry, &vc) in row.iter().zip(v.iter()) {
                rhs[r] -= *entry * vc;
            }
        }
        lu_solve_in_place(block, &permutation, &mut rhs);
        for (k, &c) in self.dependent.iter().enumerate() {
            v[c] = rhs[k];
        }
        Ok(())
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
        partition.factor::<f64, UnitPendulum>(0.0, &at_side, &mut scratch, &mut block).unwrap();
        assert_eq!((partition.dependent(), partition.choices), (Some(&[0, 2]), 1));
        // Still well conditioned at x = 0.1 (measure 0.1 of 1 at the choice: kept).
        let near = [[0.2, 1.99, 0.0], [0.0, 0.0, 1.0]];
        partition.factor::<f64, UnitPendulum>(0.1, &near, &mut scratch, &mut block).unwrap();
        assert_eq!((partition.dependent(), partition.choices), (Some(&[0, 2]), 1));
        // At x = 0.005 (measure 2.5e-3): y becomes dependent.
        let bottom = [[0.01, -2.0, 0.0], [0.0, 0.0, 1.0]];
        partition.factor::<f64, UnitPendulum>(0.2, &bottom, &mut scratch, &mut block).unwrap();
        assert_eq!((partition.dependent(), partition.choices), (Some(&[1, 2]), 2));
    }

    /// Rows that depend on each other leave no partition: the error names the row.
    #[test]
    fn dependent_rows_are_named() {
        let mut partition = Partition::<3, 2>::new();
        let (mut scratch, mut block) = ([[0.0; 3]; 2], [[0.0; 2]; 2]);
        let twice = [[2.0, 0.0, 0.0], [4.0, 0.0, 0.0]];
        let err = partition.factor::<f64, UnitPendulum>(0.3, &twice, &mut scratch, &mut block).unwrap_err();
        assert!(matches!(err, SimulationError::Dynamics(DynamicsError::DependentConstraint { t, .. }) if t == 0.3), "{err:?}");
    }
}
