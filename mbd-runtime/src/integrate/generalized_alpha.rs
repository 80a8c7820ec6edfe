//! The generalized-α method (Chung & Hulbert 1993; Arnold & Brüls 2007) on the index-3
//! equations M v̇ − Dᵀλ = h, Φ = 0: [`GeneralizedAlpha`] and its [`GeneralizedAlphaOptions`].
//!
//! Implicit and second-order accurate, with numerical damping of high frequencies set by ρ∞:
//! α_m = (2ρ∞ − 1)/(ρ∞ + 1), α_f = ρ∞/(ρ∞ + 1), γ = ½ + α_f − α_m, β = ¼(γ + ½)². Each step
//! solves for (v̇₊, λ₊) by Newton in velocity space with the exact (∂h/∂q)B, ∂h/∂v and
//! ∂(Dᵀλ)/∂q·B (the equations are on [`GeneralizedAlpha`]); fit for stiff springs and dampers.

use super::implicit::{finish, solve, NewtonSettings, StateMap};
use super::{fixed_step, hermite_state, Integrator, Point, SimulationError, System};
use crate::model::mechanism::{Kinematics, NewtonMatrix};
use crate::model::workspace::WorkArrays;
use crate::real::Real;

crate::options::options! {
    /// Options of [`GeneralizedAlpha`], in the scalar type `T` of the mechanism (default `f64`).
    /// Build from [`Default`] and the `with_*` setters.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct GeneralizedAlphaOptions<T> {
        /// Step size h (s). Default 1e-3 s.
        step: T = T::from_f64(1e-3) => with_step,
        /// Spectral radius at infinite frequency ρ∞ ∈ [0, 1]: 1 adds no numerical damping, 0
        /// annihilates the highest frequencies in one step. Default 0.8. (With
        /// [`project_velocities`](Self::project_velocities), the default, each step still loses the
        /// kinetic energy of its O(h²) velocity violation: T + V falls by O((ωh)³ ωt), about as
        /// much as ρ∞ = 0.8's damping costs a slow mode.)
        rho_infinity: T = T::from_f64(0.8) => with_rho_infinity,
        /// Newton tolerance on ‖Φ‖∞ (m, rad) and on the position correction β'h²‖Δv̇‖∞ (m, rad).
        /// Default 1e-10, raised to what the scalar type resolves at q ([`crate::RESOLUTION_ULPS`]
        /// ε max(1, ‖q‖∞): 7.6e-6 in f32 at 1 m).
        tolerance: T = T::from_f64(1e-10) => with_tolerance,
        /// Newton tolerance on the multipliers, relative, measured by the constraint forces they
        /// exert: ‖DᵀΔλ‖∞ ≤ `lambda_tolerance` · (the force scale max(‖Dᵀλ‖∞, ‖h‖∞, ‖M v̇‖∞), N
        /// or N·m). Needed on its own: λ reaches the positions only through M⁻¹Dᵀ and β'h², so at
        /// small steps a λ wrong by percents moves q by less than `tolerance`. (Dᵀλ rather than λ:
        /// near a singular position the part of λ that exerts no force is rounding.) Default 1e-6:
        /// reactions to six digits; 1e-8 costs a third Newton iteration in most steps (2.9 against
        /// 2.0 on average on a 16-link chain at h = 1 ms). The force change is never asked below
        /// what one rounding of the positions makes, m · resolution/(β'h²) (m the largest mass or
        /// inertia): q₊ carries v̇₊ times β'h², so at small steps (1e-3 N per kg in f64 at 1e-5 s)
        /// and in f32 (25 N per kg at 1 ms) no iteration gets below it.
        lambda_tolerance: T = T::from_f64(1e-6) => with_lambda_tolerance,
        /// Newton iterations per step before failing. Default 12.
        max_iterations: u32 = 12 => with_max_iterations,
        /// Reuse the iteration matrix's factors within a step (modified Newton): the matrix factored
        /// at a step's first iteration serves the next ones while each correction is below a
        /// quarter of the one before (else it is evaluated and factored again). Default true: most
        /// steps then factor once instead of once per iteration — the iterate converges to the same
        /// tolerances, linearly instead of quadratically, which at these corrections (the
        /// predictor's error, O(h²)) costs no extra iteration in most steps.
        reuse_factors: bool = true => with_reuse_factors,
        /// Relative pivot tolerance of the LU of the iteration matrix ([`crate::sparse`]). Default
        /// 1e-13. A multiplier whose pivot is at most this times its scale Σ_c D_rc²/|u_cc| belongs
        /// to a dependent constraint row: with
        /// [`DynamicsOptions::allow_redundant`](crate::DynamicsOptions::allow_redundant) (the
        /// default) its Δλ is set to 0 for the rest of the step, otherwise the step fails naming it.
        /// A velocity whose pivot is at most this times its row's largest entry fails the step
        /// naming it ([`SimulationError::SingularIterationMatrix`]).
        pivot_tolerance: T = T::from_f64(1e-13) => with_pivot_tolerance,
        /// Project each step's velocities onto D v = ν in the metric of M
        /// ([`crate::ForwardDynamics::project_velocities`], one sparse Schur solve). The index-3 equations
        /// enforce Φ = 0 but leave D v − ν = O(h²); without damping (ρ∞ = 1) that error feeds an
        /// oscillation that grows with time at every step size (a pendulum's energy grew about 20×
        /// per second from t = 1 s until Newton failed at 5–9 s), and a coordinate-partitioning
        /// correction turns it into a first-order error. Default true.
        project_velocities: bool = true => with_project_velocities,
        /// Step-size control by a local error estimate: `None` (the default) takes fixed steps of
        /// [`step`](Self::step); `Some` makes `step` the first step tried and adapts the rest to
        /// the tolerances ([`ErrorControl`]).
        error_control: Option<ErrorControl<T>> = None => with_error_control,
    }
}

