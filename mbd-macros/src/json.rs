//! The model's JSON description (`Mechanism::MODEL_JSON`, schema in docs/formulation.md), written
//! from the validated model — not from the symbolic graph — so the CasADi oracle rebuilds the
//! equations from the same joint definitions the user wrote, independently of `sym`. Each kind
//! writes its own fields (`Joint::json`, `Force::json`); this file writes the whole.

use serde_json::{json, Value};

use crate::model::{BodyRef, Inertia, Loc, MBin, MExpr, Model, Space};
use crate::sym::Cmp;

/// What a kind's JSON needs: the model (names) and the first row of each constraint.
pub struct Ctx<'a> {
    pub model: &'a Model,
    pub first_rows: &'a [usize],
}

impl Ctx<'_> {
    pub fn expr(&self, e: &MExpr) -> Value {
        let m = self.model;
        match e {
            MExpr::Num(v) => json!(["num", v]),
            MExpr::Pi => json!(["pi"]),
            MExpr::T => json!(["t"]),
            MExpr::Param(k) => json!(["param", m.params[*k].name.to_string()]),
            MExpr::Coord(b, c) => json!(["coord", m.body_name(*b), c.name()]),
            // planar velocities are named by their coordinate (the oracle's schema), spatial
            // ones by themselves (`wx`)
            MExpr::Vel(b, c) => {
                let name = if m.space == Space::Planar { m.space.coordinates()[c.index()].name() } else { c.name() };
                json!(["vel", m.body_name(*b), name])
            }
            MExpr::Neg(a) => json!(["neg", self.expr(a)]),
            MExpr::Bin(op, a, b) => {
                let op = match op {
                    MBin::Add => "add",
                    MBin::Sub => "sub",
                    MBin::Mul => "mul",
                    MBin::Div => "div",
                    MBin::Pow => "pow",
                };
                json!([op, self.expr(a), self.expr(b)])
            }
            MExpr::Call(f, a) => json!([f.name(), self.expr(a)]),
            MExpr::Atan2(y, x) => json!(["atan2", self.expr(y), self.expr(x)]),
            MExpr::Kink(k, args) => {
                let mut v = vec![json!(k.name())];
                v.extend(args.iter().map(|a| self.expr(a)));
                Value::Array(v)
            }
            MExpr::If(cmp, e) => {
                let op = match cmp {
                    Cmp::Gt => "if_gt",
                    Cmp::Ge => "if_ge",
                };
                let mut v = vec![json!(op)];
                v.extend(e.iter().map(|a| self.expr(a)));
                Value::Array(v)
            }
        }
    }

    pub fn opt(&self, e: &Option<MExpr>) -> Value {
        e.as_ref().map_or(Value::Null, |e| self.expr(e))
    }

    /// A point's or vector's components (or any list of expressions).
    pub fn list(&self, v: &[MExpr]) -> Value {
        Value::Array(v.iter().map(|e| self.expr(e)).collect())
    }

    pub fn body(&self, b: BodyRef) -> String {
        self.model.body_name(b)
    }

    pub fn loc(&self, l: &Loc) -> Value {
        json!({"body": self.body(l.body), "point": self.list(&l.point)})
    }

    pub fn loc_axis(&self, l: &Loc, axis: &[MExpr]) -> Value {
        json!({"body": self.body(l.body), "point": self.list(&l.point), "axis": self.list(axis)})
    }
}

/// `object` with `"kind"` and `"name"` added.
fn tagged(mut object: Value, kind: &str, name: &str) -> Value {
    if let Value::Object(map) = &mut object {
        map.insert("kind".to_string(), json!(kind));
        map.insert("name".to_string(), json!(name));
    }
    object
}

/// The model JSON text, with the formulation's row names, first rows and Jacobian pattern.
pub fn model_json(m: &Model, row_names: &[String], first_rows: &[usize], jacobian_pattern: &[(usize, usize)]) -> String {
    let cx = Ctx { model: m, first_rows };
    let locals = |list: &[crate::model::Local]| -> Vec<Value> {
        list.iter().map(|l| json!({"body": m.body_name(l.body), "name": l.name, "local": cx.list(&l.local)})).collect()
    };
    let body = |b: &crate::model::Body| match &b.inertia {
        Inertia::Planar(j) => json!({
            "name": b.name.to_string(), "mass": cx.expr(&b.mass), "inertia": cx.expr(j),
            "q0": cx.list(&b.q0), "qd0": cx.list(&b.v0),
        }),
        Inertia::Tensor(rows) => json!({
            "name": b.name.to_string(), "mass": cx.expr(&b.mass), "inertia": rows.iter().map(|r| cx.list(r)).collect::<Vec<_>>(),
            "q0": cx.list(&b.q0), "v0": cx.list(&b.v0),
        }),
    };
    let mut v = json!({
        "name": m.name.to_string(),
        "scalar": m.scalar.name(),
        "params": m.params.iter().map(|p| json!({"name": p.name.to_string(), "default": p.default})).collect::<Vec<_>>(),
        "bodies": m.bodies.iter().map(body).collect::<Vec<_>>(),
        "points": locals(&m.points),
        "vectors": locals(&m.vectors),
        "coordinates": m.coordinate_names(),
        "constraint_rows": row_names,
        "jacobian_pattern": jacobian_pattern.iter().map(|&(r, c)| json!([r, c])).collect::<Vec<_>>(),
        "constraints": m.constraints.iter().map(|c| tagged(c.kind.json(&cx), c.kind.kind(), &c.name)).collect::<Vec<_>>(),
        "gravity": m.gravity.as_ref().map_or(Value::Null, |g| cx.list(g)),
        "forces": m.forces.iter().map(|f| tagged(f.kind.json(&cx), f.kind.kind(), &f.name)).collect::<Vec<_>>(),
    });
    if let Value::Object(map) = &mut v {
        if m.space == Space::Spatial {
            map.insert("dimension".to_string(), json!(3));
            map.insert("velocities".to_string(), json!(m.velocity_names()));
        }
        if let Some(tree) = &m.tree {
            // joint coordinates: how each body hangs, parents first, and its slots in q and v
            let links: Vec<Value> = tree
                .order
                .iter()
                .map(|&k| {
                    let link = &tree.links[k];
                    json!({
                        "body": m.bodies[k].name.to_string(), "parent": m.body_name(link.parent),
                        "joint": link.joint.map(|j| m.constraints[j].name.clone()), "reversed": link.reversed,
                        "q": link.first, "nq": link.count, "v": link.first_v, "nv": link.count_v,
                    })
                })
                .collect();
            map.insert("tree".to_string(), json!(links));
            map.insert("velocities".to_string(), json!(m.velocity_names()));
        }
    }
    v.to_string()
}
