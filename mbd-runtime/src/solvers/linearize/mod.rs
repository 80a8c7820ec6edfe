//! Linearization on the constraint manifold and modal analysis (Wallrapp 3.6.4–3.6.6), exact
//! from the generated derivatives.
//!
//! # The state and its chart
//!
//! The equations of motion M v̇ − Dᵀλ = h(q, v, t) + (∂h/∂u) δu, D v̇ = γ(q, v, t) hold on the
//! manifold Φ(q, t) = 0, D v = ν. About a state (q₀, v₀) at the instant t₀ the velocities split
//! into f = NV − rank D independent ones, I, and dependent ones (rank-revealing Gaussian
//! elimination with full pivoting on D, each row scaled to its largest entry; or named by the
//! user, [`LinearizeOptions::independent`]). The state of the linear model is
//!
//! ```text
//! x = (y, w),   y = E δ,   w = E v,
//! ```
//!
//! E picking the independent entries, δ the displacement q = q₀ ⊕ δ in velocity space
//! ([`crate::Kinematics::integrate_positions`]; planar δ = q − q₀, spatial a rotation vector per body in
//! its frame), the dependent entries following from Φ = 0 and D v = ν. To first order
//! δ = Z y and δv = Z δw − R G Z y, with the null-space basis Z (Z_I = 1, Z_D = −D_D⁻¹ D_I; D Z = 0),
//! the right inverse R (R_I = 0, R_D = D_D⁻¹) and G = ∂(D v₀ − ν)/∂q B, the change of the
//! velocity constraint with position.
//!
//! # The exact linearization
//!
//! Differentiating the equations of motion about (q₀, v₀, λ₀) gives the saddle-point system for
//! δv̇ and δλ
//!
//! ```text
//! [ M   −Dᵀ ] [δv̇]   [ (H + K) δ + H_v δv + H_u δu                        ]
//! [ D    0  ] [δλ] = [ (Γ_q − Q(v̇₀)) δ + Γ_v δv                           ]
//! ```
//!
//! with H = (∂h/∂q) B, H_v = ∂h/∂v, H_u = ∂h/∂u ([`crate::Dynamics`], [`Linearize::forces_input`]),
//! K = ∂(Dᵀλ₀)/∂q B the constraints' geometric stiffness ([`crate::ConstraintForces`]), Γ_q, Γ_v the
//! derivatives of γ ([`Linearize::gamma_derivatives`]) and Q(a) = ∂(D a)/∂q B, whose row r is
//! aᵀ K(e_r). λ₀ and v̇₀ are the forward dynamics at the state, without Baumgarte terms.
//! G = Q(v₀) − ½ Γ_v(q₀, 0) (γ is quadratic in v, and its part linear in v is −2 Φ_tq B v = 2 ν_q v).
//! In the plane Q(a) = −½ (Γ_v(a) − Γ_v(0)), Q being symmetric there. The system is solved in
//! the null space: δv̇ = Z s + R b (b its lower block), s = M_r⁻¹ Zᵀ (t − M R b) (t its upper
//! block) by one f × f Cholesky, δλ = Rᵀ (M δv̇ − t). Then
//!
//! ```text
//! ẋ = A x + B u,  A = [ E Ω Z        1     ],   B = [ 0       ]
//!                     [ E δv̇/δy   E δv̇/δw ]        [ E δv̇/δu ]
//! ```
//!
//! where Ω = ∂δ̇/∂δ is 0 in the plane and −½[ω₀′×] on a spatial body's rotation (the chart's
//! rotation vector θ moves as θ̇ = ω′ + ½ θ × ω′). Outputs y_out = C x + D u are displacements,
//! velocities, multipliers (δλ from the same solve) or any quantity given by its rate
//! ([`Output`]). The second-order form M_r ÿ + D_r ẏ + K_r y = B_r u has M_r = Zᵀ M Z,
//! K_r = −M_r A₂₁, D_r = −M_r A₂₂, B_r = M_r B₂ — at an equilibrium K_r = −Zᵀ (H + K) Z and
//! D_r = −Zᵀ H_v Z. Redundant constraint rows (dependent on the others at q₀) are left out of the
//! solve; their δλ is reported as 0 (one of the many valid sets).
//!
//! About an equilibrium the linearization is that of the motion; about a moving state it is the
//! frozen-time Jacobian of the vector field in this chart (a different chart changes A by terms
//! proportional to ẋ₀, as for any linearization of a non-stationary point).
//!
//! # The finite-difference linearization
//!
//! [`Linearizer::finite_differences`] takes the same chart and differentiates the forward dynamics
//! itself: each state and input is moved by ±ε (ε = ∛u · max(1, |x|)), the state mapped onto the
//! manifold (Newton on the dependent displacements, the dependent velocities from D v = ν) and
//! v̇, λ evaluated — what a tool without symbolic derivatives does, and an independent check of
//! the exact path: they agree to the differences' truncation error, O(ε²) ≈ 1e-10 relative.
//!
//! # Modes
//!
//! [`Linearization::modes`]: eigenvalues s of A and their eigenvectors, one [`Mode`] per
//! oscillation (a conjugate pair) or real eigenvalue, with the natural frequency |s|/2π (Hz),
//! damping ratio −Re s/|s| and the shape over every velocity. Without damping (D_r = 0, K_r
//! symmetric, Ω = 0) the generalized symmetric problem K_r φ = ω² M_r φ is solved instead, whose
//! shapes are real.
//!
//! Needs the heap (feature `alloc`, part of `std`) for nalgebra's dense matrices, not the
//! standard library: without `std` the elementary functions come from `libm` and only
//! [`Linearization::write_csv`], which writes files, is left out.

