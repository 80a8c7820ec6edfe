//! Kinematic analysis of a driven mechanism (DOF = NV − NC = 0): at each time t, solve
//!
//! ```text
//! Φ(q, t) = 0        position      (Newton–Raphson: D Δv = −Φ, q ← q ⊕ Δv)
//! D v = ν            velocity      (ν = −Φ_t)
//! D v̇ = γ            acceleration  (γ = −𝒟(𝒟Φ); planar −(Φ_q q̇)_q q̇ − 2 Φ_qt q̇ − Φ_tt)
//! ```
//!
//! with D = Φ_q B in velocity space (planar: v = q̇, D = Φ_q), all three over the LDLᵀ of D Dᵀ
//! that `mechanism!` plans at compile time where D is square (the dense LU of D where that
//! finds no pivot, and for the separate velocity and acceleration solves); q ⊕ Δv is
//! [`Kinematics::integrate_positions`] with h = 1. Coordinates are in m and rad, velocities in
//! m/s and rad/s, accelerations in m/s² and rad/s², times in s. Assembly ([`KinematicSolver::assemble`]) also handles DOF > 0 with
//! minimum-norm Newton steps.
//!
//! Nothing here allocates. D (NC × NV) and, for minimum-norm steps, D Dᵀ (NC × NC) live in the
//! caller's [`Workspace`]; the stack holds only O(NV + NC) scalars, so large mechanisms run on
//! an ordinary thread's stack.

use crate::linalg::orthogonal::{least_determined, orthogonalize, rank_revealing_step, solve_orthogonalized};
use crate::linalg::{self, LinalgError, LuWork};
use crate::model::mechanism::{Kinematics, Mechanism, PositionStep};
use crate::model::workspace::{Vectors, WorkArrays, Workspace};
use crate::real::Real;
use crate::solvers::error::{KinematicError, NonFiniteQuantity};
use crate::solvers::flow::Flow;
use crate::solvers::newton::{Newton, NewtonNext};

mod closest;
use closest::closest;

/// Default [`KinematicOptions::tolerance`]: ‖Φ‖∞ ≤ 1e-10 (m, rad), about 10⁶ ulps of a 1 m
/// coordinate in f64. Below what f32 resolves (its ulp at 1 m is 1.2e-7): every tolerance is
/// raised to [`RESOLUTION_ULPS`] ulps of the coordinates' scale, 7.6e-6 m for f32 at 1 m.
pub const DEFAULT_TOLERANCE: f64 = 1e-10;
/// The smallest ‖Φ‖∞ a position solve is asked for, in units of the scalar's machine epsilon ε
/// times the coordinates' scale max(1, ‖q‖∞): a tolerance below 64 ε max(1, ‖q‖∞) is raised to
/// it. Φ is a sum of a few products of coordinates, so rounding alone leaves it at a few ε times
/// their size, and Newton cannot go below that; 64 ε leaves a factor of ten or so. It binds for
/// f32 (7.6e-6 m at 1 m) and for f64 in mechanisms of kilometres (1.4e-10 m at 10 km); at
/// metres in f64 the default 1e-10 is 7000 times above it.
pub const RESOLUTION_ULPS: f64 = 64.0;
/// Default [`KinematicOptions::max_iterations`]: Newton converges quadratically, so from a
/// reasonable guess 3–6 iterations suffice; 25 leaves room for rough guesses.
pub const DEFAULT_MAX_ITERATIONS: u32 = 25;
/// Default [`KinematicOptions::pivot_tolerance`]: a pivot below 1e-12 of its column's largest
/// original entry means the column is dependent to about four orders above f64 rounding.
pub const DEFAULT_PIVOT_TOLERANCE: f64 = 1e-12;
/// Default [`KinematicOptions::reuse_safety`]: the kept factors of D are trusted for a last
/// step when ‖Φ‖∞ times the last step's contraction is 100 times within the tolerance. Near the
/// solution Newton's contraction θ = ‖Φ_k‖/‖Φ_(k−1)‖ is about κ‖Δq‖, and so is the chord
/// method's from factors taken one step back (its rate is κ times the distance travelled since
/// they were taken), so ‖Φ_k‖ θ predicts the residual after one more step with them. The
/// prediction is good to an order of magnitude, not two: measured on the slider-crank a
/// millisecond on, 7.2e-7 m times θ = 1.1e-4 predicts 8e-11 and the kept factors reach 1.0e-9
/// (Newton 1.6e-12), so a factor of 100 makes that step take a fresh D, while the driven chain
/// of 16 (1.1e-8 m, θ = 2.4e-5: 2.6e-11 after the factor) ends on the kept ones at 1e-16.
pub const DEFAULT_REUSE_SAFETY: f64 = 100.0;
/// Default [`KinematicOptions::max_step`]: a Newton step moves no coordinate by more than 1 (m
/// or rad). Near a singular position (a dead centre) D is nearly singular and the full step
/// D⁻¹(−Φ) is huge — measured on a slider-crank driven by its slider, the first step after the
/// dead centre was 264 rad: the crank landed 42 turns away, on a solution of the same pose but
/// with its angle no longer continuous. A step of 1 rad is already far outside where the
/// linearization holds, and no step of a sweep or of a drift correction comes near it.
pub const DEFAULT_MAX_STEP: f64 = 1.0;
/// The pivot ratio of D Dᵀ (a squared sine: rows meeting at 1e-3) below which an analysis
/// checks that its velocity is determined (`check_determined` in the source): a few dense
/// solves and three evaluations of Φ, only near a singular position.
const NEAR_SINGULAR_RATIO: f64 = 1e-6;
/// The solves of the inverse iteration of `check_determined`.
const INVERSE_ITERATIONS: usize = 3;
/// `check_determined` refuses a position whose nearby singular one satisfies Φ to this many
/// times the position tolerance: its estimates of σ and κ are each good to a factor of about
/// two. (Measured: the slider-crank and the four-bar at their toggles read 2.4 and 3.2 times
/// the tolerance; 1e-8 m from the slider-crank's dead centre, 160 times.)
const DETERMINED_MARGIN: f64 = 8.0;
/// Default [`KinematicOptions::predictor`]: on.
pub const DEFAULT_PREDICTOR: bool = true;
/// Default [`KinematicOptions::rank_tolerance`]: a constraint row whose angle to the rows before
/// it has a sine of at most 1e-8 is redundant. Rounding leaves about 1e-15 × the condition of
/// the rows before it, so a clearly redundant row reads 1e-14 or so (the parallelogram with a
/// third crank: 2e-17), while a row kept at 1e-8 still carries eight digits of its own.
pub const DEFAULT_RANK_TOLERANCE: f64 = 1e-8;

