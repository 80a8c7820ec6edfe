//! Bodies: their fields, mass and inertia, initial pose and velocity, planar and spatial.

use super::*;

/// A body statement's fields by name; `false` when one is unknown or given twice (each reported).
pub(super) fn body_fields<'b>(r: &mut Resolver, b: &'b parse::BodyDef, known: &[&str], help: &str) -> (HashMap<String, &'b Value>, bool) {
    let mut fields: HashMap<String, &Value> = HashMap::new();
    let mut ok = true;
    for f in &b.fields {
        let key = f.name.to_string();
        if !known.contains(&key.as_str()) {
            let hint = parse::closest(&key, known, &[]);
            r.errors.push(f.name.span(), format!("unknown body field: expected {help}, found `{key}`{hint}"));
            ok = false;
            // A misspelt field stands for the field it is near, so it is not also missing.
            if let Some(near) = parse::nearest(&key, known, &[]) {
                fields.entry(near.to_string()).or_insert(&f.value);
            }
        } else if fields.insert(key.clone(), &f.value).is_some() {
            r.errors.push(f.name.span(), format!("duplicate field `{key}`: expected each field once, found `{key}` again; keep one"));
            ok = false;
        }
    }
    (fields, ok)
}

/// A required positive number field of a body (mass, planar inertia).
pub(super) fn positive_field(
    r: &mut Resolver,
    b: &parse::BodyDef,
    fields: &HashMap<String, &Value>,
    name: &str,
    unit: &str,
) -> Option<MExpr> {
    match fields.get(name) {
        None => {
            r.errors.push(
                b.name.span(),
                format!("body `{}` has no `{name}`: expected `{name}` in {unit}, e.g. `{name}: 1.0`, found none", b.name),
            );
            None
        }
        Some(Value::List(v)) => {
            r.errors.push(v.span, format!("`{name}` is a number: expected a number ({unit}), found a list"));
            None
        }
        Some(Value::Expr(e)) => {
            let m = r.expr(e, Scope::Params)?;
            if name == "inertia" && m.constant_value() == Some(0.0) {
                r.errors.at_expr(
                    e,
                    format!("the inertia of body `{0}` must be positive: expected a value above 0, found 0; a point mass is a particle, `particle {0} {{ mass: ..., at: [x, y] }}`", b.name),
                );
                return None;
            }
            check_positive(r.errors, &m, e, &format!("the {name} of body `{}`", b.name));
            Some(m)
        }
    }
}

/// An optional list field of a body with one of the allowed lengths (zeros when absent).
pub(super) fn list_field(
    r: &mut Resolver,
    fields: &HashMap<String, &Value>,
    name: &str,
    what: &str,
    lengths: &[usize],
) -> Option<Option<Vec<MExpr>>> {
    match fields.get(name) {
        None => Some(None),
        Some(Value::Expr(e)) => {
            r.errors.push(e.span, format!("`{name}` is a list: expected `[{what}]`, found a number"));
            None
        }
        Some(Value::List(v)) => {
            if !lengths.contains(&v.items.len()) {
                r.errors.push(v.span, format!("`{name}: [{what}]`: expected {} entries, found {}", lengths[0], v.items.len()));
                return None;
            }
            let items: Vec<Option<MExpr>> = v.items.iter().map(|e| r.expr(e, Scope::Params)).collect();
            items.into_iter().collect::<Option<Vec<_>>>().map(Some)
        }
    }
}

pub(super) fn zeros(n: usize) -> Vec<MExpr> {
    vec![MExpr::Num(0.0); n]
}

