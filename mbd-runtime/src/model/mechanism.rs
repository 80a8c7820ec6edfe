//! The traits that `mechanism!` implements for every generated mechanism.
//!
//! Positions and velocities are separate (docs/formulation.md): q has `NQ` entries, the velocity
//! v has `NV`, and q̇ = B(q) v. Every derivative the solvers use is taken in velocity space:
//! D = Φ_q B (NC × NV), D v̇ = γ, h and M have NV rows.
//!
//! The formulation `mechanism!` generates says what q and v are; the runtime reads it from the
//! generated descriptors ([`Mechanism::COORDINATES`], [`Mechanism::VELOCITIES`]) and each body's
//! pose and twist ([`crate::BodyFrames`]), never from a place in q. Today's formulation is body
//! coordinates:
//! - planar bodies (Nikravesh ch. 7): body `k` (ground excluded) owns `q[3k..3k+3] = (x, y, φ)`
//!   — its centre of mass and angle, in m and rad — and v = q̇, so NV = NQ and B = I;
//! - spatial bodies: body `k` owns `q[7k..7k+7] = (x, y, z, e0, e1, e2, e3)` (centre of mass and
//!   Euler parameters) and `v[6k..6k+6] = (vx, vy, vz, ωx′, ωy′, ωz′)` (global ṙ and the
//!   body-frame angular velocity).
//!
//! Constraints `Φ(q, t) = 0` stack the rows of every joint, driver and user constraint in
//! declaration order.

use crate::model::workspace::DenseScratch;
use crate::real::Real;

/// Operation count of one generated function, after common-subexpression elimination:
/// what one call costs at least, whatever the compiler does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OpCount {
    /// Name of the generated function (`"jacobian"`).
    pub function: &'static str,
    /// Additions and subtractions, and the comparisons of `abs`, `min`, `max`, `clamp`, `sign`
    /// and `if`.
    pub add: u32,
    /// Multiplications (and negations, which are free in practice, are not counted).
    pub mul: u32,
    /// Divisions.
    pub div: u32,
    /// Elementary-function calls (`sin_cos` of one angle counts once).
    pub call: u32,
}

impl OpCount {
    /// All operations together.
    pub const fn total(&self) -> u32 {
        self.add + self.mul + self.div + self.call
    }
}

/// One joint, driver or user constraint of a mechanism: its name, its rows of Φ and the bodies it
/// connects — what reaction forces are reported by.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct JointInfo {
    /// `"revolute crank~rod"`, `"drive crank.phi"`, or the name the user gave it.
    pub name: &'static str,
    /// Planar: `"revolute"`, `"translational"`, `"revolute_revolute"`,
    /// `"revolute_translational"`, `"rigid"`, `"fix"`, `"drive"`, `"drive_angle"`,
    /// `"drive_distance"`; spatial: `"spherical"`, `"universal"`, `"revolute"`, `"cylindrical"`,
    /// `"translational"`, `"planar"`, `"rigid"`, `"point_on_line"`, `"point_on_plane"`,
    /// `"distance"`, `"drive"`, `"drive_angle"`, `"drive_stroke"`; both: `"constraint"`.
    pub kind: &'static str,
    /// Its first row in Φ.
    pub first_row: u16,
    /// How many rows of Φ it has.
    pub rows: u16,
    /// The first body it connects (index among the moving bodies; `None` for ground or, for a
    /// user constraint, for no particular body).
    pub body_i: Option<u16>,
    /// The second body it connects (`None` for ground, for a driver of one body's coordinate and
    /// for a user constraint).
    pub body_j: Option<u16>,
}

impl JointInfo {
    /// Its rows of Φ — and of λ: `&lambda[Name::JOINTS[Name::MOTOR].row_range()]` are a driver's
    /// multipliers (its force or torque, N or N·m, up to the sign of the row's definition).
    pub const fn row_range(&self) -> core::ops::Range<usize> {
        self.first_row as usize..(self.first_row + self.rows) as usize
    }
}

/// One force element of a mechanism (gravity included, as `"gravity"`): its name and the
/// velocities its generalized force reaches — what a NaN or infinite force is traced back by.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ForceInfo {
    /// `"spring crank~rod"`, `"gravity"`, or the name the user gave it.
    pub name: &'static str,
    /// The velocities (indices into [`Mechanism::VELOCITY_NAMES`]) its generalized force or
    /// friction force is structurally non-zero on.
    pub velocities: &'static [u16],
    /// Operation counts of `forces`, `forces_q` and `forces_v` were this element the
    /// mechanism's only one, as a scene leaving out every other element and gravity (or every
    /// element, for gravity) generates them: [`Mechanism::BASE_FORCE_OP_COUNTS`] and its own
    /// terms. What it costs above that base is its cost alone.
    pub op_counts: &'static [OpCount],
}

/// What a generalized coordinate measures: its unit, and what may be done to it without moving
/// the mechanism. [`Mechanism::COORDINATES`] describes each coordinate by it, so that no analysis
/// reads a coordinate's meaning from its name or its place in q.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum CoordinateKind {
    /// A length (m).
    Length,
    /// An angle (rad): adding 2π leaves the configuration as it was, so it may be wrapped into
    /// (−π, π].
    Angle,
    /// Part `part` of a unit quaternion (Euler parameters, dimensionless) held in four
    /// consecutive coordinates: 0 is e0, the scalar part, which comes first; 1–3 the vector part.
    /// The quaternion and its negative are one orientation.
    Quaternion {
        /// 0 (e0) to 3 (e3).
        part: u8,
    },
    /// Any other dimensionless number (a component of a unit complex number (cos φ, sin φ)).
    Number,
}

