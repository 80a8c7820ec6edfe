//! The items of the generated code, one concern each: the type and its inherent items, and the
//! `Mechanism`, `Linearize` and `ConstraintForces`, `Dynamics` and `Kinematics` implementations.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::{named_items, ConstraintFunctions, DynamicsFunctions, Gen};
use crate::emit::{usize_lit, Ops};
use crate::json::model_json;

impl Gen<'_> {
    /// The mechanism's struct, its parameters as fields, documented with a summary and the
    /// tables of its coordinates, rows and costs; and its `Default`.
    pub(super) fn declaration(&self, tables: &str) -> TokenStream {
        let Gen { m, f, e, real, name, .. } = self;
        let (vis, attrs) = (&m.vis, &m.attrs);
        let (nb, nq, nv, nc, nnz) = (m.bodies.len(), f.nq, f.nv, f.nc, f.jacobian.len());
        let dof = nv as i32 - nc as i32;
        let params: Vec<_> = m.params.iter().map(|p| &p.name).collect();
        let defaults: Vec<_> = m.params.iter().map(|p| e.literal(p.default)).collect();
        let param_docs: Vec<String> = m.params.iter().map(|p| format!("Parameter `{}` (default {}).", p.name, p.default)).collect();
        let sizes = if nq == nv { format!("{nq} coordinates and velocities") } else { format!("{nq} coordinates, {nv} velocities") };
        let summary = format!(
            " {nb} {} {}, {sizes}, {nc} constraint row{} ({dof} degree{} of freedom); \
             D has {nnz} structural non-zeros of {}.",
            if m.space == crate::model::Space::Planar { "planar" } else { "spatial" },
            if nb == 1 { "body" } else { "bodies" },
            if nc == 1 { "" } else { "s" },
            if dof == 1 { "" } else { "s" },
            nv * nc
        );
        quote! {
            #(#attrs)*
            ///
            #[doc = #summary]
            #[doc = #tables]
            #[derive(Clone, Copy, Debug, PartialEq)]
            #vis struct #name {
                #( #[doc = #param_docs] pub #params: #real, )*
            }

            // The defaults are the user's expressions evaluated (`2.0 * PI` → 6.283185307179586), not
            // hand-typed approximations of a constant.
            #[allow(clippy::approx_constant)]
            impl ::core::default::Default for #name {
                fn default() -> Self {
                    Self { #( #params: #defaults, )* }
                }
            }
        }
    }

    /// The sizes as constants, named access, the parameters, the work space and the sparse
    /// constraint functions.
    pub(super) fn inherent_impl(&self, c: &ConstraintFunctions, newton_storage: usize) -> TokenStream {
        let Gen { m, f, e, real, name, inline, nq_l, nv_l, nc_l, nnz_l, .. } = self;
        let nb_l = usize_lit(m.bodies.len());
        let np = usize_lit(m.params.len());
        let dof = f.nv as i32 - f.nc as i32;
        let nz_l = usize_lit(f.nv + f.nc);
        let params: Vec<_> = m.params.iter().map(|p| &p.name).collect();
        let param_idx: Vec<Literal> = (0..m.params.len()).map(usize_lit).collect();
        let newton_storage = Literal::usize_unsuffixed(newton_storage);
        let (per_body_q, per_body_v) = match m.space {
            crate::model::Space::Planar => ("3 per body: x, y, φ", "3 per body; planar v = q̇, so NV = NQ"),
            crate::model::Space::Spatial => ("7 per body: x, y, z, e0, e1, e2, e3", "6 per body: ẋ, ẏ, ż, ω′x, ω′y, ω′z"),
        };
        let (doc_nq, doc_nv) =
            (format!(" Number of generalized coordinates q ({per_body_q})."), format!(" Number of velocities v ({per_body_v})."));
        let named = named_items(m, f, e);
        let (values_body, full_values_body) = (&c.values, &c.full_values);
        quote! {
            // Constants are the user's expressions evaluated (`PI / 2.0` → 1.5707963267948966).
            #[allow(unused_variables, unused_parens, clippy::approx_constant)]
            impl #name {
                /// Number of moving bodies.
                pub const N_BODIES: usize = #nb_l;
                #[doc = #doc_nq]
                pub const NQ: usize = #nq_l;
                #[doc = #doc_nv]
                pub const NV: usize = #nv_l;
                /// Number of constraint rows (joints, drivers and user constraints).
                pub const NC: usize = #nc_l;
                /// Degrees of freedom: `NV − NC`.
                pub const DOF: i32 = #dof;
                /// Number of structurally non-zero entries of Φ_q.
                pub const NNZ: usize = #nnz_l;
                /// Number of runtime parameters.
                pub const NP: usize = #np;
                /// Scalars of one planned Newton matrix (D's non-zeros and the factors' entries of
                /// [[A, −Dᵀ], [D, 0]], fill included): the last size of this mechanism's
                /// `Workspace`, which statics and generalized-α keep their matrices in.
                pub const NEWTON_STORAGE: usize = #newton_storage;

                #named

                /// Parameter values in declaration order (see `PARAM_NAMES`).
                pub fn params(&self) -> [#real; #np] {
                    [#( self.#params, )*]
                }

                /// A mechanism with the given parameter values, in declaration order.
                pub fn from_params(p: [#real; #np]) -> Self {
                    Self { #( #params: p[#param_idx], )* }
                }

                ::mbd::__if_std! {
                    /// The work space every solver takes (its O(N²) arrays: D, the saddle-point
                    /// matrix, NV × NV derivatives, and three planned Newton matrices of
                    /// `NEWTON_STORAGE` scalars), zeroed on the heap. Make it once and pass it to
                    /// each analysis; without `std`, put a `Workspace::new()` of the same type in a
                    /// `static`.
                    pub fn workspace() -> ::mbd::workspace::Boxed<#real, #nv_l, #nc_l, #nz_l, #newton_storage> {
                        ::mbd::Workspace::boxed()
                    }
                }

                /// A generalized-α integrator for this mechanism.
                pub fn generalized_alpha(options: ::mbd::GeneralizedAlphaOptions<#real>) -> ::mbd::GeneralizedAlpha<#real, #nv_l> {
                    ::mbd::GeneralizedAlpha::new(options)
                }

                /// The structural non-zeros of Φ_q(q, t), in the order of `JACOBIAN_PATTERN`.
                #inline
                pub fn jacobian_values(&self, q: &[#real; #nq_l], t: #real, out: &mut [#real; #nnz_l]) {
                    #values_body
                }

                /// Φ, the structural non-zeros of Φ_q (in the order of `JACOBIAN_PATTERN`), ν and γ in
                /// one evaluation: the sparse twin of `Kinematics::full_eval`.
                #inline
                #[allow(clippy::too_many_arguments)]
                pub fn full_eval_values(
                    &self,
                    q: &[#real; #nq_l],
                    v: &[#real; #nv_l],
                    t: #real,
                    phi: &mut [#real; #nc_l],
                    out: &mut [#real; #nnz_l],
                    nu: &mut [#real; #nc_l],
                    gamma: &mut [#real; #nc_l],
                ) {
                    #full_values_body
                }
            }
        }
    }

    /// `impl Mechanism`: the names, descriptors, sizes, sparsity, operation counts, joints,
    /// force elements, effects and the model's JSON.
    pub(super) fn mechanism_impl(&self, op_counts: &[TokenStream], force_ops: &([Ops; 3], Vec<[Ops; 3]>)) -> TokenStream {
        let Gen { m, f, name, .. } = self;
        let dof = f.nv as i32 - f.nc as i32;
        let body_names: Vec<String> = m.bodies.iter().map(|b| b.name.to_string()).collect();
        let coordinate_names = m.coordinate_names();
        // planar v = q̇: the velocities are named by their coordinates, as the runtime's messages say
        let velocity_names = if m.space == crate::model::Space::Planar { m.coordinate_names() } else { m.velocity_names() };
        let (coordinate_infos, velocity_infos) = crate::coordinates::Coordinates::of(m).descriptors(m);
        let row_names = &f.row_names;
        let row_units = f.row_units.iter().map(|u| u.multiplier());
        let param_names: Vec<String> = m.params.iter().map(|p| p.name.to_string()).collect();
        let pattern: Vec<(usize, usize)> = f.jacobian.iter().map(|&(r, c, _)| (r, c)).collect();
        let pattern_tokens = pattern.iter().map(|&(r, c)| {
            let (r, c) = (r as u16, c as u16);
            quote!((#r, #c))
        });
        let phi_t_zero = f.phi_t_is_zero();
        let json = model_json(m, &f.row_names, &f.first_rows, &pattern);
        let formulation = m.tree.as_ref().map(|_| {
            quote!(
                const FORMULATION: ::mbd::Formulation = ::mbd::Formulation::JointCoordinates;
            )
        });
        let name_str = name.to_string();
        let joints = self.joint_infos();
        let effects = effects(m);
        let force_counts = |counts: &[Ops; 3]| {
            let counts = ["forces", "forces_q", "forces_v"].iter().zip(counts).map(|(name, &ops)| super::op_count(name, ops));
            quote!(&[#(#counts),*])
        };
        let base_force_counts = force_counts(&force_ops.0);
        let force_elements = f.force_velocities.iter().zip(&force_ops.1).map(|((name, velocities), alone)| {
            let velocities = velocities.iter().map(|&i| i as u16);
            let counts = force_counts(alone);
            quote!(::mbd::ForceInfo { name: #name, velocities: &[#(#velocities),*], op_counts: #counts })
        });
        quote! {
            impl ::mbd::Mechanism for #name {
                const NAME: &'static str = #name_str;
                const BODY_NAMES: &'static [&'static str] = &[#(#body_names),*];
                const COORDINATE_NAMES: &'static [&'static str] = &[#(#coordinate_names),*];
                const VELOCITY_NAMES: &'static [&'static str] = &[#(#velocity_names),*];
                const COORDINATES: &'static [::mbd::CoordinateInfo] = &[#(#coordinate_infos),*];
                const VELOCITIES: &'static [::mbd::VelocityInfo] = &[#(#velocity_infos),*];
                const CONSTRAINT_NAMES: &'static [&'static str] = &[#(#row_names),*];
                const PARAM_NAMES: &'static [&'static str] = &[#(#param_names),*];
                const DOF: i32 = #dof;
                const JACOBIAN_PATTERN: &'static [(u16, u16)] = &[#(#pattern_tokens),*];
                const PHI_T_IS_ZERO: bool = #phi_t_zero;
                const OP_COUNTS: &'static [::mbd::OpCount] = &[#(#op_counts),*];
                const JOINTS: &'static [::mbd::JointInfo] = &[#(#joints),*];
                const FORCE_ELEMENTS: &'static [::mbd::ForceInfo] = &[#(#force_elements),*];
                const BASE_FORCE_OP_COUNTS: &'static [::mbd::OpCount] = #base_force_counts;
                const EFFECTS: &'static [&'static str] = &[#(#effects),*];
                const CONSTRAINT_UNITS: &'static [&'static str] = &[#(#row_units),*];
                // the trait documents it; the type's page would show the whole JSON text
                #[doc(hidden)]
                const MODEL_JSON: &'static str = #json;
                #formulation
            }
        }
    }

    /// `Mechanism::JOINTS`: each joint's, driver's and user constraint's name, kind, rows and
    /// bodies.
    fn joint_infos(&self) -> Vec<TokenStream> {
        let Gen { m, f, .. } = self;
        let mut joints = Vec::new();
        let mut first_row = 0u16;
        for (index, c) in m.constraints.iter().enumerate() {
            let end = f.first_rows.get(index + 1).copied().unwrap_or(f.nc);
            let rows = (end - f.first_rows[index]) as u16;
            let kind = c.kind.kind();
            let (bi, bj) = c.kind.bodies();
            let body = |b: Option<crate::model::BodyRef>| match b {
                Some(crate::model::BodyRef::Body(k)) => {
                    let k = k as u16;
                    quote!(::core::option::Option::Some(#k))
                }
                _ => quote!(::core::option::Option::None),
            };
            let (bi, bj) = (body(bi), body(bj));
            let name = &c.name;
            joints
                .push(quote!(::mbd::JointInfo { name: #name, kind: #kind, first_row: #first_row, rows: #rows, body_i: #bi, body_j: #bj }));
            first_row += rows;
        }
        joints
    }

    /// `impl Linearize` (γ's derivatives, the inputs' forces) and `impl ConstraintForces`
    /// (∂(Dᵀλ)/∂q).
    pub(super) fn linearize_impl(&self, d: &DynamicsFunctions) -> TokenStream {
        let Gen { m, f, real, name, zero, inline, nq_l, nv_l, nc_l, .. } = self;
        let input_names: Vec<String> = f.inputs.iter().map(|&k| m.params[k].name.to_string()).collect();
        let input_fields: Vec<&syn::Ident> = f.inputs.iter().map(|&k| &m.params[k].name).collect();
        let input_indices: Vec<Literal> = (0..f.inputs.len()).map(usize_lit).collect();
        let DynamicsFunctions { gamma_derivatives: gamma_derivatives_body, forces_input_cases, constraint_force_q: cfq_body, .. } = d;
        quote! {
            // Constants are the user's expressions evaluated (`PI / 2.0` → 1.5707963267948966).
            #[allow(unused_variables, unused_parens, clippy::approx_constant)]
            impl ::mbd::Linearize<#real, #nq_l, #nv_l, #nc_l> for #name {
                const INPUTS: &'static [&'static str] = &[#(#input_names),*];
                #inline
                fn gamma_derivatives(
                    &self,
                    q: &[#real; #nq_l],
                    v: &[#real; #nv_l],
                    t: #real,
                    gamma_q: &mut [[#real; #nv_l]; #nc_l],
                    gamma_v: &mut [[#real; #nv_l]; #nc_l],
                ) {
                    for row in gamma_q.iter_mut().chain(gamma_v.iter_mut()) {
                        *row = [#zero; #nv_l];
                    }
                    #gamma_derivatives_body
                }
                #inline
                fn forces_input(&self, k: usize, q: &[#real; #nq_l], v: &[#real; #nv_l], t: #real, dh: &mut [#real; #nv_l]) {
                    *dh = [#zero; #nv_l];
                    match k {
                        #(#forces_input_cases)*
                        _ => {}
                    }
                }
                fn input(&self, k: usize) -> #real {
                    match k {
                        #( #input_indices => self.#input_fields, )*
                        _ => #zero,
                    }
                }
                fn set_input(&mut self, k: usize, value: #real) {
                    match k {
                        #( #input_indices => self.#input_fields = value, )*
                        _ => {}
                    }
                }
            }

            #[allow(unused_variables, unused_parens, clippy::approx_constant)]
            impl ::mbd::ConstraintForces<#real, #nq_l, #nv_l, #nc_l> for #name {
                #inline
                fn constraint_force_q(&self, q: &[#real; #nq_l], t: #real, lambda: &[#real; #nc_l], k: &mut [[#real; #nv_l]; #nv_l]) {
                    for row in k.iter_mut() {
                        *row = [#zero; #nv_l];
                    }
                    #cfq_body
                }
            }
        }
    }

    /// `impl Dynamics`: M, h and its derivatives, V, the switching functions, friction and the
    /// non-conservative power.
    pub(super) fn dynamics_impl(&self, d: &DynamicsFunctions) -> TokenStream {
        let Gen { real, name, zero, inline, nq_l, nv_l, nc_l, .. } = self;
        let DynamicsFunctions {
            mass: mass_body,
            zero_y,
            mass_entries,
            coupling_decl,
            coupling_times,
            coupling_add,
            h_q: h_q_body,
            h_v: h_v_body,
            friction_derivatives,
            ..
        } = d;
        let common = self.common_dynamics_items(d, friction_derivatives);
        quote! {
            // Constants are the user's expressions evaluated (`PI / 2.0` → 1.5707963267948966).
            #[allow(unused_variables, unused_parens, unused_mut, clippy::approx_constant)]
            impl ::mbd::Dynamics<#real, #nq_l, #nv_l, #nc_l> for #name {
                #inline
                fn mass_times(&self, q: &[#real; #nq_l], x: &[#real; #nv_l], y: &mut [#real; #nv_l]) {
                    let mut m = [#zero; #nv_l];
                    #coupling_decl
                    #mass_body
                    #zero_y
                    #( y[#mass_entries] = m[#mass_entries] * x[#mass_entries]; )*
                    #coupling_times
                }
                #inline
                fn add_mass_matrix(&self, q: &[#real; #nq_l], scale: #real, a: &mut [[#real; #nv_l]; #nv_l]) {
                    let mut m = [#zero; #nv_l];
                    #coupling_decl
                    #mass_body
                    #( a[#mass_entries][#mass_entries] += scale * m[#mass_entries]; )*
                    #coupling_add
                }
                #inline
                fn forces_q(&self, q: &[#real; #nq_l], v: &[#real; #nv_l], t: #real, dh: &mut [[#real; #nv_l]; #nv_l]) {
                    for row in dh.iter_mut() {
                        *row = [#zero; #nv_l];
                    }
                    #h_q_body
                }
                #inline
                fn forces_v(&self, q: &[#real; #nq_l], v: &[#real; #nv_l], t: #real, dh: &mut [[#real; #nv_l]; #nv_l]) {
                    for row in dh.iter_mut() {
                        *row = [#zero; #nv_l];
                    }
                    #h_v_body
                }
                #common
            }
        }
    }

    /// The `Dynamics` items every formulation writes alike: h, V, the switching functions,
    /// friction (its derivatives' body given: entries or columns) and the non-conservative power.
    pub(super) fn common_dynamics_items(&self, d: &DynamicsFunctions, friction_derivatives: &TokenStream) -> TokenStream {
        let Gen { real, zero, inline, nq_l, nv_l, nc_l, .. } = self;
        let DynamicsFunctions {
            h: h_body,
            potential: v_body,
            switching,
            power: power_body,
            friction: friction_fn,
            friction_multiplier_derivatives,
            inertia_check,
            ..
        } = d;
        quote! {
            #inertia_check
            #inline
            fn forces(&self, q: &[#real; #nq_l], v: &[#real; #nv_l], t: #real, h: &mut [#real; #nv_l]) {
                #h_body
            }
            #inline
            fn potential_energy(&self, q: &[#real; #nq_l], t: #real) -> #real {
                let mut energy = [#zero; 1];
                #v_body
                energy[0]
            }
            #switching
            #inline
            fn friction_forces(&self, q: &[#real; #nq_l], v: &[#real; #nv_l], t: #real, lambda: &[#real; #nc_l], h: &mut [#real; #nv_l]) {
                #friction_fn
            }
            #inline
            fn friction_derivatives(
                &self,
                q: &[#real; #nq_l],
                v: &[#real; #nv_l],
                t: #real,
                lambda: &[#real; #nc_l],
                d_q: &mut [[#real; #nv_l]; #nv_l],
                d_v: &mut [[#real; #nv_l]; #nv_l],
            ) {
                #friction_derivatives
            }
            #inline
            fn friction_multiplier_derivatives(
                &self,
                q: &[#real; #nq_l],
                v: &[#real; #nv_l],
                t: #real,
                lambda: &[#real; #nc_l],
                d_lambda: &mut [[#real; #nv_l]; #nc_l],
            ) {
                #friction_multiplier_derivatives
            }
            #inline
            fn nonconservative_power(&self, q: &[#real; #nq_l], v: &[#real; #nv_l], t: #real) -> #real {
                let mut power = [#zero; 1];
                #power_body
                power[0]
            }
        }
    }

    /// `impl Kinematics`: the initial guesses, the velocity map, Φ, D, ν, γ and the fused
    /// evaluations; and `impl __private::KinematicsHooks`: a driven mechanism's planned position
    /// solve, velocity, acceleration and multipliers.
    pub(super) fn kinematics_impl(&self, c: &ConstraintFunctions, position_step: &TokenStream) -> TokenStream {
        let Gen { m, e, real, name, zero, inline, nq_l, nv_l, nc_l, .. } = self;
        let positions_code = crate::coordinates::Coordinates::of(m).position_updates(m, e);
        let ConstraintFunctions {
            phi: phi_body,
            jacobian: jac_body,
            nu: zero_nu,
            gamma: gamma_body,
            position_eval: pos_body,
            full_eval: full_body,
            initial_positions: q0_body,
            initial_velocities: v0_body,
            ..
        } = c;
        quote! {
            // The solves planned for a driven mechanism (none otherwise): runtime plumbing, on a
            // hidden trait of their own.
            #[allow(unused_variables, unused_parens, clippy::approx_constant)]
            impl ::mbd::__private::KinematicsHooks<#real, #nq_l, #nv_l, #nc_l> for #name {
                #position_step
            }
            // Constants are the user's expressions evaluated (`PI / 2.0` → 1.5707963267948966).
            #[allow(unused_variables, unused_parens, clippy::approx_constant)]
            impl ::mbd::Kinematics<#real, #nq_l, #nv_l, #nc_l> for #name {
                #inline
                fn initial_positions(&self) -> [#real; #nq_l] {
                    let mut q = [#zero; #nq_l];
                    #q0_body
                    q
                }
                #inline
                fn initial_velocities(&self) -> [#real; #nv_l] {
                    let mut v = [#zero; #nv_l];
                    #v0_body
                    v
                }
                #positions_code
                #inline
                fn constraints(&self, q: &[#real; #nq_l], t: #real, phi: &mut [#real; #nc_l]) {
                    #phi_body
                }
                #inline
                fn jacobian(&self, q: &[#real; #nq_l], t: #real, d: &mut [[#real; #nv_l]; #nc_l]) {
                    for row in d.iter_mut() {
                        *row = [#zero; #nv_l];
                    }
                    #jac_body
                }
                #inline
                fn velocity_rhs(&self, q: &[#real; #nq_l], t: #real, nu: &mut [#real; #nc_l]) {
                    #zero_nu
                }
                #inline
                fn gamma(&self, q: &[#real; #nq_l], v: &[#real; #nv_l], t: #real, gamma: &mut [#real; #nc_l]) {
                    #gamma_body
                }
                #inline
                fn position_eval(&self, q: &[#real; #nq_l], t: #real, phi: &mut [#real; #nc_l], d: &mut [[#real; #nv_l]; #nc_l]) {
                    #pos_body
                }
                #inline
                fn full_eval(
                    &self,
                    q: &[#real; #nq_l],
                    v: &[#real; #nv_l],
                    t: #real,
                    phi: &mut [#real; #nc_l],
                    d: &mut [[#real; #nv_l]; #nc_l],
                    nu: &mut [#real; #nc_l],
                    gamma: &mut [#real; #nc_l],
                ) {
                    #full_body
                }
            }
        }
    }
}

/// The physical effects the mechanism declares, gravity first (`Mechanism::EFFECTS`).
fn effects(m: &crate::model::Model) -> Vec<&'static str> {
    let mut effects: Vec<&str> = Vec::new();
    if m.gravity.is_some() {
        effects.push("gravity");
    }
    for element in &m.forces {
        if !effects.contains(&element.kind.effect()) {
            effects.push(element.kind.effect());
        }
    }
    effects
}
