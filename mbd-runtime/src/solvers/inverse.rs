//! Inverse dynamics (Nikravesh, *Planar Multibody Dynamics*, ch. 12): for a kinematically driven
//! mechanism (DOF = NV − NC = 0) the motion q(t) is known, so the equations of motion
//! M v̇ − Dᵀ λ = h give the Lagrange multipliers directly, Dᵀ λ = M v̇ − h, and from them the
//! driver forces and torques and the reaction of every joint:
//!
//! the generalized reaction a joint with rows R applies is `g = D[R]ᵀ λ[R]`; each of its bodies'
//! twist Jacobian J_b turns it into the force (N, global) and the moment (N·m, global) about that
//! body's centre of mass with which the joint acts on the body ([`joint_reaction`]). A driver's
//! reaction is the force or torque the actuator must supply.

use crate::linalg::{lu_factor, lu_solve_in_place, LinalgError, LuWork};
use crate::model::body::{transpose_times, BodyFrames, BodyWrench, JointLoads};
use crate::model::dynamics::DynamicsError;
use crate::model::mechanism::Dynamics;
use crate::model::workspace::{Vectors, WorkArrays, Workspace};
use crate::real::Real;
use crate::solvers::error::{KinematicError, NonFiniteQuantity};
use crate::solvers::kinematics::independent_rows;
use crate::solvers::kinematics::{first_non_finite, name, require_driven};
use core::fmt;

/// The force and moment a joint applies to one body, in global components, and the body's
/// orientation to read them in its own frame. The same for planar and spatial bodies: a planar
/// force has z = 0 and a planar moment is (0, 0, n), n counter-clockwise positive.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wrench<T> {
    /// The body, by name.
    pub body: &'static str,
    /// Its index among the moving bodies.
    pub body_index: usize,
    /// Force on the body, global components (N).
    pub force: [T; 3],
    /// Moment about the body's centre of mass, global components (N·m).
    pub moment: [T; 3],
    /// The body's rotation A at the state of the reaction (body-frame components → global,
    /// `rotation[i][j]` = A_ij): planar a turn by φ about z, spatial A(p) of its Euler
    /// parameters.
    pub rotation: [[T; 3]; 3],
    /// The body's centre of mass r at the state of the reaction, global (m): the point the
    /// moment is about.
    pub centre: [T; 3],
}

impl<T: Real> Wrench<T> {
    /// The force in the body's own frame, Aᵀ f (N).
    pub fn force_in_body_frame(&self) -> [T; 3] {
        transpose_times(&self.rotation, &self.force)
    }

    /// The moment about the centre of mass in the body's own frame, Aᵀ n (N·m).
    pub fn moment_in_body_frame(&self) -> [T; 3] {
        transpose_times(&self.rotation, &self.moment)
    }

    /// The moment about a point of the body at `arm` = r_P − r (global, m) from its centre:
    /// n_P = n − arm × f (N·m, global). For a revolute or spherical joint taken at its pin, this
    /// is zero.
    pub fn moment_about(&self, arm: [T; 3]) -> [T; 3] {
        let cross = crate::model::body::cross(arm, self.force);
        core::array::from_fn(|k| self.moment[k] - cross[k])
    }

    /// The moment about the point P (global position, m): n_P = n − (P − r) × f (N·m, global)
    /// — at a joint's pin, what the joint's bearing must hold besides the force.
    pub fn moment_at(&self, point: [T; 3]) -> [T; 3] {
        self.moment_about(core::array::from_fn(|k| point[k] - self.centre[k]))
    }
}

/// The reaction of one joint (or driver, or user constraint) on each moving body it connects.
/// A joint's sides are as declared (`revolute ground ~ arm`: `on_j` is on the arm); a driver of
/// a joint's angle or stroke (`drive motor: hinge.angle`) has the joint's sides; a driver of one
/// body's coordinate (`drive arm.phi`) and a distance driver from ground act on that body as
/// `on_i` and `on_j` respectively ([`crate::JointInfo`] says which for each). Pick a side by
/// body with [`on`](Self::on).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointReaction<T> {
    /// The joint's name (`"revolute crank~rod"`).
    pub joint: &'static str,
    /// On its first body (`None` for ground).
    pub on_i: Option<Wrench<T>>,
    /// On its second body (`None` for ground).
    pub on_j: Option<Wrench<T>>,
}

impl<T: Copy> JointReaction<T> {
    /// The wrench on the body named `body` (`"crank"`, as in [`crate::Mechanism::BODY_NAMES`]),
    /// on whichever side it is; `None` if the joint does not act on it.
    pub fn on(&self, body: &str) -> Option<Wrench<T>> {
        [self.on_i, self.on_j].into_iter().flatten().find(|w| w.body == body)
    }
}

