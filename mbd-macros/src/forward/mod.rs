//! The generated forward dynamics (docs/formulation.md, "Forward dynamics"): the sparse LDLᵀ of
//! S = D M⁻¹ Dᵀ planned by [`Schur`] at compile time, fused with one evaluation of Φ, D's
//! non-zeros, ν, γ, h and M, and the mass-weighted projections that reuse its factor. Planar:
//! v = q̇, NV = NQ, D = Φ_q, and a projection step q ⊕ Δv is q + Δv.
//!
//! By concern: the products with D, Dᵀ and M⁻¹ over their compile-time patterns (`products`);
//! the `ForwardDynamics` implementation — accelerations with Coulomb friction's fixed point, and
//! the projections (`accelerations`); a driven mechanism's kinematic solves over the same
//! factorization with unit weights (`driven`); the factorization and solve themselves, here.

mod accelerations;
mod driven;
mod products;

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use crate::emit::{real, usize_lit, Emitter, Ops};
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

/// What every part of the forward dynamics' code is written from: the formulation, its sizes,
/// D's pattern, M⁻¹'s coupling and the factorization planned from them.
struct Plan<'a> {
    m: &'a Model,
    f: &'a Formulation,
    e: &'a Emitter<'a>,
    real: TokenStream,
    zero: TokenStream,
    one: TokenStream,
    nq: usize,
    nv: usize,
    nc: usize,
    nq_l: Literal,
    nv_l: Literal,
    nc_l: Literal,
    nnz_l: Literal,
    nl_l: Literal,
    /// D's structural non-zeros as (row, column), in the order of `jv`.
    pattern: Vec<(usize, usize)>,
    /// M⁻¹ off its diagonal (spatial bodies with products of inertia): `minv_off[k]` is the k-th
    /// of `coupling`, read with the diagonal of those blocks from the evaluated `mi`.
    coupling: Vec<(usize, usize)>,
    schur: Schur,
    /// 0..NC and 0..NV as literals.
    rows: Vec<Literal>,
    cols: Vec<Literal>,
}

impl<'a> Plan<'a> {
    fn new(m: &'a Model, f: &'a Formulation, e: &'a Emitter<'a>) -> Self {
        let (nq, nv, nc) = (f.nq, f.nv, f.nc);
        let pattern: Vec<(usize, usize)> = f.jacobian.iter().map(|&(r, c, _)| (r, c)).collect();
        let coupling: Vec<(usize, usize)> = f.mass_inverse.iter().filter(|e| e.0 != e.1).map(|&(r, c, _)| (r, c)).collect();
        let schur = Schur::plan(nc, &pattern, &coupling);
        Plan {
            m,
            f,
            e,
            real: real(m.scalar),
            zero: e.literal(0.0),
            one: e.literal(1.0),
            nq,
            nv,
            nc,
            nq_l: usize_lit(nq),
            nv_l: usize_lit(nv),
            nc_l: usize_lit(nc),
            nnz_l: usize_lit(f.jacobian.len()),
            nl_l: usize_lit(schur.nl()),
            pattern,
            coupling,
            schur,
            rows: (0..nc).map(usize_lit).collect(),
            cols: (0..nv).map(usize_lit).collect(),
        }
    }

    /// Whether M⁻¹ has entries off its diagonal.
    fn coupled(&self) -> bool {
        !self.coupling.is_empty()
    }

