//! The compile-time plan of generalized-α's Newton matrix [[A, −Dᵀ], [D, 0]] (A = M − c_v ∂h/∂v
//! − c_q (∂h/∂q + K)) and the generated `NewtonMatrix` implementation that fills it.
//!
//! The plan orders the NV + NC unknowns (v̇ entries, then multipliers) by minimum degree on the
//! matrix's structure, with one constraint: a multiplier waits until every velocity its row of
//! D touches has been eliminated. That order needs no row exchanges (`mbd_runtime::sparse`
//! explains why), so the fill-in is fixed here, once, and the runtime factors over exactly the
//! planned entries: a chain's factors grow linearly with its length.

use std::collections::{BTreeMap, BTreeSet};

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use crate::emit::{in_functions, jacobian_values_outputs, real, usize_lit, vector_outputs, Emitter, Ops, Output, PartSignature};
use crate::formulation::Formulation;

/// The ordering and the filled pattern of the LU factors.
pub struct NewtonPlan {
    nv: usize,
    /// The entries the matrix sets before factoring (A's structure and D, both ways), in
    /// positions; the rest of the pattern is fill-in.
    original: BTreeSet<(usize, usize)>,
    /// The unknown at each position and the position of each unknown.
    unknown: Vec<usize>,
    position: Vec<usize>,
    /// Row-wise storage of the filled pattern, columns (positions) ascending.
    row_start: Vec<usize>,
    columns: Vec<usize>,
    diagonal: Vec<usize>,
    /// (row position, column position) → storage index.
    index: BTreeMap<(usize, usize), usize>,
}

impl NewtonPlan {
    /// Plans the factors for `nv` velocities, the structural non-zeros `velocity` of A (pairs of
    /// velocities, either triangle) and D's pattern `jacobian` (row, velocity) of `nc` rows.
    pub fn plan(nv: usize, nc: usize, velocity: &BTreeSet<(usize, usize)>, jacobian: &[(usize, usize)]) -> NewtonPlan {
        let n = nv + nc;
        let mut adjacency: Vec<BTreeSet<usize>> = vec![BTreeSet::new(); n];
        for &(i, j) in velocity {
            if i != j {
                adjacency[i].insert(j);
                adjacency[j].insert(i);
            }
        }
        for &(r, c) in jacobian {
            adjacency[nv + r].insert(c);
            adjacency[c].insert(nv + r);
        }
        let unknown = constrained_minimum_degree(&adjacency, nv);
        let (position, mut graph) = filled_graph(&adjacency, &unknown);
        let (mut row_start, mut columns, mut diagonal, mut index) = (vec![0], Vec::new(), Vec::new(), BTreeMap::new());
        for (p, neighbours) in graph.iter_mut().enumerate() {
            neighbours.insert(p);
            for &c in neighbours.iter() {
                if c == p {
                    diagonal.push(columns.len());
                }
                index.insert((p, c), columns.len());
                columns.push(c);
            }
            row_start.push(columns.len());
        }
        let mut original: BTreeSet<(usize, usize)> = (0..n).map(|p| (p, p)).collect();
        for (u, neighbours) in adjacency.iter().enumerate() {
            original.extend(neighbours.iter().map(|&w| (position[u], position[w])));
        }
        NewtonPlan { nv, original, unknown, position, row_start, columns, diagonal, index }
    }

    /// Stored entries of L and U, fill-in included.
    pub fn entries(&self) -> usize {
        self.columns.len()
    }

    /// Multiply-subtract updates of one factorization: the straight-line code's length.
    pub fn updates(&self) -> usize {
        (0..self.unknown.len())
            .map(|i| {
                (self.row_start[i]..self.diagonal[i])
                    .map(|p| self.row_start[self.columns[p] + 1] - self.diagonal[self.columns[p]] - 1)
                    .sum::<usize>()
            })
            .sum()
    }

