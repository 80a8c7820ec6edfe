//! `drive distance(a.P, b.Q) = f(t);` — a relative-distance driver (Nikravesh 7.4).
//!
//! Row `distance`: (dᵀd − f(t)²)/(2 f(t)), d = r^P_j − r^P_i: |d| − f to first order, so its
//! multiplier is the driver's force in N. f must not reach 0.

use serde_json::{json, Value};
use syn::Ident;

use super::{Joint, Resolved};
use crate::frames::{Builder, Row, RowUnit};
use crate::json::Ctx;
use crate::model::{BodyRef, Loc, MExpr, Resolver};
use crate::parse::{DriveDef, PointRef};

#[derive(Debug)]
pub struct DriveDistance {
    pub i: Loc,
    pub j: Loc,
    pub f: MExpr,
}

pub fn resolve<'a>(
    r: &mut Resolver,
    d: &'a DriveDef,
    i: &(Ident, PointRef),
    j: &(Ident, PointRef),
    f: Option<MExpr>,
) -> Option<Resolved<'a>> {
    let li = r.loc(&i.0, &i.1);
    let lj = r.loc(&j.0, &j.1);
    match (li, lj, f) {
        (Some(li), Some(lj), _) if li.body == lj.body => {
            r.errors
                .push(j.0.span(), "a distance driver needs points on two different bodies: expected a second body, found the first again");
            None
        }
        (Some(_), Some(_), Some(f)) if f.is_zero_in_time() => {
            r.errors.at_expr(&d.f, "a distance driver to length 0 has no direction to pull along: expected a length that stays positive, found 0; drive the points' coordinates, or join them with a `revolute`");
            None
        }
        (Some(li), Some(lj), Some(f)) => {
            let name = format!("drive distance {}~{}", i.0, j.0);
            Some((d.label.as_ref(), name, d.keyword.span(), Box::new(DriveDistance { i: li, j: lj, f }) as Box<dyn Joint>, Vec::new()))
        }
        _ => None,
    }
}

impl Joint for DriveDistance {
    fn kind(&self) -> &'static str {
        "drive_distance"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (Some(self.i.body), Some(self.j.body))
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        let f = b.expr(&self.f);
        vec![Row { name: "distance", value: b.distance_between(&self.i, &self.j, f), unit: RowUnit::Length }]
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"i": cx.loc(&self.i), "j": cx.loc(&self.j), "f": cx.expr(&self.f)})
    }
}
