//! Spatial trees (Wallrapp 2.6.2, 3A.2): each body's pose (r, p) and twist along the tree, and
//! the initial joint coordinates (docs/formulation.md, "Spatial joint coordinates").
//!
//! A joint relates its markers' frames (`elements::spatial::Marker`: a point s′ and a triad C,
//! the columns x′, y′, z′ in body axes): A_j C_j = A_i C_i R_z(θ) F — a turn θ about z_i
//! (revolute, cylindrical; θ = 0 otherwise) and a constant half-turn F or none, read from the
//! bodies' `at:` poses (the rows of a translational or rigid joint hold at four such relative
//! orientations, of a revolute at two) — and P_j = P_i + s z_i (translational, cylindrical). A
//! spherical joint's coordinates are body j's orientation in body i's frame, a unit quaternion
//! s (A_j = A_i A(s)), its velocities the relative angular velocity in j's frame. In Euler
//! parameters, with ⊗ the quaternion product and c_i the quaternion of C_i, the child's is
//!
//! p_j = p_i ⊗ c_i ⊗ z(θ) ⊗ f ⊗ c_j*,  or  p_i = p_j ⊗ c_j ⊗ f* ⊗ z(−θ) ⊗ c_i*  where the tree
//! runs the joint from j,
//!
//! and r_c = r_p + A_p s′_p (± s z_i) − A_c s′_c. Each of the link's velocities v_m moves the
//! child by a screw constant in the child's frame, σ_m = (σ_lin, σ_ang): a turn about z by
//! σ_ang = ±z′ with σ_lin = s′_c × σ_ang (the joint point stays), a slide by σ_lin = ±z′, a
//! spherical joint's ω_m by σ_ang = e_m. So the twist follows its parent's as
//!
//! ω′_c = A_cᵀ ω_p + Σ σ_ang,m v_m,  ṙ_c = ṙ_p + ω_p × (r_c − r_p) + A_c Σ σ_lin,m v_m,
//!
//! ω_p global; a free body's twist is its velocities, as in body coordinates. The twist's rate
//! at constant v (J̇ v) follows the same way, d(A_c y′)/dt = ω_c × A_c y′ for the link's own
//! motion y′ = σ v:
//!
//! ω̇_c = ω̇_p + ω_c × A_c Σ σ_ang,m v_m,  r̈_c = r̈_p + ω̇_p × d + ω_p × ḋ + ω_c × A_c Σ σ_lin,m v_m,
//!
//! d = r_c − r_p, and ω̇′_c = A_cᵀ ω̇_c as body coordinates hold it.

use super::{Articulation, Tree, TreeFrame};
use crate::elements::spatial::Marker;
use crate::elements::{Relative, SpatialKind};
use crate::frames::{rotation_matrix, Builder};
use crate::model::{BodyRef, Coord};
use crate::sym::{Func, Id, Var};

type Vec3 = [Id; 3];
type Quaternion = [Id; 4];
type Rotation = [[Id; 3]; 3];

/// A body placed by the tree: its pose, rotation, global twist and the twist's rate at constant
/// v (J̇ v, global: r̈ and ω̇ with v̇ = 0).
#[derive(Clone, Copy)]
struct Placed {
    r: Vec3,
    p: Quaternion,
    a: Rotation,
    v: Vec3,
    w: Vec3,
    dv: Vec3,
    dw: Vec3,
}

/// How a tree joint places its child: the child's orientation relative to the parent's
/// (p_c = p_p ⊗ relative), the translation from the parent's origin to the child's in the
/// parent's and the child's frames (r_c = r_p + A_p to_point − A_c from_point + stroke), and
/// the screws, constant in the child's frame.
struct Placement {
    relative: Quaternion,
    parent_point: Vec3,
    child_point: Vec3,
    /// s z_i (global) where the joint slides, given the child's rotation.
    stroke: Option<(Id, Vec3, BodyRef)>,
    screws: Vec<([Id; 3], [Id; 3])>,
    /// A spherical joint: its velocities are ω′ of the child relative to the parent.
    ball: bool,
}

