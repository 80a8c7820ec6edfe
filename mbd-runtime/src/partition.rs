//! Coordinate partitioning (Nikravesh 13.6.2) in velocity space: the NV velocity directions
//! split into NV − NC independent ones, kept as integrated, and NC dependent ones. Positions are
//! corrected by Newton on Φ(q, t) = 0 with steps Δv that are zero in the independent entries,
//! D_d Δv_d = −Φ (D_d the square block of D = Φ_q B), applied as q ⊕ Δv
//! ([`Kinematics::integrate_positions`], h = 1; planar: the dependent coordinates move, the
//! others stay); velocities from D_d v_d = ν − D_i v_i.
//!
//! The split is chosen by Gaussian elimination with full pivoting on D: each step takes the
//! largest remaining entry, whose column becomes dependent. It is chosen again when D_d's LU
//! meets a pivot below 1e-4 of its column's largest entry, i.e. when the independent
//! velocities stop determining the others well (Nikravesh: "when the dependent Jacobian
//! becomes ill-conditioned").

use crate::integrate::SimulationError;
use crate::kinematics::name;
use crate::linalg::{lu_factor, lu_solve_in_place, LinalgError};
use crate::{DynamicsError, Kinematics, Mechanism, Real, Workspace};

/// Pivot ratio below which D_d is chosen anew.
const REPARTITION_PIVOT: f64 = 1e-4;
/// Pivot ratio below which even a fresh partition is singular.
const SINGULAR_PIVOT: f64 = 1e-12;

/// A choice of dependent velocities (planar: coordinates).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Partition<const NV: usize, const NC: usize> {
    /// The dependent velocities, one per constraint row.
    dependent: [usize; NC],
    chosen: bool,
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
        Self { dependent: [0; NC], chosen: false, choices: 0 }
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
            if !self.chosen || attempt == 1 {
                if let Err(row) = self.choose(d, scratch) {
                    return Err(DynamicsError::DependentConstraint { t: t.to_f64(), row: name(M::CONSTRAINT_NAMES, row) }.into());
                }
            }
            for (r, row) in block.iter_mut().enumerate() {
                for (k, entry) in row.iter_mut().enumerate() {
                    *entry = d[r][self.dependent[k]];
                }
            }
            let tolerance = if attempt == 0 { REPARTITION_PIVOT } else { SINGULAR_PIVOT };
            match lu_factor(block, T::from_f64(tolerance)) {
                Ok(p) => return Ok(p),
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
    pub fn correct<T: Real, M: Kinematics<T, NQ, NV, NC>, const NQ: usize, const N: usize>(
        &mut self,
        mechanism: &M,
        ws: &mut Workspace<T, NV, NC, N>,
        t: T,
        q: &mut [T; NQ],
        v: &mut [T; NV],
        tolerance: T,
        max_iterations: u32,
    ) -> Result<(), SimulationError> {
        let mut phi = [T::ZERO; NC];
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
