//! The planned sparse LU (`crate::sparse` is its public face and holds the method's
//! documentation) and the helpers the generated factorizations call (`crate::__private`).

use crate::linalg::LinalgError;
use crate::real::Real;

/// The pattern of a Newton matrix's LU factors, planned by `mechanism!` at compile time.
///
/// Unknowns are numbered v̇ entries first (0..NV), then multipliers (NV..NV + NC); they are
/// factored in the order `unknown`. Row p of the factors (position p) holds its entries at
/// `row_start[p]..row_start[p + 1]` of the value array, columns (positions) ascending, fill-in
/// included: the part left of `diagonal[p]` is L (unit diagonal, not stored), the rest U.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SparsePattern {
    /// The unknown factored at each position.
    pub unknown: &'static [u32],
    /// The position of each unknown.
    pub position: &'static [u32],
    /// Where each row's entries start; one more than the positions, the last is the total.
    pub row_start: &'static [u32],
    /// The column (a position) of each entry.
    pub columns: &'static [u32],
    /// The index of each row's diagonal entry.
    pub diagonal: &'static [u32],
}

impl SparsePattern {
    /// Rows (and columns) of the matrix: NV + NC.
    pub const fn size(&self) -> usize {
        self.unknown.len()
    }

    /// Stored entries of L and U together, fill-in included.
    pub const fn entries(&self) -> usize {
        self.columns.len()
    }
}

/// The decision at one pivot, shared by [`factor`] and the factorizations `mechanism!`
/// generates: `Ok(true)` keeps it; `Ok(false)` drops the multiplier (the caller makes its row
/// the identity); an error names the unknown. `smallest_ratio` tracks the smallest ratio
/// pivot/scale of a kept multiplier. Velocities fail at |pivot| ≤ `tolerance` · `scale`,
/// multipliers at a ratio ≤ `tolerance` or when already marked in `dropped` (module docs).
/// The k-th pivot of the generated LDLᵀ of S = D M⁻¹ Dᵀ (`schur_factor`): (d_k, 1/d_k) for
/// d_k = S_kk − Σ_j L_kj² d_j, or `None` for a dependent row. A pivot above `exact` · τ S_kk
/// is taken as it is (one division). With `allow_redundant` a smaller one is weighted,
/// 1/d̂ = w/d with w = 1/(1 + ρ⁸), ρ = τ S_kk/d: the exact pivot where ρ ≪ 1 (relative change
/// ρ⁸), the row dropped (w → 0) as d → 0, smooth in between; ρ⁸ may overflow to ∞ (w = 0), never
/// to NaN. One call per pivot keeps the generated factorization short (a 240-body chain's was
/// 171 000 tokens with this logic written out at each of its 480 pivots).
#[doc(hidden)]
#[inline(always)]
pub fn schur_pivot<T: Real>(skk: T, dk: T, exact: T, tolerance: T, allow_redundant: bool) -> Option<(T, T)> {
    if dk > exact * tolerance * skk {
        Some((dk, T::ONE / dk))
    } else if allow_redundant && skk > T::ZERO && dk.is_finite() {
        if dk > T::ZERO {
            let rho = tolerance * skk / dk;
            let rho4 = (rho * rho) * (rho * rho);
            let w = T::ONE / (T::ONE + rho4 * rho4);
            Some((if w > T::ZERO { dk / w } else { T::ZERO }, w / dk))
        } else {
            Some((T::ZERO, T::ZERO))
        }
    } else {
        None
    }
}

/// A span of a fixed-size array as an array, by reference, for the element bindings of
/// generated code (`let [__l_5, __l_6] = l.window_mut::<5, 2>();`): rustc type-checks a
/// pattern once where it checks every index expression on its own, at about 100 µs each. A
/// method, so that one call serves a local array and a reference to one alike (the receiver
/// is auto-referenced or auto-dereferenced).
#[doc(hidden)]
pub trait Elements<T, const N: usize> {
    /// The whole array.
    fn all(&self) -> &[T; N];
    /// The whole array, mutable.
    fn all_mut(&mut self) -> &mut [T; N];
    /// Elements K..K + M.
    fn window<const K: usize, const M: usize>(&self) -> &[T; M];
    /// Elements K..K + M, mutable.
    fn window_mut<const K: usize, const M: usize>(&mut self) -> &mut [T; M];
}

