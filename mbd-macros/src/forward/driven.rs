//! A driven mechanism's kinematic solves (NV = NC) over the factorization of the forward
//! dynamics with unit weights, S = D Dᵀ: the position solve's Newton loop
//! (`Kinematics::sparse_position_solve`), the velocity and acceleration
//! (`sparse_velocity_acceleration`) and inverse dynamics' multipliers (`sparse_multipliers`),
//! each linear solve refined on its residual.

use proc_macro2::TokenStream;
use quote::quote;

use super::Plan;
use crate::emit::{in_functions, jacobian_values_outputs, usize_lit, vector_outputs, Output, PartSignature};

impl Plan<'_> {
    /// `Kinematics::sparse_position_solve`, `sparse_velocity_acceleration` and
    /// `sparse_multipliers`, and the helpers `constraint_solve` and `transpose_solve` they call.
    pub(super) fn driven(&self) -> (TokenStream, TokenStream, TokenStream) {
        let position_step = self.position_solve();
        let motion_step = self.velocity_acceleration();
        let multipliers_step = self.multipliers();
        let (constraint_solve, transpose_solve) = self.refined_solves();
        (quote!(#position_step #motion_step #multipliers_step), constraint_solve, transpose_solve)
    }

    /// M⁻¹'s off-diagonal argument of `schur_factor` with unit weights: zeros, where coupled.
    fn unit_off(&self) -> TokenStream {
        let zero = &self.zero;
        if self.coupled() {
            let n_off = usize_lit(self.coupling.len());
            quote!(&[#zero; #n_off],)
        } else {
            quote!()
        }
    }

    /// The kinematic position solve: Newton's iteration with the step −Dᵀ(D Dᵀ)⁻¹Φ over the same
    /// factorization with unit weights (the step is D⁻¹(−Φ) for any weights when D is square and
    /// regular), the loop in the generated code: what depends only on t (a driver's sin(ωt)) is
    /// computed once before it, and D only after Φ's convergence test, in stages sharing their
    /// subexpressions. The rules — convergence, the iteration limit, when D's factors are kept
    /// (simplified Newton), the damped step — are the runtime's `mbd::__private::Newton`, which the dense
    /// solve follows too.
    ///
    /// Where Φ and D together take more than `PART_NODES` operations, the loop evaluates them
    /// apart, each through `Emitter::body_in_parts` (in methods of bounded size where it is
    /// larger still): one straight-line loop body of Φ and D made the 240-body chain's
    /// `sparse_position_solve` the largest function LLVM compiled, 2.7 times as long as at 120
    /// bodies. Apart, D recomputes what it shares with Φ (the bodies' sines and cosines), and
    /// what depends on t alone is no longer computed once per solve.
    fn position_solve(&self) -> TokenStream {
        let Plan { f, e, real, zero, one, nq_l, nv_l, nc_l, nnz_l, nl_l, .. } = self;
        let phi_outputs = vector_outputs("phi", &f.phi);
        let jv_outputs = jacobian_values_outputs(f, "jv");
        let together: Vec<Output> = phi_outputs.iter().chain(&jv_outputs).cloned().collect();
        let (time_terms, phi_stage, jv_stage) = if e.nodes(&together) > crate::emit::PART_NODES {
            let phi_part = PartSignature {
                name: "position_solve_phi",
                params: quote!(q: &[#real; #nq_l], t: #real, phi: &mut [#real; #nc_l],),
                args: quote!(q, t, phi,),
            };
            let (phi_in_parts, _) = e.body_in_parts(&phi_outputs, &phi_part);
            let jv_part = PartSignature {
                name: "position_solve_jacobian",
                params: quote!(q: &[#real; #nq_l], t: #real, jv: &mut [#real; #nnz_l],),
                args: quote!(q, t, &mut jv,),
            };
            let (jv_in_parts, _) = e.body_in_parts(&jv_outputs, &jv_part);
            (quote!(), phi_in_parts, jv_in_parts)
        } else {
            let (time_terms, mut stages) = e.staged(&[&phi_outputs, &jv_outputs]);
            let jv_stage = stages.pop().expect("two stages");
            let phi_stage = stages.pop().expect("two stages");
            (time_terms, phi_stage, jv_stage)
        };
        let unit_off = self.unit_off();
        let step_columns: Vec<TokenStream> = (0..self.nv)
            .filter_map(|c| {
                let cl = usize_lit(c);
                self.transpose_column(&quote!(b), c).map(|t| quote!(step[#cl] = -#t;))
            })
            .collect();
        let step_columns = in_functions(&step_columns, "step_columns", &[], real);
        let step_inline = self.inline_if_small(false);
        quote! {
            #step_inline
            #[allow(clippy::too_many_arguments)]
            fn sparse_position_solve(
                &self,
                q: &mut [#real; #nq_l],
                t: #real,
                tolerance: #real,
                pivot_tolerance: #real,
                max_iterations: u32,
                reuse: #real,
                max_step: #real,
                phi: &mut [#real; #nc_l],
                step: &mut [#real; #nv_l],
            ) -> ::core::option::Option<(::mbd::PositionStep, u32, u32)> {
                let mut jv = [#zero; #nnz_l];
                let mut l = [#zero; #nl_l];
                let mut dinv = [#zero; #nc_l];
                let mut newton = ::mbd::__private::Newton::new(tolerance, max_iterations, reuse, max_step);
                #time_terms
                loop {
                    {
                        let q: &[#real; #nq_l] = q;
                        #phi_stage
                        match newton.after_residual(phi) {
                            ::mbd::__private::NewtonNext::Stop(end) => return ::core::option::Option::Some(newton.end(end)),
                            ::mbd::__private::NewtonNext::Factor => {
                                #jv_stage
                                if Self::schur_factor(&jv, &[#one; #nv_l], #unit_off pivot_tolerance, false, &mut l, &mut dinv).is_err() {
                                    return ::core::option::Option::Some(newton.end(::mbd::PositionStep::Singular));
                                }
                                newton.factored();
                            }
                            ::mbd::__private::NewtonNext::Reuse => {}
                        }
                        let mut b = *phi;
                        Self::schur_solve(&l, &dinv, &mut b);
                        *step = [#zero; #nv_l];
                        #step_columns
                    }
                    if !newton.accept_step(step) {
                        return ::core::option::Option::Some(newton.end(::mbd::PositionStep::Step));
                    }
                    ::mbd::Kinematics::integrate_positions(self, q, step, #one);
                }
            }
        }
    }

    /// The kinematic velocity and acceleration of a driven mechanism over the same
    /// factorization: D, ν, then γ with the velocity solved, each solve x = Dᵀ(D Dᵀ)⁻¹ b refined
    /// on its residual (`constraint_solve`). Where Φ_t vanishes, D v = 0 and v = 0 without a
    /// solve.
    fn velocity_acceleration(&self) -> TokenStream {
        let Plan { f, e, real, zero, one, nq_l, nv_l, nc_l, nnz_l, nl_l, .. } = self;
        let phi_t_zero = f.phi_t_is_zero();
        let mut first_outputs = jacobian_values_outputs(f, "jv");
        if !phi_t_zero {
            first_outputs.extend(vector_outputs("nu", &f.nu));
        }
        let gamma_outputs = vector_outputs("gamma", &f.gamma);
        let both: Vec<Output> = first_outputs.iter().chain(&gamma_outputs).cloned().collect();
        // Large: the `Kinematics` methods that evaluate them already (in parts), called; parts
        // of their own would recompute the same and only add to the build.
        let (motion_time_terms, first_stage, gamma_stage) = if e.nodes(&both) > crate::emit::PART_NODES {
            let nu_call = (!phi_t_zero).then(|| quote!(::mbd::Kinematics::velocity_rhs(self, q, t, &mut nu);));
            (quote!(), quote!(self.jacobian_values(q, t, &mut jv); #nu_call), quote!(::mbd::Kinematics::gamma(self, q, v, t, &mut gamma);))
        } else {
            let (time_terms, mut stages) = e.staged(&[&first_outputs, &gamma_outputs]);
            let gamma_stage = stages.pop().expect("two stages");
            let first_stage = stages.pop().expect("two stages");
            (time_terms, first_stage, gamma_stage)
        };
        let solve_velocity = if phi_t_zero {
            quote!(*v = [#zero; #nv_l];)
        } else {
            quote! {
                if !Self::constraint_solve(&jv, &l, &dinv, &nu, v) {
                    return false;
                }
            }
        };
        let (unit_off, step_inline) = (self.unit_off(), self.inline_if_small(false));
        quote! {
            #step_inline
            fn sparse_velocity_acceleration(
                &self,
                q: &[#real; #nq_l],
                t: #real,
                pivot_tolerance: #real,
                v: &mut [#real; #nv_l],
                vd: &mut [#real; #nv_l],
            ) -> bool {
                let mut jv = [#zero; #nnz_l];
                let mut nu = [#zero; #nc_l];
                let mut gamma = [#zero; #nc_l];
                #motion_time_terms
                #first_stage
                let mut l = [#zero; #nl_l];
                let mut dinv = [#zero; #nc_l];
                if Self::schur_factor(&jv, &[#one; #nv_l], #unit_off pivot_tolerance, false, &mut l, &mut dinv).is_err() {
                    return false;
                }
                #solve_velocity
                {
                    let v: &[#real; #nv_l] = v;
                    #gamma_stage
                }
                Self::constraint_solve(&jv, &l, &dinv, &gamma, vd)
            }
        }
    }

    /// Inverse dynamics' multipliers, Dᵀλ = b, over the same factorization: λ = (D Dᵀ)⁻¹ D b,
    /// refined on the residual b − Dᵀλ (`transpose_solve`); D's non-zeros by the `Kinematics`
    /// method.
    fn multipliers(&self) -> TokenStream {
        let Plan { real, zero, one, nq_l, nv_l, nc_l, nnz_l, nl_l, .. } = self;
        let (unit_off, step_inline) = (self.unit_off(), self.inline_if_small(false));
        quote! {
            #step_inline
            fn sparse_multipliers(
                &self,
                q: &[#real; #nq_l],
                t: #real,
                pivot_tolerance: #real,
                b: &[#real; #nv_l],
                lambda: &mut [#real; #nc_l],
            ) -> bool {
                let mut jv = [#zero; #nnz_l];
                self.jacobian_values(q, t, &mut jv);
                let mut l = [#zero; #nl_l];
                let mut dinv = [#zero; #nc_l];
                if Self::schur_factor(&jv, &[#one; #nv_l], #unit_off pivot_tolerance, false, &mut l, &mut dinv).is_err() {
                    return false;
                }
                Self::transpose_solve(&jv, &l, &dinv, b, lambda)
            }
        }
    }

    /// `constraint_solve`: x = Dᵀ(D Dᵀ)⁻¹ b, then up to four refinements
    /// x ← x + Dᵀ(D Dᵀ)⁻¹(b − D x) (`sparse::refine` says when to stop): the normal equations
    /// square D's condition number, the refinement brings the error back to an LU's. And
    /// `transpose_solve`: λ = (D Dᵀ)⁻¹ D b, then up to four refinements
    /// λ ← λ + (D Dᵀ)⁻¹ D (b − Dᵀλ).
    fn refined_solves(&self) -> (TokenStream, TokenStream) {
        let Plan { real, zero, nv_l, nc_l, nnz_l, nl_l, rows, cols, .. } = self;
        let columns_into = |x: &str, assign: TokenStream| -> TokenStream {
            let x = syn::Ident::new(x, proc_macro2::Span::call_site());
            let stmts: Vec<TokenStream> = (0..self.nv)
                .filter_map(|c| {
                    let cl = usize_lit(c);
                    self.transpose_column(&quote!(b), c).map(|t| quote!(#x[#cl] #assign #t;))
                })
                .collect();
            in_functions(&stmts, "solution_columns", &[], real)
        };
        let solution = columns_into("x", quote!(=));
        let correction = columns_into("dx", quote!(=));
        let residual_rows: Vec<TokenStream> =
            rows.iter().zip(self.row_times(&quote!(x))).map(|(r, d_x)| quote!(b[#r] = rhs[#r] - #d_x;)).collect();
        let residual_rows = in_functions(&residual_rows, "residual_rows", &[], real);
        let helper_inline_solve = self.inline_if_small(false);
        let rows_of = |y: &str| -> TokenStream {
            let y = syn::Ident::new(y, proc_macro2::Span::call_site());
            let stmts: Vec<TokenStream> = rows.iter().zip(self.row_times(&quote!(#y))).map(|(r, d_y)| quote!(b[#r] = #d_y;)).collect();
            in_functions(&stmts, "transpose_rows", &[], real)
        };
        let (rows_of_rhs, rows_of_w) = (rows_of("rhs"), rows_of("w"));
        let residual_columns: Vec<TokenStream> = cols
            .iter()
            .enumerate()
            .map(|(c, cl)| match self.transpose_column(&quote!(x), c) {
                Some(t) => quote!(w[#cl] = rhs[#cl] - #t;),
                None => quote!(w[#cl] = rhs[#cl];),
            })
            .collect();
        let residual_columns = in_functions(&residual_columns, "residual_columns", &[], real);
        let transpose_solve = quote! {
            /// x = D⁻ᵀ b for a square, regular D from `schur_factor`'s factors of D Dᵀ, refined
            /// on its residual; false where the refinement does not settle.
            #helper_inline_solve
            fn transpose_solve(
                jv: &[#real; #nnz_l],
                l: &[#real; #nl_l],
                dinv: &[#real; #nc_l],
                rhs: &[#real; #nv_l],
                x: &mut [#real; #nc_l],
            ) -> bool {
                let mut b = [#zero; #nc_l];
                #rows_of_rhs
                Self::schur_solve(l, dinv, &mut b);
                *x = b;
                ::mbd::__private::refined(x, |x, b| {
                    let mut w = [#zero; #nv_l];
                    #residual_columns
                    #rows_of_w
                    Self::schur_solve(l, dinv, b);
                })
            }
        };
        let constraint_solve = quote! {
            /// x = D⁻¹ b for a square, regular D from `schur_factor`'s factors of D Dᵀ, refined on
            /// its residual; false where the refinement does not settle.
            #helper_inline_solve
            fn constraint_solve(
                jv: &[#real; #nnz_l],
                l: &[#real; #nl_l],
                dinv: &[#real; #nc_l],
                rhs: &[#real; #nc_l],
                x: &mut [#real; #nv_l],
            ) -> bool {
                let mut b = *rhs;
                Self::schur_solve(l, dinv, &mut b);
                *x = [#zero; #nv_l];
                #solution
                ::mbd::__private::refined(x, |x, dx| {
                    let mut b = [#zero; #nc_l];
                    #residual_rows
                    Self::schur_solve(l, dinv, &mut b);
                    #correction
                })
            }
        };
        (constraint_solve, transpose_solve)
    }
}
