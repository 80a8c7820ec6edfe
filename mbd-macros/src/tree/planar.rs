//! Planar trees: each body's pose (x, y, φ) along the tree, and the initial joint coordinates.

use std::collections::HashMap;

use super::{Articulation, Tree, TreeFrame};
use crate::elements::Relative;
use crate::frames::Builder;
use crate::model::{BodyRef, MExpr};
use crate::sym::{Func, Id, Var};

/// Each body's frame: its pose ([`poses`]) and its twist, the pose's rate along v = q̇ (global
/// components either way in the plane).
pub fn frames(b: &mut Builder, tree: &Tree) -> Vec<TreeFrame> {
    let (poses, pins) = poses(b, tree);
    let (zero, one, minus) = (b.g.num(0.0), b.g.num(1.0), b.g.num(-1.0));
    let rates: Vec<Id> = (0..tree.nq).map(|i| b.g.var(Var::Qd(i as u16))).collect();
    let seed = |v: Var| match v {
        Var::Q(i) => Some(rates[i as usize]),
        _ => None,
    };
    let mut memo = HashMap::new();
    poses
        .into_iter()
        .zip(pins)
        .map(|(pose, pin)| {
            let twist: Vec<Id> = pose.iter().map(|&x| b.g.directional(x, &seed, &mut memo)).collect();
            // A revolute link at its pin, where its screw (ẋ, ẏ, φ̇) is (0, 0, ±1).
            let articulation = pin.map(|(point, forward)| Articulation {
                origin: point.to_vec(),
                screws: vec![vec![zero, zero, if forward { one } else { minus }]],
                rotated: None,
            });
            TreeFrame { pose: pose.to_vec(), global: twist.clone(), twist, bias: None, articulation }
        })
        .collect()
}

/// A revolute link's pin, global, and whether φ_child turns with +θ (the joint not run
/// backwards).
type Pin = Option<([Id; 2], bool)>;

/// A planar pose (x, y, φ).
type Pose = [Id; 3];

/// Each body's pose as a function of the joint coordinates, built parents first (Nikravesh
/// 9.2): for a joint declared `Pi ~ Pj` whose parent side is i,
///
/// - revolute: φ_j = φ_i + θ, r_j = r_i + A_i s′_i − A_j s′_j;
/// - rigid: the same with θ the joint's constant angle;
/// - translational: φ_j = φ_i + α_i − α_j (+ π where the axes point apart at the bodies' `at:`
///   poses), α the angle of a body-frame axis, so that u_j = ±u_i; r_j = r_i + A_i s′_i + s u_i
///   − A_j s′_j;
///
/// and the same relations solved for body i where the parent is j. A free body's pose is its
/// coordinates.
fn poses(b: &mut Builder, tree: &Tree) -> (Vec<[Id; 3]>, Vec<Pin>) {
    let model = b.model;
    let mut poses: Vec<Option<Pose>> = vec![None; tree.links.len()];
    let mut pins: Vec<Pin> = vec![None; tree.links.len()];
    let zero = b.g.num(0.0);
    for &k in &tree.order {
        let link = &tree.links[k];
        let q = |b: &mut Builder, i: usize| b.g.var(Var::Q((link.first + i) as u16));
        let Some(index) = link.joint else {
            poses[k] = Some([q(b, 0), q(b, 1), q(b, 2)]);
            continue;
        };
        let parent = match link.parent {
            BodyRef::Ground => [zero; 3],
            BodyRef::Body(p) => poses[p].expect("a parent is placed before its children"),
        };
        let relative = model.constraints[index].kind.relative().expect("a tree joint has a relative form");
        let coordinate = (link.count == 1).then(|| q(b, 0));
        let (pose, pin) = child_pose(b, relative, link.reversed, parent, coordinate);
        poses[k] = Some(pose);
        if matches!(relative, Relative::Revolute { .. }) {
            pins[k] = Some((pin, !link.reversed));
        }
    }
    (poses.into_iter().map(|p| p.expect("every body is placed")).collect(), pins)
}

