//! Dense linear algebra on fixed-size arrays, for the kinematic solvers: LU factorization with
//! partial (row) pivoting and forward/back substitution. Nothing allocates and nothing panics
//! on bad numbers: failures are returned as [`LinalgError`]. Internal: a user reaches
//! [`LinalgError`] and the planned sparse LU (`crate::sparse`) at the crate root.
//!
//! # When is a pivot too small?
//!
//! At elimination step `k` the candidate pivot is the entry of largest magnitude in column `k`
//! among the rows not yet used. It is accepted when
//!
//! ```text
//! |candidate| > τ · max_i |a_ik|        (max over column k of the ORIGINAL matrix)
//! ```
//!
//! with `τ` the relative tolerance. The reference is the original column, not the whole matrix,
//! because columns are the unknowns and their scales differ the most: in a constraint Jacobian a
//! column holds the derivatives with respect to one coordinate, in m or in rad, and multiplying
//! an unknown by a constant (changing its unit) scales its column and nothing else. A
//! column-relative test gives the same verdict in any units. A column that has been cancelled to
//! rounding noise by the previous steps is, to that precision, a linear combination of the
//! columns before it; a column of exact zeros (an unknown that no equation involves) always fails.
//!
//! Failure reports the step `k` (which is also the column, since only rows are exchanged) and the
//! original index of the row holding the best candidate: the first row of largest magnitude among
//! the rows not yet used, in their current (permuted) order.

pub(crate) mod orthogonal;
pub mod sparse;

use crate::real::Real;
use core::fmt;

/// Why a factorization or solve failed. Indices are 0-based.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LinalgError {
    /// No acceptable pivot at elimination step `column`: column `column` is, to the relative
    /// tolerance, a linear combination of the columns before it.
    Singular {
        /// The elimination step that failed, which is also the column without a pivot.
        column: usize,
        /// Original index of the row holding the best (largest-magnitude) candidate pivot.
        candidate_row: usize,
    },
    /// The matrix holds a NaN or an infinity at (`row`, `column`).
    NonFinite {
        /// Row of the first non-finite entry (row-major scan).
        row: usize,
        /// Column of that entry.
        column: usize,
    },
    /// An LU factorization or solve was asked of a `rows × columns` matrix with rows ≠ columns.
    NotSquare {
        /// Rows of the matrix.
        rows: usize,
        /// Columns of the matrix.
        columns: usize,
    },
    /// A minimum-norm solve was asked of a system with more equations than unknowns
    /// (redundant or contradictory equations); no least-squares solution is attempted.
    Overdetermined {
        /// Equations (rows of D).
        rows: usize,
        /// Unknowns (columns of D).
        columns: usize,
    },
}

impl fmt::Display for LinalgError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            LinalgError::Singular { column, candidate_row } => {
                write!(f, "singular matrix: no acceptable pivot in column {column} (best candidate in row {candidate_row})")
            }
            LinalgError::NonFinite { row, column } => {
                write!(f, "non-finite matrix entry (NaN or ±∞) at row {row}, column {column}")
            }
            LinalgError::NotSquare { rows, columns } => {
                write!(f, "LU factorization needs a square matrix, got {rows} × {columns}")
            }
            LinalgError::Overdetermined { rows, columns } => {
                write!(f, "overdetermined system: {rows} equations for {columns} unknowns (redundant equations are not supported)")
            }
        }
    }
}

impl core::error::Error for LinalgError {}

/// The arrays an LU factorization of an R × C matrix works in besides the matrix: the row
/// interchanges it records, which the solves read, and two columns' worth of scratch. They come
/// from the caller (a [`crate::Workspace`]'s index rows and vectors), so that a large matrix's
/// factorization does not put O(N) arrays on the stack.
pub(crate) struct LuWork<'a, T, const R: usize, const C: usize> {
    /// Written: step k exchanged rows k and `pivots[k]` ≥ k (LAPACK's `ipiv`), P their product.
    pub(crate) pivots: &'a mut [usize; R],
    /// Scratch: the pivot row's non-zero columns.
    pub(crate) columns: &'a mut [usize; C],
    /// Scratch: the largest magnitude of each column of the original matrix.
    pub(crate) scale: &'a mut [T; C],
}

/// The original row at `position` of the factors after the first `steps` interchanges of
/// `pivots`: the interchanges undone in reverse (O(steps), for error reports).
pub(crate) fn original_row<const R: usize>(pivots: &[usize; R], steps: usize, position: usize) -> usize {
    pivots[..steps].iter().enumerate().rev().fold(position, |p, (k, &swapped)| {
        if p == k {
            swapped
        } else if p == swapped {
            k
        } else {
            p
        }
    })
}

