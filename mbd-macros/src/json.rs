//! The model's JSON description (`Mechanism::MODEL_JSON`, schema in docs/formulation.md), written
//! from the validated model — not from the symbolic graph — so the CasADi oracle rebuilds the
//! equations from the same joint definitions the user wrote, independently of `sym`.

use serde_json::{json, Value};

use crate::model::{BodyRef, ConstraintKind, ForceKind, Loc, MBin, MExpr, Model};

fn expr(m: &Model, e: &MExpr) -> Value {
    match e {
        MExpr::Num(v) => json!(["num", v]),
        MExpr::Pi => json!(["pi"]),
        MExpr::T => json!(["t"]),
        MExpr::Param(k) => json!(["param", m.params[*k].name.to_string()]),
        MExpr::Coord(b, c) => json!(["coord", m.body_name(*b), c.name()]),
        MExpr::Vel(b, c) => json!(["vel", m.body_name(*b), c.name()]),
        MExpr::Neg(a) => json!(["neg", expr(m, a)]),
        MExpr::Bin(op, a, b) => {
            let op = match op {
                MBin::Add => "add",
                MBin::Sub => "sub",
                MBin::Mul => "mul",
                MBin::Div => "div",
                MBin::Pow => "pow",
            };
            json!([op, expr(m, a), expr(m, b)])
        }
        MExpr::Call(f, a) => json!([f.name(), expr(m, a)]),
        MExpr::Atan2(y, x) => json!(["atan2", expr(m, y), expr(m, x)]),
    }
}

fn pair(m: &Model, v: &[MExpr; 2]) -> Value {
    json!([expr(m, &v[0]), expr(m, &v[1])])
}

fn loc(m: &Model, l: &Loc) -> Value {
    json!({"body": m.body_name(l.body), "point": pair(m, &l.point)})
}

fn loc_axis(m: &Model, l: &Loc, axis: &[MExpr; 2]) -> Value {
    json!({"body": m.body_name(l.body), "point": pair(m, &l.point), "axis": pair(m, axis)})
}

fn constraint(m: &Model, name: &str, k: &ConstraintKind) -> Value {
    let body = |b: usize| m.body_name(BodyRef::Body(b));
    match k {
        ConstraintKind::Revolute { i, j } => json!({"kind": "revolute", "name": name, "i": loc(m, i), "j": loc(m, j)}),
        ConstraintKind::Translational { i, axis_i, j, axis_j } => {
            json!({"kind": "translational", "name": name, "i": loc_axis(m, i, axis_i), "j": loc_axis(m, j, axis_j)})
        }
        ConstraintKind::RevoluteRevolute { i, j, length } => {
            json!({"kind": "revolute_revolute", "name": name, "i": loc(m, i), "j": loc(m, j), "length": expr(m, length)})
        }
        ConstraintKind::RevoluteTranslational { i, j, axis_j, distance } => json!({
            "kind": "revolute_translational", "name": name, "i": loc(m, i), "j": loc_axis(m, j, axis_j),
            "distance": expr(m, distance)
        }),
        ConstraintKind::Rigid { i, j, angle } => {
            json!({"kind": "rigid", "name": name, "i": loc(m, i), "j": loc(m, j), "angle": expr(m, angle)})
        }
        ConstraintKind::Fix { body: b, coord, value } => {
            json!({"kind": "fix", "name": name, "body": body(*b), "coordinate": coord.name(), "value": expr(m, value)})
        }
        ConstraintKind::Drive { body: b, coord, f } => {
            json!({"kind": "drive", "name": name, "body": body(*b), "coordinate": coord.name(), "f": expr(m, f)})
        }
        ConstraintKind::DriveAngle { i, j, f } => {
            json!({"kind": "drive_angle", "name": name, "i": m.body_name(*i), "j": m.body_name(*j), "f": expr(m, f)})
        }
        ConstraintKind::DriveDistance { i, j, f } => {
            json!({"kind": "drive_distance", "name": name, "i": loc(m, i), "j": loc(m, j), "f": expr(m, f)})
        }
        ConstraintKind::User { expr: e } => json!({"kind": "constraint", "name": name, "expr": expr(m, e)}),
    }
}

