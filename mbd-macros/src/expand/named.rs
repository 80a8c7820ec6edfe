//! Named access: a constant per body and per labelled joint, an accessor per named point, and
//! each body's mass and inertia, read from the parameters.

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use crate::emit::{real, usize_lit, vector_outputs, Emitter, Output};
use crate::formulation::Formulation;
use crate::model::Model;

/// Named access: a constant per body (`Name::CRANK`, a `PlanarBody` or `SpatialBody`; a
/// `TreeBody` in joint coordinates) and per
/// labelled joint, driver or constraint (`Name::MOTOR`, its index into `JOINTS`), and an
/// accessor per named point on a body (`crank_a()`, its coordinates evaluated from the
/// parameters).
pub(super) fn named_items(m: &Model, f: &Formulation, e: &Emitter) -> TokenStream {
    let real = real(m.scalar);
    let (nq, nv) = (usize_lit(f.nq), usize_lit(f.nv));
    let (body_type, point_type) = match (m.space, &m.tree) {
        // in joint coordinates a body's pose is no entry of q: read through `mbd::BodyFrames`
        (_, Some(_)) => (quote!(::mbd::TreeBody), quote!(::mbd::TreePoint<'_, Self, #real, #nq, #nv>)),
        (crate::model::Space::Planar, None) => (quote!(::mbd::PlanarBody<#nq>), quote!(::mbd::PlanarPoint<#real, #nq>)),
        (crate::model::Space::Spatial, None) => (quote!(::mbd::SpatialBody<#nq, #nv>), quote!(::mbd::SpatialPoint<#real, #nq, #nv>)),
    };
    let bodies = m.bodies.iter().enumerate().map(|(k, b)| {
        let (name, constant) = (b.name.to_string(), format_ident!("{}", crate::model::constant_name(&b.name.to_string())));
        let (doc, k) = (format!(" Body `{name}`: its coordinates, velocities and points."), usize_lit(k));
        quote!(#[doc = #doc] pub const #constant: #body_type = <#body_type>::new(#k, #name);)
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
        let point = if m.tree.is_some() {
            quote!(::mbd::TreePoint { mechanism: self, body: Self::#constant, local: [local[0], local[1], local.get(2).copied().unwrap_or(#zero)] })
        } else {
            quote!(Self::#constant.point(local))
        };
        quote! {
            #[doc = #doc]
            #[allow(unused_parens)]
            pub fn #accessor(&self) -> #point_type {
                let mut local = [#zero; #dim];
                #local
                #point
            }
        }
    });
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
/// parameter-dependent mass reads the parameters' current values. In joint coordinates the body
/// is a `TreeBody`.
fn body_inertia(m: &Model, f: &Formulation, e: &Emitter) -> TokenStream {
    let real = real(m.scalar);
    let nb = usize_lit(m.bodies.len());
    let zero = e.literal(0.0);
    let (nq, nv) = (usize_lit(f.nq), usize_lit(f.nv));
    let body_type = match (m.space, &m.tree) {
        (_, Some(_)) => quote!(::mbd::TreeBody),
        (crate::model::Space::Planar, None) => quote!(::mbd::PlanarBody<#nq>),
        (crate::model::Space::Spatial, None) => quote!(::mbd::SpatialBody<#nq, #nv>),
    };
    let masses: Vec<Output> = f
        .bodies
        .iter()
        .enumerate()
        .map(|(k, body)| {
            let kl = usize_lit(k);
            Output { target: quote!(out[#kl]), node: body.mass }
        })
        .collect();
    let (mass_body, _) = e.body(&masses);
    // out[k][r][c] = J_rc of body k (1×1 in the plane)
    let mut js: Vec<Output> = Vec::new();
    for (k, body) in f.bodies.iter().enumerate() {
        for (r, row) in body.inertia.iter().enumerate() {
            for (c, &node) in row.iter().enumerate() {
                let (kl, rl, cl) = (usize_lit(k), usize_lit(r), usize_lit(c));
                js.push(Output { target: quote!(out[#kl][#rl][#cl]), node });
            }
        }
    }
    let (j_body, _) = e.body(&js);
    let inertia_of = match m.space {
        crate::model::Space::Planar => quote! {
            /// The moment of inertia J (kg·m²) of a body (`Name::BODY`) about its centre of mass.
            #[allow(unused_parens, clippy::approx_constant)]
            pub fn inertia_of(&self, body: #body_type) -> #real {
                let mut out = [[[#zero; 1]; 1]; #nb];
                #j_body
                out[body.index][0][0]
            }
        },
        crate::model::Space::Spatial => quote! {
            /// The inertia tensor J′ (kg·m²) of a body (`Name::BODY`) about its centre of mass,
            /// in body-frame components.
            #[allow(unused_parens, clippy::approx_constant)]
            pub fn inertia_of(&self, body: #body_type) -> ::mbd::nalgebra::Matrix3<#real> {
                let mut out = [[[#zero; 3]; 3]; #nb];
                #j_body
                ::mbd::nalgebra::Matrix3::from_fn(|r, c| out[body.index][r][c])
            }
        },
    };
    quote! {
        /// The mass (kg) of a body (`Name::BODY`).
        #[allow(unused_parens, clippy::approx_constant)]
        pub fn mass_of(&self, body: #body_type) -> #real {
            let mut out = [#zero; #nb];
            #mass_body
            out[body.index]
        }
        #inertia_of
    }
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