/// Name used when a mechanism's name lists are shorter than its sizes (a broken
/// implementation): errors still carry a name instead of panicking.
const UNNAMED: &str = "<unnamed>";

crate::options::options! {
    /// Settings of the kinematic solver, in the scalar type `T` of the mechanism (default
    /// `f64`). Build from [`Default`] and the `with_*` setters:
    ///
    /// ```
    /// # use mbd_runtime::KinematicOptions;
    /// let options = KinematicOptions::default().with_tolerance(1e-6).with_max_iterations(10);
    /// # let _: KinematicOptions<f64> = options;
    /// ```
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct KinematicOptions<T> {
        /// Convergence test of the position solve: ‖Φ(q, t)‖∞ ≤ `tolerance`, in the units of the
        /// constraint rows (m for points and distances, rad or dimensionless for angles). Default
        /// [`DEFAULT_TOLERANCE`]; raised to what the scalar type resolves, [`RESOLUTION_ULPS`] · ε ·
        /// max(1, ‖q‖∞), where it is below that.
        tolerance: T = T::from_f64(DEFAULT_TOLERANCE) => with_tolerance,
        /// Newton iterations allowed per position solve before [`KinematicError::NotConverged`].
        /// Default [`DEFAULT_MAX_ITERATIONS`].
        max_iterations: u32 = DEFAULT_MAX_ITERATIONS => with_max_iterations,
        /// The longest Newton step of a position solve, ‖Δv‖∞ (m or rad): a longer one is
        /// shortened to it along its direction (damped Newton), so that an iterate near a singular
        /// position does not leave the branch it is on; infinity takes Newton's full step. Default
        /// [`DEFAULT_MAX_STEP`].
        max_step: T = T::from_f64(DEFAULT_MAX_STEP) => with_max_step,
        /// Relative pivot tolerance τ of the LU factorization: a pivot is accepted when
        /// |pivot| > τ · (largest |entry| of its column of D): relative to the column, so the verdict
        /// is the same whatever a coordinate's unit (m or rad). Values below
        /// the scalar type's machine epsilon are raised to it (pivots that small are rounding
        /// noise). Default [`DEFAULT_PIVOT_TOLERANCE`].
        pivot_tolerance: T = T::from_f64(DEFAULT_PIVOT_TOLERANCE) => with_pivot_tolerance,
        /// In [`KinematicSolver::sweep`], start each position solve from the first-order
        /// prediction q ⊕ v (t − t_previous) instead of the previous q; if Newton fails from the
        /// prediction, the point is retried once from the previous q. Default [`DEFAULT_PREDICTOR`].
        predictor: bool = DEFAULT_PREDICTOR => with_predictor,
        /// In [`KinematicSolver::redundancy`], a row whose sine of angle to the span of the rows
        /// before it is at most this is redundant (dimensionless). Default [`DEFAULT_RANK_TOLERANCE`].
        rank_tolerance: T = T::from_f64(DEFAULT_RANK_TOLERANCE) => with_rank_tolerance,
        /// Simplified Newton in the position solve of a square D over the factorization
        /// `mechanism!` plans: a step expected to end the iteration keeps the last D and its
        /// factors and evaluates Φ alone (the chord method) — where ‖Φ_k‖∞ times the last step's
        /// contraction ‖Φ_k‖∞/‖Φ_(k−1)‖∞, times this factor, is within
        /// [`tolerance`](Self::tolerance); every other step evaluates and factors D anew. Infinity
        /// takes Newton's full step every time (dimensionless). Default [`DEFAULT_REUSE_SAFETY`].
        reuse_safety: T = T::from_f64(DEFAULT_REUSE_SAFETY) => with_reuse_safety,
    }
}

/// How a position solve ended.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Convergence {
    /// Newton iterations performed (0 when the starting q already satisfied the tolerance).
    pub iterations: u32,
    /// Evaluations and factorizations of D among them: as many as the iterations, less one for
    /// each step that kept the last factors ([`KinematicOptions::reuse_safety`]).
    pub factorizations: u32,
    /// ‖Φ(q, t)‖∞ at the returned q, in the units of the constraint rows.
    pub residual: f64,
}

/// Position, velocity and acceleration of a mechanism at one time: the result of
/// [`KinematicSolver::analyze`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct KinematicState<T, const NQ: usize, const NV: usize> {
    /// Time (s).
    pub t: T,
    /// Coordinates q with Φ(q, t) = 0 (m, rad).
    pub q: [T; NQ],
    /// Velocities v with D v = ν (m/s, rad/s; planar v = q̇).
    pub v: [T; NV],
    /// Accelerations v̇ with D v̇ = γ (m/s², rad/s²).
    pub vd: [T; NV],
    /// How the position solve converged.
    pub convergence: Convergence,
}

/// Kinematic analysis of mechanisms generated by `mechanism!` (any
/// `M: Kinematics<T, NQ, NV, NC>`).
///
/// Position, velocity, acceleration and sweeps need a driven mechanism: NV = NC (DOF = 0), or
/// more rows than velocities when some are redundant (a parallelogram with a third crank,
/// driven): those are solved over the rows independent of the rows declared before them
/// ([`crate::redundancy`]), which must then number NV. [`assemble`](Self::assemble) accepts
/// any NC. The solver holds only its options: one solver
/// serves any number of mechanisms and scalar types.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KinematicSolver<T = f64> {
    /// Tolerances and limits.
    pub options: KinematicOptions<T>,
}

impl<T: Real> Default for KinematicSolver<T> {
    fn default() -> Self {
        Self::new(KinematicOptions::new())
    }
}

