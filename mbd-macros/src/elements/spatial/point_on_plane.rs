//! `point_on_plane Pi along ai ~ Pj { distance: c };` — P_j stays at the signed distance c
//! (default 0) from the plane through P_i normal to z_i (row `offset`: z_iᵀ d − c).

use serde_json::{json, Value};

use super::{marker_json, Axis, Marker, Parts, Spec};
use crate::elements::Joint;
use crate::frames::{Builder, Row, RowUnit};
use crate::json::Ctx;
use crate::model::{BodyRef, MExpr};

pub const SPEC: Spec = Spec {
    keyword: "point_on_plane",
    axis_i: Axis::Required,
    axis_j: Axis::None,
    options: &[("distance", None)],
    build: |mut p: Parts| {
        let distance = p.options.remove("distance").unwrap_or(MExpr::Num(0.0));
        Ok(Box::new(PointOnPlane { i: p.i, j: p.j, distance }))
    },
};

#[derive(Debug)]
pub struct PointOnPlane {
    pub i: Marker,
    pub j: Marker,
    pub distance: MExpr,
}

impl Joint for PointOnPlane {
    fn kind(&self) -> &'static str {
        "point_on_plane"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (Some(self.i.loc.body), Some(self.j.loc.body))
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        let fi = b.frame(&self.i);
        let pj = b.point3(&self.j.loc);
        let d: [_; 3] = std::array::from_fn(|k| b.g.sub(pj[k], fi.origin[k]));
        let s = b.dot(&fi.z, &d);
        let c = b.expr(&self.distance);
        vec![Row { name: "offset", value: b.g.sub(s, c), unit: RowUnit::Length }]
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"i": marker_json(cx, &self.i), "j": marker_json(cx, &self.j), "distance": cx.expr(&self.distance)})
    }
}
