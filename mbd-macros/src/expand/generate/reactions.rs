//! `impl mbd::JointLoads`: each body's wrench from the constraint rows (D_bᵀλ), and in joint
//! coordinates what each tree joint transmits (`formulation::joint`, `Kinematics::joint_wrenches`).
//! Every body's is evaluated at once (O(N) code for a chain, the tree's recursion shared) and
//! the one asked for returned, as `BodyFrames` does.

use proc_macro2::TokenStream;
use quote::quote;

use super::Gen;
use crate::emit::{usize_lit, Output};
use crate::model::Space;
use crate::sym::Id;

impl Gen<'_> {
    /// Outputs `out[k]…[part][axis]` of each body's wrenches (`wrenches[k]`: one or two wrenches
    /// of nt entries, `side` indexing them when there are two), the plane's (F_x, F_y, n) placed
    /// at force x, y and moment z.
    fn wrench_outputs(&self, wrenches: &[Vec<Id>], sides: bool) -> Vec<Output> {
        let planar = self.m.space == Space::Planar;
        let nt = if planar { 3 } else { 6 };
        let slot = |c: usize| if planar { [(0, 0), (0, 1), (1, 2)][c] } else { (c / 3, c % 3) };
        wrenches
            .iter()
            .enumerate()
            .flat_map(|(k, w)| {
                w.iter().enumerate().map(move |(c, &node)| {
                    let (k, (part, axis)) = (usize_lit(k), slot(c % nt));
                    let (part, axis) = (usize_lit(part), usize_lit(axis));
                    let target = if sides {
                        let side = usize_lit(c / nt);
                        quote!(out[#k][#side][#part][#axis])
                    } else {
                        quote!(out[#k][#part][#axis])
                    };
                    Output { target, node }
                })
            })
            .collect()
    }

    pub(super) fn joint_loads_impl(&self) -> TokenStream {
        let Gen { m, f, e, real, name, zero, nq_l, nv_l, nc_l, .. } = self;
        let nb = usize_lit(m.bodies.len());
        let (constraint, _) = e.body(&self.wrench_outputs(&f.constraint_wrenches, false));
        let wrench = |at: TokenStream| quote!(::mbd::BodyWrench { force: #at[0], moment: #at[1] });
        let constraint_out = wrench(quote!(out[body]));
        let tree = f.tree.as_ref().zip(m.tree.as_ref()).map(|(terms, tree)| {
            let (body, _) = e.body(&self.wrench_outputs(&terms.joint_wrenches, true));
            let joints = tree.links.iter().map(|link| match link.joint {
                Some(j) => {
                    let j = j as u16;
                    quote!(::core::option::Option::Some(#j))
                }
                None => quote!(::core::option::Option::None),
            });
            let (on_child, on_parent) = (wrench(quote!(out[body][0])), wrench(quote!(out[body][1])));
            quote! {
                const TREE_JOINTS: &'static [::core::option::Option<u16>] = &[#(#joints),*];
                fn tree_joint_wrenches(
                    &self,
                    body: usize,
                    q: &[#real; #nq_l],
                    v: &[#real; #nv_l],
                    vd: &[#real; #nv_l],
                    t: #real,
                    lambda: &[#real; #nc_l],
                ) -> ::core::option::Option<[::mbd::BodyWrench<#real>; 2]> {
                    if body >= #nb || <Self as ::mbd::JointLoads<#real, #nq_l, #nv_l, #nc_l>>::TREE_JOINTS[body].is_none() {
                        return ::core::option::Option::None;
                    }
                    #[allow(clippy::redundant_locals)]
                    let dir = vd;
                    let mut out = [[[[#zero; 3]; 2]; 2]; #nb];
                    #body
                    ::core::option::Option::Some([#on_child, #on_parent])
                }
            }
        });
        quote! {
            #[allow(unused_variables, unused_mut, unused_parens, clippy::approx_constant)]
            impl ::mbd::JointLoads<#real, #nq_l, #nv_l, #nc_l> for #name {
                fn constraint_wrench(
                    &self,
                    body: usize,
                    q: &[#real; #nq_l],
                    t: #real,
                    lambda: &[#real; #nc_l],
                ) -> ::core::option::Option<::mbd::BodyWrench<#real>> {
                    if body >= #nb {
                        return ::core::option::Option::None;
                    }
                    let mut out = [[[#zero; 3]; 2]; #nb];
                    #constraint
                    ::core::option::Option::Some(#constraint_out)
                }
                #tree
            }
        }
    }
}