impl CoordinateKind {
    /// Its unit differentiated `order` times in time: m, m/s, m/s²; rad, rad/s, rad/s²; 1, 1/s,
    /// 1/s².
    pub const fn unit(self, order: usize) -> &'static str {
        let units = match self {
            CoordinateKind::Length => ["m", "m/s", "m/s²"],
            CoordinateKind::Angle => ["rad", "rad/s", "rad/s²"],
            CoordinateKind::Quaternion { .. } | CoordinateKind::Number => ["1", "1/s", "1/s²"],
        };
        units[if order < 2 { order } else { 2 }]
    }
}

/// One generalized coordinate (an entry of q): its name and what it measures.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CoordinateInfo {
    /// `"crank.phi"`: the same as its entry of [`Mechanism::COORDINATE_NAMES`].
    pub name: &'static str,
    /// What it measures.
    pub kind: CoordinateKind,
}

/// How a velocity (an entry of v) moves the coordinates through q̇ = B(q) v.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum VelocityKind {
    /// The rate of coordinate `coordinate` (an index into q), v_i = q̇_c, in its unit per second.
    Rate {
        /// The coordinate it is the rate of.
        coordinate: u16,
    },
    /// Component `axis` (0, 1, 2 for x′, y′, z′) of a body's angular velocity ω′ in the body's own
    /// frame (rad/s), the body's orientation being the unit quaternion e whose scalar part is
    /// coordinate `quaternion`: ė = ½ e ⊗ (0, ω′). The three components are consecutive in v.
    Angular {
        /// The index into q of the quaternion's e0.
        quaternion: u16,
        /// 0, 1 or 2.
        axis: u8,
    },
    /// Any other velocity, reaching several coordinates through B(q): angular (rad/s) or linear
    /// (m/s).
    Other {
        /// rad/s if `true`, m/s if not.
        angular: bool,
    },
}

/// One velocity (an entry of v, and of every velocity-space quantity: v̇, h, the columns of D).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VelocityInfo {
    /// `"crank.phi"` (a rate named as its coordinate), `"top.wx"`: the same as its entry of
    /// [`Mechanism::VELOCITY_NAMES`].
    pub name: &'static str,
    /// How it moves the coordinates.
    pub kind: VelocityKind,
    /// The small displacement it is the rate of, as linearization names its states: the
    /// coordinate's name for a rate, `"top.rx"` (a rotation about the body's x′ axis) for an
    /// angular velocity.
    pub displacement: &'static str,
}

impl VelocityInfo {
    /// Its unit differentiated `order` more times in time: m/s, m/s², m/s³ for the rate of a
    /// length, rad/s, ... for the rate of an angle and for an angular velocity.
    pub fn unit<M: Mechanism + ?Sized>(&self, order: usize) -> &'static str {
        match self.kind {
            VelocityKind::Rate { coordinate } => match M::COORDINATES.get(coordinate as usize) {
                Some(c) => c.kind.unit(order + 1),
                None => "",
            },
            VelocityKind::Angular { .. } | VelocityKind::Other { angular: true } => ["rad/s", "rad/s²", "rad/s³"][order.min(2)],
            VelocityKind::Other { angular: false } => ["m/s", "m/s²", "m/s³"][order.min(2)],
        }
    }

    /// Whether it is written as its coordinate's derivative: the rate of a coordinate whose name
    /// it carries (a planar body's velocities, `"d/dt crank.phi"`), rather than a quantity with
    /// a name of its own (a spatial body's `"top.vx"`).
    pub fn is_named_rate<M: Mechanism + ?Sized>(&self) -> bool {
        match self.kind {
            VelocityKind::Rate { coordinate } => M::COORDINATES.get(coordinate as usize).is_some_and(|c| c.name == self.name),
            VelocityKind::Angular { .. } | VelocityKind::Other { .. } => false,
        }
    }

    /// What goes before its name where its value (`order` 0) or its derivative (`order` 1) is
    /// named, in the CSV header and plots: `"d/dt "` and `"d2/dt2 "` for a velocity named as its
    /// coordinate (`"d/dt crank.phi"`), `""` and `"d/dt "` for one with a name of its own
    /// (`"top.wx"`, `"d/dt top.wx"`).
    pub fn prefix<M: Mechanism + ?Sized>(&self, order: usize) -> &'static str {
        match (self.is_named_rate::<M>(), order) {
            (true, 0) => "d/dt ",
            (true, _) => "d2/dt2 ",
            (false, 0) => "",
            (false, _) => "d/dt ",
        }
    }
}

/// Whether every velocity is the rate of a coordinate (q̇ = B v with B a selection of ones and
/// zeros: q moves as q + h v), as for planar bodies; not where an orientation is a quaternion.
#[cfg(feature = "alloc")]
pub(crate) fn velocities_are_rates<M: Mechanism + ?Sized>() -> bool {
    M::VELOCITIES.iter().all(|v| matches!(v.kind, VelocityKind::Rate { .. }))
}

