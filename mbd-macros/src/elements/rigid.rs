//! `rigid Pi ~ Pj { angle: θ };` — the bodies are welded: the points coincide and
//! φ_j − φ_i = θ (default 0).
//!
//! Rows `x`, `y`, `angle`: r^P_i − r^P_j, φ_j − φ_i − θ.

use serde_json::{json, Value};

use super::{Joint, JointSpec, Parts};
use crate::frames::{Builder, Row, RowUnit};
use crate::json::Ctx;
use crate::model::{BodyRef, Loc, MExpr};

pub const SPEC: JointSpec = JointSpec {
    keyword: "rigid",
    axis_i: false,
    axis_j: false,
    options: &[("angle", None)],
    build: |mut p: Parts| {
        let angle = p.options.remove("angle").unwrap_or(MExpr::Num(0.0));
        Ok(Box::new(Rigid { i: p.i, j: p.j, angle }))
    },
};

#[derive(Debug)]
pub struct Rigid {
    pub i: Loc,
    pub j: Loc,
    pub angle: MExpr,
}

impl Joint for Rigid {
    fn kind(&self) -> &'static str {
        "rigid"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (Some(self.i.body), Some(self.j.body))
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        let pi = b.point(&self.i);
        let pj = b.point(&self.j);
        let [x, y] = b.diff2(pi, pj);
        let rel = b.relative_angle(self.i.body, self.j.body);
        let a = b.expr(&self.angle);
        vec![
            Row { name: "x", value: x, unit: RowUnit::Length },
            Row { name: "y", value: y, unit: RowUnit::Length },
            Row { name: "angle", value: b.g.sub(rel, a), unit: RowUnit::Angle },
        ]
    }
    fn relative(&self) -> Option<super::Relative<'_>> {
        Some(super::Relative::Rigid { i: &self.i, j: &self.j, angle: &self.angle })
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"i": cx.loc(&self.i), "j": cx.loc(&self.j), "angle": cx.expr(&self.angle)})
    }
}