/// Each body's frame along the tree (the module's equations).
pub fn frames(b: &mut Builder, tree: &Tree) -> Vec<TreeFrame> {
    let (zero, one) = (b.g.num(0.0), b.g.num(1.0));
    let identity = [[one, zero, zero], [zero, one, zero], [zero, zero, one]];
    let ground = Placed { r: [zero; 3], p: [one, zero, zero, zero], a: identity, v: [zero; 3], w: [zero; 3], dv: [zero; 3], dw: [zero; 3] };
    let mut placed: Vec<Option<Placed>> = vec![None; tree.links.len()];
    let mut frames: Vec<Option<TreeFrame>> = (0..tree.links.len()).map(|_| None).collect();
    for &k in &tree.order {
        let link = &tree.links[k];
        let q: Vec<Id> = (link.first..link.first + link.count).map(|i| b.g.var(Var::Q(i as u16))).collect();
        let v: Vec<Id> = (link.first_v..link.first_v + link.count_v).map(|i| b.g.var(Var::Qd(i as u16))).collect();
        let (body, angular, articulation) = match link.joint {
            None => {
                // a free body: its own pose and velocities
                let (r, p) = ([q[0], q[1], q[2]], unit(b, [q[3], q[4], q[5], q[6]]));
                let a = rotation_matrix(&mut b.g, p);
                let angular = [v[3], v[4], v[5]];
                let w = times(b, &a, angular);
                // at its centre of mass, ω′ turned global: the six unit twists
                let screws = (0..6).map(|m| (0..6).map(|c| if c == m { one } else { zero }).collect()).collect();
                let articulation = Articulation { origin: r.to_vec(), screws, rotated: Some((3, a)) };
                // ṙ and ω′ are the velocities: no rate at constant v (d(A ω′)/dt = ω × ω = 0)
                (Placed { r, p, a, v: [v[0], v[1], v[2]], w, dv: [zero; 3], dw: [zero; 3] }, angular, articulation)
            }
            Some(index) => {
                let parent = match link.parent {
                    BodyRef::Ground => ground,
                    BodyRef::Body(p) => placed[p].expect("a parent is placed before its children"),
                };
                let placement = placement(b, tree, k, index, &q);
                let (point, screws, ball) = (placement.child_point, placement.screws.clone(), placement.ball);
                let (body, angular) = child(b, &parent, placement, &placed, &v);
                (body, angular, articulation(b, &body, point, &screws, ball))
            }
        };
        let twist = [body.v[0], body.v[1], body.v[2], angular[0], angular[1], angular[2]];
        let pose = [body.r[0], body.r[1], body.r[2], body.p[0], body.p[1], body.p[2], body.p[3]];
        let global = [body.v[0], body.v[1], body.v[2], body.w[0], body.w[1], body.w[2]];
        // J̇ v as body coordinates hold it: r̈ global, ω̇′ = Aᵀ ω̇ (d(Aᵀ)/dt ω = −ω′ × ω′ = 0)
        let dw_body = transpose_times(b, &body.a, body.dw);
        let bias = [body.dv[0], body.dv[1], body.dv[2], dw_body[0], dw_body[1], dw_body[2]];
        frames[k] = Some(TreeFrame {
            pose: pose.to_vec(),
            twist: twist.to_vec(),
            global: global.to_vec(),
            bias: Some(bias.to_vec()),
            articulation: Some(articulation),
        });
        placed[k] = Some(body);
    }
    frames.into_iter().map(|f| f.expect("every body is placed")).collect()
}