/// How a Newton iteration computes its step from D and −Φ.
#[derive(Clone, Copy, PartialEq, Eq)]
enum StepRule {
    /// D Δv = −Φ with D square (LU with partial pivoting).
    Square,
    /// The minimum-norm step over the rows independent of the rows before them
    /// ([`crate::redundancy`]): for redundant constraints, any NC.
    RankRevealing,
}

/// `names[index]`, or [`UNNAMED`] if the list is too short.
pub(crate) fn name(names: &'static [&'static str], index: usize) -> &'static str {
    names.get(index).copied().unwrap_or(UNNAMED)
}

/// Index of the first NaN or infinity in `values`.
pub(crate) fn first_non_finite<T: Real>(values: &[T]) -> Option<usize> {
    values.iter().position(|v| !v.is_finite())
}

/// (max |v_i|, i) of finite values, the first index among equals; (0, 0) when empty.
fn max_abs<T: Real>(values: &[T]) -> (T, usize) {
    values.iter().enumerate().fold((T::ZERO, 0), |(best, at), (i, v)| {
        let magnitude = v.abs();
        if magnitude > best {
            (magnitude, i)
        } else {
            (best, at)
        }
    })
}

/// The smallest constraint residual the scalar type resolves at coordinates `q`:
/// [`RESOLUTION_ULPS`] · ε · max(1, ‖q‖∞) (7.6e-6 m for f32 at 1 m, 1.4e-14 for f64). Every
/// Newton tolerance of the runtime is raised to it, so the documented defaults converge in f32.
pub(crate) fn resolution<T: Real>(q: &[T]) -> T {
    T::from_f64(RESOLUTION_ULPS) * T::EPSILON * max_abs(q).0.max(T::ONE)
}

/// Velocities minus constraint rows.
fn degrees_of_freedom(nv: usize, nc: usize) -> i32 {
    nv as i32 - nc as i32
}

/// NotDriven while degrees of freedom are left (NV > NC). More rows than velocities are
/// accepted: a driven mechanism with redundant constraints, solved over its independent rows
/// (which must then number NV; checked where D is factored).
pub(crate) fn require_driven<const NV: usize, const NC: usize>() -> Result<(), KinematicError> {
    match degrees_of_freedom(NV, NC) {
        dof if dof > 0 => Err(KinematicError::NotDriven { dof }),
        _ => Ok(()),
    }
}

/// A factored Jacobian of a driven mechanism: LU in place (NV = NC, its interchanges in the work
/// space's `indices.pivots_c`), or, with redundant rows (NC > NV), the orthogonalization of its
/// rows in the work space's `jacobian_scratch` (Q) and `constraint_square` (R) with the rows
/// left out.
enum Factors<const NC: usize> {
    Lu,
    Orthogonal { redundant: [bool; NC] },
}

/// The step rule of a driven mechanism's position solve: the square LU, or with more rows than
/// velocities the minimum-norm step over the independent rows (as assembly takes).
const fn driven_rule<const NV: usize, const NC: usize>() -> StepRule {
    if NV == NC {
        StepRule::Square
    } else {
        StepRule::RankRevealing
    }
}

/// The error for a failed factorization or solve of the square Jacobian D at time `t`.
fn jacobian_error<M: Mechanism>(error: LinalgError, t: f64) -> KinematicError {
    match error {
        LinalgError::Singular { column, candidate_row } => KinematicError::SingularJacobian {
            t,
            coordinate: name(M::VELOCITY_NAMES, column),
            constraint: name(M::CONSTRAINT_NAMES, candidate_row),
        },
        LinalgError::NonFinite { row, .. } => {
            KinematicError::NonFinite { t, quantity: NonFiniteQuantity::Jacobian, row: name(M::CONSTRAINT_NAMES, row) }
        }
        LinalgError::NotSquare { rows, columns } | LinalgError::Overdetermined { rows, columns } => {
            KinematicError::NotDriven { dof: degrees_of_freedom(columns, rows) }
        }
    }
}

/// NonFinite naming the first constraint row of D that holds a NaN or an infinity.
pub(crate) fn check_rows_finite<T: Real, M: Mechanism, const NV: usize, const NC: usize>(
    d: &[[T; NV]; NC],
    t: T,
) -> Result<(), KinematicError> {
    match d.iter().position(|row| row.iter().any(|x| !x.is_finite())) {
        Some(r) => {
            Err(KinematicError::NonFinite { t: t.to_f64(), quantity: NonFiniteQuantity::Jacobian, row: name(M::CONSTRAINT_NAMES, r) })
        }
        None => Ok(()),
    }
}

/// NonFinite for the first non-finite entry of `values`, named from `names`.
pub(crate) fn check_finite<T: Real>(
    values: &[T],
    t: T,
    quantity: NonFiniteQuantity,
    names: &'static [&'static str],
) -> Result<(), KinematicError> {
    match first_non_finite(values) {
        Some(index) => Err(KinematicError::NonFinite { t: t.to_f64(), quantity, row: name(names, index) }),
        None => Ok(()),
    }
}

/// NonFinite if t is NaN or infinite.
pub(crate) fn check_time<T: Real>(t: T) -> Result<(), KinematicError> {
    if t.is_finite() {
        Ok(())
    } else {
        Err(KinematicError::NonFinite { t: t.to_f64(), quantity: NonFiniteQuantity::Time, row: "t" })
    }
}

impl<T: Real> KinematicSolver<T> {
    /// A solver with the given options.
    pub const fn new(options: KinematicOptions<T>) -> Self {
        Self { options }
    }

    /// The relative pivot tolerance in T, raised to T's machine epsilon.
    fn pivot_tolerance(&self) -> T {
        self.options.pivot_tolerance.max(T::EPSILON)
    }

