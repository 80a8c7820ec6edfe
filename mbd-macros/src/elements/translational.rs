//! `translational Pi along ui ~ Pj along uj;` — a prismatic joint (Nikravesh 7.3.2): the axes
//! stay parallel and P_j stays on the line through P_i along u_i.
//!
//! Rows `normal`, `angle`: n_iᵀ (r^P_j − r^P_i), n_iᵀ u_j, with u = A u′/|u′| and n_i = perp(u_i).
//! Options: viscous and Coulomb sliding friction (`forces::friction`).

use serde_json::{json, Value};

use super::{Joint, JointSpec, Parts};
use crate::frames::{Builder, Row, RowUnit};
use crate::json::Ctx;
use crate::model::{BodyRef, Components, Loc};

pub const SPEC: JointSpec = JointSpec {
    keyword: "translational",
    axis_i: true,
    axis_j: true,
    options: &[
        ("viscous", None),
        ("coulomb", None),
        ("slip_velocity", Some("the slip velocity of Coulomb friction")),
        ("bearing", Some("a bearing length")),
    ],
    build: |p: Parts| {
        let (Some(axis_i), Some(axis_j)) = (p.axis_i, p.axis_j) else {
            return Err((p.keyword.span(), "a translational joint needs an axis on both bodies".to_string()));
        };
        Ok(Box::new(Translational { i: p.i, axis_i, j: p.j, axis_j }))
    },
};

#[derive(Debug)]
pub struct Translational {
    pub i: Loc,
    pub axis_i: Components,
    pub j: Loc,
    pub axis_j: Components,
}

impl Joint for Translational {
    fn kind(&self) -> &'static str {
        "translational"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (Some(self.i.body), Some(self.j.body))
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        let pi = b.point(&self.i);
        let pj = b.point(&self.j);
        let ui = b.unit(self.i.body, &self.axis_i);
        let ni = b.perp(ui);
        let uj = b.unit(self.j.body, &self.axis_j);
        let d = b.diff2(pj, pi);
        vec![
            Row { name: "normal", value: b.dot(&ni, &d), unit: RowUnit::Length },
            Row { name: "angle", value: b.dot(&ni, &uj), unit: RowUnit::Angle },
        ]
    }
    fn relative(&self) -> Option<super::Relative<'_>> {
        Some(super::Relative::Translational { i: &self.i, axis_i: &self.axis_i, j: &self.j, axis_j: &self.axis_j })
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"i": cx.loc_axis(&self.i, &self.axis_i), "j": cx.loc_axis(&self.j, &self.axis_j)})
    }
}