/// The child of a link placed from its parent: its pose, its twist (global, and ω′ in its own
/// frame).
fn child(b: &mut Builder, parent: &Placed, placement: Placement, placed: &[Option<Placed>], v: &[Id]) -> (Placed, Vec3) {
    let p = product(b, parent.p, placement.relative);
    let a = rotation_matrix(&mut b.g, p);
    let at_parent = times(b, &parent.a, placement.parent_point);
    let at_child = times(b, &a, placement.child_point);
    let mut r: Vec3 = std::array::from_fn(|c| {
        let s = b.g.add(parent.r[c], at_parent[c]);
        b.g.sub(s, at_child[c])
    });
    if let Some((s, axis, on)) = placement.stroke {
        // z_i = A_i z′_i, body i the child's own where the tree runs the joint backwards
        let rotation = match on {
            BodyRef::Ground => None,
            BodyRef::Body(k) if placed[k].is_none() => Some(a),
            BodyRef::Body(k) => placed[k].map(|body| body.a),
        };
        let z = match rotation {
            Some(rotation) => times(b, &rotation, axis),
            None => axis,
        };
        r = std::array::from_fn(|c| {
            let t = b.g.mul(s, z[c]);
            b.g.add(r[c], t)
        });
    }
    // ω′ = A_cᵀ ω_p + Σ σ_ang v; ṙ = ṙ_p + ω_p × (r − r_p) + A_c Σ σ_lin v
    let mut angular = transpose_times(b, &a, parent.w);
    let zero = b.g.num(0.0);
    let mut linear_local = [zero; 3];
    for ((lin, ang), &vm) in placement.screws.iter().zip(v) {
        for c in 0..3 {
            let (tl, ta) = (b.g.mul(lin[c], vm), b.g.mul(ang[c], vm));
            linear_local[c] = b.g.add(linear_local[c], tl);
            angular[c] = b.g.add(angular[c], ta);
        }
    }
    let arm: Vec3 = std::array::from_fn(|c| b.g.sub(r[c], parent.r[c]));
    let swing = b.cross(parent.w, arm);
    let along = times(b, &a, linear_local);
    let velocity: Vec3 = std::array::from_fn(|c| {
        let s = b.g.add(parent.v[c], swing[c]);
        b.g.add(s, along[c])
    });
    let w = times(b, &a, angular);
    // J̇ v at constant v: d(A_c y′)/dt = ω_c × A_c y′ for the link's own motion y′ = σ v, so
    // ω̇ = ω̇_p + ω_c × (A_c σ_ang v) and r̈ = r̈_p + ω̇_p × d + ω_p × ḋ + ω_c × (A_c σ_lin v)
    let turn: Vec3 = std::array::from_fn(|c| b.g.sub(w[c], parent.w[c]));
    let dw_own = b.cross(w, turn);
    let dw: Vec3 = std::array::from_fn(|c| b.g.add(parent.dw[c], dw_own[c]));
    let arm_rate: Vec3 = std::array::from_fn(|c| b.g.sub(velocity[c], parent.v[c]));
    let (lever, stretch, own) = (b.cross(parent.dw, arm), b.cross(parent.w, arm_rate), b.cross(w, along));
    let dv: Vec3 = std::array::from_fn(|c| {
        let s = b.g.add(parent.dv[c], lever[c]);
        let s = b.g.add(s, stretch[c]);
        b.g.add(s, own[c])
    });
    (Placed { r, p, a, v: velocity, w, dv, dw }, angular)
}

/// A joint's link as the articulated-body solve takes it (`Articulation`): at the joint point
/// on the child, o = r + A s′_c, where a screw (σ_lin, σ_ang) of the child's frame is
/// (A (σ_lin − s′_c × σ_ang), A σ_ang) — a turn's linear part folds to zero there, as σ_lin =
/// s′_c × σ_ang is the same node — and a ball joint's ω′ turned global, its screws (0, e_m).
fn articulation(b: &mut Builder, body: &Placed, point: Vec3, screws: &[([Id; 3], [Id; 3])], ball: bool) -> Articulation {
    let arm = times(b, &body.a, point);
    let origin = (0..3).map(|c| b.g.add(body.r[c], arm[c])).collect();
    let (zero, one) = (b.g.num(0.0), b.g.num(1.0));
    if ball {
        let screws = (0..3).map(|m| (0..6).map(|c| if c == m + 3 { one } else { zero }).collect()).collect();
        return Articulation { origin, screws, rotated: Some((0, body.a)) };
    }
    let screws = screws
        .iter()
        .map(|&(lin, ang)| {
            let swing = b.cross(point, ang);
            let at_point: Vec3 = std::array::from_fn(|c| b.g.sub(lin[c], swing[c]));
            let (lin, ang) = (times(b, &body.a, at_point), times(b, &body.a, ang));
            lin.into_iter().chain(ang).collect()
        })
        .collect();
    Articulation { origin, screws, rotated: None }
}

