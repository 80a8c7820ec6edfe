//! Radau IIA of order 5 (three stages) on the index-3 equations M v̇ − Dᵀλ = h, Φ = 0 — the
//! high-order stiff method: [`Radau5`] and its [`Radau5Options`] (issue 39, item 1; Hairer &
//! Wanner, *Solving ODEs II*, IV.8 and VII.4, as their RADAU5).
//!
//! # The stages
//!
//! A step of h from (q₀, v₀) has three stages at t₀ + c_i h, c = ((4 − √6)/10, (4 + √6)/10, 1).
//! Its unknowns are the stage accelerations A_i and multipliers Λ_i; with Radau IIA's matrix a,
//!
//! ```text
//! V_i = v₀ + h Σ_j a_ij A_j,      Q_i = q₀ + h Σ_j a_ij B(Q_j) V_j,
//! F_i = M(Q_i) A_i − D(Q_i)ᵀ Λ_i − h(Q_i, V_i) = 0,      G_i = Φ(Q_i, t_i) = 0.
//! ```
//!
//! Q is collocated in the coordinates themselves (Euler parameters included: ė = ½ e ⊗ (0, ω′)
//! is linear in e, so the Q_i are found by a contraction, one pass where q̇ = v). The step ends
//! at the last stage (the method is stiffly accurate): q₁ = Q₃ normalized, v₁ = V₃, v̇₁ = A₃,
//! λ₁ = Λ₃. The positions converge at order 5 on these index-3 equations (measured on fixed
//! steps: the double pendulum in `tests/integrators.rs`, the heavy top's Euler parameters in
//! `tests/spatial_analyses.rs`).
//!
//! # The Newton iteration, over the sparse pattern `mechanism!` planned
//!
//! Simplified Newton with the Jacobian frozen at the step's start: with P = [[M, −Dᵀ], [0, 0]],
//! C′ = [[−∂h/∂v, 0], [0, 0]] and K′ = [[−∂(h + Dᵀλ)/∂q, 0], [D, 0]], the iteration matrix of the
//! three stages is I⊗P + h a⊗C′ + h² a²⊗K′. Hairer's transformation T (T⁻¹ a⁻¹ T = diag(γ̂,
//! [[α, −β], [β, α]])) splits it into a real block and a complex one, each of the form
//!
//! ```text
//! P + c C′ + c² K′,   c = h/γ̂ (real),   c = h/(α + iβ) (complex),
//! ```
//!
//! which is the planned Newton matrix of generalized-α and BDF with slopes c_v = c, c_q = c²
//! ([`NewtonMatrix`]): the real block factored as theirs is, the complex one over the same pattern
//! in complex arithmetic ([`crate::sparse::factor_complex`]; its real and imaginary
//! parts from two real fills, the matrix being linear in c_v and c_q). No dense matrix, and the
//! work space's three Newton slots hold the three.
//!
//! # Error control
//!
//! Hairer's embedded estimate, filtered through the real block for stiff components:
//! err = (γ̂/h − J)⁻¹ (f₀ + Σ d_i Z_i / h), which for this second-order system is one solve
//! with the real factors (the damping's part of J along the estimate by one difference of the
//! forces). Tolerances are transformed as RADAU5's (rtol′ = 0.1 rtol^(2/3)); the step size
//! follows Gustafsson's predictive controller, and grows no further than keeps the simplified
//! Newton iteration's rate below a quarter (its Jacobian is the step start's, so its rate grows
//! with h: on a 4-link chain without the limit, most steps after a growth were cut again).
//!
//! The velocities are measured in full, not times h as RADAU5 measures an index-2 variable:
//! with the scaling, the velocities of the index-3 equations (one order lower than the
//! positions at the stages) went uncontrolled, and on the 4-link pendulum chain the delivered
//! error rose to 930 × rtol at rtol 1e-10, against 115 × measured in full (2026-12-06). The
//! price is on stiff models whose velocities the stages resolve poorly: the stiff flywheel
//! (issue 39's case A) needs 2 506 steps at rtol 1e-6 with the velocities in full, 736 with
//! them scaled, for errors of 1e-8 and 1e-6.
//!
//! # The step's end
//!
//! The step ends at Q₃ projected onto Φ = 0 (to what the scalar resolves: at most three
//! mass-weighted steps, quadratic from what Newton's stopping tolerance left) and V₃ onto
//! D v = ν; v̇ and λ there are forward dynamics' at that point, not the last stage's A₃ and Λ₃.
//! The stage equations are of index 3: a step that starts off Φ = 0 by δ removes δ within
//! itself, by stage accelerations of order δ/h². When such a step is rejected and retried
//! shorter, they grow, the error estimate with them, and the step shrinks on down to
//! `min_step` — the stiff flywheel at rtol 1e-3 failed so at 0.6 s, its estimate rising from 5
//! to 1 300 as h fell from 1e-3 to 5e-12 s. A₃ is the stage value these equations resolve
//! worst (Q₃ does not depend on it, (a²)₃₃ = 0), and the next step's estimate reads v̇₀.
//!
//! # Rounding
//!
//! The stages resolve the velocities only to the rounding of the positions over h, amplified: a
//! residual δ of Φ at a stage moves the stage accelerations by about δ/(|a²| h²) — a²'s
//! smallest entries are 0.007 — and the estimate's velocities by about 10 δ/h. Newton's norm and
//! the error test add [`VELOCITY_ROUNDING_ULPS`] ulps of the positions over h to each
//! velocity's weight (5.7e-11 m/s at 1 ms for coordinates of order 1), and constraint residuals
//! within [`RESIDUAL_ULPS`] are taken as zero. Without the allowance, a step whose estimate
//! sits at this floor is accepted at an error of about 0.7 that does not fall with h, and
//! Gustafsson's controller, which expects it to fall as h⁴, shortens every step after it.
//!
//! Not yet: reuse of the factors across steps of equal size (RADAU5 keeps them while the
//! iteration converges fast). Tried with a rate limit of 0.1 it took more steps on the stiff
//! flywheel and on the heavy top ended 1e-2 off at rtol 1e-4 (the error estimate's filter then
//! uses a stale Jacobian), and was taken out.
//!
//! Output between steps is the collocation polynomial through (t₀, q₀, v₀) and the three stages.

