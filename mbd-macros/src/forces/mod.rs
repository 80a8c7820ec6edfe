//! Force elements (Nikravesh ch. 4): one file per kind.
//!
//! Each kind implements [`Force`]: what it adds to the generalized forces h(q, v, t) — by
//! virtual power, against body frames ([`Builder`]) — to the potential energy V(q), or, for
//! Coulomb friction, to the λ-dependent friction forces; and its model JSON. Gravity is a
//! mechanism-wide statement (`gravity.rs`). A mechanism that declares no element of a kind
//! generates no code for it.

use std::fmt::Debug;

use serde_json::Value;

use crate::frames::Builder;
use crate::json::Ctx;
use crate::model::MExpr;
use crate::sym::{Cmp, Func, Id};

pub mod applied;
pub mod bushing;
pub mod cable;
pub mod contact;
pub mod friction;
pub mod gravity;
pub mod point_to_point;
pub mod rotational;
pub mod stroke;
pub mod torque;
pub mod tyre;

/// What force elements add up to, one node per velocity (h, friction) and V.
pub struct Generalized {
    pub h: Vec<Id>,
    /// Coulomb friction forces: functions of q, v, t and λ, kept out of h (λ-free).
    pub friction: Vec<Id>,
    pub potential: Id,
    /// The switching functions of unilateral elements (`Dynamics::switching_function`), positive
    /// while they push.
    pub switches: Vec<Id>,
}

/// A force element.
pub trait Force: Debug {
    /// The effect it adds, for `Mechanism::EFFECTS` (`"point-to-point spring-damper-actuator"`).
    fn effect(&self) -> &'static str;
    /// The model JSON kind (`"point_to_point"`).
    fn kind(&self) -> &'static str;
    /// Adds its generalized force (and potential energy) to `out`.
    fn apply(&self, b: &mut Builder, out: &mut Generalized);
    /// Its model JSON object without `"kind"` and `"name"`.
    fn json(&self, cx: &Ctx) -> Value;
    /// The constraint (index into `Model::constraints`) whose multipliers it reads — a joint's
    /// Coulomb friction reads its normal load —, if any.
    fn reads_multipliers_of(&self) -> Option<usize> {
        None
    }
}

/// A resolved force statement: label, default name, keyword span, element.
pub type Resolved<'a> = (Option<&'a syn::Ident>, String, proc_macro2::Span, Box<dyn Force>);

/// A validated force element with its name.
pub struct ForceElement {
    /// `"spring crank~rod"`, or the user's label.
    pub name: String,
    pub kind: Box<dyn Force>,
}

