//! The generated type's rustdoc: what a user reads to find an index — its coordinates and
//! velocities, named points, joints, constraint rows and force elements as tables, with the
//! indices the arrays use and the units of every entry (a row's multiplier's unit is the row's
//! own, `frames::RowUnit`, as `Mechanism::CONSTRAINT_UNITS` gives it to the runtime).
use std::fmt::Write;

use crate::emit::Ops;
use crate::formulation::Formulation;
use crate::model::{BodyRef, Coord, Model, Space, Vel};

fn coordinate_unit(c: Coord) -> &'static str {
    match c {
        Coord::X | Coord::Y | Coord::Z => "m",
        Coord::Phi => "rad",
        Coord::E0 | Coord::E1 | Coord::E2 | Coord::E3 => "1",
    }
}

fn velocity_unit(v: Vel) -> &'static str {
    match v {
        Vel::Vx | Vel::Vy | Vel::Vz => "m/s",
        Vel::Omega | Vel::Wx | Vel::Wy | Vel::Wz => "rad/s",
    }
}

/// The coordinates table of a mechanism in joint coordinates: each tree joint's angle or stroke,
/// each floating body's pose.
fn joint_coordinates(w: &mut String, m: &Model) {
    let _ = writeln!(
        w,
        "Joint coordinates: `q[i]` in every `[f64; {}::NQ]` is a tree joint's angle (rad) or stroke along \
         its first axis (m), a spherical joint's Euler parameters (body j's orientation in body i's \
         frame), or a floating body's position (m) and angle (rad) or Euler parameters. Velocities \
         are their rates, except a quaternion's: an angular velocity in the child's (or floating \
         body's) own axes (rad/s); they index v̇, h and the columns of D. Each body's pose is read \
         through `mbd::BodyFrames`.\n",
        m.name
    );
    let _ = writeln!(w, "| i | coordinate q | unit |\n|---:|---|---|");
    let Some(tree) = &m.tree else { return };
    for (i, (name, kind)) in tree.coordinate_names(m).iter().enumerate() {
        let unit = match kind {
            crate::tree::CoordinateKind::Angle => "rad",
            crate::tree::CoordinateKind::Length => "m",
            crate::tree::CoordinateKind::Quaternion(_) => "1",
        };
        let _ = writeln!(w, "| {i} | `{name}` | {unit} |");
    }
    if tree.nv != tree.nq {
        let _ = writeln!(w, "\n| i | velocity v | unit |\n|---:|---|---|");
        for (i, (name, kind, _)) in tree.velocity_names(m).iter().enumerate() {
            let unit = match kind {
                crate::tree::VelocityKind::Angular { .. } => "rad/s",
                crate::tree::VelocityKind::Rate(c) if tree.coordinate_names(m)[*c].1 == crate::tree::CoordinateKind::Angle => "rad/s",
                crate::tree::VelocityKind::Rate(_) => "m/s",
            };
            let _ = writeln!(w, "| {i} | `{name}` | {unit} |");
        }
    }
}