/// A body statement, planar or spatial.
pub(super) fn resolve_body(r: &mut Resolver, b: &parse::BodyDef) -> Option<Body> {
    match r.space {
        Space::Planar if b.particle => {
            let help = "`mass`, `at: [x, y]` or `velocity: [vx, vy]` (a particle)";
            let (fields, ok) = body_fields(r, b, &["mass", "at", "velocity"], help);
            let mass = positive_field(r, b, &fields, "mass", "kg");
            let q0 = list_field(r, &fields, "at", "x, y", &[2]);
            let v0 = list_field(r, &fields, "velocity", "vx, vy", &[2]);
            if !ok {
                return None;
            }
            let mass = mass?;
            let planar = |v: Option<Vec<MExpr>>| {
                let mut v = v.unwrap_or_else(|| zeros(2));
                v.push(MExpr::Num(0.0));
                v
            };
            Some(Body {
                name: b.name.clone(),
                particle: true,
                // J = m·(1 m)²: any positive value would do, since the angle is held; this one
                // keeps the angle's row as well scaled as the positions'.
                inertia: Inertia::Planar(mass.clone()),
                mass,
                q0: planar(q0?),
                v0: planar(v0?),
            })
        }
        Space::Planar => {
            let help = "`mass`, `inertia`, `at: [x, y, phi]` or `velocity: [vx, vy, omega]`";
            let (fields, ok) = body_fields(r, b, BODY_FIELDS, help);
            let mass = positive_field(r, b, &fields, "mass", "kg");
            let inertia = positive_field(r, b, &fields, "inertia", "kg·m² about the centre of mass");
            let q0 = list_field(r, &fields, "at", "x, y, phi", &[3]);
            let v0 = list_field(r, &fields, "velocity", "vx, vy, omega", &[3]);
            if !ok {
                return None;
            }
            Some(Body {
                name: b.name.clone(),
                particle: false,
                mass: mass?,
                inertia: Inertia::Planar(inertia?),
                q0: q0?.unwrap_or_else(|| zeros(3)),
                v0: v0?.unwrap_or_else(|| zeros(3)),
            })
        }
        Space::Spatial => spatial_body(r, b),
    }
}

/// A spatial body: mass, inertia tensor, initial pose (position and one of quaternion,
/// axis-angle or z-y-x angles) and twist (velocity, body-frame angular velocity).
pub(super) fn spatial_body(r: &mut Resolver, b: &parse::BodyDef) -> Option<Body> {
    if b.particle {
        let help = "`mass`, `at: [x, y, z]` or `velocity: [vx, vy, vz]` (a particle)";
        let (fields, ok) = body_fields(r, b, &["mass", "at", "velocity"], help);
        let mass = positive_field(r, b, &fields, "mass", "kg");
        let at = list_field(r, &fields, "at", "x, y, z", &[3]);
        let velocity = list_field(r, &fields, "velocity", "vx, vy, vz", &[3]);
        if !ok {
            return None;
        }
        let mass = mass?;
        let mut q0 = at?.unwrap_or_else(|| zeros(3));
        q0.extend([1.0, 0.0, 0.0, 0.0].map(MExpr::Num));
        let mut v0 = velocity?.unwrap_or_else(|| zeros(3));
        v0.extend(zeros(3));
        // J′ = m·(1 m)² I: any positive tensor would do, since the orientation is held.
        let j = |a: usize, c: usize| if a == c { mass.clone() } else { MExpr::Num(0.0) };
        let inertia = [[j(0, 0), j(0, 1), j(0, 2)], [j(1, 0), j(1, 1), j(1, 2)], [j(2, 0), j(2, 1), j(2, 2)]];
        return Some(Body { name: b.name.clone(), particle: true, mass, inertia: Inertia::Tensor(inertia), q0, v0 });
    }
    let help = "`mass`, `inertia: [Jxx, Jyy, Jzz]` or `[Jxx, Jyy, Jzz, Jxy, Jxz, Jyz]`, `at: [x, y, z]`, \
                one of `quaternion: [e0, e1, e2, e3]`, `axis_angle: [ax, ay, az, angle]`, `angles: [yaw, pitch, roll]`, \
                `velocity: [vx, vy, vz]` or `omega: [wx, wy, wz]` (body frame)";
    let (fields, ok) = body_fields(r, b, SPATIAL_BODY_FIELDS, help);
    let mass = positive_field(r, b, &fields, "mass", "kg");
    let inertia = match fields.get("inertia") {
        None => {
            r.errors.push(
                b.name.span(),
                format!("body `{}` has no `inertia`: expected `inertia: [Jxx, Jyy, Jzz]` (kg·m², body axes), found none", b.name),
            );
            None
        }
        Some(Value::Expr(e)) => {
            r.errors.push(e.span, "a spatial body's `inertia` is a list: expected `[Jxx, Jyy, Jzz]` or `[Jxx, Jyy, Jzz, Jxy, Jxz, Jyz]` (kg·m²), found a number");
            None
        }
        Some(Value::List(v)) => inertia_tensor(r, b, v),
    };
    let at = list_field(r, &fields, "at", "x, y, z", &[3]);
    let rotation = orientation(r, b, &fields);
    let velocity = list_field(r, &fields, "velocity", "vx, vy, vz", &[3]);
    let omega = list_field(r, &fields, "omega", "wx, wy, wz", &[3]);
    if !ok {
        return None;
    }
    let mut q0 = at?.unwrap_or_else(|| zeros(3));
    q0.extend(rotation?);
    let mut v0 = velocity?.unwrap_or_else(|| zeros(3));
    v0.extend(omega?.unwrap_or_else(|| zeros(3)));
    Some(Body { name: b.name.clone(), particle: false, mass: mass?, inertia: Inertia::Tensor(inertia?), q0, v0 })
}

