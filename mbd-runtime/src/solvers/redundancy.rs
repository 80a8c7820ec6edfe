//! Redundant constraints and the true mobility of a configuration: which constraint rows of
//! D = Φ_q B depend on the rows before them, found by a rank-revealing orthogonalization.
//!
//! Grübler's count, NV − NC, is the mobility only when the NC rows of D are independent. A
//! parallelogram with a third parallel crank counts 0 but moves with one degree of freedom: one
//! of its rows repeats what the others already impose. At a singular position (a four-bar
//! lying flat) a row becomes dependent for that configuration only, and the mechanism has one
//! instantaneous mobility more than Grübler says.
//!
//! The rows are taken in declaration order and each is orthogonalized against the independent
//! rows before it (modified Gram–Schmidt, twice, which keeps the basis orthonormal to rounding);
//! the row is **redundant** when what is left of it is at most
//! [`KinematicOptions::rank_tolerance`] of its own length, i.e. when the sine of its angle to
//! the span of the rows before it is below that tolerance (default
//! [`DEFAULT_RANK_TOLERANCE`] = 1e-8). So the row named is the later-declared one: the first
//! that depends on the rows declared before it. Angles are measured in velocity space with m/s and
//! rad/s weighted alike. The report also gives the margins of that decision: the smallest sine
//! among the rows kept and the largest among the rows named (a gap of many orders of magnitude
//! makes the rank at q clear-cut). Whether a dependent row is a redundancy or a singular
//! position shows only at another configuration: a redundancy stays, a singular position goes.
//!
//! Cost: NC² NV multiply-adds, in the caller's [`Workspace`]; nothing allocates.
//!
//! [`KinematicOptions::rank_tolerance`]: crate::KinematicOptions::rank_tolerance
//! [`DEFAULT_RANK_TOLERANCE`]: crate::DEFAULT_RANK_TOLERANCE

use crate::linalg::dot;
use crate::linalg::orthogonal::orthogonalize;
use crate::model::mechanism::Kinematics;
use crate::model::workspace::{WorkArrays, Workspace};
use crate::real::Real;
use crate::solvers::error::KinematicError;
use crate::solvers::error::NonFiniteQuantity;
use crate::solvers::kinematics::KinematicSolver;
use crate::solvers::kinematics::{check_finite, check_rows_finite, check_time};
use core::fmt;

/// Which constraint rows are redundant at a configuration, and the mobility that follows: the
/// result of [`KinematicSolver::redundancy`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Redundancy<const NC: usize> {
    /// Independent constraint rows: the rank of D.
    pub rank: usize,
    /// Grübler's count NV − NC (may be negative).
    pub grubler: i32,
    /// The mobility at this configuration, NV − rank.
    pub mobility: i32,
    /// The smallest sine of a kept row's angle to the rows before it (1 when none was kept):
    /// how close the rows kept came to being called redundant.
    pub smallest_kept: f64,
    /// The largest such sine among the redundant rows (0 when none): how close a redundant row
    /// came to being kept.
    pub largest_redundant: f64,
    redundant: [bool; NC],
    names: &'static [&'static str],
}

impl<const NC: usize> Redundancy<NC> {
    /// Whether constraint row `row` (an index into [`Mechanism::CONSTRAINT_NAMES`]) is redundant.
    ///
    /// [`Mechanism::CONSTRAINT_NAMES`]: crate::Mechanism::CONSTRAINT_NAMES
    pub fn is_redundant(&self, row: usize) -> bool {
        self.redundant.get(row).copied().unwrap_or(false)
    }

    /// The redundant rows by index, in declaration order.
    pub fn redundant_rows(&self) -> impl Iterator<Item = usize> + '_ {
        (0..NC).filter(|&r| self.redundant[r])
    }

    /// The redundant rows by name (`"revolute c3~coupler: y"`), in declaration order.
    pub fn redundant_names(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.redundant_rows().map(|r| self.names.get(r).copied().unwrap_or("<unnamed>"))
    }
}

