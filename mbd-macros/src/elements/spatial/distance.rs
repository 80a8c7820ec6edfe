//! `distance Pi ~ Pj { length: L };` — a massless spherical–spherical link: the points stay L
//! apart (row `length`: (dᵀd − L²)/(2L), whose multiplier is the link's force in N).

use serde_json::{json, Value};

use super::{marker_json, Axis, Marker, Parts, Spec};
use crate::elements::Joint;
use crate::frames::{Builder, Row, RowUnit};
use crate::json::Ctx;
use crate::model::{BodyRef, MExpr};

pub const SPEC: Spec = Spec {
    keyword: "distance",
    axis_i: Axis::None,
    axis_j: Axis::None,
    options: &[("length", Some("a link length"))],
    build: |mut p: Parts| match p.options.remove("length") {
        Some(length) if length.constant_value() == Some(0.0) => {
            Err((p.keyword.span(), "a distance joint of length 0 is a ball joint: write `spherical`".to_string()))
        }
        Some(length) => Ok(Box::new(Distance { i: p.i, j: p.j, length })),
        None => Err((p.keyword.span(), "a distance joint needs its length: `{ length: 0.3 }` (m)".to_string())),
    },
};

#[derive(Debug)]
pub struct Distance {
    pub i: Marker,
    pub j: Marker,
    pub length: MExpr,
}

impl Joint for Distance {
    fn kind(&self) -> &'static str {
        "distance"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (Some(self.i.loc.body), Some(self.j.loc.body))
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        let pi = b.point3(&self.i.loc);
        let pj = b.point3(&self.j.loc);
        let d: [_; 3] = std::array::from_fn(|k| b.g.sub(pj[k], pi[k]));
        let l = b.expr(&self.length);
        vec![Row { name: "length", value: b.distance_row(&d, l), unit: RowUnit::Length }]
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"i": marker_json(cx, &self.i), "j": marker_json(cx, &self.j), "length": cx.expr(&self.length)})
    }
}
