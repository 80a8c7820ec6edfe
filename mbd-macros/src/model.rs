//! Stage 2: syntax tree → validated model. Every name is resolved here and every rule a user can
//! break is checked here, each mistake reported as a `syn::Error` on the offending token. All
//! mistakes are collected in one pass ([`Errors`]) so one compile shows them all.

use std::collections::{HashMap, HashSet};

use proc_macro2::Span;
use syn::{Attribute, Ident, Visibility};

use crate::elements::{self, drive, drive_angle, drive_distance, fix, user, Constraint, Driven};
use crate::forces::{applied, point_to_point, rotational, torque, ForceElement};
use crate::parse::{self, AxisRef, BinOp, DriveTarget, Expr, ExprKind, Item, MechanismDef, PointRef, Value, VecLit};
use crate::sym::Func;

/// The errors of one expansion, combined into one at the end.
#[derive(Default)]
pub struct Errors(Vec<syn::Error>);

impl Errors {
    pub fn push(&mut self, span: Span, msg: impl std::fmt::Display) {
        self.0.push(syn::Error::new(span, msg));
    }
    /// An error underlining a whole expression.
    pub fn at_expr(&mut self, e: &Expr, msg: impl std::fmt::Display) {
        self.0.push(e.error(msg));
    }
    pub fn into_result(self) -> Result<(), syn::Error> {
        let mut it = self.0.into_iter();
        match it.next() {
            None => Ok(()),
            Some(mut first) => {
                first.extend(it);
                Err(first)
            }
        }
    }
}

/// The scalar type of the generated code.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Scalar {
    F32,
    F64,
}

impl Scalar {
    pub fn name(self) -> &'static str {
        match self {
            Scalar::F32 => "f32",
            Scalar::F64 => "f64",
        }
    }
}

/// Ground or a moving body, by index.
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum BodyRef {
    Ground,
    Body(usize),
}

/// A body coordinate: x, y (m) or φ (rad).
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum Coord {
    X,
    Y,
    Phi,
}

impl Coord {
    pub fn name(self) -> &'static str {
        match self {
            Coord::X => "x",
            Coord::Y => "y",
            Coord::Phi => "phi",
        }
    }
    pub fn index(self) -> usize {
        match self {
            Coord::X => 0,
            Coord::Y => 1,
            Coord::Phi => 2,
        }
    }
    pub fn from_ident(id: &Ident) -> Option<Coord> {
        match id.to_string().as_str() {
            "x" => Some(Coord::X),
            "y" => Some(Coord::Y),
            "phi" => Some(Coord::Phi),
            _ => None,
        }
    }
    fn from_velocity_ident(id: &Ident) -> Option<Coord> {
        match id.to_string().as_str() {
            "vx" => Some(Coord::X),
            "vy" => Some(Coord::Y),
            "omega" => Some(Coord::Phi),
            _ => None,
        }
    }
}