/// The tables of the type's documentation, as markdown (one `#[doc]` string).
/// `force_ops`: the operations of `forces`, `forces_q` and `forces_v` with no element, and with
/// each element alone (in the order of `f.force_velocities`).
pub fn tables(m: &Model, f: &Formulation, force_ops: &([Ops; 3], Vec<[Ops; 3]>)) -> String {
    let (base, alone) = force_ops;
    let name = &m.name;
    let mut out = String::new();
    let w = &mut out;
    let _ = writeln!(w, "\n# Coordinates and velocities\n");
    match m.space {
        _ if m.tree.is_some() => joint_coordinates(w, m),
        Space::Planar => {
            let _ = writeln!(
                w,
                "`q[i]` in every `[f64; {name}::NQ]`; planar velocities are their rates, `v[i]` = q̇ᵢ \
                 (m/s, rad/s), and v̇, h and the columns of D are indexed the same way.\n"
            );
            let _ = writeln!(w, "| i | coordinate | unit |\n|---:|---|---|");
            for (b, body) in m.bodies.iter().enumerate() {
                for (k, c) in m.space.coordinates().iter().enumerate() {
                    let _ = writeln!(w, "| {} | `{}.{}` | {} |", 3 * b + k, body.name, c.name(), coordinate_unit(*c));
                }
            }
        }
        Space::Spatial => {
            let _ = writeln!(
                w,
                "`q[i]`: position and Euler parameters of each body (7 per body); `v[i]`: its velocity \
                 and angular velocity in its own axes ω′ (6 per body), which also index v̇, h and the \
                 columns of D.\n"
            );
            let _ = writeln!(w, "| i | coordinate q | unit |\n|---:|---|---|");
            for (b, body) in m.bodies.iter().enumerate() {
                for (k, c) in m.space.coordinates().iter().enumerate() {
                    let _ = writeln!(w, "| {} | `{}.{}` | {} |", 7 * b + k, body.name, c.name(), coordinate_unit(*c));
                }
            }
            let _ = writeln!(w, "\n| i | velocity v | unit |\n|---:|---|---|");
            for (b, body) in m.bodies.iter().enumerate() {
                for (k, v) in m.space.velocities().iter().enumerate() {
                    let _ = writeln!(w, "| {} | `{}.{}` | {} |", 6 * b + k, body.name, v.name(), velocity_unit(*v));
                }
            }
        }
    }
    let moving: Vec<_> = m.points.iter().filter(|p| p.body != BodyRef::Ground && m.tree.is_none()).collect();
    if !moving.is_empty() {
        let _ =
            writeln!(w, "\n# Points\n\nEach named point has an accessor giving its position, velocity and acceleration in m, m/s, m/s².\n");
        let _ = writeln!(w, "| point | accessor |\n|---|---|");
        for p in moving {
            let body = m.body_name(p.body);
            let _ = writeln!(w, "| `{body}.{}` | [`{name}::{}`] |", p.name, crate::model::point_accessor(&body, &p.name));
        }
    }
    if !m.constraints.is_empty() {
        let _ = writeln!(
            w,
            "\n# Joints, drivers and constraints\n\nIn the order of `JOINTS` (the index `joint_reaction` takes) and of their rows in Φ.\n"
        );
        let _ = writeln!(w, "| index | joint | kind | rows of Φ |\n|---:|---|---|---|");
        for (k, c) in m.constraints.iter().enumerate() {
            let (first, end) = (f.first_rows[k], f.first_rows.get(k + 1).copied().unwrap_or(f.row_names.len()));
            let rows = match end - first {
                0 => "none: carried by the joint coordinates".to_string(),
                1 => first.to_string(),
                _ => format!("{first}–{}", end - 1),
            };
            let _ = writeln!(w, "| {k} | `{}` | {} | {rows} |", c.name, c.kind.kind());
        }
        let _ = writeln!(
            w,
            "\n# Constraint rows\n\n`Φ[r]`, and the multiplier `λ[r]`: the reaction of the row, with the sign \
             convention M v̇ − Dᵀλ = h.\n"
        );
        let _ = writeln!(w, "| r | row | λ unit |\n|---:|---|---|");
        for (r, (row, unit)) in f.row_names.iter().zip(&f.row_units).enumerate() {
            let unit = match unit.multiplier() {
                "" => "J per unit of the row",
                unit => unit,
            };
            let _ = writeln!(w, "| {r} | `{row}` | {unit} |");
        }
    }
    if !f.force_velocities.is_empty() {
        let _ = writeln!(
            w,
            "\n# Force elements\n\nIn the order of `FORCE_ELEMENTS`. Its operations alone: what `forces`, `forces_q` and \
             `forces_v` would count above the mechanism's base (no element: {}, {} and {}) were it the only element.\n",
            base[0].total(),
            base[1].total(),
            base[2].total()
        );
        let _ = writeln!(w, "| element | velocities it acts on | its operations alone |\n|---|---|---|");
        for ((element, velocities), ops) in f.force_velocities.iter().zip(alone) {
            let list = if velocities.len() > 12 {
                format!("{} of them", velocities.len())
            } else {
                velocities.iter().map(|v| v.to_string()).collect::<Vec<_>>().join(", ")
            };
            let cost: Vec<String> = ops.iter().zip(base).map(|(o, b)| o.total().saturating_sub(b.total()).to_string()).collect();
            let _ = writeln!(w, "| `{element}` | {list} | {} |", cost.join(", "));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use crate::formulation::formulate;
    use crate::parse::MechanismDef;

    /// Every row of every joint kind, driver and fix carries its unit: a row in metres gives N,
    /// an angle or a dimensionless orientation row N·m (docs/formulation.md's row tables), a user
    /// constraint nothing — checked against the row names of each kind, planar and spatial.
    #[test]
    fn every_joint_row_has_a_unit() {
        let metres = ["x", "y", "z", "normal", "distance", "length", "stroke", "offset", "offset_x", "offset_y"];
        let turns = ["phi", "angle", "cross", "twist", "rx", "ry", "rz", "axis_x", "axis_y", "normal_x", "normal_y"];
        let planar = "Planar {
            body a { mass: 1.0, inertia: 0.1, at: [0.1, 0.0, 0.0] }
            body b { mass: 1.0, inertia: 0.1, at: [0.4, 0.0, 0.0] }
            body c { mass: 1.0, inertia: 0.1, at: [0.4, 0.5, 0.0] }
            revolute pin: ground[0.0, 0.0] ~ a[-0.1, 0.0];
            translational slide: ground[0.0, 0.0] along [1.0, 0.0] ~ b[0.0, 0.0] along [1.0, 0.0];
            revolute_translational a[0.1, 0.0] ~ b[0.0, 0.0] along [1.0, 0.0];
            revolute_revolute a[0.1, 0.0] ~ c[0.0, 0.0] { length: 0.5 };
            rigid b[0.0, 0.5] ~ c[0.0, 0.0];
            point a.tip = [0.1, 0.0];
            point c.q = [0.0, 0.0];
            drive angle(a, c) = t;
            drive distance(a.tip, c.q) = 0.5 + t;
            drive a.x = 0.1;
            fix c.phi;
            constraint a.y = b.y;
        }";
        let spatial = "Spatial {
            spatial;
            body b1 { mass: 1.0, inertia: [0.1, 0.2, 0.3], at: [0.1, 0.2, 0.3] }
            body b2 { mass: 1.0, inertia: [0.1, 0.2, 0.3], at: [0.5, 0.1, 0.2] }
            spherical ground[0.0, 0.0, 0.0] ~ b1[0.1, 0.2, 0.3];
            universal b1[0.2, 0.0, 0.0] along [1.0, 0.0, 0.0] ~ b2[0.0, 0.0, 0.1] along [0.0, 1.0, 0.0];
            revolute hinge: ground[0.5, 0.0, 0.0] along [0.0, 0.0, 1.0] ~ b1[0.0, 0.1, 0.0] along [0.0, 0.0, 1.0];
            cylindrical cyl: b1[0.1, 0.0, 0.0] along [0.0, 1.0, 0.0] ~ b2[0.0, 0.0, 0.0] along [0.0, 1.0, 0.0];
            translational slide: ground[0.0, 1.0, 0.0] along [1.0, 0.0, 0.0] ~ b2[0.1, 0.0, 0.0] along [1.0, 0.0, 0.0];
            planar b1[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0] ~ b2[0.0, 0.2, 0.0] along [0.0, 0.0, 1.0];
            rigid b1[0.1, 0.0, 0.0] ~ b2[0.0, 0.0, 0.1];
            rigid b2[0.0, 0.1, 0.0] along [0.0, 1.0, 0.0] reference [0.0, 0.0, 1.0] ~ b1[0.0, 0.0, 0.0] along [0.0, 1.0, 0.0];
            point_on_line ground[0.0, 0.0, 1.0] along [1.0, 1.0, 0.0] ~ b2[0.0, 0.0, 0.2];
            point_on_plane b1[0.1, 0.0, 0.0] along [0.0, 0.0, 1.0] ~ b2[0.0, 0.0, 0.0];
            distance b1[0.0, 0.0, 0.3] ~ b2[0.1, 0.0, 0.0] { length: 0.5 };
            drive hinge.angle = t;
            drive cyl.stroke = t;
            drive slide.stroke = t;
            drive b2.z = t;
            fix b1.x;
            constraint b1.x = b2.y;
        }";
        let (mut seen_metres, mut seen_turns) = (0, 0);
        for src in [planar, spatial] {
            let model = syn::parse_str::<MechanismDef>(src).expect("parses").validate().unwrap_or_else(|_| panic!("valid: {src}"));
            let f = formulate(&model);
            for (name, unit) in f.row_names.iter().zip(&f.row_units) {
                let row = name.rsplit(": ").next().expect("a row name");
                let expected = if metres.contains(&row) {
                    seen_metres += 1;
                    "N"
                } else if turns.contains(&row) {
                    seen_turns += 1;
                    "N·m"
                } else {
                    assert_eq!(row, "user", "{name}: a row name of neither list");
                    ""
                };
                assert_eq!(unit.multiplier(), expected, "{name}");
            }
        }
        assert!(seen_metres > 20 && seen_turns > 15, "{seen_metres} rows in metres, {seen_turns} in angles");
    }
}