crate::options::options! {
    /// Tolerances and step limits of the variable-step generalized-α method
    /// ([`GeneralizedAlphaOptions::error_control`]).
    ///
    /// The local error of a step is estimated from the pseudo-accelerations: with δ = α_m − α_f,
    /// q₊'s Taylor expansion leaves e = (1/12 + δ²/4) h³ q⃛ + O(h⁴), and a₊ − a = h q⃛ + O(h²), so
    ///
    /// ```text
    /// e ≈ (1/12 + δ²/4) h² (a₊ − a)
    /// ```
    ///
    /// (for Newmark's scheme, δ = 0 and β free, this is Zienkiewicz & Xie's (1991) estimate
    /// (β − 1/6) h² (a₊ − a); here β = ¼(1 − δ)²), measured on the coordinates (q₊ ⊕ e − q₊) in
    /// the RMS of the mixed tolerance atol + rtol·max(|q|, |q₊|), as [`Dopri5`](crate::Dopri5)
    /// measures its error (only the positions: the method's velocity error is of the same order but
    /// has no estimate this cheap).
    /// By default ([`per_unit_time`](Self::per_unit_time)) that RMS is divided by h/(1 s): a step
    /// is accepted when its error is at most h/(1 s) times the tolerance, and the next one is
    /// h · clamp(0.9 err^(−1/2), 0.2, 2); the global error is then proportional to the tolerance
    /// (measured within 21× of rtol on the study's six cases from 1e-4 to 1e-8,
    /// `mbd-study/results/proportionality.md`). Bounding the error per step instead (accepted at
    /// RMS ≤ 1, next step h · clamp(0.9 err^(−1/3), 0.2, 2)) takes far fewer steps, but a
    /// second-order method's global error then falls only like rtol^(2/3) and exceeds rtol by
    /// 10³–10⁵ on those cases. A step whose Newton iteration fails to converge is retried at a
    /// quarter of its size. On a step-size change the pseudo-acceleration's lag a − v̇ ≈ δ h q⃛ is
    /// rescaled to the new step (a ← v̇ + (h₊/h)(a − v̇)), so the method stays second-order.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct ErrorControl<T> {
        /// Relative tolerance on each coordinate. Default 1e-6.
        rtol: T = T::from_f64(1e-6) => with_rtol,
        /// Absolute tolerance (m, rad). Default 1e-8.
        atol: T = T::from_f64(1e-8) => with_atol,
        /// Largest step size (s). Default 0.1 s.
        max_step: T = T::from_f64(0.1) => with_max_step,
        /// Smallest step size before failing with [`SimulationError::StepSizeTooSmall`]. Default
        /// 1e-12 s.
        min_step: T = T::from_f64(1e-12) => with_min_step,
        /// Bound the error per second of simulated time instead of per step (error per unit
        /// step, Shampine): a step of h is accepted when its estimate is at most h/(1 s) times
        /// the tolerance. The local errors of a second-order method then add up to a global error
        /// proportional to the tolerance (about rtol per second of motion, times how much the
        /// motion amplifies an error) instead of to rtol^(2/3), at the cost of about rtol^(−1/2)
        /// steps instead of rtol^(−1/3): on a 4-link chain over 1 s, error 9.2 rtol in 19 ms at
        /// rtol 1e-6, against 6 000 rtol in 0.85 ms per step. Newton's position tolerance is
        /// lowered to each step's allowance h (atol + rtol ‖q‖∞); where that is below what the
        /// positions resolve (in f64: at rtol 1e-10 on five of the study's six cases, on none at
        /// 1e-8) the run fails with
        /// [`SimulationError::ToleranceBelowResolution`]. Default true (since 2026-12-02; before,
        /// the error was bounded per step).
        per_unit_time: bool = true => with_per_unit_time,
    }
}