crate::options::options! {
    /// Options of [`InverseDynamics`], in the scalar type `T` of the mechanism (default `f64`).
    /// Build from [`Default`] and the `with_*` setters.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct InverseDynamicsOptions<T> {
        /// Relative pivot tolerance of the planned LDLᵀ of D Dᵀ and of the dense LU of Dᵀ it
        /// falls back to where it finds no pivot (partial pivoting, each pivot relative to its
        /// column). Default 1e-12.
        pivot_tolerance: T = T::from_f64(1e-12) => with_pivot_tolerance,
        /// With redundant rows (NC > NV): a row is dependent on the rows declared before it when
        /// the sine of its angle to their span is below this. Default
        /// [`crate::DEFAULT_RANK_TOLERANCE`].
        rank_tolerance: T = T::from_f64(crate::solvers::kinematics::DEFAULT_RANK_TOLERANCE) => with_rank_tolerance,
        /// Coulomb friction's loads are iterated until the largest change of λ is below this
        /// times max(1, max |λ|). Default 1e-12.
        friction_tolerance: T = T::from_f64(1e-12) => with_friction_tolerance,
        /// Fixed-point iterations on the friction loads before
        /// [`InverseDynamicsError::FrictionNotConverged`]. Default 50.
        max_friction_iterations: u32 = 50 => with_max_friction_iterations,
    }
}

/// Inverse dynamics of a driven mechanism: the loads (λ, and from them the driver forces and
/// joint reactions) of a known motion. Made by [`new`](Self::new) or [`Default`], holding only
/// its options: one solver serves any number of mechanisms.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InverseDynamics<T = f64> {
    /// Tolerances and limits.
    pub options: InverseDynamicsOptions<T>,
}

/// A failed inverse-dynamics solve ([`InverseDynamics::solve`]). Times are in s.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum InverseDynamicsError {
    /// The motion does not determine the loads: degrees of freedom are left (NV > NC; `dof`
    /// of them), drivers are missing.
    NotDriven {
        /// Velocities minus constraint rows.
        dof: i32,
    },
    /// D has no full rank at this position (a toggle or lock-up, where λ is not unique and
    /// grows without bound nearby): no pivot for `velocity`, best candidate `constraint`.
    SingularJacobian {
        /// Time (s).
        t: f64,
        /// The velocity whose column of D had no acceptable pivot, from
        /// [`crate::Mechanism::VELOCITY_NAMES`].
        velocity: &'static str,
        /// The constraint row that held the best candidate pivot, from
        /// [`crate::Mechanism::CONSTRAINT_NAMES`].
        constraint: &'static str,
    },
    /// A NaN or an infinity in the input or in an evaluated quantity.
    NonFinite {
        /// Time (s).
        t: f64,
        /// What held the value: q, v, v̇ (also M v̇ − h, the right-hand side), or D.
        quantity: NonFiniteQuantity,
        /// The coordinate, velocity or constraint row.
        row: &'static str,
    },
    /// A body's mass or inertia, as the parameters make it, is not positive
    /// ([`Dynamics::check_inertia`]): the loads of such a body mean nothing.
    NonPositiveMass {
        /// The body, from [`crate::Mechanism::BODY_NAMES`].
        body: &'static str,
        /// The offending mass (kg) or moment of inertia (kg·m²; spatial: J′'s smallest
        /// principal moment).
        value: f64,
    },
    /// The loads of Coulomb friction did not settle: friction so large that it changes the
    /// loads it depends on more than they change it (μ too large, or a wedging geometry).
    FrictionNotConverged {
        /// Time (s).
        t: f64,
        /// Iterations performed ([`InverseDynamicsOptions::max_friction_iterations`]).
        iterations: u32,
        /// The last change of max |λ| (N, N·m).
        change: f64,
    },
}

impl fmt::Display for InverseDynamicsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            InverseDynamicsError::NotDriven { dof } => write!(
                f,
                "inverse dynamics needs a driven mechanism, but {dof} degree(s) of freedom are left: add {dof} driver(s)"
            ),
            InverseDynamicsError::SingularJacobian { t, velocity, constraint } => write!(
                f,
                "inverse dynamics at t = {t} s: singular constraint Jacobian, no usable pivot for '{velocity}' \
                 (best candidate: constraint '{constraint}'); at a lock-up or toggle position the loads are not unique"
            ),
            InverseDynamicsError::NonFinite { t, quantity, row } => {
                write!(f, "inverse dynamics at t = {t} s: non-finite value (NaN or ±∞) in {quantity} '{row}'")
            }
            InverseDynamicsError::NonPositiveMass { body, value } => {
                write!(f, "inverse dynamics: body `{body}` has a mass or moment of inertia of {value}: it must be positive")
            }
            InverseDynamicsError::FrictionNotConverged { t, iterations, change } => write!(
                f,
                "inverse dynamics at t = {t} s: the Coulomb friction loads did not settle in {iterations} iterations (last change of λ: {change})"
            ),
        }
    }
}

