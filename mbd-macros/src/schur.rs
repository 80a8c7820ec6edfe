//! Straight-line sparse solves with S = Φ_q M⁻¹ Φ_qᵀ, the Schur complement of the equations of
//! motion, whose sparsity is fixed by the Jacobian's pattern.
//!
//! With M diagonal, S_ij = Σ_c D_ic D_jc / m_c is structurally non-zero exactly when rows i and j
//! of D share a velocity; a spatial body with products of inertia adds the off-diagonal entries
//! of its block J′⁻¹ (`minv_off`), coupling the rows on any of its three angular velocities. At compile time this stage orders the rows by minimum degree
//! (a chain's block-tridiagonal S stays without fill, so the cost grows linearly with its
//! length), computes the pattern of the LDLᵀ factor, and emits code that touches only its
//! structural non-zeros:
//!
//! * `schur_factor(jv, minv, [minv_off,] tol, allow_redundant, l, dinv)`: S from the Jacobian's
//!   non-zeros `jv` (in `JACOBIAN_PATTERN` order), M⁻¹'s diagonal `minv` and, with products of
//!   inertia, its off-diagonal non-zeros `minv_off`, then S = L D Lᵀ. A pivot
//!   `d_k ≤ tol · S_kk` means row k is (to `tol`) a combination of the rows eliminated before it:
//!   the factorization fails naming that row, or, with `allow_redundant`, drops it smoothly:
//!   1/d_k becomes w/d_k with w = 1/(1 + ρ⁸), ρ = τ S_kk/d_k (its multiplier fades to 0, a
//!   valid choice for a consistent redundant constraint; a regular pivot changes by ρ⁸, and not
//!   at all where ρ < 1e-2).
//! * `schur_solve(l, dinv, b)`: b ← S⁻¹ b, in place, rows in Φ's order.

use std::collections::{BTreeMap, BTreeSet};

use proc_macro2::{Literal, TokenStream};
use quote::quote;

/// One term of an entry S_ij: D_i,c1 (M⁻¹)_c1c2 D_j,c2, by the indices into jv of the two
/// Jacobian entries and where (M⁻¹)_c1c2 is: `minv[c]` on the diagonal, `minv_off[k]` off it.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Term {
    Diagonal(usize, usize, usize),
    Off(usize, usize, usize),
}

type Terms = Vec<Term>;

/// The compile-time plan of the sparse LDLᵀ of S.
pub struct Schur {
    nc: usize,
    /// `order[k]`: the constraint row eliminated k-th.
    order: Vec<usize>,
    /// Structural non-zeros of S as (i, j, terms) with i ≥ j in row indices of Φ; terms are
    /// (index into jv of D_ic, index into jv of D_jc, c).
    s: BTreeMap<(usize, usize), Terms>,
    /// Structural non-zeros of L below the diagonal as (row position, column position), mapped
    /// to their index in the `l` array. Positions are in elimination order.
    l: BTreeMap<(usize, usize), usize>,
}

/// Entries (a pivot with its row of L counts one each) per group of element bindings in the
/// factorization ([`crate::emit::scalarized_blocks`]).
const PIVOTS_PER_BLOCK: usize = 128;

fn lit(n: usize) -> Literal {
    Literal::usize_unsuffixed(n)
}

impl Schur {
    /// Plans the factorization for a Jacobian pattern (row, column), row-major, of `nc` rows, and
    /// the off-diagonal structural non-zeros (c1, c2) of M⁻¹ (both triangles; `minv_off[k]` is
    /// the k-th), empty for a diagonal M.
    pub fn plan(nc: usize, pattern: &[(usize, usize)], coupling: &[(usize, usize)]) -> Schur {
        // Entries of each column: (row, index into jv).
        let mut columns: BTreeMap<usize, Vec<(usize, usize)>> = BTreeMap::new();
        for (k, &(r, c)) in pattern.iter().enumerate() {
            columns.entry(c).or_default().push((r, k));
        }
        let mut s: BTreeMap<(usize, usize), Terms> = BTreeMap::new();
        for (&c, entries) in &columns {
            for &(ri, ki) in entries {
                for &(rj, kj) in entries {
                    if ri >= rj {
                        s.entry((ri, rj)).or_default().push(Term::Diagonal(ki, kj, c));
                    }
                }
            }
        }
        let none = Vec::new();
        for (index, &(c1, c2)) in coupling.iter().enumerate() {
            for &(ri, ki) in columns.get(&c1).unwrap_or(&none) {
                for &(rj, kj) in columns.get(&c2).unwrap_or(&none) {
                    if ri >= rj {
                        s.entry((ri, rj)).or_default().push(Term::Off(ki, kj, index));
                    }
                }
            }
        }
        let mut adjacency: Vec<BTreeSet<usize>> = vec![BTreeSet::new(); nc];
        for &(i, j) in s.keys() {
            if i != j {
                adjacency[i].insert(j);
                adjacency[j].insert(i);
            }
        }
        let order = minimum_degree(&adjacency);
        // Symbolic factorization on the elimination graph, in positions.
        let (_, graph) = crate::newton::filled_graph(&adjacency, &order);
        let mut l = BTreeMap::new();
        for (k, neighbours) in graph.iter().enumerate() {
            for &i in neighbours.iter().filter(|&&i| i > k) {
                let next = l.len();
                l.insert((i, k), next);
            }
        }
        Schur { nc, order, s, l }
    }