use alloc::boxed::Box;
use alloc::format;
use alloc::string::{String, ToString};
use alloc::vec;
use alloc::vec::Vec;
use core::fmt;
#[cfg(feature = "std")]
use std::io::{self, Write};
#[cfg(feature = "std")]
use std::path::Path;

use nalgebra::{Cholesky, Complex, ComplexField, DMatrix, DVector, SymmetricEigen};

use crate::model::dynamics::{DynamicsError, DynamicsOptions, ForwardDynamics};
use crate::model::mechanism::velocities_are_rates;
use crate::model::mechanism::{Linearize, Mechanism, VelocityKind};
use crate::model::workspace::{DenseScratch, Vectors, VECTOR_ROWS};

mod chart;
mod jacobians;
mod modes;

use self::chart::*;
use self::jacobians::*;

/// Default relative tolerance of the rank of D: a pivot below 1e-10 of its row's largest entry
/// marks the row as dependent on the others.
pub const DEFAULT_LINEARIZE_RANK_TOLERANCE: f64 = 1e-10;
/// Default tolerance on ‖Φ‖∞ (m, rad) and ‖D v − ν‖∞ (m/s, rad/s) at the state: the
/// linearization is of the motion on the manifold, so the state must be on it.
pub const DEFAULT_LINEARIZE_CONSISTENCY: f64 = 1e-8;