impl<T, const N: usize> Elements<T, N> for [T; N] {
    #[inline(always)]
    fn all(&self) -> &[T; N] {
        self
    }
    #[inline(always)]
    fn all_mut(&mut self) -> &mut [T; N] {
        self
    }
    #[inline(always)]
    fn window<const K: usize, const M: usize>(&self) -> &[T; M] {
        const { assert!(K + M <= N, "a window past the array's end") };
        // SAFETY: elements K..K + M lie within the array (the assertion above is evaluated
        // when the method is instantiated, so a window past the end does not compile), and
        // [T; M] has T's alignment and M·size_of::<T>() bytes, the layout of those elements.
        unsafe { &*self.as_ptr().add(K).cast::<[T; M]>() }
    }
    #[inline(always)]
    fn window_mut<const K: usize, const M: usize>(&mut self) -> &mut [T; M] {
        const { assert!(K + M <= N, "a window past the array's end") };
        // SAFETY: as in `window`; the exclusive borrow of the array covers the elements.
        unsafe { &mut *self.as_mut_ptr().add(K).cast::<[T; M]>() }
    }
}

/// x ← x + Δx, one step of iterative refinement in the kinematic velocity and acceleration
/// solves and inverse dynamics' multipliers that `mechanism!` generates (x = Dᵀ(D Dᵀ)⁻¹ b or
/// λ = (D Dᵀ)⁻¹ D b through the planned LDLᵀ of D Dᵀ, whose relative error is about κ(D)² ε,
/// refined on the residual b − D x or b − Dᵀλ): true when the step was
/// small enough to end the refinement, ‖Δx‖∞ ≤ √ε ‖x‖∞ with x and Δx finite. A step of
/// relative size ρ measures the error it corrects, and the solve that made it errs by about ρ
/// of itself, so about ρ² ≤ ε is left: what an LU of D leaves, κ(D) ε, once κ(D)² ε < 1.
#[doc(hidden)]
#[inline]
pub fn refine<T: Real, const N: usize>(x: &mut [T; N], dx: &[T; N]) -> bool {
    for (xi, &d) in x.iter_mut().zip(dx) {
        *xi += d;
    }
    let (size, finite_x) = max_abs_finite(x);
    let (step, finite_dx) = max_abs_finite(dx);
    finite_x && finite_dx && step <= T::EPSILON.sqrt() * size
}

/// The most corrections [`refined`] makes. Each multiplies the error by about κ(D)² ε, the
/// relative accuracy of the solve through the normal equations, so a few suffice wherever
/// κ(D)² ε ≪ 1; where it is not, more corrections would not settle either.
pub const REFINEMENTS: u32 = 4;

/// Iterative refinement of a solve x ≈ A⁻¹ b, the loop written once for the kinematic solves
/// and inverse dynamics' multipliers that `mechanism!` generates: `correction(x, dx)` writes
/// into `dx` (zeroed) the correction of x solved on its residual, dx ≈ A⁻¹(b − A x), and x takes
/// it ([`refine`]), at most [`REFINEMENTS`] times. True when a correction was small enough to
/// stop; false when none was (the solve is then left to the dense LU, which names the row).
#[doc(hidden)]
#[inline]
pub fn refined<T: Real, const N: usize>(x: &mut [T; N], mut correction: impl FnMut(&[T; N], &mut [T; N])) -> bool {
    for _ in 0..REFINEMENTS {
        let mut dx = [T::ZERO; N];
        correction(x, &mut dx);
        if refine(x, &dx) {
            return true;
        }
    }
    false
}

/// (max_i |x_i|, whether every x_i is finite): the convergence test of the Newton loops
/// `mechanism!` generates. Four running maxima over interleaved entries, so that their
/// comparisons do not wait on one another: a single running `max` with NaN handling made the
/// test of a 48-row Φ a chain of 48 dependent compare-and-selects, a fifth of the chain of 16's
/// position solve. Where an entry is not finite the maximum is meaningless (NaN is ignored by
/// the comparisons), and the flag says so.
#[doc(hidden)]
#[inline(always)]
pub fn max_abs_finite<T: Real>(x: &[T]) -> (T, bool) {
    let mut worst = [T::ZERO; 4];
    let mut finite = true;
    let mut chunks = x.chunks_exact(4);
    for chunk in &mut chunks {
        for (w, &v) in worst.iter_mut().zip(chunk) {
            let a = v.abs();
            if a > *w {
                *w = a;
            }
            finite &= v.is_finite();
        }
    }
    for (w, &v) in worst.iter_mut().zip(chunks.remainder()) {
        let a = v.abs();
        if a > *w {
            *w = a;
        }
        finite &= v.is_finite();
    }
    let pair = |a: T, b: T| if a > b { a } else { b };
    (pair(pair(worst[0], worst[1]), pair(worst[2], worst[3])), finite)
}

