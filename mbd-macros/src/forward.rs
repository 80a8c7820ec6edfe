//! The generated forward dynamics (docs/formulation.md, "Forward dynamics"): the sparse LDLᵀ of
//! S = D M⁻¹ Dᵀ planned by [`Schur`] at compile time, fused with one evaluation of Φ, D's
//! non-zeros, ν, γ, h and M, and the mass-weighted projections that reuse its factor. Planar:
//! v = q̇, NV = NQ, D = Φ_q, and a projection step q ⊕ Δv is q + Δv.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use crate::emit::{
    friction_outputs, in_functions, jacobian_values_outputs, real, usize_lit, vector_outputs, Emitter, Ops, Output, PartSignature,
};
use crate::formulation::Formulation;
use crate::model::Model;
use crate::schur::Schur;

use crate::emit::INLINE_ROWS as INLINE_SCHUR_ROWS;

/// The generated forward dynamics: private helpers (the LDLᵀ of S and its solve) and the
/// `ForwardDynamics` implementation.
pub struct ForwardCode {
    pub helpers: TokenStream,
    /// `Kinematics::sparse_position_solve`, `sparse_velocity_acceleration` and
    /// `sparse_multipliers` of a driven mechanism (NV = NC; nothing otherwise), for the
    /// `Kinematics` implementation.
    pub position_step: TokenStream,
    pub impl_block: TokenStream,
    pub eval_ops: Ops,
}

