//! `impl Dynamics` in joint coordinates (`formulation::joint`): M x, h, V and the power as
//! straight-line code, O(N) each; M and the dense derivatives ∂h/∂q, ∂h/∂v, ∂(M x)/∂q and the
//! friction's filled one column at a time from their products with a direction (a private
//! method each, O(N) code; O(N) work per column). Their op counts are one column's.

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use super::{DynamicsFunctions, Gen};
use crate::emit::{usize_lit, vector_outputs, Ops, Output};
use crate::formulation::TreeTerms;
use crate::sym::Id;

impl Gen<'_> {
    /// A private method `name(&self, <params>, out)` writing `out = nodes` (every entry), for
    /// the mechanism's inherent `impl`; its op counts.
    fn product(&self, name: &str, nodes: &[Id], params: TokenStream) -> Ops {
        let Gen { e, real, zero, nv_l, .. } = self;
        let (body, ops) = e.body(&vector_outputs("out", nodes));
        let name = format_ident!("{}", name);
        e.parts.borrow_mut().push(quote! {
            #[inline(never)]
            fn #name(&self, #params, out: &mut [#real; #nv_l]) {
                *out = [#zero; #nv_l];
                #body
            }
        });
        ops
    }

    /// `matrix[r][c] (op)= scale · column_c[r]` for every column c, each from `call` with the
    /// unit vector `dir = e_c`.
    fn by_columns(&self, call: TokenStream, matrix: TokenStream, assign: TokenStream) -> TokenStream {
        let Gen { e, zero, nv_l, .. } = self;
        let one = e.literal(1.0);
        quote! {
            let mut dir = [#zero; #nv_l];
            let mut out = [#zero; #nv_l];
            for c in 0..#nv_l {
                dir[c] = #one;
                #call;
                dir[c] = #zero;
                for (row, &value) in #matrix.iter_mut().zip(&out) {
                    row[c] #assign value;
                }
            }
        }
    }

    /// `Dynamics::solve_mass` (x ← M⁻¹x, `dir` = x) and `Dynamics::free_accelerations`
    /// (v̇ = M⁻¹h) by the articulated-body recursion.
    fn recursions(&self, terms: &TreeTerms) -> (TokenStream, [Ops; 2], Option<[Ops; 2]>) {
        let Gen { real, nq_l, nv_l, .. } = self;
        let (solve_body, solve_ops) = self.pivot_checked(&terms.mass_solve, terms, quote!(x));
        let (free_body, free_ops) = self.pivot_checked(&terms.free_accelerations, terms, quote!(vd));
        let (rows, rows_ops) = match self.solve_mass_rows(terms) {
            Some((code, ops)) => (code, Some(ops)),
            None => (quote!(), None),
        };
        let code = quote! {
            #rows
            #[inline(never)]
            fn solve_mass(&self, q: &[#real; #nq_l], x: &mut [#real; #nv_l]) -> ::core::option::Option<::core::result::Result<(), usize>> {
                let dir = *x;
                #solve_body
            }
            #[inline(never)]
            fn free_accelerations(
                &self,
                q: &[#real; #nq_l],
                v: &[#real; #nv_l],
                t: #real,
                vd: &mut [#real; #nv_l],
            ) -> ::core::option::Option<::core::result::Result<(), usize>> {
                #free_body
            }
        };
        (code, [solve_ops, free_ops], rows_ops)
    }

    /// `Dynamics::solve_mass_rows` (each row r ← M⁻¹ row r, the constraint rows' right-hand
    /// sides) where there are rows: the recursion staged over `dir` alone, so that what depends
    /// on q only — the articulated inertias, their factors and the links' transforms — is
    /// computed once before the loop over the rows, and each row runs only the passes of its
    /// right-hand side. Its op counts: the shared part, and each row's.
    fn solve_mass_rows(&self, terms: &TreeTerms) -> Option<(TokenStream, [Ops; 2])> {
        let Gen { e, real, zero, nq_l, nv_l, nc_l, .. } = self;
        if self.f.nc == 0 {
            return None;
        }
        let mut outputs = vector_outputs("out", &terms.mass_solve);
        let pivot_nodes: Vec<Id> = terms.pivots.iter().map(|&(_, node)| node).collect();
        outputs.extend(vector_outputs("pivots", &pivot_nodes));
        let (shared, mut stages, ops) = e.staged_over(&[&outputs], |v| matches!(v, crate::sym::Var::Dir(_)));
        let each = stages.pop().expect("one stage");
        let n = usize_lit(pivot_nodes.len());
        let velocities = terms.pivots.iter().map(|&(i, _)| usize_lit(i));
        let code = quote! {
            #[inline(never)]
            fn solve_mass_rows(&self, q: &[#real; #nq_l], rows: &mut [[#real; #nv_l]; #nc_l]) -> ::core::option::Option<::core::result::Result<(), usize>> {
                const VELOCITY: [usize; #n] = [#(#velocities),*];
                #shared
                for (r, row) in rows.iter_mut().enumerate() {
                    let dir = *row;
                    let mut out = [#zero; #nv_l];
                    let mut pivots = [#zero; #n];
                    #each
                    // The pivots depend on q alone: checked with the first row.
                    if r == 0 {
                        for (&pivot, &velocity) in pivots.iter().zip(&VELOCITY) {
                            if !(pivot.is_finite() && pivot > #zero) {
                                return ::core::option::Option::Some(::core::result::Result::Err(velocity));
                            }
                        }
                    }
                    *row = out;
                }
                ::core::option::Option::Some(::core::result::Result::Ok(()))
            }
        };
        Some((code, [ops[0], ops[1]]))
    }

    /// The recursion's outputs and pivots evaluated, the pivots checked (each positive and
    /// finite, else `Some(Err(the first velocity of its link))`), then the outputs written to
    /// `target`.
    fn pivot_checked(&self, outputs: &[Id], terms: &TreeTerms, target: TokenStream) -> (TokenStream, Ops) {
        let Gen { e, zero, nv_l, .. } = self;
        let mut all = vector_outputs("out", outputs);
        let pivot_nodes: Vec<Id> = terms.pivots.iter().map(|&(_, node)| node).collect();
        all.extend(vector_outputs("pivots", &pivot_nodes));
        let (body, ops) = e.body(&all);
        let n = usize_lit(pivot_nodes.len());
        let velocities = terms.pivots.iter().map(|&(i, _)| usize_lit(i));
        let code = quote! {
            let mut out = [#zero; #nv_l];
            let mut pivots = [#zero; #n];
            #body
            const VELOCITY: [usize; #n] = [#(#velocities),*];
            for (&pivot, &velocity) in pivots.iter().zip(&VELOCITY) {
                if !(pivot.is_finite() && pivot > #zero) {
                    return ::core::option::Option::Some(::core::result::Result::Err(velocity));
                }
            }
            *#target = out;
            ::core::option::Option::Some(::core::result::Result::Ok(()))
        };
        (code, ops)
    }

    /// `Dynamics::add_mass_matrix`: a += scale M, M entry by entry by the composite-rigid-body
    /// algorithm where the tree emits it (and its op counts), else a column at a time from M x.
    fn mass_matrix(&self, terms: &TreeTerms) -> (TokenStream, Option<Ops>) {
        let Gen { e, zero, nv_l, .. } = self;
        let Some(rows) = &terms.mass_matrix else {
            return (self.by_columns(quote!(self.mbd_mass_times(q, &dir, &mut out)), quote!(a), quote!(+= scale *)), None);
        };
        let outputs: Vec<Output> = rows
            .iter()
            .enumerate()
            .flat_map(|(r, row)| {
                row.iter().enumerate().map(move |(c, &node)| {
                    let (r, c) = (usize_lit(r), usize_lit(c));
                    Output { target: quote!(m[#r][#c]), node }
                })
            })
            .collect();
        let (body, ops) = e.body(&outputs);
        let code = quote! {
            let mut m = [[#zero; #nv_l]; #nv_l];
            #body
            for (row, entries) in a.iter_mut().zip(&m) {
                for (x, &y) in row.iter_mut().zip(entries) {
                    *x += scale * y;
                }
            }
        };
        (code, Some(ops))
    }

    /// `Dynamics::motion_size`: every body's twist J_b x (one pass over the tree), its largest
    /// component.
    fn motion_size(&self) -> TokenStream {
        let Gen { f, e, real, zero, nq_l, nv_l, .. } = self;
        let twists: Vec<Id> = f.frames.iter().flat_map(|frame| frame.twist.iter().copied()).collect();
        let (body, _) = e.body(&vector_outputs("twists", &twists));
        let n = usize_lit(twists.len());
        quote! {
            fn motion_size(&self, q: &[#real; #nq_l], x: &[#real; #nv_l]) -> #real {
                #[allow(clippy::redundant_locals)]
                let v = x;
                let mut twists = [#zero; #n];
                #body
                twists.iter().fold(#zero, |size, &x| <#real as ::mbd::Real>::max(size, <#real as ::mbd::Real>::abs(x)))
            }
        }
    }

    /// `ConstraintForces::constraint_force_q`'s body for a tree, K a column at a time, and one
    /// column's op counts.
    pub(super) fn joint_constraint_force_q(&self, terms: &TreeTerms) -> (TokenStream, Ops) {
        let Gen { real, nq_l, nv_l, nc_l, .. } = self;
        let params = quote!(q: &[#real; #nq_l], t: #real, lambda: &[#real; #nc_l], dir: &[#real; #nv_l]);
        let ops = self.product("mbd_constraint_force_q_along", &terms.constraint_force_dq, params);
        (self.by_columns(quote!(self.mbd_constraint_force_q_along(q, t, lambda, &dir, &mut out)), quote!(k), quote!(=)), ops)
    }

    /// The `Dynamics` implementation of a tree, and one column's op counts of the dense
    /// functions.
    pub(super) fn joint_dynamics_impl(&self, d: &DynamicsFunctions, terms: &TreeTerms) -> (TokenStream, Vec<(&'static str, Ops)>) {
        let Gen { real, name, inline, nq_l, nv_l, nc_l, .. } = self;
        let state = quote!(q: &[#real; #nq_l], v: &[#real; #nv_l], t: #real);
        let direction = quote!(dir: &[#real; #nv_l]);
        let mass_ops = self.product("mbd_mass_times", &terms.mass_x, quote!(q: &[#real; #nq_l], v: &[#real; #nv_l]));
        let mass_q_ops =
            self.product("mbd_mass_derivative_along", &terms.mass_x_dq, quote!(q: &[#real; #nq_l], v: &[#real; #nv_l], #direction));
        let inverse_ops = self.product("mbd_inverse_forces", &terms.inverse, quote!(#state, #direction));
        let h_q_ops = self.product("mbd_forces_q_along", &terms.h_dq, quote!(#state, #direction));
        let h_v_ops = self.product("mbd_forces_v_along", &terms.h_dv, quote!(#state, #direction));
        let (mass_matrix, crba_ops) = self.mass_matrix(terms);
        let mass_derivative = self.by_columns(quote!(self.mbd_mass_derivative_along(q, x, &dir, &mut out)), quote!(a), quote!(+= scale *));
        let forces_q = self.by_columns(quote!(self.mbd_forces_q_along(q, v, t, &dir, &mut out)), quote!(dh), quote!(=));
        let forces_v = self.by_columns(quote!(self.mbd_forces_v_along(q, v, t, &dir, &mut out)), quote!(dh), quote!(=));
        let friction_derivatives = if terms.friction_dq.is_empty() {
            quote!()
        } else {
            let params = quote!(#state, lambda: &[#real; #nc_l], #direction);
            self.product("mbd_friction_q_along", &terms.friction_dq, params.clone());
            self.product("mbd_friction_v_along", &terms.friction_dv, params);
            let along_q = self.by_columns(quote!(self.mbd_friction_q_along(q, v, t, lambda, &dir, &mut out)), quote!(d_q), quote!(+=));
            let along_v = self.by_columns(quote!(self.mbd_friction_v_along(q, v, t, lambda, &dir, &mut out)), quote!(d_v), quote!(+=));
            quote!({ #along_q } { #along_v })
        };
        let (recursions, [solve_ops, free_ops], rows_ops) = self.recursions(terms);
        let motion_size = self.motion_size();
        let common = self.common_dynamics_items(d, &friction_derivatives);
        let mut ops = vec![
            ("solve_mass", solve_ops),
            ("free_accelerations", free_ops),
            ("mass_times", mass_ops),
            ("inverse_forces", inverse_ops),
            ("add_mass_derivative (one column)", mass_q_ops),
            ("forces_q (one column)", h_q_ops),
            ("forces_v (one column)", h_v_ops),
        ];
        ops.extend(crba_ops.map(|o| ("add_mass_matrix", o)));
        if let Some([shared, each]) = rows_ops {
            ops.extend([("solve_mass_rows (shared)", shared), ("solve_mass_rows (each row)", each)]);
        }
        let code = quote! {
            // Constants are the user's expressions evaluated (`PI / 2.0` → 1.5707963267948966).
            #[allow(unused_variables, unused_parens, unused_mut, clippy::approx_constant)]
            impl ::mbd::Dynamics<#real, #nq_l, #nv_l, #nc_l> for #name {
                #inline
                fn mass_times(&self, q: &[#real; #nq_l], x: &[#real; #nv_l], y: &mut [#real; #nv_l]) {
                    self.mbd_mass_times(q, x, y);
                }
                fn inverse_forces(&self, q: &[#real; #nq_l], v: &[#real; #nv_l], vd: &[#real; #nv_l], t: #real, tau: &mut [#real; #nv_l]) {
                    self.mbd_inverse_forces(q, v, t, vd, tau);
                }
                fn add_mass_matrix(&self, q: &[#real; #nq_l], scale: #real, a: &mut [[#real; #nv_l]; #nv_l]) {
                    #mass_matrix
                }
                fn add_mass_derivative(&self, q: &[#real; #nq_l], x: &[#real; #nv_l], scale: #real, a: &mut [[#real; #nv_l]; #nv_l]) {
                    #mass_derivative
                }
                #recursions
                #motion_size
                fn forces_q(&self, q: &[#real; #nq_l], v: &[#real; #nv_l], t: #real, dh: &mut [[#real; #nv_l]; #nv_l]) {
                    #forces_q
                }
                fn forces_v(&self, q: &[#real; #nq_l], v: &[#real; #nv_l], t: #real, dh: &mut [[#real; #nv_l]; #nv_l]) {
                    #forces_v
                }
                #common
            }
        };
        (code, ops)
    }
}
