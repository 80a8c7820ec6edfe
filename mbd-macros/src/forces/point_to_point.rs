//! `spring`, `damper`, `actuator` Pi ~ Pj { k, length, c, force } — a point-to-point
//! spring-damper-actuator (Nikravesh 4.2.1): tension f = k (l − length) + c l̇ + force along the
//! line between the points, pulling them together; Q = −f (∂l̇/∂v)ᵀ, V = ½ k (l − length)².

use serde_json::{json, Value};

use super::{Force, Generalized, Resolved};
use crate::frames::Builder;
use crate::json::Ctx;
use crate::model::{BodyRef, Loc, MExpr, Resolver, Scope};
use crate::parse::JointDef;

#[derive(Debug)]
pub struct PointToPoint {
    pub i: Loc,
    pub j: Loc,
    pub k: Option<MExpr>,
    pub length: MExpr,
    pub c: Option<MExpr>,
    pub force: Option<MExpr>,
}

pub fn resolve<'a>(r: &mut Resolver, f: &'a JointDef, body_name: &dyn Fn(BodyRef) -> String) -> Option<Resolved<'a>> {
    let kind = f.kind.to_string();
    let li = r.loc(&f.i.body, &f.i.point);
    let lj = r.loc(&f.j.body, &f.j.point);
    if !super::no_axis(r, f, &format!("a {kind} acts along the line between its points: it takes no axis")) {
        return None;
    }
    let known = [("k", Scope::Params), ("length", Scope::Params), ("c", Scope::Params), ("force", Scope::Force)];
    let mut o = super::options(r, &f.kind, &f.options, &known)?;
    let (li, lj) = (li?, lj?);
    if li.body == lj.body {
        r.errors.push(
            f.j.body.span(),
            format!("a {kind} of body `{0}` to itself does nothing: expected a second body, found `{0}` again", f.j.body),
        );
        return None;
    }
    let required = match kind.as_str() {
        "spring" => ("k", "a spring needs its stiffness: expected `k` (N/m), found none; e.g. `{ k: 2.0e3, length: 0.3 }` (N/m, m)"),
        "damper" => ("c", "a damper needs its damping coefficient: `{ c: 50.0 }` (N·s/m)"),
        _ => ("force", "an actuator needs its force: `{ force: 100.0 * sin(t) }` (N, tension positive)"),
    };
    if !o.contains_key(required.0) {
        r.errors.push(f.kind.span(), required.1);
        return None;
    }
    if o.contains_key("k") && !o.contains_key("length") {
        r.errors.push(f.kind.span(), "a spring needs its free length: expected `length` (m), found none; e.g. `length: 0.3`");
        return None;
    }
    let name = format!("{kind} {}~{}", body_name(li.body), body_name(lj.body));
    let element = PointToPoint {
        i: li,
        j: lj,
        k: o.remove("k"),
        length: o.remove("length").unwrap_or(MExpr::Num(0.0)),
        c: o.remove("c"),
        force: o.remove("force"),
    };
    Some((f.label.as_ref(), name, f.kind.span(), Box::new(element)))
}

impl Force for PointToPoint {
    fn effect(&self) -> &'static str {
        "point-to-point spring-damper-actuator"
    }
    fn kind(&self) -> &'static str {
        "point_to_point"
    }
    fn apply(&self, b: &mut Builder, out: &mut Generalized) {
        let l = b.length_between(&self.i, &self.j);
        let ldot = b.rate(l);
        let (f, spring) = b.law(l, ldot, &self.k, &self.length, &self.c, &self.force);
        b.add_along(&mut out.h, l, f);
        out.potential = b.add_spring_energy(out.potential, spring);
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({
            "i": cx.loc(&self.i), "j": cx.loc(&self.j),
            "k": cx.opt(&self.k), "length": cx.expr(&self.length), "c": cx.opt(&self.c), "force": cx.opt(&self.force)
        })
    }
}