/// `[Jxx, Jyy, Jzz]` or `[Jxx, Jyy, Jzz, Jxy, Jxz, Jyz]` as the symmetric tensor; constant
/// diagonal entries must be positive.
pub(super) fn inertia_tensor(r: &mut Resolver, b: &parse::BodyDef, v: &parse::VecLit) -> Option<[[MExpr; 3]; 3]> {
    if v.items.len() != 3 && v.items.len() != 6 {
        r.errors.push(
            v.span,
            format!("`inertia`: expected 3 entries `[Jxx, Jyy, Jzz]` or 6 `[Jxx, Jyy, Jzz, Jxy, Jxz, Jyz]`, found {}", v.items.len()),
        );
        return None;
    }
    let items: Vec<Option<MExpr>> = v.items.iter().map(|e| r.expr(e, Scope::Params)).collect();
    let items: Vec<MExpr> = items.into_iter().collect::<Option<_>>()?;
    for (k, axis) in ["Jxx", "Jyy", "Jzz"].iter().enumerate() {
        check_positive(r.errors, &items[k], &v.items[k], &format!("the moment of inertia {axis} of body `{}`", b.name));
    }
    let off = |k: usize| items.get(k).cloned().unwrap_or(MExpr::Num(0.0));
    let (xy, xz, yz) = (off(3), off(4), off(5));
    // A constant tensor with products must be positive definite (with parameters in it, the
    // solvers check it at run time, `Dynamics::check_inertia`).
    let values: Option<Vec<f64>> = [&items[0], &items[1], &items[2], &xy, &xz, &yz].iter().map(|e| e.constant_value()).collect();
    if let Some(&[jxx, jyy, jzz, jxy, jxz, jyz]) = values.as_deref() {
        let det = jxx * (jyy * jzz - jyz * jyz) - jxy * (jxy * jzz - jyz * jxz) + jxz * (jxy * jyz - jyy * jxz);
        let minors = [jxx, jxx * jyy - jxy * jxy, det];
        if jxx > 0.0 && jyy > 0.0 && jzz > 0.0 && !minors.iter().all(|&m| m > 0.0) {
            r.errors.push(
                v.span,
                format!(
                    "the inertia tensor of body `{}` must be positive definite: expected products of inertia small enough \
                     that every principal moment is positive, found [Jxx, Jyy, Jzz, Jxy, Jxz, Jyz] = \
                     [{jxx}, {jyy}, {jzz}, {jxy}, {jxz}, {jyz}]",
                    b.name
                ),
            );
        }
    }
    Some([[items[0].clone(), xy.clone(), xz.clone()], [xy, items[1].clone(), yz.clone()], [xz, yz, items[2].clone()]])
}