// The tableau's constants keep the digits they were computed with (30, by mpmath), rounded to f64
// by the compiler; a stage index i and a coordinate index k index several arrays alike.
#![allow(clippy::excessive_precision, clippy::needless_range_loop)]

use super::implicit::position_ulps;
use super::{check_step, fixed_step, hermite_state, Integrator, Point, SimulationError, System};
use crate::linalg::sparse::{factor_complex, solve_complex};
use crate::model::mechanism::NewtonMatrix;
use crate::model::workspace::{DenseScratch, Vectors, WorkArrays};
use crate::real::Real;

/// Radau IIA's nodes c_i.
const C: [f64; 3] = [0.155_051_025_721_682_19, 0.644_948_974_278_317_8, 1.0];
/// Radau IIA's matrix a.
const A: [[f64; 3]; 3] = [
    [0.196_815_477_223_660_43, -0.065_535_425_850_198_39, 0.023_770_974_348_220_15],
    [0.394_424_314_739_087_3, 0.292_073_411_665_228_46, -0.041_548_752_125_997_93],
    [0.376_403_062_700_467_3, 0.512_485_826_188_421_6, 0.111_111_111_111_111_11],
];
/// a², the positions' weights of the stage accelerations.
const A2: [[f64; 3]; 3] = [
    [0.021_835_034_190_722_74, -0.019_857_254_098_612_275, 0.010_042_630_196_562_411],
    [0.177_190_587_431_945_6, 0.038_164_965_809_277_26, -0.007_375_963_529_895_744],
    [0.318_041_381_743_977_2, 0.181_958_618_256_022_83, 0.0],
];
/// T (RADAU5's T11 … T33), whose columns turn a⁻¹ into diag(γ̂, [[α, −β], [β, α]]).
const T_: [[f64; 3]; 3] = [
    [0.091_232_394_870_892_94, -0.141_255_295_020_954_2, -0.030_029_194_105_147_424],
    [0.241_717_932_707_107, 0.204_129_352_293_799_93, 0.382_942_112_757_261_94],
    [0.966_048_182_615_092_9, 1.0, 0.0],
];
/// T⁻¹.
const TI: [[f64; 3]; 3] = [
    [4.325_579_890_063_155, 0.339_199_251_815_809_87, 0.541_770_539_935_874_9],
    [-4.178_718_591_551_905, -0.327_682_820_761_062_4, 0.476_623_554_500_550_45],
    [-0.502_872_634_945_786_9, 2.571_926_949_855_605_4, -0.596_039_204_828_224_9],
];
/// The Newton iteration's convergence rate the step-size control aims below (module docs).
const RATE_LIMIT: f64 = 0.25;
/// a⁻¹'s real eigenvalue γ̂ and its complex pair α ± iβ.
const GAMMA: f64 = 3.637_834_252_744_495_7;
const ALPHA: f64 = 2.681_082_873_627_752;
const BETA: f64 = 3.050_430_199_247_410_6;
/// The error estimate's weights: aᵀd on the accelerations for the velocities, (a²)ᵀd for the
/// positions (d = RADAU5's DD1, DD2, DD3), the start's own term having cancelled (dᵀc = −1).
const E_V: [f64; 3] = [-1.558_078_204_724_922_4, 0.891_411_538_058_255_7, -0.333_333_333_333_333_3];
const E_Q: [f64; 3] = [-0.080_527_207_932_398_78, 0.191_638_319_043_509_9, -0.111_111_111_111_111_11];

crate::options::options! {
    /// Options of [`Radau5`], in the scalar type `T` of the mechanism (default `f64`). Build from
    /// [`Default`] and the `with_*` setters.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct Radau5Options<T> {
        /// Relative tolerance on each coordinate and velocity. Default 1e-6.
        rtol: T = T::from_f64(1e-6) => with_rtol,
        /// Absolute tolerance (m, rad, m/s, rad/s). Default 1e-8.
        atol: T = T::from_f64(1e-8) => with_atol,
        /// The first step tried (s); 0 (the default) chooses it from the initial rates, as
        /// DOPRI5 does.
        initial_step: T = T::ZERO => with_initial_step,
        /// Largest step size (s). Default 0.1 s.
        max_step: T = T::from_f64(0.1) => with_max_step,
        /// Smallest step size before failing with [`SimulationError::StepSizeTooSmall`]. Default
        /// 1e-12 s.
        min_step: T = T::from_f64(1e-12) => with_min_step,
        /// The Newton iteration's stopping tolerance, in the error test's norm (1: the
        /// tolerance): it stops when the error it estimates is below this. 0 (the default)
        /// chooses RADAU5's, max(10ε/rtol′, min(0.03, √rtol′)).
        newton_tolerance: T = T::ZERO => with_newton_tolerance,
        /// Newton iterations per step before the step is retried at half its size. Default 7
        /// (RADAU5's).
        max_iterations: u32 = 7 => with_max_iterations,
        /// Relative pivot tolerance of the iteration matrices' LU, as generalized-α's. Default
        /// 1e-13.
        pivot_tolerance: T = T::from_f64(1e-13) => with_pivot_tolerance,
        /// Project each step's velocities onto D v = ν in the metric of M (the index-3
        /// equations leave D v − ν of the order of the velocities' error). Default true.
        project_velocities: bool = true => with_project_velocities,
    }
}

