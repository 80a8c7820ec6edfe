//! `force body.P = [fx, fy];` and `local_force body.P = [fx, fy];` (three components in space) — a force at a point, in
//! global or body components (N), any expression of q, v, t and parameters:
//! Q = (∂ṙ^P/∂v)ᵀ F, F = A F′ for body components.

use serde_json::{json, Value};

use super::{Force, Generalized, Resolved};
use crate::frames::Builder;
use crate::json::Ctx;
use crate::model::{BodyRef, Components, Loc, Resolver, Scope};
use crate::parse::ForceDef;

#[derive(Debug)]
pub struct Applied {
    pub at: Loc,
    pub force: Components,
    pub local: bool,
}

pub fn resolve<'a>(r: &mut Resolver, f: &'a ForceDef) -> Option<Resolved<'a>> {
    let at = r.loc(&f.body, &f.point);
    let shape = r.shape(["fx", "fy", "fz"]);
    let value = r.components(&f.value, Scope::Force, &format!("a force `{shape}` (N)"));
    match (at, value) {
        (Some(at), _) if at.body == BodyRef::Ground => {
            r.errors.push(f.body.span(), "a force on the ground does nothing: expected a moving body, found `ground`");
            None
        }
        (Some(at), Some(force)) => {
            let local = f.kind == "local_force";
            Some((f.label.as_ref(), format!("{} on {}", f.kind, f.body), f.kind.span(), Box::new(Applied { at, force, local })))
        }
        _ => None,
    }
}

impl Force for Applied {
    fn effect(&self) -> &'static str {
        "applied force"
    }
    fn kind(&self) -> &'static str {
        if self.local {
            "local_force"
        } else {
            "force"
        }
    }
    fn apply(&self, b: &mut Builder, out: &mut Generalized) {
        let mut f: Vec<_> = self.force.iter().map(|e| b.expr(e)).collect();
        if self.local {
            f = b.rotate_n(self.at.body, f);
        }
        let p = b.point_n(&self.at);
        // h_k += Fᵀ ∂ṙ_P/∂v_k
        for a in 0..p.len() {
            for (k, dp) in b.gradient(p[a]) {
                let w = b.g.mul(f[a], dp);
                out.h[k] = b.g.add(out.h[k], w);
            }
        }
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"at": cx.loc(&self.at), "force": cx.list(&self.force)})
    }
}