/// A resolved expression.
#[derive(Clone, Debug)]
pub enum MExpr {
    Num(f64),
    Pi,
    T,
    Param(usize),
    Coord(BodyRef, Coord),
    /// A body velocity ẋ, ẏ or φ̇ (force expressions only).
    Vel(BodyRef, Coord),
    Neg(Box<MExpr>),
    Bin(MBin, Box<MExpr>, Box<MExpr>),
    Call(Func, Box<MExpr>),
    Atan2(Box<MExpr>, Box<MExpr>),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MBin {
    Add,
    Sub,
    Mul,
    Div,
    Pow,
}

impl MExpr {
    /// The value of an expression made of numbers, `PI` and functions only.
    pub fn constant_value(&self) -> Option<f64> {
        Some(match self {
            MExpr::Num(v) => *v,
            MExpr::Pi => std::f64::consts::PI,
            MExpr::T | MExpr::Param(_) | MExpr::Coord(..) | MExpr::Vel(..) => return None,
            MExpr::Neg(a) => -a.constant_value()?,
            MExpr::Bin(op, a, b) => {
                let (a, b) = (a.constant_value()?, b.constant_value()?);
                match op {
                    MBin::Add => a + b,
                    MBin::Sub => a - b,
                    MBin::Mul => a * b,
                    MBin::Div => a / b,
                    MBin::Pow => a.powf(b),
                }
            }
            MExpr::Call(f, a) => {
                let a = a.constant_value()?;
                match f {
                    Func::Sin => a.sin(),
                    Func::Cos => a.cos(),
                    Func::Tan => a.tan(),
                    Func::Asin => a.asin(),
                    Func::Acos => a.acos(),
                    Func::Atan => a.atan(),
                    Func::Sqrt => a.sqrt(),
                    Func::Exp => a.exp(),
                    Func::Ln => a.ln(),
                }
            }
            MExpr::Atan2(y, x) => y.constant_value()?.atan2(x.constant_value()?),
        })
    }
}

/// What an expression may refer to, by where it stands.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Scope {
    /// Numbers, `PI` and functions: parameter defaults.
    Constant,
    /// Also parameters: geometry, masses, initial values.
    Params,
    /// Also `t`: drivers.
    Time,
    /// Also coordinates: user constraints.
    State,
    /// Also velocities: forces.
    Force,
}

impl Scope {
    fn describe(self) -> &'static str {
        match self {
            Scope::Constant => "a parameter default is a constant: numbers, `PI` and functions of them",
            Scope::Params => "geometry, masses and initial values may use numbers, `PI` and parameters, not `t` or coordinates",
            Scope::Time => "a driver is a function of `t` and parameters, not of coordinates",
            Scope::State => "a constraint is a function of coordinates, `t` and parameters, not of velocities",
            Scope::Force => "",
        }
    }
}

pub struct Param {
    pub name: Ident,
    pub default: f64,
}

pub struct Body {
    pub name: Ident,
    pub mass: MExpr,
    pub inertia: MExpr,
    /// Initial guess of (x, y, φ).
    pub q0: [MExpr; 3],
    /// Initial velocities (ẋ, ẏ, φ̇).
    pub qd0: [MExpr; 3],
}

/// A named point or vector, local to its body.
pub struct Local {
    pub body: BodyRef,
    pub name: String,
    pub local: [MExpr; 2],
}

/// A point on a body, by its body-fixed coordinates.
#[derive(Clone, Debug)]
pub struct Loc {
    pub body: BodyRef,
    pub point: [MExpr; 2],
}

/// A validated mechanism.
pub struct Model {
    pub attrs: Vec<Attribute>,
    pub vis: Visibility,
    pub name: Ident,
    pub scalar: Scalar,
    pub params: Vec<Param>,
    pub bodies: Vec<Body>,
    pub points: Vec<Local>,
    pub vectors: Vec<Local>,
    pub constraints: Vec<Constraint>,
    /// Gravitational acceleration (m/s²), if declared.
    pub gravity: Option<[MExpr; 2]>,
    pub forces: Vec<ForceElement>,
}

impl Model {
    pub fn body_name(&self, b: BodyRef) -> String {
        match b {
            BodyRef::Ground => "ground".to_string(),
            BodyRef::Body(k) => self.bodies[k].name.to_string(),
        }
    }
    /// Coordinate names, `"crank.phi"`.
    pub fn coordinate_names(&self) -> Vec<String> {
        self.bodies.iter().flat_map(|b| ["x", "y", "phi"].into_iter().map(move |c| format!("{}.{}", b.name, c))).collect()
    }
}

/// What a partially invalid mechanism still yields, so the macro can emit its type and keep
/// follow-up errors quiet.
pub struct Partial {
    pub attrs: Vec<Attribute>,
    pub vis: Visibility,
    pub name: Ident,
    pub scalar: Scalar,
    pub params: Vec<Ident>,
}

pub struct Resolver<'a> {
    pub errors: &'a mut Errors,
    params: HashMap<String, usize>,
    bodies: HashMap<String, usize>,
    points: HashMap<(BodyRef, String), [MExpr; 2]>,
    vectors: HashMap<(BodyRef, String), [MExpr; 2]>,
}

