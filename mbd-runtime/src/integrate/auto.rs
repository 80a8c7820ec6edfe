//! The stiff-aware default: [`Auto`] and its [`AutoOptions`] (issue 39, item 2). It runs
//! [`Dopri5`] while the model is not stiff and [`Bdf`] while it is, switching as LSODA does
//! (Petzold 1983) on estimates of the fastest mode:
//!
//! * **to BDF** when DOPRI5's own stiffness test fires ([`StiffnessDetected`]: h|λ| at its
//!   stability bound, 3.25, for 15 accepted steps; Hairer & Wanner, *Solving ODEs II*, IV.2).
//!   The fast mode's rate ρ = |λ| is kept, and BDF starts at order 1 from DOPRI5's last step.
//! * **back to DOPRI5** when the fast mode has gone: 8 BDF steps after the switch, ρ is
//!   estimated again at the step's end by three power iterations on the ODE's Jacobian
//!   J = ∂(q̇, v̇)/∂(q, v) by differences of forward dynamics (four evaluations, from the
//!   direction of BDF's last error estimate) — and again after twice as many steps each time it
//!   held (up to 64), after 8 where it fell by half — and where it is below a tenth of ρ at the
//!   switch, with DOPRI5's stable step
//!   3.25/ρ above BDF's step, at two probes in a row, DOPRI5 goes on at BDF's step. A stiff
//!   element that let go (a contact, a cable gone slack) gives back the explicit method's
//!   steps; a stiff mode still there keeps BDF, even where BDF's steps are short for accuracy
//!   (its error constants are larger than DOPRI5's).
//! * **back to DOPRI5 where BDF cannot go on**: a BDF step whose size falls below `min_step`
//!   is taken by DOPRI5 instead ([`Auto::fallbacks`] counts them), and the next switch waits
//!   for twice as many stiffness detections as the last. BDF's first step after a switch is of
//!   order 1, whose multipliers are O(1) off in motion ([`Bdf`]'s docs); where Coulomb friction
//!   reads them — a plank bridge on two rubbing pins, 9 ms into its swing — that step must be
//!   short (about 1e-8 s there), and before BDF's velocities had a rounding allowance no step
//!   size met its error test (issue 39). A collapse of BDF's step does not stop `Auto`; where
//!   it recurs, the run is no faster than DOPRI5.
//!
//! Both methods take the same rtol and atol. Where nothing is stiff, a run is DOPRI5's, step for
//! step (the stiffness test is free); a stiff run pays DOPRI5's first 15 steps at the stability
//! bound, then takes BDF's steps. What each costs is in the user's guide's integrator table (`guide/dynamics.md`) and the
//! study (`cargo run --release -p mbd-study`).

use super::stiffness::StiffnessDetected;
use super::{Bdf, BdfOptions, Dopri5, Dopri5Options, Integrator, Point, SimulationError, System};
use crate::model::mechanism::NewtonMatrix;
use crate::model::workspace::{DenseScratch, WorkArrays};
use crate::real::Real;

/// BDF steps between two estimates of the fastest mode's rate after a switch, and where the
/// rate fell by half since the last; each estimate that finds it held doubles the interval, up
/// to [`PROBE_AT_MOST_EVERY`]. A probe costs about four BDF steps' evaluations: every 8 steps
/// it was 5 % of the stiff flywheel's run, whose stiff mode stays.
const PROBE_EVERY: u32 = 8;
/// The longest interval between two estimates (BDF steps).
const PROBE_AT_MOST_EVERY: u32 = 64;
/// DOPRI5's stability bound on the negative real axis (h|λ|).
const DOPRI5_BOUND: f64 = 3.25;

crate::options::options! {
    /// Options of [`Auto`], in the scalar type `T` of the mechanism (default `f64`). Build from
    /// [`Default`] and the `with_*` setters. The defaults are [`Dopri5Options`]'.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct AutoOptions<T> {
        /// Relative tolerance on each coordinate and velocity, of both methods. Default 1e-8.
        rtol: T = T::from_f64(1e-8) => with_rtol,
        /// Absolute tolerance (m, rad, m/s, rad/s), of both methods. Default 1e-10.
        atol: T = T::from_f64(1e-10) => with_atol,
        /// Largest step size (s). Default 0.1 s.
        max_step: T = T::from_f64(0.1) => with_max_step,
        /// Smallest step size before failing with [`SimulationError::StepSizeTooSmall`]. Default
        /// 1e-12 s.
        min_step: T = T::from_f64(1e-12) => with_min_step,
        /// Go back to DOPRI5 where the stiffness has gone (module docs). Default true.
        switch_back: bool = true => with_switch_back,
    }
}