/// What every generated mechanism says about itself: sizes, names, sparsity, model description.
///
/// Everything here is a compile-time constant of the mechanism; nothing depends on the scalar
/// type or on parameter values.
pub trait Mechanism {
    /// The mechanism's name as written in `mechanism!`.
    const NAME: &'static str;
    /// Moving bodies, in declaration order (ground excluded).
    const BODY_NAMES: &'static [&'static str];
    /// Generalized coordinates q: `"crank.x"`, `"crank.y"`, `"crank.phi"`, ... (planar, 3 per
    /// body); `"top.x"`, ..., `"top.e3"` (spatial, 7 per body).
    const COORDINATE_NAMES: &'static [&'static str];
    /// Velocities v, the entries of every velocity-space quantity (v, v̇, h, the columns of D):
    /// planar v = q̇, so the coordinate names (the default); spatial `"top.vx"`, ..., `"top.wz"`
    /// (6 per body).
    const VELOCITY_NAMES: &'static [&'static str] = Self::COORDINATE_NAMES;
    /// Each coordinate's name and kind, in the order of q: what the analyses read (units, which
    /// coordinates are angles that may be wrapped, which are quaternions), never the names.
    const COORDINATES: &'static [CoordinateInfo];
    /// Each velocity's name and kind, in the order of v.
    const VELOCITIES: &'static [VelocityInfo];
    /// Constraint rows, `"revolute crank~rod: x"`, in the order of Φ.
    const CONSTRAINT_NAMES: &'static [&'static str];
    /// The unit of each row's multiplier λ, in the order of Φ: `"N"` for a row measured in
    /// metres (points, distances, strokes), `"N·m"` for an angle or orientation row, `""` for a
    /// user constraint (whose row's unit the mechanism does not know). Empty: not known.
    const CONSTRAINT_UNITS: &'static [&'static str] = &[];
    /// Runtime parameters, in declaration order.
    const PARAM_NAMES: &'static [&'static str];
    /// Degrees of freedom: velocities − constraints, NV − NC (drivers count as constraints).
    const DOF: i32;
    /// Structurally non-zero entries of D = Φ_q B as `(row, velocity)`, row-major. Every other
    /// entry is zero for every q, t and parameter value.
    const JACOBIAN_PATTERN: &'static [(u16, u16)];
    /// `true` when Φ does not depend on t: then Φ_t = ν = 0 and solvers skip them.
    const PHI_T_IS_ZERO: bool;
    /// Operation counts of each generated function.
    const OP_COUNTS: &'static [OpCount];
    /// Its joints, drivers and user constraints in the order of their rows in Φ.
    const JOINTS: &'static [JointInfo] = &[];
    /// Its force elements, gravity first, then in declaration order.
    const FORCE_ELEMENTS: &'static [ForceInfo] = &[];
    /// Operation counts of `forces`, `forces_q` and `forces_v` with no force element and no
    /// gravity, as a scene leaving them all out generates them: nothing, or a spatial
    /// mechanism's gyroscopic terms.
    ///
    /// The mechanism's own counts of these functions ([`Mechanism::OP_COUNTS`]) are this base,
    /// plus each element's cost alone above it ([`ForceInfo::op_counts`]), less what elements
    /// share (a coil and a shock on one strut compute its length once; two elements on one body
    /// its sine and cosine), plus one addition wherever the terms of two elements meet in one
    /// entry. Empty: not known.
    const BASE_FORCE_OP_COUNTS: &'static [OpCount] = &[];
    /// The physical effects the mechanism declares (`"gravity"`, `"point-to-point
    /// spring-damper-actuator"`, ...): everything else generates no code and costs nothing.
    const EFFECTS: &'static [&'static str] = &[];
    /// A JSON description of the model (bodies, points, vectors, params, constraints with their
    /// expressions), read by the CasADi oracle and by tools. Schema: `docs/formulation.md`.
    const MODEL_JSON: &'static str;
    /// What q and v are: each body's own pose and velocity (body coordinates, the default), or
    /// the relative coordinates of a spanning tree of the joints (`joint_coordinates;`).
    const FORMULATION: Formulation = Formulation::BodyCoordinates;
}

/// What a mechanism's coordinates are ([`Mechanism::FORMULATION`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Formulation {
    /// Each body's pose in q, its velocity in v (Nikravesh ch. 7; Wallrapp's absolute
    /// coordinates): constraints at every joint, M constant.
    BodyCoordinates,
    /// The relative coordinates of a spanning tree of the joints (Nikravesh ch. 9): cut joints,
    /// drivers and user constraints are the only rows, M depends on q, and a body's pose is read
    /// through [`BodyFrames`](crate::BodyFrames).
    JointCoordinates,
}

/// What a generated position solve (`KinematicsHooks::sparse_position_solve`) ended with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PositionStep {
    /// ‖Φ‖∞ is within the tolerance.
    Converged,
    /// Stopped at a value that is not finite or after the most steps allowed.
    Step,
    /// D Dᵀ had no acceptable pivot (a singular position, or a NaN in D).
    Singular,
}

/// A mechanism in body coordinates: `mechanism!` implements it for every mechanism that does
/// not state `joint_coordinates;`. What reads a body's wrench from the multipliers
/// ([`joint_reaction`](crate::joint_reaction)) or draws the bodies from q (`Animation`) requires
/// it, so that `cargo check` refuses a mechanism in joint coordinates there and says why.
#[diagnostic::on_unimplemented(
    message = "joint reactions and animations read the bodies from q and λ: expected a mechanism in body coordinates, found `{Self}` in joint coordinates",
    label = "a mechanism declared with `joint_coordinates;`",
    note = "in joint coordinates a tree joint has no multiplier and a body's pose is not an entry of q: \
            `joint_reaction_at` gives joint reactions there, and `Animation::from_bodies` draws such a mechanism"
)]
pub trait BodyCoordinates: Mechanism {}