/// The pose of a joint's child from its parent's: body j from body i, or body i from body j
/// where `reversed`; and the joint's point on the parent, global (r_parent + A_parent s′_parent).
fn child_pose(b: &mut Builder, relative: Relative, reversed: bool, parent: Pose, coordinate: Option<Id>) -> (Pose, [Id; 2]) {
    let [fp, fc] = if reversed { [-1.0, 1.0] } else { [1.0, -1.0] };
    let (sign_p, sign_c) = (b.g.num(fp), b.g.num(fc));
    let (parent_point, child_point, turn) = match relative {
        Relative::Revolute { i, j } => {
            let (pi, pj) = (local(b, &i.point), local(b, &j.point));
            let theta = coordinate.expect("a revolute joint has its angle");
            (if reversed { pj } else { pi }, if reversed { pi } else { pj }, theta)
        }
        Relative::Rigid { i, j, angle } => {
            let (pi, pj) = (local(b, &i.point), local(b, &j.point));
            let theta = b.expr(angle);
            (if reversed { pj } else { pi }, if reversed { pi } else { pj }, theta)
        }
        Relative::Translational { i, axis_i, j, axis_j } => {
            let (pi, pj) = (local(b, &i.point), local(b, &j.point));
            let offset = axis_offset(b, [i.body, j.body], [axis_i, axis_j]);
            (if reversed { pj } else { pi }, if reversed { pi } else { pj }, offset)
        }
        Relative::Spatial { .. } => unreachable!("a planar tree has planar joints"),
    };
    // φ_child = φ_parent ± turn; r_child = r_parent + A_parent s′_parent − A_child s′_child
    let signed_turn = b.g.mul(sign_p, turn);
    let phi = b.g.add(parent[2], signed_turn);
    let arm_p = rotate(b, parent[2], parent_point);
    let arm_c = rotate(b, phi, child_point);
    let point = [0, 1].map(|a| b.g.add(parent[a], arm_p[a]));
    let mut r = [0, 1].map(|a| b.g.sub(point[a], arm_c[a]));
    if let (Relative::Translational { axis_i, .. }, Some(s)) = (relative, coordinate) {
        // P_j = P_i + s u_i, u_i on body i: the parent, or the child where reversed.
        let phi_i = if reversed { phi } else { parent[2] };
        let u = unit(b, axis_i);
        let u = rotate(b, phi_i, u);
        for a in 0..2 {
            let su = b.g.mul(s, u[a]);
            let signed = b.g.mul(sign_c, su);
            r[a] = b.g.sub(r[a], signed);
        }
    }
    ([r[0], r[1], phi], point)
}

/// α_i − α_j (+ π where the axes point apart at the bodies' `at:` poses, evaluated at the
/// parameters' defaults): φ_j − φ_i of a translational joint whose axes stay parallel.
fn axis_offset(b: &mut Builder, bodies: [BodyRef; 2], axes: [&Vec<MExpr>; 2]) -> Id {
    let [alpha_i, alpha_j] = axes.map(|axis| {
        let [x, y] = local(b, axis);
        b.g.atan2(y, x)
    });
    let offset = b.g.sub(alpha_i, alpha_j);
    let model = b.model;
    let [phi_i, phi_j] = bodies.map(|body| match body {
        BodyRef::Ground => b.g.num(0.0),
        BodyRef::Body(k) => b.expr(&model.bodies[k].q0[2]),
    });
    // cos(φ_j + α_j − φ_i − α_i) at the initial poses
    let relative = b.g.sub(phi_j, phi_i);
    let apart = b.g.sub(relative, offset);
    let cos = b.g.call(Func::Cos, apart);
    let params = &b.model.params;
    let value = b.g.eval(cos, &|v| match v {
        Var::Param(k) => params[k as usize].default,
        _ => 0.0,
    });
    if value < 0.0 {
        let pi = b.g.num(std::f64::consts::PI);
        b.g.add(offset, pi)
    } else {
        offset
    }
}

