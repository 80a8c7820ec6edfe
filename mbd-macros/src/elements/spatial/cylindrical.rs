//! `cylindrical Pi along ai ~ Pj along aj;` — z_j stays along z_i and P_j on the line through
//! P_i along z_i (rows `axis_x`, `axis_y`, `offset_x`, `offset_y`: x_iᵀ z_j, y_iᵀ z_j, x_iᵀ d,
//! y_iᵀ d with d = r^P_j − r^P_i). Both its angle and its stroke can be driven.

use serde_json::Value;

use super::{pair_json, revolute::aligned, Axis, Marker, Parts, Spec};
use crate::elements::Joint;
use crate::frames::{Builder, Row, RowUnit};
use crate::json::Ctx;
use crate::model::BodyRef;

pub const SPEC: Spec = Spec {
    keyword: "cylindrical",
    axis_i: Axis::Required,
    axis_j: Axis::Required,
    options: &[],
    build: |p: Parts| Ok(Box::new(Cylindrical { i: p.i, j: p.j })),
};

#[derive(Debug)]
pub struct Cylindrical {
    pub i: Marker,
    pub j: Marker,
}

/// x_iᵀ d and y_iᵀ d: P_j stays on the line through P_i along z_i.
pub fn on_axis(b: &mut Builder, i: &Marker, j: &Marker) -> Vec<Row> {
    let (fi, fj) = (b.frame(i), b.frame(j));
    let d = b.separation(&fi, &fj);
    vec![
        Row { name: "offset_x", value: b.dot(&fi.x, &d), unit: RowUnit::Length },
        Row { name: "offset_y", value: b.dot(&fi.y, &d), unit: RowUnit::Length },
    ]
}

impl Joint for Cylindrical {
    fn kind(&self) -> &'static str {
        "cylindrical"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (Some(self.i.loc.body), Some(self.j.loc.body))
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        let mut rows = aligned(b, &self.i, &self.j, ["axis_x", "axis_y"]);
        rows.extend(on_axis(b, &self.i, &self.j));
        rows
    }
    fn json(&self, cx: &Ctx) -> Value {
        pair_json(cx, &self.i, &self.j)
    }
    fn markers(&self) -> Option<[&Marker; 2]> {
        Some([&self.i, &self.j])
    }
    fn relative(&self) -> Option<crate::elements::Relative<'_>> {
        Some(crate::elements::Relative::Spatial { kind: crate::elements::SpatialKind::Cylindrical, i: &self.i, j: &self.j })
    }
}
