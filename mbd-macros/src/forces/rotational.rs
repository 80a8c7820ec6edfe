//! `rotational_spring`, `rotational_damper`, `torque_actuator` i ~ j { k, angle, c, torque } — a
//! rotational spring-damper-actuator (Nikravesh 4.2.2) on θ = φ_j − φ_i: torque
//! τ = k (θ − angle) + c θ̇ + torque resisting θ; Q = −τ (∂θ̇/∂v)ᵀ, V = ½ k (θ − angle)².
//! In space, `rotational_spring J { ... }` acts on the angle θ_J of the revolute or cylindrical
//! joint J (labelled), θ̇_J its total time derivative along q̇ = B v.

use serde_json::{json, Value};

use super::{Force, Generalized, Resolved};
use crate::elements::spatial::Marker;
use crate::frames::Builder;
use crate::json::Ctx;
use crate::model::{BodyRef, MExpr, Resolver, Scope, SpatialJoints};
use crate::parse::AxisForceDef;

#[derive(Debug)]
pub struct Rotational {
    pub i: BodyRef,
    pub j: BodyRef,
    pub k: Option<MExpr>,
    pub angle: MExpr,
    pub c: Option<MExpr>,
    pub torque: Option<MExpr>,
}

/// A rotational spring-damper-actuator on a spatial revolute or cylindrical joint's angle.
#[derive(Debug)]
pub struct JointRotational {
    /// The joint's name and markers.
    pub joint: String,
    pub i: Marker,
    pub j: Marker,
    pub k: Option<MExpr>,
    pub angle: MExpr,
    pub c: Option<MExpr>,
    pub torque: Option<MExpr>,
}

pub fn resolve<'a>(r: &mut Resolver, f: &'a AxisForceDef, joints: &SpatialJoints) -> Option<Resolved<'a>> {
    let kind = f.kind.to_string();
    let known = [("k", Scope::Params), ("angle", Scope::Params), ("c", Scope::Params), ("torque", Scope::Force)];
    let spatial = r.space == crate::model::Space::Spatial;
    let (sides, on_joint) = match (&f.j, spatial) {
        (Some(j), false) => {
            let bi = r.body(&f.i);
            let bj = r.body(j);
            (Some((bi, bj, j)), None)
        }
        (None, true) => match joints.get(&f.i.to_string()) {
            Some((jk, mi, mj)) if matches!(*jk, "revolute" | "cylindrical") => (None, Some((mi.clone(), mj.clone()))),
            Some((jk, ..)) => {
                r.errors.push(
                    f.i.span(),
                    format!("a {kind} acts on a joint's angle: expected a revolute or cylindrical joint, found `{}`, a {jk} joint", f.i),
                );
                return None;
            }
            None => {
                r.errors.push(f.i.span(), format!("unknown joint: expected a labelled revolute or cylindrical joint, found `{}`; a {kind} in space acts on one, `{kind} hinge {{ ... }};`", f.i));
                return None;
            }
        },
        (Some(j), true) => {
            r.errors
                .push(j.span(), format!("in space a {kind} acts on a joint's angle: `{kind} hinge {{ ... }};` with `revolute hinge: ...`"));
            return None;
        }
        (None, false) => {
            r.errors.push(f.i.span(), format!("a {kind} connects two bodies: expected `{kind} {} ~ other {{ ... }};`, found no `~`", f.i));
            return None;
        }
    };
    let mut o = super::options(r, &f.kind, &f.options, &known)?;
    let required = match kind.as_str() {
        "rotational_spring" => ("k", "a rotational spring needs its stiffness: expected `k` (N·m/rad), found none; e.g. `{ k: 50.0 }`"),
        "rotational_damper" => ("c", "a rotational damper needs its damping coefficient: `{ c: 0.5 }` (N·m·s/rad)"),
        _ => ("torque", "a torque actuator needs its torque: `{ torque: 2.0 * sin(t) }` (N·m)"),
    };
    if !o.contains_key(required.0) {
        r.errors.push(f.kind.span(), required.1);
        return None;
    }
    let (k, angle, c, torque) = (o.remove("k"), o.remove("angle").unwrap_or(MExpr::Num(0.0)), o.remove("c"), o.remove("torque"));
    if let Some((i, j)) = on_joint {
        let element = JointRotational { joint: f.i.to_string(), i, j, k, angle, c, torque };
        return Some((f.label.as_ref(), format!("{kind} {}", f.i), f.kind.span(), Box::new(element)));
    }
    let (bi, bj, j) = sides?;
    let (bi, bj) = (bi?, bj?);
    if bi == bj {
        r.errors.push(j.span(), format!("a {kind} of body `{j}` to itself does nothing: expected a second body, found `{j}` again"));
        return None;
    }
    let name = format!("{kind} {}~{}", f.i, j);
    let element = Rotational { i: bi, j: bj, k, angle, c, torque };
    Some((f.label.as_ref(), name, f.kind.span(), Box::new(element)))
}

impl Force for Rotational {
    fn effect(&self) -> &'static str {
        "rotational spring-damper-actuator"
    }
    fn kind(&self) -> &'static str {
        "rotational"
    }
    fn apply(&self, b: &mut Builder, out: &mut Generalized) {
        let theta = b.relative_angle(self.i, self.j);
        let thetadot = b.rate(theta);
        let (tau, spring) = b.law(theta, thetadot, &self.k, &self.angle, &self.c, &self.torque);
        b.add_along(&mut out.h, theta, tau);
        out.potential = b.add_spring_energy(out.potential, spring);
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({
            "i": cx.body(self.i), "j": cx.body(self.j),
            "k": cx.opt(&self.k), "angle": cx.expr(&self.angle), "c": cx.opt(&self.c), "torque": cx.opt(&self.torque)
        })
    }
}

impl Force for JointRotational {
    fn effect(&self) -> &'static str {
        "rotational spring-damper-actuator"
    }
    fn kind(&self) -> &'static str {
        "rotational"
    }
    fn apply(&self, b: &mut Builder, out: &mut Generalized) {
        let theta = b.joint_angle(&self.i, &self.j);
        let thetadot = b.rate(theta);
        let (tau, spring) = b.law(theta, thetadot, &self.k, &self.angle, &self.c, &self.torque);
        b.add_along(&mut out.h, theta, tau);
        out.potential = b.add_spring_energy(out.potential, spring);
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({
            "joint": self.joint,
            "k": cx.opt(&self.k), "angle": cx.expr(&self.angle), "c": cx.opt(&self.c), "torque": cx.opt(&self.torque)
        })
    }
}
