//! Name resolution: expressions, points, vectors and axes of the statements, resolved against
//! the declared parameters, bodies, points and vectors.

use super::*;

pub(super) const BODY_FIELDS: &[&str] = &["mass", "inertia", "at", "velocity"];
pub(super) const SPATIAL_BODY_FIELDS: &[&str] = &["mass", "inertia", "at", "quaternion", "axis_angle", "angles", "velocity", "omega"];
pub(super) const FUNCTIONS: &[&str] =
    &["sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sqrt", "exp", "ln", "pow", "abs", "sign", "min", "max", "clamp", "deg"];

impl Resolver<'_> {
    /// Whether a name is `ground` or a declared body (nothing reported).
    pub fn is_body(&self, id: &Ident) -> bool {
        id == "ground" || self.bodies.contains_key(&id.to_string())
    }

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
                    .push(id.span(), format!("unknown body: expected a declared body or `ground`, found `{id}`{hint}; declare it with `body {id} {{ mass: ..., inertia: ... }}`"));
                None
            }
        }
    }

    /// An expression resolved in its scope; a constant part of it that is not finite (`ln(0)`,
    /// `sqrt(-1)`, `1e999`), or beyond f32's range under `scalar f32;`, is an error on that part.
    pub fn expr(&mut self, e: &Expr, scope: Scope) -> Option<MExpr> {
        let m = self.expr_unchecked(e, scope)?;
        match m.constant_value() {
            Some(v) if !v.is_finite() => {
                self.errors.at_expr(
                    e,
                    format!("expected a finite value, found {v} for every state and time: a constant such as ln(0), 1/0 or sqrt(-1)"),
                );
                None
            }
            Some(v) if v.abs() > self.largest => {
                self.errors.at_expr(e, format!("this constant is beyond the range of f32: expected at most ±3.4e38, found {v:e}"));
                None
            }
            _ => Some(m),
        }
    }

    fn expr_unchecked(&mut self, e: &Expr, scope: Scope) -> Option<MExpr> {
        Some(match &e.kind {
            ExprKind::Num(v) => MExpr::Num(*v),
            ExprKind::Ident(id) => {
                let s = id.to_string();
                if s == "PI" {
                    MExpr::Pi
                } else if s == "t" {
                    if matches!(scope, Scope::Constant | Scope::Params) {
                        self.errors.push(id.span(), format!("time `t` is not allowed here: expected {}, found `t`", scope.describe()));
                        return None;
                    }
                    MExpr::T
                } else if let Some(&k) = self.params.get(&s) {
                    if scope == Scope::Constant {
                        self.errors
                            .push(id.span(), format!("parameter `{s}` is not allowed here: expected {}, found `{s}`", scope.describe()));
                        return None;
                    }
                    MExpr::Param(k)
                } else {
                    let names: Vec<&str> = self.params.keys().map(|s| s.as_str()).collect();
                    let hint = parse::closest(&s, &names, &["t", "PI"]);
                    self.errors.push(
                        id.span(),
                        format!("unknown identifier: expected a number, a parameter declared in `params {{ }}`, `t`, `PI` or a coordinate like `crank.phi`, found `{s}`{hint}"),
                    );
                    return None;
                }
            }
            ExprKind::Coord(b, c) => {
                let position = Coord::from_ident(self.space, c);
                let velocity = Vel::from_ident(self.space, c);
                if position.is_none() && velocity.is_none() {
                    self.errors.push(
                        c.span(),
                        format!(
                            "unknown coordinate: expected {} or, in forces, a velocity {}, found `{c}`",
                            self.space.coordinate_list(),
                            self.space.velocity_list()
                        ),
                    );
                    return None;
                }
                let allowed = matches!((position, scope), (Some(_), Scope::State | Scope::Force) | (None, Scope::Force));
                if !allowed {
                    let what = if position.is_some() { "coordinate" } else { "velocity" };
                    self.errors.at_expr(e, format!("{what} `{b}.{c}` is not allowed here: expected {}, found `{b}.{c}`", scope.describe()));
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
                    "deg" => 1,
                    n if Func::from_name(n).is_some() => 1,
                    n if Kink::from_name(n).is_some() => Kink::from_name(n)?.arity(),
                    _ => {
                        let hint = parse::closest(&name, FUNCTIONS, &[]);
                        self.errors.push(
                            f.span(),
                            format!("unknown function: expected {}, found `{name}`{hint}", parse::one_of(FUNCTIONS, "a function")),
                        );
                        return None;
                    }
                };
                if args.len() != arity {
                    self.errors.at_expr(e, format!("wrong number of arguments to `{name}`: expected {arity}, found {}", args.len()));
                    return None;
                }
                let resolved: Vec<Option<MExpr>> = args.iter().map(|a| self.expr(a, scope)).collect();
                let resolved = resolved.into_iter().collect::<Option<Vec<_>>>()?;
                if let Some(k) = Kink::from_name(&name) {
                    return Some(MExpr::Kink(k, resolved.into()));
                }
                let mut resolved = resolved.into_iter();
                let a = Box::new(resolved.next()?);
                match name.as_str() {
                    "atan2" => MExpr::Atan2(a, Box::new(resolved.next()?)),
                    "pow" => MExpr::Bin(MBin::Pow, a, Box::new(resolved.next()?)),
                    // degrees to radians
                    "deg" => MExpr::Bin(MBin::Mul, a, Box::new(MExpr::Num(std::f64::consts::PI / 180.0))),
                    n => MExpr::Call(Func::from_name(n)?, a),
                }
            }
            ExprKind::If(c, then, otherwise) => {
                let (a, b) = (self.expr(&c.lhs, scope), self.expr(&c.rhs, scope));
                let (x, y) = (self.expr(then, scope), self.expr(otherwise, scope));
                let (a, b, x, y) = (a?, b?, x?, y?);
                let (cmp, a, b) = match c.op {
                    CmpOp::Gt => (Cmp::Gt, a, b),
                    CmpOp::Ge => (Cmp::Ge, a, b),
                    CmpOp::Lt => (Cmp::Gt, b, a),
                    CmpOp::Le => (Cmp::Ge, b, a),
                };
                MExpr::If(cmp, Box::new([a, b, x, y]))
            }
        })
    }

    /// A list of as many components as the space has (2 or 3), each of the given scope.
    pub fn components(&mut self, v: &VecLit, scope: Scope, what: &str) -> Option<Components> {
        let n = self.space.dim();
        if v.items.len() != n {
            self.errors.push(v.span, format!("{what}: expected {n} entries, found {}", v.items.len()));
            return None;
        }
        let items: Vec<Option<MExpr>> = v.items.iter().map(|e| self.expr(e, scope)).collect();
        items.into_iter().collect()
    }

    /// "`[ξ, η]`" or "`[ξ, η, ζ]`".
    pub fn shape(&self, names: [&str; 3]) -> String {
        format!("[{}]", names[..self.space.dim()].join(", "))
    }

    pub fn point(&mut self, body: BodyRef, p: &PointRef) -> Option<Components> {
        let shape = self.shape(["ξ", "η", "ζ"]);
        match p {
            PointRef::Inline(v) => self.components(v, Scope::Params, &format!("a point `{shape}` in body coordinates")),
            PointRef::Named(name) => match self.points.get(&(body, name.to_string())) {
                Some(p) => Some(p.clone()),
                None => {
                    let body_name = match body {
                        BodyRef::Ground => "ground".to_string(),
                        BodyRef::Body(k) => self.bodies.iter().find(|(_, &i)| i == k).map(|(n, _)| n.clone()).unwrap_or_default(),
                    };
                    let mut declared: Vec<&str> = self.points.keys().filter(|(b, _)| *b == body).map(|(_, n)| n.as_str()).collect();
                    declared.sort_unstable();
                    let hint = parse::closest(&name.to_string(), &declared, &[]);
                    let expected = match declared.as_slice() {
                        [] => "a declared point".to_string(),
                        some => format!("one of {}", some.iter().map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", ")),
                    };
                    self.errors.push(
                        name.span(),
                        format!(
                            "unknown point on body `{body_name}`: expected {expected}, found `{name}`{hint}; declare it with `point {body_name}.{name} = {shape};`"
                        ),
                    );
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

    pub fn axis(&mut self, body: BodyRef, a: &AxisRef) -> Option<Components> {
        match a {
            AxisRef::Inline(v) => {
                let shape = self.shape(["x", "y", "z"]);
                let axis = self.components(v, Scope::Params, &format!("an axis `{shape}` in body coordinates"))?;
                let values: Option<Vec<f64>> = axis.iter().map(|c| c.constant_value()).collect();
                if values.is_some_and(|v| v.iter().all(|&c| c == 0.0)) {
                    self.errors.push(v.span, "an axis has a direction: expected a non-zero vector, found the zero vector");
                    return None;
                }
                Some(axis)
            }
            AxisRef::Named(b, name) => {
                if self.body(b)? != body {
                    self.errors
                        .push(b.span(), "the axis must be a vector of the same body as the point: expected that body, found another");
                    return None;
                }
                match self.vectors.get(&(body, name.to_string())) {
                    Some(v) => Some(v.clone()),
                    None => {
                        let shape = self.shape(["x", "y", "z"]);
                        self.errors.push(name.span(), format!("unknown vector: expected a declared vector, found `{name}`; declare it with `vector {b}.{name} = {shape};`"));
                        None
                    }
                }
            }
        }
    }
}