/// The solves `mechanism!` plans and generates for a driven mechanism, which the kinematic
/// solver and inverse dynamics call first: plumbing between the generated code and the runtime,
/// not an API (`mbd::__private`, as serde keeps its own). Every method is provided, doing nothing
/// (`None`, `false`: the solvers then take their dense paths), so a mechanism written by hand
/// implements it empty, `impl KinematicsHooks<T, NQ, NV, NC> for MyMechanism {}`.
#[doc(hidden)]
pub trait KinematicsHooks<T: Real, const NQ: usize, const NV: usize, const NC: usize> {
    /// A driven mechanism's position solve over the sparse factorization planned at compile
    /// time: Newton's iteration q ← q ⊕ Δv with Δv = −Dᵀ(D Dᵀ)⁻¹Φ — for a square, regular D
    /// (NV = NC) the Newton step D⁻¹(−Φ) itself — from the LDLᵀ of D Dᵀ that `mechanism!` plans
    /// (the Schur complement of the forward dynamics with unit weights), the loop in generated
    /// code and its rules from `Newton` (`solvers/newton.rs`), the dense solve's. A step expected to
    /// end the iteration keeps D and its factors (simplified Newton): where ‖Φ‖∞ · (‖Φ‖∞ / ‖Φ‖∞ at the last step) · `reuse` ≤ `tolerance`; infinite
    /// `reuse` evaluates and factors D at every step. A step longer than `max_step` (‖Δv‖∞) is
    /// shortened to it along its direction (`limit_step`). Returns what it
    /// ended with, the steps taken and the factorizations of D made, q at the last iterate and
    /// Φ(q, t) in `phi`:
    /// [`PositionStep::Converged`] when ‖Φ‖∞ ≤ `tolerance`; [`PositionStep::Singular`] when a
    /// pivot is at most `pivot_tolerance` times its diagonal; [`PositionStep::Step`] when Φ or a
    /// step is not finite or `max_iterations` steps are taken. The solver goes on from there
    /// with the dense LU, which names the coordinate without a pivot or the row that is not
    /// finite. `None` (the provided method) where nothing is generated: the dense path from the
    /// start.
    #[allow(clippy::too_many_arguments)]
    fn sparse_position_solve(
        &self,
        q: &mut [T; NQ],
        t: T,
        tolerance: T,
        pivot_tolerance: T,
        max_iterations: u32,
        reuse: T,
        max_step: T,
        phi: &mut [T; NC],
        step: &mut [T; NV],
    ) -> Option<(PositionStep, u32, u32)> {
        let _ = (q, t, tolerance, pivot_tolerance, max_iterations, reuse, max_step, phi, step);
        None
    }
    /// A driven mechanism's velocity and acceleration (NV = NC, D regular) over the sparse
    /// factorization planned at compile time: D v = ν(q, t), then D v̇ = γ(q, v, t), each as
    /// x = Dᵀ(D Dᵀ)⁻¹ b from one LDLᵀ of D Dᵀ (the position solve's), refined on the residual
    /// b − D x until a correction is below √ε of x (at most four times). q must satisfy
    /// Φ(q, t) = 0. False — `v` and `vd` unspecified — where a pivot is at most
    /// `pivot_tolerance` times its diagonal, a value is not finite or the refinement does not
    /// settle: the solver then takes the dense LU, which names the coordinate or row. False
    /// (the provided method) where nothing is generated.
    fn sparse_velocity_acceleration(&self, q: &[T; NQ], t: T, pivot_tolerance: T, v: &mut [T; NV], vd: &mut [T; NV]) -> bool {
        let _ = (q, t, pivot_tolerance, v, vd);
        false
    }
    /// A driven mechanism's multipliers (NV = NC, D regular) from Dᵀλ = b, as inverse dynamics
    /// needs them, over the sparse factorization planned at compile time: λ = (D Dᵀ)⁻¹ D b,
    /// refined on the residual b − Dᵀλ as `sparse_velocity_acceleration` is.
    /// False — `lambda` unspecified — where a pivot is at most `pivot_tolerance` times its
    /// diagonal, a value is not finite or the refinement does not settle: inverse dynamics then
    /// takes the dense LU of Dᵀ, which names what failed. False (the provided method) where
    /// nothing is generated.
    fn sparse_multipliers(&self, q: &[T; NQ], t: T, pivot_tolerance: T, b: &[T; NV], lambda: &mut [T; NC]) -> bool {
        let _ = (q, t, pivot_tolerance, b, lambda);
        false
    }
}

/// Constraint equations of a mechanism and their exact derivatives in velocity space, for `NQ`
/// coordinates, `NV` velocities and `NC` constraint rows (planar: NV = NQ). Generated by
/// `mechanism!`; every function is straight-line code that writes into the caller's storage and
/// never allocates or panics.
pub trait Kinematics<T: Real, const NQ: usize, const NV: usize, const NC: usize>: Mechanism + KinematicsHooks<T, NQ, NV, NC> {
    /// The initial guess for the coordinates (`at:` of each body), in m and rad.
    fn initial_positions(&self) -> [T; NQ];
    /// The initial guess for the velocities (`velocity:` of each body), in m/s and rad/s.
    fn initial_velocities(&self) -> [T; NV];
    /// q̇ = B(q) v: the rates of the coordinates (planar: q̇ = v).
    fn position_rates(&self, q: &[T; NQ], v: &[T; NV], qdot: &mut [T; NQ]);
    /// q ← q ⊕ h·dv: q + h B(q) dv, then each orientation renormalized (spatial; planar:
    /// q + h dv). Every position update in velocity space goes through here: integrator steps,
    /// Newton corrections (Δv solved from D Δv = −Φ, applied with h = 1).
    fn integrate_positions(&self, q: &mut [T; NQ], dv: &[T; NV], h: T);
    /// Projects q onto the normalization manifold: each body's Euler parameters divided by their
    /// norm (spatial); nothing (planar). Integrators call it after each accepted step.
    fn normalize_positions(&self, q: &mut [T; NQ]);
    /// Φ(q, t).
    fn constraints(&self, q: &[T; NQ], t: T, phi: &mut [T; NC]);
    /// D = Φ_q(q, t) B(q), written whole (structural zeros included).
    fn jacobian(&self, q: &[T; NQ], t: T, d: &mut [[T; NV]; NC]);
    /// ν = −Φ_t(q, t): the right-hand side of the velocity equations D v = ν.
    fn velocity_rhs(&self, q: &[T; NQ], t: T, nu: &mut [T; NC]);
    /// γ = −𝒟(𝒟Φ) along q̇ = B(q)v with v̇ = 0: the right-hand side of D v̇ = γ (planar:
    /// γ = −(Φ_q q̇)_q q̇ − 2 Φ_qt q̇ − Φ_tt).
    fn gamma(&self, q: &[T; NQ], v: &[T; NV], t: T, gamma: &mut [T; NC]);
    /// Φ and D in one evaluation (shared subexpressions computed once): a Newton step's inputs.
    fn position_eval(&self, q: &[T; NQ], t: T, phi: &mut [T; NC], d: &mut [[T; NV]; NC]);
    /// Φ, D, ν and γ in one evaluation (shared subexpressions computed once).
    #[allow(clippy::too_many_arguments)]
    fn full_eval(&self, q: &[T; NQ], v: &[T; NV], t: T, phi: &mut [T; NC], d: &mut [[T; NV]; NC], nu: &mut [T; NC], gamma: &mut [T; NC]);
}