const BODY_FIELDS: &[&str] = &["mass", "inertia", "at", "velocity"];
const FUNCTIONS: &[&str] = &["sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sqrt", "exp", "ln", "pow"];

impl Resolver<'_> {
    pub fn body(&mut self, id: &Ident) -> Option<BodyRef> {
        if id == "ground" {
            return Some(BodyRef::Ground);
        }
        match self.bodies.get(&id.to_string()) {
            Some(&k) => Some(BodyRef::Body(k)),
            None => {
                let names: Vec<&str> = self.bodies.keys().map(|s| s.as_str()).collect();
                let hint = parse::closest(&id.to_string(), &names, &["ground"]);
                self.errors
                    .push(id.span(), format!("unknown body `{id}`{hint}: declare it with `body {id} {{ mass: ..., inertia: ... }}`"));
                None
            }
        }
    }

    pub fn expr(&mut self, e: &Expr, scope: Scope) -> Option<MExpr> {
        Some(match &e.kind {
            ExprKind::Num(v) => MExpr::Num(*v),
            ExprKind::Ident(id) => {
                let s = id.to_string();
                if s == "PI" {
                    MExpr::Pi
                } else if s == "t" {
                    if matches!(scope, Scope::Constant | Scope::Params) {
                        self.errors.push(id.span(), format!("time `t` is not allowed here: {}", scope.describe()));
                        return None;
                    }
                    MExpr::T
                } else if let Some(&k) = self.params.get(&s) {
                    if scope == Scope::Constant {
                        self.errors.push(id.span(), format!("parameter `{s}` is not allowed here: {}", scope.describe()));
                        return None;
                    }
                    MExpr::Param(k)
                } else {
                    let names: Vec<&str> = self.params.keys().map(|s| s.as_str()).collect();
                    let hint = parse::closest(&s, &names, &["t", "PI"]);
                    self.errors.push(
                        id.span(),
                        format!("unknown identifier `{s}`{hint}: an expression may use numbers, parameters declared in `params {{ }}`, `t`, `PI` and coordinates like `crank.phi`"),
                    );
                    return None;
                }
            }
            ExprKind::Coord(b, c) => {
                let position = Coord::from_ident(c);
                let velocity = Coord::from_velocity_ident(c);
                if position.is_none() && velocity.is_none() {
                    self.errors.push(
                        c.span(),
                        format!("unknown coordinate `{c}`: a body has `x`, `y`, `phi` and, in forces, velocities `vx`, `vy`, `omega`"),
                    );
                    return None;
                }
                let allowed = matches!((position, scope), (Some(_), Scope::State | Scope::Force) | (None, Scope::Force));
                if !allowed {
                    let what = if position.is_some() { "coordinate" } else { "velocity" };
                    self.errors.at_expr(e, format!("{what} `{b}.{c}` is not allowed here: {}", scope.describe()));
                    return None;
                }
                let body = self.body(b)?;
                match (position, velocity) {
                    (Some(coord), _) => MExpr::Coord(body, coord),
                    (None, Some(coord)) => MExpr::Vel(body, coord),
                    (None, None) => return None,
                }
            }
            ExprKind::Neg(a) => MExpr::Neg(Box::new(self.expr(a, scope)?)),
            ExprKind::Bin(op, a, b) => {
                let a = self.expr(a, scope);
                let b = self.expr(b, scope);
                let op = match op {
                    BinOp::Add => MBin::Add,
                    BinOp::Sub => MBin::Sub,
                    BinOp::Mul => MBin::Mul,
                    BinOp::Div => MBin::Div,
                    BinOp::Pow => MBin::Pow,
                };
                MExpr::Bin(op, Box::new(a?), Box::new(b?))
            }
            ExprKind::Call(f, args) => {
                let name = f.to_string();
                let arity = match name.as_str() {
                    "atan2" | "pow" => 2,
                    n if Func::from_name(n).is_some() => 1,
                    _ => {
                        let hint = parse::closest(&name, FUNCTIONS, &[]);
                        self.errors.push(
                            f.span(),
                            format!(
                                "unknown function `{name}`{hint}: available are sin, cos, tan, asin, acos, atan, atan2, sqrt, exp, ln, pow"
                            ),
                        );
                        return None;
                    }
                };
                if args.len() != arity {
                    self.errors
                        .at_expr(e, format!("`{name}` takes {arity} argument{}, found {}", if arity == 1 { "" } else { "s" }, args.len()));
                    return None;
                }
                let resolved: Vec<Option<MExpr>> = args.iter().map(|a| self.expr(a, scope)).collect();
                let mut resolved = resolved.into_iter().collect::<Option<Vec<_>>>()?.into_iter();
                let a = Box::new(resolved.next()?);
                match name.as_str() {
                    "atan2" => MExpr::Atan2(a, Box::new(resolved.next()?)),
                    "pow" => MExpr::Bin(MBin::Pow, a, Box::new(resolved.next()?)),
                    n => MExpr::Call(Func::from_name(n)?, a),
                }
            }
        })
    }

    /// A bracketed list of exactly `N` expressions.
    pub fn list<const N: usize>(&mut self, v: &VecLit, scope: Scope, what: &str) -> Option<[MExpr; N]> {
        if v.items.len() != N {
            self.errors.push(v.span, format!("{what} has {N} entries, found {}", v.items.len()));
            return None;
        }
        let items: Vec<Option<MExpr>> = v.items.iter().map(|e| self.expr(e, scope)).collect();
        let items: Vec<MExpr> = items.into_iter().collect::<Option<_>>()?;
        items.try_into().ok()
    }

    pub fn point(&mut self, body: BodyRef, p: &PointRef) -> Option<[MExpr; 2]> {
        match p {
            PointRef::Inline(v) => self.list::<2>(v, Scope::Params, "a point `[ξ, η]` in body coordinates"),
            PointRef::Named(name) => match self.points.get(&(body, name.to_string())) {
                Some(p) => Some(p.clone()),
                None => {
                    self.errors
                        .push(name.span(), format!("unknown point `{name}` on this body: declare it with `point body.{name} = [ξ, η];`"));
                    None
                }
            },
        }
    }

    pub fn loc(&mut self, body_id: &Ident, p: &PointRef) -> Option<Loc> {
        let body = self.body(body_id)?;
        let point = self.point(body, p)?;
        Some(Loc { body, point })
    }

    pub fn axis(&mut self, body: BodyRef, a: &AxisRef) -> Option<[MExpr; 2]> {
        match a {
            AxisRef::Inline(v) => {
                let axis = self.list::<2>(v, Scope::Params, "an axis `[x, y]` in body coordinates")?;
                if let (Some(x), Some(y)) = (axis[0].constant_value(), axis[1].constant_value()) {
                    if x == 0.0 && y == 0.0 {
                        self.errors.push(v.span, "an axis must not be the zero vector");
                        return None;
                    }
                }
                Some(axis)
            }
            AxisRef::Named(b, name) => {
                if self.body(b)? != body {
                    self.errors.push(b.span(), "the axis must be a vector of the same body as the point");
                    return None;
                }
                match self.vectors.get(&(body, name.to_string())) {
                    Some(v) => Some(v.clone()),
                    None => {
                        self.errors.push(name.span(), format!("unknown vector `{name}`: declare it with `vector {b}.{name} = [x, y];`"));
                        None
                    }
                }
            }
        }
    }
}

