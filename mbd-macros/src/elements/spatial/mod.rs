//! Spatial joints and drivers (`spatial;`, docs/formulation.md "Spatial bodies"): one file per
//! kind, each written against marker frames (Wallrapp 2.5) — a point s′ on a body with, where the
//! kind needs them, an axis a′ and a reference direction b′ — never against coordinates.
//!
//! The kinds with the shape `keyword Pi [along ai [reference bi]] ~ Pj [along aj [reference bj]]
//! { options };` are registered in [`JOINTS`]. Drivers of a joint's angle or stroke
//! (`drive J.angle = f;`, `drive J.stroke = f;`) have their own files.

use std::collections::HashMap;

use serde_json::{json, Value};
use syn::Ident;

use super::{Joint, Mistake, Named, Resolved};
use crate::forces::friction;
use crate::frames::Builder;
use crate::json::Ctx;
use crate::model::{BodyRef, Components, Loc, MExpr, Resolver};
use crate::parse;
use crate::sym::Id;

pub mod cylindrical;
pub mod distance;
pub mod drive_angle;
pub mod drive_stroke;
pub mod planar;
pub mod point_on_line;
pub mod point_on_plane;
pub mod revolute;
pub mod rigid;
pub mod spherical;
pub mod translational;
pub mod universal;

/// A marker: a point on a body and, where its joint needs a direction, a unit triad from the
/// axis a′ (its z) and the reference b′ (its x after Gram–Schmidt). Body-frame components as
/// written; `axis` and `reference` are empty where the kind takes no axis.
#[derive(Clone, Debug)]
pub struct Marker {
    pub loc: Loc,
    pub axis: Components,
    pub reference: Components,
}

/// A marker frame in global components.
pub struct Frame {
    pub origin: [Id; 3],
    pub x: [Id; 3],
    pub y: [Id; 3],
    pub z: [Id; 3],
}

impl Builder<'_> {
    /// The global frame of a marker with an axis.
    pub fn frame(&mut self, m: &Marker) -> Frame {
        let origin = self.point3(&m.loc);
        let [x, y, z] = self.triad(m.loc.body, &m.axis, &m.reference);
        Frame { origin, x, y, z }
    }

    /// r^P_j − r^P_i.
    pub fn separation(&mut self, i: &Frame, j: &Frame) -> [Id; 3] {
        std::array::from_fn(|k| self.g.sub(j.origin[k], i.origin[k]))
    }

    /// θ_J = atan2(y_iᵀ x_j, x_iᵀ x_j): the turn of marker j about z_i from x_i (revolute,
    /// cylindrical).
    pub fn joint_angle(&mut self, i: &Marker, j: &Marker) -> Id {
        let (fi, fj) = (self.frame(i), self.frame(j));
        let s = self.dot(&fi.y, &fj.x);
        let c = self.dot(&fi.x, &fj.x);
        self.g.atan2(s, c)
    }

    /// s_J = z_iᵀ (r^P_j − r^P_i): the slide of marker j along z_i (translational, cylindrical).
    pub fn joint_stroke(&mut self, i: &Marker, j: &Marker) -> Id {
        let (fi, fj) = (self.frame(i), self.frame(j));
        let d = self.separation(&fi, &fj);
        self.dot(&fi.z, &d)
    }
}

/// What a spatial two-marker statement resolved to, handed to its kind's `build`.
pub struct Parts {
    pub i: Marker,
    pub j: Marker,
    pub options: HashMap<String, MExpr>,
    pub keyword: Ident,
}

/// A spatial joint kind: its keyword, which sides take an axis (and reference), its options and
/// how it is built.
pub struct Spec {
    pub keyword: &'static str,
    pub axis_i: Axis,
    pub axis_j: Axis,
    pub options: &'static [(&'static str, Option<&'static str>)],
    pub build: fn(Parts) -> Result<Box<dyn Joint>, Mistake>,
}

/// Whether a marker of a kind has an axis.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    /// No axis (a point only).
    None,
    /// An axis the user must give.
    Required,
    /// An axis with a default: the body's z-axis, reference x.
    Default,
}

/// Every spatial kind with the two-marker shape.
pub const JOINTS: &[Spec] = &[
    spherical::SPEC,
    universal::SPEC,
    revolute::SPEC,
    cylindrical::SPEC,
    translational::SPEC,
    planar::SPEC,
    rigid::SPEC,
    point_on_line::SPEC,
    point_on_plane::SPEC,
    distance::SPEC,
];

