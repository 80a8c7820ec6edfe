//! Joint friction, declared as options of a revolute or translational joint (Nikravesh 4.5.3,
//! 14.6):
//!
//! - `viscous: c` — torque c θ̇ (θ = φ_j − φ_i) or force c ṡ (s = u_iᵀ(r^P_j − r^P_i)) resisting
//!   the joint's motion, in h;
//! - `coulomb: μ` — regularized Coulomb friction μ N v/√(v² + v_s²) whose normal load N comes
//!   from the joint's own multipliers λ: revolute (`radius: R`) N = |(λ_x, λ_y)| acting on the
//!   arm R; translational N = |λ_normal|, or with `bearing: w` the load of two pads w apart,
//!   |λ_n/2 + λ_a/w| + |λ_n/2 − λ_a/w|. λ-dependent, so kept out of h (`Dynamics::friction_forces`).
//!   `slip_velocity: v_s` (default 1e-3) names the regularization.

use std::collections::HashMap;

use serde_json::{json, Value};

use super::{Force, Generalized};
use crate::elements::spatial::Marker;
use crate::elements::Named;
use crate::frames::Builder;
use crate::json::Ctx;
use crate::model::{BodyRef, Components, Loc, MExpr};

/// The friction forces a joint's options declare (taking those options out), each with the word
/// that names it (`"viscous friction"`). `Err` holds a message in which `{kind}` stands for the
/// joint's keyword.
pub fn from_joint_options(
    options: &mut HashMap<String, MExpr>,
    i: &Loc,
    axis_i: Option<&Components>,
    j: &Loc,
    joint: usize,
) -> Result<Vec<Named>, String> {
    let mut out: Vec<Named> = Vec::new();
    if let Some(c) = options.remove("viscous") {
        let element: Box<dyn Force> = match axis_i {
            Some(axis_i) => Box::new(TranslationalViscous { i: i.clone(), axis_i: axis_i.clone(), j: j.clone(), c }),
            None => Box::new(RevoluteViscous { i: i.body, j: j.body, c }),
        };
        out.push(("viscous friction", element));
    }
    let slip = options.remove("slip_velocity");
    let radius = options.remove("radius");
    let bearing = options.remove("bearing");
    match options.remove("coulomb") {
        Some(mu) => {
            let slip = slip.unwrap_or(MExpr::Num(1e-3));
            let element: Box<dyn Force> = match (axis_i, radius) {
                (Some(axis_i), _) => {
                    Box::new(TranslationalCoulomb { i: i.clone(), axis_i: axis_i.clone(), j: j.clone(), mu, slip, bearing, joint })
                }
                (None, Some(radius)) => Box::new(RevoluteCoulomb { i: i.body, j: j.body, mu, radius, slip, joint }),
                (None, None) => {
                    return Err(
                        "Coulomb friction in a revolute joint needs the pin radius: expected `radius` (m) with `coulomb`, found none; e.g. `{ coulomb: 0.1, radius: 0.01 }`".to_string()
                    )
                }
            };
            out.push(("Coulomb friction", element));
        }
        None => {
            if slip.is_some() || radius.is_some() || bearing.is_some() {
                return Err(
                    "`radius`, `slip_velocity` and `bearing` describe Coulomb friction: give the {kind} joint `coulomb: μ` too".to_string()
                );
            }
        }
    }
    Ok(out)
}

/// Viscous friction in a revolute joint: torque c (φ̇_j − φ̇_i) resisting relative rotation.
#[derive(Debug)]
pub struct RevoluteViscous {
    pub i: BodyRef,
    pub j: BodyRef,
    pub c: MExpr,
}

impl Force for RevoluteViscous {
    fn effect(&self) -> &'static str {
        "viscous joint friction"
    }
    fn kind(&self) -> &'static str {
        "revolute_viscous"
    }
    fn apply(&self, b: &mut Builder, out: &mut Generalized) {
        let theta = b.relative_angle(self.i, self.j);
        let thetadot = b.rate(theta);
        let (tau, _) = b.law(theta, thetadot, &None, &MExpr::Num(0.0), &Some(self.c.clone()), &None);
        b.add_along(&mut out.h, theta, tau);
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"i": cx.body(self.i), "j": cx.body(self.j), "c": cx.expr(&self.c)})
    }
}

