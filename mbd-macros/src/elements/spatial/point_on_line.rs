//! `point_on_line Pi along ai ~ Pj;` — P_j stays on the line through P_i along z_i (rows
//! `offset_x`, `offset_y`: x_iᵀ d, y_iᵀ d).

use serde_json::Value;

use super::{pair_json, Axis, Marker, Parts, Spec};
use crate::elements::Joint;
use crate::frames::{Builder, Row, RowUnit};
use crate::json::Ctx;
use crate::model::BodyRef;

pub const SPEC: Spec = Spec {
    keyword: "point_on_line",
    axis_i: Axis::Required,
    axis_j: Axis::None,
    options: &[],
    build: |p: Parts| Ok(Box::new(PointOnLine { i: p.i, j: p.j })),
};

#[derive(Debug)]
pub struct PointOnLine {
    pub i: Marker,
    pub j: Marker,
}

impl Joint for PointOnLine {
    fn kind(&self) -> &'static str {
        "point_on_line"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (Some(self.i.loc.body), Some(self.j.loc.body))
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        let fi = b.frame(&self.i);
        let pj = b.point3(&self.j.loc);
        let d: [_; 3] = std::array::from_fn(|k| b.g.sub(pj[k], fi.origin[k]));
        vec![
            Row { name: "offset_x", value: b.dot(&fi.x, &d), unit: RowUnit::Length },
            Row { name: "offset_y", value: b.dot(&fi.y, &d), unit: RowUnit::Length },
        ]
    }
    fn json(&self, cx: &Ctx) -> Value {
        pair_json(cx, &self.i, &self.j)
    }
}