    /// `#[inline]` (or `#[inline(always)]`) for a small mechanism's solves, where a call's cost
    /// matters; `#[inline(never)]` for a large one's.
    fn inline_if_small(&self, always: bool) -> TokenStream {
        match (self.nc <= INLINE_SCHUR_ROWS, always) {
            (true, true) => quote!(#[inline(always)]),
            (true, false) => quote!(#[inline]),
            (false, _) => quote!(#[inline(never)]),
        }
    }

    /// The LDLᵀ of S and its solve, and a driven mechanism's refined solves over them.
    fn helpers(&self, constraint_solve: TokenStream, transpose_solve: TokenStream) -> TokenStream {
        let Plan { real, nv_l, nc_l, nnz_l, nl_l, .. } = self;
        let factor = self.schur.factor(real, &self.zero);
        let solve = self.schur.solve(real);
        let minv_off_param = if self.coupled() {
            let n_off = usize_lit(self.coupling.len());
            quote!(minv_off: &[#real; #n_off],)
        } else {
            quote!()
        };
        // Inlined into small mechanisms' solves (a call's cost matters there); kept apart in
        // large ones, where LLVM's optimization of the factor's straight-line, branchy code
        // inlined into each caller grew superlinearly (a 60-link chain's RK4 build took 166 s, a
        // 30-link one 6 s).
        let helper_inline = self.inline_if_small(true);
        quote! {
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
        }
    }
}

/// The forward dynamics of mechanism `m` in formulation `f`: the `ForwardDynamics`
/// implementation, the helpers it calls, and a driven mechanism's kinematic solves.
pub fn forward_dynamics(m: &Model, f: &Formulation, e: &Emitter) -> ForwardCode {
    let plan = Plan::new(m, f, e);
    if !f.mass_blocks {
        return plan.dense();
    }
    let (impl_block, eval_ops) = plan.forward_impl();
    // The kinematic solves of a driven mechanism: the runtime calls them only where D is square;
    // elsewhere the provided methods stand, and nothing is generated to type-check.
    let (position_step, constraint_solve, transpose_solve) =
        if plan.nv != plan.nc { (quote!(), quote!(), quote!()) } else { plan.driven() };
    let helpers = plan.helpers(constraint_solve, transpose_solve);
    ForwardCode { helpers, position_step, impl_block, eval_ops }
}

impl Plan<'_> {
    /// Where M depends on q (joint coordinates): the `ForwardDynamics` implementation by the
    /// runtime's dense factorizations of M(q) and S (`mbd::dense_forward`), and a driven
    /// mechanism's kinematic solves as in body coordinates (they weigh by I, not M). Its
    /// evaluation counts Φ, D, ν, γ and h (M is NV products `mass_times`, counted apart).
    fn dense(&self) -> ForwardCode {
        let Plan { m, f, e, real, nq_l, nv_l, nc_l, .. } = self;
        let name = &m.name;
        let coordinates = crate::coordinates::Coordinates::of(m);
        let mass_bodies: Vec<u16> = (0..self.nv).map(|i| coordinates.body_of_velocity(m, i) as u16).collect();
        let mass_bodies = quote!(&[#(#mass_bodies),*]);
        let friction = !crate::emit::friction_outputs(f).is_empty();
        let mut outputs = crate::emit::vector_outputs("phi", &f.phi);
        outputs.extend(crate::emit::jacobian_values_outputs(f, "jv"));
        outputs.extend(crate::emit::vector_outputs("nu", &f.nu));
        outputs.extend(crate::emit::vector_outputs("gamma", &f.gamma));
        outputs.extend(crate::emit::vector_outputs("h", &f.h));
        outputs.extend(crate::emit::vector_outputs("m", &f.mass));
        outputs.extend(f.mass_coupling.iter().enumerate().map(|(k, &(_, _, node))| {
            let k = usize_lit(k);
            crate::emit::Output { target: quote!(mc[#k]), node }
        }));
        let (_, eval_ops) = e.body(&outputs);
        let (position_step, constraint_solve, transpose_solve) =
            if self.nv != self.nc { (quote!(), quote!(), quote!()) } else { self.driven() };
        let helpers = if self.nv != self.nc { quote!() } else { self.helpers(constraint_solve, transpose_solve) };
        let impl_block = quote! {
            impl ::mbd::ForwardDynamics<#real, #nq_l, #nv_l, #nc_l> for #name {
                #[inline]
                fn accelerations(
                    &self,
                    q: &[#real; #nq_l],
                    v: &[#real; #nv_l],
                    t: #real,
                    options: &::mbd::DynamicsOptions<#real>,
                    vd: &mut [#real; #nv_l],
                    lambda: &mut [#real; #nc_l],
                ) -> ::core::result::Result<(), ::mbd::DynamicsError> {
                    let mut arrays = ::mbd::DenseArrays::new();
                    ::mbd::dense_forward::accelerations(self, arrays.scratch(), q, v, t, options, #friction, #mass_bodies, vd, lambda)
                }
                #[inline]
                fn accelerations_in(
                    &self,
                    scratch: ::mbd::DenseScratch<'_, #real, #nv_l, #nc_l>,
                    q: &[#real; #nq_l],
                    v: &[#real; #nv_l],
                    t: #real,
                    options: &::mbd::DynamicsOptions<#real>,
                    vd: &mut [#real; #nv_l],
                    lambda: &mut [#real; #nc_l],
                ) -> ::core::result::Result<(), ::mbd::DynamicsError> {
                    ::mbd::dense_forward::accelerations(self, scratch, q, v, t, options, #friction, #mass_bodies, vd, lambda)
                }
                #[inline]
                fn project_positions_step(
                    &self,
                    q: &mut [#real; #nq_l],
                    t: #real,
                    options: &::mbd::DynamicsOptions<#real>,
                ) -> ::core::result::Result<#real, ::mbd::DynamicsError> {
                    let mut arrays = ::mbd::DenseArrays::new();
                    ::mbd::dense_forward::project_positions_step(self, arrays.scratch(), q, t, options, #mass_bodies)
                }
                #[inline]
                fn project_positions_step_in(
                    &self,
                    scratch: ::mbd::DenseScratch<'_, #real, #nv_l, #nc_l>,
                    q: &mut [#real; #nq_l],
                    t: #real,
                    options: &::mbd::DynamicsOptions<#real>,
                ) -> ::core::result::Result<#real, ::mbd::DynamicsError> {
                    ::mbd::dense_forward::project_positions_step(self, scratch, q, t, options, #mass_bodies)
                }
                #[inline]
                fn project_velocities(
                    &self,
                    q: &[#real; #nq_l],
                    v: &mut [#real; #nv_l],
                    t: #real,
                    options: &::mbd::DynamicsOptions<#real>,
                ) -> ::core::result::Result<#real, ::mbd::DynamicsError> {
                    let mut arrays = ::mbd::DenseArrays::new();
                    ::mbd::dense_forward::project_velocities(self, arrays.scratch(), q, v, t, options, #mass_bodies)
                }
                #[inline]
                fn project_velocities_in(
                    &self,
                    scratch: ::mbd::DenseScratch<'_, #real, #nv_l, #nc_l>,
                    q: &[#real; #nq_l],
                    v: &mut [#real; #nv_l],
                    t: #real,
                    options: &::mbd::DynamicsOptions<#real>,
                ) -> ::core::result::Result<#real, ::mbd::DynamicsError> {
                    ::mbd::dense_forward::project_velocities(self, scratch, q, v, t, options, #mass_bodies)
                }
            }
        };
        ForwardCode { helpers, position_step, impl_block, eval_ops }
    }
}