/// Viscous friction in a translational joint: force c ṡ resisting sliding, s = u_iᵀ(r_Pj − r_Pi).
#[derive(Debug)]
pub struct TranslationalViscous {
    pub i: Loc,
    pub axis_i: Components,
    pub j: Loc,
    pub c: MExpr,
}

impl Force for TranslationalViscous {
    fn effect(&self) -> &'static str {
        "viscous joint friction"
    }
    fn kind(&self) -> &'static str {
        "translational_viscous"
    }
    fn apply(&self, b: &mut Builder, out: &mut Generalized) {
        let s = b.slide(&self.i, &self.axis_i, &self.j);
        let sdot = b.rate(s);
        let (f, _) = b.law(s, sdot, &None, &MExpr::Num(0.0), &Some(self.c.clone()), &None);
        b.add_along(&mut out.h, s, f);
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"i": cx.loc_axis(&self.i, &self.axis_i), "j": cx.loc(&self.j), "c": cx.expr(&self.c)})
    }
}

/// Coulomb friction in a revolute joint: torque μ R N ω/√(ω² + v_s²) resisting ω = φ̇_j − φ̇_i,
/// N = |(λ_x, λ_y)| the pin force of the joint's rows x, y.
#[derive(Debug)]
pub struct RevoluteCoulomb {
    pub i: BodyRef,
    pub j: BodyRef,
    pub mu: MExpr,
    pub radius: MExpr,
    pub slip: MExpr,
    /// The joint, by its index among the constraints.
    pub joint: usize,
}

impl Force for RevoluteCoulomb {
    fn effect(&self) -> &'static str {
        "Coulomb joint friction"
    }
    fn reads_multipliers_of(&self) -> Option<usize> {
        Some(self.joint)
    }
    fn kind(&self) -> &'static str {
        "revolute_coulomb"
    }
    fn apply(&self, b: &mut Builder, out: &mut Generalized) {
        let theta = b.relative_angle(self.i, self.j);
        let omega = b.rate(theta);
        let (lx, ly) = (b.lambda(self.joint, 0), b.lambda(self.joint, 1));
        let (lx2, ly2) = (b.g.powi(lx, 2), b.g.powi(ly, 2));
        let load2 = b.g.add(lx2, ly2);
        let load = b.g.call(crate::sym::Func::Sqrt, load2);
        let radius = b.expr(&self.radius);
        let arm = b.g.mul(radius, load);
        let tau = b.coulomb(&self.mu, &self.slip, arm, omega);
        b.add_along(&mut out.friction, theta, tau);
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({
            "i": cx.body(self.i), "j": cx.body(self.j), "mu": cx.expr(&self.mu), "radius": cx.expr(&self.radius),
            "slip_velocity": cx.expr(&self.slip), "row": cx.first_rows[self.joint]
        })
    }
}

/// Coulomb friction in a translational joint: force μ N ṡ/√(ṡ² + v_s²) resisting sliding,
/// N = |λ_normal|, or with a bearing length w the load of two pads w apart,
/// |λ_n/2 + λ_a/w| + |λ_n/2 − λ_a/w| (λ_a the reaction moment of the angle row).
#[derive(Debug)]
pub struct TranslationalCoulomb {
    pub i: Loc,
    pub axis_i: Components,
    pub j: Loc,
    pub mu: MExpr,
    pub slip: MExpr,
    pub bearing: Option<MExpr>,
    /// The joint, by its index among the constraints.
    pub joint: usize,
}

impl Force for TranslationalCoulomb {
    fn effect(&self) -> &'static str {
        "Coulomb joint friction"
    }
    fn reads_multipliers_of(&self) -> Option<usize> {
        Some(self.joint)
    }
    fn kind(&self) -> &'static str {
        "translational_coulomb"
    }
    fn apply(&self, b: &mut Builder, out: &mut Generalized) {
        let s = b.slide(&self.i, &self.axis_i, &self.j);
        let sdot = b.rate(s);
        let ln = b.lambda(self.joint, 0);
        let load = match &self.bearing {
            None => b.abs(ln),
            Some(w) => {
                let la = b.lambda(self.joint, 1);
                let w = b.expr(w);
                let half = b.g.num(0.5);
                let f = b.g.mul(half, ln);
                let m = b.g.div(la, w);
                let (p1, p2) = (b.g.add(f, m), b.g.sub(f, m));
                let (a1, a2) = (b.abs(p1), b.abs(p2));
                b.g.add(a1, a2)
            }
        };
        let f = b.coulomb(&self.mu, &self.slip, load, sdot);
        b.add_along(&mut out.friction, s, f);
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({
            "i": cx.loc_axis(&self.i, &self.axis_i), "j": cx.loc(&self.j), "mu": cx.expr(&self.mu),
            "slip_velocity": cx.expr(&self.slip), "bearing": self.bearing.as_ref().map(|w| cx.expr(w)),
            "row": cx.first_rows[self.joint]
        })
    }
}