impl<const NC: usize> fmt::Display for Redundancy<NC> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let redundant = NC - self.rank;
        write!(f, "Grübler's count {}, mobility {} (rank {} of {NC} rows)", self.grubler, self.mobility, self.rank)?;
        if redundant == 0 {
            return write!(f, ": no redundant row (smallest sine kept {:.1e})", self.smallest_kept);
        }
        write!(f, "; {redundant} redundant row{}:", if redundant == 1 { "" } else { "s" })?;
        for (k, name) in self.redundant_names().enumerate() {
            write!(f, "{} '{name}'", if k == 0 { "" } else { "," })?;
        }
        write!(f, " (largest sine among them {:.1e}, smallest kept {:.1e})", self.largest_redundant, self.smallest_kept)?;
        write!(
            f,
            ". If they stay redundant at a nearby configuration, the joint that repeats the others \
             may stay: the solves drop such rows by default (DynamicsOptions::allow_redundant), with \
             reactions that are one of many valid sets — remove it for unique reactions; if not, \
             this is a singular position"
        )
    }
}

impl<T: Real> KinematicSolver<T> {
    /// Which constraint rows are redundant at (q, t) and the mobility NV − rank that follows,
    /// next to Grübler's count NV − NC (the algorithm: [the `redundancy` module](crate::redundancy)).
    /// `q` need not satisfy the constraints exactly, but the answer is about the configuration
    /// q: assemble first.
    ///
    /// # Errors
    /// [`KinematicError::NonFinite`] for a NaN or infinite t, q or D.
    pub fn redundancy<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
        &self,
        m: &M,
        ws: &mut Workspace<T, NV, NC, N, NS>,
        q: &[T; NQ],
        t: T,
    ) -> Result<Redundancy<NC>, KinematicError>
    where
        M: Kinematics<T, NQ, NV, NC>,
    {
        check_time(t)?;
        check_finite(q, t, NonFiniteQuantity::Coordinate, M::COORDINATE_NAMES)?;
        let WorkArrays { jacobian: d, jacobian_scratch: basis, constraint_square, .. } = &mut **ws;
        m.jacobian(q, t, d);
        check_rows_finite::<T, M, NV, NC>(d, t)?;
        let tolerance = self.options.rank_tolerance;
        let mut redundant = [false; NC];
        let split = orthogonalize(d, tolerance, basis, constraint_square, &mut redundant);
        Ok(Redundancy {
            rank: split.rank,
            grubler: NV as i32 - NC as i32,
            mobility: NV as i32 - split.rank as i32,
            smallest_kept: split.smallest_kept.to_f64(),
            largest_redundant: split.largest_redundant.to_f64(),
            redundant,
            names: M::CONSTRAINT_NAMES,
        })
    }
}

