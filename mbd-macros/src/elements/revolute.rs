//! `revolute Pi ~ Pj;` — a pin: the two points coincide (Nikravesh 7.3.1).
//!
//! Rows `x`, `y`: r^P_i − r^P_j. Options: viscous and Coulomb pin friction (`forces::friction`).

use serde_json::{json, Value};

use super::{Joint, JointSpec, Parts};
use crate::frames::{Builder, Row, RowUnit};
use crate::json::Ctx;
use crate::model::{BodyRef, Loc};

pub const SPEC: JointSpec = JointSpec {
    keyword: "revolute",
    axis_i: false,
    axis_j: false,
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
    pub i: Loc,
    pub j: Loc,
}

impl Joint for Revolute {
    fn kind(&self) -> &'static str {
        "revolute"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (Some(self.i.body), Some(self.j.body))
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        let pi = b.point(&self.i);
        let pj = b.point(&self.j);
        let [x, y] = b.diff2(pi, pj);
        vec![Row { name: "x", value: x, unit: RowUnit::Length }, Row { name: "y", value: y, unit: RowUnit::Length }]
    }
    fn relative(&self) -> Option<super::Relative<'_>> {
        Some(super::Relative::Revolute { i: &self.i, j: &self.j })
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"i": cx.loc(&self.i), "j": cx.loc(&self.j)})
    }
}