    /// Position solve: Newton–Raphson on Φ(q, t) = 0 for a driven mechanism (NV = NC; with
    /// redundant rows, NC > NV, the minimum-norm step over the independent rows),
    ///
    /// ```text
    /// D(q_k, t) Δv = −Φ(q_k, t),   q_{k+1} = q_k ⊕ Δv   (Kinematics::integrate_positions, h = 1),
    /// ```
    ///
    /// from the q given, until ‖Φ‖∞ ≤ [`KinematicOptions::tolerance`]. Each iteration costs one
    /// evaluation of Φ and D and one factorization of D (for a square D, the LDLᵀ of D Dᵀ
    /// `mechanism!` plans), except that a last step expected to converge keeps D's factors and
    /// evaluates Φ alone ([`KinematicOptions::reuse_safety`]). On success `q` holds the
    /// solution (m, rad); on error it holds the last iterate.
    ///
    /// # Errors
    /// [`KinematicError::NotDriven`] if NV > NC; [`KinematicError::NonFinite`] for a NaN or
    /// infinite t, q, Φ, D or step; [`KinematicError::SingularJacobian`] (also where the
    /// independent rows of a redundant mechanism number fewer than NV);
    /// [`KinematicError::NotConverged`].
    pub fn solve_position<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
        &self,
        m: &M,
        ws: &mut Workspace<T, NV, NC, N, NS>,
        q: &mut [T; NQ],
        t: T,
    ) -> Result<Convergence, KinematicError>
    where
        M: Kinematics<T, NQ, NV, NC>,
    {
        require_driven::<NV, NC>()?;
        let guess = *q;
        let convergence = self.newton(m, q, t, ws, driven_rule::<NV, NC>()).map_err(|e| self.diagnose(m, &guess, t, ws, e))?;
        if NV != NC {
            // With redundant rows the independent ones must still determine every velocity.
            self.factor::<M, NV, NC, N, NS>(ws, t)?;
        }
        Ok(convergence)
    }

    /// Assembly: brings a rough guess `q` onto the constraint manifold Φ(q, t) = 0, for any
    /// number of constraint rows, with undamped Newton steps of minimum norm over the rows that
    /// are independent at the iterate,
    ///
    /// ```text
    /// Δv = −D_Iᵀ (D_I D_Iᵀ)⁻¹ Φ_I(q_k, t),   q_{k+1} = q_k ⊕ Δv,
    /// ```
    ///
    /// which, among all corrections that zero those linearized rows, moves q the least: the free
    /// coordinates stay as close to the guess as the constraints allow. D's rows are
    /// orthogonalized in declaration order ([`crate::redundancy`]; no Gram matrix, so D's
    /// condition number is not squared), and a row is left out of this step — I is the rest —
    /// when the sine of its angle to the rows before it is at most
    /// max([`KinematicOptions::rank_tolerance`], min(0.1, ‖Φ‖∞ / max(1, ‖q‖∞))): along a
    /// direction that nearly repeats others the linearization cannot be trusted while the
    /// residual is large, and near the solution the test falls to `rank_tolerance`, so
    /// convergence is Newton's. After a step that did not halve ‖Φ‖∞ every row takes part in
    /// the next (a waiting row may be the one holding the residual).
    /// Redundant constraints (a parallelogram with a third crank, two collinear guides: NC may
    /// exceed NV) therefore assemble: a consistent redundant row is met when the others are. A
    /// row that contradicts the others is left violated, and the error names it. The guess must
    /// lie in the basin of attraction of the wanted assembly mode: Newton converges to the
    /// nearest branch, not to a chosen one.
    ///
    /// Where Newton does not converge, a Levenberg–Marquardt descent on ½‖Φ‖² from the guess
    /// takes over (it accepts only steps that lower ‖Φ‖): if it reaches the tolerance, that is
    /// the assembly (counted in [`Convergence::iterations`]); if it stops at a local minimum,
    /// the constraints cannot all hold near the guess, and the error says so with the residual
    /// and the rows of the loop that does not close, `q` left at that closest configuration.
    ///
    /// # Errors
    /// [`KinematicError::NonFinite`]; [`KinematicError::CannotAssemble`] (Newton and the
    /// descent both stopped short).
    pub fn assemble<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
        &self,
        m: &M,
        ws: &mut Workspace<T, NV, NC, N, NS>,
        q: &mut [T; NQ],
        t: T,
    ) -> Result<Convergence, KinematicError>
    where
        M: Kinematics<T, NQ, NV, NC>,
    {
        let guess = *q;
        let newton = self.newton(m, q, t, ws, StepRule::RankRevealing);
        let Err(KinematicError::NotConverged { iterations, .. }) = newton else { return newton };
        *q = guess;
        let tolerance = self.position_tolerance(q);
        let reached = closest(m, q, t, tolerance, ws);
        match reached.rows {
            None => Ok(Convergence {
                iterations: iterations + reached.steps,
                factorizations: iterations + reached.steps,
                residual: reached.residual,
            }),
            Some(rows) => Err(KinematicError::CannotAssemble { t: t.to_f64(), residual: reached.residual, rows }),
        }
    }

    /// A driven solve's Newton failure, told apart: where a descent from `guess` finds no
    /// configuration that meets the constraints, [`KinematicError::CannotAssemble`] naming the
    /// loop; where it does, the guess was too far (or the tolerance too tight) and Newton's
    /// [`KinematicError::NotConverged`] stands. `q` is left as Newton left it.
    fn diagnose<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
        &self,
        m: &M,
        guess: &[T; NQ],
        t: T,
        ws: &mut Workspace<T, NV, NC, N, NS>,
        error: KinematicError,
    ) -> KinematicError
    where
        M: Kinematics<T, NQ, NV, NC>,
    {
        if !matches!(error, KinematicError::NotConverged { .. }) {
            return error;
        }
        let mut q = *guess;
        let tolerance = self.position_tolerance(&q);
        let reached = closest(m, &mut q, t, tolerance, ws);
        match reached.rows {
            None => error,
            Some(rows) => KinematicError::CannotAssemble { t: t.to_f64(), residual: reached.residual, rows },
        }
    }

    /// Velocity solve for a driven mechanism (NV = NC, or NC > NV with redundant rows):
    /// D(q, t) v = ν(q, t), ν = −Φ_t, written to `v` (m/s, rad/s). `q` must already satisfy
    /// Φ(q, t) = 0 (it is not checked). ν is not evaluated when [`Mechanism::PHI_T_IS_ZERO`].
    /// `v` is unspecified on error.
    ///
    /// # Errors
    /// [`KinematicError::NotDriven`]; [`KinematicError::NonFinite`] for t, q, D, ν or v;
    /// [`KinematicError::SingularJacobian`].
    pub fn solve_velocity<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
        &self,
        m: &M,
        ws: &mut Workspace<T, NV, NC, N, NS>,
        q: &[T; NQ],
        t: T,
        v: &mut [T; NV],
    ) -> Result<(), KinematicError>
    where
        M: Kinematics<T, NQ, NV, NC>,
    {
        require_driven::<NV, NC>()?;
        check_time(t)?;
        check_finite(q, t, NonFiniteQuantity::Coordinate, M::COORDINATE_NAMES)?;
        m.jacobian(q, t, &mut ws.jacobian);
        let factors = self.factor::<M, NV, NC, N, NS>(ws, t)?;
        velocity_from_factors(m, q, t, ws, &factors, v)
    }

    /// Acceleration solve for a driven mechanism (NV = NC, or NC > NV with redundant rows):
    /// D(q, t) v̇ = γ(q, v, t), written to `vd` (m/s², rad/s²). `q` and `v` must already satisfy
    /// Φ = 0 and D v = ν (not checked). `vd` is unspecified on error.
    ///
    /// # Errors
    /// [`KinematicError::NotDriven`]; [`KinematicError::NonFinite`] for t, q, v, D, γ or v̇;
    /// [`KinematicError::SingularJacobian`].
    pub fn solve_acceleration<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
        &self,
        m: &M,
        ws: &mut Workspace<T, NV, NC, N, NS>,
        q: &[T; NQ],
        v: &[T; NV],
        t: T,
        vd: &mut [T; NV],
    ) -> Result<(), KinematicError>
    where
        M: Kinematics<T, NQ, NV, NC>,
    {
        require_driven::<NV, NC>()?;
        check_time(t)?;
        check_finite(q, t, NonFiniteQuantity::Coordinate, M::COORDINATE_NAMES)?;
        check_finite(v, t, NonFiniteQuantity::Velocity, M::VELOCITY_NAMES)?;
        m.jacobian(q, t, &mut ws.jacobian);
        let factors = self.factor::<M, NV, NC, N, NS>(ws, t)?;
        acceleration_from_factors(m, q, v, t, ws, &factors, vd)
    }

    /// Complete kinematic analysis at time t from the guess `q`: position (Newton, as
    /// [`solve_position`](Self::solve_position)), then velocity D v = ν and acceleration
    /// D v̇ = γ with a single factorization of D at the converged q.
    ///
    /// Where D is square and `mechanism!` planned its factorization, one generated function
    /// evaluates D and ν, factors D Dᵀ over the planned pattern, solves v = Dᵀ(D Dᵀ)⁻¹ν, evaluates
    /// γ with the sines and cosines already taken, and solves v̇ the same way; each solve is
    /// refined on its residual until a correction is below √ε of the answer, which takes the
    /// normal equations' κ(D)² ε of error back to an LU's κ(D) ε. Where that finds no pivot or
    /// a value that is not finite, D is evaluated and factored by the dense LU, which names the
    /// coordinate or row that failed: the whole analysis then costs the Newton iterations plus
    /// one [`Kinematics::jacobian`], one [`Kinematics::velocity_rhs`], one
    /// [`Kinematics::gamma`] and one factorization.
    ///
    /// # Errors
    /// Those of [`solve_position`](Self::solve_position), [`solve_velocity`](Self::solve_velocity)
    /// and [`solve_acceleration`](Self::solve_acceleration); and
    /// [`KinematicError::SingularJacobian`] where the position solved is as close to a
    /// singular one as the position tolerance τ tells: D's smallest singular value σ and Φ's
    /// curvature κ along its direction put the singular position σ/κ away with Φ about
    /// σ²/(2κ) there; where that is within 8τ, D v = ν and D v̇ = γ determine nothing (see
    /// `check_determined` in the source). A smaller tolerance resolves positions closer to it.
    pub fn analyze<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
        &self,
        m: &M,
        ws: &mut Workspace<T, NV, NC, N, NS>,
        q: &[T; NQ],
        t: T,
    ) -> Result<KinematicState<T, NQ, NV>, KinematicError>
    where
        M: Kinematics<T, NQ, NV, NC>,
    {
        require_driven::<NV, NC>()?;
        let mut state = KinematicState {
            t,
            q: *q,
            v: [T::ZERO; NV],
            vd: [T::ZERO; NV],
            convergence: Convergence { iterations: 0, factorizations: 0, residual: 0.0 },
        };
        state.convergence = self.analyze_in_place(m, &mut state.q, t, ws, &mut state.v, &mut state.vd)?;
        Ok(state)
    }

    /// Kinematic sweep of a driven mechanism (NV ≤ NC, see above) over `times` (s): for each t in turn,
    ///
    /// 1. start from the previous solution q — or, with [`KinematicOptions::predictor`], from
    ///    its first-order prediction q ⊕ v (t − t_previous), which cuts Newton iterations when
    ///    the steps are small against the motion (if Newton fails from the prediction, the
    ///    point is retried once from the previous q);
    /// 2. solve the position, velocity and acceleration as [`analyze`](Self::analyze) does;
    /// 3. call `f(t, q, v, v̇)`; if it returns [`ControlFlow::Break`](core::ops::ControlFlow)
    ///    rather than `()` or `Continue`, the sweep ends there ([`crate::Flow`]).
    ///
    /// The first point starts from the `q` given, which should be consistent (see
    /// [`assemble`](Self::assemble)) or close to it. On return `q` holds the last solution that
    /// was reached: the last point on success, the last good point before an error (the failed
    /// point's iterate is discarded), so a caller can inspect it or resume. Nothing is
    /// allocated; `times` may be any iterator of times or of references to them (`&times`, as
    /// [`Simulation`](crate::Simulation) takes them), in any order.
    ///
    /// # Errors
    /// The first error of any point (each carries its t); the sweep stops there.
    pub fn sweep<M, R, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
        &self,
        m: &M,
        ws: &mut Workspace<T, NV, NC, N, NS>,
        q: &mut [T; NQ],
        times: impl IntoIterator<Item = impl core::borrow::Borrow<T>>,
        mut f: impl FnMut(T, &[T; NQ], &[T; NV], &[T; NV]) -> R,
    ) -> Result<(), KinematicError>
    where
        M: Kinematics<T, NQ, NV, NC>,
        R: Flow,
    {
        require_driven::<NV, NC>()?;
        let mut v = [T::ZERO; NV];
        let mut vd = [T::ZERO; NV];
        let mut previous_time: Option<T> = None;
        for t in times {
            let t = *t.borrow();
            let mut trial = *q;
            let predicted = match previous_time {
                Some(t_previous) if self.options.predictor => {
                    m.integrate_positions(&mut trial, &v, t - t_previous);
                    true
                }
                _ => false,
            };
            let mut result = self.analyze_in_place(m, &mut trial, t, ws, &mut v, &mut vd);
            if predicted && result.is_err() {
                trial = *q;
                result = self.analyze_in_place(m, &mut trial, t, ws, &mut v, &mut vd);
            }
            result?;
            *q = trial;
            if f(t, q, &v, &vd).stops() {
                break;
            }
            previous_time = Some(t);
        }
        Ok(())
    }

    /// Position, velocity and acceleration at t into `q`, `v`, `vd` (NV ≤ NC, checked by the
    /// callers), with `jacobian` as work space.
    fn analyze_in_place<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
        &self,
        m: &M,
        q: &mut [T; NQ],
        t: T,
        ws: &mut Workspace<T, NV, NC, N, NS>,
        v: &mut [T; NV],
        vd: &mut [T; NV],
    ) -> Result<Convergence, KinematicError>
    where
        M: Kinematics<T, NQ, NV, NC>,
    {
        let guess = *q;
        let convergence = self.newton(m, q, t, ws, driven_rule::<NV, NC>()).map_err(|e| self.diagnose(m, &guess, t, ws, e))?;
        if NV == NC {
            // The factorization planned at compile time; where a pivot is near dependence
            // (`NEAR_SINGULAR_RATIO`) or a value is not finite, the dense path below, which
            // names what failed and checks that the velocity is determined.
            if m.sparse_velocity_acceleration(q, t, self.near_singular_ratio(q), v, vd) {
                return Ok(convergence);
            }
            // D at the converged q (the sparse step of a square D leaves `ws.jacobian` as it was).
            m.jacobian(q, t, &mut ws.jacobian);
        }
        let factors = self.factor::<M, NV, NC, N, NS>(ws, t)?;
        if NV == NC {
            self.check_determined(m, q, t, ws, &factors)?;
        }
        velocity_from_factors(m, q, t, ws, &factors, v)?;
        acceleration_from_factors(m, q, v, t, ws, &factors, vd)?;
        Ok(convergence)
    }

    /// The position tolerance at q: [`KinematicOptions::tolerance`], raised to what the scalar
    /// resolves ([`RESOLUTION_ULPS`] ε max(1, ‖q‖∞)).
    fn position_tolerance(&self, q: &[T]) -> T {
        self.options.tolerance.max(resolution(q))
    }

    /// The pivot ratio of D Dᵀ (to its diagonal: the squared sine of a row's angle to the rows
    /// eliminated before it) below which an analysis takes the dense path and
    /// [`check_determined`](Self::check_determined): [`NEAR_SINGULAR_RATIO`], or a thousand
    /// times the position tolerance relative to max(1, ‖q‖∞) where that is larger, so that every
    /// position that check refuses is screened.
    fn near_singular_ratio(&self, q: &[T]) -> T {
        let tolerance = self.position_tolerance(q);
        let relative = tolerance / max_abs(q).0.max(T::ONE);
        (T::from_f64(1e3) * relative).max(T::from_f64(NEAR_SINGULAR_RATIO)).max(self.pivot_tolerance())
    }

    /// Whether the velocity and acceleration of an analysis are determined at the q it solved,
    /// which satisfies Φ(q, t) = 0 only to the position tolerance τ, before they are solved;
    /// `ws.jacobian` holds D's LU.
    ///
    /// Near a singular position, D's smallest singular value σ, along the direction n, grows
    /// with the distance from it: Φ(q + s n) ≈ Φ(q) + s σ u + ½ s² κ, κ = Φ's curvature along n,
    /// so the singular position lies σ/κ away, where Φ is about σ²/(2κ). Where that is within
    /// the tolerance the position solved is the singular one as far as τ can tell, and D v = ν
    /// determines nothing there: on a slider-crank driven by its slider, and on a four-bar
    /// driven by its rocker, each on a grid that reached the toggle exactly, the crank read
    /// ω = 0 while it turned at 1.2 and 6.3 rad/s (at sines of 6e-6 and 5.5e-5: κ differs by
    /// mechanism, so a fixed pivot tolerance cannot tell). So where σ²/(2κ) ≤
    /// [`DETERMINED_MARGIN`] τ the analysis returns [`KinematicError::SingularJacobian`], naming
    /// the velocity n moves most and the row that bends most along it.
    ///
    /// n is D⁻¹ b for a fixed b with no special direction, normalized, with D⁻¹ applied twice
    /// more (inverse iteration): D is nearly singular along n alone, so every other direction
    /// shrinks at each solve. (After one solve the four-bar at its toggle read σ twice too
    /// large, and the criterion missed it.) σ = ‖D n‖, and κ the second difference of Φ over
    /// ±h n, h = 1e-4 max(1, ‖q‖∞) (rounding leaves ε/h² ≈ 1e-8 of it). Its arrays are only on
    /// the stack while it runs: near a singular position.
    #[inline(never)]
    fn check_determined<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
        &self,
        m: &M,
        q: &[T; NQ],
        t: T,
        ws: &mut Workspace<T, NV, NC, N, NS>,
        factors: &Factors<NC>,
    ) -> Result<(), KinematicError>
    where
        M: Kinematics<T, NQ, NV, NC>,
    {
        let mut b: [T; NC] = core::array::from_fn(|i| T::from_f64(1.0 + ((i * 618) % 1000) as f64 / 1000.0));
        let mut n = [T::ZERO; NV];
        for _ in 0..INVERSE_ITERATIONS {
            solve_factored::<T, M, NV, NC, N, NS>(ws, factors, &b, &mut n, t)?;
            let size = n.iter().fold(T::ZERO, |s, &x| s + x * x).sqrt();
            if !(size > T::ZERO && size.is_finite()) {
                return Ok(());
            }
            for x in n.iter_mut() {
                *x /= size;
            }
            b = core::array::from_fn(|i| n[i]);
        }
        m.jacobian(q, t, &mut ws.jacobian_scratch);
        let sigma = ws.jacobian_scratch.iter().fold(T::ZERO, |s, row| {
            let dn = row.iter().zip(&n).fold(T::ZERO, |a, (&d, &x)| a + d * x);
            s + dn * dn
        });
        let sigma = sigma.sqrt();
        let h = T::from_f64(1e-4) * max_abs(q).0.max(T::ONE);
        // Φ(q ⊕ h n) + Φ(q ⊕ −h n) − 2 Φ(q), over h², into `bend`.
        let (mut bend, mut phi) = ([T::ZERO; NC], [T::ZERO; NC]);
        m.constraints(q, t, &mut phi);
        for (r, &x) in phi.iter().enumerate() {
            bend[r] = T::ZERO - (x + x);
        }
        for side in [h, T::ZERO - h] {
            let mut moved = *q;
            m.integrate_positions(&mut moved, &n, side);
            m.constraints(&moved, t, &mut phi);
            for (bend, &x) in bend.iter_mut().zip(&phi) {
                *bend += x;
            }
        }
        for x in bend.iter_mut() {
            *x /= h * h;
        }
        let kappa = bend.iter().fold(T::ZERO, |s, &x| s + x * x).sqrt();
        let tolerance = self.position_tolerance(q);
        if sigma * sigma <= T::from_f64(2.0 * DETERMINED_MARGIN) * kappa * tolerance {
            return Err(KinematicError::SingularJacobian {
                t: t.to_f64(),
                coordinate: name(M::VELOCITY_NAMES, max_abs(&n).1),
                constraint: name(M::CONSTRAINT_NAMES, max_abs(&bend).1),
            });
        }
        Ok(())
    }

    /// D (in `ws.jacobian`) factored: LU in place when square, with failures named after the
    /// mechanism's rows and velocities; with more rows than velocities, its rows orthogonalized
    /// in declaration order, those that depend on the rows before them (sine ≤
    /// [`KinematicOptions::rank_tolerance`]) left out — the independent rows must number NV,
    /// else the velocity they leave least determined is named as a singular Jacobian's.
    fn factor<M, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
        &self,
        ws: &mut Workspace<T, NV, NC, N, NS>,
        t: T,
    ) -> Result<Factors<NC>, KinematicError>
    where
        M: Mechanism,
    {
        if NV == NC {
            let WorkArrays { jacobian, vectors, indices, .. } = &mut **ws;
            let work = LuWork {
                pivots: &mut indices.pivots_c,
                columns: &mut indices.columns_v,
                scale: Vectors::new(vectors.flat()).take_written(),
            };
            return linalg::lu_factor(jacobian, self.pivot_tolerance(), work)
                .map(|()| Factors::Lu)
                .map_err(|e| jacobian_error::<M>(e, t.to_f64()));
        }
        let WorkArrays { jacobian, jacobian_scratch: basis, constraint_square: r, .. } = &mut **ws;
        check_rows_finite::<T, M, NV, NC>(jacobian, t)?;
        let redundant = independent_rows::<T, M, NV, NC>(jacobian, self.options.rank_tolerance, basis, r, t)?;
        Ok(Factors::Orthogonal { redundant })
    }

    /// Newton iteration on Φ(q, t) = 0 with the given step rule, each step Δv applied as
    /// q ⊕ Δv. A square D takes the generated `sparse_position_solve` first and, when that
    /// converges, leaves `jacobian` alone; otherwise (and from where that stopped), on success,
    /// `jacobian` holds D(q, t) at the returned q (unfactored): the convergence test comes after
    /// each evaluation, so the last evaluation is at the solution.
    fn newton<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
        &self,
        m: &M,
        q: &mut [T; NQ],
        t: T,
        ws: &mut Workspace<T, NV, NC, N, NS>,
        rule: StepRule,
    ) -> Result<Convergence, KinematicError>
    where
        M: Kinematics<T, NQ, NV, NC>,
    {
        check_time(t)?;
        check_finite(q, t, NonFiniteQuantity::Coordinate, M::COORDINATE_NAMES)?;
        let time = t.to_f64();
        let tolerance = self.position_tolerance(q);
        let pivot_tolerance = self.pivot_tolerance();
        let (max_iterations, max_step) = (self.options.max_iterations, self.options.max_step);
        let mut previous_norm = T::from_f64(f64::INFINITY);
        let WorkArrays { jacobian, jacobian_scratch, constraint_square, vectors, indices, .. } = &mut **ws;
        let mut vectors = Vectors::new(vectors.flat());
        let [residual, negative_residual] = vectors.rows::<NC, 2>();
        let step = vectors.take::<NV>();
        let scale = vectors.take_written::<NV>();
        // A square D: the iteration over the sparse factorization planned at compile time; the
        // dense LU where none is generated or from where that stopped (a pivot not found: the LU
        // names the coordinate without one, or finds one, D Dᵀ's pivots being D's squared; a
        // value not finite or too many steps: the loop below names the row).
        let mut newton = Newton::new(tolerance, max_iterations, T::from_f64(f64::INFINITY), max_step);
        if rule == StepRule::Square {
            let reuse = self.options.reuse_safety;
            let sparse = m.sparse_position_solve(q, t, tolerance, pivot_tolerance, max_iterations, reuse, max_step, residual, step);
            if let Some((end, taken, factored)) = sparse {
                if end == PositionStep::Converged {
                    return Ok(Convergence { iterations: taken, factorizations: factored, residual: max_abs(residual).0.to_f64() });
                }
                newton = newton.resumed(taken, factored);
            }
        }
        // The same rules as the sparse loop's, D evaluated and factored at every step.
        loop {
            m.position_eval(q, t, residual, jacobian);
            check_finite(residual, t, NonFiniteQuantity::Constraint, M::CONSTRAINT_NAMES)?;
            let (norm, worst) = max_abs(residual);
            if let NewtonNext::Stop(end) = newton.after_residual(residual) {
                let (end, iterations, factorizations) = newton.end(end);
                return match end {
                    PositionStep::Converged => Ok(Convergence { iterations, factorizations, residual: norm.to_f64() }),
                    _ => Err(KinematicError::NotConverged {
                        t: time,
                        iterations,
                        worst_row: name(M::CONSTRAINT_NAMES, worst),
                        residual: norm.to_f64(),
                    }),
                };
            }
            for (negated, &value) in negative_residual.iter_mut().zip(residual.iter()) {
                *negated = -value;
            }
            match rule {
                StepRule::Square => {
                    let work = LuWork { pivots: &mut indices.pivots_c, columns: &mut indices.columns_v, scale: &mut *scale };
                    linalg::lu_factor(jacobian, pivot_tolerance, work)
                        .and_then(|()| linalg::lu_solve(jacobian, &indices.pivots_c, negative_residual, step))
                        .map_err(|e| jacobian_error::<M>(e, time))
                }
                StepRule::RankRevealing => {
                    check_rows_finite::<T, M, NV, NC>(jacobian, t)?;
                    // A row whose independent part is small against the residual is near-
                    // dependent at this iterate: the linearization cannot be trusted along it,
                    // so it waits (sine ≤ min(0.1, ‖Φ‖∞ / max(1, ‖q‖∞)): a step at most ten
                    // times a row's residual); near the solution the test falls to
                    // `rank_tolerance` and the step is Newton's. If the last step did not halve
                    // ‖Φ‖∞, every row takes part (a waiting row may hold the residual).
                    let rank_tolerance = self.options.rank_tolerance;
                    let threshold = if norm <= T::from_f64(0.5) * previous_norm {
                        let relative = norm / max_abs(q).0.max(T::ONE);
                        let cap = T::from_f64(0.1);
                        (if relative < cap { relative } else { cap }).max(rank_tolerance)
                    } else {
                        rank_tolerance
                    };
                    previous_norm = norm;
                    rank_revealing_step(jacobian, negative_residual, threshold, jacobian_scratch, constraint_square, step);
                    Ok(())
                }
            }?;
            newton.factored();
            check_finite(step, t, NonFiniteQuantity::Step, M::VELOCITY_NAMES)?;
            let accepted = newton.accept_step(step);
            debug_assert!(accepted, "a finite step");
            m.integrate_positions(q, step, T::ONE);
        }
    }
}

