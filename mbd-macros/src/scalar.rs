//! Constant-index array accesses of generated straight-line code read and written through
//! bindings of the elements: `l[5] = x[1] * l[6];` becomes
//!
//! ```text
//! let [__x_1] = x.window::<1, 1>();
//! let [__l_5, __l_6] = l.window_mut::<5, 2>();
//! (*__l_5) = (*__x_1) * (*__l_6);
//! ```
//!
//! (`mbd::__private::Elements`: `window::<K, M>()` is the array's elements K..K + M as an array,
//! by reference, so that the pattern names only the span the code touches.)
//!
//! Why: rustc type-checks every `a[k]` as an overloaded index (autoderef, the `Index` impls of
//! arrays and slices, their obligations), about 100 µs each and faster than linearly in the
//! function's length, where a pattern is checked once for the whole array. Measured on plain
//! straight-line code (`rustc --emit=metadata -Ztime-passes`), 20 000 statements
//! `y[a] = x[b] * x[c] + y[a]` took 7.5 s to type-check, and 0.42 s written on bindings; in the
//! 240-body chain of the build-scaling benchmark, type checking was 16.6 s of a 44.7 s build,
//! mostly the generated functions' indexing. The machine code is the indexing's: a binding is a
//! pointer to the element. Bindings by value instead (scalar locals copied in and stored back)
//! made LLVM's register allocation and scheduling on the long live ranges 3 times as long.
//!
//! A reference binding is live from its pattern to its last use, and the borrow checker's work
//! grows with the sum of those spans: scalarized whole, the 240-body chain's functions took it
//! from 3.3 to 6.5 s. So [`crate::emit::in_blocks`] rewrites each of its basic blocks (at most a
//! few hundred statements) on its own: every span is bounded, and the work is linear.
//!
//! Every identifier followed by a bracketed integer literal is taken for an array (the
//! generated code indexes nothing else that way), and rewritten only where every occurrence of
//! it in the code is such an access: an array used whole (`Self::schur_solve(&l, …)`, `*phi`,
//! a loop over it, its declaration), at a computed index, by nested indices (`d[2][5]`), or as
//! a field or path segment (`self.l`, `x::l`) keeps its indexing, so no binding's borrow meets
//! another use of the array.

use std::collections::{BTreeMap, BTreeSet};

use proc_macro2::{Delimiter, Group, Ident, Literal, Span, TokenStream, TokenTree};
use quote::{format_ident, quote};

