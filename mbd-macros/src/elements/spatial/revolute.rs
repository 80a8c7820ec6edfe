//! `revolute Pi along ai ~ Pj along aj;` in space — a hinge: the points coincide and z_j stays
//! along z_i (rows `x`, `y`, `z`, `axis_x`, `axis_y`: r^P_i − r^P_j, x_iᵀ z_j, y_iᵀ z_j).
//! Its angle θ = atan2(y_iᵀ x_j, x_iᵀ x_j) can be driven (`drive J.angle = f;`) and carries
//! rotational springs and viscous friction (`{ viscous: c }`).

use serde_json::Value;

use super::{pair_json, spherical::coincide, Axis, Marker, Parts, Spec};
use crate::elements::Joint;
use crate::frames::{Builder, Row, RowUnit};
use crate::json::Ctx;
use crate::model::BodyRef;

pub const SPEC: Spec = Spec {
    keyword: "revolute",
    axis_i: Axis::Required,
    axis_j: Axis::Required,
    options: &[
        ("viscous", None),
        ("coulomb", None),
        ("radius", Some("a pin radius")),
        ("slip_velocity", Some("the slip velocity of Coulomb friction")),
    ],
    build: |p: Parts| Ok(Box::new(Revolute { i: p.i, j: p.j })),
};

#[derive(Debug)]
pub struct Revolute {
    pub i: Marker,
    pub j: Marker,
}

/// x_iᵀ z_j and y_iᵀ z_j, named with `prefix`: z_j stays along z_i.
pub fn aligned(b: &mut Builder, i: &Marker, j: &Marker, names: [&'static str; 2]) -> Vec<Row> {
    let (fi, fj) = (b.frame(i), b.frame(j));
    vec![
        Row { name: names[0], value: b.dot(&fi.x, &fj.z), unit: RowUnit::Angle },
        Row { name: names[1], value: b.dot(&fi.y, &fj.z), unit: RowUnit::Angle },
    ]
}

impl Joint for Revolute {
    fn kind(&self) -> &'static str {
        "revolute"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (Some(self.i.loc.body), Some(self.j.loc.body))
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        let mut rows = coincide(b, &self.i, &self.j);
        rows.extend(aligned(b, &self.i, &self.j, ["axis_x", "axis_y"]));
        rows
    }
    fn json(&self, cx: &Ctx) -> Value {
        pair_json(cx, &self.i, &self.j)
    }
    fn markers(&self) -> Option<[&Marker; 2]> {
        Some([&self.i, &self.j])
    }
    fn relative(&self) -> Option<crate::elements::Relative<'_>> {
        Some(crate::elements::Relative::Spatial { kind: crate::elements::SpatialKind::Revolute, i: &self.i, j: &self.j })
    }
}
