//! The declarations of pass 1 (scalar, parameters, bodies) and the names every statement
//! claims: generated items, joint and element names.

use super::*;

/// The name of a joint, driver, constraint or force element — its label, or its default name —
/// if no other statement has it yet; otherwise an error on the label or the statement's keyword.
pub(super) fn claim_name(
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
        format!("duplicate name `{name}`: expected a new name, found `{name}` again; rename one of them")
    } else {
        format!("a second `{name}`: give one of them a name, e.g. `{} name: ...`", name.split(' ').next().unwrap_or(""))
    };
    errors.push(span, msg);
    None
}

/// Associated items of every generated mechanism type: a body or joint whose generated constant
/// (its name in upper case) or a point whose accessor (`body_point`) would take one of these
/// names is refused.
pub(super) const GENERATED_ITEMS: &[&str] = &[
    "N_BODIES",
    "NQ",
    "NV",
    "NC",
    "DOF",
    "NNZ",
    "NP",
    "NEWTON_STORAGE",
    "NAME",
    "BODY_NAMES",
    "COORDINATE_NAMES",
    "VELOCITY_NAMES",
    "COORDINATES",
    "VELOCITIES",
    "CONSTRAINT_NAMES",
    "PARAM_NAMES",
    "JACOBIAN_PATTERN",
    "PHI_T_IS_ZERO",
    "OP_COUNTS",
    "JOINTS",
    "EFFECTS",
    "FORCE_ELEMENTS",
    "MODEL_JSON",
    "params",
    "from_params",
    "workspace",
    "generalized_alpha",
    "mass_of",
    "inertia_of",
    "jacobian_values",
    "full_eval_values",
    "schur_factor",
    "schur_solve",
    "NEWTON_PATTERN",
    "newton_storage",
    "newton_jacobian",
    "newton_matrix",
];

/// The joint coordinates a labelled spatial joint gets an accessor for (`hinge_angle(&q)`), by
/// the kinds that have them.
pub const JOINT_COORDINATES: &[(&str, &[&str])] = &[("angle", &["revolute", "cylindrical"]), ("stroke", &["translational", "cylindrical"])];

/// The generated constant of a body or labelled joint: its name in upper case (`Name::CRANK`).
pub fn constant_name(name: &str) -> String {
    name.to_uppercase()
}

/// The generated accessor of a named point: `crank.A` → `crank_a()`.
pub fn point_accessor(body: &str, point: &str) -> String {
    format!("{body}_{point}").to_lowercase()
}

/// `scalar f32;`: the scalar type, once.
pub(super) fn declare_scalar(r: &mut Resolver, s: &Ident, scalar: &mut Option<(Scalar, Span)>) {
    let sc = match s.to_string().as_str() {
        "f64" => Scalar::F64,
        "f32" => Scalar::F32,
        other => {
            r.errors.push(s.span(), format!("unsupported scalar type: expected `f64` or `f32`, found `{other}`"));
            return;
        }
    };
    if scalar.is_some() {
        r.errors.push(s.span(), "the scalar type is declared twice: expected one `scalar`, found a second one");
    }
    *scalar = Some((sc, s.span()));
}

/// `params { ... }`: each parameter with its default, unless its name is taken or reserved.
/// False where one has a mistake (the others are still declared).
pub(super) fn declare_params(r: &mut Resolver, ps: &[(Ident, Expr)], params: &mut Vec<Param>) -> bool {
    let mut ok = true;
    for (name, value) in ps {
        if r.params.contains_key(&name.to_string()) {
            r.errors
                .push(name.span(), format!("duplicate parameter `{name}`: expected a new name, found `{name}` again; rename one of them"));
            ok = false;
            continue;
        }
        if ["t", "PI", "ground"].contains(&name.to_string().as_str()) {
            r.errors.push(
                name.span(),
                format!(
                    "`{name}` is reserved: expected a parameter's name, found `{name}`, which expressions read as {}",
                    match name.to_string().as_str() {
                        "t" => "time",
                        "PI" => "π",
                        _ => "the fixed frame",
                    }
                ),
            );
            ok = false;
            continue;
        }
        // A default with a mistake is reported; the parameter is still declared,
        // so that what uses it is not reported too.
        let default = match r.expr(value, Scope::Constant).map(|d| d.constant_value().unwrap_or(f64::NAN)) {
            Some(d) if d.is_finite() => d,
            Some(d) => {
                r.errors.at_expr(value, format!("the default of `{name}` is not finite: expected a finite value, found {d}"));
                ok = false;
                0.0
            }
            None => {
                ok = false;
                0.0
            }
        };
        r.params.insert(name.to_string(), params.len());
        r.defaults.push(default);
        params.push(Param { name: name.clone(), default });
    }
    ok
}

/// A body's name, unless taken: false where it is `ground`, a duplicate, or generates an item
/// that clashes.
pub(super) fn declare_body<'d>(
    r: &mut Resolver,
    b: &'d BodyDef,
    items: &mut HashMap<String, String>,
    bodies: &mut Vec<&'d BodyDef>,
) -> bool {
    if b.name == "ground" {
        r.errors.push(b.name.span(), "`ground` is the fixed frame, always present: expected another body name, found `ground`");
        return false;
    }
    if r.bodies.contains_key(&b.name.to_string()) {
        r.errors.push(b.name.span(), format!("duplicate body `{0}`: expected a new name, found `{0}` again; rename one of them", b.name));
        return false;
    }
    let item = constant_name(&b.name.to_string());
    if !claim_item(items, r.errors, item, format!("body `{}`", b.name), b.name.span()) {
        return false;
    }
    r.bodies.insert(b.name.to_string(), bodies.len());
    bodies.push(b);
    true
}

/// Claims a generated item name (a body's or labelled joint's constant, a point's accessor) for
/// `what`; an error on `span` if a generated item or an earlier name has it.
pub(super) fn claim_item(items: &mut HashMap<String, String>, errors: &mut Errors, item: String, what: String, span: Span) -> bool {
    if GENERATED_ITEMS.contains(&item.as_str()) {
        errors.push(span, format!("{what} would generate `{item}`, which every mechanism already has: expected another name, found one that clashes; rename it"));
        return false;
    }
    if let Some(other) = items.insert(item.clone(), what.clone()) {
        errors.push(span, format!("{what} and {other} would both generate `{item}`: expected names that differ in more than case, found two that do not; rename one"));
        return false;
    }
    true
}

/// Checks a number that must be positive when it is a constant (a parameter's value is checked
/// at run time by the solver that needs it).
pub fn check_positive(errors: &mut Errors, e: &MExpr, written: &Expr, what: &str) {
    if let Some(v) = e.constant_value() {
        #[allow(clippy::neg_cmp_op_on_partial_ord)] // NaN is not positive either
        if !(v > 0.0) {
            errors.at_expr(written, format!("{what} must be positive: expected a value above 0, found {v}"));
        }
    }
}
