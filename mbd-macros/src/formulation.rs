//! Stage 3: validated model → symbolic equations in planar body coordinates (docs/formulation.md).
//!
//! Body k owns `q[3k..3k+3] = (x, y, φ)`. This stage writes Φ(q, t) row by row into one shared
//! [`Graph`] and derives from it, exactly: the sparse Jacobian Φ_q, Φ_t, ν = −Φ_t and
//! γ = −𝒟(𝒟Φ) with 𝒟f = f_q q̇ + f_t (a directional derivative taken twice; no Hessian is formed).

use std::collections::{BTreeSet, HashMap};

use crate::forces::{gravity, Generalized};
use crate::frames::{collect_vars, Builder};
use crate::model::Model;
use crate::sym::{Graph, Id, Var};

/// The symbolic equations of one mechanism.
pub struct Formulation {
    pub graph: Graph,
    pub nq: usize,
    pub nc: usize,
    /// Constraint row names, `"revolute crank~rod: x"`, in the order of Φ.
    pub row_names: Vec<String>,
    /// The first row of each constraint in Φ.
    pub first_rows: Vec<usize>,
    /// Φ, one node per row.
    pub phi: Vec<Id>,
    /// Structurally non-zero entries of Φ_q as (row, column, node), row-major.
    pub jacobian: Vec<(usize, usize, Id)>,
    /// ν = −Φ_t, one node per row.
    pub nu: Vec<Id>,
    /// γ, one node per row.
    pub gamma: Vec<Id>,
    /// Initial guesses of q and q̇ (functions of the parameters).
    pub q0: Vec<Id>,
    pub qd0: Vec<Id>,
    /// Diagonal of the mass matrix: (m, m, J) per body.
    pub mass: Vec<Id>,
    /// h(q, q̇, t), one node per coordinate.
    pub h: Vec<Id>,
    /// Structural non-zeros of ∂h/∂q and ∂h/∂q̇ as (row, column, node).
    pub h_q: Vec<(usize, usize, Id)>,
    pub h_qd: Vec<(usize, usize, Id)>,
    /// Potential energy of gravity and springs, V(q).
    pub potential: Id,
    /// Coulomb friction forces, one node per coordinate, functions of q, q̇ and the multipliers λ
    /// (the joints' normal loads); kept out of h, which does not depend on λ.
    pub friction: Vec<Id>,
    /// Structural non-zeros of the friction forces' ∂/∂q and ∂/∂q̇ at given λ (for implicit
    /// integration; empty without Coulomb friction).
    pub friction_q: Vec<(usize, usize, Id)>,
    pub friction_qd: Vec<(usize, usize, Id)>,
    /// Power of the non-conservative forces, q̇ᵀh + dV/dt: what dampers, actuators, applied
    /// forces and friction put in (J/s). Then d(T + V)/dt = this + λᵀ Φ_q q̇.
    pub power: Id,
    /// Structural non-zeros of ∂(Φ_qᵀλ)/∂q (the constraints' geometric stiffness), with λ as
    /// variables.
    pub constraint_force_q: Vec<(usize, usize, Id)>,
}

impl Formulation {
    /// Whether Φ does not depend on t (then ν = 0 and solvers skip it).
    pub fn phi_t_is_zero(&self) -> bool {
        self.nu.iter().all(|&n| self.graph.is_zero(n))
    }
}

