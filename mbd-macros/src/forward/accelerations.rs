//! The `ForwardDynamics` implementation: the accelerations and multipliers from one fused
//! evaluation and one factorization of S = D M⁻¹ Dᵀ (with Coulomb friction, a fixed point on the
//! normal loads, each iteration one more solve), and the mass-weighted projections of positions
//! and velocities over the same factorization.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::products::inverse_outputs;
use super::Plan;
use crate::emit::{friction_outputs, in_functions, jacobian_values_outputs, usize_lit, vector_outputs, Ops, Output, PartSignature};

/// The fused evaluations, each in parts where large: the accelerations' (Φ, D's non-zeros, ν,
/// γ, h, M), the position projection's (Φ, D, M) and the velocity projection's (D, ν, M).
struct Evaluations {
    accelerations: TokenStream,
    ops: Ops,
    positions: TokenStream,
    velocities: TokenStream,
}

impl Plan<'_> {
    /// The signature of a function's parts: its inputs, the locals they write (M⁻¹'s blocks too
    /// when coupled).
    fn part(&self, name: &'static str, inputs: TokenStream, input_args: TokenStream, locals: &[(&str, &Literal)]) -> PartSignature {
        let real = &self.real;
        let (mi_param, mi_arg) = if !self.coupled() {
            (quote!(), quote!())
        } else {
            let n_mi = usize_lit(self.f.mass_inverse.len());
            (quote!(mi: &mut [#real; #n_mi],), quote!(&mut mi,))
        };
        let names: Vec<syn::Ident> = locals.iter().map(|(n, _)| syn::Ident::new(n, proc_macro2::Span::call_site())).collect();
        let lengths = locals.iter().map(|(_, l)| l);
        PartSignature {
            name,
            params: quote!(#inputs #(#names: &mut [#real; #lengths],)* #mi_param),
            args: quote!(#input_args #(&mut #names,)* #mi_arg),
        }
    }

    fn evaluations(&self) -> Evaluations {
        let Plan { f, e, real, nq_l, nv_l, nc_l, nnz_l, .. } = self;
        let jv_outputs: Vec<Output> = f
            .jacobian
            .iter()
            .enumerate()
            .map(|(k, &(_, _, node))| {
                let k = usize_lit(k);
                Output { target: quote!(jv[#k]), node }
            })
            .collect();
        let phi_t_zero = f.phi_t_is_zero();
        let mut outputs = jv_outputs;
        outputs.extend(vector_outputs("phi", &f.phi));
        if !phi_t_zero {
            outputs.extend(vector_outputs("nu", &f.nu));
        }
        outputs.extend(vector_outputs("gamma", &f.gamma));
        outputs.extend(vector_outputs("h", &f.h));
        outputs.extend(vector_outputs("m", &f.mass));
        outputs.extend(inverse_outputs(f));
        let evaluation = self.part(
            "accelerations",
            quote!(q: &[#real; #nq_l], v: &[#real; #nv_l], t: #real,),
            quote!(q, v, t,),
            &[("jv", nnz_l), ("phi", nc_l), ("nu", nc_l), ("gamma", nc_l), ("h", nv_l), ("m", nv_l)],
        );
        let (accelerations, ops) = e.body_in_parts(&outputs, &evaluation);

        let mut positions = vector_outputs("phi", &f.phi);
        positions.extend(jacobian_values_outputs(f, "jv"));
        positions.extend(vector_outputs("m", &f.mass));
        positions.extend(inverse_outputs(f));
        let position_part =
            self.part("positions", quote!(q: &[#real; #nq_l], t: #real,), quote!(q, t,), &[("jv", nnz_l), ("phi", nc_l), ("m", nv_l)]);
        let (positions, _) = e.body_in_parts(&positions, &position_part);

        let mut velocities = jacobian_values_outputs(f, "jv");
        if !phi_t_zero {
            velocities.extend(vector_outputs("nu", &f.nu));
        }
        velocities.extend(vector_outputs("m", &f.mass));
        velocities.extend(inverse_outputs(f));
        let velocity_part =
            self.part("velocities", quote!(q: &[#real; #nq_l], t: #real,), quote!(q, t,), &[("jv", nnz_l), ("nu", nc_l), ("m", nv_l)]);
        let (velocities, _) = e.body_in_parts(&velocities, &velocity_part);
        Evaluations { accelerations, ops, positions, velocities }
    }

    /// λ from S λ = γ − D M⁻¹h − Baumgarte's terms, then v̇ = M⁻¹(h + Dᵀλ): without Coulomb
    /// friction one solve; with it, fixed-point iteration on the normal loads λ (the
    /// factorization of S does not depend on them, so each iteration is one more solve).
    fn solve_for_lambda(&self) -> TokenStream {
        let Plan { f, e, real, zero, nv_l, nc_l, rows, cols, .. } = self;
        let (d_vd, d_v) = (self.row_times(&quote!(vd)), self.row_times(&quote!(v)));
        let lambda_vd = self.add_transpose(&quote!(vd), &quote!(lambda), quote!(+=));
        let minv_h = if self.coupled() {
            self.add_minv(&quote!(vd), &quote!(=), &|c| {
                let cl = usize_lit(c);
                Some(quote!(h[#cl]))
            })
        } else {
            cols.iter().map(|c| quote!(vd[#c] = h[#c] * minv[#c];)).collect()
        };
        let lambda_rows: Vec<TokenStream> = rows
            .iter()
            .zip(d_vd.iter().zip(&d_v))
            .map(|(r, (d_vd, d_v))| quote!(lambda[#r] = gamma[#r] - #d_vd - two_alpha * (#d_v - nu[#r]) - beta2 * phi[#r];))
            .collect();
        let (minv_h, lambda_rows, lambda_vd) = (
            in_functions(&minv_h, "minv_h", &[], real),
            in_functions(&lambda_rows, "lambda_rows", &["two_alpha", "beta2"], real),
            in_functions(&lambda_vd, "lambda_vd", &[], real),
        );
        let one_solve = quote! {
            #minv_h
            #lambda_rows
            Self::schur_solve(&l, &dinv, lambda);
            #lambda_vd
        };
        let friction = friction_outputs(f);
        if friction.is_empty() {
            return quote! {
                #one_solve
                ::core::result::Result::Ok(())
            };
        }
        let (friction_body, _) = e.body(&friction);
        // Coulomb friction's loads by the runtime's fixed point (`mbd::settle_loads`): each
        // step the friction forces of the λ it is given, then the solve with them
        quote! {
            let applied = h;
            ::mbd::settle_loads(options.friction_tolerance, options.friction_iterations, lambda, |lambda: &mut [#real; #nc_l]| {
                let mut hf = [#zero; #nv_l];
                {
                    let lambda: &[#real; #nc_l] = lambda;
                    #friction_body
                }
                #( h[#cols] = applied[#cols] + hf[#cols]; )*
                #one_solve
            })
            .map(|_| ())
            .map_err(|(_, change)| ::mbd::DynamicsError::FrictionNotConverged {
                t: <#real as ::mbd::Real>::to_f64(t),
                change: <#real as ::mbd::Real>::to_f64(change),
            })
        }
    }

    /// M⁻¹ from the evaluated mass and the LDLᵀ of S into `l` and `dinv`; on a failed pivot, the
    /// error naming a body without a positive mass, a value that is not finite, or the row.
    fn factor_call(&self) -> TokenStream {
        let Plan { real, zero, nv, nv_l, nc_l, nl_l, .. } = self;
        let (minv, minv_off) = self.inverse_mass();
        let coordinates = crate::coordinates::Coordinates::of(self.m);
        let mass_bodies = (0..*nv).map(|i| coordinates.body_of_velocity(self.m, i) as u16);
        let (minv_off_decl, minv_off_arg) = if self.coupled() {
            let n_off = usize_lit(self.coupling.len());
            (quote!(let mut minv_off = [#zero; #n_off]; #(#minv_off)*), quote!(&minv_off,))
        } else {
            (quote!(), quote!())
        };
        quote! {
            let mut minv = [#zero; #nv_l];
            #(#minv)*
            #minv_off_decl
            let mut l = [#zero; #nl_l];
            let mut dinv = [#zero; #nc_l];
            if let ::core::result::Result::Err(row) =
                Self::schur_factor(&jv, &minv, #minv_off_arg options.pivot_tolerance, options.allow_redundant, &mut l, &mut dinv)
            {
                let finite = q.iter().chain(jv.iter()).chain(m.iter()).all(|x| x.is_finite());
                const MASS_BODIES: [u16; #nv_l] = [#(#mass_bodies),*];
                return ::core::result::Result::Err(::mbd::DynamicsError::from_pivot::<Self, #real>(
                    t, row, &m, &MASS_BODIES, &jv, finite, options.allow_redundant,
                ));
            }
        }
    }

    /// The projections' steps: q ← q ⊕ (−M⁻¹ Dᵀ b) — directly in q where v = q̇, through the
    /// velocity map otherwise — the velocity residual b = D v − ν, and v ← v − M⁻¹ Dᵀ b.
    fn projection_steps(&self) -> (TokenStream, TokenStream, TokenStream) {
        let Plan { real, zero, one, nv_l, rows, .. } = self;
        let q_step = if self.nq == self.nv {
            self.add_transpose(&quote!(q), &quote!(b), quote!(-=))
        } else {
            let mut step = vec![quote!(let mut dv = [#zero; #nv_l];)];
            step.extend(self.add_transpose(&quote!(dv), &quote!(b), quote!(-=)));
            step.push(quote!(::mbd::Kinematics::integrate_positions(self, q, &dv, #one);));
            step
        };
        let v_step = self.add_transpose(&quote!(v), &quote!(b), quote!(-=));
        let d_v = self.row_times(&quote!(v));
        let velocity_rows: Vec<TokenStream> = rows.iter().zip(&d_v).map(|(r, d_v)| quote!(b[#r] = #d_v - nu[#r];)).collect();
        (
            in_functions(&q_step, "q_step", &[], real),
            in_functions(&v_step, "v_step", &[], real),
            in_functions(&velocity_rows, "velocity_rows", &[], real),
        )
    }

    /// `impl ForwardDynamics` and the operation count of its evaluation.
    pub(super) fn forward_impl(&self) -> (TokenStream, Ops) {
        let Plan { real, zero, nq_l, nv_l, nc_l, nnz_l, .. } = self;
        let name = &self.m.name;
        let Evaluations { accelerations: eval_body, ops, positions: positions_body, velocities: velocities_body } = self.evaluations();
        let solve_for_lambda = self.solve_for_lambda();
        let factor_call = self.factor_call();
        let (q_step, v_step, velocity_rows) = self.projection_steps();
        let mi_decl = if self.coupled() {
            let n_mi = usize_lit(self.f.mass_inverse.len());
            quote!(let mut mi = [#zero; #n_mi];)
        } else {
            quote!()
        };
        // ‖b‖∞, NaN entries ignored (the callers check the result for finiteness).
        let max_abs = quote! {
            let (worst, _) = ::mbd::__private::max_abs_finite(&b);
        };
        let inline = crate::emit::inline_hint(self.nc);
        let impl_block = quote! {
            // Constants are the user's expressions evaluated (`PI / 2.0` → 1.5707963267948966).
            #[allow(unused_variables, unused_parens, unused_mut, clippy::approx_constant)]
            impl ::mbd::ForwardDynamics<#real, #nq_l, #nv_l, #nc_l> for #name {
                #inline
                fn accelerations(
                    &self,
                    q: &[#real; #nq_l],
                    v: &[#real; #nv_l],
                    t: #real,
                    options: &::mbd::DynamicsOptions<#real>,
                    vd: &mut [#real; #nv_l],
                    lambda: &mut [#real; #nc_l],
                ) -> ::core::result::Result<(), ::mbd::DynamicsError> {
                    let mut jv = [#zero; #nnz_l];
                    let mut phi = [#zero; #nc_l];
                    let mut nu = [#zero; #nc_l];
                    let mut gamma = [#zero; #nc_l];
                    let mut h = [#zero; #nv_l];
                    let mut m = [#zero; #nv_l];
                    #mi_decl
                    #eval_body
                    #factor_call
                    let two_alpha = options.baumgarte_alpha + options.baumgarte_alpha;
                    let beta2 = options.baumgarte_beta * options.baumgarte_beta;
                    #solve_for_lambda
                }

                #inline
                fn project_positions_step(
                    &self,
                    q: &mut [#real; #nq_l],
                    t: #real,
                    options: &::mbd::DynamicsOptions<#real>,
                ) -> ::core::result::Result<#real, ::mbd::DynamicsError> {
                    let mut jv = [#zero; #nnz_l];
                    let mut phi = [#zero; #nc_l];
                    let mut m = [#zero; #nv_l];
                    #mi_decl
                    {
                        let q: &[#real; #nq_l] = q;
                        #positions_body
                    }
                    // Φ copied and its norm taken before the factorization's call, not after: Φ's
                    // values kept live across the call took LLVM's instruction selection 24 s of a
                    // 240-body chain's 74 s build (1.8 s this way).
                    let mut b = phi;
                    #max_abs
                    #factor_call
                    Self::schur_solve(&l, &dinv, &mut b);
                    #q_step
                    ::core::result::Result::Ok(worst)
                }

                #inline
                fn project_velocities(
                    &self,
                    q: &[#real; #nq_l],
                    v: &mut [#real; #nv_l],
                    t: #real,
                    options: &::mbd::DynamicsOptions<#real>,
                ) -> ::core::result::Result<#real, ::mbd::DynamicsError> {
                    let mut jv = [#zero; #nnz_l];
                    let mut nu = [#zero; #nc_l];
                    let mut m = [#zero; #nv_l];
                    #mi_decl
                    #velocities_body
                    #factor_call
                    let mut b = [#zero; #nc_l];
                    {
                        let v: &[#real; #nv_l] = v;
                        #velocity_rows
                    }
                    #max_abs
                    Self::schur_solve(&l, &dinv, &mut b);
                    #v_step
                    ::core::result::Result::Ok(worst)
                }
            }
        };
        (impl_block, ops)
    }
}
