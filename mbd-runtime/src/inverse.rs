//! Inverse dynamics (Nikravesh, *Planar Multibody Dynamics*, ch. 12): for a kinematically driven
//! mechanism (DOF = 0) the motion q(t) is known, so the equations of motion
//! M q̈ − Φ_qᵀ λ = h give the Lagrange multipliers directly, Φ_qᵀ λ = M q̈ − h, and from them the
//! driver forces and torques and the reaction of every joint:
//!
//! the generalized reaction a joint with rows R applies is g = Φ_q[R]ᵀ λ[R]; its three entries at a
//! body's coordinates are the force (N, global x and y) and the moment (N·m) about that body's
//! centre of mass with which the joint acts on the body. A driver's reaction is the force or
//! torque the actuator must supply.

use crate::kinematics::{first_non_finite, name, require_driven};
use crate::linalg::{lu_factor, lu_solve_in_place, LinalgError};
use crate::{Dynamics, KinematicError, Mechanism, NonFiniteQuantity, Real};

/// Relative pivot tolerance of the LU factorization of Φ_qᵀ (see [`crate::linalg::lu_factor`]).
pub const INVERSE_PIVOT_TOLERANCE: f64 = 1e-12;

/// The force and moment a joint applies to one body.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wrench<T> {
    /// The body, by name.
    pub body: &'static str,
    /// Its index among the moving bodies.
    pub body_index: usize,
    /// Force on the body, global components (N).
    pub force: [T; 2],
    /// Moment about the body's centre of mass, counter-clockwise positive (N·m).
    pub moment: T,
}

impl<T: Real> Wrench<T> {
    /// The force in the body's own frame, A(φ)ᵀ f, for the body's angle φ (rad).
    pub fn force_in_body_frame(&self, phi: T) -> [T; 2] {
        let (s, c) = phi.sin_cos();
        [c * self.force[0] + s * self.force[1], -s * self.force[0] + c * self.force[1]]
    }

    /// The moment about a point of the body at `arm` = r_P − r (global, m) from its centre:
    /// M_P = M − arm × f (N·m). For a revolute joint taken at its pin, this is zero.
    pub fn moment_about(&self, arm: [T; 2]) -> T {
        self.moment - (arm[0] * self.force[1] - arm[1] * self.force[0])
    }
}

/// The reaction of one joint (or driver, or user constraint) on each moving body it connects.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointReaction<T> {
    /// The joint's name (`"revolute crank~rod"`).
    pub joint: &'static str,
    /// On its first body (`None` for ground).
    pub on_i: Option<Wrench<T>>,
    /// On its second body (`None` for ground).
    pub on_j: Option<Wrench<T>>,
}

