//! `planar Pi along ai ~ Pj along aj;` — body j slides and turns in the plane through P_i
//! normal to z_i (rows `normal_x`, `normal_y`, `offset`: x_iᵀ z_j, y_iᵀ z_j, z_iᵀ d).

use serde_json::Value;

use super::{pair_json, revolute::aligned, Axis, Marker, Parts, Spec};
use crate::elements::Joint;
use crate::frames::{Builder, Row, RowUnit};
use crate::json::Ctx;
use crate::model::BodyRef;

pub const SPEC: Spec = Spec {
    keyword: "planar",
    axis_i: Axis::Required,
    axis_j: Axis::Required,
    options: &[],
    build: |p: Parts| Ok(Box::new(Planar { i: p.i, j: p.j })),
};

#[derive(Debug)]
pub struct Planar {
    pub i: Marker,
    pub j: Marker,
}

impl Joint for Planar {
    fn kind(&self) -> &'static str {
        "planar"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (Some(self.i.loc.body), Some(self.j.loc.body))
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        let mut rows = aligned(b, &self.i, &self.j, ["normal_x", "normal_y"]);
        let offset = b.joint_stroke(&self.i, &self.j);
        rows.push(Row { name: "offset", value: offset, unit: RowUnit::Length });
        rows
    }
    fn json(&self, cx: &Ctx) -> Value {
        pair_json(cx, &self.i, &self.j)
    }
    fn markers(&self) -> Option<[&Marker; 2]> {
        Some([&self.i, &self.j])
    }
}