/// Radau IIA of order 5 with variable steps (module docs): implicit, L-stable and stiffly
/// accurate, for stiff models at tight tolerances — a mode far faster than the motion of
/// interest, a stiff spring or damper, a contact — where BDF's order is held down. Each step
/// solves the three stages' Φ = 0 by simplified Newton over the sparse iteration matrix
/// `mechanism!` planned, in a real and a complex block (the work space must be the
/// mechanism's, `Name::workspace()`, whose three Newton slots it uses); the integrator holds
/// O(NQ + NV + NC): the last step's stages.
#[derive(Clone, Copy, Debug)]
pub struct Radau5<T, const NQ: usize, const NV: usize, const NC: usize> {
    /// Tolerances and Newton options.
    pub options: Radau5Options<T>,
    /// The step size the next step will try (s); 0 before the first.
    pub next_step: T,
    /// Steps accepted so far.
    pub accepted: u64,
    /// Steps rejected so far (too large an error, or Newton failing).
    pub rejected: u64,
    /// Newton iterations so far, rejected steps' included.
    pub iterations: u64,
    // The last accepted step: its start and size, stage accelerations and multipliers (to
    // start the next step's iteration from their polynomial), and its first two stages'
    // positions and velocities (its dense output).
    last: Option<(T, T)>,
    accelerations: [[T; NV]; 3],
    multipliers: [[T; NC]; 3],
    stage_q: [[T; NQ]; 2],
    stage_v: [[T; NV]; 2],
    // Gustafsson's controller: the last accepted step and its error; whether the step before
    // this attempt was rejected; the Newton iteration's convergence factor θ/(1 − θ).
    accepted_step: T,
    accepted_error: T,
    just_rejected: bool,
    contraction: T,
    // The convergence rate θ last measured (an iteration that converges at once measures none).
    rate: T,
    // ‖Φ‖∞ the last step's end was projected from (`Integrator::projected_end`).
    end_residual: Option<T>,
}

impl<T: Real, const NQ: usize, const NV: usize, const NC: usize> Radau5<T, NQ, NV, NC> {
    /// A Radau IIA integrator with the given options.
    pub fn new(options: Radau5Options<T>) -> Self {
        Self {
            options,
            next_step: T::ZERO,
            accepted: 0,
            rejected: 0,
            iterations: 0,
            last: None,
            accelerations: [[T::ZERO; NV]; 3],
            multipliers: [[T::ZERO; NC]; 3],
            stage_q: [[T::ZERO; NQ]; 2],
            stage_v: [[T::ZERO; NV]; 2],
            accepted_step: T::ZERO,
            accepted_error: T::ZERO,
            just_rejected: false,
            contraction: T::ONE,
            rate: T::ZERO,
            end_residual: None,
        }
    }
}

impl<T: Real, const NQ: usize, const NV: usize, const NC: usize> Default for Radau5<T, NQ, NV, NC> {
    fn default() -> Self {
        Self::new(Radau5Options::default())
    }
}

fn f<T: Real>(x: f64) -> T {
    T::from_f64(x)
}

/// The weights of the polynomial through `nodes`, at `t`.
fn lagrange<T: Real, const K: usize>(nodes: [T; K], t: T) -> [T; K] {
    core::array::from_fn(|j| (0..K).filter(|&m| m != j).fold(T::ONE, |x, m| x * (t - nodes[m]) / (nodes[j] - nodes[m])))
}

/// One step's stage states from its stage accelerations (module docs): V_i, and Q_i collocated
/// in the coordinates (a contraction where B depends on q; one pass where q̇ = v). `false` where
/// the contraction does not settle (a step too long for the rotation rate).
fn stage_states<T: Real, M: NewtonMatrix<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize>(
    mech: &M,
    from: &Point<T, NQ, NV, NC>,
    h: T,
    acc: &[[T; NV]; 3],
    q: &mut [[T; NQ]; 3],
    v: &mut [[T; NV]; 3],
    mut vectors: Vectors<'_, T>,
) -> bool {
    for i in 0..3 {
        for k in 0..NV {
            v[i][k] = from.v[k] + h * (0..3).fold(T::ZERO, |s, j| s + f::<T>(A[i][j]) * acc[j][k]);
        }
    }
    // Where q̇ = v (NQ = NV), q₀ + h Σ a_ij V_j exactly; otherwise its ⊕ as the contraction's start.
    let dv = vectors.take::<NV>();
    for i in 0..3 {
        for (k, x) in dv.iter_mut().enumerate() {
            *x = (0..3).fold(T::ZERO, |s, j| s + f::<T>(A[i][j]) * v[j][k]);
        }
        q[i] = from.q;
        mech.integrate_positions(&mut q[i], dv, h);
    }
    if NQ == NV {
        return true;
    }
    let floor = T::from_f64(4.0) * T::EPSILON * from.q.iter().fold(T::ONE, |m, x| m.max(x.abs()));
    let rates = vectors.rows::<NQ, 3>();
    for _ in 0..40 {
        for j in 0..3 {
            mech.position_rates(&q[j], &v[j], &mut rates[j]);
        }
        let mut change = T::ZERO;
        for i in 0..3 {
            for k in 0..NQ {
                let x = from.q[k] + h * (0..3).fold(T::ZERO, |s, j| s + f::<T>(A[i][j]) * rates[j][k]);
                change = change.max((x - q[i][k]).abs());
                q[i][k] = x;
            }
        }
        if change <= floor {
            return true;
        }
    }
    false
}

/// Stage i's residual (F_i; G_i) into `r` (N = NV + NC entries): M A_i − Dᵀ Λ_i − h, then Φ.
#[allow(clippy::too_many_arguments)]
fn stage_residual<T: Real, M: NewtonMatrix<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
    mech: &M,
    t: T,
    q: &[T; NQ],
    v: &[T; NV],
    acc: &[T; NV],
    lambda: &[T; NC],
    s: &mut M::NewtonStorage,
    mut scratch: DenseScratch<'_, T, NV, NC>,
    r: &mut [T; N],
) {
    let (phi, force, inertia) = (scratch.vectors.take::<NC>(), scratch.vectors.take::<NV>(), scratch.vectors.take::<NV>());
    // Φ and D's non-zeros into the front of the real block's slot (its factors lie after them).
    mech.newton_jacobian(q, t, phi, s, scratch);
    mech.forces(q, v, t, force);
    mech.friction_forces(q, v, t, lambda, force);
    mech.mass_times(q, acc, inertia);
    for k in 0..NV {
        r[k] = inertia[k] - force[k];
    }
    for (&value, &(row, column)) in s.as_ref().iter().zip(M::JACOBIAN_PATTERN) {
        r[column as usize] -= value * lambda[row as usize];
    }
    r[NV..].copy_from_slice(phi);
}