/// Viscous friction in a spatial joint (docs/formulation.md): torque c θ̇_J resisting the turn of
/// a revolute joint, or force c ṡ_J resisting the slide of a translational one, θ_J and s_J
/// from the joint's markers.
#[derive(Debug)]
pub struct SpatialViscous {
    /// The joint's name, its markers, the coefficient and whether it resists sliding.
    pub joint: String,
    pub i: Marker,
    pub j: Marker,
    pub c: MExpr,
    pub sliding: bool,
}

impl Force for SpatialViscous {
    fn effect(&self) -> &'static str {
        "viscous joint friction"
    }
    fn kind(&self) -> &'static str {
        if self.sliding {
            "translational_viscous"
        } else {
            "revolute_viscous"
        }
    }
    fn apply(&self, b: &mut Builder, out: &mut Generalized) {
        let s = if self.sliding { b.joint_stroke(&self.i, &self.j) } else { b.joint_angle(&self.i, &self.j) };
        let sdot = b.rate(s);
        let (f, _) = b.law(s, sdot, &None, &MExpr::Num(0.0), &Some(self.c.clone()), &None);
        b.add_along(&mut out.h, s, f);
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({"joint": self.joint, "c": cx.expr(&self.c)})
    }
}

/// Coulomb friction in a spatial joint (docs/formulation.md): a revolute joint's torque
/// μ R N θ̇/√(θ̇² + v_s²), N = |(λ_x, λ_y, λ_z)| its pin force; a translational joint's force
/// μ N ṡ/√(ṡ² + v_s²), N = |(λ_offset_x, λ_offset_y)|; each resisting θ_J or s_J, in the
/// λ-dependent friction forces.
#[derive(Debug)]
pub struct SpatialCoulomb {
    /// The joint's name, its index among the constraints, its markers.
    pub joint: String,
    pub index: usize,
    pub i: Marker,
    pub j: Marker,
    pub mu: MExpr,
    /// The pin radius of a revolute joint; `None` for a translational one.
    pub radius: Option<MExpr>,
    pub slip: MExpr,
}

impl Force for SpatialCoulomb {
    fn effect(&self) -> &'static str {
        "Coulomb joint friction"
    }
    fn reads_multipliers_of(&self) -> Option<usize> {
        Some(self.index)
    }
    fn kind(&self) -> &'static str {
        if self.radius.is_some() {
            "revolute_coulomb"
        } else {
            "translational_coulomb"
        }
    }
    fn apply(&self, b: &mut Builder, out: &mut Generalized) {
        let (s, rows) = match self.radius {
            Some(_) => (b.joint_angle(&self.i, &self.j), 0..3),
            None => (b.joint_stroke(&self.i, &self.j), 2..4),
        };
        let sdot = b.rate(s);
        let mut load2 = b.g.num(0.0);
        for row in rows {
            let l = b.lambda(self.index, row);
            let l2 = b.g.powi(l, 2);
            load2 = b.g.add(load2, l2);
        }
        let mut load = b.g.call(crate::sym::Func::Sqrt, load2);
        if let Some(radius) = &self.radius {
            let radius = b.expr(radius);
            load = b.g.mul(radius, load);
        }
        let f = b.coulomb(&self.mu, &self.slip, load, sdot);
        b.add_along(&mut out.friction, s, f);
    }
    fn json(&self, cx: &Ctx) -> Value {
        json!({
            "joint": self.joint, "mu": cx.expr(&self.mu), "radius": self.radius.as_ref().map(|r| cx.expr(r)),
            "slip_velocity": cx.expr(&self.slip), "row": cx.first_rows[self.index]
        })
    }
}
