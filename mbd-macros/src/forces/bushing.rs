//! `bushing Pi [along ai [reference bi]] ~ Pj [along aj [reference bj]] { k: [6], c: [6],
//! preload: [6] };` — a linear six-component spring-damper between two marker frames (spatial;
//! docs/formulation.md): δ = (x_iᵀd, y_iᵀd, z_iᵀd, z_iᵀy_j, x_iᵀz_j, y_iᵀx_j), the offset of
//! marker j from marker i along marker i's axes, then the sines of j's small turns about them;
//! f_c = k_c (δ_c − preload_c) + c_c δ̇_c, Q = −Σ f_c (∂δ̇_c/∂v)ᵀ, V = Σ ½ k_c (δ_c − preload_c)².
//! Without axes a marker is its body's own axes.

use serde_json::{json, Value};

use super::{Force, Generalized, Resolved};
use crate::elements::spatial::{marker, marker_json, Axis, Marker};
use crate::frames::Builder;
use crate::json::Ctx;
use crate::model::{BodyRef, MExpr, Resolver, Scope, Space};
use crate::parse::{JointDef, Value as FieldValue};

#[derive(Debug)]
pub struct Bushing {
    pub i: Marker,
    pub j: Marker,
    pub k: Vec<MExpr>,
    pub c: Option<Vec<MExpr>>,
    pub preload: Vec<MExpr>,
}

pub fn resolve<'a>(r: &mut Resolver, f: &'a JointDef, body_name: &dyn Fn(BodyRef) -> String) -> Option<Resolved<'a>> {
    if r.space != Space::Spatial {
        r.errors.push(f.kind.span(), "a bushing is a spatial element: expected `spatial;` in the mechanism, found a planar one; in the plane use springs and rotational springs");
        return None;
    }
    let mi = marker(r, &f.i, Axis::Default, "bushing", "first");
    let mj = marker(r, &f.j, Axis::Default, "bushing", "second");
    let mut lists: [Option<Vec<MExpr>>; 3] = [None, None, None];
    let mut bad = false;
    for field in &f.options {
        let key = field.name.to_string();
        let Some(slot) = ["k", "c", "preload"].iter().position(|n| *n == key) else {
            r.errors.push(
                field.name.span(),
                format!(
                    "unknown option of a bushing: expected one of `k`, `c`, `preload`, found `{key}`{}",
                    crate::parse::closest(&key, &["k", "c", "preload"], &[])
                ),
            );
            bad = true;
            continue;
        };
        match &field.value {
            FieldValue::Expr(e) => {
                r.errors.at_expr(e, format!("`{key}` of a bushing is a list of six: expected x, y, z along marker i's axes, then turns about them, found a number"));
                bad = true;
            }
            FieldValue::List(v) if v.items.len() != 6 => {
                r.errors.push(v.span, format!("`{key}` of a bushing: expected 6 entries (x, y, z, rx, ry, rz), found {}", v.items.len()));
                bad = true;
            }
            FieldValue::List(v) => {
                let items: Option<Vec<MExpr>> = v.items.iter().map(|e| r.expr(e, Scope::Params)).collect();
                match items {
                    Some(_) if lists[slot].is_some() => {
                        r.errors.push(
                            field.name.span(),
                            format!("duplicate option `{key}`: expected each option once, found `{key}` again; keep one"),
                        );
                        bad = true;
                    }
                    Some(items) => lists[slot] = Some(items),
                    None => bad = true,
                }
            }
        }
    }
    let (mi, mj) = (mi?, mj?);
    if bad {
        return None;
    }
    if mi.loc.body == mj.loc.body {
        r.errors.push(
            f.j.body.span(),
            format!("a bushing of body `{0}` to itself does nothing: expected a second body, found `{0}` again", f.j.body),
        );
        return None;
    }
    let [k, c, preload] = lists;
    let Some(k) = k else {
        r.errors
            .push(f.kind.span(), "a bushing needs its stiffnesses: expected `k: [kx, ky, kz, krx, kry, krz]` (N/m, N·m/rad), found none");
        return None;
    };
    let name = format!("bushing {}~{}", body_name(mi.loc.body), body_name(mj.loc.body));
    let preload = preload.unwrap_or_else(|| vec![MExpr::Num(0.0); 6]);
    Some((f.label.as_ref(), name, f.kind.span(), Box::new(Bushing { i: mi, j: mj, k, c, preload })))
}

impl Force for Bushing {
    fn effect(&self) -> &'static str {
        "bushing"
    }
    fn kind(&self) -> &'static str {
        "bushing"
    }
    fn apply(&self, b: &mut Builder, out: &mut Generalized) {
        let (fi, fj) = (b.frame(&self.i), b.frame(&self.j));
        let d = b.separation(&fi, &fj);
        let delta = [b.dot(&fi.x, &d), b.dot(&fi.y, &d), b.dot(&fi.z, &d), b.dot(&fi.z, &fj.y), b.dot(&fi.x, &fj.z), b.dot(&fi.y, &fj.x)];
        for (n, s) in delta.into_iter().enumerate() {
            let sdot = b.rate(s);
            let c = self.c.as_ref().map(|c| c[n].clone());
            let (f, spring) = b.law(s, sdot, &Some(self.k[n].clone()), &self.preload[n], &c, &None);
            b.add_along(&mut out.h, s, f);
            out.potential = b.add_spring_energy(out.potential, spring);
        }
    }
    fn json(&self, cx: &Ctx) -> Value {
        let c: Vec<Value> = match &self.c {
            Some(c) => c.iter().map(|e| cx.expr(e)).collect(),
            None => vec![Value::Null; 6],
        };
        json!({"i": marker_json(cx, &self.i), "j": marker_json(cx, &self.j), "k": cx.list(&self.k), "c": c, "preload": cx.list(&self.preload)})
    }
}
