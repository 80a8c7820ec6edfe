//! `torque body = τ;` — a torque on a body (N·m, counter-clockwise positive), any expression of
//! q, v, t and parameters: Q = τ (∂ω/∂v)ᵀ.

use serde_json::{json, Value};

use super::{Force, Generalized, Resolved};
use crate::frames::Builder;
use crate::json::Ctx;
use crate::model::{BodyRef, MExpr, Resolver, Scope};
use crate::parse::TorqueDef;

#[derive(Debug)]
pub struct Torque {
    pub body: usize,
    pub torque: MExpr,
}

pub fn resolve<'a>(r: &mut Resolver, tq: &'a TorqueDef) -> Option<Resolved<'a>> {
    let body = r.body(&tq.body);
    let torque = r.expr(&tq.value, Scope::Force);
    match (body, torque) {
        (Some(BodyRef::Ground), _) => {
            r.errors.push(tq.body.span(), "a torque on the ground does nothing: apply it to a moving body");
            None
        }
        (Some(BodyRef::Body(k)), Some(torque)) => {
            Some((tq.label.as_ref(), format!("torque on {}", tq.body), tq.keyword.span(), Box::new(Torque { body: k, torque })))
        }
        _ => None,
    }
}

impl Force for Torque {
    fn effect(&self) -> &'static str {
        "applied torque"
    }
    fn kind(&self) -> &'static str {
        "torque"
    }
    fn apply(&self, b: &mut Builder, out: &mut Generalized) {
        let tau = b.expr(&self.torque);
        b.add_to_angular_velocity(&mut out.h, self.body, tau);
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"body": cx.body(BodyRef::Body(self.body)), "torque": cx.expr(&self.torque)})
    }
}
