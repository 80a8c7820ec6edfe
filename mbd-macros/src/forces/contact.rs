//! `contact Pi ~ Pj along nj { k, exponent, c };` — a unilateral stop: point P_i against the plane
//! (a line in the plane) through P_j with outward normal n_j fixed in body j. The penetration is
//! δ = −n̂ᵀ(r^P_i − r^P_j), n̂ = A_j n′_j/|n′_j|; while δ > 0 the surface pushes P_i out with
//! F = max(δᵉ (k + c δ̇), 0) (Hunt & Crossley: the damping c δᵉ δ̇ vanishes at first touch and
//! the force never pulls), and V = k δᵉ⁺¹/(e + 1). Q = −F (∂δ̇/∂v)ᵀ. Units: k in N/mᵉ, c in
//! N·s/mᵉ⁺¹; `exponent` defaults to 1 (linear; 1.5 is Hertz's sphere on a plane).

use serde_json::{json, Value};

use super::{Force, Generalized, Resolved};
use crate::frames::Builder;
use crate::json::Ctx;
use crate::model::{BodyRef, Components, Loc, MExpr, Resolver, Scope};
use crate::parse::JointDef;
use crate::sym::Func;

#[derive(Debug)]
pub struct Contact {
    pub i: Loc,
    pub j: Loc,
    pub normal: Components,
    pub k: MExpr,
    pub exponent: MExpr,
    pub c: Option<MExpr>,
}

pub fn resolve<'a>(r: &mut Resolver, f: &'a JointDef, body_name: &dyn Fn(BodyRef) -> String) -> Option<Resolved<'a>> {
    let li = r.loc(&f.i.body, &f.i.point);
    let lj = r.loc(&f.j.body, &f.j.point);
    if let Some(a) = &f.i.along {
        r.errors.push(a.keyword.span(), "the contact point takes no axis: expected a point, found `along`; the surface's normal goes on the second side, `~ Pj along n`");
        return None;
    }
    let Some(along) = &f.j.along else {
        let shape = r.shape(["nx", "ny", "nz"]);
        r.errors.push(
            f.j.body.span(),
            format!(
                "a contact needs its surface's outward normal: expected `~ {}.P along {shape}` (in the body's frame), found no `along`",
                f.j.body
            ),
        );
        return None;
    };
    let (li, lj) = (li?, lj?);
    let normal = r.axis(lj.body, &along.axis)?;
    let known = [("k", Scope::Params), ("exponent", Scope::Params), ("c", Scope::Params)];
    let mut o = super::options(r, &f.kind, &f.options, &known)?;
    if li.body == lj.body {
        r.errors.push(
            f.j.body.span(),
            format!("a contact of body `{0}` with itself does nothing: expected another body or the ground, found `{0}` again", f.j.body),
        );
        return None;
    }
    let Some(k) = o.remove("k") else {
        r.errors.push(
            f.kind.span(),
            "a contact needs its stiffness: expected `k` (N/m; N/mᵉ with an `exponent`), found none; e.g. `{ k: 1.0e5 }`",
        );
        return None;
    };
    let name = format!("contact {}~{}", body_name(li.body), body_name(lj.body));
    let element = Contact { i: li, j: lj, normal, k, exponent: o.remove("exponent").unwrap_or(MExpr::Num(1.0)), c: o.remove("c") };
    Some((f.label.as_ref(), name, f.kind.span(), Box::new(element)))
}

impl Force for Contact {
    fn effect(&self) -> &'static str {
        "contact"
    }
    fn kind(&self) -> &'static str {
        "contact"
    }
    fn apply(&self, b: &mut Builder, out: &mut Generalized) {
        let pi = b.point_n(&self.i);
        let pj = b.point_n(&self.j);
        let n: Vec<_> = self.normal.iter().map(|e| b.expr(e)).collect();
        let nn = b.dot(&n, &n);
        let norm = b.g.call(Func::Sqrt, nn);
        let unit = n.into_iter().map(|c| b.g.div(c, norm)).collect();
        let n = b.rotate_n(self.j.body, unit);
        let d = b.diff_n(&pj, &pi);
        let delta = b.dot(&n, &d);
        let (f, potential, switch) = b.unilateral(delta, &self.k, Some(&self.exponent), self.c.as_ref());
        b.add_along(&mut out.h, delta, f);
        out.potential = b.g.add(out.potential, potential);
        out.switches.push(switch);
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({
            "i": cx.loc(&self.i), "j": cx.loc(&self.j), "normal": cx.list(&self.normal),
            "k": cx.expr(&self.k), "exponent": cx.expr(&self.exponent), "c": cx.opt(&self.c)
        })
    }
}