/// x = D⁻¹ b from the factors of D: the LU's, or over the independent rows.
fn solve_factored<T, M, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    ws: &Workspace<T, NV, NC, N, NS>,
    factors: &Factors<NC>,
    b: &[T; NC],
    x: &mut [T; NV],
    t: T,
) -> Result<(), KinematicError>
where
    T: Real,
    M: Mechanism,
{
    match factors {
        Factors::Lu => linalg::lu_solve(&ws.jacobian, &ws.indices.pivots_c, b, x).map_err(|e| jacobian_error::<M>(e, t.to_f64())),
        Factors::Orthogonal { redundant } => {
            solve_orthogonalized(&ws.jacobian_scratch, &ws.constraint_square, redundant, NV, b, x);
            Ok(())
        }
    }
}

/// v = D⁻¹ ν from the factors of D.
fn velocity_from_factors<T, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    m: &M,
    q: &[T; NQ],
    t: T,
    ws: &Workspace<T, NV, NC, N, NS>,
    factors: &Factors<NC>,
    v: &mut [T; NV],
) -> Result<(), KinematicError>
where
    T: Real,
    M: Kinematics<T, NQ, NV, NC>,
{
    let mut nu = [T::ZERO; NC];
    if !M::PHI_T_IS_ZERO {
        m.velocity_rhs(q, t, &mut nu);
        check_finite(&nu, t, NonFiniteQuantity::VelocityRhs, M::CONSTRAINT_NAMES)?;
    }
    solve_factored::<T, M, NV, NC, N, NS>(ws, factors, &nu, v, t)?;
    check_finite(v, t, NonFiniteQuantity::Velocity, M::VELOCITY_NAMES)
}