/// The name of a joint, driver, constraint or force element — its label, or its default name —
/// if no other statement has it yet; otherwise an error on the label or the statement's keyword.
fn claim_name(
    names: &mut HashMap<String, Span>,
    errors: &mut Errors,
    label: Option<&Ident>,
    default_name: String,
    span: Span,
) -> Option<String> {
    let (name, span) = match label {
        Some(l) => (l.to_string(), l.span()),
        None => (default_name, span),
    };
    if names.insert(name.clone(), span).is_none() {
        return Some(name);
    }
    let msg = if label.is_some() {
        format!("duplicate name `{name}`")
    } else {
        format!("a second `{name}`: give one of them a name, e.g. `{} name: ...`", name.split(' ').next().unwrap_or(""))
    };
    errors.push(span, msg);
    None
}

/// Checks a number that must be positive when it is a constant (a parameter's value is checked
/// at run time by the solver that needs it).
pub fn check_positive(errors: &mut Errors, e: &MExpr, written: &Expr, what: &str) {
    if let Some(v) = e.constant_value() {
        #[allow(clippy::neg_cmp_op_on_partial_ord)] // NaN is not positive either
        if !(v > 0.0) {
            errors.at_expr(written, format!("{what} must be positive, found {v}"));
        }
    }
}

impl MechanismDef {
    /// What survives of the mechanism's outline even when its body has mistakes.
    pub fn partial(&self) -> Partial {
        let mut scalar = Scalar::F64;
        let mut params = Vec::new();
        for item in &self.items {
            match item {
                Item::Scalar(s) if s == "f32" => scalar = Scalar::F32,
                Item::Params(ps) => params.extend(ps.iter().map(|(n, _)| n.clone())),
                _ => {}
            }
        }
        let mut seen = HashSet::new();
        params.retain(|p| seen.insert(p.to_string()));
        Partial { attrs: self.attrs.clone(), vis: self.vis.clone(), name: self.name.clone(), scalar, params }
    }