pub(super) fn bin(op: MBin, a: MExpr, b: MExpr) -> MExpr {
    MExpr::Bin(op, Box::new(a), Box::new(b))
}

pub(super) fn call(f: Func, a: MExpr) -> MExpr {
    MExpr::Call(f, Box::new(a))
}

/// The initial Euler parameters (e0, e1, e2, e3) of a spatial body from at most one of
/// `quaternion` (normalized here), `axis_angle` (a unit turn about the normalized axis) or
/// `angles` (yaw ψ about z, then pitch θ about the new y, then roll φ about the new x:
/// A = R_z(ψ) R_y(θ) R_x(φ)); the identity when none is given.
pub(super) fn orientation(r: &mut Resolver, b: &parse::BodyDef, fields: &HashMap<String, &Value>) -> Option<Vec<MExpr>> {
    let given: Vec<&str> = ["quaternion", "axis_angle", "angles"].into_iter().filter(|k| fields.contains_key(*k)).collect();
    if given.len() > 1 {
        r.errors.push(
            b.name.span(),
            format!(
                "body `{}` gives its orientation twice: expected one of `quaternion`, `axis_angle` or `angles`, found `{}`; keep one",
                b.name,
                given.join("` and `")
            ),
        );
        return None;
    }
    let norm = |v: &[MExpr]| {
        let sum = v.iter().map(|c| bin(MBin::Pow, c.clone(), MExpr::Num(2.0))).reduce(|a, c| bin(MBin::Add, a, c));
        call(Func::Sqrt, sum.unwrap_or(MExpr::Num(0.0)))
    };
    let half = |a: &MExpr| bin(MBin::Mul, MExpr::Num(0.5), a.clone());
    Some(match given.first() {
        None => vec![MExpr::Num(1.0), MExpr::Num(0.0), MExpr::Num(0.0), MExpr::Num(0.0)],
        Some(&"quaternion") => {
            let p = list_field(r, fields, "quaternion", "e0, e1, e2, e3", &[4])??;
            let n = norm(&p);
            p.into_iter().map(|e| bin(MBin::Div, e, n.clone())).collect()
        }
        Some(&"axis_angle") => {
            let v = list_field(r, fields, "axis_angle", "ax, ay, az, angle", &[4])??;
            let n = norm(&v[..3]);
            let s = call(Func::Sin, half(&v[3]));
            let mut p = vec![call(Func::Cos, half(&v[3]))];
            p.extend(v[..3].iter().map(|a| bin(MBin::Mul, s.clone(), bin(MBin::Div, a.clone(), n.clone()))));
            p
        }
        Some(_) => {
            let v = list_field(r, fields, "angles", "yaw, pitch, roll", &[3])??;
            let [(sy, cy), (sp, cp), (sr, cr)] = [0, 1, 2].map(|k| (call(Func::Sin, half(&v[k])), call(Func::Cos, half(&v[k]))));
            let prod = |a: &MExpr, b: &MExpr, c: &MExpr| bin(MBin::Mul, bin(MBin::Mul, a.clone(), b.clone()), c.clone());
            vec![
                bin(MBin::Add, prod(&cr, &cp, &cy), prod(&sr, &sp, &sy)),
                bin(MBin::Sub, prod(&sr, &cp, &cy), prod(&cr, &sp, &sy)),
                bin(MBin::Add, prod(&cr, &sp, &cy), prod(&sr, &cp, &sy)),
                bin(MBin::Sub, prod(&cr, &cp, &sy), prod(&sr, &sp, &cy)),
            ]
        }
    })
}