/// v̇ = D⁻¹ γ(q, v, t) from the factors of D.
#[allow(clippy::too_many_arguments)]
fn acceleration_from_factors<T, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    m: &M,
    q: &[T; NQ],
    v: &[T; NV],
    t: T,
    ws: &Workspace<T, NV, NC, N, NS>,
    factors: &Factors<NC>,
    vd: &mut [T; NV],
) -> Result<(), KinematicError>
where
    T: Real,
    M: Kinematics<T, NQ, NV, NC>,
{
    let mut gamma = [T::ZERO; NC];
    m.gamma(q, v, t, &mut gamma);
    check_finite(&gamma, t, NonFiniteQuantity::Gamma, M::CONSTRAINT_NAMES)?;
    solve_factored::<T, M, NV, NC, N, NS>(ws, factors, &gamma, vd, t)?;
    check_finite(vd, t, NonFiniteQuantity::Acceleration, M::VELOCITY_NAMES)
}

#[cfg(test)]
mod tests;

/// The rows of a driven mechanism's D with redundant ones (NC > NV): orthogonalized as in
/// [`orthogonalize`], the redundant rows marked; `Err` — a singular Jacobian naming the velocity
/// least determined and the first row left out — when the independent rows number fewer than NV.
pub(crate) fn independent_rows<T: Real, M: Mechanism, const NV: usize, const NC: usize>(
    d: &[[T; NV]; NC],
    tolerance: T,
    basis: &mut [[T; NV]; NC],
    r: &mut [[T; NC]; NC],
    t: T,
) -> Result<[bool; NC], KinematicError> {
    let mut redundant = [false; NC];
    let split = orthogonalize(d, tolerance, basis, r, &mut redundant);
    if split.rank < NV {
        return Err(KinematicError::SingularJacobian {
            t: t.to_f64(),
            coordinate: name(M::VELOCITY_NAMES, least_determined(basis, split.rank)),
            constraint: name(M::CONSTRAINT_NAMES, redundant.iter().position(|&x| x).unwrap_or(0)),
        });
    }
    Ok(redundant)
}