/// An output of the linear model: a row of C and D.
pub enum Output {
    /// The displacement δ of one velocity direction, by name from
    /// [`Mechanism::VELOCITY_NAMES`]: in the plane a coordinate (`"cart.x"` in m, `"pole.phi"`
    /// in rad); in space `"top.vx"` is the displacement along x (m), `"top.wx"` the small
    /// rotation about the body's x′ axis (rad).
    Displacement(&'static str),
    /// One velocity, by name from [`Mechanism::VELOCITY_NAMES`] (m/s, rad/s).
    Velocity(&'static str),
    /// The multiplier of one constraint row, by name from [`Mechanism::CONSTRAINT_NAMES`]: its
    /// reaction (N or N·m, as [`crate::CsvWriter`]'s header says).
    Multiplier(&'static str),
    /// Any quantity whose rate is linear in v — a point's coordinate, a joint's angle — given by
    /// its rate (`|q, v| Car::WHEEL_C.velocity(q, v).y`): its displacement is the rate with v
    /// replaced by δ. Made by [`Output::rate`].
    Rate {
        /// The name of the output's row.
        name: String,
        /// The quantity's rate at (q, v), linear in v.
        rate: Rate,
        /// The sizes (NQ, NV) of the state the rate takes: the mechanism's, checked when it is
        /// linearized.
        sizes: (usize, usize),
    },
}

/// The rate function of an [`Output::Rate`]: (q, v) ↦ the quantity's rate, linear in v, over
/// slices of the sizes the output holds (NaN for others, which [`Linearizer`] refuses first).
pub type Rate = Box<dyn Fn(&[f64], &[f64]) -> f64>;

impl Output {
    /// A quantity given by its rate ([`Output::Rate`]), a function of the mechanism's
    /// `&[f64; NQ]` and `&[f64; NV]` (so a generated accessor takes them as they are:
    /// `|q, v| Car::WHEEL_C.velocity(q, v).y`).
    pub fn rate<const NQ: usize, const NV: usize>(name: impl Into<String>, rate: impl Fn(&[f64; NQ], &[f64; NV]) -> f64 + 'static) -> Self {
        let rate = move |q: &[f64], v: &[f64]| match (<&[f64; NQ]>::try_from(q), <&[f64; NV]>::try_from(v)) {
            (Ok(q), Ok(v)) => rate(q, v),
            _ => f64::NAN,
        };
        Output::Rate { name: name.into(), rate: Box::new(rate), sizes: (NQ, NV) }
    }

    fn name(&self) -> String {
        match self {
            Output::Displacement(n) => n.to_string(),
            Output::Velocity(n) => format!("{n}_dot"),
            Output::Multiplier(n) => format!("lambda {n}"),
            Output::Rate { name, .. } => name.clone(),
        }
    }
}

impl fmt::Debug for Output {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Output({})", self.name())
    }
}

/// Options of a [`Linearizer`]. Build from [`Default`] and the
/// `with_*` setters. Unlike the solvers' options they are not generic over the scalar:
/// linearization runs in f64 only. Not `Copy`: it holds the lists of inputs and outputs.
#[derive(Debug)]
#[non_exhaustive]
pub struct LinearizeOptions {
    /// The inputs u, by name: a parameter from [`Linearize::INPUTS`] (one that enters only the
    /// applied forces: an actuator's force, a motor's torque; N or N·m), or a driver from
    /// [`Mechanism::JOINTS`] (`"drive crank.phi"`, or the label it was given), whose input is its
    /// acceleration (m/s² or rad/s²) at the driven position and velocity of the state. Default
    /// none.
    pub inputs: Vec<&'static str>,
    /// The outputs. Default none (C and D then have no rows).
    pub outputs: Vec<Output>,
    /// The independent velocities, by name from [`Mechanism::VELOCITY_NAMES`], exactly as many
    /// as the mechanism has degrees of freedom at the state. Default: chosen by pivoting.
    pub independent: Vec<&'static str>,
    /// [`DEFAULT_LINEARIZE_RANK_TOLERANCE`].
    pub rank_tolerance: f64,
    /// [`DEFAULT_LINEARIZE_CONSISTENCY`].
    pub consistency_tolerance: f64,
}

impl Default for LinearizeOptions {
    fn default() -> Self {
        Self::new()
    }
}

impl LinearizeOptions {
    /// The defaults, as each field documents them.
    pub fn new() -> Self {
        Self {
            inputs: Vec::new(),
            outputs: Vec::new(),
            independent: Vec::new(),
            rank_tolerance: DEFAULT_LINEARIZE_RANK_TOLERANCE,
            consistency_tolerance: DEFAULT_LINEARIZE_CONSISTENCY,
        }
    }
    /// Sets [`inputs`](Self::inputs).
    #[must_use]
    pub fn with_inputs(mut self, names: &[&'static str]) -> Self {
        self.inputs = names.to_vec();
        self
    }
    /// Sets [`outputs`](Self::outputs).
    #[must_use]
    pub fn with_outputs(mut self, outputs: Vec<Output>) -> Self {
        self.outputs = outputs;
        self
    }
    /// Adds one output to [`outputs`](Self::outputs).
    #[must_use]
    pub fn with_output(mut self, output: Output) -> Self {
        self.outputs.push(output);
        self
    }
    /// Sets [`independent`](Self::independent).
    #[must_use]
    pub fn with_independent(mut self, names: &[&'static str]) -> Self {
        self.independent = names.to_vec();
        self
    }
    /// Sets [`rank_tolerance`](Self::rank_tolerance).
    #[must_use]
    pub fn with_rank_tolerance(mut self, rank_tolerance: f64) -> Self {
        self.rank_tolerance = rank_tolerance;
        self
    }
    /// Sets [`consistency_tolerance`](Self::consistency_tolerance).
    #[must_use]
    pub fn with_consistency_tolerance(mut self, consistency_tolerance: f64) -> Self {
        self.consistency_tolerance = consistency_tolerance;
        self
    }
}

/// Why a linearization failed.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum LinearizeError {
    /// The state is not on the position manifold: Φ's `row` is `value` (m or rad).
    NotAssembled {
        /// The constraint row, from [`Mechanism::CONSTRAINT_NAMES`].
        row: &'static str,
        /// Its value.
        value: f64,
    },
    /// The velocities violate D v = ν at `row` by `value` (m/s or rad/s).
    InconsistentVelocity {
        /// The constraint row.
        row: &'static str,
        /// D v − ν there.
        value: f64,
    },
    /// A name the mechanism does not have.
    UnknownName {
        /// What it was meant to be: `"input"`, `"velocity"`, `"constraint row"`.
        what: &'static str,
        /// The name given.
        name: String,
        /// The names it can be.
        choices: Vec<&'static str>,
    },
    /// The independent velocities named are not as many as the degrees of freedom, or the
    /// others cannot follow from them (the constraints do not fix them).
    BadIndependent {
        /// What is wrong, in words.
        reason: String,
    },
    /// An [`Output::rate`] takes a state of other sizes than the mechanism's: its closure was
    /// written for another mechanism.
    RateSizes {
        /// The output's name.
        name: String,
        /// The (NQ, NV) it takes.
        takes: (usize, usize),
        /// The mechanism's (NQ, NV).
        mechanism: (usize, usize),
    },
    /// The forward dynamics failed at the state (or at a perturbed one).
    Dynamics(DynamicsError),
    /// The saddle-point matrix [[M, −Dᵀ], [D, 0]] is singular at the state (a mass or inertia
    /// of zero on a free direction).
    Singular,
}

impl fmt::Display for LinearizeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LinearizeError::NotAssembled { row, value } => {
                write!(f, "the state is not assembled: constraint row `{row}` is {value:e} (solve the positions first)")
            }
            LinearizeError::InconsistentVelocity { row, value } => {
                write!(f, "the velocities violate constraint row `{row}` by {value:e} (solve the velocities first)")
            }
            LinearizeError::UnknownName { what, name, choices } => {
                write!(
                    f,
                    "unknown {what} `{name}`; the mechanism has: {}",
                    if choices.is_empty() { "none".to_string() } else { choices.join(", ") }
                )
            }
            LinearizeError::BadIndependent { reason } => write!(f, "independent velocities: {reason}"),
            LinearizeError::RateSizes { name, takes, mechanism } => write!(
                f,
                "output `{name}` is a rate of a state with {} coordinates and {} velocities, but the mechanism has {} and {}",
                takes.0, takes.1, mechanism.0, mechanism.1
            ),
            LinearizeError::Dynamics(e) => write!(f, "forward dynamics at the state: {e}"),
            LinearizeError::Singular => write!(f, "the saddle-point matrix [[M, -D^T], [D, 0]] is singular at the state"),
        }
    }
}

