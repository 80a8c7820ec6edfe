//! `torque body = τ;` — a torque on a planar body (N·m, counter-clockwise positive):
//! Q = τ (∂φ̇/∂v)ᵀ. In space, `torque body = [tx, ty, tz];` (global components) and
//! `local_torque body = [tx, ty, tz];` (body frame): Q = [0; Aᵀ T] and [0; T′] at the body's ω′.
//! Any expression of q, v, t and parameters.

use serde_json::{json, Value};

use super::{Force, Generalized, Resolved};
use crate::frames::Builder;
use crate::json::Ctx;
use crate::model::{BodyRef, MExpr, Resolver, Scope, Space};
use crate::parse::{TorqueDef, Value as FieldValue};

#[derive(Debug)]
pub struct Torque {
    pub body: usize,
    pub torque: MExpr,
}

/// A torque on a spatial body, global or body-frame components.
#[derive(Debug)]
pub struct SpatialTorque {
    pub body: usize,
    pub torque: Vec<MExpr>,
    pub local: bool,
}

pub fn resolve<'a>(r: &mut Resolver, tq: &'a TorqueDef) -> Option<Resolved<'a>> {
    let body = r.body(&tq.body);
    let spatial = r.space == Space::Spatial;
    let torque = match (&tq.value, spatial) {
        (FieldValue::Expr(e), false) => r.expr(e, Scope::Force).map(|t| vec![t]),
        (FieldValue::List(v), true) => r.components(v, Scope::Force, "a torque `[tx, ty, tz]` (N·m)"),
        (FieldValue::Expr(e), true) => {
            r.errors.at_expr(e, "a torque in space has three components: expected `[tx, ty, tz]` (N·m), found a number");
            None
        }
        (FieldValue::List(v), false) => {
            r.errors.push(v.span, "a planar torque is a number: expected a number (N·m, counter-clockwise positive), found a list");
            None
        }
    };
    if tq.keyword == "local_torque" && !spatial {
        r.errors.push(tq.keyword.span(), "`local_torque` is for spatial mechanisms: expected `spatial;` in the mechanism, found a planar one; a planar torque is `torque body = τ;`");
        return None;
    }
    match (body, torque) {
        (Some(BodyRef::Ground), _) => {
            r.errors.push(tq.body.span(), "a torque on the ground does nothing: expected a moving body, found `ground`");
            None
        }
        (Some(BodyRef::Body(k)), Some(mut torque)) => {
            let name = format!("{} on {}", tq.keyword, tq.body);
            let element: Box<dyn Force> = if spatial {
                Box::new(SpatialTorque { body: k, torque, local: tq.keyword == "local_torque" })
            } else {
                Box::new(Torque { body: k, torque: torque.remove(0) })
            };
            Some((tq.label.as_ref(), name, tq.keyword.span(), element))
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

impl Force for SpatialTorque {
    fn effect(&self) -> &'static str {
        "applied torque"
    }
    fn kind(&self) -> &'static str {
        if self.local {
            "local_torque"
        } else {
            "torque"
        }
    }
    fn apply(&self, b: &mut Builder, out: &mut Generalized) {
        let t = [0, 1, 2].map(|k| b.expr(&self.torque[k]));
        let local = if self.local { t } else { b.unrotate3(BodyRef::Body(self.body), t) };
        b.add_to_body_angular_velocity(&mut out.h, self.body, local);
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"body": cx.body(BodyRef::Body(self.body)), "torque": cx.list(&self.torque)})
    }
}
