//! `drive J.stroke = f;` — drives the stroke s = z_iᵀ (r^P_j − r^P_i) of a spatial
//! translational or cylindrical joint J as f(t): row `stroke`, s − f.

use serde_json::{json, Value};

use super::Marker;
use crate::elements::Joint;
use crate::frames::{Builder, Row, RowUnit};
use crate::json::Ctx;
use crate::model::{BodyRef, MExpr};

#[derive(Debug)]
pub struct DriveStroke {
    /// The driven joint's name and markers.
    pub joint: String,
    pub i: Marker,
    pub j: Marker,
    pub f: MExpr,
}

impl Joint for DriveStroke {
    fn kind(&self) -> &'static str {
        "drive_stroke"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (Some(self.i.loc.body), Some(self.j.loc.body))
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        let s = b.joint_stroke(&self.i, &self.j);
        let f = b.expr(&self.f);
        vec![Row { name: "stroke", value: b.g.sub(s, f), unit: RowUnit::Length }]
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"joint": self.joint, "f": cx.expr(&self.f)})
    }
}
