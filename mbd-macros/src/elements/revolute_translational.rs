//! `revolute_translational Pi ~ Pj along uj { distance: L };` — P_i stays at distance L (default
//! 0: a pin in a slot) from the line through P_j along u_j (Nikravesh 7.3.4).
//!
//! Row `distance`: n_jᵀ (r^P_i − r^P_j) − L, n_j = perp(A_j u′_j/|u′_j|).

use serde_json::{json, Value};

use super::{Joint, JointSpec, Parts};
use crate::frames::{Builder, Row, RowUnit};
use crate::json::Ctx;
use crate::model::{BodyRef, Loc, MExpr};

pub const SPEC: JointSpec = JointSpec {
    keyword: "revolute_translational",
    axis_i: false,
    axis_j: true,
    options: &[("distance", None)],
    build: |mut p: Parts| {
        let Some(axis_j) = p.axis_j else {
            return Err((p.keyword.span(), "a revolute_translational joint needs an axis on its second body".to_string()));
        };
        let distance = p.options.remove("distance").unwrap_or(MExpr::Num(0.0));
        Ok(Box::new(RevoluteTranslational { i: p.i, j: p.j, axis_j, distance }))
    },
};

#[derive(Debug)]
pub struct RevoluteTranslational {
    pub i: Loc,
    pub j: Loc,
    pub axis_j: crate::model::Components,
    pub distance: MExpr,
}

impl Joint for RevoluteTranslational {
    fn kind(&self) -> &'static str {
        "revolute_translational"
    }
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>) {
        (Some(self.i.body), Some(self.j.body))
    }
    fn rows(&self, b: &mut Builder) -> Vec<Row> {
        let pi = b.point(&self.i);
        let pj = b.point(&self.j);
        let uj = b.unit(self.j.body, &self.axis_j);
        let nj = b.perp(uj);
        let d = b.diff2(pi, pj);
        let n = b.dot(&nj, &d);
        let l = b.expr(&self.distance);
        vec![Row { name: "distance", value: b.g.sub(n, l), unit: RowUnit::Length }]
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"i": cx.loc(&self.i), "j": cx.loc_axis(&self.j, &self.axis_j), "distance": cx.expr(&self.distance)})
    }
}