/// Mass matrix and forces of a mechanism, for `NQ` coordinates, `NV` velocities and `NC`
/// constraint rows: the equations of motion M v̇ − Dᵀ λ = h(q, v, t), D v̇ = γ (Nikravesh
/// ch. 13; spatial: the Newton–Euler equations, docs/formulation.md). Generated by `mechanism!`
/// from the bodies' masses and the declared force elements; a force element the mechanism does
/// not declare generates no code.
pub trait Dynamics<T: Real, const NQ: usize, const NV: usize, const NC: usize>: Kinematics<T, NQ, NV, NC> {
    /// y = M(q) x for the NV × NV mass matrix M: in body coordinates diag(m, m, J) per planar
    /// body, blockdiag(m I₃, J′) per spatial body (kg, kg·m²), constant; in joint coordinates
    /// M(q) = Σ_b m_b J_rᵀJ_r + J_ωᵀ J_b J_ω over the bodies' twist Jacobians.
    fn mass_times(&self, q: &[T; NQ], x: &[T; NV], y: &mut [T; NV]);
    /// Each body's mass and inertia as the parameters make them, checked: the first body whose
    /// mass is not positive and finite, or whose inertia is not (planar J; spatial J′ positive
    /// definite, its smallest principal moment reported), as
    /// [`DynamicsError::NonPositiveMass`](crate::DynamicsError::NonPositiveMass). Every analysis that uses M — simulation, inverse
    /// dynamics, statics, linearization — calls it first, so that a mass given as a parameter
    /// (`Name { m: -1.0, .. }`) is refused by each of them naming the body. `mechanism!`
    /// generates it; the provided method checks nothing (a hand-written model).
    fn check_inertia(&self) -> Result<(), crate::model::dynamics::DynamicsError> {
        Ok(())
    }
    /// a += scale · M(q); only M's structural non-zeros are touched.
    fn add_mass_matrix(&self, q: &[T; NQ], scale: T, a: &mut [[T; NV]; NV]);
    /// a += scale · (∂(M(q) x)/∂q) B at fixed x: the change of the inertia forces M v̇ with the
    /// configuration, which a linearization and an implicit Newton matrix need where M depends
    /// on q. Nothing where M is constant (body coordinates), as this provided method does.
    fn add_mass_derivative(&self, q: &[T; NQ], x: &[T; NV], scale: T, a: &mut [[T; NV]; NV]) {
        let _ = (q, x, scale, a);
    }
    /// x ← M(q)⁻¹ x by the mechanism's own recursion, where it has one: a tree in joint
    /// coordinates solves by the articulated-body algorithm, O(N) operations, without forming
    /// M. `Some(Ok(()))` when solved; `Some(Err(i))` when an articulated inertia is not positive
    /// (a body without mass at the end of a branch), i the first velocity of its link, x
    /// unchanged; `None` where the mechanism has no recursion and the caller factors M, as this
    /// provided method says.
    fn solve_mass(&self, q: &[T; NQ], x: &mut [T; NV]) -> Option<Result<(), usize>> {
        let _ = (q, x);
        None
    }
    /// Each row of `rows` ← M(q)⁻¹ row: the NC right-hand sides of the constraint rows' Schur
    /// complement D M⁻¹ Dᵀ over one factorization. Where the mechanism has a recursion with
    /// rows (a closed loop in joint coordinates), what depends on q only — the articulated
    /// inertias and their factors — is computed once and each row runs only its own passes;
    /// as this provided method does, [`solve_mass`](Self::solve_mass) row by row elsewhere.
    /// The same `Some` and `None` as `solve_mass` (with no rows, what `solve_mass` says of a zero
    /// vector); on an error the rows are unspecified.
    fn solve_mass_rows(&self, q: &[T; NQ], rows: &mut [[T; NV]; NC]) -> Option<Result<(), usize>> {
        if NC == 0 {
            return self.solve_mass(q, &mut [T::ZERO; NV]);
        }
        let mut solved = None;
        for row in rows.iter_mut() {
            solved = self.solve_mass(q, row);
            if !matches!(solved, Some(Ok(()))) {
                break;
            }
        }
        solved
    }
    /// The size of a velocity-space vector x as a motion: the largest component of any body's
    /// twist J_b x (m or rad). In body coordinates that is x's largest entry (a spatial body's
    /// angular components in its own frame), as this provided method says; in joint
    /// coordinates a joint near ground moves every body beyond it, farther than its own entry.
    /// Statics measures its steps by it.
    fn motion_size(&self, q: &[T; NQ], x: &[T; NV]) -> T {
        let _ = q;
        x.iter().fold(T::ZERO, |size, x| size.max(x.abs()))
    }
    /// v̇ = M(q)⁻¹ h(q, v, t), the accelerations without constraint forces, by the
    /// mechanism's own recursion where it has one (one pass for h and the solve: what
    /// [`solve_mass`](Self::solve_mass) of [`forces`](Self::forces) gives, for less); the
    /// same `Some` and `None` as `solve_mass`.
    fn free_accelerations(&self, q: &[T; NQ], v: &[T; NV], t: T, vd: &mut [T; NV]) -> Option<Result<(), usize>> {
        let _ = (q, v, t, vd);
        None
    }
    /// τ = M(q) v̇ − h(q, v, t): the generalized forces a motion needs besides the constraint
    /// forces — a tree's joint torques (N·m) and forces (N), its whole inverse dynamics. As this
    /// provided method computes it, `mass_times` minus `forces`; a tree in joint coordinates
    /// generates one recursive Newton–Euler pass (O(N), the bodies' twists computed once).
    fn inverse_forces(&self, q: &[T; NQ], v: &[T; NV], vd: &[T; NV], t: T, tau: &mut [T; NV]) {
        let mut h = [T::ZERO; NV];
        self.forces(q, v, t, &mut h);
        self.mass_times(q, vd, tau);
        for (x, h) in tau.iter_mut().zip(&h) {
            *x -= *h;
        }
    }
    /// h(q, v, t): the generalized applied forces — gravity, springs, dampers, actuators,
    /// applied forces and torques, and (spatial) the gyroscopic term — in N (translational rows)
    /// and N·m (rotational rows).
    fn forces(&self, q: &[T; NQ], v: &[T; NV], t: T, h: &mut [T; NV]);
    /// (∂h/∂q) B, the tangent stiffness (planar: ∂h/∂q), written whole (structural zeros
    /// included).
    fn forces_q(&self, q: &[T; NQ], v: &[T; NV], t: T, dh: &mut [[T; NV]; NV]);
    /// ∂h/∂v, written whole (structural zeros included).
    fn forces_v(&self, q: &[T; NQ], v: &[T; NV], t: T, dh: &mut [[T; NV]; NV]);
    /// Potential energy of gravity and springs V(q) in J (h = −(∂V/∂q) B + non-conservative
    /// forces).
    fn potential_energy(&self, q: &[T; NQ], t: T) -> T;
    /// Adds the Coulomb friction forces of the joints declared with `coulomb: μ` to `h`, for the
    /// joint reactions given by the multipliers λ (their normal loads). Does nothing for a
    /// mechanism without Coulomb friction. Not part of [`Dynamics::forces`], which is λ-free.
    fn friction_forces(&self, q: &[T; NQ], v: &[T; NV], t: T, lambda: &[T; NC], h: &mut [T; NV]);
    /// Adds the exact (∂/∂q) B and ∂/∂v of [`Dynamics::friction_forces`] at fixed λ to `d_q` and
    /// `d_v` (only their structural non-zeros are touched; nothing without Coulomb friction).
    /// The regularized law's slope in the sliding speed s, μN v_s²/(s² + v_s²)^{3/2} (μN/v_s at
    /// s = 0), is what makes sticking stiff: implicit integrators need it in their iteration
    /// matrix.
    #[allow(clippy::too_many_arguments)]
    fn friction_derivatives(&self, q: &[T; NQ], v: &[T; NV], t: T, lambda: &[T; NC], d_q: &mut [[T; NV]; NV], d_v: &mut [[T; NV]; NV]);
    /// Adds the slope of [`Dynamics::friction_forces`] in the multipliers at fixed (q, v), row by
    /// row: row r of `d_lambda` gets ∂f/∂λ_r (force or torque per unit of λ_r), the layout of
    /// D, beside which it stands in the implicit methods' iteration
    /// matrix (−Dᵀ − ∂f/∂λ in the momentum rows' λ columns). A joint's friction grows with its
    /// load — μ R |(λ_x, λ_y)| in a revolute pin — so at most μ (times the pin radius) per unit
    /// of load; without it, Newton converges only linearly where loads carry much friction.
    /// Where a load is exactly zero, the slope of |λ| is taken as zero. Nothing without Coulomb
    /// friction.
    fn friction_multiplier_derivatives(&self, q: &[T; NQ], v: &[T; NV], t: T, lambda: &[T; NC], d_lambda: &mut [[T; NV]; NC]);
    /// Power of the non-conservative forces, vᵀh + dV/dt (W): what dampers, actuators, applied
    /// forces and friction put into the mechanism. The energy balance reads
    /// d(T + V)/dt = this + λᵀ D v (the second term is the power of drivers).
    fn nonconservative_power(&self, q: &[T; NQ], v: &[T; NV], t: T) -> T;
    /// The names of the switching functions: one per unilateral force element (`contact`,
    /// `cable`, `tyre`), the element's name; then the time events, one per comparison of an
    /// expression of t alone (`"road: time event 1"`). Empty for a mechanism without them.
    const SWITCH_NAMES: &'static [&'static str] = &[];
    /// How many of the switching functions, the last ones, are time events: functions of t
    /// alone, whose instants [`Simulation`](crate::Simulation) finds before a step and ends the
    /// step on, where the others are found within a step it has taken. 0 by default.
    const TIME_SWITCHES: usize = 0;
    /// Switching function `k` of [`Dynamics::SWITCH_NAMES`] at (q, v, t), positive exactly while
    /// the element's force acts: its overlap δ (penetration, stretch, tyre compression; m) out of
    /// contact, its unclamped force law (N) in contact. Where it changes sign within a step,
    /// [`Simulation`](crate::Simulation) locates the instant and cuts the step there. 0 for k past
    /// the end.
    fn switching_function(&self, k: usize, q: &[T; NQ], v: &[T; NV], t: T) -> T {
        let _ = (k, q, v, t);
        T::ZERO
    }
}

