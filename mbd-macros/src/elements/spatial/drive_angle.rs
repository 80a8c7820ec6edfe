//! `drive J.angle = f;` — drives the angle θ of a spatial revolute or cylindrical joint J (the
//! turn of marker j about z_i from x_i) as f(t): row `angle`,
//! (y_iᵀ x_j) cos f − (x_iᵀ x_j) sin f = sin(θ − f), whose Jacobian at its root is that of θ − f.

use serde_json::{json, Value};

use super::Marker;
use crate::elements::Joint;
use crate::frames::{Builder, Row, RowUnit};
use crate::json::Ctx;
use crate::model::{BodyRef, MExpr};
use crate::sym::Func;

#[derive(Debug)]
pub struct DriveAngle {
    /// The driven joint's name and markers.
    pub joint: String,
    pub i: Marker,
    pub j: Marker,
    pub f: MExpr,
}

impl Joint for DriveAngle {
    fn kind(&self) -> &'static str {
        "drive_angle"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (Some(self.i.loc.body), Some(self.j.loc.body))
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        let (fi, fj) = (b.frame(&self.i), b.frame(&self.j));
        let s = b.dot(&fi.y, &fj.x);
        let c = b.dot(&fi.x, &fj.x);
        let f = b.expr(&self.f);
        let (sf, cf) = (b.g.call(Func::Sin, f), b.g.call(Func::Cos, f));
        let a = b.g.mul(s, cf);
        let bb = b.g.mul(c, sf);
        vec![Row { name: "angle", value: b.g.sub(a, bb), unit: RowUnit::Angle }]
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"joint": self.joint, "f": cx.expr(&self.f)})
    }
}