impl<T: Real> KinematicSolver<T> {
    /// The reactions of least Euclidean norm that exert the same generalized constraint force
    /// as `lambda`: with redundant rows (as [`redundancy`](Self::redundancy) decides at (q, t))
    /// the multipliers are not unique — any λ + n with Dᵀn = 0 balances the same load — and the
    /// solvers return the one whose redundant rows carry nothing. This replaces `lambda` by
    /// argmin ‖λ‖ subject to Dᵀλ = Dᵀλ₀: the load shared among the joints that repeat each other
    /// (for a parallelogram with a third crank, across all three) as a pseudo-inverse would,
    /// with N and N·m rows weighted alike. Without redundant rows `lambda` is left as it is.
    ///
    /// With D's kept rows D_K = R Q and each redundant row d_i = c_iᵀ D_K (C = R⁻ᵀ Q Dᵀ_R), every
    /// valid λ has λ_K = μ − Cᵀ λ_R for the μ of `lambda` with its redundant rows folded in, so
    /// the least norm is λ_R = (I + C Cᵀ)⁻¹ C μ, λ_K = μ − Cᵀ λ_R. Cost: the orthogonalization
    /// (NC² NV) and a Cholesky factorization of the p × p matrix of the p redundant rows, in the
    /// caller's work space; nothing allocates.
    ///
    /// # Errors
    /// [`KinematicError::NonFinite`] for a NaN or infinite t, q, D or λ.
    pub fn minimum_norm_reactions<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
        &self,
        m: &M,
        ws: &mut Workspace<T, NV, NC, N, NS>,
        q: &[T; NQ],
        t: T,
        lambda: &mut [T; NC],
    ) -> Result<(), KinematicError>
    where
        M: Kinematics<T, NQ, NV, NC>,
    {
        check_time(t)?;
        check_finite(q, t, NonFiniteQuantity::Coordinate, M::COORDINATE_NAMES)?;
        check_finite(lambda, t, NonFiniteQuantity::Multiplier, M::CONSTRAINT_NAMES)?;
        let WorkArrays { jacobian: d, jacobian_scratch: basis, constraint_square: r, coupling, .. } = &mut **ws;
        m.jacobian(q, t, d);
        check_rows_finite::<T, M, NV, NC>(d, t)?;
        let mut redundant = [false; NC];
        let split = orthogonalize(d, self.options.rank_tolerance, basis, r, &mut redundant);
        let rank = split.rank;
        let p = NC - rank;
        if p == 0 {
            return Ok(());
        }
        let kept: [usize; NC] = {
            let mut kept = [0; NC];
            for (slot, i) in kept.iter_mut().zip((0..NC).filter(|&i| !redundant[i])) {
                *slot = i;
            }
            kept
        };
        // C (p × rank) in coupling[j][0..rank]: for redundant row i, solve Rᵀ c = Q d_i (R lower
        // triangular, so Rᵀ upper: back substitution).
        let dropped = (0..NC).filter(|&i| redundant[i]);
        for (j, i) in dropped.clone().enumerate() {
            let coef: [T; NC] = core::array::from_fn(|k| if k < rank { dot(&basis[k], &d[i]) } else { T::ZERO });
            for k in (0..rank).rev() {
                let mut value = coef[k];
                for l in k + 1..rank {
                    value -= r[l][k] * coupling[j][l];
                }
                coupling[j][k] = value / r[k][k];
            }
        }
        // μ: λ with each redundant row's load moved onto the kept rows it repeats
        // (D_Rᵀ λ_R = D_Kᵀ Cᵀ λ_R), so that D_Kᵀ μ = Dᵀ λ.
        let mut mu = [T::ZERO; NC];
        for k in 0..rank {
            mu[k] = lambda[kept[k]];
        }
        for (j, i) in dropped.clone().enumerate() {
            for k in 0..rank {
                mu[k] += coupling[j][k] * lambda[i];
            }
        }
        // I + C Cᵀ (p × p, symmetric positive definite) in coupling[a][rank..rank + p], then its
        // Cholesky factor in place (lower triangle), then λ_R = (I + C Cᵀ)⁻¹ C μ.
        for a in 0..p {
            for b in 0..=a {
                let value = (0..rank).fold(if a == b { T::ONE } else { T::ZERO }, |s, k| s + coupling[a][k] * coupling[b][k]);
                coupling[a][rank + b] = value;
            }
        }
        for a in 0..p {
            for b in 0..=a {
                let mut value = coupling[a][rank + b];
                for k in 0..b {
                    value -= coupling[a][rank + k] * coupling[b][rank + k];
                }
                coupling[a][rank + b] = if a == b { value.sqrt() } else { value / coupling[b][rank + b] };
            }
        }
        let mut y = [T::ZERO; NC];
        for a in 0..p {
            let mut value = (0..rank).fold(T::ZERO, |s, k| s + coupling[a][k] * mu[k]);
            for k in 0..a {
                value -= coupling[a][rank + k] * y[k];
            }
            y[a] = value / coupling[a][rank + a];
        }
        for a in (0..p).rev() {
            let mut value = y[a];
            for k in a + 1..p {
                value -= coupling[k][rank + a] * y[k];
            }
            y[a] = value / coupling[a][rank + a];
        }
        // λ_K = μ − Cᵀ λ_R.
        for k in 0..rank {
            let folded = (0..p).fold(T::ZERO, |s, a| s + coupling[a][k] * y[a]);
            lambda[kept[k]] = mu[k] - folded;
        }
        for (j, i) in dropped.enumerate() {
            lambda[i] = y[j];
        }
        Ok(())
    }
}
