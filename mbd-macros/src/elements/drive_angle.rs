//! `drive angle(i, j) = f(t);` — a relative-angle driver (Nikravesh 7.4).
//!
//! Row `angle`: φ_j − φ_i − f(t).

use serde_json::{json, Value};
use syn::Ident;

use super::{Driven, Joint, Resolved};
use crate::frames::{Builder, Row, RowUnit};
use crate::json::Ctx;
use crate::model::{BodyRef, MExpr, Resolver};
use crate::parse::DriveDef;

#[derive(Debug)]
pub struct DriveAngle {
    pub i: BodyRef,
    pub j: BodyRef,
    pub f: MExpr,
}

pub fn resolve<'a>(r: &mut Resolver, d: &'a DriveDef, i: &Ident, j: &Ident, f: Option<MExpr>, driven: &mut Driven) -> Option<Resolved<'a>> {
    let (bi, bj) = (r.body(i), r.body(j));
    match (bi, bj, f) {
        (Some(bi), Some(bj), _) if bi == bj => {
            r.errors.push(j.span(), format!("a relative angle needs two different bodies: expected a second body, found `{j}` again"));
            None
        }
        (Some(bi), Some(bj), f) => {
            let key = if format!("{bi:?}") < format!("{bj:?}") { (bi, bj) } else { (bj, bi) };
            if !driven.angles.insert(key) {
                r.errors.push(
                    i.span(),
                    format!("the angle between `{i}` and `{j}` is driven twice: expected one driver, found a second one; remove one"),
                );
                return None;
            }
            let f = f?;
            Some((
                d.label.as_ref(),
                format!("drive angle {i}~{j}"),
                d.keyword.span(),
                Box::new(DriveAngle { i: bi, j: bj, f }) as Box<dyn Joint>,
                Vec::new(),
            ))
        }
        _ => None,
    }
}

impl Joint for DriveAngle {
    fn kind(&self) -> &'static str {
        "drive_angle"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (Some(self.i), Some(self.j))
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        let rel = b.relative_angle(self.i, self.j);
        let f = b.expr(&self.f);
        vec![Row { name: "angle", value: b.g.sub(rel, f), unit: RowUnit::Angle }]
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"i": cx.body(self.i), "j": cx.body(self.j), "f": cx.expr(&self.f)})
    }
}