impl<T: Real> GeneralizedAlphaOptions<T> {
    /// The Newton iteration's settings.
    fn newton(&self) -> NewtonSettings<T> {
        NewtonSettings {
            tolerance: self.tolerance,
            lambda_tolerance: self.lambda_tolerance,
            max_iterations: self.max_iterations,
            reuse_factors: self.reuse_factors,
            pivot_tolerance: self.pivot_tolerance,
            project_velocities: self.project_velocities,
            end_position_step: false,
        }
    }
}

impl<T: Real> ErrorControl<T> {
    /// See [`check_step_control`](super::dopri5::check_step_control).
    fn check(&self) -> Result<(), SimulationError> {
        super::dopri5::check_step_control(
            [self.rtol, self.atol, self.max_step, self.min_step],
            [
                "rtol and atol (ErrorControl) must be non-negative, not both zero",
                "ErrorControl::max_step must be positive, min_step non-negative",
            ],
        )
    }
}

/// The generalized-α method on the index-3 equations of motion (Chung & Hulbert 1993; Arnold &
/// Brüls 2007, as in Chrono and Exudyn), in velocity space: with pseudo-accelerations a,
///
/// ```text
/// (1 − α_m) a₊ + α_m a = (1 − α_f) v̇₊ + α_f v̇
/// q₊ = q ⊕ (h v + h² (½ − β) a + h² β a₊),     v₊ = v + h (1 − γ) a + h γ a₊
/// M v̇₊ − Dᵀ λ₊ = h(q₊, v₊, t₊),               Φ(q₊, t₊) = 0
/// ```
///
/// (q ⊕ Δ is [`Kinematics::integrate_positions`] with h = 1 from q; planar: q + Δ), solved for
/// (v̇₊, λ₊) by Newton with the exact iteration matrix
/// [[M − γ'h ∂h/∂v − β'h² ((∂h/∂q)B + ∂(Dᵀλ)/∂q·B), −Dᵀ], [D, 0]] (β' = β(1−α_f)/(1−α_m),
/// γ' = γ(1−α_f)/(1−α_m); the constraint rows scaled by 1/(β'h²)). h includes Coulomb friction
/// at the iterate's λ, with its exact derivatives in q and v ([`Dynamics::friction_derivatives`])
/// and its slope in the loads beside −Dᵀ ([`Dynamics::friction_multiplier_derivatives`]). Where a
/// full Newton step makes the residual ‖r‖₂ grow — a saturating law such as regularized friction
/// near sticking makes Newton overshoot and cycle — the step is halved, up to six times.
/// The iteration matrix is built and factored in the sparse storage whose order and fill
/// `mechanism!` planned ([`NewtonMatrix`], [`crate::sparse`]), in the [`Workspace`](crate::Workspace)'s first
/// Newton slot (O(its non-zeros), no dense matrix; the work space must be the mechanism's,
/// `Name::workspace()`); the integrator itself holds O(NV).
///
/// [`Kinematics::integrate_positions`]: crate::Kinematics::integrate_positions
///
/// [`Dynamics::friction_derivatives`]: crate::Dynamics::friction_derivatives
/// [`Dynamics::friction_multiplier_derivatives`]: crate::Dynamics::friction_multiplier_derivatives
#[derive(Clone, Copy, Debug)]
pub struct GeneralizedAlpha<T, const NV: usize> {
    /// Step size, damping and Newton options.
    pub options: GeneralizedAlphaOptions<T>,
    /// Newton iterations of the last step.
    pub iterations: u32,
    /// Newton iterations of every step so far, rejected ones included (each evaluates the
    /// residual once).
    pub total_iterations: u64,
    /// Steps accepted so far.
    pub accepted: u64,
    /// Steps rejected so far by the error control (too large an error, or Newton failing).
    pub rejected: u64,
    /// With error control, the step size the next step will try (s); 0 before the first.
    pub next_step: T,
    // Pseudo-acceleration a of the last point, the step that produced it, and whether it is valid.
    a: [T; NV],
    last_step: T,
    started: bool,
}

