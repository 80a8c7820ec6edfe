//! `translational_spring`, `translational_damper`, `force_actuator` J { k, length, c, force } — a
//! translational spring-damper-actuator on the stroke s = z_iᵀ (r^P_j − r^P_i) of a spatial
//! translational or cylindrical joint J (labelled): force f = k (s − length) + c ṡ + force
//! resisting s (a positive `force` pulls the markers together along the axis, as a spring's
//! tension does); Q = −f (∂ṡ/∂v)ᵀ, V = ½ k (s − length)².

use serde_json::{json, Value};

use super::{Force, Generalized, Resolved};
use crate::elements::spatial::Marker;
use crate::frames::Builder;
use crate::json::Ctx;
use crate::model::{MExpr, Resolver, Scope, SpatialJoints};
use crate::parse::AxisForceDef;

/// The keywords of this element.
pub const KINDS: &[&str] = &["translational_spring", "translational_damper", "force_actuator"];

#[derive(Debug)]
pub struct Stroke {
    /// The joint's name and markers.
    pub joint: String,
    pub i: Marker,
    pub j: Marker,
    pub k: Option<MExpr>,
    pub length: MExpr,
    pub c: Option<MExpr>,
    pub force: Option<MExpr>,
}

pub fn resolve<'a>(r: &mut Resolver, f: &'a AxisForceDef, joints: &SpatialJoints) -> Option<Resolved<'a>> {
    let kind = f.kind.to_string();
    if r.space != crate::model::Space::Spatial {
        r.errors.push(
            f.kind.span(),
            format!("a {kind} acts on a spatial joint's stroke: expected `spatial;` in the mechanism, found a planar one; in the plane, use `spring Pi ~ Pj {{ ... }}` between two points on the axis"),
        );
        return None;
    }
    if let Some(j) = &f.j {
        r.errors.push(
            j.span(),
            format!("a {kind} acts on a joint's stroke: expected `{kind} slide {{ ... }};` with `translational slide: ...`, found `~ {j}`"),
        );
        return None;
    }
    let (i, j) = match joints.get(&f.i.to_string()) {
        Some((jk, mi, mj)) if matches!(*jk, "translational" | "cylindrical") => (mi.clone(), mj.clone()),
        Some((jk, ..)) => {
            r.errors.push(
                f.i.span(),
                format!("a {kind} acts on a joint's stroke: expected a translational or cylindrical joint, found `{}`, a {jk} joint", f.i),
            );
            return None;
        }
        None => {
            r.errors.push(f.i.span(), format!("unknown joint: expected a labelled translational or cylindrical joint, found `{}`; a {kind} acts on one, `{kind} slide {{ ... }};`", f.i));
            return None;
        }
    };
    let known = [("k", Scope::Params), ("length", Scope::Params), ("c", Scope::Params), ("force", Scope::Force)];
    let mut o = super::options(r, &f.kind, &f.options, &known)?;
    let required = match kind.as_str() {
        "translational_spring" => ("k", "a translational spring needs its stiffness: expected `k` (N/m), found none; e.g. `{ k: 2.0e4 }`"),
        "translational_damper" => {
            ("c", "a translational damper needs its damping coefficient: expected `c` (N·s/m), found none; e.g. `{ c: 50.0 }`")
        }
        _ => ("force", "a force actuator needs its force: expected `force` (N), found none; e.g. `{ force: 100.0 * sin(t) }`"),
    };
    if !o.contains_key(required.0) {
        r.errors.push(f.kind.span(), required.1);
        return None;
    }
    let (k, length, c, force) = (o.remove("k"), o.remove("length").unwrap_or(MExpr::Num(0.0)), o.remove("c"), o.remove("force"));
    let element = Stroke { joint: f.i.to_string(), i, j, k, length, c, force };
    Some((f.label.as_ref(), format!("{kind} {}", f.i), f.kind.span(), Box::new(element)))
}

impl Force for Stroke {
    fn effect(&self) -> &'static str {
        "translational spring-damper-actuator"
    }
    fn kind(&self) -> &'static str {
        "translational"
    }
    fn apply(&self, b: &mut Builder, out: &mut Generalized) {
        let s = b.joint_stroke(&self.i, &self.j);
        let sdot = b.rate(s);
        let (force, spring) = b.law(s, sdot, &self.k, &self.length, &self.c, &self.force);
        b.add_along(&mut out.h, s, force);
        out.potential = b.add_spring_energy(out.potential, spring);
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({
            "joint": self.joint,
            "k": cx.opt(&self.k), "length": cx.expr(&self.length), "c": cx.opt(&self.c), "force": cx.opt(&self.force)
        })
    }
}