/// Damped Newton: a step longer than `max_step` in ‖·‖∞ is scaled down to it, its direction
/// kept ([`crate::KinematicOptions::max_step`]). The step is finite (checked before).
#[doc(hidden)]
#[inline]
pub fn limit_step<T: Real>(step: &mut [T], max_step: T) {
    let (size, _) = max_abs_finite(step);
    if size > max_step {
        let scale = max_step / size;
        for x in step.iter_mut() {
            *x *= scale;
        }
    }
}

#[doc(hidden)]
#[allow(clippy::too_many_arguments)]
#[inline]
pub fn pivot<T: Real>(
    pivot: T,
    scale: T,
    unknown: usize,
    nv: usize,
    tolerance: T,
    allow_redundant: bool,
    dropped: &mut [bool],
    smallest_ratio: &mut T,
) -> Result<bool, LinalgError> {
    if !pivot.is_finite() {
        return Err(LinalgError::NonFinite { row: unknown, column: unknown });
    }
    if unknown < nv {
        return if pivot.abs() > tolerance * scale {
            Ok(true)
        } else {
            Err(LinalgError::Singular { column: unknown, candidate_row: unknown })
        };
    }
    let r = unknown - nv;
    let ratio = pivot.abs() / scale;
    if !dropped[r] && ratio > tolerance {
        if ratio < *smallest_ratio {
            *smallest_ratio = ratio;
        }
        return Ok(true);
    }
    if !allow_redundant {
        return Err(LinalgError::Singular { column: unknown, candidate_row: unknown });
    }
    dropped[r] = true;
    Ok(false)
}

/// Factors `a` (the values over `pattern`, L and U overwriting them) without row exchanges;
/// returns the smallest pivot ratio of a kept multiplier (1 without multipliers): how close the
/// kept rows of D are to depending on each other.
///
/// `nv` is the number of velocity unknowns. A velocity whose pivot is at most `tolerance` times
/// the largest entry of its original row fails with [`LinalgError::Singular`] (its unknown as
/// the column). A multiplier whose pivot ratio (module docs) is at most `tolerance`, or that is
/// already marked in `dropped`, is dropped when `allow_redundant` (its row becomes the identity,
/// so with a zero right-hand side Δλ_r = 0, and `dropped[r]` is set) and fails otherwise. A
/// non-finite entry or pivot fails with [`LinalgError::NonFinite`] naming its row's unknown.
pub fn factor<T: Real>(
    pattern: &SparsePattern,
    a: &mut [T],
    nv: usize,
    tolerance: T,
    allow_redundant: bool,
    dropped: &mut [bool],
) -> Result<T, LinalgError> {
    let SparsePattern { unknown, row_start, columns, diagonal, .. } = *pattern;
    let mut smallest_ratio = T::ONE;
    for i in 0..unknown.len() {
        let (start, diag, end) = (row_start[i] as usize, diagonal[i] as usize, row_start[i + 1] as usize);
        let u = unknown[i] as usize;
        // The row's scale from its original entries: for a multiplier Σ D_rc²/|u_cc| over the
        // velocities before it, for a velocity its largest entry.
        let mut scale = T::ZERO;
        for p in start..end {
            let x = a[p];
            if !x.is_finite() {
                return Err(LinalgError::NonFinite { row: u, column: unknown[columns[p] as usize] as usize });
            }
            if u >= nv {
                if p < diag {
                    scale += x * x / a[diagonal[columns[p] as usize] as usize].abs();
                }
            } else {
                scale = scale.max(x.abs());
            }
        }
        // Eliminate with each row k before this one that the row reaches: l_ik = a_ik / u_kk,
        // then a_ij −= l_ik u_kj for k's entries right of its diagonal (all in this row's
        // pattern, by the planned fill).
        for p in start..diag {
            let k = columns[p] as usize;
            let l = a[p] / a[diagonal[k] as usize];
            a[p] = l;
            if l == T::ZERO {
                continue;
            }
            let mut target = p + 1;
            for s in diagonal[k] as usize + 1..row_start[k + 1] as usize {
                let j = columns[s];
                while columns[target] != j {
                    target += 1;
                }
                a[target] -= l * a[s];
            }
        }
        if !pivot(a[diag], scale, u, nv, tolerance, allow_redundant, dropped, &mut smallest_ratio)? {
            for x in &mut a[start..end] {
                *x = T::ZERO;
            }
            a[diag] = T::ONE;
        }
    }
    Ok(smallest_ratio)
}

