//! `tyre wheel.C ~ ground[0.0, 0.0] { radius, k, c, road };` — Nikravesh's point-follower tyre: a radial
//! spring-damper between the wheel centre C and a road whose height above the ground point O is
//! `road`, any function of coordinates (the wheel's `x`), `t` and parameters. The vertical is y in
//! the plane and z in space. The tyre's compression is δ = (h_O + road + radius) − h_C; while
//! δ > 0 the road pushes with f = max(k δ + c δ̇, 0), and it lets go when the wheel leaves it;
//! V = ½ k δ² in contact. Q = −f (∂δ̇/∂v)ᵀ: vertical on a flat road, and tilted by the road's
//! slope, −f ∂road/∂x, where it climbs (the force of the potential). Units: k in N/m, c in N·s/m.

use serde_json::{json, Value};

use super::{Force, Generalized, Resolved};
use crate::frames::Builder;
use crate::json::Ctx;
use crate::model::{BodyRef, Loc, MExpr, Resolver, Scope};
use crate::parse::JointDef;

#[derive(Debug)]
pub struct Tyre {
    pub wheel: Loc,
    pub road_at: Loc,
    pub radius: MExpr,
    pub k: MExpr,
    pub c: Option<MExpr>,
    pub road: MExpr,
}

pub fn resolve<'a>(r: &mut Resolver, f: &'a JointDef, body_name: &dyn Fn(BodyRef) -> String) -> Option<Resolved<'a>> {
    let li = r.loc(&f.i.body, &f.i.point);
    let lj = r.loc(&f.j.body, &f.j.point);
    if !super::no_axis(r, f, "a tyre pushes along the vertical: it takes no axis") {
        return None;
    }
    let known = [("radius", Scope::Params), ("k", Scope::Params), ("c", Scope::Params), ("road", Scope::State)];
    let mut o = super::options(r, &f.kind, &f.options, &known)?;
    let (li, lj) = (li?, lj?);
    if lj.body != BodyRef::Ground {
        r.errors.push(
            f.j.body.span(),
            "a tyre rolls on the road, which is fixed: expected `~ ground[0.0, 0.0]` (the road's height is measured from that point), found a moving body",
        );
        return None;
    }
    if li.body == BodyRef::Ground {
        r.errors.push(f.i.body.span(), "a tyre's first point is its wheel's centre: expected a point on a moving body, found `ground`");
        return None;
    }
    let (Some(radius), Some(k)) = (o.remove("radius"), o.remove("k")) else {
        r.errors.push(f.kind.span(), "a tyre needs its radius and radial stiffness: expected `radius` (m) and `k` (N/m), found not both; e.g. `{ radius: 0.3, k: 2.0e5 }`");
        return None;
    };
    let name = format!("tyre {}", body_name(li.body));
    let road = o.remove("road").unwrap_or(MExpr::Num(0.0));
    Some((f.label.as_ref(), name, f.kind.span(), Box::new(Tyre { wheel: li, road_at: lj, radius, k, c: o.remove("c"), road })))
}

impl Force for Tyre {
    fn effect(&self) -> &'static str {
        "tyre"
    }
    fn kind(&self) -> &'static str {
        "tyre"
    }
    fn apply(&self, b: &mut Builder, out: &mut Generalized) {
        let wheel = b.point_n(&self.wheel);
        let datum = b.point_n(&self.road_at);
        let up = wheel.len() - 1;
        let road = b.expr(&self.road);
        let radius = b.expr(&self.radius);
        let surface = b.g.add(datum[up], road);
        let top = b.g.add(surface, radius);
        let delta = b.g.sub(top, wheel[up]);
        let (f, potential, switch) = b.unilateral(delta, &self.k, None, self.c.as_ref());
        b.add_along(&mut out.h, delta, f);
        out.potential = b.g.add(out.potential, potential);
        out.switches.push(switch);
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({
            "i": cx.loc(&self.wheel), "j": cx.loc(&self.road_at), "radius": cx.expr(&self.radius), "k": cx.expr(&self.k),
            "c": cx.opt(&self.c), "road": cx.expr(&self.road)
        })
    }
}