    /// Resolves and validates the mechanism.
    pub fn validate(&self) -> syn::Result<Model> {
        let mut errors = Errors::default();
        let model = self.build(&mut errors);
        errors.into_result()?;
        model.ok_or_else(|| syn::Error::new(self.name.span(), "invalid mechanism"))
    }

    fn build(&self, errors: &mut Errors) -> Option<Model> {
        let mut scalar = None::<(Scalar, Span)>;
        let mut r = Resolver { errors, params: HashMap::new(), bodies: HashMap::new(), points: HashMap::new(), vectors: HashMap::new() };
        let mut params = Vec::new();
        let mut bodies = Vec::new();
        let mut ok = true;

        // Pass 1: declarations (params, bodies) so statements can refer to them in any order.
        for item in &self.items {
            match item {
                Item::Scalar(s) => {
                    let sc = match s.to_string().as_str() {
                        "f64" => Scalar::F64,
                        "f32" => Scalar::F32,
                        other => {
                            r.errors.push(s.span(), format!("unsupported scalar type `{other}`: use `f64` or `f32`"));
                            continue;
                        }
                    };
                    if scalar.is_some() {
                        r.errors.push(s.span(), "the scalar type is declared twice");
                    }
                    scalar = Some((sc, s.span()));
                }
                Item::Params(ps) => {
                    for (name, value) in ps {
                        if r.params.contains_key(&name.to_string()) {
                            r.errors.push(name.span(), format!("duplicate parameter `{name}`"));
                            ok = false;
                            continue;
                        }
                        if ["t", "PI", "ground"].contains(&name.to_string().as_str()) {
                            r.errors.push(name.span(), format!("`{name}` is reserved and cannot name a parameter"));
                            ok = false;
                            continue;
                        }
                        let Some(default) = r.expr(value, Scope::Constant) else {
                            ok = false;
                            continue;
                        };
                        let default = default.constant_value().unwrap_or(f64::NAN);
                        if !default.is_finite() {
                            r.errors.at_expr(value, format!("the default of `{name}` evaluates to {default}"));
                            ok = false;
                            continue;
                        }
                        r.params.insert(name.to_string(), params.len());
                        params.push(Param { name: name.clone(), default });
                    }
                }
                Item::Body(b) => {
                    if b.name == "ground" {
                        r.errors.push(b.name.span(), "`ground` is the fixed frame, always present: it cannot be declared as a body");
                        ok = false;
                        continue;
                    }
                    if r.bodies.contains_key(&b.name.to_string()) {
                        r.errors.push(b.name.span(), format!("duplicate body `{}`", b.name));
                        ok = false;
                        continue;
                    }
                    r.bodies.insert(b.name.to_string(), bodies.len());
                    bodies.push(b);
                }
                _ => {}
            }
        }

        let mut model_bodies = Vec::new();
        for b in &bodies {
            let mut fields: HashMap<String, &Value> = HashMap::new();
            for f in &b.fields {
                let key = f.name.to_string();
                if !BODY_FIELDS.contains(&key.as_str()) {
                    let hint = parse::closest(&key, BODY_FIELDS, &[]);
                    r.errors.push(f.name.span(), format!("unknown body field `{key}`{hint}: a body has `mass`, `inertia`, `at: [x, y, phi]` and `velocity: [vx, vy, omega]`"));
                    ok = false;
                } else if fields.insert(key.clone(), &f.value).is_some() {
                    r.errors.push(f.name.span(), format!("duplicate field `{key}`"));
                    ok = false;
                }
            }
            let scalar_field = |r: &mut Resolver, name: &str, unit: &str| -> Option<MExpr> {
                match fields.get(name) {
                    None => {
                        r.errors.push(b.name.span(), format!("body `{}` has no `{name}`: give it in {unit}, e.g. `{name}: 1.0`", b.name));
                        None
                    }
                    Some(Value::List(v)) => {
                        r.errors.push(v.span, format!("`{name}` is a number ({unit}), not a list"));
                        None
                    }
                    Some(Value::Expr(e)) => {
                        let m = r.expr(e, Scope::Params)?;
                        check_positive(r.errors, &m, e, &format!("the {name} of body `{}`", b.name));
                        Some(m)
                    }
                }
            };
            let mass = scalar_field(&mut r, "mass", "kg");
            let inertia = scalar_field(&mut r, "inertia", "kg·m² about the centre of mass");
            let vec3 = |r: &mut Resolver, name: &str, what: &str| -> Option<[MExpr; 3]> {
                match fields.get(name) {
                    None => Some([MExpr::Num(0.0), MExpr::Num(0.0), MExpr::Num(0.0)]),
                    Some(Value::Expr(e)) => {
                        r.errors.push(e.span, format!("`{name}` is a list `[{what}]`"));
                        None
                    }
                    Some(Value::List(v)) => r.list::<3>(v, Scope::Params, &format!("`{name}: [{what}]`")),
                }
            };
            let q0 = vec3(&mut r, "at", "x, y, phi");
            let qd0 = vec3(&mut r, "velocity", "vx, vy, omega");
            match (mass, inertia, q0, qd0) {
                (Some(mass), Some(inertia), Some(q0), Some(qd0)) => {
                    model_bodies.push(Body { name: b.name.clone(), mass, inertia, q0, qd0 });
                }
                _ => ok = false,
            }
        }

        // Pass 2: points and vectors, then joints, drivers and constraints in declaration order.
        let mut points = Vec::new();
        let mut vectors = Vec::new();
        for item in &self.items {
            let (nv, is_point) = match item {
                Item::Point(nv) => (nv, true),
                Item::Vector(nv) => (nv, false),
                _ => continue,
            };
            let Some(body) = r.body(&nv.body) else {
                ok = false;
                continue;
            };
            let what = if is_point { "a point `[ξ, η]` in body coordinates (m)" } else { "a vector `[x, y]` in body coordinates" };
            let Some(local) = r.list::<2>(&nv.value, Scope::Params, what) else {
                ok = false;
                continue;
            };
            let key = (body, nv.name.to_string());
            let table = if is_point { &mut r.points } else { &mut r.vectors };
            if table.insert(key, local.clone()).is_some() {
                r.errors.push(nv.name.span(), format!("duplicate {} `{}.{}`", if is_point { "point" } else { "vector" }, nv.body, nv.name));
                ok = false;
                continue;
            }
            let l = Local { body, name: nv.name.to_string(), local };
            if is_point {
                points.push(l);
            } else {
                vectors.push(l);
            }
        }

        let body_name = |b: BodyRef| match b {
            BodyRef::Ground => "ground".to_string(),
            BodyRef::Body(k) => bodies[k].name.to_string(),
        };
        let mut names: HashMap<String, Span> = HashMap::new();
        let (constraints, mut forces) = constraints(&self.items, &mut r, &mut names, &model_bodies, &body_name, &mut ok);
        let gravity = force_elements(&self.items, &mut r, &mut names, &body_name, &mut forces, &mut ok);

        if bodies.is_empty() {
            r.errors.push(self.name.span(), "a mechanism needs at least one body: `body name { mass: ..., inertia: ... }`");
            ok = false;
        }
        if !ok {
            return None;
        }
        Some(Model {
            attrs: self.attrs.clone(),
            vis: self.vis.clone(),
            name: self.name.clone(),
            scalar: scalar.map(|(s, _)| s).unwrap_or(Scalar::F64),
            params,
            bodies: model_bodies,
            points,
            vectors,
            constraints,
            gravity,
            forces,
        })
    }
}