pub fn spec(keyword: &str) -> Option<&'static Spec> {
    JOINTS.iter().find(|s| s.keyword == keyword)
}

/// The reference direction written when none is given: the coordinate axis e_k with the
/// smallest |a′_k| at the parameters' defaults (first on ties), so a′ = z gets x′ = x.
fn default_reference(axis: &[MExpr], defaults: &[f64]) -> Components {
    let values: Vec<f64> = axis.iter().map(|c| c.default_value(defaults).unwrap_or(0.0).abs()).collect();
    let k = (0..3).fold(0, |best, k| if values[k] < values[best] { k } else { best });
    (0..3).map(|c| MExpr::Num(if c == k { 1.0 } else { 0.0 })).collect()
}

/// One side's marker from its attachment.
pub fn marker(r: &mut Resolver, side: &parse::Attach, axis: Axis, kind: &str, which: &str) -> Option<Marker> {
    let loc = r.loc(&side.body, &side.point)?;
    let (axis, reference) = match (&side.along, axis) {
        (None, Axis::None) => (Vec::new(), Vec::new()),
        (None, Axis::Default) => {
            let z: Components = vec![MExpr::Num(0.0), MExpr::Num(0.0), MExpr::Num(1.0)];
            (z, vec![MExpr::Num(1.0), MExpr::Num(0.0), MExpr::Num(0.0)])
        }
        (None, Axis::Required) => {
            r.errors.push(
                side.body.span(),
                format!("a {kind} joint needs an axis on its {which} body: expected `{}.P along [x, y, z]`, found no `along`", side.body),
            );
            return None;
        }
        (Some(a), Axis::None) => {
            r.errors.push(
                a.keyword.span(),
                format!("a {kind} joint takes no axis on its {which} body: expected a point, found `along`; remove the axis"),
            );
            return None;
        }
        (Some(a), _) => {
            let axis = r.axis(loc.body, &a.axis)?;
            let reference = match &a.reference {
                Some(b) => r.axis(loc.body, b)?,
                None => default_reference(&axis, &r.defaults),
            };
            (axis, reference)
        }
    };
    Some(Marker { loc, axis, reference })
}

/// Resolves a spatial two-marker joint statement: markers, options, its kind's `build` and the
/// joint friction its options ask for.
pub fn resolve<'a>(
    r: &mut Resolver,
    j: &'a parse::JointDef,
    body_name: &dyn Fn(BodyRef) -> String,
    joint_index: usize,
) -> Option<Resolved<'a>> {
    let kind = j.kind.to_string();
    let Some(spec) = spec(&kind) else {
        let planar = super::spec(&kind).is_some();
        let why = if planar { ", a planar joint, in space" } else { "" };
        r.errors.push(j.kind.span(), format!("unknown joint kind: expected a spatial joint, found `{kind}`{why}"));
        return None;
    };
    let mi = marker(r, &j.i, spec.axis_i, &kind, "first");
    let mj = marker(r, &j.j, spec.axis_j, &kind, "second");
    let (mi, mj) = (mi?, mj?);
    if mi.loc.body == mj.loc.body {
        r.errors.push(
            j.j.body.span(),
            format!(
                "a joint of body `{0}` to itself: expected a second body, found `{0}` again; a {kind} joint connects two different bodies",
                j.j.body
            ),
        );
        return None;
    }
    let mut options = super::joint_options(r, &kind, spec.options, &j.options)?;
    let name = format!("{kind} {}~{}", body_name(mi.loc.body), body_name(mj.loc.body));
    let joint_name = j.label.as_ref().map_or_else(|| name.clone(), |l| l.to_string());
    let friction = friction_options(&mut options, &kind, (&joint_name, joint_index), &mi, &mj)
        .map_err(|msg| r.errors.push(j.kind.span(), msg))
        .ok()?;
    match (spec.build)(Parts { i: mi, j: mj, options, keyword: j.kind.clone() }) {
        Ok(joint) => Some((j.label.as_ref(), name, j.kind.span(), joint, friction)),
        Err((span, msg)) => {
            r.errors.push(span, msg);
            None
        }
    }
}

