//! `translational Pi along ai ~ Pj along aj;` in space — a prismatic joint: the cylindrical
//! joint's four rows and `twist` x_iᵀ y_j, which holds x_j ∥ x_i (give both markers the same
//! reference direction in the assembled position). Its stroke s = z_iᵀ d can be driven and
//! carries viscous friction (`{ viscous: c }`).

use serde_json::Value;

use super::{cylindrical::on_axis, pair_json, revolute::aligned, Axis, Marker, Parts, Spec};
use crate::elements::Joint;
use crate::frames::{Builder, Row, RowUnit};
use crate::json::Ctx;
use crate::model::BodyRef;

pub const SPEC: Spec = Spec {
    keyword: "translational",
    axis_i: Axis::Required,
    axis_j: Axis::Required,
    options: &[("viscous", None), ("coulomb", None), ("slip_velocity", Some("the slip velocity of Coulomb friction"))],
    build: |p: Parts| Ok(Box::new(Translational { i: p.i, j: p.j })),
};

#[derive(Debug)]
pub struct Translational {
    pub i: Marker,
    pub j: Marker,
}

impl Joint for Translational {
    fn kind(&self) -> &'static str {
        "translational"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (Some(self.i.loc.body), Some(self.j.loc.body))
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        let mut rows = aligned(b, &self.i, &self.j, ["axis_x", "axis_y"]);
        rows.extend(on_axis(b, &self.i, &self.j));
        let (fi, fj) = (b.frame(&self.i), b.frame(&self.j));
        rows.push(Row { name: "twist", value: b.dot(&fi.x, &fj.y), unit: RowUnit::Angle });
        rows
    }
    fn json(&self, cx: &Ctx) -> Value {
        pair_json(cx, &self.i, &self.j)
    }
    fn markers(&self) -> Option<[&Marker; 2]> {
        Some([&self.i, &self.j])
    }
    fn relative(&self) -> Option<crate::elements::Relative<'_>> {
        Some(crate::elements::Relative::Spatial { kind: crate::elements::SpatialKind::Translational, i: &self.i, j: &self.j })
    }
}