/// The initial joint coordinates and their rates from the bodies' `at:` poses and `velocity:`
/// (docs/formulation.md, "Joint coordinates"): a revolute joint's θ = φ_j − φ_i, a translational
/// joint's stroke s = u_iᵀ(r^P_j − r^P_i) — P_j projected on the axis — and a free body's pose;
/// their rates θ̇ = ω_j − ω_i, ṡ = u̇_iᵀ d + u_iᵀ ḋ. Where the poses do not close a loop, the
/// kinematic solve (assembly) moves these guesses onto Φ = 0.
pub fn initial(b: &mut Builder, tree: &Tree) -> (Vec<Id>, Vec<Id>) {
    let model = b.model;
    let (mut q0, mut v0) = (Vec::with_capacity(tree.nq), Vec::with_capacity(tree.nq));
    let zero = b.g.num(0.0);
    let start = |b: &mut Builder, body: BodyRef| -> (Pose, Pose) {
        match body {
            BodyRef::Ground => ([zero; 3], [zero; 3]),
            BodyRef::Body(k) => {
                let at = &model.bodies[k];
                ([0, 1, 2].map(|c| b.expr(&at.q0[c])), [0, 1, 2].map(|c| b.expr(&at.v0[c])))
            }
        }
    };
    for (k, link) in tree.links.iter().enumerate() {
        let Some(index) = link.joint else {
            let (pose, rate) = start(b, BodyRef::Body(k));
            q0.extend(pose);
            v0.extend(rate);
            continue;
        };
        match model.constraints[index].kind.relative().expect("a tree joint has a relative form") {
            Relative::Rigid { .. } | Relative::Spatial { .. } => {}
            Relative::Revolute { i, j } => {
                let ((pi, wi), (pj, wj)) = (start(b, i.body), start(b, j.body));
                q0.push(b.g.sub(pj[2], pi[2]));
                v0.push(b.g.sub(wj[2], wi[2]));
            }
            Relative::Translational { i, axis_i, j, .. } => {
                let ((pi, vi), (pj, vj)) = (start(b, i.body), start(b, j.body));
                let (si, sj) = (local(b, &i.point), local(b, &j.point));
                let (arm_i, arm_j) = (rotate(b, pi[2], si), rotate(b, pj[2], sj));
                let u = unit(b, axis_i);
                let u = rotate(b, pi[2], u);
                // d = r_j + A_j s′_j − r_i − A_i s′_i, ḋ = v_j + ω_j ⊥(A_j s′_j) − v_i − ω_i ⊥(A_i s′_i)
                let d = [0, 1].map(|a| {
                    let at_j = b.g.add(pj[a], arm_j[a]);
                    let at_i = b.g.add(pi[a], arm_i[a]);
                    b.g.sub(at_j, at_i)
                });
                let swing = |b: &mut Builder, w: Id, arm: [Id; 2]| {
                    let minus_y = b.g.neg(arm[1]);
                    [b.g.mul(w, minus_y), b.g.mul(w, arm[0])]
                };
                let (turn_j, turn_i) = (swing(b, vj[2], arm_j), swing(b, vi[2], arm_i));
                let d_rate = [0, 1].map(|a| {
                    let at_j = b.g.add(vj[a], turn_j[a]);
                    let at_i = b.g.add(vi[a], turn_i[a]);
                    b.g.sub(at_j, at_i)
                });
                let u_rate = swing(b, vi[2], u);
                q0.push(b.dot(&u, &d));
                let along = b.dot(&u_rate, &d);
                let stretch = b.dot(&u, &d_rate);
                v0.push(b.g.add(along, stretch));
            }
        }
    }
    (q0, v0)
}

/// A body-frame point or axis's two components.
fn local(b: &mut Builder, v: &[MExpr]) -> [Id; 2] {
    [b.expr(&v[0]), b.expr(&v[1])]
}

/// v/|v|.
fn unit(b: &mut Builder, v: &[MExpr]) -> [Id; 2] {
    let [x, y] = local(b, v);
    let x2 = b.g.powi(x, 2);
    let y2 = b.g.powi(y, 2);
    let n2 = b.g.add(x2, y2);
    let norm = b.g.call(Func::Sqrt, n2);
    [b.g.div(x, norm), b.g.div(y, norm)]
}

/// A(φ) v.
fn rotate(b: &mut Builder, phi: Id, v: [Id; 2]) -> [Id; 2] {
    let (s, c) = (b.g.call(Func::Sin, phi), b.g.call(Func::Cos, phi));
    let cx = b.g.mul(c, v[0]);
    let sy = b.g.mul(s, v[1]);
    let sx = b.g.mul(s, v[0]);
    let cy = b.g.mul(c, v[1]);
    [b.g.sub(cx, sy), b.g.add(sx, cy)]
}
