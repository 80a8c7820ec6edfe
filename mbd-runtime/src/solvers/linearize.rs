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
    /// replaced by δ.
    Rate {
        /// The name of the output's row.
        name: String,
        /// The quantity's rate at (q, v), linear in v.
        rate: Rate,
    },
}

/// The rate function of an [`Output::Rate`]: (q, v) ↦ the quantity's rate, linear in v.
pub type Rate = Box<dyn Fn(&[f64], &[f64]) -> f64>;

impl Output {
    /// A quantity given by its rate ([`Output::Rate`]).
    pub fn rate(name: impl Into<String>, rate: impl Fn(&[f64], &[f64]) -> f64 + 'static) -> Self {
        Output::Rate { name: name.into(), rate: Box::new(rate) }
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
pub enum LinearStability {
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

fn find(what: &'static str, name: &str, choices: &'static [&'static str]) -> Result<usize, LinearizeError> {
    choices.iter().position(|&c| c == name).ok_or_else(|| LinearizeError::UnknownName {
        what,
        name: name.to_string(),
        choices: choices.to_vec(),
    })
}

/// The chart at a state: which velocities are independent, and the basis that goes with them.
struct Chart {
    /// Independent velocities.
    independent: Vec<usize>,
    /// Dependent velocities (as many as `rows`).
    dependent: Vec<usize>,
    /// The independent constraint rows.
    rows: Vec<usize>,
    /// Z (NV × f).
    z: DMatrix<f64>,
    /// R (NV × rows): R_D = D_D⁻¹ over the independent rows, R_I = 0.
    r: DMatrix<f64>,
}

impl Chart {
    /// Full pivoting on D with each row scaled to its largest entry; the columns of `forced`
    /// never pivot (they stay independent).
    fn new(d: &DMatrix<f64>, forced: &[usize], tolerance: f64) -> Result<Chart, LinearizeError> {
        let (nc, nv) = d.shape();
        let mut work = d.clone();
        for mut row in work.row_iter_mut() {
            let scale = row.amax();
            if scale > 0.0 {
                row /= scale;
            }
        }
        let (mut rows, mut dependent) = (Vec::new(), Vec::new());
        let (mut row_used, mut column_used) = (vec![false; nc], vec![false; nv]);
        for &c in forced {
            column_used[c] = true;
        }
        loop {
            let mut best = (tolerance, None);
            for r in (0..nc).filter(|&r| !row_used[r]) {
                for c in (0..nv).filter(|&c| !column_used[c]) {
                    if work[(r, c)].abs() > best.0 {
                        best = (work[(r, c)].abs(), Some((r, c)));
                    }
                }
            }
            let Some((pr, pc)) = best.1 else { break };
            row_used[pr] = true;
            column_used[pc] = true;
            for r in (0..nc).filter(|&r| !row_used[r]) {
                let factor = work[(r, pc)] / work[(pr, pc)];
                if factor != 0.0 {
                    for c in 0..nv {
                        work[(r, c)] -= factor * work[(pr, c)];
                    }
                }
            }
            rows.push(pr);
            dependent.push(pc);
        }
        let independent: Vec<usize> = (0..nv).filter(|c| !dependent.contains(c)).collect();
        let dd = DMatrix::from_fn(rows.len(), rows.len(), |i, j| d[(rows[i], dependent[j])]);
        let di = DMatrix::from_fn(rows.len(), independent.len(), |i, j| d[(rows[i], independent[j])]);
        let lu = dd.lu();
        let inverse = lu.try_inverse().ok_or(LinearizeError::Singular)?;
        let zd = -(&inverse * di);
        let mut z = DMatrix::zeros(nv, independent.len());
        let mut r = DMatrix::zeros(nv, rows.len());
        for (k, &c) in independent.iter().enumerate() {
            z[(c, k)] = 1.0;
        }
        for (i, &c) in dependent.iter().enumerate() {
            z.row_mut(c).copy_from(&zd.row(i));
            r.row_mut(c).copy_from(&inverse.row(i));
        }
        Ok(Chart { independent, dependent, rows, z, r })
    }

    /// The chart at q₀ for the options: named independent velocities, or pivoting.
    fn choose<M: Mechanism>(d: &DMatrix<f64>, options: &LinearizeOptions) -> Result<Chart, LinearizeError> {
        let free = Chart::new(d, &[], options.rank_tolerance)?;
        if options.independent.is_empty() {
            return Ok(free);
        }
        let forced = options.independent.iter().map(|n| find("velocity", n, M::VELOCITY_NAMES)).collect::<Result<Vec<_>, _>>()?;
        if forced.len() != free.independent.len() {
            return Err(LinearizeError::BadIndependent {
                reason: format!(
                    "{} named, but the mechanism has {} degrees of freedom at this state (e.g. {})",
                    forced.len(),
                    free.independent.len(),
                    free.independent.iter().map(|&i| M::VELOCITY_NAMES[i]).collect::<Vec<_>>().join(", ")
                ),
            });
        }
        let chart = Chart::new(d, &forced, options.rank_tolerance)?;
        if chart.rows.len() < free.rows.len() {
            let missing = free.rows.iter().find(|r| !chart.rows.contains(r)).copied().unwrap_or(0);
            return Err(LinearizeError::BadIndependent {
                reason: format!(
                    "{} cannot all be independent: with them given, the other velocities cannot satisfy the constraint row `{}`",
                    options.independent.join(", "),
                    M::CONSTRAINT_NAMES.get(missing).copied().unwrap_or("?")
                ),
            });
        }
        Ok(chart)
    }
}

/// Checks that (q, v) is on the manifold; returns D.
// `!(x <= tolerance)` on purpose: a NaN fails too.
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

/// What an input is.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Input {
    /// A parameter, by index into [`Linearize::INPUTS`].
    Load(usize),
    /// A driver's acceleration, by its row of Φ.
    Driver(usize),
}

/// The inputs the options name.
fn input_kinds<M: Linearize<f64, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize>(
    options: &LinearizeOptions,
) -> Result<Vec<Input>, LinearizeError> {
    let is_driver = |j: &&crate::model::mechanism::JointInfo| j.kind.starts_with("drive") && j.rows == 1;
    options
        .inputs
        .iter()
        .map(|&name| {
            if let Some(k) = M::INPUTS.iter().position(|&n| n == name) {
                return Ok(Input::Load(k));
            }
            if let Some(j) = M::JOINTS.iter().filter(is_driver).find(|j| j.name == name) {
                return Ok(Input::Driver(j.first_row as usize));
            }
            let choices = M::INPUTS.iter().copied().chain(M::JOINTS.iter().filter(is_driver).map(|j| j.name)).collect();
            let what = if M::PARAM_NAMES.contains(&name) {
                "input (a parameter that also sets the geometry, the masses or friction)"
            } else {
                "input"
            };
            Err(LinearizeError::UnknownName { what, name: name.to_string(), choices })
        })
        .collect()
}

/// Ω = ∂δ̇/∂δ: −½[ω₀′×] on the rotation of each body whose orientation is a quaternion, 0 on
/// everything else (module docs; 0 in the plane).
fn omega<M: Mechanism, const NV: usize>(v: &[f64; NV]) -> DMatrix<f64> {
    let mut o = DMatrix::zeros(NV, NV);
    for b in angular_triples::<M>().filter(|&b| b + 3 <= NV) {
        let w = [v[b], v[b + 1], v[b + 2]];
        // −½ [w×]: [w×] = [[0, −w3, w2], [w3, 0, −w1], [−w2, w1, 0]]
        let cross = [[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]];
        for r in 0..3 {
            for c in 0..3 {
                o[(b + r, b + c)] = -0.5 * cross[r][c];
            }
        }
    }
    o
}

/// The first index into v of each body-frame angular velocity ω′ (its x′ component; y′ and z′
/// follow).
fn angular_triples<M: Mechanism>() -> impl Iterator<Item = usize> {
    M::VELOCITIES.iter().enumerate().filter_map(|(i, v)| matches!(v.kind, VelocityKind::Angular { axis: 0, .. }).then_some(i))
}

/// Names of the states: displacements (`"crank.phi"`, `"top.x"`, `"top.rx"`), then rates
/// (`"crank.phi_dot"` for a velocity named as its coordinate, else the velocity's own name,
/// `"top.wx"`).
fn state_names<M: Mechanism>(independent: &[usize]) -> Vec<String> {
    let position = |i: usize| M::VELOCITIES[i].displacement.to_string();
    let rate = |i: usize| {
        let v = &M::VELOCITIES[i];
        if v.is_named_rate::<M>() {
            format!("{}_dot", v.name)
        } else {
            v.name.to_string()
        }
    };
    independent.iter().map(|&i| position(i)).chain(independent.iter().map(|&i| rate(i))).collect()
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
        finite_differences(m, q, v, t, &self.options)
    }
}

/// [`Linearizer::linearize`].
fn exact<M, const NQ: usize, const NV: usize, const NC: usize>(
    m: &M,
    q: &[f64; NQ],
    v: &[f64; NV],
    t: f64,
    options: &LinearizeOptions,
) -> Result<Linearization, LinearizeError>
where
    M: Linearize<f64, NQ, NV, NC> + ForwardDynamics<f64, NQ, NV, NC>,
{
    let (inputs, chart) = prepare(m, q, v, t, options)?;
    let (mut vd, mut lambda) = ([0.0; NV], [0.0; NC]);
    m.accelerations(q, v, t, &DynamicsOptions::without_stabilization(), &mut vd, &mut lambda)?;

    // The derivatives, dense.
    let (mut a1, mut a2) = (boxed::<NV, NV>(), boxed::<NV, NV>());
    m.add_mass_matrix(q, 1.0, &mut a1);
    let mass = dense(&a1);
    m.forces_q(q, v, t, &mut a1);
    m.forces_v(q, v, t, &mut a2);
    m.friction_derivatives(q, v, t, &lambda, &mut a1, &mut a2);
    let (mut h, h_v) = (dense(&a1), dense(&a2));
    m.constraint_force_q(q, t, &lambda, &mut a1);
    h += dense(&a1);
    let (mut g1, mut g2) = (boxed::<NC, NV>(), boxed::<NC, NV>());
    let mut gamma_v_at = |a: &[f64; NV]| {
        m.gamma_derivatives(q, a, t, &mut g1, &mut g2);
        (dense(&g1), dense(&g2))
    };
    // ½ Γ_v(q₀, 0) = ν_q B, and Q(a) = ∂(D a)/∂q B for a = v₀ and v̇₀.
    let (_, gamma_v0) = gamma_v_at(&[0.0; NV]);
    let (gamma_q, gamma_v) = gamma_v_at(v);
    let (q_v, q_a) = if velocities_are_rates::<M>() {
        // Where q̇ = v (in the plane) Q(a)b = Φ_qq(a, b) is symmetric in a and b, so
        // Γ_v(a) = −2 Q(a) − 2 Φ_tq and Q(a) = −½ (Γ_v(a) − Γ_v(0)): two evaluations of γ's
        // derivatives.
        let (_, gamma_va) = gamma_v_at(&vd);
        ((&gamma_v - &gamma_v0) * -0.5, (gamma_va - &gamma_v0) * -0.5)
    } else {
        // In space B(q) makes Q(a)b − Q(b)a = Φ_q [Bb, Ba] ≠ 0: row r is aᵀ K(e_r).
        let (mut q_v, mut q_a) = (DMatrix::zeros(NC, NV), DMatrix::zeros(NC, NV));
        let (v0, a0) = (DVector::from_column_slice(v), DVector::from_column_slice(&vd));
        for &r in &chart.rows {
            let mut unit = [0.0; NC];
            unit[r] = 1.0;
            m.constraint_force_q(q, t, &unit, &mut a1);
            let k = dense(&a1);
            q_v.row_mut(r).copy_from(&(v0.transpose() * &k));
            q_a.row_mut(r).copy_from(&(a0.transpose() * &k));
        }
        (q_v, q_a)
    };
    let g = q_v - gamma_v0 * 0.5;
    let mut h_u = DMatrix::zeros(NV, inputs.len());
    for (j, &input) in inputs.iter().enumerate() {
        if let Input::Load(k) = input {
            let mut column = [0.0; NV];
            m.forces_input(k, q, v, t, &mut column);
            h_u.column_mut(j).copy_from_slice(&column);
        }
    }

    // The saddle-point system [[M, −Dᵀ], [D, 0]] [δv̇; δλ] = [top; bottom] over the independent
    // rows, one column per state and input, solved in the null space: δv̇ = Z s + R bottom with
    // s = M_r⁻¹ Zᵀ (top − M R bottom), and E δv̇ = s is A's row; δλ = Rᵀ (M δv̇ − top).
    let (f, nr, ni) = (chart.independent.len(), chart.rows.len(), inputs.len());
    let pick = |a: &DMatrix<f64>| DMatrix::from_fn(nr, a.ncols(), |i, c| a[(chart.rows[i], c)]);
    let z = &chart.z;
    let correction = &chart.r * pick(&g) * z; // δv = Z w − R G Z y
    let mut top = DMatrix::zeros(NV, 2 * f + ni);
    let mut bottom = DMatrix::zeros(nr, 2 * f + ni);
    top.view_mut((0, 0), (NV, f)).copy_from(&(&h * z - &h_v * &correction));
    bottom.view_mut((0, 0), (nr, f)).copy_from(&(pick(&(&gamma_q - &q_a)) * z - pick(&gamma_v) * &correction));
    top.view_mut((0, f), (NV, f)).copy_from(&(&h_v * z));
    bottom.view_mut((0, f), (nr, f)).copy_from(&(pick(&gamma_v) * z));
    top.view_mut((0, 2 * f), (NV, ni)).copy_from(&h_u);
    for (j, &input) in inputs.iter().enumerate() {
        // A driver's row reads D v̇ = γ_r + u: its acceleration input.
        if let Some(i) = chart.rows.iter().position(|&r| Input::Driver(r) == input) {
            bottom[(i, 2 * f + j)] = 1.0;
        }
    }
    let particular = &chart.r * &bottom;
    let reduced_mass = z.transpose() * &mass * z;
    let s = Cholesky::new(reduced_mass).ok_or(LinearizeError::Singular)?.solve(&(z.transpose() * (&top - &mass * &particular)));
    let mut a = DMatrix::zeros(2 * f, 2 * f);
    if !velocities_are_rates::<M>() {
        let omega_z = omega::<M, NV>(v) * z;
        a.view_mut((0, 0), (f, f)).copy_from(&DMatrix::from_fn(f, f, |i, k| omega_z[(chart.independent[i], k)]));
    }
    a.view_mut((0, f), (f, f)).fill_with_identity();
    a.view_mut((f, 0), (f, 2 * f)).copy_from(&s.columns(0, 2 * f));
    let mut b = DMatrix::zeros(2 * f, ni);
    b.view_mut((f, 0), (f, ni)).copy_from(&s.columns(2 * f, ni));
    let multipliers = if options.outputs.iter().any(|o| matches!(o, Output::Multiplier(_))) {
        let accelerations = z * &s + particular;
        chart.r.transpose() * (&mass * accelerations - &top)
    } else {
        DMatrix::zeros(nr, 2 * f + ni)
    };

    // Outputs.
    let no = options.outputs.len();
    let (mut c, mut dd) = (DMatrix::zeros(no, 2 * f), DMatrix::zeros(no, ni));
    for (o, output) in options.outputs.iter().enumerate() {
        match output {
            Output::Displacement(name) => {
                let i = find("displacement (a velocity direction)", name, M::VELOCITY_NAMES)?;
                c.view_mut((o, 0), (1, f)).copy_from(&z.row(i));
            }
            Output::Velocity(name) => {
                let i = find("velocity", name, M::VELOCITY_NAMES)?;
                c.view_mut((o, 0), (1, f)).copy_from(&(-correction.row(i)));
                c.view_mut((o, f), (1, f)).copy_from(&z.row(i));
            }
            Output::Multiplier(name) => {
                let row = find("constraint row", name, M::CONSTRAINT_NAMES)?;
                if let Some(i) = chart.rows.iter().position(|&r| r == row) {
                    c.row_mut(o).copy_from(&multipliers.view((i, 0), (1, 2 * f)));
                    dd.row_mut(o).copy_from(&multipliers.view((i, 2 * f), (1, ni)));
                }
            }
            Output::Rate { rate, .. } => {
                for k in 0..f {
                    c[(o, k)] = rate(q, z.column(k).as_slice());
                }
            }
        }
    }
    Ok(assemble::<M>((t, q, v), a, b, c, dd, mass, chart, options))
}

/// The model's matrices with the second-order form and the names.
#[allow(clippy::too_many_arguments)]
fn assemble<M: Mechanism>(
    (t, q, v): (f64, &[f64], &[f64]),
    a: DMatrix<f64>,
    b: DMatrix<f64>,
    c: DMatrix<f64>,
    d: DMatrix<f64>,
    mass: DMatrix<f64>,
    chart: Chart,
    options: &LinearizeOptions,
) -> Linearization {
    let f = chart.independent.len();
    let mass_diagonal = mass.diagonal().iter().copied().collect();
    let reduced_mass = chart.z.transpose() * mass * &chart.z;
    let stiffness = -(&reduced_mass * a.view((f, 0), (f, f)));
    let damping = -(&reduced_mass * a.view((f, f), (f, f)));
    let input_forces = &reduced_mass * b.rows(f, f);
    let input_names = options.inputs.iter().map(|n| n.to_string()).collect();
    Linearization {
        t,
        q: q.to_vec(),
        v: v.to_vec(),
        state_names: state_names::<M>(&chart.independent),
        a,
        b,
        c,
        d,
        mass: reduced_mass,
        damping,
        stiffness,
        input_forces,
        basis: chart.z,
        independent: chart.independent,
        input_names,
        output_names: options.outputs.iter().map(Output::name).collect(),
        velocity_names: M::VELOCITY_NAMES,
        mass_diagonal,
    }
}

/// [`Linearizer::finite_differences`].
fn finite_differences<M, const NQ: usize, const NV: usize, const NC: usize>(
    m: &M,
    q: &[f64; NQ],
    v: &[f64; NV],
    t: f64,
    options: &LinearizeOptions,
) -> Result<Linearization, LinearizeError>
where
    M: Linearize<f64, NQ, NV, NC> + ForwardDynamics<f64, NQ, NV, NC> + Clone,
{
    let (inputs, chart) = prepare(m, q, v, t, options)?;
    let f = chart.independent.len();
    let ni = inputs.len();
    let no = options.outputs.len();
    // The state (y, w) at (q, v): y = 0, w = E v.
    let x0: Vec<f64> = (0..f).map(|_| 0.0).chain(chart.independent.iter().map(|&i| v[i])).collect();
    let u0: Vec<f64> = inputs
        .iter()
        .map(|&input| match input {
            Input::Load(k) => m.input(k),
            Input::Driver(_) => 0.0,
        })
        .collect();
    // ẋ and the outputs at (x, u).
    let evaluate = |x: &[f64], u: &[f64]| -> Result<(Vec<f64>, Vec<f64>), LinearizeError> {
        let mut model = m.clone();
        let mut offsets = [0.0; NC];
        for (&input, &value) in inputs.iter().zip(u) {
            match input {
                Input::Load(k) => model.set_input(k, value),
                Input::Driver(row) => offsets[row] = value,
            }
        }
        let (qx, delta) = chart.position::<M, NQ, NV, NC>(m, q, t, &x[..f])?;
        let vx = chart.velocity::<M, NQ, NV, NC>(m, &qx, t, &x[f..])?;
        let (mut vd, mut lambda) = ([0.0; NV], [0.0; NC]);
        model.accelerations(&qx, &vx, t, &DynamicsOptions::without_stabilization(), &mut vd, &mut lambda)?;
        if offsets.iter().any(|&o| o != 0.0) {
            // A driver's acceleration offset: the saddle-point system at this state with γ_r + u
            // (and the joints' friction at the loads just found), solved densely.
            driven_accelerations(&model, &chart, &qx, &vx, t, &offsets, &mut vd, &mut lambda)?;
        }
        let rates = displacement_rates::<M, NQ, NV>(q, &qx, &vx);
        let xdot: Vec<f64> = chart.independent.iter().map(|&i| rates[i]).chain(chart.independent.iter().map(|&i| vd[i])).collect();
        let mut y = Vec::with_capacity(no);
        for output in &options.outputs {
            y.push(match output {
                Output::Displacement(name) => delta[find("displacement (a velocity direction)", name, M::VELOCITY_NAMES)?],
                Output::Velocity(name) => vx[find("velocity", name, M::VELOCITY_NAMES)?],
                Output::Multiplier(name) => lambda[find("constraint row", name, M::CONSTRAINT_NAMES)?],
                Output::Rate { rate, .. } => rate(q, &delta),
            });
        }
        Ok((xdot, y))
    };
    // Central differences along each state, then each input: (ẋ, y) columns.
    let mut columns = Vec::with_capacity(2 * f + ni);
    for k in 0..2 * f + ni {
        let (which, i) = if k < 2 * f { (0, k) } else { (1, k - 2 * f) };
        let mut args = [x0.clone(), u0.clone()];
        let at = args[which][i];
        let h = f64::EPSILON.cbrt() * at.abs().max(1.0);
        args[which][i] = at + h;
        let plus = evaluate(&args[0], &args[1])?;
        args[which][i] = at - h;
        let minus = evaluate(&args[0], &args[1])?;
        let difference = |p: &[f64], m: &[f64]| p.iter().zip(m).map(|(a, b)| (a - b) / (2.0 * h)).collect::<Vec<f64>>();
        columns.push((difference(&plus.0, &minus.0), difference(&plus.1, &minus.1)));
    }
    let a = DMatrix::from_fn(2 * f, 2 * f, |i, k| columns[k].0[i]);
    let b = DMatrix::from_fn(2 * f, ni, |i, k| columns[2 * f + k].0[i]);
    let c = DMatrix::from_fn(no, 2 * f, |i, k| columns[k].1[i]);
    let dd = DMatrix::from_fn(no, ni, |i, k| columns[2 * f + k].1[i]);
    let mut mass = boxed::<NV, NV>();
    m.add_mass_matrix(q, 1.0, &mut mass);
    Ok(assemble::<M>((t, q, v), a, b, c, dd, dense(&mass), chart, options))
}

/// v̇ and λ from [[M, −Dᵀ], [D, 0]] [v̇; λ] = [h + h_f(λ); γ + offsets] over the chart's rows,
/// the friction h_f at the λ passed in.
#[allow(clippy::too_many_arguments)]
fn driven_accelerations<M, const NQ: usize, const NV: usize, const NC: usize>(
    m: &M,
    chart: &Chart,
    q: &[f64; NQ],
    v: &[f64; NV],
    t: f64,
    offsets: &[f64; NC],
    vd: &mut [f64; NV],
    lambda: &mut [f64; NC],
) -> Result<(), LinearizeError>
where
    M: ForwardDynamics<f64, NQ, NV, NC>,
{
    let (mut h, mut gamma) = ([0.0; NV], [0.0; NC]);
    m.forces(q, v, t, &mut h);
    m.friction_forces(q, v, t, lambda, &mut h);
    m.gamma(q, v, t, &mut gamma);
    let (mut mass, mut d) = (boxed::<NV, NV>(), boxed::<NC, NV>());
    m.add_mass_matrix(q, 1.0, &mut mass);
    m.jacobian(q, t, &mut d);
    let nr = chart.rows.len();
    let mut kkt = DMatrix::zeros(NV + nr, NV + nr);
    let mut rhs = DVector::zeros(NV + nr);
    for i in 0..NV {
        rhs[i] = h[i];
        for j in 0..NV {
            kkt[(i, j)] = mass[i][j];
        }
    }
    for (k, &r) in chart.rows.iter().enumerate() {
        rhs[NV + k] = gamma[r] + offsets[r];
        for j in 0..NV {
            kkt[(NV + k, j)] = d[r][j];
            kkt[(j, NV + k)] = -d[r][j];
        }
    }
    let x = kkt.lu().solve(&rhs).ok_or(LinearizeError::Singular)?;
    vd.copy_from_slice(x.rows(0, NV).as_slice());
    *lambda = [0.0; NC];
    for (k, &r) in chart.rows.iter().enumerate() {
        lambda[r] = x[NV + k];
    }
    Ok(())
}

impl Chart {
    /// q₀ ⊕ δ with δ_I = y and δ_D such that Φ = 0 (Newton, D_D at the current q); returns q
    /// and δ.
    fn position<M, const NQ: usize, const NV: usize, const NC: usize>(
        &self,
        m: &M,
        q0: &[f64; NQ],
        t: f64,
        y: &[f64],
    ) -> Result<([f64; NQ], [f64; NV]), LinearizeError>
    where
        M: ForwardDynamics<f64, NQ, NV, NC>,
    {
        let mut delta = [0.0; NV];
        for (&i, &value) in self.independent.iter().zip(y) {
            delta[i] = value;
        }
        let mut d = boxed::<NC, NV>();
        let mut phi = [0.0; NC];
        for _ in 0..50 {
            let mut q = *q0;
            m.integrate_positions(&mut q, &delta, 1.0);
            m.position_eval(&q, t, &mut phi, &mut d);
            let residual = self.rows.iter().fold(0.0f64, |a, &r| a.max(phi[r].abs()));
            if residual <= 1e-15 * (1.0 + q.iter().fold(0.0f64, |a, b| a.max(b.abs()))) {
                return Ok((q, delta));
            }
            let dd = DMatrix::from_fn(self.rows.len(), self.rows.len(), |i, j| d[self.rows[i]][self.dependent[j]]);
            let rhs = DVector::from_fn(self.rows.len(), |i, _| -phi[self.rows[i]]);
            let step = dd.lu().solve(&rhs).ok_or(LinearizeError::Singular)?;
            for (&c, &s) in self.dependent.iter().zip(step.iter()) {
                delta[c] += s;
            }
        }
        let worst = self.rows.iter().copied().max_by(|&a, &b| phi[a].abs().total_cmp(&phi[b].abs())).unwrap_or(0);
        Err(LinearizeError::NotAssembled { row: M::CONSTRAINT_NAMES[worst], value: phi[worst] })
    }

    /// v with v_I = w and D v = ν at q.
    fn velocity<M, const NQ: usize, const NV: usize, const NC: usize>(
        &self,
        m: &M,
        q: &[f64; NQ],
        t: f64,
        w: &[f64],
    ) -> Result<[f64; NV], LinearizeError>
    where
        M: ForwardDynamics<f64, NQ, NV, NC>,
    {
        let mut d = boxed::<NC, NV>();
        let mut nu = [0.0; NC];
        m.jacobian(q, t, &mut d);
        m.velocity_rhs(q, t, &mut nu);
        let mut v = [0.0; NV];
        for (&i, &value) in self.independent.iter().zip(w) {
            v[i] = value;
        }
        let dd = DMatrix::from_fn(self.rows.len(), self.rows.len(), |i, j| d[self.rows[i]][self.dependent[j]]);
        let rhs = DVector::from_fn(self.rows.len(), |i, _| {
            let r = self.rows[i];
            nu[r] - self.independent.iter().map(|&c| d[r][c] * v[c]).sum::<f64>()
        });
        let vd = dd.lu().solve(&rhs).ok_or(LinearizeError::Singular)?;
        for (&c, &value) in self.dependent.iter().zip(vd.iter()) {
            v[c] = value;
        }
        Ok(v)
    }
}

/// δ̇ at q = q₀ ⊕ δ moving with v: v for a rate; for each body-frame angular velocity ω′, the
/// rate of the chart's rotation vector θ = 2 p_v / p_s, p = e₀* ⊗ e, from ṗ = ½ p ⊗ (0, ω′), e the
/// body's quaternion.
fn displacement_rates<M: Mechanism, const NQ: usize, const NV: usize>(q0: &[f64; NQ], q: &[f64; NQ], v: &[f64; NV]) -> [f64; NV] {
    let mut rates = *v;
    for b in angular_triples::<M>().filter(|&b| b + 3 <= NV) {
        let VelocityKind::Angular { quaternion, .. } = M::VELOCITIES[b].kind else { continue };
        let c = quaternion as usize;
        if c + 4 > NQ {
            continue;
        }
        let (e0, e) = (&q0[c..c + 4], &q[c..c + 4]);
        // p = conj(e0) ⊗ e
        let p = quaternion_product([e0[0], -e0[1], -e0[2], -e0[3]], [e[0], e[1], e[2], e[3]]);
        let w = &v[b..b + 3];
        let pd = quaternion_product(p, [0.0, w[0], w[1], w[2]]).map(|x| 0.5 * x);
        for a in 0..3 {
            rates[b + a] = 2.0 * (pd[a + 1] * p[0] - p[a + 1] * pd[0]) / (p[0] * p[0]);
        }
    }
    rates
}

fn quaternion_product(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

/// Relative size below which a real part counts as 0 in [`Linearization::stability`] and an
/// imaginary part makes no oscillation in [`Linearization::modes`]: of the largest |s|.
const ZERO_EIGENVALUE: f64 = 1e-9;

impl Linearization {
    /// Degrees of freedom f of the model (A is 2f × 2f).
    pub fn dof(&self) -> usize {
        self.independent.len()
    }

    /// The eigenvalues of A.
    pub fn eigenvalues(&self) -> Vec<Complex<f64>> {
        if self.a.is_empty() {
            return Vec::new();
        }
        match nalgebra::Schur::try_new(self.a.clone(), f64::EPSILON, 10_000) {
            Some(schur) => schur.complex_eigenvalues().iter().copied().collect(),
            None => vec![Complex::new(f64::NAN, f64::NAN); self.a.nrows()],
        }
    }

    /// Whether the second-order form is undamped and symmetric (D_r = 0, K_r = K_rᵀ to
    /// rounding, no rotation term in A₁₁): then the modes are real.
    fn undamped(&self) -> bool {
        let f = self.dof();
        let scale = self.stiffness.amax().max(f64::MIN_POSITIVE);
        self.damping.amax() == 0.0
            && self.a.view((0, 0), (f, f)).amax() == 0.0
            && (&self.stiffness - self.stiffness.transpose()).amax() <= 1e-9 * scale
    }

    /// The modes, by natural frequency (module docs): one per oscillation (a conjugate pair of
    /// eigenvalues) and one per real eigenvalue.
    pub fn modes(&self) -> Vec<Mode> {
        if self.dof() == 0 {
            return Vec::new();
        }
        let mut modes = match self.undamped_modes() {
            Some(modes) => modes,
            None => {
                let eigenvalues = self.eigenvalues();
                let scale = eigenvalues.iter().fold(0.0f64, |a, s| a.max(s.modulus()));
                // one of each conjugate pair: Im s ≥ 0
                eigenvalues
                    .iter()
                    .filter(|s| s.re.is_finite() && s.im >= -ZERO_EIGENVALUE * scale)
                    .map(|&s| self.damped_mode(s, scale))
                    .collect()
            }
        };
        modes.sort_by(|a, b| a.natural_frequency.total_cmp(&b.natural_frequency));
        modes
    }

    /// Undamped modes from the symmetric problem K_r φ = ω² M_r φ, when the model is undamped
    /// (`None` otherwise): M_r = L Lᵀ, (L⁻¹ K_r L⁻ᵀ) x = ω² x, φ = L⁻ᵀ x.
    fn undamped_modes(&self) -> Option<Vec<Mode>> {
        let f = self.dof();
        if !self.undamped() {
            return None;
        }
        let li = Cholesky::new(self.mass.clone())?.l().try_inverse()?;
        let k = &li * &self.stiffness * li.transpose();
        let eigen = SymmetricEigen::new((&k + k.transpose()) * 0.5);
        let modes = eigen
            .eigenvalues
            .iter()
            .enumerate()
            .map(|(j, &w2)| {
                let phi = li.transpose() * eigen.eigenvectors.column(j);
                let shape: Vec<Complex<f64>> = (&self.basis * &phi).iter().map(|&x| Complex::new(x, 0.0)).collect();
                let s = if w2 >= 0.0 { Complex::new(0.0, w2.sqrt()) } else { Complex::new((-w2).sqrt(), 0.0) };
                self.mode(s, shape)
            })
            .collect::<Vec<_>>();
        debug_assert_eq!(modes.len(), f);
        Some(modes)
    }

    /// The mode of eigenvalue s of A (`scale` the largest |s|) by inverse iteration, s' a hair
    /// off s so that the matrix is regular: on the pencil s'² − s' A₂₂ − A₂₁ (f × f) for y when
    /// A₁₁ = 0 (ẏ = w), else on A − s' (2f × 2f).
    fn damped_mode(&self, s: Complex<f64>, scale: f64) -> Mode {
        let f = self.dof();
        let s = if s.im.abs() <= ZERO_EIGENVALUE * scale { Complex::new(s.re, 0.0) } else { s };
        let complex = |m: DMatrix<f64>| m.map(|x| Complex::new(x, 0.0));
        let second_order = self.a.view((0, 0), (f, f)).amax() == 0.0;
        let shift = s + Complex::new(1e-10 * scale.max(1e-300), 1e-10 * scale.max(1e-300));
        let n = if second_order { f } else { 2 * f };
        let mut shifted = if second_order {
            let (a21, a22) = (complex(self.a.view((f, 0), (f, f)).into_owned()), complex(self.a.view((f, f), (f, f)).into_owned()));
            -(a21 + a22 * shift)
        } else {
            -complex(self.a.clone())
        };
        let diagonal = if second_order { shift * shift } else { shift };
        for i in 0..n {
            shifted[(i, i)] += diagonal;
        }
        let lu = shifted.lu();
        let mut x = DVector::from_element(n, Complex::new(1.0, 0.0));
        for _ in 0..3 {
            if let Some(next) = lu.solve(&x) {
                let norm = next.norm();
                if norm.is_finite() && norm > 0.0 {
                    x = next / Complex::new(norm, 0.0);
                }
            }
        }
        let shape: Vec<Complex<f64>> =
            (0..self.basis.nrows()).map(|i| (0..f).fold(Complex::new(0.0, 0.0), |acc, k| acc + x[k] * self.basis[(i, k)])).collect();
        self.mode(s, shape)
    }

    /// A mode of eigenvalue s and (unscaled) shape.
    fn mode(&self, s: Complex<f64>, mut shape: Vec<Complex<f64>>) -> Mode {
        let weight = |i: usize| self.mass_diagonal.get(i).map_or(1.0, |m| m.abs().sqrt());
        let (k, _) =
            shape
                .iter()
                .enumerate()
                .fold((0, 0.0), |best, (i, &x)| if x.modulus() * weight(i) > best.1 { (i, x.modulus() * weight(i)) } else { best });
        let largest = shape.get(k).copied().unwrap_or(Complex::new(0.0, 0.0));
        if largest.modulus() > 0.0 {
            for x in &mut shape {
                *x /= largest;
            }
        }
        let norm = s.modulus();
        let tau = 2.0 * core::f64::consts::PI;
        Mode {
            eigenvalue: s,
            natural_frequency: norm / tau,
            damped_frequency: s.im.abs() / tau,
            // + 0.0: an undamped mode's −0 prints as 0
            damping_ratio: if norm > 0.0 { -s.re / norm + 0.0 } else { 0.0 },
            shape,
            dominant: self.velocity_names.get(k).copied().unwrap_or("?"),
        }
    }

    /// Whether the motion about the state is stable, from the eigenvalues of A: a real part
    /// within 1e-9 of the largest |s| counts as 0.
    pub fn stability(&self) -> LinearStability {
        if self.dof() == 0 {
            return LinearStability::Asymptotic { decay: f64::INFINITY };
        }
        let (eigenvalues, undamped) = match self.undamped_modes() {
            Some(modes) => (modes.iter().map(|m| m.eigenvalue).collect::<Vec<_>>(), Some(modes)),
            None => (self.eigenvalues(), None),
        };
        let scale = eigenvalues.iter().fold(0.0f64, |a, s| a.max(s.modulus()));
        let band = ZERO_EIGENVALUE * scale;
        let Some(&worst) = eigenvalues.iter().max_by(|a, b| a.re.total_cmp(&b.re)) else {
            return LinearStability::Asymptotic { decay: f64::INFINITY };
        };
        if worst.re > band {
            // The shape only of the mode that grows fastest.
            let direction = match &undamped {
                Some(modes) => modes.iter().find(|m| m.eigenvalue == worst).map_or("?", |m| m.dominant),
                None => self.damped_mode(worst, scale).dominant,
            };
            LinearStability::Unstable { growth: worst.re, direction }
        } else if worst.re >= -band {
            LinearStability::Marginal
        } else {
            LinearStability::Asymptotic { decay: -worst.re }
        }
    }

    /// The model as JSON: `{"t", "q", "v", "states", "inputs", "outputs", "velocities",
    /// "independent", "A", "B", "C", "D", "M_r", "D_r", "K_r", "B_r", "Z"}` — the state
    /// linearized about, the names (`"independent"`: the velocities the states are), the matrices
    /// as arrays of rows (Z: NV × f, rows named by `"velocities"`).
    pub fn to_json(&self) -> String {
        let names = |n: &mut dyn Iterator<Item = String>| format!("[{}]", n.map(|s| format!("{s:?}")).collect::<Vec<_>>().join(", "));
        let numbers = |x: &[f64]| format!("[{}]", x.iter().map(|x| json_number(*x)).collect::<Vec<_>>().join(", "));
        let matrix = |m: &DMatrix<f64>| {
            let rows: Vec<String> = m.row_iter().map(|r| numbers(&r.iter().copied().collect::<Vec<_>>())).collect();
            format!("[{}]", rows.join(", "))
        };
        let strings = |n: &[String]| names(&mut n.iter().cloned());
        format!(
            "{{\"t\": {}, \"q\": {}, \"v\": {}, \"states\": {}, \"inputs\": {}, \"outputs\": {}, \"velocities\": {}, \"independent\": {}, \
             \"A\": {}, \"B\": {}, \"C\": {}, \"D\": {}, \"M_r\": {}, \"D_r\": {}, \"K_r\": {}, \"B_r\": {}, \"Z\": {}}}",
            json_number(self.t),
            numbers(&self.q),
            numbers(&self.v),
            strings(&self.state_names),
            strings(&self.input_names),
            strings(&self.output_names),
            names(&mut self.velocity_names.iter().map(|n| n.to_string())),
            names(&mut self.independent.iter().map(|&i| self.velocity_names.get(i).copied().unwrap_or("?").to_string())),
            matrix(&self.a),
            matrix(&self.b),
            matrix(&self.c),
            matrix(&self.d),
            matrix(&self.mass),
            matrix(&self.damping),
            matrix(&self.stiffness),
            matrix(&self.input_forces),
            matrix(&self.basis),
        )
    }

    /// Writes `A.csv`, `B.csv`, `C.csv`, `D.csv`, the second-order form's `M_r.csv`, `D_r.csv`,
    /// `K_r.csv`, `B_r.csv` and the basis `Z.csv` into `dir` (created if missing): a header of
    /// column names (states, inputs, independent displacements) after an empty corner, then one
    /// row per state, output, displacement or velocity, its name first. Full precision (`{:e}`
    /// round-trips). Needs `std`.
    #[cfg(feature = "std")]
    pub fn write_csv(&self, dir: &Path) -> io::Result<()> {
        std::fs::create_dir_all(dir)?;
        let write = |file: &str, m: &DMatrix<f64>, rows: &[String], columns: &[String]| -> io::Result<()> {
            let mut out = io::BufWriter::new(std::fs::File::create(dir.join(file))?);
            writeln!(out, "\"\",{}", columns.iter().map(|c| format!("{c:?}")).collect::<Vec<_>>().join(","))?;
            for (name, row) in rows.iter().zip(m.row_iter()) {
                writeln!(out, "{name:?},{}", row.iter().map(|x| format!("{x:e}")).collect::<Vec<_>>().join(","))?;
            }
            out.flush()
        };
        let f = self.dof();
        let positions = &self.state_names[..f];
        let velocities: Vec<String> = self.velocity_names.iter().map(|n| n.to_string()).collect();
        write("A.csv", &self.a, &self.state_names, &self.state_names)?;
        write("B.csv", &self.b, &self.state_names, &self.input_names)?;
        write("C.csv", &self.c, &self.output_names, &self.state_names)?;
        write("D.csv", &self.d, &self.output_names, &self.input_names)?;
        write("M_r.csv", &self.mass, positions, positions)?;
        write("D_r.csv", &self.damping, positions, positions)?;
        write("K_r.csv", &self.stiffness, positions, positions)?;
        write("B_r.csv", &self.input_forces, positions, &self.input_names)?;
        write("Z.csv", &self.basis, &velocities, positions)
    }
}

/// A JSON number (`null` for NaN and infinities, which JSON cannot hold).
fn json_number(x: f64) -> String {
    if x.is_finite() {
        format!("{x:e}")
    } else {
        "null".to_string()
    }
}