/// Solves L U x = b in place with the factors from [`factor`]; `b` indexed by unknown (v̇
/// entries, then multipliers), as the residuals are, so nothing is permuted.
pub fn solve<T: Real>(pattern: &SparsePattern, lu: &[T], b: &mut [T]) {
    let SparsePattern { unknown, row_start, columns, diagonal, .. } = *pattern;
    let n = diagonal.len();
    for i in 0..n {
        let mut x = b[unknown[i] as usize];
        for p in row_start[i] as usize..diagonal[i] as usize {
            x -= lu[p] * b[unknown[columns[p] as usize] as usize];
        }
        b[unknown[i] as usize] = x;
    }
    for i in (0..n).rev() {
        let diag = diagonal[i] as usize;
        let mut x = b[unknown[i] as usize];
        for p in diag + 1..row_start[i + 1] as usize {
            x -= lu[p] * b[unknown[columns[p] as usize] as usize];
        }
        b[unknown[i] as usize] = x / lu[diag];
    }
}

/// [`factor`] of a complex matrix, its real and imaginary parts in `re` and `im` over the same
/// pattern (the complex block of the Radau IIA iteration, [`crate::Radau5`]): the same
/// elimination without row exchanges, the pivot tests on moduli. `dropped` holds the rows the
/// real factorization of the same D dropped; they are dropped here too.
pub fn factor_complex<T: Real>(
    pattern: &SparsePattern,
    re: &mut [T],
    im: &mut [T],
    nv: usize,
    tolerance: T,
    allow_redundant: bool,
    dropped: &mut [bool],
) -> Result<T, LinalgError> {
    let SparsePattern { unknown, row_start, columns, diagonal, .. } = *pattern;
    let modulus = |a: T, b: T| (a * a + b * b).sqrt();
    let mut smallest_ratio = T::ONE;
    for i in 0..unknown.len() {
        let (start, diag, end) = (row_start[i] as usize, diagonal[i] as usize, row_start[i + 1] as usize);
        let u = unknown[i] as usize;
        let mut scale = T::ZERO;
        for p in start..end {
            let (x, y) = (re[p], im[p]);
            if !(x.is_finite() && y.is_finite()) {
                return Err(LinalgError::NonFinite { row: u, column: unknown[columns[p] as usize] as usize });
            }
            if u >= nv {
                if p < diag {
                    let d = diagonal[columns[p] as usize] as usize;
                    scale += (x * x + y * y) / modulus(re[d], im[d]);
                }
            } else {
                scale = scale.max(modulus(x, y));
            }
        }
        for p in start..diag {
            let k = columns[p] as usize;
            let d = diagonal[k] as usize;
            // l = a_ik / u_kk, complex.
            let den = re[d] * re[d] + im[d] * im[d];
            let (lr, li) = ((re[p] * re[d] + im[p] * im[d]) / den, (im[p] * re[d] - re[p] * im[d]) / den);
            (re[p], im[p]) = (lr, li);
            if lr == T::ZERO && li == T::ZERO {
                continue;
            }
            let mut target = p + 1;
            for s in d + 1..row_start[k + 1] as usize {
                let j = columns[s];
                while columns[target] != j {
                    target += 1;
                }
                re[target] -= lr * re[s] - li * im[s];
                im[target] -= lr * im[s] + li * re[s];
            }
        }
        if !pivot(modulus(re[diag], im[diag]), scale, u, nv, tolerance, allow_redundant, dropped, &mut smallest_ratio)? {
            re[start..end].fill(T::ZERO);
            im[start..end].fill(T::ZERO);
            re[diag] = T::ONE;
        }
    }
    Ok(smallest_ratio)
}