/// Pass 3: joints, drivers and user constraints in declaration order, each resolved by its
/// kind's file, with the joint friction their options declare.
fn constraints(
    items: &[Item],
    r: &mut Resolver,
    names: &mut HashMap<String, Span>,
    bodies: &[Body],
    body_name: &dyn Fn(BodyRef) -> String,
    ok: &mut bool,
) -> (Vec<Constraint>, Vec<ForceElement>) {
    let mut constraints = Vec::new();
    let mut forces = Vec::new();
    let mut driven = Driven::default();
    for (index, item) in items.iter().enumerate() {
        let built = match item {
            Item::Joint(j) => elements::resolve(r, j, body_name, constraints.len()),
            Item::Fix(f) => fix::resolve(r, f, &mut driven, bodies),
            Item::Drive(d) => {
                let f = r.expr(&d.f, Scope::Time);
                match &d.target {
                    DriveTarget::Coordinate { body, coordinate } => drive::resolve(r, d, body, coordinate, f, &mut driven),
                    DriveTarget::Angle { i, j, .. } => drive_angle::resolve(r, d, i, j, f, &mut driven),
                    DriveTarget::Distance { i, j, .. } => drive_distance::resolve(r, d, i, j, f),
                }
            }
            Item::Constraint(c) => user::resolve(r, c, index),
            _ => continue,
        };
        let Some((label, default_name, span, kind, friction)) = built else {
            *ok = false;
            continue;
        };
        let Some(name) = claim_name(names, r.errors, label, default_name, span) else {
            *ok = false;
            continue;
        };
        for (what, kind) in friction {
            forces.push(ForceElement { name: format!("{name} {what}"), kind });
        }
        constraints.push(Constraint { name, kind });
    }
    (constraints, forces)
}