/// `code` with its literal-index array accesses read and written through bindings of the
/// elements, declared by `let` statements put before it (not in a block of their own: `code`'s
/// own `let`s stay visible after it). An array written anywhere in `code` (`=`, `+=`, `-=`,
/// `*=`, `/=` after the access) is bound with `window_mut`, else with `window`.
pub fn scalarize(code: TokenStream) -> TokenStream {
    let mut uses = Uses::default();
    survey(&code, &mut uses);
    // A written array is bound through one window (two mutable ones could not coexist): where
    // its accesses lie in several clusters it keeps its indexing (the Newton matrix's storage,
    // written at scattered entries, would need patterns of thousands of `_`, and checking a
    // pattern costs rustc in proportion to its length).
    let rewritten: BTreeMap<&String, Vec<Vec<usize>>> = uses
        .indices
        .iter()
        .filter(|(name, _)| !uses.whole.contains(*name))
        .map(|(name, indices)| (name, clusters(indices)))
        .filter(|(name, clusters)| clusters.len() == 1 || !uses.written.contains(*name))
        .collect();
    if rewritten.is_empty() {
        return code;
    }
    let body = rewrite(code, &rewritten.keys().map(|n| (*n).clone()).collect());
    let lets = rewritten.iter().flat_map(|(name, clusters)| {
        let array = Ident::new(name, Span::call_site());
        let window = if uses.written.contains(*name) { quote!(window_mut) } else { quote!(window) };
        clusters.iter().map(move |cluster| {
            let (first, last) = (cluster[0], cluster[cluster.len() - 1]);
            let elements = (first..=last).map(|k| {
                if cluster.binary_search(&k).is_ok() {
                    let element = binding(name, k);
                    quote!(#element)
                } else {
                    quote!(_)
                }
            });
            let (start, len) = (Literal::usize_unsuffixed(first), Literal::usize_unsuffixed(last + 1 - first));
            quote!(let [#(#elements),*] = #array.#window::<#start, #len>();)
        })
    });
    quote!(use ::mbd::__private::Elements as _; #(#lets)* #body)
}

/// The arrays straight-line statements index by literal (each with whether they write it) and
/// the scalars of `scalars` they read, if that is all they read: `None` where they use an
/// array otherwise, read another identifier (a temporary, `self`), declare a local or may
/// leave early (`return`, `?`, `break`, `continue`).
pub fn free_arrays(stmts: &[TokenStream], scalars: &[&str]) -> Option<FreeNames> {
    let code = quote!(#(#stmts)*);
    let mut uses = Uses::default();
    survey(&code, &mut uses);
    let mut names = FreeNames::default();
    if !free_only(&code, scalars, &uses, &mut names.scalars) {
        return None;
    }
    names.arrays = uses.indices.keys().map(|n| (n.clone(), uses.written.contains(n))).collect();
    Some(names)
}

/// What [`free_arrays`] found: arrays (name, written) and scalars, each once, in name order.
#[derive(Default)]
pub struct FreeNames {
    pub arrays: Vec<(String, bool)>,
    pub scalars: BTreeSet<String>,
}

/// Whether every identifier of `code` is an array indexed by literal, a scalar of `scalars`
/// (collected into `found`), a path segment, a field or method, or one of the few keywords
/// straight-line array code uses.
fn free_only(code: &TokenStream, scalars: &[&str], uses: &Uses, found: &mut BTreeSet<String>) -> bool {
    let trees: Vec<TokenTree> = code.clone().into_iter().collect();
    for (i, tree) in trees.iter().enumerate() {
        match tree {
            TokenTree::Group(g) if !free_only(&g.stream(), scalars, uses, found) => return false,
            TokenTree::Punct(p) if p.as_char() == '?' => return false,
            TokenTree::Ident(id) => {
                let name = id.to_string();
                let path_head = matches!(trees.get(i + 1), Some(TokenTree::Punct(p)) if p.as_char() == ':');
                if qualified(&trees, i) || path_head || matches!(name.as_str(), "if" | "else" | "true" | "false" | "as") {
                    continue;
                }
                if uses.indices.contains_key(&name) && !uses.whole.contains(&name) {
                    continue;
                }
                if scalars.contains(&name.as_str()) {
                    found.insert(name);
                    continue;
                }
                return false;
            }
            _ => {}
        }
    }
    true
}

/// Indices more than this apart start a new cluster (a window of their own).
const CLUSTER_GAP: usize = 8;

/// The ascending indices cut where two are more than [`CLUSTER_GAP`] apart.
fn clusters(indices: &BTreeSet<usize>) -> Vec<Vec<usize>> {
    let mut out: Vec<Vec<usize>> = Vec::new();
    for &k in indices {
        match out.last_mut() {
            Some(cluster) if k - cluster[cluster.len() - 1] <= CLUSTER_GAP => cluster.push(k),
            _ => out.push(vec![k]),
        }
    }
    out
}

/// What the code does with each array.
#[derive(Default)]
struct Uses {
    /// The literal indices it accesses.
    indices: BTreeMap<String, BTreeSet<usize>>,
    /// Names used otherwise than by a literal index (the array whole, a computed index, nested
    /// indices, a field or path segment of that name); most identifiers are never arrays and
    /// land here.
    whole: BTreeSet<String>,
    /// Names with an access assigned to (`=`, `+=`, `-=`, `*=`, `/=` after it).
    written: BTreeSet<String>,
}

/// The binding of element `k` of array `name`.
fn binding(name: &str, k: usize) -> Ident {
    format_ident!("__{}_{}", name, k)
}

/// The literal index of a bracket group holding one unsuffixed integer (`[12]`).
fn literal_index(tree: Option<&TokenTree>) -> Option<usize> {
    let Some(TokenTree::Group(g)) = tree else { return None };
    if g.delimiter() != Delimiter::Bracket {
        return None;
    }
    let mut inner = g.stream().into_iter();
    match (inner.next(), inner.next()) {
        (Some(TokenTree::Literal(l)), None) => l.to_string().parse().ok(),
        _ => None,
    }
}

/// Whether the tokens from `at` start an assignment (`=` not part of `==`, or `+=` and the like).
fn assigns(trees: &[TokenTree], at: usize) -> bool {
    let punct = |i: usize| match trees.get(i) {
        Some(TokenTree::Punct(p)) => Some(p.as_char()),
        _ => None,
    };
    match (punct(at), punct(at + 1)) {
        (Some('='), Some('=')) => false,
        (Some('='), _) => true,
        (Some('+' | '-' | '*' | '/'), Some('=')) => true,
        _ => false,
    }
}

/// Whether the identifier at `at` is a path segment or a field (`a::q`, `self.q`), not the
/// variable.
fn qualified(trees: &[TokenTree], at: usize) -> bool {
    match at.checked_sub(1).and_then(|i| trees.get(i)) {
        Some(TokenTree::Punct(p)) => p.as_char() == '.' || (p.as_char() == ':' && at >= 2),
        _ => false,
    }
}

fn survey(code: &TokenStream, uses: &mut Uses) {
    let trees: Vec<TokenTree> = code.clone().into_iter().collect();
    for (i, tree) in trees.iter().enumerate() {
        match tree {
            TokenTree::Group(g) => survey(&g.stream(), uses),
            TokenTree::Ident(id) => {
                let name = id.to_string();
                let index = literal_index(trees.get(i + 1));
                let nested = matches!(trees.get(i + 2), Some(TokenTree::Group(g)) if g.delimiter() == Delimiter::Bracket);
                match index {
                    Some(k) if !qualified(&trees, i) && !nested => {
                        uses.indices.entry(name.clone()).or_default().insert(k);
                        if assigns(&trees, i + 2) {
                            uses.written.insert(name);
                        }
                    }
                    _ => {
                        uses.whole.insert(name);
                    }
                }
            }
            _ => {}
        }
    }
}

fn rewrite(code: TokenStream, names: &BTreeSet<String>) -> TokenStream {
    let trees: Vec<TokenTree> = code.into_iter().collect();
    let mut out = Vec::with_capacity(trees.len());
    let mut i = 0;
    while i < trees.len() {
        match &trees[i] {
            TokenTree::Group(g) => {
                let mut group = Group::new(g.delimiter(), rewrite(g.stream(), names));
                group.set_span(g.span());
                out.push(TokenTree::Group(group));
            }
            TokenTree::Ident(id) if names.contains(&id.to_string()) && !qualified(&trees, i) => {
                if let Some(k) = literal_index(trees.get(i + 1)) {
                    let element = binding(&id.to_string(), k);
                    out.extend(quote!((*#element)));
                    i += 2;
                    continue;
                }
                out.push(trees[i].clone());
            }
            other => out.push(other.clone()),
        }
        i += 1;
    }
    out.into_iter().collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proc_macro2::Literal;

    fn lit(n: usize) -> Literal {
        Literal::usize_unsuffixed(n)
    }

    fn text(t: TokenStream) -> String {
        t.to_string().split_whitespace().collect::<Vec<_>>().join(" ")
    }

    #[test]
    fn literal_accesses_become_bindings_and_writes_bind_mutably() {
        let (a, b) = (lit(3), lit(1));
        let code = quote!(l[#a] = jv[#b] * jv[#a] * d[#b]; d[#a] -= l[#a];);
        let expected = quote!(
            use ::mbd::__private::Elements as _;
            let [__d_1, _, __d_3] = d.window_mut::<1, 3>();
            let [__jv_1, _, __jv_3] = jv.window::<1, 3>();
            let [__l_3] = l.window_mut::<3, 1>();
            (*__l_3) = (*__jv_1) * (*__jv_3) * (*__d_1);
            (*__d_3) -= (*__l_3);
        );
        assert_eq!(text(scalarize(code)), text(expected));
    }

    /// An array used whole, at a computed index or by nested indices keeps its indexing; a
    /// comparison is not a write; a field or path of the same name makes the name ambiguous,
    /// and it is left alone.
    #[test]
    fn an_array_used_otherwise_is_left_alone() {
        let k = lit(1);
        let code = quote!(b[#k] = l[#k] + x[#k] + self.x + y::z; z[#k] = 1.0; solve(&b); if l[#k] == l[0] {} c[i] = c[#k]; m[0][1] = l[0];);
        let expected = quote!(
            use ::mbd::__private::Elements as _;
            let [__l_0, __l_1] = l.window::<0, 2>();
            b[#k] = (*__l_1) + x[#k] + self.x + y::z; z[#k] = 1.0; solve(&b); if (*__l_1) == (*__l_0) {} c[i] = c[#k]; m[0][1] = (*__l_0);
        );
        assert_eq!(text(scalarize(code)), text(expected));
    }

    /// The arrays and named scalars of pure array code, for `emit::in_functions`; anything a
    /// nested function could not see or would change (a temporary, `self`, a `let`, an early
    /// `return`, `?`, an array also used whole) makes it `None`.
    #[test]
    fn free_arrays_are_the_indexed_arrays_and_the_named_scalars() {
        let code = [quote!(b[3] -= l[5] * b[1];), quote!(lambda[0] = gamma[0] - two_alpha * nu[0];)];
        let names = free_arrays(&code, &["two_alpha", "beta2"]).expect("pure array code");
        let arrays: Vec<(&str, bool)> = names.arrays.iter().map(|(n, w)| (n.as_str(), *w)).collect();
        assert_eq!(arrays, [("b", true), ("gamma", false), ("l", false), ("lambda", true), ("nu", false)]);
        assert_eq!(names.scalars.into_iter().collect::<Vec<_>>(), ["two_alpha"]);
        for other in [
            quote!(b[0] = tmp * l[1];),
            quote!(b[0] = self.x;),
            quote!(let x = l[0];),
            quote!(if b[0] > 1.0 {
                return;
            }),
            quote!(b[0] = f(l[0])?;),
            quote!(b[0] = l[0]; solve(&b);),
        ] {
            assert!(free_arrays(std::slice::from_ref(&other), &["two_alpha"]).is_none(), "{other}");
        }
    }

    /// Accesses far apart are bound through a window each where the array is only read, and
    /// left indexed where it is written (one mutable window at a time).
    #[test]
    fn scattered_accesses_take_a_window_each_or_keep_their_indexing() {
        let code = quote!(s[40] = x[0] + x[30] + x[31]; s[2] = 1.0; y[5] = x[0];);
        let expected = quote!(
            use ::mbd::__private::Elements as _;
            let [__x_0] = x.window::<0, 1>();
            let [__x_30, __x_31] = x.window::<30, 2>();
            let [__y_5] = y.window_mut::<5, 1>();
            s[40] = (*__x_0) + (*__x_30) + (*__x_31); s[2] = 1.0; (*__y_5) = (*__x_0);
        );
        assert_eq!(text(scalarize(code)), text(expected));
    }
}