impl core::error::Error for InverseDynamicsError {}

/// An error of the checks inverse dynamics shares with kinematics (`require_driven`, the
/// redundancy split) in this analysis's terms.
fn shared(e: KinematicError) -> InverseDynamicsError {
    match e {
        KinematicError::NotDriven { dof } => InverseDynamicsError::NotDriven { dof },
        KinematicError::SingularJacobian { t, coordinate, constraint } => {
            InverseDynamicsError::SingularJacobian { t, velocity: coordinate, constraint }
        }
        KinematicError::NonFinite { t, quantity, row } => InverseDynamicsError::NonFinite { t, quantity, row },
        // A position solve's error, which neither shared check returns: the row it names.
        KinematicError::NotConverged { t, worst_row, .. } => {
            InverseDynamicsError::NonFinite { t, quantity: NonFiniteQuantity::Constraint, row: worst_row }
        }
        KinematicError::CannotAssemble { t, rows, .. } => {
            InverseDynamicsError::NonFinite { t, quantity: NonFiniteQuantity::Constraint, row: rows.names().next().unwrap_or("?") }
        }
    }
}

impl<T: Real> Default for InverseDynamics<T> {
    fn default() -> Self {
        Self::new(InverseDynamicsOptions::new())
    }
}

impl<T: Real> InverseDynamics<T> {
    /// A solver with the given options.
    pub const fn new(options: InverseDynamicsOptions<T>) -> Self {
        InverseDynamics { options }
    }