/// The first non-finite entry of a matrix in row-major order, as (row, column).
fn first_non_finite<T: Real, const R: usize, const C: usize>(a: &[[T; C]; R]) -> Option<(usize, usize)> {
    a.iter().enumerate().find_map(|(i, row)| row.iter().position(|v| !v.is_finite()).map(|j| (i, j)))
}

/// LU factorization with partial pivoting, in place: P A = L U for a square `A` (`R == C`;
/// the two sizes are separate so that a constraint Jacobian typed `[[T; NQ]; NC]` can be
/// factored where it lies when NQ = NC).
///
/// On success `a` holds U on and above the diagonal and the multipliers of the unit
/// lower-triangular L below it, and `work.pivots` the interchanges that make P. `relative_tolerance` is
/// τ of the module's pivot test (|pivot| > τ · max |original column|); a negative or NaN τ is
/// taken as 0, so only exactly-zero pivots are rejected.
///
/// # Errors
/// [`LinalgError::NotSquare`] if `R ≠ C`; [`LinalgError::NonFinite`] if `a` holds a NaN or an
/// infinity (checked before anything is modified); [`LinalgError::Singular`] at the first step
/// without an acceptable pivot, leaving `a` partly eliminated.
pub(crate) fn lu_factor<T: Real, const R: usize, const C: usize>(
    a: &mut [[T; C]; R],
    relative_tolerance: T,
    work: LuWork<'_, T, R, C>,
) -> Result<(), LinalgError> {
    if R != C {
        return Err(LinalgError::NotSquare { rows: R, columns: C });
    }
    if let Some((row, column)) = first_non_finite(a) {
        return Err(LinalgError::NonFinite { row, column });
    }
    let LuWork { pivots, columns, scale: column_scale } = work;
    let tolerance = if relative_tolerance > T::ZERO { relative_tolerance } else { T::ZERO };
    // Largest magnitude of each column of the original matrix: the pivot test's reference.
    column_scale.fill(T::ZERO);
    for row in a.iter() {
        for (scale, value) in column_scale.iter_mut().zip(row.iter()) {
            *scale = scale.max(value.abs());
        }
    }
    // R == C from here on, so every a[i][k] and column_scale[k] below is in bounds.
    for k in 0..R {
        let mut best_row = k;
        let mut best = a[k][k].abs();
        for (i, row) in a.iter().enumerate().skip(k + 1) {
            let magnitude = row[k].abs();
            if magnitude > best {
                best = magnitude;
                best_row = i;
            }
        }
        let acceptable = best > tolerance * column_scale[k];
        if !acceptable {
            return Err(LinalgError::Singular { column: k, candidate_row: original_row(pivots, k, best_row) });
        }
        pivots[k] = best_row;
        if best_row != k {
            // `swap_with_slice`, not `a.swap`: the latter moved whole rows through three `memcpy`
            // calls even for k = best_row, a tenth of a small generalized-α step (17 × 17 saddle
            // matrix, a swap per λ column).
            let (upper, lower) = a.split_at_mut(best_row);
            upper[k].swap_with_slice(&mut lower[0]);
        }
        let (done, remaining) = a.split_at_mut(k + 1);
        let pivot_row = &done[k];
        let pivot = pivot_row[k];
        // Mechanism matrices are sparse (Jacobians, KKT matrices): update only where the pivot
        // row has non-zeros, and only the rows with a non-zero in the pivot column. Exact zeros
        // skipped change no result; the cost falls from O(n³) towards O(n · fill).
        let mut n_columns = 0;
        for (j, &value) in pivot_row.iter().enumerate().skip(k + 1) {
            if value != T::ZERO {
                columns[n_columns] = j;
                n_columns += 1;
            }
        }
        for row in remaining.iter_mut() {
            if row[k] == T::ZERO {
                continue;
            }
            let multiplier = row[k] / pivot;
            row[k] = multiplier;
            for &j in &columns[..n_columns] {
                row[j] -= multiplier * pivot_row[j];
            }
        }
    }
    Ok(())
}