    /// Number of stored entries of L below the diagonal.
    pub fn nl(&self) -> usize {
        self.l.len()
    }

    /// S_ij (rows of Φ, i ≥ j) as an expression of `jv` and `minv`, if structurally non-zero.
    fn s_entry(&self, i: usize, j: usize) -> Option<TokenStream> {
        let (i, j) = if i >= j { (i, j) } else { (j, i) };
        let terms = self.s.get(&(i, j))?;
        let terms = terms.iter().map(|&term| match term {
            Term::Diagonal(ki, kj, c) => {
                let (ki, kj, c) = (lit(ki), lit(kj), lit(c));
                quote!(jv[#ki] * jv[#kj] * minv[#c])
            }
            Term::Off(ki, kj, k) => {
                let (ki, kj, k) = (lit(ki), lit(kj), lit(k));
                quote!(jv[#ki] * jv[#kj] * minv_off[#k])
            }
        });
        Some(quote!((#(#terms)+*)))
    }

    /// The body of `schur_factor`: writes `l` and `dinv`, returns `Err(row)` for a dependent row.
    /// Above [`STATEMENTS_PER_PART`] statements the pivots are factored by nested functions of
    /// about that many statements each, called in turn ([`in_parts`]).
    pub fn factor(&self, real: &TokenStream, zero: &TokenStream) -> TokenStream {
        let mut stmts = Vec::new();
        // d[k] (pivots, in positions) kept in a local array; dinv written to the output.
        for k in 0..self.nc {
            let row_k = self.order[k];
            let (kl, row_kl) = (lit(k), lit(row_k));
            let skk = self.s_entry(row_k, row_k).unwrap_or_else(|| zero.clone());
            // d_k = S_kk − Σ_j L_kj² d_j
            let sub: Vec<TokenStream> = (0..k)
                .filter_map(|j| self.l.get(&(k, j)).map(|&idx| (j, idx)))
                .map(|(j, idx)| {
                    let (jl, idx) = (lit(j), lit(idx));
                    quote!(- l[#idx] * l[#idx] * d[#jl])
                })
                .collect();
            stmts.push(quote! {
                let skk: #real = #skk;
                let dk: #real = skk #(#sub)*;
                let ::core::option::Option::Some((dk, dik)) = ::mbd::__private::schur_pivot(skk, dk, exact, tol, allow_redundant) else {
                    return ::core::result::Result::Err(#row_kl);
                };
                d[#kl] = dk;
                dinv[#kl] = dik;
            });
            // L_ik = (S_ik − Σ_j L_ij L_kj d_j) / d_k
            for i in (k + 1)..self.nc {
                let Some(&idx) = self.l.get(&(i, k)) else { continue };
                let sik = self.s_entry(self.order[i], row_k).unwrap_or_else(|| zero.clone());
                let sub: Vec<TokenStream> = (0..k)
                    .filter_map(|j| Some((j, *self.l.get(&(i, j))?, *self.l.get(&(k, j))?)))
                    .map(|(j, a, b)| {
                        let (jl, a, b) = (lit(j), lit(a), lit(b));
                        quote!(- l[#a] * l[#b] * d[#jl])
                    })
                    .collect();
                let idx = lit(idx);
                stmts.push(quote!(l[#idx] = (#sik #(#sub)*) * dinv[#kl];));
            }
        }
        let nc = lit(self.nc);
        let off = self.coupled().then(|| quote!(minv_off: &[#real; NOFF],));
        let off_generic = self.coupled().then(|| quote!(const NOFF: usize,));
        let off_arg = self.coupled().then(|| quote!(minv_off,));
        let part = Part {
            generics: quote!(<const NNZ: usize, const NV: usize, #off_generic const NL: usize, const NC: usize>),
            params: quote!(jv: &[#real; NNZ], minv: &[#real; NV], #off tol: #real, exact: #real, allow_redundant: bool, l: &mut [#real; NL], d: &mut [#real; NC], dinv: &mut [#real; NC]),
            output: quote!(-> ::core::result::Result<(), usize>),
            ok: quote!(::core::result::Result::Ok(())),
            call: quote!((jv, minv, #off_arg tol, exact, allow_redundant, l, &mut d, dinv)?;),
        };
        // Each pivot's test is a branch of its own: the blocks stay short without `in_blocks`'s
        // cuts; its element bindings (`crate::scalar`) are made for every few pivots.
        let stmts = in_parts(&stmts, &part, |group| crate::emit::scalarized_blocks(group, PIVOTS_PER_BLOCK));
        quote! {
            let mut d = [#zero; #nc];
            // Pivots above this · τ S_kk are taken exactly (one division): with
            // `allow_redundant` the smooth weight below is 1 there to rounding (ρ⁸ < 1e-16).
            let exact: #real = if allow_redundant { 1e2 } else { 1.0 };
            #stmts
            ::core::result::Result::Ok(())
        }
    }

    /// Whether M⁻¹ has entries off its diagonal (`minv_off`).
    fn coupled(&self) -> bool {
        self.s.values().flatten().any(|t| matches!(t, Term::Off(..)))
    }

    /// The body of `schur_solve`: b ← S⁻¹ b in place (forward, diagonal, back substitution),
    /// in nested functions of about [`STATEMENTS_PER_PART`] statements above that many.
    pub fn solve(&self, real: &TokenStream) -> TokenStream {
        let mut stmts = Vec::new();
        let pos = |k: usize| lit(self.order[k]);
        // b_k −= L_kj b_j one term at a time: the same left-to-right rounding as one long
        // difference, written as assignment operators.
        for k in 0..self.nc {
            let bk = pos(k);
            for (j, idx) in (0..k).filter_map(|j| self.l.get(&(k, j)).map(|&idx| (j, idx))) {
                let (bj, idx) = (pos(j), lit(idx));
                stmts.push(quote!(b[#bk] -= l[#idx] * b[#bj];));
            }
        }
        for k in 0..self.nc {
            let (bk, kl) = (pos(k), lit(k));
            stmts.push(quote!(b[#bk] *= dinv[#kl];));
        }
        for k in (0..self.nc).rev() {
            let bk = pos(k);
            for (i, idx) in ((k + 1)..self.nc).filter_map(|i| self.l.get(&(i, k)).map(|&idx| (i, idx))) {
                let (bi, idx) = (pos(i), lit(idx));
                stmts.push(quote!(b[#bk] -= l[#idx] * b[#bi];));
            }
        }
        let part = Part {
            generics: quote!(<const NL: usize, const NC: usize>),
            params: quote!(l: &[#real; NL], dinv: &[#real; NC], b: &mut [#real; NC]),
            output: quote!(),
            ok: quote!(),
            call: quote!((l, dinv, b);),
        };
        in_parts(&stmts, &part, crate::emit::in_blocks)
    }
}

/// Statements of the factorization or the solve up to which they are emitted in one function;
/// above, in nested functions of about this many each. LLVM's instruction selection and
/// register allocation work on a whole function and grow faster than linearly in its length:
/// the 240-body chain's `schur_factor` (480 pivots) took 3.8 times as long to optimize as the
/// 120-body chain's (`-Zllvm-time-trace`), its `schur_solve` 3.2 times.
pub const STATEMENTS_PER_PART: usize = 512;

/// How the statements of one function are cut into nested functions: their generic
/// parameters (sizes, so the parts need not know them), parameters, return type and success
/// value, and the arguments the function passes (ending in `;`, or `?;` to pass an error on).
struct Part {
    generics: TokenStream,
    params: TokenStream,
    output: TokenStream,
    ok: TokenStream,
    call: TokenStream,
}

/// `stmts` as one function body (through `emit`), or, above [`STATEMENTS_PER_PART`], as nested
/// `#[inline(never)]` functions of about that many statements, each emitted through `emit`,
/// called in turn.
fn in_parts(stmts: &[TokenStream], part: &Part, emit: impl Fn(&[TokenStream]) -> TokenStream) -> TokenStream {
    if stmts.len() <= STATEMENTS_PER_PART {
        return emit(stmts);
    }
    let Part { generics, params, output, ok, call } = part;
    let parts = stmts.chunks(STATEMENTS_PER_PART).enumerate().map(|(k, group)| {
        let name = quote::format_ident!("__mbd_part_{}", k);
        let body = emit(group);
        quote! {
            #[inline(never)]
            #[allow(clippy::too_many_arguments)]
            fn #name #generics(#params) #output {
                #body
                #ok
            }
            #name #call
        }
    });
    quote!(#(#parts)*)
}

/// Minimum-degree ordering of a graph given by adjacency sets (exact elimination-graph degrees;
/// ties to the shallowest pivot, then the lowest index, so a chain is ordered from both ends at
/// once and never fills).
fn minimum_degree(adjacency: &[BTreeSet<usize>]) -> Vec<usize> {
    // Every row may go at any time: no "multipliers" waiting for their velocities.
    crate::newton::constrained_minimum_degree(adjacency, adjacency.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A chain of n bodies on revolutes (2 rows each, joint k between bodies k−1 and k): S is
    /// block-tridiagonal, and the minimum-degree order factors it without fill, so L has no
    /// more entries than S's lower triangle.
    #[test]
    fn a_chain_factors_without_fill() {
        let n = 16;
        let mut pattern = Vec::new();
        for k in 0..n {
            for row in [2 * k, 2 * k + 1] {
                if k > 0 {
                    for c in 3 * (k - 1)..3 * k {
                        pattern.push((row, c));
                    }
                }
                for c in 3 * k..3 * k + 3 {
                    pattern.push((row, c));
                }
            }
        }
        pattern.sort();
        let schur = Schur::plan(2 * n, &pattern, &[]);
        let off_diagonal = schur.s.keys().filter(|(i, j)| i != j).count();
        assert_eq!(schur.nl(), off_diagonal, "no fill");
        assert!(schur.nl() <= 7 * n, "L grows linearly: {}", schur.nl());
        let mut seen = schur.order.clone();
        seen.sort();
        assert_eq!(seen, (0..2 * n).collect::<Vec<_>>(), "the order is a permutation");
    }

    /// A ring of four bodies (joint k between bodies k and k+1 mod 4, one row each): S is a
    /// 4-cycle, and eliminating any row of a cycle joins its two neighbours, so L must have one
    /// entry more than S's lower triangle — the fill a planner that forgot it would leave out
    /// (every mechanism that closes its loops through ground factors without fill). The
    /// generated solve of such a loop is checked against a dense one in tests/forward.rs.
    #[test]
    fn a_ring_needs_fill() {
        let mut pattern = Vec::new();
        for k in 0..4 {
            for b in [k, (k + 1) % 4] {
                pattern.push((k, 3 * b));
            }
        }
        pattern.sort();
        let schur = Schur::plan(4, &pattern, &[]);
        let off_diagonal = schur.s.keys().filter(|(i, j)| i != j).count();
        assert_eq!(off_diagonal, 4, "a 4-cycle");
        assert_eq!(schur.nl(), off_diagonal + 1, "one fill entry");
    }

    /// Two rows on the same coordinates: S is full 2×2, one entry of L.
    #[test]
    fn coupled_rows_share_one_entry() {
        let schur = Schur::plan(2, &[(0, 0), (0, 1), (1, 0), (1, 1)], &[]);
        assert_eq!(schur.nl(), 1);
        assert_eq!(schur.s.len(), 3);
    }

    /// Two rows on different angular velocities of one body are uncoupled with a diagonal
    /// inertia and coupled through its products of inertia (M⁻¹ off the diagonal).
    #[test]
    fn products_of_inertia_couple_rows() {
        let pattern = [(0, 3), (1, 4)];
        assert_eq!(Schur::plan(2, &pattern, &[]).nl(), 0);
        let coupled = Schur::plan(2, &pattern, &[(3, 4), (4, 3)]);
        assert_eq!(coupled.nl(), 1);
        assert_eq!(coupled.s[&(1, 0)], [Term::Off(1, 0, 1)], "S_10 = D_1,4 (M⁻¹)_43 D_0,3");
    }
}
