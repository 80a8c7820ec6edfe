//! The chain parse → model → formulation → emit, and the code that ties the emitted functions
//! into the mechanism's type and its `mbd::Mechanism` / `mbd::Kinematics` implementations.

use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

use crate::emit::{self, friction_outputs, jacobian_values_outputs, real, usize_lit, vector_outputs, Emitter, Ops, Output};
use crate::formulation::{formulate, Formulation};
use crate::forward::{forward_dynamics, ForwardCode};
use crate::json::model_json;
use crate::model::{Model, Partial};
use crate::parse::{BodyDef, Expr, Item, MechanismDef};

/// Expands a `mechanism!` invocation: its parts and loops expanded ([`crate::part`],
/// [`crate::repeat`]), then the base mechanism and each of its scenes ([`crate::scene`]); every
/// name in its texts as the user wrote it ([`crate::names`]). Never fails: mistakes become
/// `compile_error!`s next to a placeholder of the mechanism's type, generated from its statements
/// without mistakes, so code that uses the type does not add follow-up errors. A mistake in the
/// base is reported once: its scenes, which share it, are then only placeholders.
pub fn expand(input: TokenStream) -> TokenStream {
    let mut names = crate::names::Names::default();
    let written = input.clone();
    let out = refuse_raw_identifiers(&input)
        .and_then(|()| crate::part::expand(input, &mut names))
        .and_then(|input| crate::scene::split(input.clone(), &names).map_err(|e| statements_that_do_not_parse(input).unwrap_or(e)))
        .map(|(base, scenes)| {
            let (mut out, ok) = expand_one(base);
            for scene in scenes {
                if ok {
                    out.extend(expand_one(scene).0);
                } else if let Ok((def, _)) = syn::parse::Parser::parse2(MechanismDef::parse_recovering, scene) {
                    out.extend(placeholder(def));
                }
            }
            out
        });
    // A mistake in a part, a loop, an instance or a scene: the placeholders of the mechanism
    // expanded leniently, or without the statement that has it.
    let out = out.unwrap_or_else(|e| {
        let errors = crate::wording::compile_errors(e);
        let placeholders = placeholders_without_the_mistake(written);
        quote!(#errors #placeholders)
    });
    names.rewrite_strings(out)
}

/// The errors of the mechanism's statements that do not parse, its scenes set aside: where a
/// scene names what the mechanism does not have, a statement that does not parse (a missing `;`
/// that joins `drive motor: ...` to the statement before it) is the mistake to report.
fn statements_that_do_not_parse(input: TokenStream) -> Option<syn::Error> {
    use proc_macro2::{Delimiter, Group, TokenTree};
    let without_scenes: TokenStream = input
        .into_iter()
        .map(|tt| match tt {
            TokenTree::Group(g) if g.delimiter() == Delimiter::Brace => {
                let kept = crate::scene::statements(g.stream())
                    .into_iter()
                    .filter(|s| !matches!(s.first(), Some(TokenTree::Ident(k)) if k == "scene"))
                    .flatten()
                    .collect();
                TokenTree::Group(Group::new(Delimiter::Brace, kept))
            }
            other => other,
        })
        .collect();
    syn::parse::Parser::parse2(MechanismDef::parse_recovering, without_scenes).ok().and_then(|(_, errors)| errors)
}

/// The placeholders of a mechanism (and its scenes) whose parts, loops, instances or scenes do
/// not expand: made of the mechanism with its instances' parameters taken leniently, or without
/// the first top-level statement whose removal lets it expand, or, when no one statement does,
/// of what parses as written.
fn placeholders_without_the_mistake(written: TokenStream) -> TokenStream {
    use proc_macro2::{Delimiter, Group, TokenTree};
    let tokens: Vec<TokenTree> = written.clone().into_iter().collect();
    let body = tokens.iter().position(|t| matches!(t, TokenTree::Group(g) if g.delimiter() == Delimiter::Brace));
    let expands = |input: TokenStream| {
        let names = &mut crate::names::Names::default();
        refuse_raw_identifiers(&input)
            .and_then(|()| crate::part::expand_leniently(input, names))
            .and_then(|input| crate::scene::split_leniently(input, names))
    };
    let placeholder_of =
        |input: TokenStream| syn::parse::Parser::parse2(MechanismDef::parse_recovering, input).map(|(def, _)| placeholder(def)).ok();
    // Instances' parameters and scenes' items are taken leniently: one missing or misspelt loses
    // nothing else.
    if let Ok((base, scenes)) = expands(written.clone()) {
        return std::iter::once(base).chain(scenes).filter_map(placeholder_of).collect();
    }
    if let Some(at) = body {
        let TokenTree::Group(g) = &tokens[at] else { unreachable!("found as a brace group") };
        let statements = crate::scene::statements(g.stream());
        for k in 0..statements.len() {
            let kept: TokenStream = statements.iter().enumerate().filter(|&(i, _)| i != k).flat_map(|(_, s)| s.clone()).collect();
            let mut candidate = tokens.clone();
            candidate[at] = TokenTree::Group(Group::new(Delimiter::Brace, kept));
            if let Ok((base, scenes)) = expands(candidate.into_iter().collect()) {
                return std::iter::once(base).chain(scenes).filter_map(placeholder_of).collect();
            }
        }
    }
    placeholder_of(written).unwrap_or_default()
}

/// A raw identifier (`r#type`) names nothing in a mechanism: the names it makes from names
/// (`l_3`, `front_left_hub`, `CRANK`) would not be identifiers.
fn refuse_raw_identifiers(input: &TokenStream) -> syn::Result<()> {
    for tt in input.clone() {
        match tt {
            proc_macro2::TokenTree::Ident(id) if id.to_string().starts_with("r#") => {
                let plain = id.to_string()[2..].to_string();
                return Err(syn::Error::new(
                    id.span(),
                    format!("a raw identifier cannot name a body, point or element: expected a plain name, found `{id}`; write `{plain}_`"),
                ));
            }
            proc_macro2::TokenTree::Group(g) => refuse_raw_identifiers(&g.stream())?,
            _ => {}
        }
    }
    Ok(())
}

/// Expands one mechanism; whether it had no mistakes. With mistakes: their errors, and a
/// placeholder of the mechanism ([`placeholder`]).
fn expand_one(input: TokenStream) -> (TokenStream, bool) {
    let (def, parse_errors) = match syn::parse::Parser::parse2(MechanismDef::parse_recovering, input) {
        Ok(parsed) => parsed,
        Err(e) => return (crate::wording::compile_errors(e), false),
    };
    let errors = match parse_errors {
        // The statements that did not parse are reported; the rest are not checked, since what
        // they name may be in a statement that did not parse.
        Some(e) => e,
        None => match def.validate().and_then(|m| generate(&m)) {
            Ok(ts) => return (ts, true),
            Err(e) => e,
        },
    };
    let errors = crate::wording::compile_errors(errors);
    let placeholder = placeholder(def);
    (quote!(#errors #placeholder), false)
}

/// The type of a mechanism that has mistakes, generated in full from its statements without
/// mistakes, so that the user's code using it — its constants, traits, accessors and solvers —
/// adds no errors of its own: one mistake, one error. Statements are taken in order, each kept
/// if it adds no error (a joint naming a body whose statement is wrong goes with it), or else
/// replaced by the first of its [`stand_ins`] that has fewer errors, so that what names it still
/// resolves. If what is left still does not generate, the bare struct with its parameters.
fn placeholder(mut def: MechanismDef) -> TokenStream {
    let count = |def: &MechanismDef| def.validate().err().map_or(0, |e| e.into_iter().count());
    let partial = def.partial();
    let spatial = def.items.iter().any(|i| matches!(i, Item::Spatial(_)));
    let body_names: Vec<String> =
        def.items.iter().filter_map(|i| if let Item::Body(b) = i { Some(b.name.to_string()) } else { None }).collect();
    let bodies: Vec<&str> = body_names.iter().map(String::as_str).collect();
    let mut left = std::mem::take(&mut def.items);
    let mut errors = count(&def);
    // Passes until one keeps nothing more: a statement may name what a later one declares.
    loop {
        let kept = def.items.len();
        let mut dropped = Vec::new();
        for statement in left {
            let candidates = stand_ins(&statement, spatial, &bodies);
            def.items.push(statement);
            let mut now = count(&def);
            // The first stand-in with fewer errors, instead.
            for stand_in in candidates {
                if now == 0 {
                    break;
                }
                let original = std::mem::replace(def.items.last_mut().expect("just pushed"), stand_in);
                let instead = count(&def);
                if instead < now {
                    now = instead;
                    break;
                }
                *def.items.last_mut().expect("just pushed") = original;
            }
            if now > errors {
                dropped.extend(def.items.pop());
            } else {
                errors = now;
            }
        }
        if dropped.is_empty() || def.items.len() == kept {
            break;
        }
        left = dropped;
    }
    // A type needs a body: where none is left, one of unit mass and inertia stands in.
    if !def.items.iter().any(|i| matches!(i, Item::Body(_))) {
        let name = proc_macro2::Ident::new("placeholder", def.name.span());
        def.items.push(Item::Body(BodyDef::unit(name, spatial, false)));
    }
    let generated = def.validate().and_then(|mut m| {
        m.warnings.clear();
        generate(&m)
    });
    generated.unwrap_or_else(|_| stub(&partial))
}

/// What may stand in for a statement with a mistake, in order ([`placeholder`]), so that the
/// names it makes (`Name::MOTOR`, `Name::CRANK`) are still there: a body of unit mass and
/// inertia, parameters with defaults 0, a driver of a constant (of each of its body's
/// coordinates, where its own is wrong), a joint without its options, a point on a misspelt
/// body on the body whose name is nearest.
fn stand_ins(statement: &Item, spatial: bool, bodies: &[&str]) -> Vec<Item> {
    match statement {
        // A point on a misspelt body: on the body it is nearest to.
        Item::Point(p) => crate::parse::nearest(&p.body.to_string(), bodies, &["ground"])
            .map(|body| Item::Point(crate::parse::NamedVector { body: syn::Ident::new(body, p.body.span()), ..p.clone() }))
            .into_iter()
            .collect(),
        // A driver of a constant; where its coordinate is what is wrong, of each of its body's.
        Item::Drive(d) => {
            let constant = crate::parse::DriveDef { f: Expr::number(1.0, d.f.span, d.f.end), ..d.clone() };
            let mut candidates = vec![Item::Drive(constant.clone())];
            if let crate::parse::DriveTarget::Coordinate { body, coordinate } = &d.target {
                candidates.extend(["phi", "x", "y", "z"].iter().map(|c| {
                    let target =
                        crate::parse::DriveTarget::Coordinate { body: body.clone(), coordinate: syn::Ident::new(c, coordinate.span()) };
                    Item::Drive(crate::parse::DriveDef { target, ..constant.clone() })
                }));
            }
            candidates
        }
        Item::Joint(j) if !j.options.is_empty() => vec![Item::Joint(crate::parse::JointDef { options: Vec::new(), ..j.clone() })],
        Item::Body(b) => vec![Item::Body(BodyDef::unit(b.name.clone(), spatial, b.particle))],
        Item::Params(ps) => {
            vec![Item::Params(ps.iter().map(|(name, value)| (name.clone(), Expr::number(0.0, value.span, value.end))).collect())]
        }
        _ => Vec::new(),
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

fn op_count(name: &str, ops: Ops) -> TokenStream {
    let Ops { add, mul, div, call } = ops;
    quote!(::mbd::OpCount { function: #name, add: #add, mul: #mul, div: #div, call: #call })
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
#[allow(clippy::too_many_lines)] // 541 lines: to be split by concern (issue 38, item 7)
pub fn generate(m: &Model) -> syn::Result<TokenStream> {
    let f = formulate(m);
    emit::check_finite(m, &f, m.name.span())?;
    let e: Emitter = emit::emitter(m, &f);
    // Warnings through the one channel stable Rust gives a macro: a deprecated item used on the
    // span. The compiler names the item first ("use of deprecated unit struct
    // `_::mbd_warning`: ..."), so it is named for what it is.
    let warnings = m.warnings.iter().map(|(span, msg)| {
        let use_ = quote::quote_spanned!(*span=> let _ = mbd_warning;);
        quote! {
            const _: () = {
                #[deprecated(note = #msg)]
                #[allow(non_camel_case_types)]
                struct mbd_warning;
                #use_
            };
        }
    });
    let warnings = quote!(#(#warnings)*);
    let real = real(m.scalar);
    let name = &m.name;
    let vis = &m.vis;
    let attrs = &m.attrs;
    let (nb, nq, nv, nc, nnz) = (m.bodies.len(), f.nq, f.nv, f.nc, f.jacobian.len());
    let (nb_l, nq_l, nv_l, nc_l, nnz_l) = (usize_lit(nb), usize_lit(nq), usize_lit(nv), usize_lit(nc), usize_lit(nnz));
    let np = usize_lit(m.params.len());
    let dof = nv as i32 - nc as i32;
    let zero = e.literal(0.0);
    let inline = crate::emit::inline_hint(nc);

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
    // The constant diagonal of M, only its non-zeros.
    let mass_entries: Vec<usize> = (0..nv).filter(|&i| !f.graph.is_zero(f.mass[i])).collect();
    let mass_outputs: Vec<Output> = mass_entries
        .iter()
        .map(|&i| {
            let il = usize_lit(i);
            Output { target: quote!(m[#il]), node: f.mass[i] }
        })
        .collect();
    // and its products of inertia (spatial bodies), `mc[k]` the k-th of `mass_coupling`
    let mut mass_outputs = mass_outputs;
    mass_outputs.extend(f.mass_coupling.iter().enumerate().map(|(k, &(_, _, node))| {
        let k = usize_lit(k);
        Output { target: quote!(mc[#k]), node }
    }));
    let (mass_body, _) = e.body(&mass_outputs);
    // y = M x writes every entry: zeros first only where M has a zero on its diagonal.
    let zero_y = if mass_entries.len() < nv { quote!(*y = [#zero; #nv_l];) } else { quote!() };
    let mass_entries: Vec<Literal> = mass_entries.into_iter().map(usize_lit).collect();
    let (coupling_decl, coupling_times, coupling_add) = if f.mass_coupling.is_empty() {
        (quote!(), quote!(), quote!())
    } else {
        let n = usize_lit(f.mass_coupling.len());
        let (k, r, c): (Vec<Literal>, Vec<Literal>, Vec<Literal>) =
            f.mass_coupling.iter().enumerate().map(|(k, &(r, c, _))| (usize_lit(k), usize_lit(r), usize_lit(c))).collect();
        (quote!(let mut mc = [#zero; #n];), quote!(#( y[#r] += mc[#k] * x[#c]; )*), quote!(#( a[#r][#c] += scale * mc[#k]; )*))
    };
    let coordinates = crate::coordinates::Coordinates::of(m.space);
    let positions_code = coordinates.position_updates(m, &e);
    let body_frames = coordinates.body_frames(m, name);
    let named = named_items(m, &f, &e);
    // What h, ∂h/∂q and ∂h/∂v cost with no element, and with each element alone.
    let alone = |t: &crate::formulation::ForceTerms| -> [Ops; 3] {
        [e.body(&vector_outputs("h", &t.h)).1, e.body(&matrix_outputs("dh", &t.h_q)).1, e.body(&matrix_outputs("dh", &t.h_qd)).1]
    };
    let force_ops = (alone(&f.base_forces), f.alone_forces.iter().map(alone).collect::<Vec<_>>());
    let (h_body, h_ops) = e.body(&vector_outputs("h", &f.h));
    let (h_q_body, h_q_ops) = e.body(&matrix_outputs("dh", &f.h_q));
    let (h_v_body, h_v_ops) = e.body(&matrix_outputs("dh", &f.h_qd));
    let (v_body, v_ops) = e.body(&[Output { target: quote!(energy[0]), node: f.potential }]);
    let switching = if f.switches.is_empty() {
        quote!()
    } else {
        let names = f.switches.iter().map(|(n, _)| n.as_str());
        let cases = f.switches.iter().enumerate().map(|(k, &(_, node))| {
            let (body, _) = e.body(&[Output { target: quote!(g[0]), node }]);
            let k = usize_lit(k);
            quote!(#k => {
                let mut g = [#zero; 1];
                #body
                g[0]
            })
        });
        quote! {
            const SWITCH_NAMES: &'static [&'static str] = &[#(#names),*];
            #inline
            fn switching_function(&self, k: usize, q: &[#real; #nq_l], v: &[#real; #nv_l], t: #real) -> #real {
                match k {
                    #(#cases)*
                    _ => #zero,
                }
            }
        }
    };
    let (cfq_body, cfq_ops) = e.body(&matrix_outputs("k", &f.constraint_force_q));
    let mut gamma_outputs = matrix_outputs("gamma_q", &f.gamma_q);
    gamma_outputs.extend(matrix_outputs("gamma_v", &f.gamma_v));
    let (gamma_derivatives_body, _) = e.body(&gamma_outputs);
    let input_names: Vec<String> = f.inputs.iter().map(|&k| m.params[k].name.to_string()).collect();
    let input_fields: Vec<&syn::Ident> = f.inputs.iter().map(|&k| &m.params[k].name).collect();
    let input_indices: Vec<Literal> = (0..f.inputs.len()).map(usize_lit).collect();
    let forces_input_cases = (0..f.inputs.len()).map(|k| {
        let entries: Vec<Output> = f
            .h_u
            .iter()
            .filter(|e| e.1 == k)
            .map(|&(r, _, node)| {
                let r = usize_lit(r);
                Output { target: quote!(dh[#r]), node }
            })
            .collect();
        let (body, _) = e.body(&entries);
        let k = usize_lit(k);
        quote!(#k => { #body })
    });
    let (power_body, power_ops) = e.body(&[Output { target: quote!(power[0]), node: f.power }]);
    let forward = forward_dynamics(m, &f, &e);
    let newton = crate::newton::newton_matrix(&f, &e, name);
    let friction = friction_outputs(&f);
    let friction_fn = if friction.is_empty() {
        quote!()
    } else {
        let (body, _) = e.body(&friction);
        let indices: Vec<Literal> =
            f.friction.iter().enumerate().filter(|(_, &n)| !f.graph.is_zero(n)).map(|(i, _)| usize_lit(i)).collect();
        quote! {
            let mut hf = [#zero; #nv_l];
            #body
            #( h[#indices] += hf[#indices]; )*
        }
    };
    // ∂/∂q and ∂/∂v of the friction forces, added into the caller's dense matrices.
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
        let (add_q, add_v) = (add(quote!(d_q), quote!(fq), &f.friction_q), add(quote!(d_v), quote!(fqd), &f.friction_qd));
        quote! {
            let mut fq = [#zero; #n_q];
            let mut fqd = [#zero; #n_qd];
            #body
            #add_q
            #add_v
        }
    };
    let nz_l = usize_lit(nv + nc);
    let mut joints = Vec::new();
    let mut first_row = 0u16;
    for (index, c) in m.constraints.iter().enumerate() {
        let end = f.first_rows.get(index + 1).copied().unwrap_or(nc);
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
        joints.push(quote!(::mbd::JointInfo { name: #name, kind: #kind, first_row: #first_row, rows: #rows, body_i: #bi, body_j: #bj }));
        first_row += rows;
    }
    let mut effects: Vec<&str> = Vec::new();
    if m.gravity.is_some() {
        effects.push("gravity");
    }
    for element in &m.forces {
        if !effects.contains(&element.kind.effect()) {
            effects.push(element.kind.effect());
        }
    }
    let force_counts = |counts: &[Ops; 3]| {
        let counts = ["forces", "forces_q", "forces_v"].iter().zip(counts).map(|(name, &ops)| op_count(name, ops));
        quote!(&[#(#counts),*])
    };
    let base_force_counts = force_counts(&force_ops.0);
    let force_elements = f.force_velocities.iter().zip(&force_ops.1).map(|((name, velocities), alone)| {
        let velocities = velocities.iter().map(|&i| i as u16);
        let counts = force_counts(alone);
        quote!(::mbd::ForceInfo { name: #name, velocities: &[#(#velocities),*], op_counts: #counts })
    });
    let (v0_body, _) = e.body(&vector_outputs("v", &f.qd0));

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
        op_count("forces_v", h_v_ops),
        op_count("potential_energy", v_ops),
        op_count("constraint_force_q", cfq_ops),
        op_count("nonconservative_power", power_ops),
        op_count("accelerations (evaluation, before the solve)", forward.eval_ops),
        op_count("newton_matrix (Φ, D and generalized-α's matrix, before the factorization)", newton.matrix_ops),
    ];
    let ForwardCode { helpers, impl_block, position_step, .. } = forward;
    let newton_impl = newton.impl_block;
    let newton_storage = Literal::usize_unsuffixed(newton.storage);

    let body_names: Vec<String> = m.bodies.iter().map(|b| b.name.to_string()).collect();
    let coordinate_names = m.coordinate_names();
    // planar v = q̇: the velocities are named by their coordinates, as the runtime's messages say
    let velocity_names = if m.space == crate::model::Space::Planar { m.coordinate_names() } else { m.velocity_names() };
    let (coordinate_infos, velocity_infos) = crate::coordinates::Coordinates::of(m.space).descriptors(m);
    let row_names = &f.row_names;
    let row_units = f.row_units.iter().map(|u| u.multiplier());
    let tables = crate::docs::tables(m, &f, &force_ops);
    let param_names: Vec<String> = m.params.iter().map(|p| p.name.to_string()).collect();
    let pattern: Vec<(usize, usize)> = f.jacobian.iter().map(|&(r, c, _)| (r, c)).collect();
    let pattern_tokens = pattern.iter().map(|&(r, c)| {
        let (r, c) = (r as u16, c as u16);
        quote!((#r, #c))
    });
    let phi_t_zero = f.phi_t_is_zero();
    let json = model_json(m, &f.row_names, &f.first_rows, &pattern);
    let name_str = name.to_string();

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
    let (per_body_q, per_body_v) = match m.space {
        crate::model::Space::Planar => ("3 per body: x, y, φ", "3 per body; planar v = q̇, so NV = NQ"),
        crate::model::Space::Spatial => ("7 per body: x, y, z, e0, e1, e2, e3", "6 per body: ẋ, ẏ, ż, ω′x, ω′y, ω′z"),
    };
    let (doc_nq, doc_nv) =
        (format!(" Number of generalized coordinates q ({per_body_q})."), format!(" Number of velocities v ({per_body_v})."));
    let zero_nu = if phi_t_zero { quote!(*nu = [#zero; #nc_l];) } else { nu_body };

    // The parts of functions emitted in parts (`Emitter::body_in_parts`), all generated by now.
    let parts = e.parts.take();
    let parts = (!parts.is_empty()).then(|| {
        quote! {
            // Constants are the user's expressions evaluated (`PI / 2.0` → 1.5707963267948966).
            #[allow(unused_variables, unused_parens, unused_mut, clippy::approx_constant, clippy::too_many_arguments)]
            impl #name {
                #(#parts)*
            }
        }
    });

    Ok(quote! {
        #warnings
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
        }

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
            fn forces(&self, q: &[#real; #nq_l], v: &[#real; #nv_l], t: #real, h: &mut [#real; #nv_l]) {
                #h_body
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
                #friction_derivatives_fn
            }
            #inline
            fn nonconservative_power(&self, q: &[#real; #nq_l], v: &[#real; #nv_l], t: #real) -> #real {
                let mut power = [#zero; 1];
                #power_body
                power[0]
            }
        }

        // Constants are the user's expressions evaluated (`PI / 2.0` → 1.5707963267948966).
        #[allow(unused_variables, unused_parens, unused_mut, clippy::approx_constant)]
        impl #name {
            #helpers
        }

        #impl_block
        #newton_impl
        #body_frames
        #parts

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
            #position_step
            #inline
            fn position_eval(&self, q: &[#real; #nq_l], t: #real, phi: &mut [#real; #nc_l], d: &mut [[#real; #nv_l]; #nc_l]) {
                for row in d.iter_mut() {
                    *row = [#zero; #nv_l];
                }
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
                for row in d.iter_mut() {
                    *row = [#zero; #nv_l];
                }
                #full_body
            }
        }
    })
}

/// Named access: a constant per body (`Name::CRANK`, a `PlanarBody` or `SpatialBody`) and per
/// labelled joint, driver or constraint (`Name::MOTOR`, its index into `JOINTS`), and an
/// accessor per named point on a body (`crank_a()`, its coordinates evaluated from the
/// parameters).
fn named_items(m: &Model, f: &Formulation, e: &Emitter) -> TokenStream {
    let real = real(m.scalar);
    let (body_type, point_type) = match m.space {
        crate::model::Space::Planar => (quote!(::mbd::PlanarBody), quote!(::mbd::PlanarPoint)),
        crate::model::Space::Spatial => (quote!(::mbd::SpatialBody), quote!(::mbd::SpatialPoint)),
    };
    let bodies = m.bodies.iter().enumerate().map(|(k, b)| {
        let (name, constant) = (b.name.to_string(), format_ident!("{}", crate::model::constant_name(&b.name.to_string())));
        let (doc, k) = (format!(" Body `{name}`: its coordinates, velocities and points."), usize_lit(k));
        quote!(#[doc = #doc] pub const #constant: #body_type = #body_type::new(#k, #name);)
    });
    let joints = m.constraints.iter().enumerate().filter(|(_, c)| syn::parse_str::<syn::Ident>(&c.name).is_ok()).map(|(k, c)| {
        let constant = format_ident!("{}", crate::model::constant_name(&c.name));
        let (doc, k) = (format!(" The {} `{}`: its index into `JOINTS` (for `joint_reaction`).", c.kind.kind(), c.name), usize_lit(k));
        quote!(#[doc = #doc] pub const #constant: usize = #k;)
    });
    let dim = usize_lit(m.space.dim());
    let points = m.points.iter().zip(&f.points).map(|(p, nodes)| {
        let crate::model::BodyRef::Body(k) = p.body else { return ground_point(m, &p.name, nodes, e) };
        let body = m.bodies[k].name.to_string();
        let accessor = format_ident!("{}", crate::model::point_accessor(&body, &p.name));
        let (doc, constant) = (format!(" Point `{body}.{}`.", p.name), format_ident!("{}", crate::model::constant_name(&body)));
        let (local, _) = e.body(&vector_outputs("local", nodes));
        let zero = e.literal(0.0);
        quote! {
            #[doc = #doc]
            #[allow(unused_parens)]
            pub fn #accessor(&self) -> #point_type<#real> {
                let mut local = [#zero; #dim];
                #local
                Self::#constant.point(local)
            }
        }
    });
    let (nq, nv) = (usize_lit(f.nq), usize_lit(f.nv));
    let coordinates = f.joint_coordinates.iter().map(|(accessor, node, rate)| {
        let (what, unit, joint) = match accessor.rsplit_once('_') {
            Some((joint, "angle")) => {
                ("angle θ (rad): the turn of its second marker about the first one's axis from its x-axis", "rad/s", joint)
            }
            Some((joint, _)) => ("stroke s (m): the slide of its second marker along the first one's axis", "m/s", joint),
            None => ("coordinate", "", accessor.as_str()),
        };
        let doc = format!(" The {what}, of joint `{joint}` at q (valid within (−π, π) for an angle).");
        let rate_doc = format!(" The rate ({unit}) of `{accessor}`, at (q, v): its derivative along q̇ = B(q) v.");
        let rate_accessor = format_ident!("{}_rate", accessor);
        let accessor = format_ident!("{}", accessor);
        let (body, _) = e.body(&[Output { target: quote!(out[0]), node: *node }]);
        let (rate_body, _) = e.body(&[Output { target: quote!(out[0]), node: *rate }]);
        let zero = e.literal(0.0);
        quote! {
            #[doc = #doc]
            #[allow(unused_parens, clippy::approx_constant)]
            pub fn #accessor(&self, q: &[#real; #nq]) -> #real {
                let mut out = [#zero; 1];
                #body
                out[0]
            }
            #[doc = #rate_doc]
            #[allow(unused_parens, unused_variables, clippy::approx_constant)]
            pub fn #rate_accessor(&self, q: &[#real; #nq], v: &[#real; #nv]) -> #real {
                let mut out = [#zero; 1];
                #rate_body
                out[0]
            }
        }
    });
    let inertia = body_inertia(m, f, e);
    quote!(#(#bodies)* #(#joints)* #(#points)* #(#coordinates)* #inertia)
}

/// `mass_of(Name::BODY)` (kg) and `inertia_of(Name::BODY)`: J (kg·m²) about the centre of mass
/// in the plane, the 3×3 tensor J′ in the body frame in space — read from the model, so a
/// parameter-dependent mass reads the parameters' current values.
fn body_inertia(m: &Model, f: &Formulation, e: &Emitter) -> TokenStream {
    let real = real(m.scalar);
    let n = m.bodies.len();
    let per_body = f.nv / n.max(1);
    let masses: Vec<Output> = (0..n)
        .map(|k| {
            let kl = usize_lit(k);
            Output { target: quote!(out[#kl]), node: f.mass[per_body * k] }
        })
        .collect();
    let (mass_body, _) = e.body(&masses);
    let zero = e.literal(0.0);
    let nb = usize_lit(n);
    let (body_type, inertia_of) = match m.space {
        crate::model::Space::Planar => {
            let js: Vec<Output> = (0..n)
                .map(|k| {
                    let kl = usize_lit(k);
                    Output { target: quote!(out[#kl]), node: f.mass[3 * k + 2] }
                })
                .collect();
            let (j_body, _) = e.body(&js);
            let inertia_of = quote! {
                /// The moment of inertia J (kg·m²) of a body (`Name::BODY`) about its centre of mass.
                #[allow(unused_parens, clippy::approx_constant)]
                pub fn inertia_of(&self, body: ::mbd::PlanarBody) -> #real {
                    let mut out = [#zero; #nb];
                    #j_body
                    out[body.index]
                }
            };
            (quote!(::mbd::PlanarBody), inertia_of)
        }
        crate::model::Space::Spatial => {
            // out[k][r][c] = J′_rc of body k: the diagonal from M's, the products from its coupling.
            let mut js: Vec<Output> = Vec::new();
            for k in 0..n {
                let kl = usize_lit(k);
                for r in 0..3 {
                    let rl = usize_lit(r);
                    js.push(Output { target: quote!(out[#kl][#rl][#rl]), node: f.mass[6 * k + 3 + r] });
                }
            }
            for &(r, c, node) in &f.mass_coupling {
                let (kl, rl, cl) = (usize_lit(r / 6), usize_lit(r % 6 - 3), usize_lit(c % 6 - 3));
                js.push(Output { target: quote!(out[#kl][#rl][#cl]), node });
            }
            let (j_body, _) = e.body(&js);
            let inertia_of = quote! {
                /// The inertia tensor J′ (kg·m²) of a body (`Name::BODY`) about its centre of mass,
                /// in body-frame components.
                #[allow(unused_parens, clippy::approx_constant)]
                pub fn inertia_of(&self, body: ::mbd::SpatialBody) -> ::mbd::nalgebra::Matrix3<#real> {
                    let mut out = [[[#zero; 3]; 3]; #nb];
                    #j_body
                    ::mbd::nalgebra::Matrix3::from_fn(|r, c| out[body.index][r][c])
                }
            };
            (quote!(::mbd::SpatialBody), inertia_of)
        }
    };
    let mass_of = quote! {
        /// The mass (kg) of a body (`Name::BODY`).
        #[allow(unused_parens, clippy::approx_constant)]
        pub fn mass_of(&self, body: #body_type) -> #real {
            let mut out = [#zero; #nb];
            #mass_body
            out[body.index]
        }
    };
    quote!(#mass_of #inertia_of)
}

/// The accessor of a named point on ground, `ground_o()`: its fixed position (global).
fn ground_point(m: &Model, name: &str, nodes: &[u32], e: &Emitter) -> TokenStream {
    let real = real(m.scalar);
    let accessor = format_ident!("{}", crate::model::point_accessor("ground", name));
    let doc = format!(" Point `ground.{name}`: fixed, global coordinates (m).");
    let (point, dim) = match m.space {
        crate::model::Space::Planar => (quote!(::mbd::nalgebra::Point2), usize_lit(2)),
        crate::model::Space::Spatial => (quote!(::mbd::nalgebra::Point3), usize_lit(3)),
    };
    let (body, _) = e.body(&vector_outputs("p", nodes));
    let zero = e.literal(0.0);
    quote! {
        #[doc = #doc]
        #[allow(unused_parens)]
        pub fn #accessor(&self) -> #point<#real> {
            let mut p = [#zero; #dim];
            #body
            #point::from(p)
        }
    }
}

/// The expansion of `input` as text, with the temporaries `v<n>` renumbered v0, v1, … in order
/// of first appearance and `MODEL_JSON` set aside (it describes each expression as written): two
/// declarations that generate the same functions give the same text.
#[cfg(test)]
pub fn canonical(input: TokenStream) -> String {
    canonical_text(expand(input).to_string())
}

/// [`canonical`] of an expansion's text.
#[cfg(test)]
pub fn canonical_text(mut code: String) -> String {
    assert!(!code.contains("compile_error"), "{code}");
    let json = code.find("const MODEL_JSON").expect("the model JSON");
    let end = json + code[json..].find("\" ;").expect("its end");
    code.replace_range(json..end, "");
    let mut seen = std::collections::HashMap::new();
    let (mut out, mut word) = (String::new(), String::new());
    for c in code.chars().chain([' ']) {
        if c.is_ascii_alphanumeric() || c == '_' {
            word.push(c);
            continue;
        }
        if word.len() > 1 && word.starts_with('v') && word[1..].bytes().all(|b| b.is_ascii_digit()) {
            let next = seen.len();
            word = format!("v{}", seen.entry(word.clone()).or_insert(next));
        }
        out.push_str(&word);
        out.push(c);
        word.clear();
    }
    out
}

/// Panics with the first difference of two canonical expansions and its surroundings.
#[cfg(test)]
pub fn assert_same_code(a: &str, b: &str) {
    if let Some(at) = a.chars().zip(b.chars()).position(|(x, y)| x != y).or((a.len() != b.len()).then_some(a.len().min(b.len()))) {
        let around = |s: &str| s.chars().skip(at.saturating_sub(150)).take(300).collect::<String>();
        panic!("the expansions differ at character {at}:\nfirst:  …{}…\nsecond: …{}…", around(a), around(b));
    }
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
        let text =
            format!("// Generated from slider_crank.rs by `MBD_BLESS=1 cargo test -p mbd-macros snapshot`. Do not edit.\n{formatted}");
        let path = dir.join("slider_crank.expanded.rs");
        if std::env::var_os("MBD_BLESS").is_some() {
            std::fs::write(&path, &text).expect("write the snapshot");
        }
        let committed = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(committed == text, "{} is out of date: rerun with MBD_BLESS=1 and review the diff", path.display());
    }
}