impl core::error::Error for LinearizeError {}

impl From<DynamicsError> for LinearizeError {
    fn from(e: DynamicsError) -> Self {
        LinearizeError::Dynamics(e)
    }
}

/// A linear model ẋ = A x + B u, y = C x + D u about a state, with its second-order form
/// M_r ÿ + D_r ẏ + K_r y = B_r u (module docs).
#[derive(Clone, Debug)]
pub struct Linearization {
    /// The instant (s).
    pub t: f64,
    /// The coordinates linearized about (m, rad; spatial: m and Euler parameters).
    pub q: Vec<f64>,
    /// The velocities linearized about (m/s, rad/s).
    pub v: Vec<f64>,
    /// State matrix A (2f × 2f): x = (positions y, velocities w).
    pub a: DMatrix<f64>,
    /// Input matrix B (2f × inputs).
    pub b: DMatrix<f64>,
    /// Output matrix C (outputs × 2f).
    pub c: DMatrix<f64>,
    /// Feedthrough D (outputs × inputs).
    pub d: DMatrix<f64>,
    /// Reduced mass matrix M_r = Zᵀ M Z (f × f; kg, kg·m² and their products).
    pub mass: DMatrix<f64>,
    /// Reduced damping D_r (f × f).
    pub damping: DMatrix<f64>,
    /// Reduced stiffness K_r (f × f).
    pub stiffness: DMatrix<f64>,
    /// Reduced input matrix B_r (f × inputs): generalized force per unit input.
    pub input_forces: DMatrix<f64>,
    /// The null-space basis Z (NV × f): the velocity-space displacement of each independent
    /// coordinate's unit motion.
    pub basis: DMatrix<f64>,
    /// The independent velocities (indices into [`Mechanism::VELOCITY_NAMES`]).
    pub independent: Vec<usize>,
    /// Names of the states: the independent displacements (`"pole.phi"`), then their rates
    /// (`"pole.phi_dot"`).
    pub state_names: Vec<String>,
    /// Names of the inputs.
    pub input_names: Vec<String>,
    /// Names of the outputs.
    pub output_names: Vec<String>,
    /// The mechanism's velocity names (what mode shapes are indexed by).
    pub velocity_names: &'static [&'static str],
    /// The diagonal of M (kg, kg·m²): what a mode's dominant velocity is weighed by.
    mass_diagonal: Vec<f64>,
}