/// A tree joint's placement of its child (the module's equations).
fn placement(b: &mut Builder, tree: &Tree, k: usize, index: usize, q: &[Id]) -> Placement {
    let link = &tree.links[k];
    let Some(Relative::Spatial { kind, i, j }) = b.model.constraints[index].kind.relative() else {
        unreachable!("a spatial tree joint has a spatial relative form")
    };
    let (parent_marker, child_marker) = if link.reversed { (j, i) } else { (i, j) };
    let parent_point = local(b, &parent_marker.loc.point);
    let child_point = local(b, &child_marker.loc.point);
    let zero = b.g.num(0.0);
    if kind == SpatialKind::Spherical {
        let relative = unit(b, [q[0], q[1], q[2], q[3]]);
        // σ_ang = e_m, σ_lin = s′_c × e_m
        let screws = (0..3)
            .map(|m| {
                let e: Vec3 = std::array::from_fn(|c| b.g.num(if c == m { 1.0 } else { 0.0 }));
                (b.cross(child_point, e), e)
            })
            .collect();
        return Placement { relative, parent_point, child_point, stroke: None, screws, ball: true };
    }
    let (ci, cj) = (marker_quaternion(b, i), marker_quaternion(b, j));
    let flip = half_turn(b, kind, i, j);
    let (turns, slides) = match kind {
        SpatialKind::Revolute => (true, false),
        SpatialKind::Translational => (false, true),
        SpatialKind::Cylindrical => (true, true),
        SpatialKind::Rigid | SpatialKind::Spherical => (false, false),
    };
    let theta = turns.then(|| q[0]);
    let stroke = slides.then(|| q[usize::from(turns)]);
    let turn = |b: &mut Builder, sign: f64| -> Quaternion {
        let Some(theta) = theta else { return identity(b) };
        let half = b.g.num(0.5 * sign);
        let angle = b.g.mul(half, theta);
        [b.g.call(Func::Cos, angle), zero, zero, b.g.call(Func::Sin, angle)]
    };
    let relative = if link.reversed {
        let f = conjugate(b, flip.quaternion);
        let z = turn(b, -1.0);
        let ci_star = conjugate(b, ci);
        chain(b, &[cj, f, z, ci_star])
    } else {
        let z = turn(b, 1.0);
        let cj_star = conjugate(b, cj);
        chain(b, &[ci, z, flip.quaternion, cj_star])
    };
    // The joint's axis in the child's frame, signed as the child moves: +z′_j (times F's zz
    // sign) where the child is j, −z′_i where it is i.
    let axis = if link.reversed {
        let z = unit_axis(b, i);
        z.map(|c| b.g.neg(c))
    } else {
        let z = unit_axis(b, j);
        let s = b.g.num(flip.z_sign);
        z.map(|c| b.g.mul(s, c))
    };
    let mut screws = Vec::new();
    if turns {
        screws.push((b.cross(child_point, axis), axis));
    }
    if slides {
        screws.push((axis, [zero; 3]));
    }
    let stroke = stroke.map(|s| {
        // P_j = P_i + s z_i; z_i = A_i z′_i on body i
        let z = unit_axis(b, i);
        let signed = if link.reversed { b.g.neg(s) } else { s };
        (signed, z, i.loc.body)
    });
    Placement { relative, parent_point, child_point, stroke, screws, ball: false }
}