impl<T: Real, const NQ: usize, const NV: usize, const NC: usize> Radau5<T, NQ, NV, NC> {
    /// The iteration's first guess of the stage accelerations and multipliers: the last step's
    /// stage polynomials extrapolated where this step continues it, else the start's v̇ and λ.
    fn first_guess(&self, from: &Point<T, NQ, NV, NC>, h: T, acc: &mut [[T; NV]; 3], lam: &mut [[T; NC]; 3]) {
        match self.last {
            // Extrapolated over at most twice the last step (beyond, the polynomial's error grows
            // as the cube of the ratio: a stiff pendulum's iteration diverged from it at 4×).
            Some((t0, h0)) if t0 + h0 == from.t && h <= T::from_f64(2.0) * h0 => {
                let nodes = [t0 + f::<T>(C[0]) * h0, t0 + f::<T>(C[1]) * h0, from.t];
                for x in acc.iter_mut().flatten().chain(lam.iter_mut().flatten()) {
                    *x = T::ZERO;
                }
                for i in 0..3 {
                    let w = lagrange(nodes, from.t + f::<T>(C[i]) * h);
                    for j in 0..3 {
                        for k in 0..NV {
                            acc[i][k] += w[j] * self.accelerations[j][k];
                        }
                        for k in 0..NC {
                            lam[i][k] += w[j] * self.multipliers[j][k];
                        }
                    }
                }
            }
            _ => {
                for i in 0..3 {
                    (acc[i], lam[i]) = (from.vd, from.lambda);
                }
            }
        }
    }
}

// The two rounding constants were chosen on a probe of the study's ten mechanisms at rtol 1e-3
// to 1e-10 (atol rtol/100, no correction: 80 runs, 2026-12-06). With (2, 256) two runs fail,
// both on the change-point four-bar at its flat position.

/// Constraint residuals at or below this many ulps of the positions are taken as zero (module
/// docs, "Rounding"). With none (0), 20 runs of the probe failed, 13 of them at t = 0 (the
/// chains, the suspension, the spatial slider-crank at rtol ≤ 1e-6: the correction of a
/// residual at rounding, divided by h², stalled Newton at every step size); with 16, seven (a
/// residual left that large is itself a perturbation the stages amplify as 1/h²).
const RESIDUAL_ULPS: f64 = 2.0;

/// The velocities' allowance for rounding, in ulps of the positions over h (module docs,
/// "Rounding"). With 16, six runs of the probe failed (the chains and the stiff flywheel at
/// rtol 1e-10, the heavy top at 1e-8 to 1e-10); with 64, five.
const VELOCITY_ROUNDING_ULPS: f64 = 256.0;

/// Position projection steps at most at each step's end (module docs, "The step's end").
const END_PROJECTION_STEPS: usize = 3;

/// The tolerances RADAU5 works to (its transformation: the embedded estimate is of order 3, so
/// a local tolerance of 0.1 rtol^(2/3) gives a global error near rtol), floored at rounding.
fn working_tolerances<T: Real>(o: &Radau5Options<T>) -> (T, T) {
    let floor = T::from_f64(16.0) * T::EPSILON;
    if o.rtol > T::ZERO {
        let rtol = (T::from_f64(0.1) * o.rtol.powf(T::from_f64(2.0 / 3.0))).max(floor);
        (rtol, (o.atol * rtol / o.rtol).max(floor))
    } else {
        (T::ZERO, o.atol.max(floor))
    }
}

impl<T: Real, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize> Integrator<T, M, NQ, NV, NC, N, NS>
    for Radau5<T, NQ, NV, NC>