/// Derives the symbolic equations of a model.
pub fn formulate(model: &Model) -> Formulation {
    let mut b = Builder::new(model);
    let nq = b.nq();
    let mut phi = Vec::new();
    let mut row_names = Vec::new();
    for c in &model.constraints {
        b.first_rows.push(phi.len());
        for row in c.kind.rows(&mut b) {
            row_names.push(format!("{}: {}", c.name, row.name));
            phi.push(row.value);
        }
    }
    let mut q0 = Vec::with_capacity(nq);
    let mut qd0 = Vec::with_capacity(nq);
    let mut mass = Vec::with_capacity(nq);
    for body in &model.bodies {
        for k in 0..3 {
            q0.push(b.expr(&body.q0[k]));
            qd0.push(b.expr(&body.qd0[k]));
        }
        let m = b.expr(&body.mass);
        let j = b.expr(&body.inertia);
        mass.extend([m, m, j]);
    }
    let zero = b.g.num(0.0);
    let mut out = Generalized { h: vec![zero; nq], friction: vec![zero; nq], potential: zero };
    if let Some(g) = &model.gravity {
        gravity::apply(&mut b, g, &mut out);
    }
    for element in &model.forces {
        element.kind.apply(&mut b, &mut out);
    }
    let Generalized { h, friction, potential } = out;
    // dV/dt = V_q q̇ + V_t
    let v_rate = b.rate(potential);
    let mut memo_v = HashMap::new();
    let v_t = b.g.diff(potential, Var::T, &mut memo_v);
    let mut power = b.g.add(v_rate, v_t);
    for (i, &hi) in h.iter().enumerate() {
        let qd = b.g.var(Var::Qd(i as u16));
        let p = b.g.mul(qd, hi);
        power = b.g.add(power, p);
    }
    let first_rows = std::mem::take(&mut b.first_rows);
    let mut g = b.g;
    let h_q = sparse_derivative(&mut g, &h, |v| if let Var::Q(i) = v { Some(i) } else { None }, Var::Q);
    let h_qd = sparse_derivative(&mut g, &h, |v| if let Var::Qd(i) = v { Some(i) } else { None }, Var::Qd);
    let friction_q = sparse_derivative(&mut g, &friction, |v| if let Var::Q(i) = v { Some(i) } else { None }, Var::Q);
    let friction_qd = sparse_derivative(&mut g, &friction, |v| if let Var::Qd(i) = v { Some(i) } else { None }, Var::Qd);

    // Φ_q: differentiate each row only by the coordinates it contains; every other entry is a
    // structural zero.
    let jacobian = sparse_derivative(&mut g, &phi, |v| if let Var::Q(i) = v { Some(i) } else { None }, Var::Q);

    // ν = −Φ_t
    let mut memo_t = HashMap::new();
    let nu: Vec<Id> = phi
        .iter()
        .map(|&row| {
            let d = g.diff(row, Var::T, &mut memo_t);
            g.neg(d)
        })
        .collect();

    // γ = −𝒟(𝒟Φ), 𝒟 the total time derivative with q̈ = 0: one seed, one memo for all rows.
    let qd: Vec<Id> = (0..nq).map(|i| g.var(Var::Qd(i as u16))).collect();
    let one = g.num(1.0);
    let seed = |v: Var| match v {
        Var::Q(i) => Some(qd[i as usize]),
        Var::T => Some(one),
        Var::Qd(_) | Var::Param(_) | Var::Lambda(_) => None,
    };
    let mut memo = HashMap::new();
    let first: Vec<Id> = phi.iter().map(|&row| g.directional(row, &seed, &mut memo)).collect();
    let gamma: Vec<Id> = first
        .iter()
        .map(|&d1| {
            let d2 = g.directional(d1, &seed, &mut memo);
            g.neg(d2)
        })
        .collect();

    // (Φ_qᵀλ)_k = Σ_r λ_r D_rk, then its exact derivative by q.
    let zero = g.num(0.0);
    let mut constraint_force = vec![zero; nq];
    for &(r, c, d) in &jacobian {
        let l = g.var(Var::Lambda(r as u16));
        let term = g.mul(l, d);
        constraint_force[c] = g.add(constraint_force[c], term);
    }
    let constraint_force_q = sparse_derivative(&mut g, &constraint_force, |v| if let Var::Q(i) = v { Some(i) } else { None }, Var::Q);

    Formulation {
        nc: phi.len(),
        row_names,
        first_rows,
        graph: g,
        nq,
        phi,
        jacobian,
        nu,
        gamma,
        q0,
        qd0,
        mass,
        h,
        h_q,
        h_qd,
        potential,
        power,
        friction,
        friction_q,
        friction_qd,
        constraint_force_q,
    }
}