/// The constant half-turn F between two markers at the bodies' `at:` poses (evaluated at the
/// parameters' defaults): for a turning joint the identity or a half-turn about x (z_j = ±z_i),
/// else the one of the identity and the half-turns about x, y, z nearest C_iᵀ A_iᵀ A_j C_j.
struct HalfTurn {
    quaternion: Quaternion,
    /// F's zz entry: whether z_j = z_i (1) or −z_i (−1).
    z_sign: f64,
}

fn half_turn(b: &mut Builder, kind: SpatialKind, i: &Marker, j: &Marker) -> HalfTurn {
    let [ti, tj] = [i, j].map(|m| {
        let p = initial_quaternion(b, m.loc.body);
        let a = rotation_matrix(&mut b.g, p);
        let local = b.local_triad(&m.axis, &m.reference);
        local.map(|column| times(b, &a, column))
    });
    let params = &b.model.params;
    let value = |b: &Builder, x: Id| {
        b.g.eval(x, &|v| match v {
            Var::Param(k) => params[k as usize].default,
            _ => 0.0,
        })
    };
    // (x_iᵀ x_j, y_iᵀ y_j, z_iᵀ z_j)
    let d: [f64; 3] = std::array::from_fn(|c| {
        let dot = b.dot(&ti[c], &tj[c]);
        value(b, dot)
    });
    let candidates: [([f64; 3], [f64; 4]); 4] = [
        ([1.0, 1.0, 1.0], [1.0, 0.0, 0.0, 0.0]),
        ([1.0, -1.0, -1.0], [0.0, 1.0, 0.0, 0.0]),
        ([-1.0, 1.0, -1.0], [0.0, 0.0, 1.0, 0.0]),
        ([-1.0, -1.0, 1.0], [0.0, 0.0, 0.0, 1.0]),
    ];
    let turning = matches!(kind, SpatialKind::Revolute | SpatialKind::Cylindrical);
    let (signs, quaternion) = if turning {
        candidates[if d[2] < 0.0 { 1 } else { 0 }]
    } else {
        let score = |s: &[f64; 3]| s.iter().zip(&d).map(|(a, b)| a * b).sum::<f64>();
        *candidates.iter().max_by(|x, y| score(&x.0).total_cmp(&score(&y.0))).expect("four candidates")
    };
    HalfTurn { quaternion: quaternion.map(|x| b.g.num(x)), z_sign: signs[2] }
}

/// q̇ = B(q) v along the tree: v = q̇ for angles and strokes, ṡ = ½ Lᵀ(s) ω for a spherical
/// joint's quaternion, and a free body's ṙ = v_r, ṗ = ½ Lᵀ(p) ω′.
pub fn coordinate_rates(b: &mut Builder, tree: &Tree) -> Vec<Id> {
    let mut rates = Vec::with_capacity(tree.nq);
    for link in &tree.links {
        let q = |b: &mut Builder, i: usize| b.g.var(Var::Q((link.first + i) as u16));
        let v = |b: &mut Builder, i: usize| b.g.var(Var::Qd((link.first_v + i) as u16));
        let Some(at) = link.quaternion() else {
            rates.extend((0..link.count).map(|i| v(b, i)));
            continue;
        };
        rates.extend((0..at).map(|i| v(b, i)));
        let e: Quaternion = std::array::from_fn(|c| q(b, at + c));
        let w: Vec3 = std::array::from_fn(|c| v(b, at + c));
        let half = b.g.num(0.5);
        for row in l_transpose(b, e) {
            let d = b.dot(&row, &w);
            rates.push(b.g.mul(half, d));
        }
    }
    rates
}

/// Lᵀ(p) (4×3), ṗ = ½ Lᵀ(p) ω′.
pub fn l_transpose(b: &mut Builder, [e0, e1, e2, e3]: Quaternion) -> [[Id; 3]; 4] {
    let [n1, n2, n3] = [e1, e2, e3].map(|e| b.g.neg(e));
    [[n1, n2, n3], [e0, n3, e2], [e3, e0, n1], [n2, e1, e0]]
}