/// [`solve`] with the complex factors of [`factor_complex`]: `b` = `b_re` + i `b_im`, in place.
pub fn solve_complex<T: Real>(pattern: &SparsePattern, re: &[T], im: &[T], b_re: &mut [T], b_im: &mut [T]) {
    let SparsePattern { unknown, row_start, columns, diagonal, .. } = *pattern;
    let n = diagonal.len();
    for i in 0..n {
        let ui = unknown[i] as usize;
        let (mut x, mut y) = (b_re[ui], b_im[ui]);
        for p in row_start[i] as usize..diagonal[i] as usize {
            let j = unknown[columns[p] as usize] as usize;
            x -= re[p] * b_re[j] - im[p] * b_im[j];
            y -= re[p] * b_im[j] + im[p] * b_re[j];
        }
        (b_re[ui], b_im[ui]) = (x, y);
    }
    for i in (0..n).rev() {
        let ui = unknown[i] as usize;
        let diag = diagonal[i] as usize;
        let (mut x, mut y) = (b_re[ui], b_im[ui]);
        for p in diag + 1..row_start[i + 1] as usize {
            let j = unknown[columns[p] as usize] as usize;
            x -= re[p] * b_re[j] - im[p] * b_im[j];
            y -= re[p] * b_im[j] + im[p] * b_re[j];
        }
        let den = re[diag] * re[diag] + im[diag] * im[diag];
        (b_re[ui], b_im[ui]) = ((x * re[diag] + y * im[diag]) / den, (y * re[diag] - x * im[diag]) / den);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2 × 2 system solved with an inverse 0.01 % too small: each correction divides the
    /// error by 10⁴, so the third is below √ε of x and x is exact to 1e-11; an inverse 150 %
    /// too large makes the error grow and is refused.
    #[test]
    fn refined_corrects_an_inaccurate_solve_and_refuses_a_divergent_one() {
        let (a, b) = ([[4.0, 1.0], [1.0, 3.0]], [1.0, 2.0]);
        let exact = [1.0 / 11.0, 7.0 / 11.0];
        let solve_with = |scale: f64| {
            move |x: &[f64; 2], dx: &mut [f64; 2]| {
                let r = [b[0] - a[0][0] * x[0] - a[0][1] * x[1], b[1] - a[1][0] * x[0] - a[1][1] * x[1]];
                // The exact inverse, scaled.
                dx[0] = scale * (3.0 * r[0] - r[1]) / 11.0;
                dx[1] = scale * (4.0 * r[1] - r[0]) / 11.0;
            }
        };
        let mut x = [0.0; 2];
        assert!(refined(&mut x, solve_with(0.9999)));
        assert!((x[0] - exact[0]).abs() < 1e-11 && (x[1] - exact[1]).abs() < 1e-11, "{x:?}");
        let mut x = [0.0; 2];
        assert!(!refined(&mut x, solve_with(2.5)));
    }

    /// [[2, 0, −1], [0, 3, −2], [1, 2, 0]]: two velocities and one multiplier, identity order,
    /// dense pattern.
    const PATTERN: SparsePattern = SparsePattern {
        unknown: &[0, 1, 2],
        position: &[0, 1, 2],
        row_start: &[0, 3, 6, 9],
        columns: &[0, 1, 2, 0, 1, 2, 0, 1, 2],
        diagonal: &[0, 4, 8],
    };

    fn matrix() -> [f64; 9] {
        [2.0, 0.0, -1.0, 0.0, 3.0, -2.0, 1.0, 2.0, 0.0]
    }

    #[test]
    fn windows_are_the_spans_they_name() {
        let mut a = [0.0, 1.0, 2.0, 3.0, 4.0];
        assert_eq!(a.window::<1, 3>(), &[1.0, 2.0, 3.0]);
        assert_eq!(a.window::<0, 5>(), &a);
        let [x, y] = a.window_mut::<3, 2>();
        (*x, *y) = (-3.0, -4.0);
        assert_eq!(a, [0.0, 1.0, 2.0, -3.0, -4.0]);
        let r = &mut a;
        assert_eq!(r.window::<4, 1>(), &[-4.0]);
    }

    #[test]
    fn max_abs_finite_is_the_largest_magnitude_and_sees_every_non_finite_entry() {
        for n in 0..11 {
            let x: Vec<f64> = (0..n).map(|i| ((i * 7) % 5) as f64 - 2.5 * (i % 2) as f64).collect();
            let expected = x.iter().fold(0.0_f64, |w, v| w.max(v.abs()));
            assert_eq!(max_abs_finite(&x), (expected, true), "{x:?}");
            for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                for k in 0..n {
                    let mut y = x.clone();
                    y[k] = bad;
                    assert!(!max_abs_finite(&y).1, "{y:?}");
                }
            }
        }
        assert_eq!(max_abs_finite(&[-3.0_f32, 1.0, 2.0, -0.5, 7.5]), (7.5, true));
    }

    #[test]
    fn solves_a_saddle_system() {
        let mut a = matrix();
        let smallest_ratio = factor(&PATTERN, &mut a, 2, 1e-13, false, &mut [false]).unwrap();
        // The multiplier's pivot: D A⁻¹ Dᵀ = 1/2 + 4/3 against its scale, the same sum.
        assert_eq!(smallest_ratio, 1.0);
        let x = [1.0, -2.0, 0.5];
        let a0 = matrix();
        let mut b: [f64; 3] = core::array::from_fn(|i| (0..3).map(|j| a0[3 * i + j] * x[j]).sum());
        solve(&PATTERN, &a, &mut b);
        for i in 0..3 {
            assert!((b[i] - x[i]).abs() < 1e-14, "{b:?}");
        }
    }

    /// The saddle matrix plus i times another of the same pattern: the complex factors solve
    /// (A + iB) x = b for a complex x, checked by multiplying back (rounding: 1e-14).
    #[test]
    fn solves_a_complex_saddle_system() {
        let (a0, b0) = (matrix(), [0.5, 0.0, 0.0, 0.0, -1.5, 0.0, 0.0, 0.0, 0.0]);
        let (mut re, mut im) = (a0, b0);
        factor_complex(&PATTERN, &mut re, &mut im, 2, 1e-13, false, &mut [false]).unwrap();
        let (x_re, x_im) = ([1.0, -2.0, 0.5], [0.25, 3.0, -1.0]);
        let product = |i: usize| -> (f64, f64) {
            (0..3).fold((0.0, 0.0), |(r, m), j| {
                let (a, b) = (a0[3 * i + j], b0[3 * i + j]);
                (r + a * x_re[j] - b * x_im[j], m + a * x_im[j] + b * x_re[j])
            })
        };
        let (mut b_re, mut b_im): ([f64; 3], [f64; 3]) = (core::array::from_fn(|i| product(i).0), core::array::from_fn(|i| product(i).1));
        solve_complex(&PATTERN, &re, &im, &mut b_re, &mut b_im);
        for i in 0..3 {
            assert!((b_re[i] - x_re[i]).abs() < 1e-14 && (b_im[i] - x_im[i]).abs() < 1e-14, "{b_re:?} {b_im:?}");
        }
    }

    #[test]
    fn a_dependent_multiplier_is_dropped_or_named() {
        // D = 0: the multiplier's row has no pivot at all.
        let zero_d = || [2.0, 0.0, 0.0, 0.0, 3.0, 0.0, 0.0, 0.0, 0.0];
        let mut dropped = [false];
        let mut a = zero_d();
        assert!(matches!(factor(&PATTERN, &mut a, 2, 1e-13, false, &mut dropped), Err(LinalgError::Singular { column: 2, .. })));
        // Its scale is 0, so the ratio is NaN, which is not above the tolerance either.
        let mut a = zero_d();
        factor(&PATTERN, &mut a, 2, 1e-13, true, &mut dropped).unwrap();
        assert_eq!(dropped, [true]);
        let mut b = [2.0, 3.0, 0.0];
        solve(&PATTERN, &a, &mut b);
        assert_eq!(b, [1.0, 1.0, 0.0]);
    }

    #[test]
    fn a_velocity_without_pivot_is_named() {
        let mut a = matrix();
        a[4] = 0.0;
        a[5] = 0.0;
        a[7] = 0.0;
        assert_eq!(factor(&PATTERN, &mut a, 2, 1e-13, true, &mut [false]), Err(LinalgError::Singular { column: 1, candidate_row: 1 }));
        let mut a = matrix();
        a[7] = f64::NAN;
        assert_eq!(factor(&PATTERN, &mut a, 2, 1e-13, true, &mut [false]), Err(LinalgError::NonFinite { row: 2, column: 1 }));
    }
}