impl Builder<'_> {
    /// k (x − x0) + c ẋ + extra, each term only when declared; also (k, x − x0) when there is a
    /// spring, for its energy.
    pub fn law(
        &mut self,
        x: Id,
        xdot: Id,
        k: &Option<MExpr>,
        x0: &MExpr,
        c: &Option<MExpr>,
        extra: &Option<MExpr>,
    ) -> (Id, Option<(Id, Id)>) {
        let mut f = self.g.num(0.0);
        let mut spring = None;
        if let Some(k) = k {
            let k = self.expr(k);
            let x0 = self.expr(x0);
            let stretch = self.g.sub(x, x0);
            let fk = self.g.mul(k, stretch);
            f = self.g.add(f, fk);
            spring = Some((k, stretch));
        }
        if let Some(c) = c {
            let c = self.expr(c);
            let fc = self.g.mul(c, xdot);
            f = self.g.add(f, fc);
        }
        if let Some(e) = extra {
            let e = self.expr(e);
            f = self.g.add(f, e);
        }
        (f, spring)
    }

    /// v + ½ k s² for a spring (k, s); v without one.
    pub fn add_spring_energy(&mut self, v: Id, spring: Option<(Id, Id)>) -> Id {
        match spring {
            None => v,
            Some((k, s)) => {
                let s2 = self.g.powi(s, 2);
                let ks2 = self.g.mul(k, s2);
                let half = self.g.num(0.5);
                let e = self.g.mul(half, ks2);
                self.g.add(v, e)
            }
        }
    }

    /// A force that only pushes, on an overlap δ(q, t) (a penetration, a cable's stretch):
    /// F = max(δᵉ (k + c δ̇), 0) while δ > 0 and 0 otherwise, with V = k δᵉ⁺¹/(e + 1) while δ > 0.
    /// With an exponent (Hunt & Crossley) the damping c δᵉ δ̇ vanishes at first touch; without
    /// one the law is linear, F = max(k δ + c δ̇, 0). Either way the force never pulls, and its
    /// derivatives at δ = 0 are those of the side δ ≤ 0: zero. Also returns the switching
    /// function, positive exactly while the force acts: the unclamped law where δ > 0, δ elsewhere
    /// (a damped contact lets go where the law reaches 0, before δ does).
    pub fn unilateral(&mut self, delta: Id, k: &MExpr, exponent: Option<&MExpr>, c: Option<&MExpr>) -> (Id, Id, Id) {
        let zero = self.g.num(0.0);
        let k = self.expr(k);
        let rate = self.rate_with_time(delta);
        let (f, potential) = match exponent {
            Some(e) => {
                let e = self.expr(e);
                let de = self.g.pow(delta, e);
                let mut stiffness = k;
                if let Some(c) = c {
                    let c = self.expr(c);
                    let cr = self.g.mul(c, rate);
                    stiffness = self.g.add(k, cr);
                }
                let f = self.g.mul(de, stiffness);
                let one = self.g.num(1.0);
                let e1 = self.g.add(e, one);
                let de1 = self.g.pow(delta, e1);
                let kde1 = self.g.mul(k, de1);
                (f, self.g.div(kde1, e1))
            }
            None => {
                let mut f = self.g.mul(k, delta);
                if let Some(c) = c {
                    let c = self.expr(c);
                    let cr = self.g.mul(c, rate);
                    f = self.g.add(f, cr);
                }
                let d2 = self.g.powi(delta, 2);
                let kd2 = self.g.mul(k, d2);
                let half = self.g.num(0.5);
                (f, self.g.mul(half, kd2))
            }
        };
        let switch = self.g.select(Cmp::Gt, delta, zero, f, delta);
        let pushing = self.g.max(f, zero);
        let f = self.g.select(Cmp::Gt, delta, zero, pushing, zero);
        let potential = self.g.select(Cmp::Gt, delta, zero, potential, zero);
        (f, potential, switch)
    }

    /// Regularized Coulomb law μ N v / √(v² + v_s²): ±μN beyond the slip velocity v_s, linear
    /// (a stiff viscous law) through v = 0, smooth for the integrators.
    pub fn coulomb(&mut self, mu: &MExpr, slip: &MExpr, load: Id, v: Id) -> Id {
        let mu = self.expr(mu);
        let vs = self.expr(slip);
        let v2 = self.g.powi(v, 2);
        let vs2 = self.g.powi(vs, 2);
        let r2 = self.g.add(v2, vs2);
        let r = self.g.call(Func::Sqrt, r2);
        let ratio = self.g.div(v, r);
        let mn = self.g.mul(mu, load);
        self.g.mul(mn, ratio)
    }
}

/// An element whose direction is its own (a spring's line, a tyre's vertical) takes no axis:
/// false, with `why` reported on the first `along`, if a side has one.
pub fn no_axis(r: &mut crate::model::Resolver, f: &crate::parse::JointDef, why: &str) -> bool {
    match [&f.i, &f.j].into_iter().find_map(|side| side.along.as_ref()) {
        Some(a) => {
            r.errors.push(a.keyword.span(), why);
            false
        }
        None => true,
    }
}

/// The options of a force element: each known name at most once, each a number-valued
/// expression of the given scope.
pub fn options(
    r: &mut crate::model::Resolver,
    kind: &syn::Ident,
    fields: &[crate::parse::Field],
    known: &[(&str, crate::model::Scope)],
) -> Option<std::collections::HashMap<String, MExpr>> {
    use crate::parse::Value;
    let mut out = std::collections::HashMap::new();
    let mut bad = false;
    for f in fields {
        let key = f.name.to_string();
        let Some(&(_, scope)) = known.iter().find(|(n, _)| *n == key) else {
            let list: Vec<&str> = known.iter().map(|(n, _)| *n).collect();
            r.errors.push(
                f.name.span(),
                format!(
                    "unknown option of a {kind}: expected {}, found `{key}`{}",
                    crate::parse::one_of(&list, "no option"),
                    crate::parse::closest(&key, &list, &[])
                ),
            );
            bad = true;
            continue;
        };
        match &f.value {
            Value::List(v) => {
                r.errors.push(v.span, format!("`{key}` is a number: expected a number, found a list"));
                bad = true;
            }
            Value::Expr(e) => match r.expr(e, scope) {
                Some(m) => {
                    if out.insert(key.clone(), m).is_some() {
                        r.errors.push(
                            f.name.span(),
                            format!("duplicate option `{key}`: expected each option once, found `{key}` again; keep one"),
                        );
                        bad = true;
                    }
                }
                None => bad = true,
            },
        }
    }
    (!bad).then_some(out)
}
