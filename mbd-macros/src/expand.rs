//! The chain parse → model → formulation → emit, and the code that ties the emitted functions
//! into the mechanism's type and its `mbd::Mechanism` / `mbd::Kinematics` implementations.

use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

use crate::emit::{self, Emitter, Ops, Output};
use crate::formulation::{formulate, Formulation};
use crate::json::model_json;
use crate::model::{Model, Partial, Scalar};
use crate::parse::MechanismDef;
use crate::schur::Schur;

/// Expands a `mechanism!` invocation. Never fails: mistakes become `compile_error!`s next to a
/// stub of the mechanism's type, so code that uses the type does not add follow-up errors.
pub fn expand(input: TokenStream) -> TokenStream {
    let def: MechanismDef = match syn::parse2(input) {
        Ok(d) => d,
        Err(e) => return e.to_compile_error(),
    };
    match def.validate().and_then(|m| generate(&m)) {
        Ok(ts) => ts,
        Err(e) => {
            let errors = e.to_compile_error();
            let stub = stub(&def.partial());
            quote!(#errors #stub)
        }
    }
}

fn real(s: Scalar) -> TokenStream {
    match s {
        Scalar::F32 => quote!(f32),
        Scalar::F64 => quote!(f64),
    }
}

/// The type of a mechanism whose description has mistakes: its name and parameters, `Default`,
/// and nothing that could raise errors of its own.
fn stub(p: &Partial) -> TokenStream {
    let Partial { attrs, vis, name, scalar, params } = p;
    let real = real(*scalar);
    quote! {
        #(#attrs)*
        #[derive(Clone, Copy, Debug, Default, PartialEq)]
        #vis struct #name { #(pub #params: #real,)* }
    }
}

fn usize_lit(n: usize) -> Literal {
    Literal::usize_unsuffixed(n)
}

fn op_count(name: &str, ops: Ops) -> TokenStream {
    let Ops { add, mul, div, call } = ops;
    quote!(::mbd::OpCount { function: #name, add: #add, mul: #mul, div: #div, call: #call })
}

/// Outputs `out[i] = nodes[i]`.
fn vector_outputs(out: &str, nodes: &[u32]) -> Vec<Output> {
    let out = format_ident!("{}", out);
    nodes
        .iter()
        .enumerate()
        .map(|(i, &node)| {
            let i = usize_lit(i);
            Output { target: quote!(#out[#i]), node }
        })
        .collect()
}

/// Outputs `d[r][c] = Φ_q[r][c]` for the structural non-zeros.
fn jacobian_outputs(f: &Formulation) -> Vec<Output> {
    f.jacobian
        .iter()
        .map(|&(r, c, node)| {
            let (r, c) = (usize_lit(r), usize_lit(c));
            Output { target: quote!(d[#r][#c]), node }
        })
        .collect()
}

/// Outputs `name[r][c] = node` for sparse matrix entries.
fn matrix_outputs(name: &str, entries: &[(usize, usize, u32)]) -> Vec<Output> {
    let name = format_ident!("{}", name);
    entries
        .iter()
        .map(|&(r, c, node)| {
            let (r, c) = (usize_lit(r), usize_lit(c));
            Output { target: quote!(#name[#r][#c]), node }
        })
        .collect()
}

/// Generates the mechanism's type and trait implementations.
pub fn generate(m: &Model) -> syn::Result<TokenStream> {
    let f = formulate(m);
    emit::check_finite(&f, m.name.span())?;
    let e: Emitter = emit::emitter(m, &f);
    let real = real(m.scalar);
    let name = &m.name;
    let vis = &m.vis;
    let attrs = &m.attrs;
    let (nb, nq, nc, nnz) = (m.bodies.len(), f.nq, f.nc, f.jacobian.len());
    let (nb_l, nq_l, nc_l, nnz_l) = (usize_lit(nb), usize_lit(nq), usize_lit(nc), usize_lit(nnz));
    let np = usize_lit(m.params.len());
    let dof = nq as i32 - nc as i32;
    let zero = e.literal(0.0);

    let params: Vec<_> = m.params.iter().map(|p| &p.name).collect();
    let defaults: Vec<_> = m.params.iter().map(|p| e.literal(p.default)).collect();
    let param_docs: Vec<String> = m.params.iter().map(|p| format!("Parameter `{}` (default {}).", p.name, p.default)).collect();
    let param_idx: Vec<Literal> = (0..m.params.len()).map(usize_lit).collect();

    // The functions, each with its own common-subexpression elimination.
    let (phi_body, phi_ops) = e.body(&vector_outputs("phi", &f.phi));
    let (jac_body, jac_ops) = e.body(&jacobian_outputs(&f));
    let (nu_body, nu_ops) = e.body(&vector_outputs("nu", &f.nu));
    let (gamma_body, gamma_ops) = e.body(&vector_outputs("gamma", &f.gamma));
    let mut pos = vector_outputs("phi", &f.phi);
    pos.extend(jacobian_outputs(&f));
    let (pos_body, pos_ops) = e.body(&pos);
    let mut full = pos;
    full.extend(vector_outputs("nu", &f.nu));
    full.extend(vector_outputs("gamma", &f.gamma));
    let (full_body, full_ops) = e.body(&full);
    let values = jacobian_values_outputs(&f, "out");
    let (values_body, values_ops) = e.body(&values);
    let mut full_values = vector_outputs("phi", &f.phi);
    full_values.extend(values.iter().map(|o| Output { target: o.target.clone(), node: o.node }));
    full_values.extend(vector_outputs("nu", &f.nu));
    full_values.extend(vector_outputs("gamma", &f.gamma));
    let (full_values_body, full_values_ops) = e.body(&full_values);
    let (q0_body, _) = e.body(&vector_outputs("q", &f.q0));
    let (mass_body, _) = e.body(&vector_outputs("m", &f.mass));
    let (h_body, h_ops) = e.body(&vector_outputs("h", &f.h));
    let (h_q_body, h_q_ops) = e.body(&matrix_outputs("dh", &f.h_q));
    let (h_qd_body, h_qd_ops) = e.body(&matrix_outputs("dh", &f.h_qd));
    let (v_body, v_ops) = e.body(&[Output { target: quote!(energy[0]), node: f.potential }]);
    let (cfq_body, cfq_ops) = e.body(&matrix_outputs("k", &f.constraint_force_q));
    let (power_body, power_ops) = e.body(&[Output { target: quote!(power[0]), node: f.power }]);
    let forward = forward_dynamics(m, &f, &e);
    let friction = friction_outputs(&f);
    let friction_fn = if friction.is_empty() {
        quote!()
    } else {
        let (body, _) = e.body(&friction);
        let indices: Vec<Literal> = f.friction.iter().enumerate().filter(|(_, &n)| !f.graph.is_zero(n)).map(|(i, _)| usize_lit(i)).collect();
        quote! {
            let mut hf = [#zero; #nq_l];
            #body
            #( h[#indices] += hf[#indices]; )*
        }
    };
    // ∂/∂q and ∂/∂q̇ of the friction forces, added into the caller's dense matrices.
    let friction_derivatives_fn = if f.friction_q.is_empty() && f.friction_qd.is_empty() {
        quote!()
    } else {
        let mut outputs = Vec::new();
        for (name, entries) in [("fq", &f.friction_q), ("fqd", &f.friction_qd)] {
            let name = format_ident!("{}", name);
            for (k, &(_, _, node)) in entries.iter().enumerate() {
                let k = usize_lit(k);
                outputs.push(Output { target: quote!(#name[#k]), node });
            }
        }
        let (body, _) = e.body(&outputs);
        let (n_q, n_qd) = (usize_lit(f.friction_q.len()), usize_lit(f.friction_qd.len()));
        let add = |matrix: TokenStream, scratch: TokenStream, entries: &[(usize, usize, u32)]| {
            let adds = entries.iter().enumerate().map(|(k, &(r, c, _))| {
                let (k, r, c) = (usize_lit(k), usize_lit(r), usize_lit(c));
                quote!(#matrix[#r][#c] += #scratch[#k];)
            });
            quote!(#(#adds)*)
        };
        let (add_q, add_qd) = (add(quote!(d_q), quote!(fq), &f.friction_q), add(quote!(d_qd), quote!(fqd), &f.friction_qd));
        quote! {
            let mut fq = [#zero; #n_q];
            let mut fqd = [#zero; #n_qd];
            #body
            #add_q
            #add_qd
        }
    };
    let nz_l = usize_lit(nq + nc);
    let mut joints = Vec::new();
    let mut first_row = 0u16;
    for c in &m.constraints {
        let rows = c.kind.row_names().len() as u16;
        let (kind, bi, bj) = c.kind.kind_and_bodies();
        let body = |b: Option<crate::model::BodyRef>| match b {
            Some(crate::model::BodyRef::Body(k)) => {
                let k = k as u16;
                quote!(::core::option::Option::Some(#k))
            }
            _ => quote!(::core::option::Option::None),
        };
        let (bi, bj) = (body(bi), body(bj));
        let name = &c.name;
        joints.push(quote!(::mbd::JointInfo { name: #name, kind: #kind, first_row: #first_row, rows: #rows, body_i: #bi, body_j: #bj }));
        first_row += rows;
    }
    let mut effects: Vec<&str> = Vec::new();
    if m.gravity.is_some() {
        effects.push("gravity");
    }
    for element in &m.forces {
        if !effects.contains(&element.effect()) {
            effects.push(element.effect());
        }
    }
    let (qd0_body, _) = e.body(&vector_outputs("qd", &f.qd0));

    let op_counts = [
        op_count("constraints", phi_ops),
        op_count("jacobian", jac_ops),
        op_count("jacobian_values", values_ops),
        op_count("velocity_rhs", nu_ops),
        op_count("gamma", gamma_ops),
        op_count("position_eval", pos_ops),
        op_count("full_eval", full_ops),
        op_count("full_eval_values", full_values_ops),
        op_count("forces", h_ops),
        op_count("forces_q", h_q_ops),
        op_count("forces_qd", h_qd_ops),
        op_count("potential_energy", v_ops),
        op_count("constraint_force_q", cfq_ops),
        op_count("nonconservative_power", power_ops),
        op_count("accelerations (evaluation, before the solve)", forward.eval_ops),
    ];
    let ForwardCode { helpers, impl_block, .. } = forward;

    let body_names: Vec<String> = m.bodies.iter().map(|b| b.name.to_string()).collect();
    let coordinate_names = m.coordinate_names();
    let row_names = m.row_names();
    let param_names: Vec<String> = m.params.iter().map(|p| p.name.to_string()).collect();
    let pattern: Vec<(usize, usize)> = f.jacobian.iter().map(|&(r, c, _)| (r, c)).collect();
    let pattern_tokens = pattern.iter().map(|&(r, c)| {
        let (r, c) = (r as u16, c as u16);
        quote!((#r, #c))
    });
    let phi_t_zero = f.phi_t_is_zero();
    let json = model_json(m, &pattern);
    let name_str = name.to_string();

    let summary = format!(
        " {nb} bodies, {nq} coordinates, {nc} constraint rows ({dof} degrees of freedom); \
         Φ_q has {nnz} structural non-zeros of {}.",
        nq * nc
    );
    let zero_nu = if phi_t_zero { quote!(*nu = [#zero; #nc_l];) } else { nu_body };

    Ok(quote! {
        #(#attrs)*
        ///
        #[doc = #summary]
        #[derive(Clone, Copy, Debug, PartialEq)]
        #vis struct #name {
            #( #[doc = #param_docs] pub #params: #real, )*
        }

        impl ::core::default::Default for #name {
            fn default() -> Self {
                Self { #( #params: #defaults, )* }
            }
        }

        #[allow(unused_variables, unused_parens, clippy::all)]
        impl #name {
            /// Number of moving bodies.
            pub const N_BODIES: usize = #nb_l;
            /// Number of generalized coordinates (3 per body).
            pub const NQ: usize = #nq_l;
            /// Number of constraint rows (joints, drivers and user constraints).
            pub const NC: usize = #nc_l;
            /// Degrees of freedom: `NQ − NC`.
            pub const DOF: i32 = #dof;
            /// Number of structurally non-zero entries of Φ_q.
            pub const NNZ: usize = #nnz_l;
            /// Number of runtime parameters.
            pub const NP: usize = #np;

            /// Parameter values in declaration order (see `PARAM_NAMES`).
            pub fn params(&self) -> [#real; #np] {
                [#( self.#params, )*]
            }

            /// A mechanism with the given parameter values, in declaration order.
            pub fn from_params(p: [#real; #np]) -> Self {
                Self { #( #params: p[#param_idx], )* }
            }

            /// Work space for solvers that factor the (NQ + NC)-square saddle-point matrix
            /// [[K, Φ_qᵀ], [Φ_q, 0]] (static equilibrium).
            pub fn kkt_workspace() -> ::mbd::KktWorkspace<#real, #nz_l> {
                ::mbd::KktWorkspace::new()
            }

            /// A generalized-α integrator with work space for this mechanism's NQ + NC unknowns.
            pub fn generalized_alpha(options: ::mbd::GeneralizedAlphaOptions<#real>) -> ::mbd::GeneralizedAlpha<#real, #nz_l> {
                ::mbd::GeneralizedAlpha::new(options)
            }

            /// The structural non-zeros of Φ_q(q, t), in the order of `JACOBIAN_PATTERN`.
            #[inline]
            pub fn jacobian_values(&self, q: &[#real; #nq_l], t: #real, out: &mut [#real; #nnz_l]) {
                #values_body
            }

            /// Φ, the structural non-zeros of Φ_q (in the order of `JACOBIAN_PATTERN`), ν and γ in
            /// one evaluation: the sparse twin of `Kinematics::full_eval`.
            #[inline]
            #[allow(clippy::too_many_arguments)]
            pub fn full_eval_values(
                &self,
                q: &[#real; #nq_l],
                qd: &[#real; #nq_l],
                t: #real,
                phi: &mut [#real; #nc_l],
                out: &mut [#real; #nnz_l],
                nu: &mut [#real; #nc_l],
                gamma: &mut [#real; #nc_l],
            ) {
                #full_values_body
            }
        }

        impl ::mbd::Mechanism for #name {
            const NAME: &'static str = #name_str;
            const BODY_NAMES: &'static [&'static str] = &[#(#body_names),*];
            const COORDINATE_NAMES: &'static [&'static str] = &[#(#coordinate_names),*];
            const CONSTRAINT_NAMES: &'static [&'static str] = &[#(#row_names),*];
            const PARAM_NAMES: &'static [&'static str] = &[#(#param_names),*];
            const DOF: i32 = #dof;
            const JACOBIAN_PATTERN: &'static [(u16, u16)] = &[#(#pattern_tokens),*];
            const PHI_T_IS_ZERO: bool = #phi_t_zero;
            const OP_COUNTS: &'static [::mbd::OpCount] = &[#(#op_counts),*];
            const JOINTS: &'static [::mbd::JointInfo] = &[#(#joints),*];
            const EFFECTS: &'static [&'static str] = &[#(#effects),*];
            const MODEL_JSON: &'static str = #json;
        }

        #[allow(unused_variables, unused_parens, clippy::all)]
        impl ::mbd::ConstraintForces<#real, #nq_l, #nc_l> for #name {
            #[inline]
            fn constraint_force_q(&self, q: &[#real; #nq_l], t: #real, lambda: &[#real; #nc_l], k: &mut [[#real; #nq_l]; #nq_l]) {
                *k = [[#zero; #nq_l]; #nq_l];
                #cfq_body
            }
        }

        #[allow(unused_variables, unused_parens, clippy::all)]
        impl ::mbd::Dynamics<#real, #nq_l, #nc_l> for #name {
            #[inline]
            fn mass_diagonal(&self) -> [#real; #nq_l] {
                let mut m = [#zero; #nq_l];
                #mass_body
                m
            }
            #[inline]
            fn forces(&self, q: &[#real; #nq_l], qd: &[#real; #nq_l], t: #real, h: &mut [#real; #nq_l]) {
                #h_body
            }
            #[inline]
            fn forces_q(&self, q: &[#real; #nq_l], qd: &[#real; #nq_l], t: #real, dh: &mut [[#real; #nq_l]; #nq_l]) {
                *dh = [[#zero; #nq_l]; #nq_l];
                #h_q_body
            }
            #[inline]
            fn forces_qd(&self, q: &[#real; #nq_l], qd: &[#real; #nq_l], t: #real, dh: &mut [[#real; #nq_l]; #nq_l]) {
                *dh = [[#zero; #nq_l]; #nq_l];
                #h_qd_body
            }
            #[inline]
            fn potential_energy(&self, q: &[#real; #nq_l], t: #real) -> #real {
                let mut energy = [#zero; 1];
                #v_body
                energy[0]
            }
            #[inline]
            fn friction_forces(&self, q: &[#real; #nq_l], qd: &[#real; #nq_l], t: #real, lambda: &[#real; #nc_l], h: &mut [#real; #nq_l]) {
                #friction_fn
            }
            #[inline]
            fn friction_derivatives(
                &self,
                q: &[#real; #nq_l],
                qd: &[#real; #nq_l],
                t: #real,
                lambda: &[#real; #nc_l],
                d_q: &mut [[#real; #nq_l]; #nq_l],
                d_qd: &mut [[#real; #nq_l]; #nq_l],
            ) {
                #friction_derivatives_fn
            }
            #[inline]
            fn nonconservative_power(&self, q: &[#real; #nq_l], qd: &[#real; #nq_l], t: #real) -> #real {
                let mut power = [#zero; 1];
                #power_body
                power[0]
            }
        }

        #[allow(unused_variables, unused_parens, unused_mut, clippy::all)]
        impl #name {
            #helpers
        }

        #impl_block

        #[allow(unused_variables, unused_parens, clippy::all)]
        impl ::mbd::Kinematics<#real, #nq_l, #nc_l> for #name {
            #[inline]
            fn initial_positions(&self) -> [#real; #nq_l] {
                let mut q = [#zero; #nq_l];
                #q0_body
                q
            }
            #[inline]
            fn initial_velocities(&self) -> [#real; #nq_l] {
                let mut qd = [#zero; #nq_l];
                #qd0_body
                qd
            }
            #[inline]
            fn constraints(&self, q: &[#real; #nq_l], t: #real, phi: &mut [#real; #nc_l]) {
                #phi_body
            }
            #[inline]
            fn jacobian(&self, q: &[#real; #nq_l], t: #real, d: &mut [[#real; #nq_l]; #nc_l]) {
                *d = [[#zero; #nq_l]; #nc_l];
                #jac_body
            }
            #[inline]
            fn velocity_rhs(&self, q: &[#real; #nq_l], t: #real, nu: &mut [#real; #nc_l]) {
                #zero_nu
            }
            #[inline]
            fn gamma(&self, q: &[#real; #nq_l], qd: &[#real; #nq_l], t: #real, gamma: &mut [#real; #nc_l]) {
                #gamma_body
            }
            #[inline]
            fn position_eval(&self, q: &[#real; #nq_l], t: #real, phi: &mut [#real; #nc_l], d: &mut [[#real; #nq_l]; #nc_l]) {
                *d = [[#zero; #nq_l]; #nc_l];
                #pos_body
            }
            #[inline]
            fn full_eval(
                &self,
                q: &[#real; #nq_l],
                qd: &[#real; #nq_l],
                t: #real,
                phi: &mut [#real; #nc_l],
                d: &mut [[#real; #nq_l]; #nc_l],
                nu: &mut [#real; #nc_l],
                gamma: &mut [#real; #nc_l],
            ) {
                *d = [[#zero; #nq_l]; #nc_l];
                #full_body
            }
        }
    })
}

/// The generated forward dynamics: private helpers (the LDLᵀ of S and its solve) and the
/// `ForwardDynamics` implementation.
struct ForwardCode {
    helpers: TokenStream,
    impl_block: TokenStream,
    eval_ops: Ops,
}

fn forward_dynamics(m: &Model, f: &Formulation, e: &Emitter) -> ForwardCode {
    let real = real(m.scalar);
    let name = &m.name;
    let zero = e.literal(0.0);
    let one = e.literal(1.0);
    let (nq, nc, nnz) = (f.nq, f.nc, f.jacobian.len());
    let (nq_l, nc_l, nnz_l) = (usize_lit(nq), usize_lit(nc), usize_lit(nnz));
    let pattern: Vec<(usize, usize)> = f.jacobian.iter().map(|&(r, c, _)| (r, c)).collect();
    let schur = Schur::plan(nc, &pattern);
    let nl_l = usize_lit(schur.nl());
    let factor = schur.factor(&real, &zero);
    let solve = schur.solve();
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

    // q̈ = M⁻¹ h (+ M⁻¹ Φ_qᵀ λ later), M⁻¹ once per distinct mass expression.
    let mut minv = Vec::new();
    for (i, &node) in f.mass.iter().enumerate() {
        let il = usize_lit(i);
        match f.mass[..i].iter().position(|&n| n == node) {
            Some(j) => {
                let jl = usize_lit(j);
                minv.push(quote!(minv[#il] = minv[#jl];));
            }
            None => minv.push(quote!(minv[#il] = #one / m[#il];)),
        }
    }
    // (Φ_q x)_r for a vector x, straight-line over the pattern.
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
    // x[c] += minv[c] (Φ_qᵀ y)_c, straight-line over the pattern.
    let add_transpose = |x: &TokenStream, y: &TokenStream, sign: TokenStream| -> Vec<TokenStream> {
        (0..nq)
            .filter_map(|c| {
                let terms: Vec<TokenStream> = pattern
                    .iter()
                    .enumerate()
                    .filter(|(_, &(_, col))| col == c)
                    .map(|(k, &(r, _))| {
                        let (k, r) = (usize_lit(k), usize_lit(r));
                        quote!(jv[#k] * #y[#r])
                    })
                    .collect();
                let cl = usize_lit(c);
                (!terms.is_empty()).then(|| quote!(#x[#cl] #sign minv[#cl] * (#(#terms)+*);))
            })
            .collect()
    };
    let rows: Vec<Literal> = (0..nc).map(usize_lit).collect();
    let cols: Vec<Literal> = (0..nq).map(usize_lit).collect();

    // accelerations: one fused evaluation of Φ, Φ_q's non-zeros, ν, γ, h and M.
    let mut outputs = jv_outputs;
    outputs.extend(vector_outputs("phi", &f.phi));
    if !phi_t_zero {
        outputs.extend(vector_outputs("nu", &f.nu));
    }
    outputs.extend(vector_outputs("gamma", &f.gamma));
    outputs.extend(vector_outputs("h", &f.h));
    outputs.extend(vector_outputs("m", &f.mass));
    let (eval_body, eval_ops) = e.body(&outputs);
    let dq = row_times(&quote!(qdd));
    let dqd = row_times(&quote!(qd));
    let lambda_qdd = add_transpose(&quote!(qdd), &quote!(lambda), quote!(+=));

    let mut positions = vector_outputs("phi", &f.phi);
    positions.extend(jacobian_values_outputs(f, "jv"));
    positions.extend(vector_outputs("m", &f.mass));
    let (positions_body, _) = e.body(&positions);
    let q_step = add_transpose(&quote!(q), &quote!(b), quote!(-=));

    let mut velocities = jacobian_values_outputs(f, "jv");
    if !phi_t_zero {
        velocities.extend(vector_outputs("nu", &f.nu));
    }
    velocities.extend(vector_outputs("m", &f.mass));
    let (velocities_body, _) = e.body(&velocities);
    let qd_step = add_transpose(&quote!(qd), &quote!(b), quote!(-=));

    // Without Coulomb friction one solve; with it, fixed-point iteration on the normal loads λ
    // (the factorization of S does not depend on h, so each iteration is one more solve).
    let one_solve = quote! {
        #( qdd[#cols] = h[#cols] * minv[#cols]; )*
        #( lambda[#rows] = gamma[#rows] - #dq - two_alpha * (#dqd - nu[#rows]) - beta2 * phi[#rows]; )*
        Self::schur_solve(&l, &dinv, lambda);
        #(#lambda_qdd)*
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
                let mut hf = [#zero; #nq_l];
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
    let fail = quote! {
        let finite = q.iter().chain(jv.iter()).chain(m.iter()).all(|v| v.is_finite());
        return ::core::result::Result::Err(::mbd::DynamicsError::from_pivot::<Self, #real>(t, row, &m, finite));
    };
    let factor_call = quote! {
        let mut minv = [#zero; #nq_l];
        #(#minv)*
        let mut l = [#zero; #nl_l];
        let mut dinv = [#zero; #nc_l];
        if let ::core::result::Result::Err(row) =
            Self::schur_factor(&jv, &minv, options.pivot_tolerance, options.allow_redundant, &mut l, &mut dinv)
        {
            #fail
        }
    };
    let max_abs = quote! {
        let mut worst = #zero;
        for v in b.iter() {
            worst = <#real as ::mbd::Real>::max(worst, <#real as ::mbd::Real>::abs(*v));
        }
    };

    let helpers = quote! {
        /// LDLᵀ of S = Φ_q M⁻¹ Φ_qᵀ over its compile-time pattern; `Err(row)` for a dependent row.
        #[inline(always)]
        fn schur_factor(
            jv: &[#real; #nnz_l],
            minv: &[#real; #nq_l],
            tol: #real,
            allow_redundant: bool,
            l: &mut [#real; #nl_l],
            dinv: &mut [#real; #nc_l],
        ) -> ::core::result::Result<(), usize> {
            #factor
        }

        /// b ← S⁻¹ b with the factors of `schur_factor`.
        #[inline(always)]
        fn schur_solve(l: &[#real; #nl_l], dinv: &[#real; #nc_l], b: &mut [#real; #nc_l]) {
            #solve
        }
    };
    let impl_block = quote! {
        #[allow(unused_variables, unused_parens, unused_mut, clippy::all)]
        impl ::mbd::ForwardDynamics<#real, #nq_l, #nc_l> for #name {
            #[inline]
            fn accelerations(
                &self,
                q: &[#real; #nq_l],
                qd: &[#real; #nq_l],
                t: #real,
                options: &::mbd::DynamicsOptions<#real>,
                qdd: &mut [#real; #nq_l],
                lambda: &mut [#real; #nc_l],
            ) -> ::core::result::Result<(), ::mbd::DynamicsError> {
                let mut jv = [#zero; #nnz_l];
                let mut phi = [#zero; #nc_l];
                let mut nu = [#zero; #nc_l];
                let mut gamma = [#zero; #nc_l];
                let mut h = [#zero; #nq_l];
                let mut m = [#zero; #nq_l];
                #eval_body
                #factor_call
                let two_alpha = options.baumgarte_alpha + options.baumgarte_alpha;
                let beta2 = options.baumgarte_beta * options.baumgarte_beta;
                #solve_for_lambda
            }

            #[inline]
            fn project_positions_step(
                &self,
                q: &mut [#real; #nq_l],
                t: #real,
                options: &::mbd::DynamicsOptions<#real>,
            ) -> ::core::result::Result<#real, ::mbd::DynamicsError> {
                let mut jv = [#zero; #nnz_l];
                let mut phi = [#zero; #nc_l];
                let mut m = [#zero; #nq_l];
                {
                    let q: &[#real; #nq_l] = q;
                    #positions_body
                }
                #factor_call
                let mut b = phi;
                #max_abs
                Self::schur_solve(&l, &dinv, &mut b);
                #(#q_step)*
                ::core::result::Result::Ok(worst)
            }

            #[inline]
            fn project_velocities(
                &self,
                q: &[#real; #nq_l],
                qd: &mut [#real; #nq_l],
                t: #real,
                options: &::mbd::DynamicsOptions<#real>,
            ) -> ::core::result::Result<#real, ::mbd::DynamicsError> {
                let mut jv = [#zero; #nnz_l];
                let mut nu = [#zero; #nc_l];
                let mut m = [#zero; #nq_l];
                #velocities_body
                #factor_call
                let mut b = [#zero; #nc_l];
                {
                    let qd: &[#real; #nq_l] = qd;
                    #( b[#rows] = #dqd - nu[#rows]; )*
                }
                #max_abs
                Self::schur_solve(&l, &dinv, &mut b);
                #(#qd_step)*
                ::core::result::Result::Ok(worst)
            }
        }
    };
    ForwardCode { helpers, impl_block, eval_ops }
}

/// Outputs `hf[i] = friction force on coordinate i` for the coordinates friction acts on.
fn friction_outputs(f: &Formulation) -> Vec<Output> {
    f.friction
        .iter()
        .enumerate()
        .filter(|(_, &node)| !f.graph.is_zero(node))
        .map(|(i, &node)| {
            let i = usize_lit(i);
            Output { target: quote!(hf[#i]), node }
        })
        .collect()
}

/// Outputs `name[k] = Φ_q`'s k-th structural non-zero.
fn jacobian_values_outputs(f: &Formulation, name: &str) -> Vec<Output> {
    let name = format_ident!("{}", name);
    f.jacobian
        .iter()
        .enumerate()
        .map(|(k, &(_, _, node))| {
            let k = usize_lit(k);
            Output { target: quote!(#name[#k]), node }
        })
        .collect()
}

#[cfg(test)]
mod snapshot {
    use std::path::PathBuf;

    /// The expansion of `examples/expand/slider_crank.rs`, formatted, equals the committed
    /// `slider_crank.expanded.rs` (regenerate with `MBD_BLESS=1`).
    #[test]
    fn snapshot() {
        let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../examples/expand");
        let source = std::fs::read_to_string(dir.join("slider_crank.rs")).expect("read the snapshot's input");
        let file = syn::parse_file(&source).expect("the snapshot's input parses");
        let tokens = file
            .items
            .iter()
            .find_map(|item| match item {
                syn::Item::Macro(m) if m.mac.path.is_ident("mechanism") => Some(m.mac.tokens.clone()),
                _ => None,
            })
            .expect("the snapshot's input holds a mechanism! invocation");
        let expanded = super::expand(tokens);
        let formatted = prettyplease::unparse(&syn::parse2(expanded).expect("the expansion is valid Rust"));
        let text = format!(
            "// Generated from slider_crank.rs by `MBD_BLESS=1 cargo test -p mbd-macros snapshot`. Do not edit.\n{formatted}"
        );
        let path = dir.join("slider_crank.expanded.rs");
        if std::env::var_os("MBD_BLESS").is_some() {
            std::fs::write(&path, &text).expect("write the snapshot");
        }
        let committed = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(committed == text, "{} is out of date: rerun with MBD_BLESS=1 and review the diff", path.display());
    }
}