/// Which method takes the steps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AutoPhase {
    /// DOPRI5: the model is not stiff.
    Explicit,
    /// BDF: a fast mode holds DOPRI5's steps.
    Stiff,
}

/// DOPRI5 while the model is not stiff, BDF while it is (module docs): the integrator to start
/// with when you do not know. Its work space must be the mechanism's (`Name::workspace()`), for
/// BDF's Newton iteration.
#[derive(Clone, Copy, Debug)]
pub struct Auto<T, const NQ: usize, const NV: usize, const NC: usize> {
    /// Tolerances and step limits.
    pub options: AutoOptions<T>,
    /// The explicit method, with its counts.
    pub explicit: Dopri5<T, NQ, NV>,
    /// The stiff method, with its counts.
    pub stiff: Bdf<T, NQ, NV>,
    /// The method of the next step.
    pub phase: AutoPhase,
    /// Switches to BDF so far.
    pub switches: u32,
    /// The first switch to BDF: where DOPRI5 saw the model stiff.
    pub first_stiff: Option<StiffnessDetected>,
    /// Steps BDF could not take (its step size fell below `min_step`), which DOPRI5 took
    /// instead (module docs).
    pub fallbacks: u32,
    /// The method that took the last step (its dense output and correction are the step's).
    last: AutoPhase,
    /// DOPRI5's detections acted on, and how many more it takes to switch again (doubled by
    /// each fallback).
    seen: u32,
    patience: u32,
    /// The fastest mode's rate (1/s), from the last estimate.
    rate: T,
    /// BDF steps since its start or the last probe, the steps until the next, and probes in a
    /// row that allowed DOPRI5.
    since_probe: u32,
    probe_every: u32,
    calm: u32,
    /// The fastest mode's rate (1/s) when DOPRI5 saw the model stiff.
    switch_rate: T,
    /// BDF has not stepped since the switch to it.
    fresh: bool,
    /// BDF's first step's start after a switch: the step's start on the constraints.
    start: Point<T, NQ, NV, NC>,
}

impl<T: Real, const NQ: usize, const NV: usize, const NC: usize> Auto<T, NQ, NV, NC> {
    /// The integrator with the given options, starting with DOPRI5.
    pub fn new(options: AutoOptions<T>) -> Self {
        let o = options;
        let explicit =
            Dopri5::new(Dopri5Options::default().with_rtol(o.rtol).with_atol(o.atol).with_max_step(o.max_step).with_min_step(o.min_step));
        let stiff = Bdf::new(BdfOptions::default().with_rtol(o.rtol).with_atol(o.atol).with_max_step(o.max_step).with_min_step(o.min_step));
        Self {
            options,
            explicit,
            stiff,
            phase: AutoPhase::Explicit,
            switches: 0,
            first_stiff: None,
            fallbacks: 0,
            last: AutoPhase::Explicit,
            seen: 0,
            patience: 1,
            rate: T::ZERO,
            since_probe: 0,
            probe_every: PROBE_EVERY,
            calm: 0,
            switch_rate: T::ZERO,
            fresh: false,
            start: Point::zero(),
        }
    }

    /// Steps accepted by both methods.
    pub fn accepted(&self) -> u64 {
        self.explicit.accepted + self.stiff.accepted
    }
}

impl<T: Real, const NQ: usize, const NV: usize, const NC: usize> Auto<T, NQ, NV, NC> {
    /// BDF could not take the step from `from`: DOPRI5 takes it and goes on, and DOPRI5's
    /// stiffness test must fire twice as often as before for the next switch.
    fn fall_back<M: NewtonMatrix<T, NQ, NV, NC>, const N: usize, const NS: usize>(
        &mut self,
        system: &System<'_, M, T>,
        ws: &mut WorkArrays<T, NV, NC, N, NS>,
        from: &Point<T, NQ, NV, NC>,
        t_max: T,
        to: &mut Point<T, NQ, NV, NC>,
    ) -> Result<(), SimulationError> {
        self.fallbacks += 1;
        self.patience = self.patience.saturating_mul(2);
        (self.phase, self.last, self.fresh) = (AutoPhase::Explicit, AutoPhase::Explicit, false);
        self.explicit.watch_again();
        Integrator::<T, M, NQ, NV, NC, N, NS>::step(&mut self.explicit, system, ws, from, t_max, to)
    }
}