where
    M: NewtonMatrix<T, NQ, NV, NC>,
{
    /// Its Newton solves Φ = 0 at every stage.
    fn holds_constraints(&self) -> bool {
        true
    }

    fn projected_end(&self) -> Option<T> {
        self.end_residual
    }

    // `!(x > y)` on purpose: it is also true when either side is NaN.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    fn step(
        &mut self,
        system: &System<'_, M, T>,
        ws: &mut WorkArrays<T, NV, NC, N, NS>,
        from: &Point<T, NQ, NV, NC>,
        t_max: T,
        to: &mut Point<T, NQ, NV, NC>,
    ) -> Result<(), SimulationError> {
        let ([real, complex_re, complex_im], mut dense) = super::implicit::newton_space::<T, M, NQ, NV, NC, N, NS>(ws)?;
        let o = self.options;
        super::dopri5::check_step_control(
            [o.rtol, o.atol, o.max_step, o.min_step],
            [
                "Radau5Options::rtol and atol must be non-negative, not both zero",
                "Radau5Options::max_step must be positive, min_step non-negative",
            ],
        )?;
        if !(t_max > from.t) {
            to.copy_from(from);
            return Ok(());
        }
        let mech = system.mechanism;
        let (rtol, atol) = working_tolerances(&o);
        if !(self.next_step > T::ZERO) {
            self.next_step = super::implicit::first_step(mech, from, o.initial_step, (rtol, atol), o.max_step);
        }
        // RADAU5's Newton tolerance, in the error norm.
        let newton_tolerance = if o.newton_tolerance > T::ZERO {
            o.newton_tolerance
        } else {
            (T::from_f64(10.0) * T::EPSILON / rtol.max(T::EPSILON)).max(T::from_f64(0.03).min(rtol.sqrt()))
        };
        let mut h = self.next_step.min(o.max_step);
        let mut first_attempt = self.accepted == 0;
        let mut stages = Stages::take(&mut dense.vectors);
        loop {
            let (h_try, t1) = fixed_step(from.t, h, t_max);
            let slots = [&mut *real, &mut *complex_re, &mut *complex_im];
            let attempt =
                self.attempt::<M, N>(system, (rtol, atol), newton_tolerance, from, h_try, slots, dense.reborrow(), &mut stages)?;
            let Attempt::Converged { error, newton_iterations } = attempt else {
                // Newton did not converge (or the positions' contraction did not): a shorter step.
                self.rejected += 1;
                self.just_rejected = true;
                h = h_try * if let Attempt::Slow { factor } = attempt { factor } else { T::from_f64(0.5) };
                if !(h >= o.min_step) {
                    return Err(SimulationError::StepSizeTooSmall { t: from.t.to_f64(), step: h.to_f64() });
                }
                continue;
            };
            let quot = self.step_quotient(error, newton_iterations, h_try);
            if error < T::ONE {
                let mut next = h_try / quot;
                if self.just_rejected {
                    next = next.min(h_try);
                }
                // The iteration's rate grows with the step (the Jacobian is the start's; on the
                // stiff pendulum faster than h): a step that would take it past a quarter, as if
                // it grew as h², is not tried (it would be cut again and its factorizations
                // wasted).
                if self.rate > T::ZERO {
                    next = next.min(h_try * T::ONE.max((T::from_f64(RATE_LIMIT) / self.rate).sqrt()));
                }
                self.accept(system, from, (h_try, t1), &stages, to, dense.reborrow())?;
                self.next_step = next.min(o.max_step);
                self.just_rejected = false;
                return Ok(());
            }
            self.rejected += 1;
            self.just_rejected = true;
            h = if first_attempt { h_try * T::from_f64(0.1) } else { h_try / quot };
            first_attempt = false;
            if !(h >= o.min_step) {
                return Err(SimulationError::StepSizeTooSmall { t: from.t.to_f64(), step: h.to_f64() });
            }
        }
    }

    fn prepare_interpolation(
        &mut self,
        _system: &System<'_, M, T>,
        _ws: &mut WorkArrays<T, NV, NC, N, NS>,
        _from: &Point<T, NQ, NV, NC>,
        _to: &Point<T, NQ, NV, NC>,
    ) -> Result<(), SimulationError> {
        // The collocation polynomial needs the kept stages only.
        Ok(())
    }

    /// The collocation polynomial through the step's start and its three stages, at t; the
    /// cubic Hermite interpolant between `from` and `to` where the last step is not theirs.
    fn interpolate(&self, mechanism: &M, from: &Point<T, NQ, NV, NC>, to: &Point<T, NQ, NV, NC>, t: T, q: &mut [T; NQ], v: &mut [T; NV]) {
        match self.last {
            Some((t0, h)) if t0 == from.t && t0 + h == to.t => {
                let w = lagrange([T::ZERO, f(C[0]), f(C[1]), T::ONE], (t - t0) / h);
                for k in 0..NQ {
                    q[k] = w[0] * from.q[k] + w[1] * self.stage_q[0][k] + w[2] * self.stage_q[1][k] + w[3] * to.q[k];
                }
                for k in 0..NV {
                    v[k] = w[0] * from.v[k] + w[1] * self.stage_v[0][k] + w[2] * self.stage_v[1][k] + w[3] * to.v[k];
                }
            }
            _ => hermite_state(mechanism, from, to, t, q, v),
        }
    }

    fn restart(&mut self) {
        self.last = None;
        self.accepted_step = T::ZERO;
        self.just_rejected = false;
        self.end_residual = None;
    }

    /// v̇ and λ are unknowns of the method: the corrected point keeps them.
    fn after_correction(
        &mut self,
        _system: &System<'_, M, T>,
        _ws: &mut WorkArrays<T, NV, NC, N, NS>,
        _to: &mut Point<T, NQ, NV, NC>,
    ) -> Result<(), SimulationError> {
        Ok(())
    }
}

/// How one try of a step went.
enum Attempt<T> {
    /// Newton converged after this many iterations; the step's scaled error (accepted ≤ 1).
    Converged { error: T, newton_iterations: u32 },
    /// Newton would not converge in time: try again at `factor` times the step.
    Slow { factor: T },
    /// Newton diverged, or the stage positions would not settle: try again at half the step.
    Diverged,
}

/// The three stages of a try: accelerations, multipliers, positions, velocities.
struct Stages<'a, T, const NQ: usize, const NV: usize, const NC: usize> {
    acc: &'a mut [[T; NV]; 3],
    lam: &'a mut [[T; NC]; 3],
    q: &'a mut [[T; NQ]; 3],
    v: &'a mut [[T; NV]; 3],
}

impl<'a, T: Real, const NQ: usize, const NV: usize, const NC: usize> Stages<'a, T, NQ, NV, NC> {
    /// Zeroed stages from the work space's vectors.
    fn take(vectors: &mut Vectors<'a, T>) -> Self {
        Self { acc: vectors.rows(), lam: vectors.rows(), q: vectors.rows(), v: vectors.rows() }
    }
}

impl<T: Real, const NQ: usize, const NV: usize, const NC: usize> Radau5<T, NQ, NV, NC> {
    /// h / h_next for a step of `h` with scaled `error` after `iterations` Newton iterations:
    /// RADAU5's, the estimate's with a safety factor that shrinks with the iterations, between
    /// an eighth and five, and for an accepted step Gustafsson's predictive controller (which
    /// this records the step for).
    fn step_quotient(&mut self, error: T, iterations: u32, h: T) -> T {
        let max_it = T::from_f64(f64::from(self.options.max_iterations.max(1)));
        let two = T::from_f64(2.0);
        let safety = T::from_f64(0.9).min(T::from_f64(0.9) * (T::ONE + two * max_it) / (T::from_f64(f64::from(iterations)) + two * max_it));
        let limit = |x: T| T::from_f64(0.125).max(T::from_f64(5.0).min(x));
        let mut quot = limit(error.powf(T::from_f64(0.25)) / safety);
        if error < T::ONE {
            if self.accepted > 0 && self.accepted_step > T::ZERO {
                let predicted = (self.accepted_step / h) * (error * error / self.accepted_error).powf(T::from_f64(0.25)) / T::from_f64(0.9);
                quot = quot.max(limit(predicted));
            }
            self.accepted_step = h;
            self.accepted_error = error.max(T::from_f64(1e-2));
        }
        quot
    }

