//! `revolute_revolute Pi ~ Pj { length: L };` — a massless link of length L between two pins
//! (Nikravesh 7.3.3).
//!
//! Row `length`: (dᵀd − L²)/(2L), d = r^P_j − r^P_i: its multiplier is the link's force in N.

use serde_json::{json, Value};

use super::{Joint, JointSpec, Parts};
use crate::frames::{Builder, Row, RowUnit};
use crate::json::Ctx;
use crate::model::{BodyRef, Loc, MExpr};

pub const SPEC: JointSpec = JointSpec {
    keyword: "revolute_revolute",
    axis_i: false,
    axis_j: false,
    options: &[("length", Some("the length of a revolute-revolute link"))],
    build: |mut p: Parts| match p.options.remove("length") {
        Some(length) if length.constant_value() == Some(0.0) => {
            Err((p.keyword.span(), "a revolute_revolute link of length 0 is a pin: write `revolute`".to_string()))
        }
        Some(length) => Ok(Box::new(RevoluteRevolute { i: p.i, j: p.j, length })),
        None => Err((p.keyword.span(), "a revolute_revolute link needs its length: `{ length: 0.3 }` (m)".to_string())),
    },
};

#[derive(Debug)]
pub struct RevoluteRevolute {
    pub i: Loc,
    pub j: Loc,
    pub length: MExpr,
}

impl Joint for RevoluteRevolute {
    fn kind(&self) -> &'static str {
        "revolute_revolute"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (Some(self.i.body), Some(self.j.body))
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        let l = b.expr(&self.length);
        vec![Row { name: "length", value: b.distance_between(&self.i, &self.j, l), unit: RowUnit::Length }]
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"i": cx.loc(&self.i), "j": cx.loc(&self.j), "length": cx.expr(&self.length)})
    }
}