/// One mode of a [`Linearization`]: an eigenvalue of A (one of a conjugate pair) with its shape.
#[derive(Clone, Debug, PartialEq)]
pub struct Mode {
    /// The eigenvalue s (1/s): the mode goes as e^{st}. Of a pair, the one with Im s > 0.
    pub eigenvalue: Complex<f64>,
    /// Natural frequency |s|/2π (Hz).
    pub natural_frequency: f64,
    /// Damped frequency |Im s|/2π (Hz): 0 for a real eigenvalue.
    pub damped_frequency: f64,
    /// Damping ratio −Re s/|s|: 0 undamped, 1 critically damped, negative for a growing
    /// oscillation; a real eigenvalue has ±1 (decay or growth).
    pub damping_ratio: f64,
    /// The shape: the displacement of every velocity direction (in the order of
    /// [`Mechanism::VELOCITY_NAMES`]; m and rad), scaled so that the dominant entry is 1.
    pub shape: Vec<Complex<f64>>,
    /// The velocity that carries the largest share of the mode's kinetic energy (the largest
    /// |shapeᵢ| √Mᵢᵢ): units do not decide it.
    pub dominant: &'static str,
}

/// Stability of the linear model's motion about its state.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum LinearStability {
    /// No degree of freedom (DOF = 0): the joints and drivers fix the motion, and no
    /// disturbance can move it (a scene without its drivers, `scene Free without motor;`, has
    /// the motion to linearize).
    Determined,
    /// Every eigenvalue has Re s < 0: disturbances decay.
    Asymptotic {
        /// The slowest decay rate, −max Re s (1/s).
        decay: f64,
    },
    /// No eigenvalue grows, some have Re s = 0 to rounding (undamped oscillation, a free
    /// rotation): disturbances stay bounded or drift.
    Marginal,
    /// Some eigenvalue has Re s > 0.
    Unstable {
        /// The fastest growth rate, max Re s (1/s).
        growth: f64,
        /// The velocity that dominates the fastest-growing mode.
        direction: &'static str,
    },
}

