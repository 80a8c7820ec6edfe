//! `rotational_spring`, `rotational_damper`, `torque_actuator` i ~ j { k, angle, c, torque } — a
//! rotational spring-damper-actuator (Nikravesh 4.2.2) on θ = φ_j − φ_i: torque
//! τ = k (θ − angle) + c θ̇ + torque resisting θ; Q = −τ (∂θ̇/∂v)ᵀ, V = ½ k (θ − angle)².

use serde_json::{json, Value};

use super::{Force, Generalized, Resolved};
use crate::frames::Builder;
use crate::json::Ctx;
use crate::model::{BodyRef, MExpr, Resolver, Scope};
use crate::parse::RotationalDef;

#[derive(Debug)]
pub struct Rotational {
    pub i: BodyRef,
    pub j: BodyRef,
    pub k: Option<MExpr>,
    pub angle: MExpr,
    pub c: Option<MExpr>,
    pub torque: Option<MExpr>,
}

pub fn resolve<'a>(r: &mut Resolver, f: &'a RotationalDef) -> Option<Resolved<'a>> {
    let kind = f.kind.to_string();
    let bi = r.body(&f.i);
    let bj = r.body(&f.j);
    let known = [("k", Scope::Params), ("angle", Scope::Params), ("c", Scope::Params), ("torque", Scope::Force)];
    let mut o = super::options(r, &f.kind, &f.options, &known)?;
    let (bi, bj) = (bi?, bj?);
    if bi == bj {
        r.errors.push(f.j.span(), format!("a {kind} of body `{}` to itself does nothing: it connects two different bodies", f.j));
        return None;
    }
    let required = match kind.as_str() {
        "rotational_spring" => ("k", "a rotational spring needs its stiffness: `{ k: 50.0 }` (N·m/rad)"),
        "rotational_damper" => ("c", "a rotational damper needs its damping coefficient: `{ c: 0.5 }` (N·m·s/rad)"),
        _ => ("torque", "a torque actuator needs its torque: `{ torque: 2.0 * sin(t) }` (N·m)"),
    };
    if !o.contains_key(required.0) {
        r.errors.push(f.kind.span(), required.1);
        return None;
    }
    let name = format!("{kind} {}~{}", f.i, f.j);
    let element = Rotational {
        i: bi,
        j: bj,
        k: o.remove("k"),
        angle: o.remove("angle").unwrap_or(MExpr::Num(0.0)),
        c: o.remove("c"),
        torque: o.remove("torque"),
    };
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
