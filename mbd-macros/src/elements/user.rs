//! `constraint [name:] lhs = rhs;` — a user constraint on coordinates, t and parameters.
//!
//! Row `user`: lhs − rhs.

use serde_json::{json, Value};

use super::{Joint, Resolved};
use crate::frames::{Builder, Row, RowUnit};
use crate::json::Ctx;
use crate::model::{BodyRef, MBin, MExpr, Resolver, Scope};
use crate::parse::ConstraintDef;

#[derive(Debug)]
pub struct User {
    pub expr: MExpr,
}

/// `index` is the statement's position, which names an unlabelled constraint.
pub fn resolve<'a>(r: &mut Resolver, c: &'a ConstraintDef, index: usize) -> Option<Resolved<'a>> {
    let lhs = r.expr(&c.lhs, Scope::State);
    let rhs = r.expr(&c.rhs, Scope::State);
    let (l, rh) = (lhs?, rhs?);
    let expr = match rh.constant_value() {
        Some(0.0) => l,
        _ => MExpr::Bin(MBin::Sub, Box::new(l), Box::new(rh)),
    };
    Some((c.label.as_ref(), format!("constraint {index}"), c.keyword.span(), Box::new(User { expr }) as Box<dyn Joint>, Vec::new()))
}

impl Joint for User {
    fn kind(&self) -> &'static str {
        "constraint"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (None, None)
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        vec![Row { name: "user", value: b.expr(&self.expr), unit: RowUnit::Unknown }]
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"expr": cx.expr(&self.expr)})
    }
}