    /// Solves Dᵀ λ = M v̇ − h for the Lagrange multipliers λ of a driven mechanism (NV = NC), given
    /// its motion (q, v, v̇) at time t, e.g. from a kinematic analysis. On success
    /// [`WorkArrays::jacobian`](crate::WorkArrays::jacobian) holds D(q, t), which [`joint_reaction`] takes with λ to give each
    /// joint's reaction in N and N·m.
    ///
    /// For NV = NC the solve runs over the LDLᵀ of D Dᵀ that `mechanism!` plans at compile time,
    /// λ = (D Dᵀ)⁻¹ D b refined on the residual b − Dᵀλ to an LU's accuracy; where that finds no
    /// pivot or a value that is not finite, the dense LU of Dᵀ takes over and names what failed.
    ///
    /// With redundant constraints (NC > NV) the loads are not unique; they are solved over the rows
    /// independent of the rows declared before them (sine of the angle to their span above
    /// [`InverseDynamicsOptions::rank_tolerance`]), and each row left out carries none (λ = 0) — the rule
    /// of forward dynamics and statics.
    ///
    /// # Errors
    /// [`InverseDynamicsError::NotDriven`] while degrees of freedom are left (NV > NC);
    /// `SingularJacobian` (naming a velocity and the dependent constraint) at a singular
    /// position, where λ is not unique; `NonFinite` for NaN or infinite inputs or forces;
    /// `FrictionNotConverged`.
    // The state as a kinematic sweep hands it out (q, v, v̇, t), the mechanism, its work space
    // and the output: the arguments of `KinematicSolver`'s methods, with v̇.
    #[allow(clippy::too_many_arguments)]
    pub fn solve<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
        &self,
        m: &M,
        ws: &mut Workspace<T, NV, NC, N, NS>,
        q: &[T; NQ],
        v: &[T; NV],
        vd: &[T; NV],
        t: T,
        lambda: &mut [T; NC],
    ) -> Result<(), InverseDynamicsError>
    where
        M: Dynamics<T, NQ, NV, NC>,
    {
        require_driven::<NV, NC>().map_err(shared)?;
        if let Err(DynamicsError::NonPositiveMass { body, value }) = m.check_inertia() {
            return Err(InverseDynamicsError::NonPositiveMass { body, value });
        }
        let time = t.to_f64();
        if let Some(i) = first_non_finite(q) {
            return Err(InverseDynamicsError::NonFinite {
                t: time,
                quantity: NonFiniteQuantity::Coordinate,
                row: name(M::COORDINATE_NAMES, i),
            });
        }
        for (values, quantity) in [(v, NonFiniteQuantity::Velocity), (vd, NonFiniteQuantity::Acceleration)] {
            if let Some(i) = first_non_finite(values) {
                return Err(InverseDynamicsError::NonFinite { t: time, quantity, row: name(M::VELOCITY_NAMES, i) });
            }
        }
        let WorkArrays { jacobian: d, jacobian_scratch: basis, constraint_square: r, velocity_square: dt, vectors, indices, .. } =
            &mut **ws;
        m.jacobian(q, t, d);
        let mut base = [T::ZERO; NV];
        m.inverse_forces(q, v, vd, t, &mut base);
        if let Some(i) = first_non_finite(&base) {
            return Err(InverseDynamicsError::NonFinite {
                t: time,
                quantity: NonFiniteQuantity::Acceleration,
                row: name(M::VELOCITY_NAMES, i),
            });
        }
        // Dᵀ λ = b: with NV = NC over the LDLᵀ of D Dᵀ that `mechanism!` plans, refined on the
        // residual (`Kinematics::sparse_multipliers`), else by the LU of Dᵀ (square: row k is
        // velocity k, column r constraint r), which names a singular or non-finite D; with redundant
        // rows (NC > NV) over the rows independent of those declared before them, D_I = R Q
        // (`redundancy::orthogonalize`), λ_I = R⁻ᵀ Q b and λ = 0 on the rows left out — the rule
        // forward dynamics and statics follow: the dropped row carries no load.
        let pivot_tolerance = self.options.pivot_tolerance;
        let sparse = NV == NC && m.sparse_multipliers(q, t, pivot_tolerance, &base, lambda);
        let solver = if sparse {
            Solver::Sparse
        } else if NV == NC {
            for (r, row) in d.iter().enumerate() {
                for (c, &value) in row.iter().enumerate() {
                    dt[c][r] = value;
                }
            }
            let work = LuWork {
                pivots: &mut indices.pivots_v,
                columns: &mut indices.columns_v,
                scale: Vectors::new(vectors.flat()).take_written(),
            };
            lu_factor(dt, pivot_tolerance, work).map_err(|e| match e {
                // Column r of Dᵀ is constraint r; the candidate row is a velocity.
                LinalgError::Singular { column, candidate_row } => InverseDynamicsError::SingularJacobian {
                    t: time,
                    velocity: name(M::VELOCITY_NAMES, candidate_row),
                    constraint: name(M::CONSTRAINT_NAMES, column),
                },
                LinalgError::NonFinite { column, .. } => InverseDynamicsError::NonFinite {
                    t: time,
                    quantity: NonFiniteQuantity::Jacobian,
                    row: name(M::CONSTRAINT_NAMES, column),
                },
                LinalgError::NotSquare { .. } | LinalgError::Overdetermined { .. } => {
                    InverseDynamicsError::NotDriven { dof: NV as i32 - NC as i32 }
                }
            })?;
            Solver::Lu(&indices.pivots_v)
        } else {
            if let Some(i) = d.iter().position(|row| first_non_finite(row).is_some()) {
                return Err(InverseDynamicsError::NonFinite {
                    t: time,
                    quantity: NonFiniteQuantity::Jacobian,
                    row: name(M::CONSTRAINT_NAMES, i),
                });
            }
            Solver::Orthogonal(independent_rows::<T, M, NV, NC>(d, self.options.rank_tolerance, basis, r, t).map_err(shared)?)
        };
        let solve = |b: &[T; NV], lambda: &mut [T; NC]| match &solver {
            // The same D as the first solve: only a friction load that is not finite fails here,
            // and its NaN ends the friction iteration with `FrictionNotConverged`.
            Solver::Sparse => {
                if !m.sparse_multipliers(q, t, pivot_tolerance, b, lambda) {
                    *lambda = [T::from_f64(f64::NAN); NC];
                }
            }
            Solver::Lu(pivots) => {
                let mut x = [T::ZERO; NV];
                x.copy_from_slice(b);
                lu_solve_in_place(dt, pivots, &mut x);
                lambda.copy_from_slice(&x[..NC]);
            }
            Solver::Orthogonal(redundant) => {
                // Q b, then Rᵀ y = Q b by back substitution (Rᵀ upper triangular), over the kept rows.
                let qb: [T; NV] = core::array::from_fn(|j| basis[j].iter().zip(b.iter()).fold(T::ZERO, |s, (x, y)| s + *x * *y));
                let mut y = [T::ZERO; NV];
                for j in (0..NV).rev() {
                    let mut value = qb[j];
                    for k in j + 1..NV {
                        value -= r[k][j] * y[k];
                    }
                    y[j] = value / r[j][j];
                }
                let mut kept = 0;
                for (l, &dropped) in lambda.iter_mut().zip(redundant.iter()) {
                    *l = if dropped {
                        T::ZERO
                    } else {
                        kept += 1;
                        y[kept - 1]
                    };
                }
            }
        };
        if !sparse {
            solve(&base, lambda);
        }
        self.settle_friction(m, q, v, t, &base, solve, lambda)
    }

    /// Coulomb friction depends on the loads it changes: fixed-point iteration on λ, each step
    /// `solve`d for Dᵀλ = b − f(λ) (nothing to do for a mechanism without friction, whose friction
    /// forces are all zero).
    #[allow(clippy::too_many_arguments)]
    fn settle_friction<M, const NQ: usize, const NV: usize, const NC: usize>(
        &self,
        m: &M,
        q: &[T; NQ],
        v: &[T; NV],
        t: T,
        base: &[T; NV],
        solve: impl Fn(&[T; NV], &mut [T; NC]),
        lambda: &mut [T; NC],
    ) -> Result<(), InverseDynamicsError>
    where
        M: Dynamics<T, NQ, NV, NC>,
    {
        let mut friction = [T::ZERO; NV];
        m.friction_forces(q, v, t, lambda, &mut friction);
        if friction.iter().all(|f| *f == T::ZERO) {
            // no Coulomb friction (or none loaded): the first solve stands
            return Ok(());
        }
        let step = |lambda: &mut [T; NC]| {
            let mut friction = [T::ZERO; NV];
            m.friction_forces(q, v, t, lambda, &mut friction);
            let rhs: [T; NV] = core::array::from_fn(|k| base[k] - friction[k]);
            let mut next = [T::ZERO; NC];
            solve(&rhs, &mut next);
            *lambda = next;
        };
        crate::solvers::friction::settle_loads(self.options.friction_tolerance, self.options.max_friction_iterations, lambda, step)
            .map(|_| ())
            .map_err(|(iterations, change)| InverseDynamicsError::FrictionNotConverged {
                t: t.to_f64(),
                iterations,
                change: change.to_f64(),
            })
    }
}