/// Forward then back substitution in place (`x` holds b, becomes the solution) with factors
/// from [`lu_factor`]: P applied as its interchanges, then L y = P b, then U x = y. Callers
/// guarantee `R == C` (every index below is then in bounds).
fn substitute<T: Real, const R: usize, const C: usize>(lu: &[[T; C]; R], pivots: &[usize; R], x: &mut [T; C]) {
    for (k, &swapped) in pivots.iter().enumerate() {
        x.swap(k, swapped);
    }
    // L y = P b (L unit lower-triangular); y is stored in x.
    for i in 0..R {
        let mut sum = x[i];
        for (l, &y) in lu[i].iter().zip(x.iter()).take(i) {
            sum -= *l * y;
        }
        x[i] = sum;
    }
    // U x = y.
    for i in (0..R).rev() {
        let mut sum = x[i];
        for (u, &xj) in lu[i].iter().zip(x.iter()).skip(i + 1) {
            sum -= *u * xj;
        }
        x[i] = sum / lu[i][i];
    }
}

/// Solves A x = b given the factors of A from [`lu_factor`]: x = U⁻¹ L⁻¹ P b, in the units of
/// b divided by those of A. `rhs` (length R) and `x` (length C) are separate arrays so that the
/// right-hand side of a constraint system (`[T; NC]`) and its solution (`[T; NQ]`) keep their
/// own types; see [`lu_solve_in_place`] for the square-typed form.
///
/// # Errors
/// [`LinalgError::NotSquare`] if `R ≠ C` (such factors cannot come from [`lu_factor`]).
pub(crate) fn lu_solve<T: Real, const R: usize, const C: usize>(
    lu: &[[T; C]; R],
    pivots: &[usize; R],
    rhs: &[T; R],
    x: &mut [T; C],
) -> Result<(), LinalgError> {
    if R != C {
        return Err(LinalgError::NotSquare { rows: R, columns: C });
    }
    x.copy_from_slice(rhs.as_slice());
    substitute(lu, pivots, x);
    Ok(())
}

/// Solves A x = b in place (`b` becomes x) given the factors of a square A from [`lu_factor`].
pub(crate) fn lu_solve_in_place<T: Real, const N: usize>(lu: &[[T; N]; N], pivots: &[usize; N], b: &mut [T; N]) {
    substitute(lu, pivots, b);
}