/// Pass 4: gravity and the force elements (Nikravesh ch. 4), each resolved by its kind's file.
/// Returns gravity, if declared.
fn force_elements(
    items: &[Item],
    r: &mut Resolver,
    names: &mut HashMap<String, Span>,
    body_name: &dyn Fn(BodyRef) -> String,
    forces: &mut Vec<ForceElement>,
    ok: &mut bool,
) -> Option<[MExpr; 2]> {
    let mut gravity = None;
    for item in items {
        let built = match item {
            Item::Gravity(kw, v) => {
                if gravity.is_some() {
                    r.errors.push(kw.span(), "gravity is declared twice");
                    *ok = false;
                }
                gravity = r.list::<2>(v, Scope::Params, "gravity `[gx, gy]` (m/s²)");
                if gravity.is_none() {
                    *ok = false;
                }
                continue;
            }
            Item::PointForce(f) => point_to_point::resolve(r, f, body_name),
            Item::RotationalForce(f) => rotational::resolve(r, f),
            Item::Force(f) => applied::resolve(r, f),
            Item::Torque(tq) => torque::resolve(r, tq),
            _ => continue,
        };
        let Some((label, default_name, span, kind)) = built else {
            *ok = false;
            continue;
        };
        let Some(name) = claim_name(names, r.errors, label, default_name, span) else {
            *ok = false;
            continue;
        };
        forces.push(ForceElement { name, kind });
    }
    gravity
}

