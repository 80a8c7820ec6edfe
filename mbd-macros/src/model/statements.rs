//! Joints, drivers, constraints and force elements resolved in declaration order.

use super::*;

/// An angle driver whose rate, at the parameters' defaults, is above 100 rev/s or a whole
/// multiple of 90 rad/s — degrees per second written as radians (`360 * t` turns at 57 rev/s) —
/// gets a warning on its expression; `deg(360) * t` is one turn a second.
pub(super) fn angle_rate_check(r: &mut Resolver, written: &Expr, f: &MExpr) {
    let rate = |t: f64| {
        let h = 1e-6 * t.abs().max(1.0);
        Some((f.value_at(&r.defaults, t + h)? - f.value_at(&r.defaults, t - h)?) / (2.0 * h))
    };
    let rates: Option<Vec<f64>> = [0.0, 0.25, 0.5, 1.0, 2.0].into_iter().map(rate).collect();
    let Some(rates) = rates else { return };
    let fastest = rates.iter().fold(0.0f64, |m, w| m.max(w.abs()));
    let whole = rates[0].round();
    let rev = |w: f64| w / std::f64::consts::TAU;
    if fastest > 100.0 * std::f64::consts::TAU && fastest.is_finite() {
        r.errors.warn(
            written.span,
            format!(
                "this angle driver turns at {:.0} rev/s ({fastest:.0} rad/s): expected an angle in radians, found a rate above 100 rev/s, which reads like degrees; for degrees write `deg(...)`",
                rev(fastest)
            ),
        );
    } else if whole.abs() >= 90.0 && whole % 90.0 == 0.0 && (rates[0] - whole).abs() < 1e-6 * whole.abs() {
        r.errors.warn(
            written.span,
            format!(
                "this angle driver turns at {whole} rad/s ({:.1} rev/s): expected an angle in radians, found a rate that reads like degrees per second; for {whole}°/s write `deg({whole}) * t`",
                rev(whole)
            ),
        );
    }
}