/// The derivative of the constraint forces Dᵀλ by q along B, for fixed multipliers λ:
/// K(q, t, λ) = ∂(Dᵀ λ)/∂q · B (NV × NV; planar: Σ_r λ_r ∂²Φ_r/∂q², symmetric), the
/// constraints' geometric stiffness. Newton iterations on the equilibrium or index-3 equations
/// of motion need it. Generated by `mechanism!` exactly, from the symbolic Jacobian.
pub trait ConstraintForces<T: Real, const NQ: usize, const NV: usize, const NC: usize>: Kinematics<T, NQ, NV, NC> {
    /// Writes K(q, t, λ) whole (structural zeros included).
    fn constraint_force_q(&self, q: &[T; NQ], t: T, lambda: &[T; NC], k: &mut [[T; NV]; NV]);
}

/// Generalized-α's Newton matrix in sparse storage planned at compile time
/// ([`crate::sparse`]): D's structural non-zeros and the entries of
///
/// ```text
/// [ M − c_v ∂h/∂v − c_q (∂h/∂q·B + K)   −Dᵀ ]
/// [ D                                     0  ]
/// ```
///
/// over [`NEWTON_PATTERN`](Self::NEWTON_PATTERN), fill-in included (c_v = γ'h, c_q = β'h²;
/// ∂h/∂q and ∂h/∂v with Coulomb friction's at fixed λ; K from [`ConstraintForces`]). Where the
/// step's end is q₊ = q ⊕ Δ on the rotation group (generalized-α), every derivative by the
/// positions — c_q's terms and the rows of D — is taken times the tangent operator T(Δ) on each
/// body's three rotational columns (`crate::model::group`'s docs), so the pattern holds all
/// three of a body's rotational columns in a row that touches one.
/// `mechanism!` generates all of it in body coordinates, straight-line over the structural
/// non-zeros only. The provided methods build the same storage from the dense derivatives, for
/// joint coordinates (M(q) and its derivatives are dense) and mechanisms that are not generated
/// (a wrapper such as [`crate::FiniteDifferences`], a hand-written test model), in a work
/// space's arrays ([`DenseScratch`]).
pub trait NewtonMatrix<T: Real, const NQ: usize, const NV: usize, const NC: usize>:
    crate::model::dynamics::ForwardDynamics<T, NQ, NV, NC> + ConstraintForces<T, NQ, NV, NC>
{
    /// `[T; NNZ + entries]`: D's non-zeros in [`Mechanism::JACOBIAN_PATTERN`] order, then the
    /// matrix's entries over [`NEWTON_PATTERN`](Self::NEWTON_PATTERN).
    type NewtonStorage: crate::model::workspace::NewtonStorage<T>;
    /// Elimination order and fill of the Newton matrix's LU factors.
    const NEWTON_PATTERN: crate::linalg::sparse::SparsePattern;
    /// Storage of zeros.
    fn newton_storage() -> Self::NewtonStorage;
    /// Factors the matrix in `s` in place ([`crate::sparse::factor`], whose arguments and errors
    /// these are; unknowns as errors name them: v̇ entries, then multipliers). `mechanism!`
    /// generates it straight-line for small mechanisms; larger ones run the planned pattern.
    fn newton_factor(
        s: &mut Self::NewtonStorage,
        tolerance: T,
        allow_redundant: bool,
        dropped: &mut [bool; NC],
    ) -> Result<T, crate::linalg::LinalgError> {
        let nnz = Self::JACOBIAN_PATTERN.len();
        crate::linalg::sparse::factor(&Self::NEWTON_PATTERN, &mut s.as_mut()[nnz..], NV, tolerance, allow_redundant, dropped)
    }
    /// Solves with the factors in `s`, in place: `b` holds NV + NC entries, v̇'s then λ's.
    fn newton_solve(s: &Self::NewtonStorage, b: &mut [T]) {
        let nnz = Self::JACOBIAN_PATTERN.len();
        crate::linalg::sparse::solve(&Self::NEWTON_PATTERN, &s.as_ref()[nnz..], b);
    }
    /// Φ(q, t) into `phi` and D's non-zeros into the front of `s`; the provided method
    /// evaluates D densely in `scratch.d` (a work space's, [`Workspace::dense`](crate::WorkArrays::dense)).
    fn newton_jacobian(&self, q: &[T; NQ], t: T, phi: &mut [T; NC], s: &mut Self::NewtonStorage, scratch: DenseScratch<'_, T, NV, NC>) {
        let d = scratch.d;
        self.position_eval(q, t, phi, d);
        for (value, &(r, c)) in s.as_mut().iter_mut().zip(Self::JACOBIAN_PATTERN) {
            *value = d[r as usize][c as usize];
        }
    }
    /// What [`newton_jacobian`](Self::newton_jacobian) writes, and the matrix's entries at
    /// (q, v, v̇, t, λ) after D's in `s`, fill-in zeroed, ready for the factorization: one
    /// evaluation for both. v̇ enters where M depends on q, through c_q ∂(M v̇)/∂q.
    /// `displacement`: the Δ of q = q₀ ⊕ Δ on the group, whose tangent operator multiplies the
    /// derivatives by the positions (the trait's docs); `None` for none (T = I: statics, and
    /// methods that move q by q + B(q)Δ). The provided method fills it from dense derivatives: A,
    /// D and D T in `scratch` (the work space's), the second NV × NV matrix in `s`'s entries,
    /// which it writes last (off the stack where they are NV² or more, as a dense velocity
    /// block's are: joint coordinates).
    #[allow(clippy::too_many_arguments)]
    fn newton_matrix(
        &self,
        q: &[T; NQ],
        v: &[T; NV],
        vd: &[T; NV],
        t: T,
        lambda: &[T; NC],
        displacement: Option<&[T; NV]>,
        c_v: T,
        c_q: T,
        phi: &mut [T; NC],
        s: &mut Self::NewtonStorage,
        mut scratch: DenseScratch<'_, T, NV, NC>,
    ) {
        self.newton_jacobian(q, t, phi, s, scratch.reborrow());
        let DenseScratch { d, y: d_tangent, l: a, .. } = scratch;
        // Rows times T(Δ) on each body's rotational columns, in place.
        let tangent = |rows: &mut [[T; NV]]| crate::model::group::turn_columns::<T, Self, NQ, NV, NC>(displacement, rows);
        // D from the front of the storage, densely (the pattern's entries only: a wrapper's
        // differences leave noise off it).
        let nnz = Self::JACOBIAN_PATTERN.len();
        for row in d.iter_mut() {
            row.fill(T::ZERO);
        }
        for (&value, &(r, c)) in s.as_ref().iter().zip(Self::JACOBIAN_PATTERN) {
            d[r as usize][c as usize] = value;
        }
        let turned = displacement.is_some() && Self::VELOCITIES.iter().any(|v| matches!(v.kind, VelocityKind::Angular { .. }));
        // The constraint rows' D T (D where there is no T) apart, so that `d` can take
        // friction's slope in λ for the λ columns: −Dᵀ − ∂f/∂λ.
        d_tangent.copy_from_slice(&d[..]);
        if turned {
            tangent(d_tangent);
        }
        self.friction_multiplier_derivatives(q, v, t, lambda, d);
        let d_rows: &[[T; NV]; NC] = d_tangent;
        // The derivatives by the positions, ∂(h − M v̇)/∂q·B (∂(M v̇)/∂q through q₊'s dependence
        // on v̇: nothing where M is constant) and K, each times T before they are summed.
        self.forces_q(q, v, t, a);
        with_square(&mut s.as_mut()[nnz..], |second| {
            self.forces_v(q, v, t, second);
            self.friction_derivatives(q, v, t, lambda, a, second);
            self.add_mass_derivative(q, vd, -T::ONE, a);
            tangent(a);
            for (row, damping) in a.iter_mut().zip(second.iter()) {
                for (x, &c) in row.iter_mut().zip(damping) {
                    *x = -c_q * *x - c_v * c;
                }
            }
            self.constraint_force_q(q, t, lambda, second);
            tangent(second);
            for (row, stiffness) in a.iter_mut().zip(second.iter()) {
                for (x, &k) in row.iter_mut().zip(stiffness) {
                    *x -= c_q * k;
                }
            }
        });
        self.add_mass_matrix(q, T::ONE, a);
        let pattern = Self::NEWTON_PATTERN;
        let values = &mut s.as_mut()[nnz..];
        for i in 0..pattern.size() {
            let u = pattern.unknown[i] as usize;
            let row = pattern.row_start[i] as usize..pattern.row_start[i + 1] as usize;
            for (value, &column) in values[row.clone()].iter_mut().zip(&pattern.columns[row]) {
                let w = pattern.unknown[column as usize] as usize;
                *value = match (u < NV, w < NV) {
                    (true, true) => a[u][w],
                    (true, false) => -d[w - NV][u],
                    (false, true) => d_rows[u - NV][w],
                    (false, false) => T::ZERO,
                };
            }
        }
    }
}