#[cfg(test)]
mod tests {
    use super::*;

    fn validate(src: &str) -> syn::Result<Model> {
        syn::parse_str::<MechanismDef>(src).expect("the test input parses").validate()
    }

    /// Each statement becomes its kind, named by default after its kind and bodies; joint
    /// friction options become force elements named after their joint.
    #[test]
    fn statements_become_typed_kinds() {
        let m = validate(
            "M { body a { mass: 1.0, inertia: 0.1 } body b { mass: 2.0, inertia: 0.2, at: [1.0, 0.0, 0.0] }
                 revolute ground[0.0, 0.0] ~ a[-0.5, 0.0] { viscous: 0.1 };
                 translational slide: a[0.5, 0.0] along [1.0, 0.0] ~ b[0.0, 0.0] along [1.0, 0.0] { coulomb: 0.2 };
                 drive a.phi = t; constraint b.y = 0.0; spring a[0.0, 0.0] ~ b[0.0, 0.0] { k: 10.0, length: 1.0 }; }",
        )
        .unwrap();
        let kinds: Vec<(&str, &str)> = m.constraints.iter().map(|c| (c.kind.kind(), c.name.as_str())).collect();
        assert_eq!(
            kinds,
            [("revolute", "revolute ground~a"), ("translational", "slide"), ("drive", "drive a.phi"), ("constraint", "constraint 5")]
        );
        // (an unlabelled constraint is named by its statement's position, the bodies counted)
        let forces: Vec<(&str, &str)> = m.forces.iter().map(|f| (f.kind.kind(), f.name.as_str())).collect();
        assert_eq!(
            forces,
            [
                ("revolute_viscous", "revolute ground~a viscous friction"),
                ("translational_coulomb", "slide Coulomb friction"),
                ("point_to_point", "spring a~b")
            ]
        );
        assert_eq!(m.constraints[1].kind.bodies(), (Some(BodyRef::Body(0)), Some(BodyRef::Body(1))));
    }

    /// Every mistake of one mechanism is reported, each on its own token.
    #[test]
    fn all_mistakes_are_collected() {
        let Err(e) = validate(
            "M { body a { mass: -1.0, inertia: 0.1 }
                 revolute ground[0.0, 0.0] ~ crnk[0.0, 0.0];
                 revolute_revolute a[0.0, 0.0] ~ ground[1.0, 0.0];
                 translational a[0.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0]; }",
        ) else {
            panic!("the mechanism has mistakes")
        };
        let messages: Vec<String> = e.into_iter().map(|e| e.to_string()).collect();
        assert_eq!(messages.len(), 4, "{messages:#?}");
        assert!(messages[0].contains("mass of body `a` must be positive"), "{}", messages[0]);
        assert!(messages.iter().any(|m| m.contains("unknown body `crnk` (did you mean `a`?)") || m.contains("unknown body `crnk`")));
        assert!(messages.iter().any(|m| m.contains("needs its length")));
        assert!(messages.iter().any(|m| m.contains("needs a sliding axis on its first body")));
    }

    /// An option a kind does not take is named with the list of those it does.
    #[test]
    fn unknown_option_lists_the_known_ones() {
        let Err(e) = validate("M { body a { mass: 1.0, inertia: 0.1 } rigid ground[0.0, 0.0] ~ a[0.0, 0.0] { length: 1.0 }; }") else {
            panic!("`length` is not an option of rigid")
        };
        assert!(e.to_string().contains("unknown option `length` of a rigid joint (it takes: angle)"), "{e}");
    }
}