/// A spatial joint by its name: its kind and markers (what its drivers and force elements use).
pub type SpatialJoints = HashMap<String, (&'static str, Marker, Marker)>;

/// Pass 3: joints, drivers and user constraints in declaration order, each resolved by its
/// kind's file, with the joint friction their options declare. In space, joints are resolved
/// first, so a driver may name a joint declared after it; they are also returned by name.
pub(super) fn constraints(
    items: &[Item],
    r: &mut Resolver,
    names: &mut HashMap<String, Span>,
    generated: &mut HashMap<String, String>,
    bodies: &[Body],
    body_name: &dyn Fn(BodyRef) -> String,
    ok: &mut bool,
) -> (Vec<Constraint>, Vec<ForceElement>, SpatialJoints) {
    let mut constraints = Vec::new();
    let mut forces = Vec::new();
    let mut driven = Driven::default();
    // A particle's angle is held by a row of its own, after the declared ones.
    if r.space == Space::Planar {
        for (k, b) in bodies.iter().enumerate().filter(|(_, b)| b.particle) {
            driven.coords.insert((k, Coord::Phi), b.name.span());
        }
    }
    let mut spatial_joints = HashMap::new();
    let mut joints = SpatialJoints::new();
    if r.space == Space::Spatial {
        // the index each joint will have among the constraints (exact when every statement
        // resolves; otherwise the mechanism is refused anyway)
        let mut joint_index = 0;
        for (index, item) in items.iter().enumerate() {
            if matches!(item, Item::Fix(_) | Item::Drive(_) | Item::Constraint(_)) {
                joint_index += 1;
            }
            if let Item::Joint(j) = item {
                let resolved = spatial::resolve(r, j, body_name, joint_index);
                joint_index += 1;
                if let Some((label, default_name, _, kind, _)) = &resolved {
                    if let Some([mi, mj]) = kind.markers() {
                        let name = label.map_or_else(|| default_name.clone(), |l| l.to_string());
                        joints.insert(name, (kind.kind(), mi.clone(), mj.clone()));
                    }
                }
                spatial_joints.insert(index, resolved);
            }
        }
    }
    for (index, item) in items.iter().enumerate() {
        let built = match item {
            Item::Joint(_) if r.space == Space::Spatial => spatial_joints.remove(&index).flatten(),
            Item::Joint(j) => elements::resolve(r, j, body_name, constraints.len()),
            Item::Fix(f) => fix::resolve(r, f, &mut driven, bodies),
            Item::Drive(d) => {
                let f = r.expr(&d.f, Scope::Time);
                let angle = match &d.target {
                    DriveTarget::Coordinate { coordinate, .. } => coordinate == "phi" || coordinate == "angle",
                    DriveTarget::Angle { .. } => true,
                    DriveTarget::Distance { .. } => false,
                };
                if let (true, Some(f)) = (angle, &f) {
                    angle_rate_check(r, &d.f, f);
                }
                match &d.target {
                    DriveTarget::Coordinate { body, coordinate } if r.space == Space::Spatial && !r.is_body(body) => {
                        spatial::drive_joint(r, d, body, coordinate, f, &joints, &mut driven)
                    }
                    DriveTarget::Angle { .. } | DriveTarget::Distance { .. } if r.space == Space::Spatial => {
                        r.errors.push(d.keyword.span(), "`angle(..)` and `distance(..)` drivers are planar: expected a joint to drive in space, found a relative driver; `drive hinge.angle = f;` or `drive slider.stroke = f;`");
                        None
                    }
                    DriveTarget::Coordinate { body, .. } if !r.is_body(body) && planar_joint(items, body).is_some() => {
                        let kind = planar_joint(items, body).unwrap_or_default();
                        r.errors.push(
                            body.span(),
                            format!(
                                "`{body}` is a {kind} joint: expected a body's coordinate, found a joint's; in the plane drive a joint through its bodies, \
                                 `drive angle(body_i, body_j) = f;` or `drive distance(..) = f;` (`drive {body}.angle` drives a joint in space)"
                            ),
                        );
                        None
                    }
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
        if let Some(l) = label {
            if !claim_item(generated, r.errors, constant_name(&name), format!("joint `{name}`"), l.span()) {
                *ok = false;
                continue;
            }
            let coordinates = JOINT_COORDINATES.iter().filter(|(_, kinds)| r.space == Space::Spatial && kinds.contains(&kind.kind()));
            for (what, _) in coordinates {
                if !claim_item(generated, r.errors, format!("{name}_{what}"), format!("the {what} of joint `{name}`"), l.span())
                    || !claim_item(
                        generated,
                        r.errors,
                        format!("{name}_{what}_rate"),
                        format!("the {what} rate of joint `{name}`"),
                        l.span(),
                    )
                {
                    *ok = false;
                }
            }
        }
        for (what, kind) in friction {
            forces.push(ForceElement { name: format!("{name} {what}"), kind });
        }
        constraints.push(Constraint { name, kind });
    }
    for (k, b) in bodies.iter().enumerate().filter(|(_, b)| b.particle) {
        let Some(name) = claim_name(names, r.errors, None, format!("particle {}", b.name), b.name.span()) else {
            *ok = false;
            continue;
        };
        let kind: Box<dyn elements::Joint> = match r.space {
            Space::Planar => Box::new(fix::Fix { body: k, coord: Coord::Phi, value: MExpr::Num(0.0) }),
            Space::Spatial => Box::new(spatial::rigid::Orientation::held(k)),
        };
        constraints.push(Constraint { name, kind });
    }
    (constraints, forces, joints)
}

/// Pass 4: gravity and the force elements (Nikravesh ch. 4), each resolved by its kind's file.
/// Returns gravity, if declared.
pub(super) fn force_elements(
    items: &[Item],
    r: &mut Resolver,
    names: &mut HashMap<String, Span>,
    body_name: &dyn Fn(BodyRef) -> String,
    joints: &SpatialJoints,
    forces: &mut Vec<ForceElement>,
    ok: &mut bool,
) -> Option<Components> {
    let mut gravity = None;
    for item in items {
        let built = match item {
            Item::Gravity(kw, v) => {
                if gravity.is_some() {
                    r.errors.push(kw.span(), "gravity is declared twice: expected one `gravity`, found a second one");
                    *ok = false;
                }
                let shape = r.shape(["gx", "gy", "gz"]);
                gravity = r.components(v, Scope::Params, &format!("gravity `{shape}` (m/s²)"));
                if gravity.is_none() {
                    *ok = false;
                }
                continue;
            }
            Item::PointForce(f) if f.kind == "bushing" => bushing::resolve(r, f, body_name),
            Item::PointForce(f) if f.kind == "contact" => contact::resolve(r, f, body_name),
            Item::PointForce(f) if f.kind == "cable" => cable::resolve(r, f, body_name),
            Item::PointForce(f) if f.kind == "tyre" => tyre::resolve(r, f, body_name),
            Item::PointForce(f) => point_to_point::resolve(r, f, body_name),
            Item::AxisForce(f) if stroke::KINDS.contains(&f.kind.to_string().as_str()) => stroke::resolve(r, f, joints),
            Item::AxisForce(f) => rotational::resolve(r, f, joints),
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

/// The kind of the planar joint labelled `name` (`revolute hinge: ...`), if one is.
fn planar_joint(items: &[Item], name: &Ident) -> Option<String> {
    items.iter().find_map(|item| match item {
        Item::Joint(j) if j.label.as_ref() == Some(name) => Some(j.kind.to_string()),
        _ => None,
    })
}