    /// Fills and factors the real and complex blocks at the step's start (module docs).
    #[allow(clippy::too_many_arguments)]
    fn factor_blocks<M: NewtonMatrix<T, NQ, NV, NC>>(
        system: &System<'_, M, T>,
        o: &Radau5Options<T>,
        from: &Point<T, NQ, NV, NC>,
        h: T,
        [real, re, im]: [&mut M::NewtonStorage; 3],
        mut scratch: DenseScratch<'_, T, NV, NC>,
        dropped: &mut [bool; NC],
    ) -> Result<(), SimulationError> {
        let mech = system.mechanism;
        let phi = scratch.vectors.take::<NC>();
        let fill = |c_v: T, c_q: T, s: &mut M::NewtonStorage, scratch: DenseScratch<'_, T, NV, NC>, phi: &mut [T; NC]| {
            mech.newton_matrix(&from.q, &from.v, &from.vd, from.t, &from.lambda, None, c_v, c_q, phi, s, scratch);
        };
        let c = h / f::<T>(GAMMA);
        fill(c, c * c, real, scratch.reborrow(), phi);
        // c = h/(α + iβ) = cr + i ci, c² = (cr² − ci²) + 2i cr ci: the matrix is linear in (c_v,
        // c_q), so its real part is the fill at the real parts and its imaginary part the fill
        // at the sums less that.
        let modulus = f::<T>(ALPHA * ALPHA + BETA * BETA);
        let (cr, ci) = (h * f::<T>(ALPHA) / modulus, -h * f::<T>(BETA) / modulus);
        let (qr, qi) = (cr * cr - ci * ci, T::from_f64(2.0) * cr * ci);
        fill(cr, qr, re, scratch.reborrow(), phi);
        fill(cr + ci, qr + qi, im, scratch.reborrow(), phi);
        let nnz = M::JACOBIAN_PATTERN.len();
        for (x, &y) in im.as_mut()[nnz..].iter_mut().zip(&re.as_ref()[nnz..]) {
            *x -= y;
        }
        let allow = system.dynamics.allow_redundant;
        let error = |e| super::implicit::factorization_error::<M, T>(e, from.t, NV);
        M::newton_factor(real, o.pivot_tolerance, allow, dropped).map_err(error)?;
        factor_complex(&M::NEWTON_PATTERN, &mut re.as_mut()[nnz..], &mut im.as_mut()[nnz..], NV, o.pivot_tolerance, allow, dropped)
            .map_err(error)?;
        Ok(())
    }

    /// One try of a step of h from `from` to t1: the blocks factored, simplified Newton on the
    /// stages (into `stages`), and the error estimate.
    // `!(x < y)` on purpose: it is also true when either side is NaN.
    #[allow(clippy::too_many_arguments, clippy::neg_cmp_op_on_partial_ord)]
    fn attempt<M: NewtonMatrix<T, NQ, NV, NC>, const N: usize>(
        &mut self,
        system: &System<'_, M, T>,
        (rtol, atol): (T, T),
        newton_tolerance: T,
        from: &Point<T, NQ, NV, NC>,
        h: T,
        [real, re, im]: [&mut M::NewtonStorage; 3],
        mut scratch: DenseScratch<'_, T, NV, NC>,
        stages: &mut Stages<'_, T, NQ, NV, NC>,
    ) -> Result<Attempt<T>, SimulationError> {
        let o = self.options;
        let mech = system.mechanism;
        let mut dropped = [false; NC];
        Self::factor_blocks(system, &o, from, h, [&mut *real, &mut *re, &mut *im], scratch.reborrow(), &mut dropped)?;
        let nnz = M::JACOBIAN_PATTERN.len();
        self.first_guess(from, h, stages.acc, stages.lam);
        // The residuals, their transform and the stages' corrections (each written whole before
        // it is read).
        let (r, b, dz) = (scratch.vectors.rows::<N, 3>(), scratch.vectors.rows::<N, 3>(), scratch.vectors.rows::<N, 3>());
        // The positions' scale in velocity space: each coordinate's own where q̇ = v, else the
        // largest.
        let q_scale = from.q.iter().fold(T::ZERO, |m, x| m.max(x.abs()));
        let weight_q = |k: usize| atol + rtol * if NQ == NV { from.q[k].abs() } else { q_scale };
        let zero_residual = position_ulps(&from.q, RESIDUAL_ULPS);
        let rounding = position_ulps(&from.q, VELOCITY_ROUNDING_ULPS) / h;
        let weight_v = |k: usize| atol + rtol * from.v[k].abs() + rounding;
        let c = h / f::<T>(GAMMA);
        let modulus = f::<T>(ALPHA * ALPHA + BETA * BETA);
        let (cr, ci) = (h * f::<T>(ALPHA) / modulus, -h * f::<T>(BETA) / modulus);
        let (qr, qi) = (cr * cr - ci * ci, T::from_f64(2.0) * cr * ci);
        let q_modulus = qr * qr + qi * qi;
        self.contraction = self.contraction.max(T::EPSILON).powf(T::from_f64(0.8));
        let (mut last_size, mut last_ratio) = (T::ZERO, T::ONE);
        let max_it = o.max_iterations.max(1);
        let mut newton_iterations = 0;
        loop {
            if newton_iterations >= max_it {
                return Ok(Attempt::Diverged);
            }
            if !stage_states(mech, from, h, stages.acc, stages.q, stages.v, scratch.vectors.reborrow()) {
                return Ok(Attempt::Diverged);
            }
            for i in 0..3 {
                let t = from.t + f::<T>(C[i]) * h;
                stage_residual(mech, t, &stages.q[i], &stages.v[i], &stages.acc[i], &stages.lam[i], real, scratch.reborrow(), &mut r[i]);
                if let Some(k) = r[i].iter().position(|x| !x.is_finite()) {
                    return Err(super::implicit::non_finite_residual(mech, (&stages.q[i], &stages.v[i], t, &stages.lam[i]), from.t, k));
                }
                // A constraint residual at the rounding of Φ is zero: its correction, divided
                // by c_q ~ h², would move the stage velocities by rounding / h and, at a tight
                // atol, stall the iteration at every step size ([`RESIDUAL_ULPS`]).
                for x in &mut r[i][NV..] {
                    if x.abs() <= zero_residual {
                        *x = T::ZERO;
                    }
                }
            }
            // T⁻¹ over the stages, then each block's solve: the constraint rows divided by c_q
            // (complex for the second), dropped rows held.
            for (k, row) in b.iter_mut().enumerate() {
                for (n, x) in row.iter_mut().enumerate() {
                    *x = -(0..3).fold(T::ZERO, |s, i| s + f::<T>(TI[k][i]) * r[i][n]);
                }
            }
            for row in 0..NC {
                let n = NV + row;
                if dropped[row] {
                    (b[0][n], b[1][n], b[2][n]) = (T::ZERO, T::ZERO, T::ZERO);
                    continue;
                }
                b[0][n] /= c * c;
                let (x, y) = (b[1][n], b[2][n]);
                (b[1][n], b[2][n]) = ((x * qr + y * qi) / q_modulus, (y * qr - x * qi) / q_modulus);
            }
            let [b1, b_re, b_im] = &mut *b;
            M::newton_solve(real, b1);
            solve_complex(&M::NEWTON_PATTERN, &re.as_ref()[nnz..], &im.as_ref()[nnz..], b_re, b_im);
            for (i, row) in dz.iter_mut().enumerate() {
                for (n, x) in row.iter_mut().enumerate() {
                    *x = f::<T>(T_[i][0]) * b[0][n] + f::<T>(T_[i][1]) * b[1][n] + f::<T>(T_[i][2]) * b[2][n];
                }
            }
            if dz.iter().flatten().any(|x| !x.is_finite()) {
                return Ok(Attempt::Diverged);
            }
            // The change of the stages' positions (h² a² ΔA) and velocities (h a ΔA), in the error
            // test's weights.
            let mut sum = T::ZERO;
            for i in 0..3 {
                for k in 0..NV {
                    let dv = h * (0..3).fold(T::ZERO, |s, j| s + f::<T>(A[i][j]) * dz[j][k]);
                    let dq = h * h * (0..3).fold(T::ZERO, |s, j| s + f::<T>(A2[i][j]) * dz[j][k]);
                    sum += (dv / weight_v(k)).powi(2) + (dq / weight_q(k)).powi(2);
                }
            }
            let size = (sum / T::from_f64((6 * NV).max(1) as f64)).sqrt();
            newton_iterations += 1;
            self.iterations += 1;
            // RADAU5's convergence test: the rate θ from successive corrections, the error left
            // θ/(1 − θ) times the last; a rate that cannot reach the tolerance in the iterations
            // left shortens the step at once.
            if newton_iterations > 1 {
                let ratio = size / last_size;
                let theta = if newton_iterations == 2 { ratio } else { (ratio * last_ratio).sqrt() };
                last_ratio = ratio;
                if !(theta < T::from_f64(0.99)) {
                    return Ok(Attempt::Diverged);
                }
                self.contraction = theta / (T::ONE - theta);
                self.rate = theta;
                let left = max_it as i32 - 1 - newton_iterations as i32;
                let forecast = self.contraction * size * theta.powi(left) / newton_tolerance;
                if forecast >= T::ONE {
                    let q = forecast.max(T::from_f64(1e-4)).min(T::from_f64(20.0));
                    let factor = T::from_f64(0.8) * q.powf(-T::ONE / T::from_f64(f64::from(4 + left)));
                    return Ok(Attempt::Slow { factor });
                }
            }
            last_size = size.max(T::EPSILON);
            for i in 0..3 {
                for k in 0..NV {
                    stages.acc[i][k] += dz[i][k];
                }
                for k in 0..NC {
                    stages.lam[i][k] += dz[i][NV + k];
                }
            }
            if self.contraction * size <= newton_tolerance {
                if newton_iterations == 1 {
                    // Converged at once: no rate measured, and the last one no longer holds (kept,
                    // it would bar the step from growing on every later step: on the 4-link chain
                    // at rtol 1e-9, atol 1e-11 the step was held at 5e-12 s).
                    self.rate = T::ZERO;
                }
                break;
            }
        }
        if !stage_states(mech, from, h, stages.acc, stages.q, stages.v, scratch.vectors.reborrow()) {
            return Ok(Attempt::Diverged);
        }
        let error = self.error_estimate::<M, N>(system, (rtol, atol), from, h, real, stages, scratch.vectors);
        Ok(Attempt::Converged { error, newton_iterations })
    }

    /// The step's scaled error (module docs): Hairer's estimate filtered through the real
    /// block, positions and velocities, in the RMS of atol + rtol·|y|.
    #[allow(clippy::too_many_arguments)]
    fn error_estimate<M: NewtonMatrix<T, NQ, NV, NC>, const N: usize>(
        &self,
        system: &System<'_, M, T>,
        (rtol, atol): (T, T),
        from: &Point<T, NQ, NV, NC>,
        h: T,
        real: &M::NewtonStorage,
        stages: &Stages<'_, T, NQ, NV, NC>,
        mut vectors: Vectors<'_, T>,
    ) -> T {
        let mech = system.mechanism;
        let combine = |w: [f64; 3], k: usize| (0..3).fold(T::ZERO, |s, j| s + f::<T>(w[j]) * stages.acc[j][k]);
        let [r_q, x, f0, f1, a] = vectors.rows::<NV, 5>();
        let (rhs, e_q) = (vectors.take::<N>(), vectors.take::<NQ>());
        let c = h / f::<T>(GAMMA);
        // (M + c C + c² K) a − Dᵀμ = M (c² r_v + c r_q) + c² C r_q, with C r_q = −∂h/∂v r_q by a
        // difference of the forces along r_q.
        for k in 0..NV {
            r_q[k] = h * combine(E_Q, k);
            x[k] = c * c * (from.vd[k] + combine(E_V, k)) + c * r_q[k];
        }
        let (mx, rest) = rhs.split_at_mut(NV);
        mech.mass_times(&from.q, x, mx.try_into().expect("NV rows"));
        rest.fill(T::ZERO);
        let size = r_q.iter().fold(T::ZERO, |m, x| m.max(x.abs()));
        if size > T::ZERO {
            let v_scale = from.v.iter().fold(T::ONE, |m, x| m.max(x.abs()));
            let delta = T::EPSILON.sqrt() * v_scale / size;
            let forces = |v: &[T; NV], force: &mut [T; NV]| {
                mech.forces(&from.q, v, from.t, force);
                mech.friction_forces(&from.q, v, from.t, &from.lambda, force);
            };
            forces(&from.v, f0);
            for k in 0..NV {
                a[k] = from.v[k] + delta * r_q[k];
            }
            forces(a, f1);
            for k in 0..NV {
                rhs[k] -= c * c * (f1[k] - f0[k]) / delta;
            }
        }
        M::newton_solve(real, rhs);
        a.copy_from_slice(&rhs[..NV]);
        mech.position_rates(&from.q, a, e_q);
        let mut sum = T::ZERO;
        for k in 0..NQ {
            let scale = atol + rtol * from.q[k].abs().max(stages.q[2][k].abs());
            sum += (e_q[k] / scale).powi(2);
        }
        let rounding = position_ulps(&from.q, VELOCITY_ROUNDING_ULPS) / h;
        for k in 0..NV {
            let scale = atol + rtol * from.v[k].abs().max(stages.v[2][k].abs()) + rounding;
            sum += ((f::<T>(GAMMA) * a[k] / h - r_q[k]) / scale).powi(2);
        }
        (sum / T::from_f64((NQ + NV).max(1) as f64)).sqrt()
    }

    /// Takes the converged stages as the step to `to` and keeps them for the dense output and
    /// the next step's first guess.
    fn accept<M: NewtonMatrix<T, NQ, NV, NC>>(
        &mut self,
        system: &System<'_, M, T>,
        from: &Point<T, NQ, NV, NC>,
        (h, t1): (T, T),
        stages: &Stages<'_, T, NQ, NV, NC>,
        to: &mut Point<T, NQ, NV, NC>,
        mut scratch: DenseScratch<'_, T, NV, NC>,
    ) -> Result<(), SimulationError> {
        let mech = system.mechanism;
        let (q, v) = (&mut to.q, &mut to.v);
        *q = stages.q[2];
        *v = stages.v[2];
        mech.normalize_positions(q);
        // Onto Φ = 0 to what the scalar resolves (module docs, "The step's end"): Newton left Φ
        // within its stopping tolerance, a few mass-weighted steps (quadratic) take it to rounding.
        let resolution = crate::solvers::kinematics::resolution(q);
        let mut residual = T::ZERO;
        for _ in 0..END_PROJECTION_STEPS {
            residual = mech.project_positions_step_in(scratch.reborrow(), q, t1, &system.dynamics)?;
            if residual <= resolution {
                break;
            }
        }
        self.end_residual = None;
        if self.options.project_velocities {
            mech.project_velocities_in(scratch.reborrow(), q, v, t1, &system.dynamics)?;
            self.end_residual = Some(residual);
        }
        // v̇ and λ of the end point by forward dynamics there, not the last stage's A₃ and Λ₃
        // (module docs).
        to.power = system.derivatives_in(scratch, t1, &to.q, &to.v, &mut to.vd, &mut to.lambda)?;
        to.t = t1;
        check_step::<T, M, NQ, NV, NC>(from, to)?;
        super::implicit::accumulate_work(from, to, h);
        self.last = Some((from.t, h));
        self.accelerations = *stages.acc;
        self.multipliers = *stages.lam;
        self.stage_q = [stages.q[0], stages.q[1]];
        self.stage_v = [stages.v[0], stages.v[1]];
        self.accepted += 1;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tableau's constants against each other: a's rows sum to c, a² is a·a, T⁻¹ is T's
    /// inverse and turns a⁻¹ into diag(γ̂, [[α, −β], [β, α]]) (checked as a T = T Λ⁻¹), and the
    /// estimate's weights are aᵀd and (a²)ᵀd with dᵀc = −1 — to rounding (1e-14).
    #[test]
    fn the_tableau_is_consistent() {
        let close = |x: f64, y: f64| assert!((x - y).abs() < 1e-14, "{x} against {y}");
        let d = [-(13.0 + 7.0 * 6f64.sqrt()) / 3.0, (-13.0 + 7.0 * 6f64.sqrt()) / 3.0, -1.0 / 3.0];
        close(d.iter().zip(C).map(|(d, c)| d * c).sum(), -1.0);
        for i in 0..3 {
            close(A[i].iter().sum(), C[i]);
            close(E_V[i], (0..3).map(|k| A[k][i] * d[k]).sum());
            close(E_Q[i], (0..3).map(|k| A2[k][i] * d[k]).sum());
            for j in 0..3 {
                close(A2[i][j], (0..3).map(|k| A[i][k] * A[k][j]).sum());
                close((0..3).map(|k| TI[i][k] * T_[k][j]).sum(), if i == j { 1.0 } else { 0.0 });
            }
        }
        // Λ⁻¹ = diag(1/γ̂, [[α, −β], [β, α]]⁻¹).
        let m = ALPHA * ALPHA + BETA * BETA;
        let inverse = [[1.0 / GAMMA, 0.0, 0.0], [0.0, ALPHA / m, BETA / m], [0.0, -BETA / m, ALPHA / m]];
        for i in 0..3 {
            for j in 0..3 {
                close((0..3).map(|k| A[i][k] * T_[k][j]).sum(), (0..3).map(|k| T_[i][k] * inverse[k][j]).sum());
            }
        }
    }
}