impl<T: Real, const NV: usize> GeneralizedAlpha<T, NV> {
    /// A generalized-α integrator for a mechanism with NV velocities.
    pub fn new(options: GeneralizedAlphaOptions<T>) -> Self {
        Self {
            options,
            iterations: 0,
            total_iterations: 0,
            accepted: 0,
            rejected: 0,
            next_step: T::ZERO,
            a: [T::ZERO; NV],
            last_step: T::ZERO,
            started: false,
        }
    }

    /// Forget the pseudo-accelerations and the step size: the next step starts from v̇ of its
    /// initial point and from [`GeneralizedAlphaOptions::step`] (call after changing the state
    /// by hand).
    pub fn restart(&mut self) {
        self.started = false;
        self.next_step = T::ZERO;
    }

    /// The pseudo-acceleration a to step from with a step of h: v̇ at the start; after a step
    /// of h₀, a − v̇ ≈ δ h₀ q⃛ rescaled to δ h q⃛ (a no-op at a constant step).
    /// Into `a`.
    fn pseudo_acceleration(&self, vd: &[T; NV], h: T, a: &mut [T; NV]) {
        if !self.started {
            *a = *vd;
        } else if h == self.last_step {
            *a = self.a;
        } else {
            let ratio = h / self.last_step;
            for (i, x) in a.iter_mut().enumerate() {
                *x = vd[i] + ratio * (self.a[i] - vd[i]);
            }
        }
    }
}

impl<T: Real, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize> Integrator<T, M, NQ, NV, NC, N, NS>
    for GeneralizedAlpha<T, NV>