/// Dense copy of a fixed-size matrix.
fn dense<const R: usize, const C: usize>(a: &[[f64; C]; R]) -> DMatrix<f64> {
    DMatrix::from_fn(R, C, |r, c| a[r][c])
}

/// A zeroed R × C array on the heap (no O(N²) array on the stack: a 64-link chain's NV × NV is
/// 300 kB).
fn boxed<const R: usize, const C: usize>() -> Box<[[f64; C]; R]> {
    vec![[0.0; C]; R].into_boxed_slice().try_into().unwrap_or_else(|_| unreachable!("R rows"))
}

/// The arrays forward dynamics works in, on the heap (a [`DenseScratch`]): a linearization
/// takes no work space, and without one a large mechanism's forward dynamics keeps its arrays
/// on the stack, where they grow with it.
struct HeapArrays<const NV: usize, const NC: usize> {
    d: Box<[[f64; NV]; NC]>,
    y: Box<[[f64; NV]; NC]>,
    s: Box<[[f64; NC]; NC]>,
    l: Box<[[f64; NV]; NV]>,
    vectors: Vec<f64>,
}

impl<const NV: usize, const NC: usize> HeapArrays<NV, NC> {
    fn new() -> Self {
        let vectors = vec![0.0; VECTOR_ROWS * (NV + NC)];
        Self { d: boxed(), y: boxed(), s: boxed(), l: boxed(), vectors }
    }

    fn scratch(&mut self) -> DenseScratch<'_, f64, NV, NC> {
        DenseScratch { d: &mut self.d, y: &mut self.y, s: &mut self.s, l: &mut self.l, vectors: Vectors::new(&mut self.vectors) }
    }
}