    /// The body of a straight-line `newton_factor`: what `mbd_runtime::sparse::factor` does
    /// over this pattern, with every index a constant (`nnz`: where the entries start in `s`),
    /// except that the diagonal keeps 1/u_kk, so the solve multiplies (a chain of divisions
    /// made the back substitution the slowest part of a step).
    fn factor(&self, nnz: usize, zero: &TokenStream, one: &TokenStream) -> TokenStream {
        let n = self.unknown.len();
        let at = |p: usize| usize_lit(nnz + p);
        let mut rows = Vec::new();
        for i in 0..n {
            let (start, diag, end) = (self.row_start[i], self.diagonal[i], self.row_start[i + 1]);
            let u = self.unknown[i];
            // The row's scale from its entries before elimination (`sparse::factor`).
            let originals: Vec<usize> = (start..end).filter(|&p| self.original.contains(&(i, self.columns[p]))).collect();
            let scale = if u >= self.nv {
                // Σ D_rc² / |u_cc|: the diagonal already holds 1/u_cc for the velocities before.
                let terms = originals.iter().filter(|&&p| p < diag).map(|&p| {
                    let (x, d) = (at(p), at(self.diagonal[self.columns[p]]));
                    quote!(s[#x] * s[#x] * s[#d].abs())
                });
                quote!(let scale = #zero #(+ #terms)*;)
            } else {
                let terms = originals.iter().map(|&p| {
                    let x = at(p);
                    quote!(.max(s[#x].abs()))
                });
                quote!(let scale = #zero #(#terms)*;)
            };
            let mut eliminate = Vec::new();
            for p in start..diag {
                let k = self.columns[p];
                let (pl, kl) = (at(p), usize_lit(k));
                let updates = (self.diagonal[k] + 1..self.row_start[k + 1]).map(|q| {
                    let (t, q) = (at(self.index[&(i, self.columns[q])]), at(q));
                    quote!(s[#t] -= l * s[#q];)
                });
                eliminate.push(quote! {
                    let l = s[#pl] * inverse[#kl];
                    s[#pl] = l;
                    #(#updates)*
                });
            }
            let (il, ul, dl, (from, to)) = (usize_lit(i), usize_lit(u), at(diag), (at(start), at(end)));
            let nv = usize_lit(self.nv);
            rows.push(quote! {
                {
                    #scale
                    #({ #eliminate })*
                    let pivot = s[#dl];
                    if ::mbd::__private::pivot(pivot, scale, #ul, #nv, tolerance, allow_redundant, dropped, &mut smallest)? {
                        inverse[#il] = #one / pivot;
                        s[#dl] = inverse[#il];
                    } else {
                        for x in s[#from..#to].iter_mut() {
                            *x = #zero;
                        }
                        s[#dl] = #one;
                        inverse[#il] = #one;
                    }
                }
            });
        }
        let n = usize_lit(n);
        quote! {
            let mut smallest = #one;
            let mut inverse = [#zero; #n];
            #(#rows)*
            ::core::result::Result::Ok(smallest)
        }
    }

    /// The body of a straight-line `newton_solve` for `b: &mut [_; n]`, indexed by unknown.
    fn solve(&self, nnz: usize) -> TokenStream {
        let n = self.unknown.len();
        let at = |p: usize| usize_lit(nnz + p);
        let usize_lit = |p: usize| usize_lit(self.unknown[p]);
        let forward = (0..n).flat_map(|i| {
            let il = usize_lit(i);
            (self.row_start[i]..self.diagonal[i]).map(move |p| {
                let (pl, k) = (at(p), usize_lit(self.columns[p]));
                quote!(b[#il] -= s[#pl] * b[#k];)
            })
        });
        let backward = (0..n).rev().map(|i| {
            let (il, dl) = (usize_lit(i), at(self.diagonal[i]));
            let terms: Vec<TokenStream> = (self.diagonal[i] + 1..self.row_start[i + 1])
                .map(|p| {
                    let (pl, j) = (at(p), usize_lit(self.columns[p]));
                    quote!(- s[#pl] * b[#j])
                })
                .collect();
            if terms.is_empty() {
                quote!(b[#il] *= s[#dl];)
            } else {
                quote!(b[#il] = (b[#il] #(#terms)*) * s[#dl];)
            }
        });
        quote! {
            #(#forward)*
            #(#backward)*
        }
    }

    /// The storage index of the entry in the row of unknown `u` and the column of unknown `w`.
    fn slot(&self, u: usize, w: usize) -> usize {
        self.index[&(self.position[u], self.position[w])]
    }

    /// `::mbd::SparsePattern { .. }` for the `NEWTON_PATTERN` constant.
    fn pattern(&self) -> TokenStream {
        let list = |v: &[usize]| -> Vec<Literal> { v.iter().map(|&x| Literal::u32_unsuffixed(x as u32)).collect() };
        let (unknown, position, row_start, columns, diagonal) =
            (list(&self.unknown), list(&self.position), list(&self.row_start), list(&self.columns), list(&self.diagonal));
        quote! {
            ::mbd::SparsePattern {
                unknown: &[#(#unknown),*],
                position: &[#(#position),*],
                row_start: &[#(#row_start),*],
                columns: &[#(#columns),*],
                diagonal: &[#(#diagonal),*],
            }
        }
    }
}

/// Minimum degree over the unknowns that may go next: every velocity, and a multiplier once all
/// velocities of its row are eliminated. Ties go to the unknown whose pivot waits on the
/// shortest chain of pivots before it (its depth in the elimination tree so far), then to the
/// lower index: a chain is then eliminated from both ends at once, two independent sequences of
/// dependent divisions and multiply-subtracts that the processor overlaps, where one end after
/// the other made the factorization and the solves one sequence twice as long.
pub fn constrained_minimum_degree(adjacency: &[BTreeSet<usize>], nv: usize) -> Vec<usize> {
    let n = adjacency.len();
    let mut graph = adjacency.to_vec();
    let mut waiting: Vec<usize> = (0..n).map(|u| if u < nv { 0 } else { adjacency[u].len() }).collect();
    let mut eliminated = vec![false; n];
    let mut depth = vec![0usize; n];
    let mut order = Vec::with_capacity(n);
    for _ in 0..n {
        let u = (0..n)
            .filter(|&u| !eliminated[u] && waiting[u] == 0)
            .min_by_key(|&u| (graph[u].len(), depth[u], u))
            .expect("a velocity or a released multiplier is always left");
        eliminated[u] = true;
        order.push(u);
        let neighbours: Vec<usize> = graph[u].iter().copied().collect();
        for &a in &neighbours {
            depth[a] = depth[a].max(depth[u] + 1);
            graph[a].remove(&u);
            for &b in &neighbours {
                if a != b {
                    graph[a].insert(b);
                }
            }
        }
        graph[u].clear();
        if u < nv {
            for &w in &adjacency[u] {
                if w >= nv {
                    waiting[w] -= 1;
                }
            }
        }
    }
    order
}

/// The symbolic factorization for an elimination `order` of a graph: (the position of each
/// vertex, the graph in positions with every fill-in edge), eliminating a vertex connecting all
/// its later neighbours.
pub fn filled_graph(adjacency: &[BTreeSet<usize>], order: &[usize]) -> (Vec<usize>, Vec<BTreeSet<usize>>) {
    let n = adjacency.len();
    let mut position = vec![0; n];
    for (p, &u) in order.iter().enumerate() {
        position[u] = p;
    }
    let mut graph: Vec<BTreeSet<usize>> = vec![BTreeSet::new(); n];
    for (u, neighbours) in adjacency.iter().enumerate() {
        for &w in neighbours {
            graph[position[u]].insert(position[w]);
        }
    }
    for p in 0..n {
        let later: Vec<usize> = graph[p].iter().copied().filter(|&i| i > p).collect();
        for &a in &later {
            for &b in &later {
                if a != b {
                    graph[a].insert(b);
                }
            }
        }
    }
    (position, graph)
}

/// Updates (multiply-subtracts) up to which the factorization and solve are emitted
/// straight-line; larger mechanisms run the same plan through `mbd_runtime::sparse`. Measured on
/// 2026-11-24 (`cargo bench --bench dynamics -- generalized`, `python3
/// mbd-bench/build_scaling/run.py`): the 16-link chain (about 560 updates on the pattern of the
/// chain test below) steps in 4.8 µs straight-line against 7.4 µs through the loop, and the free
/// slider-crank in 0.82 against 1.42 µs; but straight-line code is slow to compile (the 30-link chain with torsion springs
/// of the build-scaling crate took 13.8 s to build straight-line, 8.2 s through the loop), so
/// the line sits where chains of about 20 links stop.
const GENERATED_UPDATES: usize = 1000;

/// The generated `NewtonMatrix` implementation and its operation counts.
pub struct NewtonCode {
    pub impl_block: TokenStream,
    pub matrix_ops: Ops,
    /// Scalars of `NewtonStorage`: D's non-zeros and the factors' entries.
    pub storage: usize,
}

/// The terms of each slot of A = M − c_v (damping) − c_q (stiffness), keyed by (row, column),
/// each with whether it is subtracted; and the locals the body writes them into besides Φ and s,
/// by name and length.
type Terms = (BTreeMap<(usize, usize), Vec<(bool, TokenStream)>>, Vec<(syn::Ident, usize)>);

/// The code that multiplies the derivatives by the positions by the tangent operator T(Δ) of
/// each body's rotation (`displacement`'s three rotational entries): `tangents` = the operators
/// (`None` without a displacement), then, each where given one, the stiffness's rows before A's
/// slots are summed (its slots hold it alone then) and D's rows in [[·], [D, 0]] after they are
/// copied there — each (row, first rotational velocity) of `stiffness` and `jacobian`, all
/// three columns planned. Nothing in the plane.
fn tangent_code(
    rotations: &[usize],
    stiffness: &BTreeSet<(usize, usize)>,
    jacobian: &BTreeSet<(usize, usize)>,
    at: &dyn Fn(usize, usize) -> Literal,
    nv: usize,
) -> (TokenStream, TokenStream, TokenStream) {
    if rotations.is_empty() {
        return (quote!(), quote!(), quote!());
    }
    let operators = rotations.iter().map(|&first| {
        let (a, b, c) = (usize_lit(first), usize_lit(first + 1), usize_lit(first + 2));
        quote!(::mbd::__private::tangent_operator([delta[#a], delta[#b], delta[#c]]))
    });
    let tangents = quote!(let tangents = displacement.map(|delta| [#(#operators),*]););
    // x ← x T on the row's three slots (row u of the matrix, body `first`).
    let turn = |u: usize, first: usize| {
        let body = usize_lit(rotations.iter().position(|&r| r == first).expect("a planned rotation"));
        let slots: Vec<Literal> = (first..first + 3).map(|c| at(u, c)).collect();
        let [s0, s1, s2] = [&slots[0], &slots[1], &slots[2]];
        let columns = (0..3).map(|j| {
            let (j, slot) = (usize_lit(j), &slots[j]);
            quote!(s[#slot] = x0 * t[0][#j] + x1 * t[1][#j] + x2 * t[2][#j];)
        });
        quote! {{
            let t = &tangents[#body];
            let (x0, x1, x2) = (s[#s0], s[#s1], s[#s2]);
            #(#columns)*
        }}
    };
    let guarded = |rows: Vec<TokenStream>| {
        if rows.is_empty() {
            quote!()
        } else {
            quote!(if let ::core::option::Option::Some(tangents) = &tangents { #(#rows)* })
        }
    };
    let turn_stiffness = guarded(stiffness.iter().map(|&(r, first)| turn(r, first)).collect());
    let turn_jacobian = guarded(jacobian.iter().map(|&(r, first)| turn(nv + r, first)).collect());
    (tangents, turn_stiffness, turn_jacobian)
}

/// The outputs of A's terms, pushed after Φ and D's: the masses and the damping into small
/// locals, the stiffness straight into its slot of `s` (`at`). `stiffness`: the slots of c_q's
/// terms — the stiffness's entries and those the tangent operator fills beside them.
fn a_terms(
    f: &Formulation,
    stiffness: &BTreeSet<(usize, usize)>,
    at: &dyn Fn(usize, usize) -> Literal,
    outputs: &mut Vec<Output>,
) -> Terms {
    let nv = f.nv;
    let mut terms: BTreeMap<(usize, usize), Vec<(bool, TokenStream)>> = BTreeMap::new();
    let mut locals: Vec<(syn::Ident, usize)> = Vec::new();
    let mass_entries: Vec<usize> = (0..nv).filter(|&i| !f.graph.is_zero(f.mass[i])).collect();
    if !mass_entries.is_empty() {
        locals.push((syn::Ident::new("m", proc_macro2::Span::call_site()), nv));
    }
    for &i in &mass_entries {
        let il = usize_lit(i);
        outputs.push(Output { target: quote!(m[#il]), node: f.mass[i] });
        terms.entry((i, i)).or_default().push((false, quote!(m[#il])));
    }
    let mut local = |name: &str, entries: &[(usize, usize, u32)], coefficient: Option<TokenStream>| {
        if entries.is_empty() {
            return;
        }
        let ident = syn::Ident::new(name, proc_macro2::Span::call_site());
        locals.push((ident.clone(), entries.len()));
        for (k, &(r, c, node)) in entries.iter().enumerate() {
            let k = usize_lit(k);
            outputs.push(Output { target: quote!(#ident[#k]), node });
            let term = match &coefficient {
                Some(coefficient) => (true, quote!(#coefficient * #ident[#k])),
                None => (false, quote!(#ident[#k])),
            };
            terms.entry((r, c)).or_default().push(term);
        }
    };
    local("mc", &f.mass_coupling, None);
    local("damping", &f.damping, Some(quote!(c_v)));
    for &(r, c, node) in &f.stiffness {
        let slot = at(r, c);
        outputs.push(Output { target: quote!(s[#slot]), node });
    }
    for &(r, c) in stiffness {
        let slot = at(r, c);
        terms.entry((r, c)).or_default().push((true, quote!(c_q * s[#slot])));
    }
    (terms, locals)
}

/// Coulomb friction's slopes in the multipliers subtracted from their slots of the λ columns,
/// after D's copy there: the momentum rows' −∂r/∂λ is −Dᵀ − ∂f/∂λ. Without them Newton
/// converges only linearly where the loads carry much friction (issue 39: a plank bridge held
/// by two rubbing pins stopped Radau5, whose simplified Newton keeps the matrix of the step's
/// start, 17 ms into its swing). Computed apart from the matrix's body: only mechanisms with
/// Coulomb friction have them.
fn friction_slope_entries(f: &Formulation, e: &Emitter, at: &dyn Fn(usize, usize) -> Literal) -> TokenStream {
    if f.friction_lambda.is_empty() {
        return quote!();
    }
    let (fill, slopes) = crate::emit::multiplier_slopes(f, e);
    let subtract = f.friction_lambda.iter().enumerate().map(|(k, &(c, r, _))| {
        let (k, slot) = (usize_lit(k), at(c, f.nv + r));
        quote!(s[#slot] -= #slopes[#k];)
    });
    quote!({
        #fill
        #(#subtract)*
    })
}

/// Each slot of A summed from its terms (`sums`), and D's non-zeros copied into their two slots
/// of [[A, −Dᵀ], [D, 0]] (`d_entries`).
fn slot_sums(
    f: &Formulation,
    terms: BTreeMap<(usize, usize), Vec<(bool, TokenStream)>>,
    stiffness: &BTreeSet<(usize, usize)>,
    at: &dyn Fn(usize, usize) -> Literal,
    real: &TokenStream,
) -> (TokenStream, TokenStream) {
    let nv = f.nv;
    let sums: Vec<TokenStream> = terms
        .into_iter()
        .map(|((r, c), terms)| {
            let slot = at(r, c);
            if terms.len() == 1 && stiffness.contains(&(r, c)) {
                // The stiffness alone, already in its slot.
                return quote!(s[#slot] *= -c_q;);
            }
            let mut sum = TokenStream::new();
            for (k, (negative, term)) in terms.into_iter().enumerate() {
                sum.extend(match (k, negative) {
                    (0, false) => term,
                    (0, true) => quote!(-#term),
                    (_, false) => quote!(+ #term),
                    (_, true) => quote!(- #term),
                });
            }
            quote!(s[#slot] = #sum;)
        })
        .collect();
    let d_entries: Vec<TokenStream> = f
        .jacobian
        .iter()
        .enumerate()
        .map(|(k, &(r, c, _))| {
            let (k, row, column) = (usize_lit(k), at(c, nv + r), at(nv + r, c));
            quote! {
                s[#row] = -s[#k];
                s[#column] = s[#k];
            }
        })
        .collect();
    (in_functions(&sums, "sums", &["c_q", "c_v"], real), in_functions(&d_entries, "d_entries", &[], real))
}

/// Straight-line factorization and solve up to a size; beyond, the code would cost more to
/// compile than it saves (the runtime runs the same plan from `NEWTON_PATTERN`): nothing.
fn straight_line_solver(f: &Formulation, e: &Emitter, plan: &NewtonPlan, real: &TokenStream) -> TokenStream {
    if plan.updates() > GENERATED_UPDATES {
        return quote!();
    }
    let (nv, nc, nnz) = (f.nv, f.nc, f.jacobian.len());
    let (zero, one) = (e.literal(0.0), e.literal(1.0));
    let factor = plan.factor(nnz, &zero, &one);
    let solve = plan.solve(nnz);
    let (total, nc_l, n, nnz_l) = (usize_lit(nnz + plan.entries()), usize_lit(nc), usize_lit(nv + nc), usize_lit(nnz));
    quote! {
        fn newton_factor(
            s: &mut [#real; #total],
            tolerance: #real,
            allow_redundant: bool,
            dropped: &mut [bool; #nc_l],
        ) -> ::core::result::Result<#real, ::mbd::LinalgError> {
            #factor
        }
        fn newton_solve(s: &[#real; #total], b: &mut [#real]) {
            if let ::core::result::Result::Ok(b) = <&mut [#real; #n]>::try_from(&mut *b) {
                #solve
            } else {
                ::mbd::sparse::solve(&Self::NEWTON_PATTERN, &s[#nnz_l..], b);
            }
        }
    }
}

/// The matrix's structure before the factorization is planned: A's entries (pairs of
/// velocities) and D's (row, velocity), with the entries the tangent operator fills beside the
/// stiffness's and D's in a body's rotational columns (`rotations`: the first of each body's
/// three). The rows it turns are kept as (row, first rotational velocity).
struct Structure {
    velocity: BTreeSet<(usize, usize)>,
    jacobian: Vec<(usize, usize)>,
    /// The slots of c_q's terms: the stiffness's entries and those T fills beside them.
    stiffness: BTreeSet<(usize, usize)>,
    stiffness_turned: BTreeSet<(usize, usize)>,
    jacobian_turned: BTreeSet<(usize, usize)>,
}

impl Structure {
    fn of(f: &Formulation, rotations: &[usize]) -> Structure {
        let nv = f.nv;
        // The rows of the stiffness and of D with an entry in a body's rotational columns:
        // T(Δ) fills all three of them.
        let rotation_of = |c: usize| rotations.iter().copied().find(|&first| (first..first + 3).contains(&c));
        let rows_turned = |entries: &[(usize, usize, crate::sym::Id)]| -> BTreeSet<(usize, usize)> {
            entries.iter().filter_map(|&(r, c, _)| Some((r, rotation_of(c)?))).collect()
        };
        let (stiffness_turned, jacobian_turned) = (rows_turned(&f.stiffness), rows_turned(&f.jacobian));
        let triples = |rows: &BTreeSet<(usize, usize)>| -> Vec<(usize, usize)> {
            rows.iter().flat_map(|&(r, first)| (first..first + 3).map(move |c| (r, c))).collect()
        };
        let stiffness: BTreeSet<(usize, usize)> = f.stiffness.iter().map(|&(r, c, _)| (r, c)).chain(triples(&stiffness_turned)).collect();
        // A's structure: M (its diagonal and products of inertia), the stiffness and the damping.
        let mut velocity: BTreeSet<(usize, usize)> = (0..nv).map(|i| (i, i)).collect();
        for entries in [&f.mass_coupling, &f.damping] {
            velocity.extend(entries.iter().map(|&(r, c, _)| (r, c)));
        }
        velocity.extend(stiffness.iter().copied());
        if f.tree.is_some() {
            // Joint coordinates: M(q) and the derivatives are dense.
            velocity.extend((0..nv).flat_map(|r| (0..nv).map(move |c| (r, c))));
        }
        let mut jacobian: Vec<(usize, usize)> = f.jacobian.iter().map(|&(r, c, _)| (r, c)).collect();
        jacobian.extend(triples(&jacobian_turned));
        // Friction's slope in a joint's loads stands beside −Dᵀ in the λ columns; where D has no
        // entry there (a pin at a body's origin leaves its angle out of the joint's rows), the
        // pattern gets one, zero in D's block.
        jacobian.extend(f.friction_lambda.iter().map(|&(c, r, _)| (r, c)));
        jacobian.sort_unstable();
        jacobian.dedup();
        Structure { velocity, jacobian, stiffness, stiffness_turned, jacobian_turned }
    }
}

/// `rotations`: the first velocity of each body's three rotational ones (ω′x, ω′y, ω′z), whose
/// columns the tangent operator mixes (`mbd_runtime`'s `model::group`); empty in the plane.
pub fn newton_matrix(f: &Formulation, e: &Emitter, name: &syn::Ident, rotations: &[usize]) -> NewtonCode {
    let real = real(e.scalar);
    let zero = e.literal(0.0);
    let (nq, nv, nc, nnz) = (f.nq, f.nv, f.nc, f.jacobian.len());
    let structure = Structure::of(f, rotations);
    let plan = NewtonPlan::plan(nv, nc, &structure.velocity, &structure.jacobian);
    if f.tree.is_some() {
        return dense_newton(f, e, name, &plan);
    }
    let Structure { stiffness_turned, jacobian_turned, stiffness, .. } = structure;
    let at = |u: usize, w: usize| usize_lit(nnz + plan.slot(u, w));

    // One body for Φ, D and every term, so common subexpressions (sin and cos of every angle)
    // are computed once: the stiffness straight into its slot of `s`, the damping and the
    // masses into small locals; then each slot of A is M − c_v (damping) − c_q (stiffness).
    let (nq_l, nv_l, nc_l, nnz_l, total) = (usize_lit(nq), usize_lit(nv), usize_lit(nc), usize_lit(nnz), usize_lit(nnz + plan.entries()));
    let mut outputs = vector_outputs("phi", &f.phi);
    outputs.extend(jacobian_values_outputs(f, "s"));
    let position_signature = PartSignature {
        name: "newton_jacobian",
        params: quote!(q: &[#real; #nq_l], t: #real, phi: &mut [#real; #nc_l], s: &mut [#real; #total]),
        args: quote!(q, t, phi, s),
    };
    let (position_body, _) = e.body_in_parts(&outputs, &position_signature);
    let (terms, locals) = a_terms(f, &stiffness, &at, &mut outputs);
    let local_names: Vec<&syn::Ident> = locals.iter().map(|(ident, _)| ident).collect();
    let local_lengths: Vec<proc_macro2::Literal> = locals.iter().map(|&(_, n)| usize_lit(n)).collect();
    let signature = PartSignature {
        name: "newton_matrix",
        params: quote! {
            q: &[#real; #nq_l], v: &[#real; #nv_l], t: #real, lambda: &[#real; #nc_l],
            phi: &mut [#real; #nc_l], s: &mut [#real; #total], #(#local_names: &mut [#real; #local_lengths]),*
        },
        args: quote!(q, v, t, lambda, phi, s, #(&mut #local_names),*),
    };
    let locals: Vec<TokenStream> = local_names.iter().zip(&local_lengths).map(|(ident, n)| quote!(let mut #ident = [#zero; #n];)).collect();
    let (body, matrix_ops) = e.body_in_parts(&outputs, &signature);
    let (sums, d_entries) = slot_sums(f, terms, &stiffness, &at, &real);
    let (tangents, turn_stiffness, turn_jacobian) = tangent_code(rotations, &stiffness_turned, &jacobian_turned, &|u, w| at(u, w), nv);
    let friction_slopes = friction_slope_entries(f, e, &|u, w| at(u, w));
    let pattern = plan.pattern();
    // Inlined into the step of small mechanisms; kept apart in large ones (build time, as for
    // the Schur complement's helpers).
    let jacobian_inline = if plan.updates() <= GENERATED_UPDATES { quote!(#[inline]) } else { quote!(#[inline(never)]) };
    let solver = straight_line_solver(f, e, &plan, &real);
    let impl_block = quote! {
        // Constants are the user's expressions evaluated (`PI / 2.0` → 1.5707963267948966).
        #[allow(unused_variables, unused_parens, unused_mut, clippy::approx_constant)]
        // solver plumbing: left out of the type's documentation
        #[doc(hidden)]
        impl ::mbd::NewtonMatrix<#real, #nq_l, #nv_l, #nc_l> for #name {
            type NewtonStorage = [#real; #total];
            const NEWTON_PATTERN: ::mbd::SparsePattern = #pattern;
            #[inline]
            fn newton_storage() -> [#real; #total] {
                [#zero; #total]
            }
            #jacobian_inline
            fn newton_jacobian(
                &self,
                q: &[#real; #nq_l],
                t: #real,
                phi: &mut [#real; #nc_l],
                s: &mut [#real; #total],
                _scratch: ::mbd::DenseScratch<'_, #real, #nv_l, #nc_l>,
            ) {
                #position_body
            }
            #[inline(never)]
            fn newton_matrix(
                &self,
                q: &[#real; #nq_l],
                v: &[#real; #nv_l],
                vd: &[#real; #nv_l],
                t: #real,
                lambda: &[#real; #nc_l],
                displacement: ::core::option::Option<&[#real; #nv_l]>,
                c_v: #real,
                c_q: #real,
                phi: &mut [#real; #nc_l],
                s: &mut [#real; #total],
                _scratch: ::mbd::DenseScratch<'_, #real, #nv_l, #nc_l>,
            ) {
                for x in s[#nnz_l..].iter_mut() {
                    *x = #zero;
                }
                #(#locals)*
                #body
                #tangents
                #turn_stiffness
                #sums
                #d_entries
                #friction_slopes
                #turn_jacobian
            }
            #solver
        }
    };
    NewtonCode { impl_block, matrix_ops, storage: nnz + plan.entries() }
}

/// The `NewtonMatrix` of joint coordinates: the planned dense pattern, its storage and solver;
/// the matrix filled by the trait's provided `newton_matrix` from the dense `Dynamics`
/// functions (`expand::generate::joint`).
fn dense_newton(f: &Formulation, e: &Emitter, name: &syn::Ident, plan: &NewtonPlan) -> NewtonCode {
    let real = real(e.scalar);
    let zero = e.literal(0.0);
    let (nq_l, nv_l, nc_l) = (usize_lit(f.nq), usize_lit(f.nv), usize_lit(f.nc));
    let storage = f.jacobian.len() + plan.entries();
    let total = usize_lit(storage);
    let pattern = plan.pattern();
    let solver = straight_line_solver(f, e, plan, &real);
    let impl_block = quote! {
        #[doc(hidden)]
        impl ::mbd::NewtonMatrix<#real, #nq_l, #nv_l, #nc_l> for #name {
            type NewtonStorage = [#real; #total];
            const NEWTON_PATTERN: ::mbd::SparsePattern = #pattern;
            #[inline]
            fn newton_storage() -> [#real; #total] {
                [#zero; #total]
            }
            #solver
        }
    };
    NewtonCode { impl_block, matrix_ops: Ops::default(), storage }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A chain of n planar bodies on revolutes (2 rows per joint, joint k between bodies k − 1
    /// and k), with the φφ entries of K: the planned factors grow linearly with n, and every
    /// multiplier comes after the velocities of its row.
    #[test]
    fn a_chains_factors_grow_linearly() {
        let entries = |n: usize| {
            let (nv, nc) = (3 * n, 2 * n);
            let velocity: BTreeSet<(usize, usize)> = (0..nv).map(|i| (i, i)).collect();
            let mut jacobian = Vec::new();
            for k in 0..n {
                // Row x touches x and φ of both bodies, row y their y and φ; ground has none.
                for (row, axis) in [(2 * k, 0), (2 * k + 1, 1)] {
                    let bodies = if k > 0 { vec![k - 1, k] } else { vec![k] };
                    for b in bodies {
                        jacobian.push((row, 3 * b + axis));
                        jacobian.push((row, 3 * b + 2));
                    }
                }
            }
            let plan = NewtonPlan::plan(nv, nc, &velocity, &jacobian);
            for &(r, c) in &jacobian {
                assert!(plan.position[c] < plan.position[nv + r], "row {r} before velocity {c}");
            }
            println!("{n} links: {} updates", plan.updates());
            plan.entries()
        };
        let (e16, e32, e64) = (entries(16), entries(32), entries(64));
        println!("entries of the factors: {e16}, {e32}, {e64} for 16, 32, 64 links");
        // Each link adds the same block of entries (the ends differ by a constant).
        assert_eq!(e64 - e32, 2 * (e32 - e16), "linear growth: {e16}, {e32}, {e64}");
        assert!(e64 < 64 * 5 * 10, "{e64} entries for 320 unknowns");
    }
}