impl<T: Real, const NQ: usize, const NV: usize, const NC: usize> Default for Auto<T, NQ, NV, NC> {
    fn default() -> Self {
        Self::new(AutoOptions::default())
    }
}

impl<T: Real, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize> Integrator<T, M, NQ, NV, NC, N, NS>
    for Auto<T, NQ, NV, NC>
where
    M: NewtonMatrix<T, NQ, NV, NC>,
{
    /// While BDF takes the steps, Newton solves Φ = 0 at each.
    fn holds_constraints(&self) -> bool {
        self.phase == AutoPhase::Stiff
    }

    /// Where BDF took the last step, BDF's.
    fn projected_end(&self) -> Option<T> {
        (self.last == AutoPhase::Stiff).then(|| Integrator::<T, M, NQ, NV, NC, N, NS>::projected_end(&self.stiff)).flatten()
    }

    fn step(
        &mut self,
        system: &System<'_, M, T>,
        ws: &mut WorkArrays<T, NV, NC, N, NS>,
        from: &Point<T, NQ, NV, NC>,
        t_max: T,
        to: &mut Point<T, NQ, NV, NC>,
    ) -> Result<(), SimulationError> {
        self.last = self.phase;
        match self.phase {
            AutoPhase::Explicit => {
                Integrator::<T, M, NQ, NV, NC, N, NS>::step(&mut self.explicit, system, ws, from, t_max, to)?;
                let found = Integrator::<T, M, NQ, NV, NC, N, NS>::stiffness(&self.explicit);
                if let Some(found) = found.filter(|f| f.times >= self.seen + self.patience) {
                    self.seen = found.times;
                    self.first_stiff.get_or_insert(found);
                    self.switches += 1;
                    self.phase = AutoPhase::Stiff;
                    self.rate = T::from_f64(found.h_lambda / found.step);
                    self.switch_rate = self.rate;
                    self.stiff.next_step = to.t - from.t;
                    self.stiff.restart();
                    (self.since_probe, self.probe_every, self.calm, self.fresh) = (0, PROBE_EVERY, 0, true);
                }
            }
            AutoPhase::Stiff => {
                if self.fresh {
                    // BDF's first step solves Φ = 0 and projects v: from DOPRI5's end, whose drift
                    // its error test would count, it starts on the constraints.
                    let start = &mut self.start;
                    start.copy_from(from);
                    super::simulate::project_in(
                        system.mechanism,
                        ws.dense(),
                        start.t,
                        &mut start.q,
                        &mut start.v,
                        &system.dynamics,
                        self.stiff.options.tolerance,
                        10,
                    )?;
                    system.complete_in(ws.dense(), start)?;
                }
                let start = if self.fresh { &self.start } else { from };
                match Integrator::<T, M, NQ, NV, NC, N, NS>::step(&mut self.stiff, system, ws, start, t_max, to) {
                    Err(SimulationError::StepSizeTooSmall { .. }) => return self.fall_back(system, ws, from, t_max, to),
                    result => result?,
                }
                self.fresh = false;
                self.since_probe += 1;
                if self.options.switch_back && self.since_probe >= self.probe_every {
                    self.since_probe = 0;
                    if let Some(rate) = fastest_rate(system, ws.dense(), to, self.stiff.last_error()) {
                        let falling = rate < T::from_f64(0.5) * self.rate;
                        self.probe_every = if falling { PROBE_EVERY } else { (2 * self.probe_every).min(PROBE_AT_MOST_EVERY) };
                        self.rate = rate;
                    }
                    let h = to.t - from.t;
                    // The mode that made the switch has slowed tenfold (the stiff element let
                    // go), and DOPRI5 would be stable at BDF's step.
                    let gone = T::from_f64(10.0) * self.rate < self.switch_rate && T::from_f64(DOPRI5_BOUND) > h * self.rate;
                    self.calm = if gone { self.calm + 1 } else { 0 };
                    if self.calm >= 2 {
                        self.phase = AutoPhase::Explicit;
                        self.explicit.next_step = h;
                        self.explicit.watch_again();
                        self.calm = 0;
                    }
                }
            }
        }
        Ok(())
    }

    fn prepare_interpolation(
        &mut self,
        system: &System<'_, M, T>,
        ws: &mut WorkArrays<T, NV, NC, N, NS>,
        from: &Point<T, NQ, NV, NC>,
        to: &Point<T, NQ, NV, NC>,
    ) -> Result<(), SimulationError> {
        match self.last {
            AutoPhase::Explicit => Integrator::<T, M, NQ, NV, NC, N, NS>::prepare_interpolation(&mut self.explicit, system, ws, from, to),
            AutoPhase::Stiff => Integrator::<T, M, NQ, NV, NC, N, NS>::prepare_interpolation(&mut self.stiff, system, ws, from, to),
        }
    }

    fn interpolate(&self, mechanism: &M, from: &Point<T, NQ, NV, NC>, to: &Point<T, NQ, NV, NC>, t: T, q: &mut [T; NQ], v: &mut [T; NV]) {
        match self.last {
            AutoPhase::Explicit => Integrator::<T, M, NQ, NV, NC, N, NS>::interpolate(&self.explicit, mechanism, from, to, t, q, v),
            AutoPhase::Stiff => Integrator::<T, M, NQ, NV, NC, N, NS>::interpolate(&self.stiff, mechanism, from, to, t, q, v),
        }
    }

    /// Restarts both methods; the phase stays (a switch event does not change the model's
    /// stiffness). A run that reuses the integrator starts in the phase the last one ended in.
    fn restart(&mut self) {
        Integrator::<T, M, NQ, NV, NC, N, NS>::restart(&mut self.explicit);
        self.stiff.restart();
    }

    fn after_correction(
        &mut self,
        system: &System<'_, M, T>,
        ws: &mut WorkArrays<T, NV, NC, N, NS>,
        to: &mut Point<T, NQ, NV, NC>,
    ) -> Result<(), SimulationError> {
        match self.last {
            AutoPhase::Explicit => Integrator::<T, M, NQ, NV, NC, N, NS>::after_correction(&mut self.explicit, system, ws, to),
            AutoPhase::Stiff => Integrator::<T, M, NQ, NV, NC, N, NS>::after_correction(&mut self.stiff, system, ws, to),
        }
    }

    /// None: the stiffness DOPRI5 saw was handed to BDF ([`Auto::first_stiff`],
    /// [`Auto::switches`]).
    fn stiffness(&self) -> Option<StiffnessDetected> {
        None
    }
}

