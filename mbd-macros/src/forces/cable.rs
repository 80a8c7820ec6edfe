//! `cable Pi ~ Pj { k, length, c };` — a rope or cable between two points: tension only. With
//! l = |r^P_j − r^P_i| and the stretch δ = l − length, it pulls the points together with
//! f = max(k δ + c l̇, 0) while δ > 0 and nothing while slack; V = ½ k δ² while taut.
//! Q = −f (∂l̇/∂v)ᵀ. Units: k in N/m, length in m, c in N·s/m.

use serde_json::{json, Value};

use super::{Force, Generalized, Resolved};
use crate::frames::Builder;
use crate::json::Ctx;
use crate::model::{BodyRef, Loc, MExpr, Resolver, Scope};
use crate::parse::JointDef;

#[derive(Debug)]
pub struct Cable {
    pub i: Loc,
    pub j: Loc,
    pub k: MExpr,
    pub length: MExpr,
    pub c: Option<MExpr>,
}

pub fn resolve<'a>(r: &mut Resolver, f: &'a JointDef, body_name: &dyn Fn(BodyRef) -> String) -> Option<Resolved<'a>> {
    let li = r.loc(&f.i.body, &f.i.point);
    let lj = r.loc(&f.j.body, &f.j.point);
    if !super::no_axis(r, f, "a cable pulls along the line between its points: it takes no axis") {
        return None;
    }
    let known = [("k", Scope::Params), ("length", Scope::Params), ("c", Scope::Params)];
    let mut o = super::options(r, &f.kind, &f.options, &known)?;
    let (li, lj) = (li?, lj?);
    if li.body == lj.body {
        r.errors.push(
            f.j.body.span(),
            format!("a cable from body `{0}` to itself does nothing: expected a second body, found `{0}` again", f.j.body),
        );
        return None;
    }
    let (k, length) = (o.remove("k"), o.remove("length"));
    let (Some(k), Some(length)) = (k.clone(), length.clone()) else {
        let found = match (k, length) {
            (Some(_), None) => "only `k`",
            (None, Some(_)) => "only `length`",
            _ => "neither",
        };
        r.errors.push(
            f.kind.span(),
            format!("a cable needs its stiffness and unstretched length: expected `k` (N/m) and `length` (m), found {found}; e.g. `{{ k: 5.0e4, length: 1.2 }}`"),
        );
        return None;
    };
    let name = format!("cable {}~{}", body_name(li.body), body_name(lj.body));
    Some((f.label.as_ref(), name, f.kind.span(), Box::new(Cable { i: li, j: lj, k, length, c: o.remove("c") })))
}

impl Force for Cable {
    fn effect(&self) -> &'static str {
        "cable"
    }
    fn kind(&self) -> &'static str {
        "cable"
    }
    fn apply(&self, b: &mut Builder, out: &mut Generalized) {
        let l = b.length_between(&self.i, &self.j);
        let length = b.expr(&self.length);
        let stretch = b.g.sub(l, length);
        let (f, potential, switch) = b.unilateral(stretch, &self.k, None, self.c.as_ref());
        b.add_along(&mut out.h, l, f);
        out.potential = b.g.add(out.potential, potential);
        out.switches.push(switch);
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"i": cx.loc(&self.i), "j": cx.loc(&self.j), "k": cx.expr(&self.k), "length": cx.expr(&self.length), "c": cx.opt(&self.c)})
    }
}