where
    M: NewtonMatrix<T, NQ, NV, NC>,
{
    /// Its Newton solves Φ(q₊, t₊) = 0 at every step (measured: a parallelogram chain kept its
    /// branch to 3e-12 rad through 50 flat positions at h = 1 ms without a correction).
    fn holds_constraints(&self) -> bool {
        true
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
        let ([s, _, _], mut dense) = super::implicit::newton_space::<T, M, NQ, NV, NC, N, NS>(ws)?;
        // The pseudo-accelerations at the start and the end, and the error estimate's vectors
        // (each written whole before it is read).
        let [a_n, a1, e] = dense.vectors.rows_written::<NV, 3>();
        let [shifted] = dense.vectors.rows_written::<NQ, 1>();
        let mut o = self.options;
        // Φ and the position correction to what the scalar type resolves at q (f32: 64 ε ≈ 7.6e-6
        // at 1 m), so the default 1e-10 converges in single precision.
        let resolution = crate::solvers::kinematics::resolution(&from.q);
        let scale = from.q.iter().fold(T::ONE, |m, x| m.max(x.abs()));
        o.tolerance = o.tolerance.max(resolution);
        if !(o.step > T::ZERO) {
            return Err(SimulationError::InvalidOptions { what: "GeneralizedAlphaOptions::step must be positive" });
        }
        if !(o.rho_infinity >= T::ZERO && o.rho_infinity <= T::ONE) {
            return Err(SimulationError::InvalidOptions { what: "GeneralizedAlphaOptions::rho_infinity must be in [0, 1]" });
        }
        let mech = system.mechanism;
        let one = T::ONE;
        let half = T::from_f64(0.5);
        let rho = o.rho_infinity;
        let alpha_m = (T::from_f64(2.0) * rho - one) / (rho + one);
        let alpha_f = rho / (rho + one);
        let gamma = half + alpha_f - alpha_m;
        let beta = T::from_f64(0.25) * (gamma + half) * (gamma + half);
        let coefficients = [alpha_m, alpha_f, beta, gamma];
        // δ = α_m − α_f: the local error constant of the positions is 1/12 + δ²/4.
        let delta = alpha_m - alpha_f;
        let constant = T::from_f64(1.0 / 12.0) + T::from_f64(0.25) * delta * delta;
        // Fixed steps: one attempt of `step`. With error control: from the step the last one
        // chose, retried smaller until its error estimate meets the tolerance.
        let mut h = match &o.error_control {
            None => o.step,
            Some(control) => {
                control.check()?;
                if self.next_step > T::ZERO { self.next_step } else { o.step }.min(control.max_step)
            }
        };
        loop {
            let (h_try, t1) = fixed_step(from.t, h, t_max);
            if !(h_try > T::ZERO) {
                to.copy_from(from);
                return Ok(());
            }
            self.pseudo_acceleration(&from.vd, h_try, a_n);
            self.iterations = 0;
            let map = AlphaMap { from, a_n, coefficients, h: h_try };
            let mut newton = o.newton();
            // Per unit time the estimate must resolve the step's allowance h (atol + rtol ‖q‖∞)
            // (m, rad), and it carries Newton's position residual (times C/β' ≈ 0.34 at
            // ρ∞ = 0.8): Newton stops below it. (‖q‖∞ as in `resolution`, which grows with it.)
            let allowance = o.error_control.filter(|c| c.per_unit_time).map(|c| h_try * (c.atol + c.rtol * scale));
            if let Some(allowance) = allowance {
                newton.tolerance = newton.tolerance.min(allowance).max(resolution);
            }
            let result = solve::<T, M, _, NQ, NV, NC, N>(
                system,
                &newton,
                resolution,
                &map,
                &from.vd,
                from,
                t1,
                to,
                &mut self.iterations,
                &mut None,
                s,
                dense.reborrow(),
            )
            .map(|_| map.pseudo_acceleration(&to.vd, a1));
            self.total_iterations += u64::from(self.iterations);
            let Some(control) = o.error_control else {
                result?;
                self.accept(a1, h_try);
                return finish(system, dense.reborrow(), from, to, h_try);
            };
            let factor = match result {
                Ok(()) => {
                    let mut error = local_error(mech, &control, constant, h_try, (a_n, a1), (&from.q, &to.q), (e, shifted));
                    // The estimate is O(h³); per second of motion, O(h²).
                    let order = if control.per_unit_time {
                        error /= h_try;
                        T::from_f64(2.0)
                    } else {
                        T::from_f64(3.0)
                    };
                    // 0.9 err^(−1/order): the step that would have met the tolerance, with a
                    // margin (a quarter where the estimate is not finite).
                    let factor = if error.is_finite() {
                        (T::from_f64(0.9) * error.powf(-T::ONE / order)).max(T::from_f64(0.2))
                    } else {
                        T::from_f64(0.25)
                    };
                    if error <= one {
                        // A step shortened to land on the end keeps the size it would have had.
                        self.next_step = h.max(h_try) * factor.min(T::from_f64(2.0));
                        self.accept(a1, h_try);
                        return finish(system, dense.reborrow(), from, to, h_try);
                    }
                    factor
                }
                // A Newton iteration that does not settle or that diverges: a smaller step.
                Err(SimulationError::NotConverged { .. } | SimulationError::NonFinite { .. }) => T::from_f64(0.25),
                Err(e) => return Err(e),
            };
            self.rejected += 1;
            h = h_try * factor;
            if !(h >= control.min_step) {
                // Per unit time, steps whose allowance is below the resolution have an estimate
                // that is rounding: that, not the motion, is what failed.
                if allowance.is_some_and(|a| a < resolution) {
                    return Err(SimulationError::ToleranceBelowResolution {
                        t: from.t.to_f64(),
                        step: h_try.to_f64(),
                        rtol: control.rtol.to_f64(),
                    });
                }
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
        // The cubic Hermite interpolant needs the step's ends only.
        Ok(())
    }

    fn interpolate(&self, mechanism: &M, from: &Point<T, NQ, NV, NC>, to: &Point<T, NQ, NV, NC>, t: T, q: &mut [T; NQ], v: &mut [T; NV]) {
        hermite_state(mechanism, from, to, t, q, v);
    }

    fn restart(&mut self) {
        GeneralizedAlpha::restart(self);
    }

    /// v̇ and λ are unknowns of the method: the corrected point keeps them (and the powers of the
    /// step's end), and only q and v change.
    fn after_correction(
        &mut self,
        _system: &System<'_, M, T>,
        _ws: &mut WorkArrays<T, NV, NC, N, NS>,
        _to: &mut Point<T, NQ, NV, NC>,
    ) -> Result<(), SimulationError> {
        Ok(())
    }
}

impl<T: Real, const NV: usize> GeneralizedAlpha<T, NV> {
    /// Takes an accepted step of h ending with pseudo-acceleration a₊.
    fn accept(&mut self, a1: &[T; NV], h: T) {
        self.a = *a1;
        self.last_step = h;
        self.started = true;
        self.accepted += 1;
    }
}

/// The RMS of the estimated local position error (1/12 + δ²/4) h² (a₊ − a), mapped to the
/// coordinates at q₊ (q₊ ⊕ e − q₊), in the mixed tolerance atol + rtol·max(|q|, |q₊|).
#[allow(clippy::too_many_arguments)]
fn local_error<T: Real, M: Kinematics<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize>(
    mech: &M,
    control: &ErrorControl<T>,
    constant: T,
    h: T,
    (a_n, a1): (&[T; NV], &[T; NV]),
    (q0, q1): (&[T; NQ], &[T; NQ]),
    (e, shifted): (&mut [T; NV], &mut [T; NQ]),
) -> T {
    for i in 0..NV {
        e[i] = constant * h * h * (a1[i] - a_n[i]);
    }
    *shifted = *q1;
    mech.integrate_positions(shifted, e, T::ONE);
    let mut sum = T::ZERO;
    for i in 0..NQ {
        let scale = control.atol + control.rtol * q0[i].abs().max(q1[i].abs());
        let r = (shifted[i] - q1[i]) / scale;
        sum += r * r;
    }
    (sum / T::from_f64(NQ.max(1) as f64)).sqrt()
}

/// Generalized-α's step end from v̇₊ (from `from`, with pseudo-acceleration `a_n`, a step of
/// `h` and `coefficients` = [α_m, α_f, β, γ]): the pseudo-acceleration a₊,
/// q₊ = q ⊕ (h v + h²(½ − β) a + h² β a₊) on the group ([`integrate_on_group`]) and
/// v₊ = v + h (1 − γ) a + h γ a₊.
///
/// [`integrate_on_group`]: crate::model::group::integrate_on_group
struct AlphaMap<'a, T, const NQ: usize, const NV: usize, const NC: usize> {
    from: &'a Point<T, NQ, NV, NC>,
    a_n: &'a [T; NV],
    coefficients: [T; 4],
    h: T,
}

impl<T: Real, const NQ: usize, const NV: usize, const NC: usize> AlphaMap<'_, T, NQ, NV, NC> {
    /// Δ = h v + h² (½ − β) a + h² β a₊ in place of the pseudo-acceleration a₊ in `a1`.
    fn increment(&self, a1: &mut [T; NV]) {
        let [_, _, beta, _] = self.coefficients;
        let (half, h, a) = (T::from_f64(0.5), self.h, self.a_n);
        for (i, x) in a1.iter_mut().enumerate() {
            *x = h * self.from.v[i] + h * h * ((half - beta) * a[i] + beta * *x);
        }
    }

    /// a₊ from (1 − α_m) a₊ + α_m a = (1 − α_f) v̇₊ + α_f v̇, into `a1`.
    fn pseudo_acceleration(&self, vd: &[T; NV], a1: &mut [T; NV]) {
        let [alpha_m, alpha_f, ..] = self.coefficients;
        let one = T::ONE;
        for (i, x) in a1.iter_mut().enumerate() {
            *x = (alpha_f * self.from.vd[i] + (one - alpha_f) * vd[i] - alpha_m * self.a_n[i]) / (one - alpha_m);
        }
    }
}

