//! `spherical Pi ~ Pj;` — a ball joint: the two points coincide (3 rows `x`, `y`, `z`:
//! r^P_i − r^P_j).

use serde_json::Value;

use super::{pair_json, Axis, Marker, Parts, Spec};
use crate::elements::Joint;
use crate::frames::{Builder, Row, RowUnit};
use crate::json::Ctx;
use crate::model::BodyRef;

pub const SPEC: Spec = Spec {
    keyword: "spherical",
    axis_i: Axis::None,
    axis_j: Axis::None,
    options: &[],
    build: |p: Parts| Ok(Box::new(Spherical { i: p.i, j: p.j })),
};

#[derive(Debug)]
pub struct Spherical {
    pub i: Marker,
    pub j: Marker,
}

/// r^P_i − r^P_j, named x, y, z: the rows every point-coincidence joint starts with.
pub fn coincide(b: &mut Builder, i: &Marker, j: &Marker) -> Vec<Row> {
    let pi = b.point3(&i.loc);
    let pj = b.point3(&j.loc);
    ["x", "y", "z"].into_iter().zip(0..3).map(|(name, k)| Row { name, value: b.g.sub(pi[k], pj[k]), unit: RowUnit::Length }).collect()
}

impl Joint for Spherical {
    fn kind(&self) -> &'static str {
        "spherical"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (Some(self.i.loc.body), Some(self.j.loc.body))
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        coincide(b, &self.i, &self.j)
    }
    fn json(&self, cx: &Ctx) -> Value {
        pair_json(cx, &self.i, &self.j)
    }
    fn markers(&self) -> Option<[&Marker; 2]> {
        Some([&self.i, &self.j])
    }
    fn relative(&self) -> Option<crate::elements::Relative<'_>> {
        Some(crate::elements::Relative::Spatial { kind: crate::elements::SpatialKind::Spherical, i: &self.i, j: &self.j })
    }
}