// --- initial coordinates ----------------------------------------------------------------------

/// The initial joint coordinates and velocities from the bodies' `at:` poses and velocities:
/// θ = atan2(y_iᵀ x_j, x_iᵀ x_j) and θ̇ = z_iᵀ(ω_j − ω_i); s = z_iᵀ d and ṡ = (ω_i × z_i)ᵀ d +
/// z_iᵀ ḋ, d = P_j − P_i; a spherical joint's s = p_p* ⊗ p_c and ω = A_cᵀ(ω_c − ω_p); a free
/// body's pose and velocities. Where the poses do not satisfy a tree joint, the tree places
/// the bodies from these; where they do not close a loop, the kinematic solve (assembly) moves
/// them onto Φ = 0.
pub fn initial(b: &mut Builder, tree: &Tree) -> (Vec<Id>, Vec<Id>) {
    let model = b.model;
    let (mut q0, mut v0) = (Vec::with_capacity(tree.nq), Vec::with_capacity(tree.nv));
    for (k, link) in tree.links.iter().enumerate() {
        let Some(index) = link.joint else {
            let body = &model.bodies[k];
            q0.extend(body.q0.iter().map(|e| b.expr(e)));
            v0.extend(body.v0.iter().map(|e| b.expr(e)));
            continue;
        };
        let Some(Relative::Spatial { kind, i, j }) = model.constraints[index].kind.relative() else {
            unreachable!("a spatial tree joint has a spatial relative form")
        };
        let (si, sj) = (start(b, i.loc.body), start(b, j.loc.body));
        if kind == SpatialKind::Spherical {
            let (parent, child) = if link.reversed { (&sj, &si) } else { (&si, &sj) };
            let parent_star = conjugate(b, parent.p);
            q0.extend(product(b, parent_star, child.p));
            let dw: Vec3 = std::array::from_fn(|c| b.g.sub(child.w[c], parent.w[c]));
            v0.extend(transpose_times(b, &child.a, dw));
            continue;
        }
        let triad = |b: &mut Builder, m: &Marker, s: &Start| b.local_triad(&m.axis, &m.reference).map(|c| times(b, &s.a, c));
        let ([xi, yi, zi], [xj, _, _]) = (triad(b, i, &si), triad(b, j, &sj));
        if matches!(kind, SpatialKind::Revolute | SpatialKind::Cylindrical) {
            let (s, c) = (b.dot(&yi, &xj), b.dot(&xi, &xj));
            q0.push(b.g.atan2(s, c));
            let dw: Vec3 = std::array::from_fn(|c| b.g.sub(sj.w[c], si.w[c]));
            v0.push(b.dot(&zi, &dw));
        }
        if matches!(kind, SpatialKind::Translational | SpatialKind::Cylindrical) {
            let (arm_i, arm_j) = (local(b, &i.loc.point), local(b, &j.loc.point));
            let (arm_i, arm_j) = (times(b, &si.a, arm_i), times(b, &sj.a, arm_j));
            let d: Vec3 = std::array::from_fn(|c| {
                let pj = b.g.add(sj.r[c], arm_j[c]);
                let pi = b.g.add(si.r[c], arm_i[c]);
                b.g.sub(pj, pi)
            });
            let (turn_i, turn_j) = (b.cross(si.w, arm_i), b.cross(sj.w, arm_j));
            let d_rate: Vec3 = std::array::from_fn(|c| {
                let vj = b.g.add(sj.v[c], turn_j[c]);
                let vi = b.g.add(si.v[c], turn_i[c]);
                b.g.sub(vj, vi)
            });
            let z_rate = b.cross(si.w, zi);
            q0.push(b.dot(&zi, &d));
            let (along, stretch) = (b.dot(&z_rate, &d), b.dot(&zi, &d_rate));
            v0.push(b.g.add(along, stretch));
        }
    }
    (q0, v0)
}