/// How [`InverseDynamics::solve`] solves Dᵀ λ = b: over the planned LDLᵀ of D Dᵀ, by the LU of the
/// square Dᵀ, or over D's independent rows (the flags mark the rows left out).
enum Solver<'a, const N: usize, const NC: usize> {
    Sparse,
    /// The LU's interchanges (the factors are in the work space's velocity square).
    Lu(&'a [usize; N]),
    Orthogonal([bool; NC]),
}

/// The reaction of a joint — by its label's generated constant `Name::LABEL`, its index into
/// [`crate::Mechanism::JOINTS`] — from the coordinates q, the Jacobian `d` = D(q, t) and the
/// multipliers λ at the same state. `None` if there is no such joint.
///
/// The joint's rows R give the generalized force `g = D[R]ᵀ λ[R]`; the wrench on each of its
/// bodies b is J_b g, with J_b the body's twist Jacobian ([`BodyFrames::body_twist`]): the force
/// through the centre of mass and the moment about it, both global. This holds where the bodies'
/// twists are independent (J_b J_cᵀ = δ_bc I), as in body coordinates, where J_b picks the
/// body's own velocities: planar (fx, fy, n), spatial (f, n′) with the moment A n′ in global
/// components (docs/formulation.md, "Spatial bodies").
pub fn joint_reaction<T, M, const NQ: usize, const NV: usize, const NC: usize>(
    mechanism: &M,
    q: &[T; NQ],
    d: &[[T; NV]; NC],
    lambda: &[T; NC],
    joint: usize,
) -> Option<JointReaction<T>>
where
    T: Real,
    M: BodyFrames<T, NQ, NV> + crate::model::mechanism::BodyCoordinates,
{
    let info = M::JOINTS.get(joint)?;
    let rows = (info.first_row as usize)..(info.first_row as usize + info.rows as usize);
    let mut g = [T::ZERO; NV];
    for r in rows {
        let (row, l) = (d.get(r)?, *lambda.get(r)?);
        for (gk, dk) in g.iter_mut().zip(row) {
            *gk += *dk * l;
        }
    }
    let wrench = |body: Option<u16>| -> Option<Wrench<T>> {
        let b = body? as usize;
        let twist = mechanism.body_twist(b, q, &g)?;
        let pose = mechanism.body_pose(b, q)?;
        Some(Wrench {
            body: name(M::BODY_NAMES, b),
            body_index: b,
            force: twist.velocity,
            moment: twist.angular_velocity,
            rotation: pose.rotation,
            centre: pose.position,
        })
    };
    Some(JointReaction { joint: info.name, on_i: wrench(info.body_i), on_j: wrench(info.body_j) })
}

