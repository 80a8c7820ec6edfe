//! `rigid Pi [along ai [reference bi]] ~ Pj [along aj [reference bj]];` in space — the points
//! coincide and the two marker triads stay aligned (rows `x`, `y`, `z`, `rx`, `ry`, `rz`:
//! r^P_i − r^P_j, y_iᵀ z_j, z_iᵀ x_j, x_iᵀ y_j). Without axes the markers are the bodies' own
//! axes, so the bodies keep their relative orientation of the identity.

use serde_json::Value;

use super::{pair_json, spherical::coincide, Axis, Marker, Parts, Spec};
use crate::elements::Joint;
use crate::frames::{Builder, Row, RowUnit};
use crate::json::Ctx;
use crate::model::{BodyRef, Loc, MExpr};

pub const SPEC: Spec = Spec {
    keyword: "rigid",
    axis_i: Axis::Default,
    axis_j: Axis::Default,
    options: &[],
    build: |p: Parts| Ok(Box::new(Rigid { i: p.i, j: p.j })),
};

#[derive(Debug)]
pub struct Rigid {
    pub i: Marker,
    pub j: Marker,
}

impl Joint for Rigid {
    fn kind(&self) -> &'static str {
        "rigid"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (Some(self.i.loc.body), Some(self.j.loc.body))
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        let mut rows = coincide(b, &self.i, &self.j);
        let (fi, fj) = (b.frame(&self.i), b.frame(&self.j));
        rows.push(Row { name: "rx", value: b.dot(&fi.y, &fj.z), unit: RowUnit::Angle });
        rows.push(Row { name: "ry", value: b.dot(&fi.z, &fj.x), unit: RowUnit::Angle });
        rows.push(Row { name: "rz", value: b.dot(&fi.x, &fj.y), unit: RowUnit::Angle });
        rows
    }
    fn json(&self, cx: &Ctx) -> Value {
        pair_json(cx, &self.i, &self.j)
    }
    fn markers(&self) -> Option<[&Marker; 2]> {
        Some([&self.i, &self.j])
    }
    fn relative(&self) -> Option<crate::elements::Relative<'_>> {
        Some(crate::elements::Relative::Spatial { kind: crate::elements::SpatialKind::Rigid, i: &self.i, j: &self.j })
    }
}

/// A spatial particle's orientation, held to the ground's (rows `rx`, `ry`, `rz` of a rigid
/// joint between the ground's axes and the body's): a point mass has no rotation to integrate.
#[derive(Debug)]
pub struct Orientation {
    pub i: Marker,
    pub j: Marker,
}

impl Orientation {
    /// Body `k`'s axes held to the ground's.
    pub fn held(k: usize) -> Self {
        let zero = || vec![MExpr::Num(0.0); 3];
        let axes = |body| Marker {
            loc: Loc { body, point: zero() },
            axis: vec![MExpr::Num(0.0), MExpr::Num(0.0), MExpr::Num(1.0)],
            reference: vec![MExpr::Num(1.0), MExpr::Num(0.0), MExpr::Num(0.0)],
        };
        Orientation { i: axes(BodyRef::Ground), j: axes(BodyRef::Body(k)) }
    }
}

impl Joint for Orientation {
    fn kind(&self) -> &'static str {
        "orientation"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (None, Some(self.j.loc.body))
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        let (fi, fj) = (b.frame(&self.i), b.frame(&self.j));
        vec![
            Row { name: "rx", value: b.dot(&fi.y, &fj.z), unit: RowUnit::Angle },
            Row { name: "ry", value: b.dot(&fi.z, &fj.x), unit: RowUnit::Angle },
            Row { name: "rz", value: b.dot(&fi.x, &fj.y), unit: RowUnit::Angle },
        ]
    }
    fn json(&self, cx: &Ctx) -> Value {
        pair_json(cx, &self.i, &self.j)
    }
}