/// The friction options of a spatial revolute or translational joint: `viscous: c` and
/// `coulomb: μ` (with `radius: R` for a revolute joint, `slip_velocity: v_s`), the joint given
/// by its name and its index among the constraints.
fn friction_options(
    options: &mut HashMap<String, MExpr>,
    kind: &str,
    (name, index): (&str, usize),
    i: &Marker,
    j: &Marker,
) -> Result<Vec<Named>, String> {
    let mut out: Vec<Named> = Vec::new();
    let sliding = kind == "translational";
    if let Some(c) = options.remove("viscous") {
        let element = friction::SpatialViscous { joint: name.to_string(), i: i.clone(), j: j.clone(), c, sliding };
        out.push(("viscous friction", Box::new(element)));
    }
    let (slip, radius) = (options.remove("slip_velocity"), options.remove("radius"));
    match options.remove("coulomb") {
        Some(mu) => {
            let radius = match (sliding, radius) {
                (true, _) => None,
                (false, Some(r)) => Some(r),
                (false, None) => {
                    return Err(
                        "Coulomb friction in a revolute joint needs the pin radius: expected `radius` (m) with `coulomb`, found none; e.g. `{ coulomb: 0.1, radius: 0.01 }`".to_string()
                    )
                }
            };
            let slip = slip.unwrap_or(MExpr::Num(1e-3));
            let element = friction::SpatialCoulomb { joint: name.to_string(), index, i: i.clone(), j: j.clone(), mu, radius, slip };
            out.push(("Coulomb friction", Box::new(element)));
        }
        None if slip.is_some() || radius.is_some() => {
            return Err(format!("`radius` and `slip_velocity` describe Coulomb friction: give the {kind} joint `coulomb: μ` too"));
        }
        None => {}
    }
    Ok(out)
}

/// The JSON of a marker: point, and axis and reference where it has them.
pub fn marker_json(cx: &Ctx, m: &Marker) -> Value {
    let mut v = json!({"body": cx.body(m.loc.body), "point": cx.list(&m.loc.point)});
    if !m.axis.is_empty() {
        v["axis"] = cx.list(&m.axis);
        v["reference"] = cx.list(&m.reference);
    }
    v
}

/// `{"i": marker, "j": marker}`.
pub fn pair_json(cx: &Ctx, i: &Marker, j: &Marker) -> Value {
    json!({"i": marker_json(cx, i), "j": marker_json(cx, j)})
}

/// `drive J.angle = f;` or `drive J.stroke = f;` on a spatial joint J, by its label.
pub fn drive_joint<'a>(
    r: &mut Resolver,
    d: &'a parse::DriveDef,
    joint: &Ident,
    what: &Ident,
    f: Option<MExpr>,
    joints: &crate::model::SpatialJoints,
    driven: &mut super::Driven,
) -> Option<Resolved<'a>> {
    let Some((kind, i, j)) = joints.get(&joint.to_string()) else {
        let names: Vec<&str> = joints.keys().map(|s| s.as_str()).collect();
        let hint = parse::closest(&joint.to_string(), &names, &[]);
        r.errors.push(
            joint.span(),
            format!("unknown body or joint: expected a body or a labelled joint, found `{joint}`{hint}; drive a body's `x`, `y`, `z`, or a labelled joint's `angle` or `stroke` (`revolute {joint}: ...`)"),
        );
        return None;
    };
    let (angle, stroke) = (matches!(*kind, "revolute" | "cylindrical"), matches!(*kind, "translational" | "cylindrical"));
    let element: Box<dyn Joint> = match what.to_string().as_str() {
        "angle" if angle => Box::new(drive_angle::DriveAngle { joint: joint.to_string(), i: i.clone(), j: j.clone(), f: f? }),
        "stroke" if stroke => Box::new(drive_stroke::DriveStroke { joint: joint.to_string(), i: i.clone(), j: j.clone(), f: f? }),
        other => {
            let hint = match (angle, stroke) {
                (true, true) => "drive its `angle` or its `stroke`",
                (true, false) => "drive its `angle`",
                (false, true) => "drive its `stroke`",
                (false, false) => {
                    "drivers act on a revolute or cylindrical joint's `angle` and a translational or cylindrical joint's `stroke`"
                }
            };
            r.errors.push(what.span(), format!("`{joint}.{other}` cannot be driven: expected a joint with an `angle` or a `stroke`, found `{joint}`, a {kind} joint; {hint}"));
            return None;
        }
    };
    let key = format!("{joint}.{what}");
    if !driven.joints.insert(key.clone()) {
        r.errors.push(
            what.span(),
            format!("`{key}` is driven twice: expected one driver per joint coordinate, found a second one; remove one"),
        );
        return None;
    }
    Some((d.label.as_ref(), format!("drive {key}"), d.keyword.span(), element, Vec::new()))
}