/// A body's (or the ground's) pose and global twist at its `at:` pose and velocities.
struct Start {
    r: Vec3,
    p: Quaternion,
    a: Rotation,
    v: Vec3,
    w: Vec3,
}

fn start(b: &mut Builder, body: BodyRef) -> Start {
    let zero = b.g.num(0.0);
    let p = initial_quaternion(b, body);
    let a = rotation_matrix(&mut b.g, p);
    let BodyRef::Body(k) = body else {
        return Start { r: [zero; 3], p, a, v: [zero; 3], w: [zero; 3] };
    };
    let at = &b.model.bodies[k];
    let r = std::array::from_fn(|c| b.expr(&at.q0[c]));
    let v = std::array::from_fn(|c| b.expr(&at.v0[c]));
    let body_w: Vec3 = std::array::from_fn(|c| b.expr(&at.v0[3 + c]));
    let w = times(b, &a, body_w);
    Start { r, p, a, v, w }
}

/// A body's Euler parameters at its `at:` pose; the ground's (1, 0, 0, 0).
fn initial_quaternion(b: &mut Builder, body: BodyRef) -> Quaternion {
    match body {
        BodyRef::Ground => identity(b),
        BodyRef::Body(k) => {
            let at = &b.model.bodies[k].q0;
            std::array::from_fn(|c| b.expr(&at[Coord::E0.index() + c]))
        }
    }
}

// --- quaternions ------------------------------------------------------------------------------

/// p/|p|: a link's quaternion coordinates normalized before they turn anything, so that every
/// rotation the tree builds is orthogonal wherever q is — also off the unit sphere, where an
/// explicit integrator's stages evaluate (q + h k/2 is off it by O(h²)). There the frames stay
/// those of rigid bodies, M stays a rigid tree's, and the articulated-body solve, which moves
/// twists between points rigidly and turns a ball joint's torques by Aᵀ = A⁻¹, inverts it
/// exactly. On the sphere nothing changes: the values are the same and so is every derivative
/// along q̇ = B(q) v, which stays tangent.
fn unit(b: &mut Builder, p: Quaternion) -> Quaternion {
    let norm = b.dot(&p, &p);
    let norm = b.g.call(Func::Sqrt, norm);
    let one = b.g.num(1.0);
    let inverse = b.g.div(one, norm);
    p.map(|x| b.g.mul(x, inverse))
}

fn identity(b: &mut Builder) -> Quaternion {
    let (zero, one) = (b.g.num(0.0), b.g.num(1.0));
    [one, zero, zero, zero]
}

/// a ⊗ b = (a0 b0 − a·b, a0 b + b0 a + a × b): A(a ⊗ b) = A(a) A(b).
fn product(b: &mut Builder, x: Quaternion, y: Quaternion) -> Quaternion {
    let (xv, yv) = ([x[1], x[2], x[3]], [y[1], y[2], y[3]]);
    let dot = b.dot(&xv, &yv);
    let first = b.g.mul(x[0], y[0]);
    let cross = b.cross(xv, yv);
    let mut out = [b.g.sub(first, dot), 0, 0, 0];
    for c in 0..3 {
        let (s, t) = (b.g.mul(x[0], yv[c]), b.g.mul(y[0], xv[c]));
        let st = b.g.add(s, t);
        out[c + 1] = b.g.add(st, cross[c]);
    }
    out
}

fn chain(b: &mut Builder, factors: &[Quaternion]) -> Quaternion {
    factors[1..].iter().fold(factors[0], |acc, &f| product(b, acc, f))
}

fn conjugate(b: &mut Builder, p: Quaternion) -> Quaternion {
    [p[0], b.g.neg(p[1]), b.g.neg(p[2]), b.g.neg(p[3])]
}