/// aᵀ b
pub(crate) fn dot<T: Real, const N: usize>(a: &[T; N], b: &[T; N]) -> T {
    a.iter().zip(b.iter()).fold(T::ZERO, |sum, (&x, &y)| sum + x * y)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Relative pivot tolerance used by the tests: the solver's default.
    const PIVOT_TOLERANCE: f64 = 1e-12;

    /// Factors from [`super::lu_factor`] with their interchanges, for the tests.
    #[derive(Debug)]
    struct Factored<const N: usize> {
        pivots: [usize; N],
    }

    impl<const N: usize> Factored<N> {
        /// Original row index at each position of the factors.
        fn original_rows(&self) -> [usize; N] {
            core::array::from_fn(|position| original_row(&self.pivots, N, position))
        }
    }

    /// [`super::lu_factor`] with its work arrays on the stack.
    fn lu_factor<T: Real, const R: usize, const C: usize>(a: &mut [[T; C]; R], tolerance: T) -> Result<Factored<R>, LinalgError> {
        let (mut pivots, mut columns, mut scale) = ([0; R], [0; C], [T::ZERO; C]);
        super::lu_factor(a, tolerance, LuWork { pivots: &mut pivots, columns: &mut columns, scale: &mut scale })?;
        Ok(Factored { pivots })
    }

    fn lu_solve_in_place<T: Real, const N: usize>(lu: &[[T; N]; N], factored: &Factored<N>, b: &mut [T; N]) {
        super::lu_solve_in_place(lu, &factored.pivots, b);
    }

    fn lu_solve<T: Real, const N: usize>(
        lu: &[[T; N]; N],
        factored: &Factored<N>,
        rhs: &[T; N],
        x: &mut [T; N],
    ) -> Result<(), LinalgError> {
        super::lu_solve(lu, &factored.pivots, rhs, x)
    }

    /// Deterministic xorshift64* generator: uniform values in [−1, 1), no external crate.
    struct Prng(u64);

    impl Prng {
        fn next_u64(&mut self) -> u64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
        }
        /// Uniform in [−1, 1): the top 53 bits as a fraction.
        fn uniform(&mut self) -> f64 {
            const MANTISSA_BITS: u32 = 53;
            let fraction = (self.next_u64() >> (64 - MANTISSA_BITS)) as f64 / (1u64 << MANTISSA_BITS) as f64;
            2.0 * fraction - 1.0
        }
        fn below(&mut self, n: usize) -> usize {
            (self.next_u64() % n as u64) as usize
        }
    }

    /// A well-conditioned N × N matrix whose rows are shuffled, so partial pivoting must
    /// exchange rows: the rows of (random in [−1, 1) + N·I), which is diagonally dominant and
    /// has condition number of order 1, in a random order. Returns the matrix and the order
    /// (`order[i]` = index of the diagonal-dominant row placed at row i).
    fn shuffled_dominant<const N: usize>(rng: &mut Prng) -> ([[f64; N]; N], [usize; N]) {
        let mut dominant = [[0.0; N]; N];
        for (i, row) in dominant.iter_mut().enumerate() {
            for v in row.iter_mut() {
                *v = rng.uniform();
            }
            row[i] += N as f64;
        }
        let mut order = [0; N];
        for (i, o) in order.iter_mut().enumerate() {
            *o = i;
        }
        for i in (1..N).rev() {
            order.swap(i, rng.below(i + 1));
        }
        let mut a = [[0.0; N]; N];
        for (row, &source) in a.iter_mut().zip(order.iter()) {
            *row = dominant[source];
        }
        (a, order)
    }

    fn multiply<const R: usize, const C: usize>(a: &[[f64; C]; R], x: &[f64; C]) -> [f64; R] {
        let mut b = [0.0; R];
        for (bi, row) in b.iter_mut().zip(a.iter()) {
            *bi = dot(row, x);
        }
        b
    }

    fn max_abs_difference(a: &[f64], b: &[f64]) -> f64 {
        a.iter().zip(b).fold(0.0, |m, (x, y)| m.max((x - y).abs()))
    }

    /// Random well-conditioned systems of several sizes: the solution is recovered to a few
    /// hundred ulps (the matrices have condition numbers of order 1 and entries of order N).
    #[test]
    fn solves_random_well_conditioned_systems() {
        fn check<const N: usize>(rng: &mut Prng) {
            for _ in 0..50 {
                let (a, _) = shuffled_dominant::<N>(rng);
                let mut x_true = [0.0; N];
                for v in x_true.iter_mut() {
                    *v = rng.uniform();
                }
                let b = multiply(&a, &x_true);
                let mut lu = a;
                let p = lu_factor(&mut lu, PIVOT_TOLERANCE).expect("well-conditioned");
                let mut x = b;
                lu_solve_in_place(&lu, &p, &mut x);
                let error = max_abs_difference(&x, &x_true);
                assert!(error < 1e-13, "N = {N}: |x − x_true| = {error:e}");
                let mut y = [0.0; N];
                lu_solve(&lu, &p, &b, &mut y).expect("square");
                assert_eq!(x, y, "both solve forms agree");
            }
        }
        let mut rng = Prng(0x9E37_79B9_7F4A_7C15);
        check::<1>(&mut rng);
        check::<2>(&mut rng);
        check::<5>(&mut rng);
        check::<9>(&mut rng);
        check::<24>(&mut rng);
    }

    #[test]
    #[allow(clippy::needless_range_loop)] // index notation mirrors Σ_k L_ik U_kj
    fn permutation_reconstructs_the_matrix() {
        const N: usize = 7;
        let mut rng = Prng(12345);
        for trial in 0..40 {
            // Plain random matrices: pivoting is exercised on every step. Then sparse ones (about
            // 60 % exact zeros off the diagonal, as in Jacobians and KKT matrices), which take
            // the factorization's zero-skipping paths.
            let mut a = [[0.0; N]; N];
            for (i, row) in a.iter_mut().enumerate() {
                for (j, v) in row.iter_mut().enumerate() {
                    *v = rng.uniform();
                    if trial >= 20 && i != j && rng.uniform().abs() < 0.6 {
                        *v = 0.0;
                    }
                }
            }
            let mut lu = a;
            let p = lu_factor(&mut lu, PIVOT_TOLERANCE).expect("random matrices are regular");
            let mut seen = [false; N];
            for &row in &p.original_rows() {
                assert!(!seen[row], "row {row} appears twice in {p:?}");
                seen[row] = true;
            }
            for (i, &original) in p.original_rows().iter().enumerate() {
                for j in 0..N {
                    // (L U)_ij = Σ_k L_ik U_kj with L_ii = 1.
                    let mut sum = 0.0;
                    for k in 0..=i.min(j) {
                        let l = if k == i { 1.0 } else { lu[i][k] };
                        sum += l * lu[k][j];
                    }
                    assert!((sum - a[original][j]).abs() < 1e-14, "(P A)[{i}][{j}]");
                }
                // Partial pivoting keeps every multiplier at most 1 in magnitude.
                assert!(lu[i].iter().take(i).all(|l| l.abs() <= 1.0));
            }
        }
    }

    /// Rows of a diagonally dominant matrix, shuffled: pivoting puts each back on the diagonal.
    #[test]
    fn pivoting_undoes_a_row_shuffle() {
        const N: usize = 6;
        let mut rng = Prng(777);
        for _ in 0..20 {
            let (mut a, order) = shuffled_dominant::<N>(&mut rng);
            let p = lu_factor(&mut a, PIVOT_TOLERANCE).expect("regular");
            // Position k of the factors must hold the row whose dominant entry is in column k.
            for (k, &original) in p.original_rows().iter().enumerate() {
                assert_eq!(order[original], k, "order {order:?}, permutation {p:?}");
            }
        }
        // The smallest case that needs a swap.
        let mut swap = [[0.0, 2.0], [3.0, 0.0]];
        let p = lu_factor(&mut swap, PIVOT_TOLERANCE).expect("regular");
        assert_eq!(p.original_rows(), [1, 0]);
        let mut b = [4.0, 9.0];
        lu_solve_in_place(&swap, &p, &mut b);
        assert_eq!(b, [3.0, 2.0]);
    }

    /// A row that is the sum of two others makes column 2 a combination of columns 0 and 1:
    /// the factorization stops at step 2 instead of dividing by rounding noise.
    #[test]
    fn detects_a_singular_matrix() {
        let mut a = [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [5.0, 7.0, 9.0]];
        match lu_factor(&mut a, PIVOT_TOLERANCE).map(|_| ()) {
            Err(LinalgError::Singular { column, candidate_row }) => {
                assert_eq!(column, 2);
                assert!(candidate_row < 3);
            }
            other => panic!("expected Singular, got {other:?}"),
        }
    }

    /// A zero column (an unknown no equation involves) fails at its own step; the candidate is
    /// the first remaining row.
    #[test]
    fn detects_a_zero_column() {
        let mut a = [[2.0, 0.0, 1.0], [0.0, 0.0, 3.0], [1.0, 0.0, 5.0]];
        assert_eq!(lu_factor(&mut a, PIVOT_TOLERANCE).map(|_| ()), Err(LinalgError::Singular { column: 1, candidate_row: 1 }));
    }

    /// The test is relative to each column: scaling an unknown by 10⁻⁹ (another unit) changes
    /// nothing, while the absolute size of a pivot would.
    #[test]
    fn pivot_test_is_invariant_to_column_scaling() {
        const TINY_UNIT: f64 = 1e-9;
        let mut a = [[1.0, 2.0 * TINY_UNIT], [3.0, 4.0 * TINY_UNIT]];
        let p = lu_factor(&mut a, PIVOT_TOLERANCE).expect("regular in any units");
        let mut x = [5.0, 6.0];
        lu_solve_in_place(&a, &p, &mut x);
        // Unscaled solution of [[1, 2], [3, 4]] x = [5, 6] is (−4, 4.5).
        assert!((x[0] + 4.0).abs() < 1e-12 && (x[1] * TINY_UNIT - 4.5).abs() < 1e-12, "{x:?}");
    }

    #[test]
    fn reports_non_finite_entries_and_shapes() {
        let mut a = [[1.0, 0.0], [f64::NAN, 1.0]];
        assert_eq!(lu_factor(&mut a, PIVOT_TOLERANCE).map(|_| ()), Err(LinalgError::NonFinite { row: 1, column: 0 }));
        let mut rectangular = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        assert_eq!(lu_factor(&mut rectangular, PIVOT_TOLERANCE).map(|_| ()), Err(LinalgError::NotSquare { rows: 2, columns: 3 }));
    }

    /// The same code in f32.
    #[test]
    fn works_in_f32() {
        let mut a: [[f32; 3]; 3] = [[0.0, 2.0, 1.0], [4.0, 1.0, 0.0], [1.0, 0.0, 3.0]];
        let x_true = [1.0f32, -2.0, 0.5];
        let mut b = [0.0f32; 3];
        for (bi, row) in b.iter_mut().zip(a.iter()) {
            *bi = dot(row, &x_true);
        }
        let p = lu_factor(&mut a, f32::EPSILON).expect("regular");
        lu_solve_in_place(&a, &p, &mut b);
        for (x, t) in b.iter().zip(x_true.iter()) {
            assert!((x - t).abs() < 1e-6, "{b:?}");
        }
    }
}
