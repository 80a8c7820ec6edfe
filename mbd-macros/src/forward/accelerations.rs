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
        let Plan { f, e, real, nc_l, rows, cols, .. } = self;
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
        // step the friction forces of the λ it is given, then the solve with them. `hf` starts
        // zeroed, and each iteration writes the same non-zeros.
        let applied = self.in_place(quote!(let applied = h;), quote!(applied.copy_from_slice(&h[..]);));
        let declare_hf = self.declare(&["hf"]);
        quote! {
            #applied
            ::mbd::settle_loads(options.friction_tolerance, options.friction_iterations, lambda, |lambda: &mut [#real; #nc_l]| {
                #declare_hf
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
        let Plan { real, nv, nv_l, .. } = self;
        let (minv, minv_off) = self.inverse_mass();
        let coordinates = crate::coordinates::Coordinates::of(self.m);
        let mass_bodies = (0..*nv).map(|i| coordinates.body_of_velocity(self.m, i) as u16);
        let minv_off_arg = if self.coupled() { quote!(&minv_off,) } else { quote!() };
        let (declare_minv, declare_minv_off, declare_factor) =
            (self.declare(&["minv"]), self.declare(&["minv_off"]), self.declare(&["l", "dinv"]));
        quote! {
            #declare_minv
            #(#minv)*
            #declare_minv_off
            #(#minv_off)*
            #declare_factor
            if let ::core::result::Result::Err(row) =
                Self::schur_factor(&jv, &minv, #minv_off_arg options.pivot_tolerance, options.allow_redundant, &mut l, &mut dinv)
            {
                let finite = q.iter().chain(jv.iter()).chain(m.iter()).all(|x| x.is_finite());
                const MASS_BODIES: [u16; #nv_l] = [#(#mass_bodies),*];
                return ::core::result::Result::Err(::mbd::DynamicsError::from_pivot::<Self, #real>(
                    t, row, &m[..], &MASS_BODIES, &jv[..], finite, options.allow_redundant,
                ));
            }
        }
    }

    /// The projections' steps: q ← q ⊕ (−M⁻¹ Dᵀ b) — directly in q where v = q̇, through the
    /// velocity map otherwise — the velocity residual b = D v − ν, and v ← v − M⁻¹ Dᵀ b.
    fn projection_steps(&self) -> (TokenStream, TokenStream, TokenStream) {
        let Plan { real, one, rows, .. } = self;
        let q_step = if self.nq == self.nv {
            in_functions(&self.add_transpose(&quote!(q), &quote!(b), quote!(-=)), "q_step", &[], real)
        } else {
            let dv = in_functions(&self.add_transpose(&quote!(dv), &quote!(b), quote!(-=)), "q_step", &[], real);
            let declare_dv = self.declare(&["dv"]);
            quote! {
                #declare_dv
                #dv
                ::mbd::Kinematics::integrate_positions(self, q, &dv, #one);
            }
        };
        let v_step = self.add_transpose(&quote!(v), &quote!(b), quote!(-=));
        let d_v = self.row_times(&quote!(v));
        let velocity_rows: Vec<TokenStream> = rows.iter().zip(&d_v).map(|(r, d_v)| quote!(b[#r] = #d_v - nu[#r];)).collect();
        (q_step, in_functions(&v_step, "v_step", &[], real), in_functions(&velocity_rows, "velocity_rows", &[], real))
    }

    /// The arrays a `ForwardDynamics` method of this mechanism writes, by name: D's non-zeros
    /// `jv`, S's factor `l` and `dinv`, Φ, ν, γ, h, the mass `m`, M⁻¹ (`minv`, and where M⁻¹ is
    /// coupled its blocks `mi` and off-diagonal `minv_off`), a residual `b` of NC, a velocity
    /// step `dv`, friction's `hf` and the applied forces without it.
    fn locals(&self, names: &[&'static str]) -> Vec<Local> {
        let (nnz, nl) = (self.f.jacobian.len(), self.schur.nl());
        let coupled = |name: &str| matches!(name, "mi" | "minv_off") && !self.coupled();
        names
            .iter()
            .filter(|name| !coupled(name))
            .map(|&name| {
                let (len, from) = match name {
                    "jv" => (nnz, Source::Jacobian),
                    "l" => (nl, Source::Factor),
                    "phi" | "nu" | "gamma" | "dinv" | "b" => (self.nc, Source::Vectors),
                    "h" | "m" | "minv" | "dv" | "hf" | "applied" => (self.nv, Source::Vectors),
                    "mi" => (self.f.mass_inverse.len(), Source::Vectors),
                    "minv_off" => (self.coupling.len(), Source::Vectors),
                    _ => unreachable!("a forward-dynamics array: {name}"),
                };
                // Read before (or without) being written whole: velocity steps accumulated into,
                // friction's forces where it acts, ν where Φ does not depend on t (then not
                // evaluated). The others are written whole first, and taken as they are.
                let zeroed = matches!(name, "dv" | "hf") || (name == "nu" && self.f.phi_t_is_zero());
                Local { name: syn::Ident::new(name, proc_macro2::Span::call_site()), len, from, zeroed }
            })
            .collect()
    }

    /// Whether this mechanism's forward-dynamics arrays are past [`STACK_SCALARS`].
    fn arrays_in_work_space(&self) -> bool {
        let all = ["jv", "phi", "nu", "gamma", "h", "m", "mi", "minv", "minv_off", "l", "dinv", "b", "dv", "hf", "applied"];
        self.locals(&all).iter().map(|local| local.len).sum::<usize>() > STACK_SCALARS
    }

    /// In a small mechanism, the declarations of `names` where the body first needs them (the
    /// arrays the evaluation writes are declared at the method's top, [`EVALUATED`]); in a large
    /// one nothing, as they are parameters. In place, not at the top: zeroed arrays declared far
    /// above their writes stay written twice (the free slider-crank's forward dynamics took 4 %
    /// longer so).
    fn declare(&self, names: &[&'static str]) -> TokenStream {
        if self.arrays_in_work_space() {
            return quote!();
        }
        let zero = &self.zero;
        let locals = self.locals(names);
        let (names, lengths) = locals.iter().map(|local| (&local.name, usize_lit(local.len))).unzip::<_, _, Vec<_>, Vec<_>>();
        quote!(#(let mut #names = [#zero; #lengths];)*)
    }

    /// `small` in a small mechanism, `large` in one whose arrays are parameters.
    fn in_place(&self, small: TokenStream, large: TokenStream) -> TokenStream {
        if self.arrays_in_work_space() {
            large
        } else {
            small
        }
    }

    /// A `ForwardDynamics` method `name(&self, params) -> ret` whose `body` writes `locals`,
    /// and the `_in` method that borrows them from a work space where they are past
    /// [`STACK_SCALARS`]: then both call one inherent `__mbd_name` that takes them as
    /// parameters (the method's own locals, or the work space's; the method's own where the
    /// scratch has too few rows, as a `DenseArrays` on the stack). Returns the trait methods and
    /// the inherent function.
    fn method(
        &self,
        name: &str,
        locals: &[Local],
        params: TokenStream,
        args: TokenStream,
        ret: TokenStream,
        body: TokenStream,
    ) -> (TokenStream, TokenStream) {
        let Plan { real, zero, nv_l, nc_l, .. } = self;
        let method = syn::Ident::new(name, proc_macro2::Span::call_site());
        if !self.arrays_in_work_space() {
            let inline = crate::emit::inline_hint(self.nc);
            let evaluated = locals.iter().filter(|local| EVALUATED.contains(&local.name.to_string().as_str()));
            let (names, lengths) = evaluated.map(|local| (&local.name, usize_lit(local.len))).unzip::<_, _, Vec<_>, Vec<_>>();
            let method = quote! {
                #inline
                fn #method(&self, #params) -> #ret {
                    #(let mut #names = [#zero; #lengths];)*
                    #body
                }
            };
            return (method, quote!());
        }
        let names: Vec<&syn::Ident> = locals.iter().map(|local| &local.name).collect();
        let lengths: Vec<Literal> = locals.iter().map(|local| usize_lit(local.len)).collect();
        let declarations = quote!(#(let mut #names = [#zero; #lengths];)*);
        let inner = quote::format_ident!("__mbd_{}", name);
        let method_in = quote::format_ident!("{}_in", name);
        let nnz = usize_lit(self.f.jacobian.len());
        let nl = usize_lit(self.schur.nl());
        let borrowed = locals.iter().map(|local| match local.from {
            Source::Jacobian => quote!(jv),
            Source::Factor => quote!(l),
            Source::Vectors if local.zeroed => quote!(vectors.take()),
            Source::Vectors => quote!(vectors.take_written()),
        });
        let vector_scalars = usize_lit(locals.iter().filter(|local| matches!(local.from, Source::Vectors)).map(|local| local.len).sum());
        let nq_l = &self.nq_l;
        let trait_path = quote!(::mbd::ForwardDynamics<#real, #nq_l, #nv_l, #nc_l>);
        // A scratch without the rows (`DenseArrays`, on the stack) gets the stack's arrays: the
        // method with them is never inlined, or its frame would be the `_in` method's too.
        let methods = quote! {
            #[inline(never)]
            fn #method(&self, #params) -> #ret {
                #declarations
                self.#inner(#(&mut #names,)* #args)
            }

            fn #method_in(&self, scratch: ::mbd::DenseScratch<'_, #real, #nv_l, #nc_l>, #params) -> #ret {
                match scratch.__sparse_storage::<#nnz, #nl, #vector_scalars>() {
                    ::core::option::Option::Some((jv, l, mut vectors)) => self.#inner(#(#borrowed,)* #args),
                    ::core::option::Option::None => <Self as #trait_path>::#method(self, #args),
                }
            }
        };
        let inner = quote! {
            #[inline(never)]
            #[allow(clippy::too_many_arguments)]
            fn #inner(&self, #(mut #names: &mut [#real; #lengths],)* #params) -> #ret {
                #body
            }
        };
        (methods, inner)
    }

    /// `impl ForwardDynamics` and the operation count of its evaluation.
    pub(super) fn forward_impl(&self) -> (TokenStream, Ops) {
        let Plan { real, nq_l, nv_l, nc_l, .. } = self;
        let name = &self.m.name;
        let Evaluations { accelerations: eval_body, ops, positions: positions_body, velocities: velocities_body } = self.evaluations();
        let solve_for_lambda = self.solve_for_lambda();
        let factor_call = self.factor_call();
        let (q_step, v_step, velocity_rows) = self.projection_steps();
        let friction = if friction_outputs(self.f).is_empty() { &[][..] } else { &["hf", "applied"][..] };
        let solved = ["minv", "minv_off", "l", "dinv"];
        // ‖b‖∞, NaN entries ignored (the callers check the result for finiteness).
        let max_abs = quote! {
            let (worst, _) = ::mbd::__private::max_abs_finite(&b[..]);
        };
        let result = quote!(::core::result::Result<#real, ::mbd::DynamicsError>);
        let copy_phi = self.in_place(quote!(let mut b = phi;), quote!(b.copy_from_slice(&phi[..]);));
        let declare_b = self.declare(&["b"]);

        let accelerations = self.method(
            "accelerations",
            &self.locals(&[&["jv", "phi", "nu", "gamma", "h", "m", "mi"][..], &solved, friction].concat()),
            quote! {
                q: &[#real; #nq_l],
                v: &[#real; #nv_l],
                t: #real,
                options: &::mbd::DynamicsOptions<#real>,
                vd: &mut [#real; #nv_l],
                lambda: &mut [#real; #nc_l],
            },
            quote!(q, v, t, options, vd, lambda),
            quote!(::core::result::Result<(), ::mbd::DynamicsError>),
            quote! {
                #eval_body
                #factor_call
                let two_alpha = options.baumgarte_alpha + options.baumgarte_alpha;
                let beta2 = options.baumgarte_beta * options.baumgarte_beta;
                #solve_for_lambda
            },
        );
        let step = if self.nq == self.nv { &[][..] } else { &["dv"][..] };
        let positions = self.method(
            "project_positions_step",
            &self.locals(&[&["jv", "phi", "m", "mi"][..], &solved, &["b"], step].concat()),
            quote!(q: &mut [#real; #nq_l], t: #real, options: &::mbd::DynamicsOptions<#real>,),
            quote!(q, t, options),
            result.clone(),
            quote! {
                {
                    let q: &[#real; #nq_l] = q;
                    #positions_body
                }
                // Φ copied and its norm taken before the factorization's call, not after: Φ's
                // values kept live across the call took LLVM's instruction selection 24 s of a
                // 240-body chain's 74 s build (1.8 s this way).
                #copy_phi
                #max_abs
                #factor_call
                Self::schur_solve(&l, &dinv, &mut b);
                #q_step
                ::core::result::Result::Ok(worst)
            },
        );
        let velocities = self.method(
            "project_velocities",
            &self.locals(&[&["jv", "nu", "m", "mi"][..], &solved, &["b"]].concat()),
            quote!(q: &[#real; #nq_l], v: &mut [#real; #nv_l], t: #real, options: &::mbd::DynamicsOptions<#real>,),
            quote!(q, v, t, options),
            result,
            quote! {
                #velocities_body
                #factor_call
                #declare_b
                {
                    let v: &[#real; #nv_l] = v;
                    #velocity_rows
                }
                #max_abs
                Self::schur_solve(&l, &dinv, &mut b);
                #v_step
                ::core::result::Result::Ok(worst)
            },
        );
        let [(accelerations, accelerations_inner), (positions, positions_inner), (velocities, velocities_inner)] =
            [accelerations, positions, velocities];
        let inner = if !self.arrays_in_work_space() {
            quote!()
        } else {
            quote! {
                #[allow(unused_variables, unused_parens, unused_mut, clippy::approx_constant)]
                impl #name {
                    #accelerations_inner
                    #positions_inner
                    #velocities_inner
                }
            }
        };
        let impl_block = quote! {
            // Constants are the user's expressions evaluated (`PI / 2.0` → 1.5707963267948966).
            #[allow(unused_variables, unused_parens, unused_mut, clippy::approx_constant)]
            impl ::mbd::ForwardDynamics<#real, #nq_l, #nv_l, #nc_l> for #name {
                #accelerations
                #positions
                #velocities
            }

            #inner
        };
        (impl_block, ops)
    }
}

/// Scalars of forward-dynamics arrays (16 KiB of f64) up to which a mechanism's generated
/// `ForwardDynamics` methods keep them on the stack, where LLVM may keep small ones in
/// registers; past it, a call through a work space (`accelerations_in`, the projections'
/// `_in`, as every solver and integrator makes) borrows them from its heap instead, so that the
/// stack a solve takes does not grow with the mechanism.
const STACK_SCALARS: usize = 2048;

/// The arrays a small mechanism's method declares at its top: those its evaluation writes.
const EVALUATED: [&str; 7] = ["jv", "phi", "nu", "gamma", "h", "m", "mi"];

/// Where a large mechanism's array is borrowed from in the work space: D's non-zeros fit in the
/// NC × NV dense array, S's factor in the NC × NC one (body coordinates, whose forward dynamics
/// is this sparse solve, do not use them otherwise), vectors from the solvers' rows.
#[derive(Clone, Copy)]
enum Source {
    Jacobian,
    Factor,
    Vectors,
}

/// An array of [`Plan::locals`]: its name, length, where a large mechanism borrows it from, and
/// whether it must start zeroed there.
struct Local {
    name: syn::Ident,
    len: usize,
    from: Source,
    zeroed: bool,
}