#[allow(clippy::too_many_lines)] // 624 lines: to be split by concern (issue 38, item 7)
pub fn forward_dynamics(m: &Model, f: &Formulation, e: &Emitter) -> ForwardCode {
    let real = real(m.scalar);
    let name = &m.name;
    let zero = e.literal(0.0);
    let one = e.literal(1.0);
    let (nq, nv, nc, nnz) = (f.nq, f.nv, f.nc, f.jacobian.len());
    let (nq_l, nv_l, nc_l, nnz_l) = (usize_lit(nq), usize_lit(nv), usize_lit(nc), usize_lit(nnz));
    let pattern: Vec<(usize, usize)> = f.jacobian.iter().map(|&(r, c, _)| (r, c)).collect();
    // M⁻¹ off its diagonal (spatial bodies with products of inertia): `minv_off[k]` is the k-th
    // of `coupling`, read with the diagonal of those blocks from the evaluated `mi`.
    let coupling: Vec<(usize, usize)> = f.mass_inverse.iter().filter(|e| e.0 != e.1).map(|&(r, c, _)| (r, c)).collect();
    let coupled = !coupling.is_empty();
    let schur = Schur::plan(nc, &pattern, &coupling);
    let nl_l = usize_lit(schur.nl());
    let factor = schur.factor(&real, &zero);
    let solve = schur.solve(&real);
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

    // v̇ = M⁻¹ h (+ M⁻¹ Dᵀ λ later), M⁻¹ once per distinct mass expression; a block with
    // products of inertia from its evaluated inverse.
    let mut minv = Vec::new();
    let mut minv_off = Vec::new();
    for (k, &(r, c, _)) in f.mass_inverse.iter().enumerate() {
        let (kl, rl) = (usize_lit(k), usize_lit(r));
        if r == c {
            minv.push(quote!(minv[#rl] = mi[#kl];));
        } else {
            let index = usize_lit(minv_off.len());
            minv_off.push(quote!(minv_off[#index] = mi[#kl];));
        }
    }
    let from_block = |i: usize| f.mass_inverse.iter().any(|e| e.0 == i && e.1 == i);
    for (i, &node) in f.mass.iter().enumerate() {
        let il = usize_lit(i);
        if from_block(i) {
            continue;
        }
        match (0..i).find(|&j| f.mass[j] == node && !from_block(j)) {
            Some(j) => {
                let jl = usize_lit(j);
                minv.push(quote!(minv[#il] = minv[#jl];));
            }
            None => minv.push(quote!(minv[#il] = #one / m[#il];)),
        }
    }
    // (D x)_r for a vector x, straight-line over the pattern.
    let row_times = |x: &TokenStream| -> Vec<TokenStream> {
        (0..nc)
            .map(|r| {
                let terms: Vec<TokenStream> = pattern
                    .iter()
                    .enumerate()
                    .filter(|(_, &(row, _))| row == r)
                    .map(|(k, &(_, c))| {
                        let (k, c) = (usize_lit(k), usize_lit(c));
                        quote!(jv[#k] * #x[#c])
                    })
                    .collect();
                if terms.is_empty() {
                    zero.clone()
                } else {
                    quote!((#(#terms)+*))
                }
            })
            .collect()
    };
    // (Dᵀ y)_c, straight-line over the pattern; None for a column without non-zeros.
    let transpose_column = |y: &TokenStream, c: usize| -> Option<TokenStream> {
        let terms: Vec<TokenStream> = pattern
            .iter()
            .enumerate()
            .filter(|(_, &(_, col))| col == c)
            .map(|(k, &(r, _))| {
                let (k, r) = (usize_lit(k), usize_lit(r));
                quote!(jv[#k] * #y[#r])
            })
            .collect();
        (!terms.is_empty()).then(|| quote!((#(#terms)+*)))
    };
    // x[c] += (M⁻¹ w)_c for w given per column (`w(c)`), over M⁻¹'s structural non-zeros.
    let add_minv = |x: &TokenStream, sign: &TokenStream, w: &dyn Fn(usize) -> Option<TokenStream>| -> Vec<TokenStream> {
        (0..nv)
            .filter_map(|c| {
                let cl = usize_lit(c);
                let mut terms: Vec<TokenStream> = w(c).map(|wc| quote!(minv[#cl] * #wc)).into_iter().collect();
                for (k, &(r, c2)) in coupling.iter().enumerate() {
                    if r == c {
                        if let Some(wc2) = w(c2) {
                            let kl = usize_lit(k);
                            terms.push(quote!(minv_off[#kl] * #wc2));
                        }
                    }
                }
                (!terms.is_empty()).then(|| quote!(#x[#cl] #sign #(#terms)+*;))
            })
            .collect()
    };
    // x[c] += (M⁻¹ Dᵀ y)_c; with M⁻¹ coupled, Dᵀy is formed first.
    let add_transpose = |x: &TokenStream, y: &TokenStream, sign: TokenStream| -> Vec<TokenStream> {
        if !coupled {
            return add_minv(x, &sign, &|c| transpose_column(y, c));
        }
        let columns: Vec<TokenStream> = (0..nv)
            .filter_map(|c| {
                let cl = usize_lit(c);
                transpose_column(y, c).map(|t| quote!(w[#cl] = #t;))
            })
            .collect();
        let has = |c: usize| transpose_column(y, c).is_some();
        let mut out = vec![quote!(let mut w = [#zero; #nv_l]; #(#columns)*)];
        out.extend(add_minv(x, &sign, &|c| {
            let cl = usize_lit(c);
            has(c).then(|| quote!(w[#cl]))
        }));
        out
    };
    let rows: Vec<Literal> = (0..nc).map(usize_lit).collect();
    let cols: Vec<Literal> = (0..nv).map(usize_lit).collect();

    // accelerations: one fused evaluation of Φ, D's non-zeros, ν, γ, h and M.
    let mut outputs = jv_outputs;
    outputs.extend(vector_outputs("phi", &f.phi));
    if !phi_t_zero {
        outputs.extend(vector_outputs("nu", &f.nu));
    }
    outputs.extend(vector_outputs("gamma", &f.gamma));
    outputs.extend(vector_outputs("h", &f.h));
    outputs.extend(vector_outputs("m", &f.mass));
    outputs.extend(inverse_outputs(f));
    // The parts of a large mechanism's evaluations write these locals (M⁻¹'s blocks too when
    // coupled).
    let (mi_param, mi_arg) = if !coupled {
        (quote!(), quote!())
    } else {
        let n_mi = usize_lit(f.mass_inverse.len());
        (quote!(mi: &mut [#real; #n_mi],), quote!(&mut mi,))
    };
    let part = |name: &'static str, inputs: TokenStream, input_args: TokenStream, locals: &[(&str, &Literal)]| {
        let names: Vec<syn::Ident> = locals.iter().map(|(n, _)| syn::Ident::new(n, proc_macro2::Span::call_site())).collect();
        let lengths = locals.iter().map(|(_, l)| l);
        PartSignature {
            name,
            params: quote!(#inputs #(#names: &mut [#real; #lengths],)* #mi_param),
            args: quote!(#input_args #(&mut #names,)* #mi_arg),
        }
    };
    let evaluation = part(
        "accelerations",
        quote!(q: &[#real; #nq_l], v: &[#real; #nv_l], t: #real,),
        quote!(q, v, t,),
        &[("jv", &nnz_l), ("phi", &nc_l), ("nu", &nc_l), ("gamma", &nc_l), ("h", &nv_l), ("m", &nv_l)],
    );
    let (eval_body, eval_ops) = e.body_in_parts(&outputs, &evaluation);
    let d_vd = row_times(&quote!(vd));
    let d_v = row_times(&quote!(v));
    let lambda_vd = add_transpose(&quote!(vd), &quote!(lambda), quote!(+=));

    let mut positions = vector_outputs("phi", &f.phi);
    positions.extend(jacobian_values_outputs(f, "jv"));
    positions.extend(vector_outputs("m", &f.mass));
    positions.extend(inverse_outputs(f));
    let position_part =
        part("positions", quote!(q: &[#real; #nq_l], t: #real,), quote!(q, t,), &[("jv", &nnz_l), ("phi", &nc_l), ("m", &nv_l)]);
    let (positions_body, _) = e.body_in_parts(&positions, &position_part);
    // q ← q ⊕ (−M⁻¹ Dᵀ b): directly in q where v = q̇, through the velocity map otherwise.
    let q_step = if nq == nv {
        add_transpose(&quote!(q), &quote!(b), quote!(-=))
    } else {
        let mut step = vec![quote!(let mut dv = [#zero; #nv_l];)];
        step.extend(add_transpose(&quote!(dv), &quote!(b), quote!(-=)));
        step.push(quote!(::mbd::Kinematics::integrate_positions(self, q, &dv, #one);));
        step
    };

    let mut velocities = jacobian_values_outputs(f, "jv");
    if !phi_t_zero {
        velocities.extend(vector_outputs("nu", &f.nu));
    }
    velocities.extend(vector_outputs("m", &f.mass));
    velocities.extend(inverse_outputs(f));
    let velocity_part =
        part("velocities", quote!(q: &[#real; #nq_l], t: #real,), quote!(q, t,), &[("jv", &nnz_l), ("nu", &nc_l), ("m", &nv_l)]);
    let (velocities_body, _) = e.body_in_parts(&velocities, &velocity_part);
    let v_step = add_transpose(&quote!(v), &quote!(b), quote!(-=));

    // Without Coulomb friction one solve; with it, fixed-point iteration on the normal loads λ
    // (the factorization of S does not depend on h, so each iteration is one more solve).
    let minv_h = if coupled {
        add_minv(&quote!(vd), &quote!(=), &|c| {
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
    let velocity_rows: Vec<TokenStream> = rows.iter().zip(&d_v).map(|(r, d_v)| quote!(b[#r] = #d_v - nu[#r];)).collect();
    let (minv_h, lambda_rows, lambda_vd, velocity_rows) = (
        in_functions(&minv_h, "minv_h", &[], &real),
        in_functions(&lambda_rows, "lambda_rows", &["two_alpha", "beta2"], &real),
        in_functions(&lambda_vd, "lambda_vd", &[], &real),
        in_functions(&velocity_rows, "velocity_rows", &[], &real),
    );
    let (q_step, v_step) = (in_functions(&q_step, "q_step", &[], &real), in_functions(&v_step, "v_step", &[], &real));
    let one_solve = quote! {
        #minv_h
        #lambda_rows
        Self::schur_solve(&l, &dinv, lambda);
        #lambda_vd
    };
    let friction = friction_outputs(f);
    let solve_for_lambda = if friction.is_empty() {
        quote! {
            #one_solve
            ::core::result::Result::Ok(())
        }
    } else {
        let (friction_body, _) = e.body(&friction);
        quote! {
            let applied = h;
            let mut iteration = 0u32;
            loop {
                let previous = *lambda;
                let mut hf = [#zero; #nv_l];
                {
                    let lambda: &[#real; #nc_l] = lambda;
                    #friction_body
                }
                #( h[#cols] = applied[#cols] + hf[#cols]; )*
                #one_solve
                let mut change = #zero;
                let mut size = <#real as ::mbd::Real>::ONE;
                for (new, old) in lambda.iter().zip(previous.iter()) {
                    change = <#real as ::mbd::Real>::max(change, <#real as ::mbd::Real>::abs(*new - *old));
                    size = <#real as ::mbd::Real>::max(size, <#real as ::mbd::Real>::abs(*new));
                }
                if change <= options.friction_tolerance * size {
                    return ::core::result::Result::Ok(());
                }
                iteration += 1;
                if iteration >= options.friction_iterations || !(change == change) {
                    return ::core::result::Result::Err(::mbd::DynamicsError::FrictionNotConverged {
                        t: <#real as ::mbd::Real>::to_f64(t),
                        change: <#real as ::mbd::Real>::to_f64(change),
                    });
                }
            }
        }
    };
    let coordinates = crate::coordinates::Coordinates::of(m.space);
    let mass_bodies = (0..nv).map(|i| coordinates.body_of_velocity(i) as u16);
    let fail = quote! {
        let finite = q.iter().chain(jv.iter()).chain(m.iter()).all(|x| x.is_finite());
        const MASS_BODIES: [u16; #nv_l] = [#(#mass_bodies),*];
        return ::core::result::Result::Err(::mbd::DynamicsError::from_pivot::<Self, #real>(t, row, &m, &MASS_BODIES, finite));
    };
    // With products of inertia: the evaluated blocks of M⁻¹ (`mi`) and its off-diagonal part.
    let (n_mi, n_off) = (usize_lit(f.mass_inverse.len()), usize_lit(coupling.len()));
    let (minv_off_decl, minv_off_arg, minv_off_param, mi_decl) = if coupled {
        (
            quote!(let mut minv_off = [#zero; #n_off]; #(#minv_off)*),
            quote!(&minv_off,),
            quote!(minv_off: &[#real; #n_off],),
            quote!(let mut mi = [#zero; #n_mi];),
        )
    } else {
        (quote!(), quote!(), quote!(), quote!())
    };
    let factor_call = quote! {
        let mut minv = [#zero; #nv_l];
        #(#minv)*
        #minv_off_decl
        let mut l = [#zero; #nl_l];
        let mut dinv = [#zero; #nc_l];
        if let ::core::result::Result::Err(row) =
            Self::schur_factor(&jv, &minv, #minv_off_arg options.pivot_tolerance, options.allow_redundant, &mut l, &mut dinv)
        {
            #fail
        }
    };
    // ‖b‖∞, NaN entries ignored (the callers check the result for finiteness).
    let max_abs = quote! {
        let (worst, _) = ::mbd::sparse::max_abs_finite(&b);
    };

    let inline = crate::emit::inline_hint(nc);
    // The kinematic solves of a driven mechanism: the runtime calls them only where D is square;
    // elsewhere the provided methods stand, and nothing is generated to type-check.
    let (position_step, constraint_solve, transpose_solve) = if nv != nc {
        (quote!(), None, None)
    } else {
        // The kinematic position solve: Newton's iteration with the step −Dᵀ(D Dᵀ)⁻¹Φ over the same
        // factorization with unit weights (the step is D⁻¹(−Φ) for any weights when D is square and
        // regular), the loop in the generated code: what depends only on t (a driver's sin(ωt)) is
        // computed once before it, and D only after Φ's convergence test. A step expected to end the
        // iteration keeps D and its factors (simplified Newton, the chord method: Φ alone is
        // evaluated): ‖Φ‖∞ times the last step's contraction, times the safety factor `reuse`, is
        // within the tolerance.
        //
        // Where Φ and D together take more than `PART_NODES` operations, the loop evaluates them
        // apart, each through `Emitter::body_in_parts` (in methods of bounded size where it is
        // larger still): one straight-line loop body of Φ and D made the 240-body chain's
        // `sparse_position_solve` the largest function LLVM compiled, 2.7 times as long as at 120
        // bodies. Apart, D recomputes what it shares with Φ (the bodies' sines and cosines), and
        // what depends on t alone is no longer computed once per solve.
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
        let unit_off = if coupled { quote!(&[#zero; #n_off],) } else { quote!() };
        let step_columns: Vec<TokenStream> = (0..nv)
            .filter_map(|c| {
                let cl = usize_lit(c);
                transpose_column(&quote!(b), c).map(|t| quote!(step[#cl] = -#t;))
            })
            .collect();
        let step_columns = in_functions(&step_columns, "step_columns", &[], &real);
        let step_inline = if nc <= INLINE_SCHUR_ROWS { quote!(#[inline]) } else { quote!(#[inline(never)]) };
        let position_step = quote! {
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
                // The factorizations made (`l` and `dinv` hold factors after the first), and ‖Φ‖∞
                // where the last step was taken.
                let mut factored = 0u32;
                let mut last = #zero;
                #time_terms
                let mut iterations = 0u32;
                loop {
                    {
                        let q: &[#real; #nq_l] = q;
                        #phi_stage
                        let (worst, finite) = ::mbd::sparse::max_abs_finite(phi);
                        if finite && worst <= tolerance {
                            return ::core::option::Option::Some((::mbd::PositionStep::Converged, iterations, factored));
                        }
                        if !finite || iterations >= max_iterations {
                            return ::core::option::Option::Some((::mbd::PositionStep::Step, iterations, factored));
                        }
                        if !(factored > 0 && worst * worst * reuse <= tolerance * last) {
                            #jv_stage
                            if Self::schur_factor(&jv, &[#one; #nv_l], #unit_off pivot_tolerance, false, &mut l, &mut dinv).is_err() {
                                return ::core::option::Option::Some((::mbd::PositionStep::Singular, iterations, factored));
                            }
                            factored += 1;
                        }
                        last = worst;
                        let mut b = *phi;
                        Self::schur_solve(&l, &dinv, &mut b);
                        *step = [#zero; #nv_l];
                        #step_columns
                    }
                    if !step.iter().all(|x| x.is_finite()) {
                        return ::core::option::Option::Some((::mbd::PositionStep::Step, iterations, factored));
                    }
                    ::mbd::sparse::limit_step(step, max_step);
                    ::mbd::Kinematics::integrate_positions(self, q, step, #one);
                    iterations += 1;
                }
            }
        };

        // The kinematic velocity and acceleration of a driven mechanism over the same factorization:
        // D, ν, then γ with the velocity solved, each solve x = Dᵀ(D Dᵀ)⁻¹ b refined on its residual
        // (`constraint_solve`, below). Where Φ_t vanishes, D v = 0 and v = 0 without a solve.
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
        let motion_step = quote! {
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
        };
        // Inverse dynamics' multipliers, Dᵀλ = b, over the same factorization: λ = (D Dᵀ)⁻¹ D b,
        // refined on the residual b − Dᵀλ (`transpose_solve`, below); D's non-zeros by the
        // `Kinematics` method.
        let multipliers_step = quote! {
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
        };

        // x = Dᵀ(D Dᵀ)⁻¹ b, then up to four refinements x ← x + Dᵀ(D Dᵀ)⁻¹(b − D x) (`sparse::refine`
        // says when to stop): the normal equations square D's condition number, the refinement
        // brings the error back to an LU's.
        let columns_into = |x: &str, assign: TokenStream| -> TokenStream {
            let x = syn::Ident::new(x, proc_macro2::Span::call_site());
            let stmts: Vec<TokenStream> = (0..nv)
                .filter_map(|c| {
                    let cl = usize_lit(c);
                    transpose_column(&quote!(b), c).map(|t| quote!(#x[#cl] #assign #t;))
                })
                .collect();
            in_functions(&stmts, "solution_columns", &[], &real)
        };
        let solution = columns_into("x", quote!(=));
        let correction = columns_into("dx", quote!(=));
        let residual_rows: Vec<TokenStream> =
            rows.iter().zip(row_times(&quote!(x))).map(|(r, d_x)| quote!(b[#r] = rhs[#r] - #d_x;)).collect();
        let residual_rows = in_functions(&residual_rows, "residual_rows", &[], &real);
        let helper_inline_solve = if nc <= INLINE_SCHUR_ROWS { quote!(#[inline]) } else { quote!(#[inline(never)]) };
        // λ = (D Dᵀ)⁻¹ D b, then up to four refinements λ ← λ + (D Dᵀ)⁻¹ D (b − Dᵀλ).
        let rows_of = |y: &str| -> TokenStream {
            let y = syn::Ident::new(y, proc_macro2::Span::call_site());
            let stmts: Vec<TokenStream> = rows.iter().zip(row_times(&quote!(#y))).map(|(r, d_y)| quote!(b[#r] = #d_y;)).collect();
            in_functions(&stmts, "transpose_rows", &[], &real)
        };
        let (rows_of_rhs, rows_of_w) = (rows_of("rhs"), rows_of("w"));
        let residual_columns: Vec<TokenStream> = cols
            .iter()
            .enumerate()
            .map(|(c, cl)| match transpose_column(&quote!(x), c) {
                Some(t) => quote!(w[#cl] = rhs[#cl] - #t;),
                None => quote!(w[#cl] = rhs[#cl];),
            })
            .collect();
        let residual_columns = in_functions(&residual_columns, "residual_columns", &[], &real);
        let transpose_solve = {
            quote! {
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
                    let mut w = [#zero; #nv_l];
                    for _ in 0..4 {
                        {
                            let x: &[#real; #nc_l] = x;
                            #residual_columns
                        }
                        #rows_of_w
                        Self::schur_solve(l, dinv, &mut b);
                        if ::mbd::sparse::refine(x, &b) {
                            return true;
                        }
                    }
                    false
                }
            }
        };
        let constraint_solve = {
            quote! {
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
                    let mut dx = [#zero; #nv_l];
                    for _ in 0..4 {
                        {
                            let x: &[#real; #nv_l] = x;
                            #residual_rows
                        }
                        Self::schur_solve(l, dinv, &mut b);
                        #correction
                        if ::mbd::sparse::refine(x, &dx) {
                            return true;
                        }
                    }
                    false
                }
            }
        };
        (quote!(#position_step #motion_step #multipliers_step), Some(constraint_solve), Some(transpose_solve))
    };

    // Inlined into small mechanisms' solves (a call's cost matters there); kept apart in large
    // ones, where LLVM's optimization of the factor's straight-line, branchy code inlined into
    // each caller grew superlinearly (a 60-link chain's RK4 build took 166 s, a 30-link one 6 s).
    let helper_inline = if nc <= INLINE_SCHUR_ROWS { quote!(#[inline(always)]) } else { quote!(#[inline(never)]) };
    let helpers = quote! {
        /// LDLᵀ of S = D M⁻¹ Dᵀ over its compile-time pattern; `Err(row)` for a dependent row.
        #helper_inline
        fn schur_factor(
            jv: &[#real; #nnz_l],
            minv: &[#real; #nv_l],
            #minv_off_param
            tol: #real,
            allow_redundant: bool,
            l: &mut [#real; #nl_l],
            dinv: &mut [#real; #nc_l],
        ) -> ::core::result::Result<(), usize> {
            #factor
        }

        /// b ← S⁻¹ b with the factors of `schur_factor`.
        #helper_inline
        fn schur_solve(l: &[#real; #nl_l], dinv: &[#real; #nc_l], b: &mut [#real; #nc_l]) {
            #solve
        }

        #constraint_solve
        #transpose_solve
    };
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
    ForwardCode { helpers, position_step, impl_block, eval_ops }
}

/// Outputs `mi[k]` = the k-th structural non-zero of the coupled blocks of M⁻¹ (none for a
/// diagonal M).
fn inverse_outputs(f: &Formulation) -> Vec<Output> {
    f.mass_inverse
        .iter()
        .enumerate()
        .map(|(k, &(_, _, node))| {
            let k = usize_lit(k);
            Output { target: quote!(mi[#k]), node }
        })
        .collect()
}