/// The quaternion of a marker's triad C = [x′ y′ z′] (Shepperd's method, its branch chosen by
/// the largest of 1 + tr C and the diagonal at the parameters' defaults).
fn marker_quaternion(b: &mut Builder, m: &Marker) -> Quaternion {
    let [x, y, z] = b.local_triad(&m.axis, &m.reference);
    // C[r][c]: column c is the triad's c-th vector
    let c = [[x[0], y[0], z[0]], [x[1], y[1], z[1]], [x[2], y[2], z[2]]];
    let params = &b.model.params;
    let value = |b: &Builder, x: Id| {
        b.g.eval(x, &|v| match v {
            Var::Param(k) => params[k as usize].default,
            _ => 0.0,
        })
    };
    let trace = {
        let s = b.g.add(c[0][0], c[1][1]);
        b.g.add(s, c[2][2])
    };
    let diagonal = [value(b, trace), value(b, c[0][0]), value(b, c[1][1]), value(b, c[2][2])];
    let branch = (0..4).fold(0, |best, k| if diagonal[k] > diagonal[best] { k } else { best });
    let one = b.g.num(1.0);
    let sum = |b: &mut Builder, r: usize, s: usize| b.g.add(c[r][s], c[s][r]);
    let diff = |b: &mut Builder, r: usize, s: usize| b.g.sub(c[r][s], c[s][r]);
    // 4 e_k² = 1 ± C00 ± C11 ± C22 for the branch's k, then the others over 4 e_k
    let signs: [f64; 3] = match branch {
        0 => [1.0, 1.0, 1.0],
        1 => [1.0, -1.0, -1.0],
        2 => [-1.0, 1.0, -1.0],
        _ => [-1.0, -1.0, 1.0],
    };
    let mut four_e2 = one;
    for (a, &sign) in signs.iter().enumerate() {
        let signed = if sign > 0.0 { c[a][a] } else { b.g.neg(c[a][a]) };
        four_e2 = b.g.add(four_e2, signed);
    }
    let two_e = b.g.call(Func::Sqrt, four_e2);
    let (half, four) = (b.g.num(0.5), b.g.num(4.0));
    let e = b.g.mul(half, two_e);
    let four_e = b.g.mul(four, e);
    let over = |b: &mut Builder, x: Id| b.g.div(x, four_e);
    match branch {
        0 => {
            let (e1, e2, e3) = (diff(b, 2, 1), diff(b, 0, 2), diff(b, 1, 0));
            [e, over(b, e1), over(b, e2), over(b, e3)]
        }
        1 => {
            let (e0, e2, e3) = (diff(b, 2, 1), sum(b, 0, 1), sum(b, 0, 2));
            [over(b, e0), e, over(b, e2), over(b, e3)]
        }
        2 => {
            let (e0, e1, e3) = (diff(b, 0, 2), sum(b, 0, 1), sum(b, 1, 2));
            [over(b, e0), over(b, e1), e, over(b, e3)]
        }
        _ => {
            let (e0, e1, e2) = (diff(b, 1, 0), sum(b, 0, 2), sum(b, 1, 2));
            [over(b, e0), over(b, e1), over(b, e2), e]
        }
    }
}

// --- small vector helpers ---------------------------------------------------------------------

/// A body-frame point's three components.
fn local(b: &mut Builder, v: &[crate::model::MExpr]) -> Vec3 {
    std::array::from_fn(|c| b.expr(&v[c]))
}

/// A marker's unit axis z′ in its body's frame.
fn unit_axis(b: &mut Builder, m: &Marker) -> Vec3 {
    b.local_triad(&m.axis, &m.reference)[2]
}

/// A x.
fn times(b: &mut Builder, a: &Rotation, x: Vec3) -> Vec3 {
    std::array::from_fn(|r| b.dot(&a[r], &x))
}

/// Aᵀ x.
fn transpose_times(b: &mut Builder, a: &Rotation, x: Vec3) -> Vec3 {
    std::array::from_fn(|c| {
        let column = [a[0][c], a[1][c], a[2][c]];
        b.dot(&column, &x)
    })
}
