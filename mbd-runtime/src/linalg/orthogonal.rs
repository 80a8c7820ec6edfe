//! Rank-revealing orthogonalization of the rows of D (modified Gram–Schmidt, twice), and the
//! minimum-norm solves over the independent rows it finds: what the redundancy report, the
//! kinematic solver's redundant rows and inverse dynamics build on.

use super::dot;
use crate::real::Real;

/// What [`orthogonalize`] found: the rank and the margins of its decisions.
pub(crate) struct Split<T> {
    pub rank: usize,
    pub smallest_kept: T,
    pub largest_redundant: T,
}

/// The rows of `d` in order, each orthogonalized against the independent rows before it
/// (modified Gram–Schmidt, twice: "twice is enough", Giraud et al. 2005): a row whose sine of
/// angle to their span is at most `tolerance` is marked in `redundant`; the others become the
/// orthonormal `basis` rows 0..rank, and row j of `r` holds the j-th kept row's coordinates in
/// that basis (lower triangular: D_kept = R Q).
pub(crate) fn orthogonalize<T: Real, const NV: usize, const NC: usize>(
    d: &[[T; NV]; NC],
    tolerance: T,
    basis: &mut [[T; NV]; NC],
    r: &mut [[T; NC]; NC],
    redundant: &mut [bool; NC],
) -> Split<T> {
    let mut split = Split { rank: 0, smallest_kept: T::ONE, largest_redundant: T::ZERO };
    for (i, row) in d.iter().enumerate() {
        let length = norm(row);
        let mut w = *row;
        let mut coefficients = [T::ZERO; NC];
        for _ in 0..2 {
            for (b, c) in basis.iter().take(split.rank).zip(coefficients.iter_mut()) {
                let projection = dot(b, &w);
                *c += projection;
                for (wi, &bi) in w.iter_mut().zip(b.iter()) {
                    *wi -= projection * bi;
                }
            }
        }
        let left = norm(&w);
        let sine = if length > T::ZERO { left / length } else { T::ZERO };
        if sine > tolerance {
            for (bi, &wi) in basis[split.rank].iter_mut().zip(w.iter()) {
                *bi = wi / left;
            }
            coefficients[split.rank] = left;
            r[split.rank] = coefficients;
            split.rank += 1;
            if sine < split.smallest_kept {
                split.smallest_kept = sine;
            }
            redundant[i] = false;
        } else {
            redundant[i] = true;
            split.largest_redundant = split.largest_redundant.max(sine);
        }
    }
    split
}

/// The minimum-norm Newton step over the independent rows: D_I Δv = −Φ_I with Δv in the span of
/// D_I's rows, the rows that depend on earlier ones (sine ≤ `tolerance`) left out — for a
/// consistent redundant constraint, meeting the others meets it too.
/// `basis` and `r` are work space.
pub(crate) fn rank_revealing_step<T: Real, const NV: usize, const NC: usize>(
    d: &[[T; NV]; NC],
    negative_residual: &[T; NC],
    tolerance: T,
    basis: &mut [[T; NV]; NC],
    r: &mut [[T; NC]; NC],
    step: &mut [T; NV],
) {
    let mut redundant = [false; NC];
    let split = orthogonalize(d, tolerance, basis, r, &mut redundant);
    solve_orthogonalized(basis, r, &redundant, split.rank, negative_residual, step);
}

/// x = Qᵀ y with R y = b over the kept rows (forward substitution): the minimum-norm solution of
/// D_I x = b_I from what [`orthogonalize`] left in `basis` (Q) and `r` (R); the unique one when
/// the kept rows number NV.
pub(crate) fn solve_orthogonalized<T: Real, const NV: usize, const NC: usize>(
    basis: &[[T; NV]; NC],
    r: &[[T; NC]; NC],
    redundant: &[bool; NC],
    rank: usize,
    b: &[T; NC],
    x: &mut [T; NV],
) {
    let mut y = [T::ZERO; NC];
    let kept = (0..NC).filter(|&i| !redundant[i]);
    for (j, i) in kept.enumerate() {
        let mut value = b[i];
        for k in 0..j {
            value -= r[j][k] * y[k];
        }
        y[j] = value / r[j][j];
    }
    *x = [T::ZERO; NV];
    for (q, &yj) in basis.iter().take(rank).zip(y.iter()) {
        for (s, &qi) in x.iter_mut().zip(q.iter()) {
            *s += yj * qi;
        }
    }
}

/// The velocity least in the span of the first `rank` orthonormal rows of `basis`: the largest
/// 1 − Σ_k Q_kj² — what independent rows fewer than NV leave undetermined, for an error to name.
pub(crate) fn least_determined<T: Real, const NV: usize, const NC: usize>(basis: &[[T; NV]; NC], rank: usize) -> usize {
    (0..NV)
        .map(|j| (j, T::ONE - basis.iter().take(rank).fold(T::ZERO, |s, row| s + row[j] * row[j])))
        .fold((0, T::ZERO - T::ONE), |best, (j, left)| if left > best.1 { (j, left) } else { best })
        .0
}

fn norm<T: Real, const N: usize>(a: &[T; N]) -> T {
    dot(a, a).sqrt()
}
