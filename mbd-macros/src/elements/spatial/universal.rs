//! `universal Pi along ai ~ Pj along aj;` — a Hooke joint: the points coincide and the two
//! axes stay perpendicular (rows `x`, `y`, `z`, `cross`: r^P_i − r^P_j, z_iᵀ z_j). Write the
//! axes perpendicular in the assembled position.

use serde_json::Value;

use super::{pair_json, spherical::coincide, Axis, Marker, Parts, Spec};
use crate::elements::Joint;
use crate::frames::{Builder, Row, RowUnit};
use crate::json::Ctx;
use crate::model::BodyRef;

pub const SPEC: Spec = Spec {
    keyword: "universal",
    axis_i: Axis::Required,
    axis_j: Axis::Required,
    options: &[],
    build: |p: Parts| Ok(Box::new(Universal { i: p.i, j: p.j })),
};

#[derive(Debug)]
pub struct Universal {
    pub i: Marker,
    pub j: Marker,
}

impl Joint for Universal {
    fn kind(&self) -> &'static str {
        "universal"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (Some(self.i.loc.body), Some(self.j.loc.body))
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        let mut rows = coincide(b, &self.i, &self.j);
        let (fi, fj) = (b.frame(&self.i), b.frame(&self.j));
        rows.push(Row { name: "cross", value: b.dot(&fi.z, &fj.z), unit: RowUnit::Angle });
        rows
    }
    fn json(&self, cx: &Ctx) -> Value {
        pair_json(cx, &self.i, &self.j)
    }
    fn markers(&self) -> Option<[&Marker; 2]> {
        Some([&self.i, &self.j])
    }
}