impl<T: Real, M: Kinematics<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize> StateMap<T, M, NQ, NV, NC>
    for AlphaMap<'_, T, NQ, NV, NC>
{
    /// (γ'h, β'h²) with β' = β(1 − α_f)/(1 − α_m), γ' = γ(1 − α_f)/(1 − α_m).
    fn slopes(&self) -> (T, T) {
        let [alpha_m, alpha_f, beta, gamma] = self.coefficients;
        let ratio = (T::ONE - alpha_f) / (T::ONE - alpha_m);
        (gamma * ratio * self.h, beta * ratio * self.h * self.h)
    }

    fn state(&self, mechanism: &M, vd: &[T; NV], q: &mut [T; NQ], v: &mut [T; NV], work: &mut [T; NV]) {
        let [_, _, _, gamma] = self.coefficients;
        let (one, h) = (T::ONE, self.h);
        let (from, a) = (self.from, self.a_n);
        let a1 = work;
        self.pseudo_acceleration(vd, a1);
        for i in 0..NV {
            v[i] = from.v[i] + h * ((one - gamma) * a[i] + gamma * a1[i]);
        }
        *q = from.q;
        self.increment(a1);
        crate::model::group::integrate_on_group(mechanism, q, a1);
    }

    /// Δ = h v + h² (½ − β) a + h² β a₊: q₊ = q ⊕ Δ.
    fn displacement(&self, vd: &[T; NV], out: &mut [T; NV]) -> bool {
        self.pseudo_acceleration(vd, out);
        self.increment(out);
        true
    }
}