/// The structural non-zeros of ∂rows/∂v, v ranging over the variables `pick` selects.
fn sparse_derivative(
    g: &mut Graph,
    rows: &[Id],
    pick: impl Fn(Var) -> Option<u16> + Copy,
    var: impl Fn(u16) -> Var,
) -> Vec<(usize, usize, Id)> {
    let mut out = Vec::new();
    for (r, &row) in rows.iter().enumerate() {
        let mut cols = BTreeSet::new();
        collect_vars(g, row, &mut cols, pick);
        let mut memo = HashMap::new();
        for c in cols {
            memo.clear();
            let d = g.diff(row, var(c), &mut memo);
            if !g.is_zero(d) {
                out.push((r, c as usize, d));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse::MechanismDef;

    fn formulated(src: &str) -> (Model, Formulation) {
        let model = syn::parse_str::<MechanismDef>(src).unwrap().validate().unwrap();
        let f = formulate(&model);
        (model, f)
    }

    fn eval(f: &Formulation, node: Id, q: &[f64], qd: &[f64], t: f64) -> f64 {
        f.graph.eval(node, &|v| match v {
            Var::Q(i) => q[i as usize],
            Var::Qd(i) => qd[i as usize],
            Var::T => t,
            Var::Param(_) | Var::Lambda(_) => 0.0,
        })
    }

    const PENDULUM: &str = "P { gravity [0.0, -9.81]; body a { mass: 2.0, inertia: 0.5 }
        revolute pin: ground[0.0, 0.0] ~ a[-1.0, 0.0]; drive a.phi = 2.0 * t; }";

    /// Rows and their names come from one place; first rows follow the row counts.
    #[test]
    fn rows_and_names_agree() {
        let (_, f) = formulated(PENDULUM);
        assert_eq!(f.row_names, ["pin: x", "pin: y", "drive a.phi: phi"]);
        assert_eq!(f.first_rows, [0, 2]);
        assert_eq!((f.nq, f.nc, f.phi.len(), f.gamma.len()), (3, 3, 3, 3));
    }

    /// A pendulum pinned at its end: Φ = r^P_ground − r^P_a vanishes on the circle, γ is the
    /// centripetal term, h is its weight, M = diag(m, m, J).
    #[test]
    fn pendulum_equations() {
        let (_, f) = formulated(PENDULUM);
        let phi0 = 0.3f64;
        let q = [phi0.cos(), phi0.sin(), phi0];
        for &row in &f.phi[..2] {
            assert!(eval(&f, row, &q, &[0.0; 3], 0.0).abs() < 1e-15);
        }
        // Pin rows Φ = r_ground − (r + A s′), s′ = (−1, 0): with q̈ = 0, Φ̈ = ω² A s′ = −ω² (cos φ, sin φ),
        // so γ = −Φ̈|q̈=0 = ω² (cos φ, sin φ).
        let w = 2.0;
        let qd = [-w * phi0.sin(), w * phi0.cos(), w];
        let gx = eval(&f, f.gamma[0], &q, &qd, 0.0);
        let gy = eval(&f, f.gamma[1], &q, &qd, 0.0);
        assert!((gx - w * w * phi0.cos()).abs() < 1e-12 && (gy - w * w * phi0.sin()).abs() < 1e-12, "γ = ({gx}, {gy})");
        let h: Vec<f64> = f.h.iter().map(|&n| eval(&f, n, &q, &qd, 0.0)).collect();
        assert_eq!(h, [0.0, -2.0 * 9.81, 0.0]);
        let mass: Vec<f64> = f.mass.iter().map(|&n| eval(&f, n, &q, &qd, 0.0)).collect();
        assert_eq!(mass, [2.0, 2.0, 0.5]);
        assert_eq!(eval(&f, f.nu[2], &q, &qd, 0.0), 2.0, "ν of the driver is ḟ");
    }

    /// The Jacobian's structural non-zeros are exactly the coordinates each row reads.
    #[test]
    fn jacobian_is_sparse() {
        let (_, f) = formulated(PENDULUM);
        let pattern: Vec<(usize, usize)> = f.jacobian.iter().map(|&(r, c, _)| (r, c)).collect();
        assert_eq!(pattern, [(0, 0), (0, 2), (1, 1), (1, 2), (2, 2)]);
    }
}