/// The reaction of a joint (or driver, or user constraint) — by its label's generated constant
/// `Name::LABEL`, its index into [`crate::Mechanism::JOINTS`] — at a state of motion (q, v, v̇,
/// t) with the multipliers λ, in body and in joint coordinates alike. `None` if there is no
/// such joint.
///
/// The state is what the analysis that gave λ solved at: [`InverseDynamics::solve`]'s inputs,
/// a forward-dynamics step's (q, v, v̇), or a static equilibrium's q with v = v̇ = 0. A joint
/// with rows acts on each of its bodies through them, D_bᵀλ ([`JointLoads::constraint_wrench`]);
/// a joint of the tree (joint coordinates) transmits what its subtree's motion and loads need
/// ([`JointLoads::tree_joint_wrenches`], by Newton–Euler), so it needs v and v̇ as well. Either
/// way the wrench is a force through each body's centre of mass and the moment about it, global
/// (N, N·m), as [`joint_reaction`] gives it in body coordinates.
#[allow(clippy::too_many_arguments)]
pub fn joint_reaction_at<T, M, const NQ: usize, const NV: usize, const NC: usize>(
    mechanism: &M,
    q: &[T; NQ],
    v: &[T; NV],
    vd: &[T; NV],
    t: T,
    lambda: &[T; NC],
    joint: usize,
) -> Option<JointReaction<T>>
where
    T: Real,
    M: JointLoads<T, NQ, NV, NC>,
{
    let info = M::JOINTS.get(joint)?;
    let wrench = |body: usize, w: BodyWrench<T>| -> Option<Wrench<T>> {
        let pose = mechanism.body_pose(body, q)?;
        Some(Wrench {
            body: name(M::BODY_NAMES, body),
            body_index: body,
            force: w.force,
            moment: w.moment,
            rotation: pose.rotation,
            centre: pose.position,
        })
    };
    let (on_i, on_j) = match M::TREE_JOINTS.iter().position(|&j| j == Some(joint as u16)) {
        Some(child) => {
            let [on_child, on_parent] = mechanism.tree_joint_wrenches(child, q, v, vd, t, lambda)?;
            let side = |body: Option<u16>| {
                let b = body? as usize;
                wrench(b, if b == child { on_child } else { on_parent })
            };
            (side(info.body_i), side(info.body_j))
        }
        None => {
            let mut own = [T::ZERO; NC];
            for r in info.row_range() {
                own[r] = *lambda.get(r)?;
            }
            let side = |body: Option<u16>| {
                let b = body? as usize;
                wrench(b, mechanism.constraint_wrench(b, q, t, &own)?)
            };
            (side(info.body_i), side(info.body_j))
        }
    };
    Some(JointReaction { joint: info.name, on_i, on_j })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::body::{euler_rotation, planar_rotation};
    use crate::model::body::{BodyPose, BodyTwist};
    use crate::model::mechanism::Mechanism;
    use crate::model::mechanism::{CoordinateInfo, CoordinateKind, JointInfo, OpCount, VelocityInfo, VelocityKind};

    /// The free pendulum has a degree of freedom: its loads are not determined by a motion, and
    /// the error says how many drivers are missing.
    #[test]
    fn inverse_dynamics_names_what_it_cannot_solve() {
        use crate::test_support::UnitPendulum;
        let (m, mut ws) = (UnitPendulum, Workspace::<f64, 3, 2, 5>::new());
        let q = [0.5, 0.0, 1.0, 0.0];
        let error = InverseDynamics::default().solve(&m, &mut ws, &q, &[0.0; 3], &[0.0; 3], 0.0, &mut [0.0; 2]);
        assert_eq!(error, Err(InverseDynamicsError::NotDriven { dof: 1 }));
        let message = error.unwrap_err().to_string();
        assert!(message.contains("add 1 driver"), "{message}");
    }

    /// A spatial body `top` held by a spherical joint at its body point s′ (no generated spatial
    /// mechanism exists yet): q = (r, p), v = (ṙ, ω′), Φ = r + A s′ − r_O.
    struct SphericalTop;

    impl crate::model::mechanism::BodyCoordinates for SphericalTop {}
    impl Mechanism for SphericalTop {
        const NAME: &'static str = "SphericalTop";
        const BODY_NAMES: &'static [&'static str] = &["top"];
        const COORDINATE_NAMES: &'static [&'static str] = &["top.x", "top.y", "top.z", "top.e0", "top.e1", "top.e2", "top.e3"];
        const VELOCITY_NAMES: &'static [&'static str] = &["top.vx", "top.vy", "top.vz", "top.wx", "top.wy", "top.wz"];
        const COORDINATES: &'static [CoordinateInfo] = &[
            CoordinateInfo { name: "top.x", kind: CoordinateKind::Length },
            CoordinateInfo { name: "top.y", kind: CoordinateKind::Length },
            CoordinateInfo { name: "top.z", kind: CoordinateKind::Length },
            CoordinateInfo { name: "top.e0", kind: CoordinateKind::Quaternion { part: 0 } },
            CoordinateInfo { name: "top.e1", kind: CoordinateKind::Quaternion { part: 1 } },
            CoordinateInfo { name: "top.e2", kind: CoordinateKind::Quaternion { part: 2 } },
            CoordinateInfo { name: "top.e3", kind: CoordinateKind::Quaternion { part: 3 } },
        ];
        const VELOCITIES: &'static [VelocityInfo] = &[
            VelocityInfo { name: "top.vx", kind: VelocityKind::Rate { coordinate: 0 }, displacement: "top.x" },
            VelocityInfo { name: "top.vy", kind: VelocityKind::Rate { coordinate: 1 }, displacement: "top.y" },
            VelocityInfo { name: "top.vz", kind: VelocityKind::Rate { coordinate: 2 }, displacement: "top.z" },
            VelocityInfo { name: "top.wx", kind: VelocityKind::Angular { quaternion: 3, axis: 0 }, displacement: "top.rx" },
            VelocityInfo { name: "top.wy", kind: VelocityKind::Angular { quaternion: 3, axis: 1 }, displacement: "top.ry" },
            VelocityInfo { name: "top.wz", kind: VelocityKind::Angular { quaternion: 3, axis: 2 }, displacement: "top.rz" },
        ];
        const CONSTRAINT_NAMES: &'static [&'static str] =
            &["spherical ground~top: x", "spherical ground~top: y", "spherical ground~top: z"];
        const PARAM_NAMES: &'static [&'static str] = &[];
        const DOF: i32 = 3;
        const JACOBIAN_PATTERN: &'static [(u16, u16)] = &[];
        const PHI_T_IS_ZERO: bool = true;
        const OP_COUNTS: &'static [OpCount] = &[];
        const JOINTS: &'static [JointInfo] =
            &[JointInfo { name: "spherical ground~top", kind: "spherical", first_row: 0, rows: 3, body_i: None, body_j: Some(0) }];
        const MODEL_JSON: &'static str = "{}";
    }

    /// Body coordinates' J_b of the one body: its own velocities, ω′ turned to global.
    impl BodyFrames<f64, 7, 6> for SphericalTop {
        fn body_pose(&self, body: usize, q: &[f64; 7]) -> Option<BodyPose<f64>> {
            (body == 0).then(|| BodyPose::spatial([q[0], q[1], q[2]], [q[3], q[4], q[5], q[6]]))
        }
        fn body_twist(&self, body: usize, q: &[f64; 7], x: &[f64; 6]) -> Option<BodyTwist<f64>> {
            let pose = self.body_pose(body, q)?;
            Some(BodyTwist { velocity: [x[0], x[1], x[2]], angular_velocity: pose.to_global([x[3], x[4], x[5]]) })
        }
        fn body_acceleration(&self, body: usize, q: &[f64; 7], _: &[f64; 6], vd: &[f64; 6]) -> Option<BodyTwist<f64>> {
            self.body_twist(body, q, vd)
        }
        fn add_body_wrench(&self, body: usize, q: &[f64; 7], force: [f64; 3], moment: [f64; 3], g: &mut [f64; 6]) -> bool {
            let Some(pose) = self.body_pose(body, q) else { return false };
            let n = pose.to_body(moment);
            for k in 0..3 {
                g[k] += force[k];
                g[3 + k] += n[k];
            }
            true
        }
    }

    fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    }

    /// Rodrigues' rotation by θ about the unit axis u: cos θ I + sin θ ũ + (1 − cos θ) u uᵀ.
    fn rodrigues(u: [f64; 3], theta: f64) -> [[f64; 3]; 3] {
        let (s, c) = theta.sin_cos();
        let tilde = [[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]];
        core::array::from_fn(|i| core::array::from_fn(|j| (if i == j { c } else { 0.0 }) + s * tilde[i][j] + (1.0 - c) * u[i] * u[j]))
    }

    fn max_diff(a: [f64; 3], b: [f64; 3]) -> f64 {
        (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max)
    }

    /// The reaction of a spherical joint on a rotated body, against the force and moment it
    /// applies by hand: the pin force λ at the point s = A s′ gives the moment s × λ about the
    /// centre; in the body frame Aᵀλ and s′ × Aᵀλ. D = [I, −A s̃′] is written from Rodrigues'
    /// rotation, independently of A(p).
    #[test]
    fn spherical_reaction_on_a_rotated_body() {
        let norm = (1.0f64 + 4.0 + 9.0).sqrt();
        let u = [1.0 / norm, -2.0 / norm, 3.0 / norm];
        let theta = 0.7;
        let (sh, ch) = (0.5 * theta).sin_cos();
        let q = [0.3, -0.1, 0.8, ch, sh * u[0], sh * u[1], sh * u[2]];
        let a = rodrigues(u, theta);
        // Tolerance: a few ulps of entries of size 1.
        for (i, row) in euler_rotation([q[3], q[4], q[5], q[6]]).iter().enumerate() {
            assert!(max_diff(*row, a[i]) < 1e-15, "A(p) row {i}: {row:?} vs {:?}", a[i]);
        }
        let s_local = [0.1, 0.2, -0.4];
        let s_tilde = [[0.0, -s_local[2], s_local[1]], [s_local[2], 0.0, -s_local[0]], [-s_local[1], s_local[0], 0.0]];
        let mut d = [[0.0; 6]; 3];
        for r in 0..3 {
            d[r][r] = 1.0;
            for c in 0..3 {
                d[r][3 + c] = -(0..3).map(|k| a[r][k] * s_tilde[k][c]).sum::<f64>();
            }
        }
        let lambda = [5.0, -3.0, 12.0];
        let w = joint_reaction(&SphericalTop, &q, &d, &lambda, 0).and_then(|j| j.on_j).expect("the pin acts on top");
        assert_eq!((w.body, w.body_index), ("top", 0));
        let s_global: [f64; 3] = core::array::from_fn(|i| (0..3).map(|k| a[i][k] * s_local[k]).sum());
        let force_local: [f64; 3] = core::array::from_fn(|j| (0..3).map(|i| a[i][j] * lambda[i]).sum());
        // Tolerance: rounding of sums of products of O(10) values.
        assert!(max_diff(w.force, lambda) < 1e-14, "{w:?}");
        assert!(max_diff(w.moment, cross(s_global, lambda)) < 1e-13, "{w:?}");
        assert!(max_diff(w.moment_about(s_global), [0.0; 3]) < 1e-13, "a pin has no moment about itself: {w:?}");
        let pin: [f64; 3] = core::array::from_fn(|i| w.centre[i] + s_global[i]);
        assert_eq!(w.centre, [q[0], q[1], q[2]], "the moment is about the centre of mass");
        assert!(max_diff(w.moment_at(pin), [0.0; 3]) < 1e-13, "nor at its global position: {w:?}");
        let reaction = joint_reaction(&SphericalTop, &q, &d, &lambda, 0).expect("the pin");
        assert_eq!((reaction.on("top"), reaction.on("ground")), (Some(w), None), "sides picked by body name");
        assert!(max_diff(w.force_in_body_frame(), force_local) < 1e-13, "{w:?}");
        assert!(max_diff(w.moment_in_body_frame(), cross(s_local, force_local)) < 1e-13, "{w:?}");
        assert!(joint_reaction(&SphericalTop, &q, &d, &lambda, 0).and_then(|j| j.on_i).is_none(), "ground has no wrench");
        assert!(joint_reaction(&SphericalTop, &q, &d, &lambda, 1).is_none(), "one joint only");
    }

    /// Planar: the rotation is a turn by φ about z and reads the force in the body frame as
    /// A(φ)ᵀ f.
    #[test]
    fn planar_body_frame() {
        let phi = 0.4f64;
        let (s, c) = phi.sin_cos();
        let w = Wrench {
            body: "b",
            body_index: 0,
            force: [2.0, 1.0, 0.0],
            moment: [0.0, 0.0, 3.0],
            rotation: planar_rotation(phi),
            centre: [0.5, -0.25, 0.0],
        };
        let local = w.force_in_body_frame();
        assert!(max_diff(local, [c * 2.0 + s * 1.0, -s * 2.0 + c * 1.0, 0.0]) < 1e-15, "{local:?}");
        assert_eq!(w.moment_in_body_frame()[2], 3.0);
        // about P = r + (1, 0): n − (P − r) × f = 3 − (1 · 1 − 0 · 2)
        assert_eq!(w.moment_at([1.5, -0.25, 0.0]), [0.0, 0.0, 2.0]);
        // n − arm × f with arm (1, 0, 0): 3 − (1·1 − 0·2) = 2.
        assert_eq!(w.moment_about([1.0, 0.0, 0.0]), [0.0, 0.0, 2.0]);
    }
}