fn find(what: &'static str, name: &str, choices: &'static [&'static str]) -> Result<usize, LinearizeError> {
    choices.iter().position(|&c| c == name).ok_or_else(|| LinearizeError::UnknownName {
        what,
        name: name.to_string(),
        choices: choices.to_vec(),
    })
}

#[allow(clippy::neg_cmp_op_on_partial_ord)]
fn check_state<M, const NQ: usize, const NV: usize, const NC: usize>(
    m: &M,
    q: &[f64; NQ],
    v: &[f64; NV],
    t: f64,
    tolerance: f64,
) -> Result<DMatrix<f64>, LinearizeError>
where
    M: ForwardDynamics<f64, NQ, NV, NC>,
{
    let (mut phi, mut nu) = ([0.0; NC], [0.0; NC]);
    let mut d = boxed::<NC, NV>();
    m.constraints(q, t, &mut phi);
    m.jacobian(q, t, &mut d);
    m.velocity_rhs(q, t, &mut nu);
    if let Some((row, &value)) = phi.iter().enumerate().find(|(_, p)| !(p.abs() <= tolerance)) {
        return Err(LinearizeError::NotAssembled { row: M::CONSTRAINT_NAMES[row], value });
    }
    let d = dense(&d);
    let violation = &d * DVector::from_column_slice(v) - DVector::from_column_slice(&nu);
    if let Some((row, &value)) =
        violation.iter().enumerate().find(|(_, e)| !(e.abs() <= tolerance * (1.0 + v.iter().fold(0.0f64, |a, b| a.max(b.abs())))))
    {
        return Err(LinearizeError::InconsistentVelocity { row: M::CONSTRAINT_NAMES[row], value });
    }
    Ok(d)
}

/// What both linearizations start from, at a state checked to be on the manifold: the inputs
/// the options name, and the chart.
fn prepare<M, const NQ: usize, const NV: usize, const NC: usize>(
    m: &M,
    q: &[f64; NQ],
    v: &[f64; NV],
    t: f64,
    options: &LinearizeOptions,
) -> Result<(Vec<Input>, Chart), LinearizeError>
where
    M: Linearize<f64, NQ, NV, NC> + ForwardDynamics<f64, NQ, NV, NC>,
{
    let d = check_state(m, q, v, t, options.consistency_tolerance)?;
    for output in &options.outputs {
        if let Output::Rate { name, sizes, .. } = output {
            if *sizes != (NQ, NV) {
                return Err(LinearizeError::RateSizes { name: name.clone(), takes: *sizes, mechanism: (NQ, NV) });
            }
        }
    }
    let inputs = input_kinds::<M, NQ, NV, NC>(options)?;
    let chart = Chart::choose::<M>(&d, options)?;
    Ok((inputs, chart))
}

/// Linearization of a mechanism's motion on its constraint manifold about a state, exact from the
/// generated derivatives (module docs) or by central differences to check them. Made by
/// [`new`](Self::new) or [`Default`], holding only its options: one linearizer serves any number
/// of mechanisms and states.
///
/// ```ignore
/// let lin = Linearizer::new(LinearizeOptions::default().with_inputs(&["motor"])).linearize(&m, &q, &v, 0.0)?;
/// let modes = lin.modes()?;
/// ```
#[derive(Debug, Default)]
pub struct Linearizer {
    /// The inputs, outputs, chart and tolerances.
    pub options: LinearizeOptions,
}

impl Linearizer {
    /// A linearizer with the given options.
    pub fn new(options: LinearizeOptions) -> Self {
        Linearizer { options }
    }

    /// The exact linearization of `m`'s motion about (q, v) at t (module docs). The inputs are
    /// at the values `m` holds.
    ///
    /// # Errors
    /// A [`LinearizeError`] naming the constraint row, velocity, input or output at fault.
    pub fn linearize<M, const NQ: usize, const NV: usize, const NC: usize>(
        &self,
        m: &M,
        q: &[f64; NQ],
        v: &[f64; NV],
        t: f64,
    ) -> Result<Linearization, LinearizeError>
    where
        M: Linearize<f64, NQ, NV, NC> + ForwardDynamics<f64, NQ, NV, NC>,
    {
        m.check_inertia().map_err(LinearizeError::Dynamics)?;
        exact(m, q, v, t, &self.options)
    }

    /// The same model as [`linearize`](Self::linearize), by central differences of the forward
    /// dynamics in the same chart (module docs): 2 (2f + inputs) forward-dynamics solves and as
    /// many projections onto the manifold. A check of the exact one, not a substitute.
    ///
    /// # Errors
    /// As [`linearize`](Self::linearize).
    pub fn finite_differences<M, const NQ: usize, const NV: usize, const NC: usize>(
        &self,
        m: &M,
        q: &[f64; NQ],
        v: &[f64; NV],
        t: f64,
    ) -> Result<Linearization, LinearizeError>
    where
        M: Linearize<f64, NQ, NV, NC> + ForwardDynamics<f64, NQ, NV, NC> + Clone,
    {
        m.check_inertia().map_err(LinearizeError::Dynamics)?;
        finite_differences(m, q, v, t, &self.options)
    }
}