/// Calls `f` with an NV × NV matrix in the front of `values` where it is that long, else (a
/// sparse pattern's entries, a wrapper's) with one on the stack of a function of its own, so
/// that only that case's frame holds it.
fn with_square<T: Real, const NV: usize>(values: &mut [T], f: impl FnOnce(&mut [[T; NV]; NV])) {
    #[inline(never)]
    fn on_stack<T: Real, const NV: usize>(f: impl FnOnce(&mut [[T; NV]; NV])) {
        f(&mut [[T::ZERO; NV]; NV]);
    }
    if values.len() < NV * NV {
        return on_stack(f);
    }
    // SAFETY: `values` holds at least NV² consecutive, initialized `T`s, exclusively borrowed
    // for the call; `[[T; NV]; NV]` is NV² `T`s with T's alignment and no padding. `f`'s
    // matrix borrows them for no longer than `values`.
    let square = unsafe { &mut *values.as_mut_ptr().cast::<[[T; NV]; NV]>() };
    f(square);
}

/// What a linearization needs beyond [`Dynamics`] and [`ConstraintForces`]: the exact
/// derivatives of γ, and the inputs — the parameters that enter the applied forces h and
/// nothing else (an actuator's force, a motor's torque, an applied load), so that a change of
/// one is a change of load and not of the mechanism. Generated by `mechanism!`.
pub trait Linearize<T: Real, const NQ: usize, const NV: usize, const NC: usize>:
    Dynamics<T, NQ, NV, NC> + ConstraintForces<T, NQ, NV, NC>
{
    /// The parameters that enter h and nothing else (not Φ, M or Coulomb friction), in
    /// declaration order: a linearization's possible inputs u.
    const INPUTS: &'static [&'static str];
    /// (∂γ/∂q) B and ∂γ/∂v at (q, v, t), written whole (structural zeros included).
    fn gamma_derivatives(&self, q: &[T; NQ], v: &[T; NV], t: T, gamma_q: &mut [[T; NV]; NC], gamma_v: &mut [[T; NV]; NC]);
    /// ∂h/∂u_k for input `k` of [`Linearize::INPUTS`] (N or N·m per unit of the input), written
    /// whole; zeros for k past the end.
    fn forces_input(&self, k: usize, q: &[T; NQ], v: &[T; NV], t: T, dh: &mut [T; NV]);
    /// The value of input `k` (0 for k past the end).
    fn input(&self, k: usize) -> T;
    /// Sets input `k` (nothing for k past the end).
    fn set_input(&mut self, k: usize, value: T);
}