fn opt(m: &Model, e: &Option<MExpr>) -> Value {
    e.as_ref().map_or(Value::Null, |e| expr(m, e))
}

fn force(m: &Model, name: &str, k: &ForceKind) -> Value {
    match k {
        ForceKind::PointToPoint { i, j, k, length, c, force } => json!({
            "kind": "point_to_point", "name": name, "i": loc(m, i), "j": loc(m, j),
            "k": opt(m, k), "length": expr(m, length), "c": opt(m, c), "force": opt(m, force)
        }),
        ForceKind::Rotational { i, j, k, angle, c, torque } => json!({
            "kind": "rotational", "name": name, "i": m.body_name(*i), "j": m.body_name(*j),
            "k": opt(m, k), "angle": expr(m, angle), "c": opt(m, c), "torque": opt(m, torque)
        }),
        ForceKind::Applied { at, force, local } => {
            json!({"kind": if *local { "local_force" } else { "force" }, "name": name, "at": loc(m, at), "force": pair(m, force)})
        }
        ForceKind::Torque { body, torque } => {
            json!({"kind": "torque", "name": name, "body": m.body_name(BodyRef::Body(*body)), "torque": expr(m, torque)})
        }
        ForceKind::RevoluteViscous { i, j, c } => {
            json!({"kind": "revolute_viscous", "name": name, "i": m.body_name(*i), "j": m.body_name(*j), "c": expr(m, c)})
        }
        ForceKind::TranslationalViscous { i, axis_i, j, c } => {
            json!({"kind": "translational_viscous", "name": name, "i": loc_axis(m, i, axis_i), "j": loc(m, j), "c": expr(m, c)})
        }
        ForceKind::RevoluteCoulomb { i, j, mu, radius, slip, row } => json!({
            "kind": "revolute_coulomb", "name": name, "i": m.body_name(*i), "j": m.body_name(*j),
            "mu": expr(m, mu), "radius": expr(m, radius), "slip_velocity": expr(m, slip), "row": row
        }),
        ForceKind::TranslationalCoulomb { i, axis_i, j, mu, slip, bearing, row } => json!({
            "kind": "translational_coulomb", "name": name, "i": loc_axis(m, i, axis_i), "j": loc(m, j),
            "mu": expr(m, mu), "slip_velocity": expr(m, slip), "bearing": bearing.as_ref().map(|w| expr(m, w)), "row": row
        }),
    }
}

/// The model JSON text.
pub fn model_json(m: &Model, jacobian_pattern: &[(usize, usize)]) -> String {
    let locals = |list: &[crate::model::Local]| -> Vec<Value> {
        list.iter().map(|l| json!({"body": m.body_name(l.body), "name": l.name, "local": pair(m, &l.local)})).collect()
    };
    let v = json!({
        "name": m.name.to_string(),
        "scalar": m.scalar.name(),
        "params": m.params.iter().map(|p| json!({"name": p.name.to_string(), "default": p.default})).collect::<Vec<_>>(),
        "bodies": m.bodies.iter().map(|b| json!({
            "name": b.name.to_string(),
            "mass": expr(m, &b.mass),
            "inertia": expr(m, &b.inertia),
            "q0": b.q0.iter().map(|e| expr(m, e)).collect::<Vec<_>>(),
            "qd0": b.qd0.iter().map(|e| expr(m, e)).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
        "points": locals(&m.points),
        "vectors": locals(&m.vectors),
        "coordinates": m.coordinate_names(),
        "constraint_rows": m.row_names(),
        "jacobian_pattern": jacobian_pattern.iter().map(|&(r, c)| json!([r, c])).collect::<Vec<_>>(),
        "constraints": m.constraints.iter().map(|c| constraint(m, &c.name, &c.kind)).collect::<Vec<_>>(),
        "gravity": m.gravity.as_ref().map_or(Value::Null, |g| pair(m, g)),
        "forces": m.forces.iter().map(|f| force(m, &f.name, &f.kind)).collect::<Vec<_>>(),
    });
    v.to_string()
}