/// The rate (1/s) of the fastest mode at the point `p`: three power iterations on J =
/// ∂(q̇, v̇)/∂(q, v) by differences of forward dynamics (from its value at `p`, not BDF's v̇,
/// which meets the equations only to Newton's tolerance), from the direction `seed` (BDF's
/// last error estimate); `None` where the seed is zero or an evaluation fails.
fn fastest_rate<T, M, const NQ: usize, const NV: usize, const NC: usize>(
    system: &System<'_, M, T>,
    mut scratch: DenseScratch<'_, T, NV, NC>,
    p: &Point<T, NQ, NV, NC>,
    seed: (&[T; NQ], &[T; NV]),
) -> Option<T>
where
    T: Real,
    M: NewtonMatrix<T, NQ, NV, NC>,
{
    let m = system.mechanism;
    let norm = |d: (&[T; NQ], &[T; NV])| d.0.iter().chain(d.1.iter()).fold(T::ZERO, |s, x| s + *x * *x).sqrt();
    let size = p.q.iter().chain(p.v.iter()).fold(T::ONE, |s, x| s.max(x.abs())) * T::from_f64(1e-6);
    let [qdot, moved_qdot, q, d_q] = scratch.vectors.rows::<NQ, 4>();
    let [base_vd, moved_vd, v, d_v] = scratch.vectors.rows::<NV, 4>();
    let lambda = scratch.vectors.take::<NC>();
    m.position_rates(&p.q, &p.v, qdot);
    system.derivatives_in(scratch.reborrow(), p.t, &p.q, &p.v, base_vd, lambda).ok()?;
    *d_q = *seed.0;
    *d_v = *seed.1;
    let mut rate = None;
    for _ in 0..3 {
        let n = norm((d_q, d_v));
        if !(n > T::ZERO && n.is_finite()) {
            return rate;
        }
        let scale = size / n;
        for i in 0..NQ {
            q[i] = p.q[i] + scale * d_q[i];
        }
        for i in 0..NV {
            v[i] = p.v[i] + scale * d_v[i];
        }
        lambda.fill(T::ZERO);
        system.derivatives_in(scratch.reborrow(), p.t, q, v, moved_vd, lambda).ok()?;
        m.position_rates(q, v, moved_qdot);
        for i in 0..NQ {
            d_q[i] = moved_qdot[i] - qdot[i];
        }
        for i in 0..NV {
            d_v[i] = moved_vd[i] - base_vd[i];
        }
        rate = Some(norm((d_q, d_v)) / size);
    }
    rate
}