/// Solves Φ_qᵀ λ = M q̈ − h for the Lagrange multipliers λ of a driven mechanism (NQ = NC), given
/// its motion (q, q̇, q̈) at time t, e.g. from a kinematic analysis.
///
/// Errors: `NotDriven` unless DOF = 0; `SingularJacobian` (naming a coordinate and the dependent
/// constraint) at a singular position or with redundant constraints, where λ is not unique;
/// `NonFinite` for NaN or infinite inputs or forces.
pub fn inverse_dynamics<T, M, const NQ: usize, const NC: usize>(
    m: &M,
    q: &[T; NQ],
    qd: &[T; NQ],
    qdd: &[T; NQ],
    t: T,
    lambda: &mut [T; NC],
) -> Result<(), KinematicError>
where
    T: Real,
    M: Dynamics<T, NQ, NC>,
{
    require_driven::<NQ, NC>()?;
    let time = t.to_f64();
    for (values, quantity) in
        [(q, NonFiniteQuantity::Coordinate), (qd, NonFiniteQuantity::Velocity), (qdd, NonFiniteQuantity::Acceleration)]
    {
        if let Some(i) = first_non_finite(values) {
            return Err(KinematicError::NonFinite { t: time, quantity, row: name(M::COORDINATE_NAMES, i) });
        }
    }
    let mut d = [[T::ZERO; NQ]; NC];
    m.jacobian(q, t, &mut d);
    let mut h = [T::ZERO; NQ];
    m.forces(q, qd, t, &mut h);
    let mass = m.mass_diagonal();
    // Φ_qᵀ, square because NQ = NC: row k is coordinate k, column r is constraint r.
    let mut dt = [[T::ZERO; NQ]; NQ];
    for (r, row) in d.iter().enumerate() {
        for (c, &v) in row.iter().enumerate() {
            dt[c][r] = v;
        }
    }
    let mut rhs: [T; NQ] = core::array::from_fn(|k| mass[k] * qdd[k] - h[k]);
    if let Some(i) = first_non_finite(&rhs) {
        return Err(KinematicError::NonFinite { t: time, quantity: NonFiniteQuantity::Acceleration, row: name(M::COORDINATE_NAMES, i) });
    }
    let permutation = lu_factor(&mut dt, T::from_f64(INVERSE_PIVOT_TOLERANCE)).map_err(|e| match e {
        // Column r of Φ_qᵀ is constraint r; the candidate row is a coordinate.
        LinalgError::Singular { column, candidate_row } => KinematicError::SingularJacobian {
            t: time,
            coordinate: name(M::COORDINATE_NAMES, candidate_row),
            constraint: name(M::CONSTRAINT_NAMES, column),
        },
        LinalgError::NonFinite { column, .. } => {
            KinematicError::NonFinite { t: time, quantity: NonFiniteQuantity::Jacobian, row: name(M::CONSTRAINT_NAMES, column) }
        }
        LinalgError::NotSquare { .. } | LinalgError::Overdetermined { .. } => KinematicError::NotDriven { dof: NQ as i32 - NC as i32 },
    })?;
    let base = rhs;
    lu_solve_in_place(&dt, &permutation, &mut rhs);
    lambda.copy_from_slice(&rhs);
    // Coulomb friction depends on the loads it changes: fixed-point iteration on λ (nothing
    // to do for a mechanism without it, whose friction forces are all zero).
    for _ in 0..INVERSE_FRICTION_ITERATIONS {
        let mut friction = [T::ZERO; NQ];
        m.friction_forces(q, qd, t, lambda, &mut friction);
        if friction.iter().all(|f| *f == T::ZERO) {
            return Ok(());
        }
        let mut rhs: [T; NQ] = core::array::from_fn(|k| base[k] - friction[k]);
        lu_solve_in_place(&dt, &permutation, &mut rhs);
        let mut change = T::ZERO;
        let mut size = T::ONE;
        for (l, v) in lambda.iter_mut().zip(rhs.iter()) {
            change = change.max((*l - *v).abs());
            size = size.max(v.abs());
            *l = *v;
        }
        if change <= T::from_f64(1e-12) * size {
            return Ok(());
        }
    }
    Err(KinematicError::NotConverged {
        t: time,
        iterations: INVERSE_FRICTION_ITERATIONS,
        worst_row: name(M::CONSTRAINT_NAMES, 0),
        residual: f64::NAN,
    })
}

/// Fixed-point iterations on the Coulomb friction loads of [`inverse_dynamics`].
const INVERSE_FRICTION_ITERATIONS: u32 = 50;

/// The reaction of joint number `joint` (an index into [`Mechanism::JOINTS`]) from the Jacobian
/// `d` = Φ_q(q, t) and the multipliers λ at the same state. `None` if there is no such joint.
pub fn joint_reaction<T, M, const NQ: usize, const NC: usize>(d: &[[T; NQ]; NC], lambda: &[T; NC], joint: usize) -> Option<JointReaction<T>>
where
    T: Real,
    M: Mechanism,
{
    let info = M::JOINTS.get(joint)?;
    let rows = (info.first_row as usize)..(info.first_row as usize + info.rows as usize);
    let wrench = |body: Option<u16>| -> Option<Wrench<T>> {
        let b = body? as usize;
        let mut g = [T::ZERO; 3];
        for r in rows.clone() {
            let (row, l) = (d.get(r)?, *lambda.get(r)?);
            for (k, gk) in g.iter_mut().enumerate() {
                *gk += *row.get(3 * b + k)? * l;
            }
        }
        Some(Wrench { body: name(M::BODY_NAMES, b), body_index: b, force: [g[0], g[1]], moment: g[2] })
    };
    Some(JointReaction { joint: info.name, on_i: wrench(info.body_i), on_j: wrench(info.body_j) })
}
