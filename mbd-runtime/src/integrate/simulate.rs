//! The driver: [`Simulation`] integrates with any [`Integrator`] to a list of output times,
//! corrects drift after each step ([`Correction`]: the mass-weighted [`project`]ion, or
//! coordinate partitioning, Nikravesh 13.6.2), interpolates each output with the step's dense
//! output and hands its [`Sample`] (state, v̇, λ and energies) to a callback; its
//! [`SimulationOptions`] and [`Statistics`].
//!
//! The initial state is corrected first (initial-condition correction, Nikravesh 14.3).
//!
//! Events: where a switching function changes sign within a step — a unilateral force element's
//! overlap ([`Dynamics::switching_function`](crate::Dynamics::switching_function)) or a user's
//! [`Event`] — the instant is located on the step's dense output (Illinois regula falsi) and the
//! step is taken again from its start to land on that instant, so that no step straddles a
//! switch and the force's kink is not smeared over a step ([`Simulation::events`]).

use core::ops::ControlFlow;

use super::{hermite, Energy, Integrator, Point, Sample, SimulationError, System};
use crate::integrate::branch::{BranchWatch, SingularPassage};
use crate::integrate::partition::Partition;
use crate::integrate::stiffness::StiffnessDetected;
use crate::model::dynamics::kinetic_energy_in;
use crate::model::dynamics::{DynamicsOptions, ForwardDynamics};
use crate::model::workspace::{DenseArrays, DenseScratch, WorkArrays, Workspace};
use crate::real::Real;
use crate::solvers::flow::Flow;
use crate::solvers::kinematics::name;

/// What brings the state back onto the constraint manifold after each step. Made by
/// [`Correction::projection`] or [`Correction::partitioning`] (or `Correction::None`), its
/// tolerance and iteration cap set by [`with_tolerance`](Self::with_tolerance) and
/// [`with_max_iterations`](Self::with_max_iterations).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Correction<T = f64> {
    /// Nothing (Baumgarte stabilization, if set, still acts through the accelerations).
    None,
    /// Mass-weighted projection (Newton on Φ = 0 with steps q ⊕ (−M⁻¹DᵀS⁻¹Φ), then the exact
    /// velocity projection), to ‖Φ‖∞ ≤ `tolerance`.
    #[non_exhaustive]
    Projection {
        /// On ‖Φ‖∞ (m, rad).
        tolerance: T,
        /// Newton steps before failing.
        max_iterations: u32,
    },
    /// Coordinate partitioning (Nikravesh 13.6.2) in velocity space: the integrated independent
    /// directions are kept; the dependent ones are solved from Φ = 0 (Newton steps q ⊕ Δv with
    /// Δv zero in the independent entries) and D v = ν. The partition is chosen by full
    /// pivoting on D at the start and again whenever its pivots degrade.
    #[non_exhaustive]
    Partitioning {
        /// On ‖Φ‖∞ (m, rad).
        tolerance: T,
        /// Newton steps before failing.
        max_iterations: u32,
    },
}

impl<T: Real> Correction<T> {
    /// Projection to 1e-10 in at most 10 Newton steps.
    pub fn projection() -> Self {
        Correction::Projection { tolerance: T::from_f64(1e-10), max_iterations: 10 }
    }
    /// Coordinate partitioning to 1e-10 in at most 10 Newton steps.
    pub fn partitioning() -> Self {
        Correction::Partitioning { tolerance: T::from_f64(1e-10), max_iterations: 10 }
    }

    /// Sets the tolerance on ‖Φ‖∞ (m, rad) of a projection or partitioning (nothing for
    /// `None`).
    #[must_use]
    pub fn with_tolerance(mut self, value: T) -> Self {
        match &mut self {
            Correction::None => {}
            Correction::Projection { tolerance, .. } | Correction::Partitioning { tolerance, .. } => *tolerance = value,
        }
        self
    }

    /// Sets the Newton steps of a projection or partitioning before it fails (nothing for
    /// `None`).
    #[must_use]
    pub fn with_max_iterations(mut self, value: u32) -> Self {
        match &mut self {
            Correction::None => {}
            Correction::Projection { max_iterations, .. } | Correction::Partitioning { max_iterations, .. } => *max_iterations = value,
        }
        self
    }
}

/// Projects q onto Φ(q, t) = 0 and v onto D v = ν in the metric of M (position steps
/// q ⊕ (−M⁻¹DᵀS⁻¹Φ), [`ForwardDynamics::project_positions_step`]).
///
/// # Errors
/// [`SimulationError::NotConverged`] if ‖Φ‖∞ stays above `tolerance` (raised to what the scalar
/// type resolves at q, see [`crate::RESOLUTION_ULPS`]); dynamics errors of the solve.
pub fn project<T: Real, M: ForwardDynamics<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize>(
    mechanism: &M,
    t: T,
    q: &mut [T; NQ],
    v: &mut [T; NV],
    options: &DynamicsOptions<T>,
    tolerance: T,
    max_iterations: u32,
) -> Result<(), SimulationError> {
    project_in(mechanism, DenseArrays::new().scratch(), t, q, v, options, tolerance, max_iterations)
}

/// [`project`] with the dense arrays of forward dynamics in `scratch` (a work space's).
#[allow(clippy::too_many_arguments)]
pub(crate) fn project_in<T: Real, M: ForwardDynamics<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize>(
    mechanism: &M,
    mut scratch: DenseScratch<'_, T, NV, NC>,
    t: T,
    q: &mut [T; NQ],
    v: &mut [T; NV],
    options: &DynamicsOptions<T>,
    tolerance: T,
    max_iterations: u32,
) -> Result<(), SimulationError> {
    let tolerance = tolerance.max(crate::solvers::kinematics::resolution(q));
    let mut iterations = 0;
    loop {
        if iterations == max_iterations {
            // No step left: measure where the last one ended.
            let phi = scratch.vectors.take::<NC>();
            mechanism.constraints(q, t, phi);
            let worst = phi.iter().enumerate().fold((0, T::ZERO), |w, (i, v)| if v.abs() > w.1 { (i, v.abs()) } else { w });
            if worst.1 <= tolerance {
                break;
            }
            return Err(SimulationError::NotConverged {
                t: t.to_f64(),
                newton: super::NewtonIteration::Projection,
                iterations,
                worst_row: name(M::CONSTRAINT_NAMES, worst.0),
                residual: worst.1.to_f64(),
            });
        }
        let residual = mechanism.project_positions_step_in(scratch.reborrow(), q, t, options)?;
        if residual <= tolerance {
            // The step just taken was below tolerance too: keep it (it only helps).
            break;
        }
        iterations += 1;
    }
    mechanism.project_velocities_in(scratch, q, v, t, options)?;
    Ok(())
}

/// Statistics of a [`Simulation`] run.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct Statistics {
    /// Steps taken (accepted).
    pub steps: u64,
    /// Samples handed to the callback.
    pub samples: u64,
    /// Events located (steps landed on a switch or a user's event).
    pub events: u64,
    /// The event that stopped the run, if one did.
    pub stopped_by: Option<EventHit>,
    /// Whether the output callback stopped the run (it returned [`ControlFlow::Break`](core::ops::ControlFlow::Break)); the
    /// sample it was given was the last.
    pub stopped_by_output: bool,
    /// Where a run that does not hold the assembly branch — no correction (Baumgarte
    /// stabilization alone) with an explicit integrator — passed a singular position, where
    /// the branch may have changed: the first time, its row and how many passages
    /// ([`SingularPassage`], [`SimulationOptions::watch_singular`]). `None` otherwise: the
    /// projection (the default), partitioning and generalized-α hold the branch and are not
    /// watched.
    pub singular: Option<SingularPassage>,
    /// Whether the integrator's steps were held by stability rather than accuracy (DOPRI5 and
    /// DOP853: Hairer's test, [`StiffnessDetected`]; its `Display` says what to do): the model
    /// is stiff there, and an implicit method takes steps set by the tolerance. `None` where
    /// nothing was seen or the integrator does not watch.
    pub stiffness: Option<StiffnessDetected>,
}

/// Which switching function changed sign: one of the mechanism's
/// ([`Dynamics::SWITCH_NAMES`](crate::Dynamics::SWITCH_NAMES)) or one of the user's events, by
/// index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EventHit {
    /// Switching function `k` of the mechanism: a contact, cable or tyre touching or letting
    /// go, or a time event (an expression of t alone changing branch). Two changes at one
    /// instant are delivered once, as the lower index.
    Switch(usize),
    /// The user's event `k` of [`Simulation::events`].
    User(usize),
}

/// g(t, q, v) of an [`Event`].
pub type EventFunction<'a, T, const NQ: usize, const NV: usize> = dyn FnMut(T, &[T; NQ], &[T; NV]) -> T + 'a;

/// A user's event for [`Simulation::events`]: a function g(t, q, v) whose change of sign
/// (g > 0 on one side, g ≤ 0 on the other) within a step is located; a sample is delivered at
/// that instant (its [`Sample::event`](super::Sample::event) says which), and with `stop` the run
/// ends there (e.g. a ram reaching its stroke end: `g = stroke − 0.5`).
pub struct Event<'a, T, const NQ: usize, const NV: usize> {
    /// g(t, q, v); q and v are an interpolated state inside the step while the instant is sought.
    pub function: &'a mut EventFunction<'a, T, NQ, NV>,
    /// End the run at the event.
    pub stop: bool,
}

crate::options::options! {
    /// Options of a [`Simulation`], in the scalar type `T` of the mechanism (default `f64`). Build
    /// from [`Default`] and the `with_*` setters.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct SimulationOptions<T> {
        /// Baumgarte α, β and the pivot rule of the forward-dynamics solve. Default
        /// [`DynamicsOptions::without_stabilization`]: the projection after each step holds the
        /// constraints, and Baumgarte's terms would only make the equations stiffer (DOPRI5 at
        /// rtol 1e-8 took 40 % more steps with them for a 20× larger error on a parallelogram
        /// chain).
        dynamics: DynamicsOptions<T> = DynamicsOptions::without_stabilization() => with_dynamics,
        /// Drift correction after each step. Default [`Correction::projection`]: the constraints
        /// to 1e-10 at every step, which also keeps a mechanism on its assembly branch where two
        /// branches cross (a parallelogram lying flat) — Baumgarte stabilization alone drifts
        /// onto the other branch there.
        correction: Correction<T> = Correction::projection() => with_correction,
        /// Accumulate work for the energy balance. Default off.
        track_work: bool = false => with_track_work,
        /// Step budget. Default 100 million.
        max_steps: u64 = 100_000_000 => with_max_steps,
        /// Locate the instants where the mechanism's unilateral elements touch or let go and cut
        /// the steps there. Default on (it costs two evaluations of the switching functions per
        /// step, and nothing for a mechanism without unilateral elements).
        locate_switches: bool = true => with_locate_switches,
        /// Without a correction and with an explicit integrator, watch each step end for a
        /// singular position, where such a run may change assembly branch, and report it in
        /// [`Statistics::singular`]. Default on: one factorization of D M⁻¹ Dᵀ per step, and
        /// nothing for runs that hold the branch (a correction, generalized-α) or have no
        /// constraints.
        watch_singular: bool = true => with_watch_singular,
    }
}

/// A simulation: what is integrated (a mechanism), by what ([`Integrator`]), from where
/// ([`start`](Self::start)), to which output times ([`times`](Self::times)), with which
/// [`options`](Self::options) and [`events`](Self::events); [`run`](Self::run) integrates it in
/// a work space and hands each output's [`Sample`] to a callback.
///
/// ```ignore
/// let stats = Simulation::new(&m, &mut Dopri5::default())
///     .start(0.0, &q0, &v0)
///     .times(&times)
///     .options(SimulationOptions::new().with_track_work(true))
///     .run(&mut ws, |s| println!("{} {:?}", s.point.t, s.point.q))?;
/// ```
///
/// The start and the times are required; the options default to [`SimulationOptions::new`],
/// the events to none. Nothing allocates: the samples' storage is the caller's.
#[must_use = "a simulation does nothing until it is run"]
pub struct Simulation<'a, T, M, I, const NQ: usize, const NV: usize> {
    mechanism: &'a M,
    integrator: &'a mut I,
    start: Option<(T, &'a [T; NQ], &'a [T; NV])>,
    times: &'a [T],
    options: SimulationOptions<T>,
    events: &'a mut [Event<'a, T, NQ, NV>],
}

impl<'a, T: Real, M, I, const NQ: usize, const NV: usize> Simulation<'a, T, M, I, NQ, NV> {
    /// A simulation of `mechanism` by `integrator`, with the default options and no events;
    /// give it a [`start`](Self::start) and output [`times`](Self::times) before running it.
    pub fn new(mechanism: &'a M, integrator: &'a mut I) -> Self {
        Simulation { mechanism, integrator, start: None, times: &[], options: SimulationOptions::new(), events: &mut [] }
    }

    /// The initial state: time t0 (s), coordinates q0 and velocities v0. They need not satisfy
    /// the constraints exactly: q0 is normalized and, with a [`Correction`], the state is
    /// projected onto Φ = 0, D v = ν first (initial-condition correction, Nikravesh 14.3).
    pub fn start(mut self, t0: T, q0: &'a [T; NQ], v0: &'a [T; NV]) -> Self {
        self.start = Some((t0, q0, v0));
        self
    }

    /// The output times (s): non-decreasing, none before the start's t0; the run ends at the
    /// last. A sample is delivered at each, interpolated on the step's dense output.
    pub fn times(mut self, times: &'a [T]) -> Self {
        self.times = times;
        self
    }

    /// The options (default [`SimulationOptions::new`]).
    pub fn options(mut self, options: SimulationOptions<T>) -> Self {
        self.options = options;
        self
    }

    /// The user's events, located besides the mechanism's own switches (see [`Event`]): at
    /// each the step is cut at the instant, a sample is delivered there with
    /// [`Sample::event`](super::Sample::event) set, and an event with `stop` ends the run
    /// ([`Statistics::stopped_by`]).
    pub fn events(mut self, events: &'a mut [Event<'a, T, NQ, NV>]) -> Self {
        self.events = events;
        self
    }

    /// Integrates from the start and calls `output` at each output time with the interpolated
    /// state, its v̇ and λ, and its energies (interpolated q is normalized too). `output` may
    /// return `()`, or a [`ControlFlow`](core::ops::ControlFlow) whose `Break` ends the run after that sample
    /// ([`Flow`], [`Statistics::stopped_by_output`]): a stop condition, a deadline, a user's
    /// cancel, a progress bar's tick.
    ///
    /// # Errors
    /// [`SimulationError::Incomplete`] without a start or output times; otherwise the first
    /// [`SimulationError`] met, the samples before it having been delivered.
    pub fn run<R, const NC: usize, const N: usize, const NS: usize>(
        self,
        ws: &mut Workspace<T, NV, NC, N, NS>,
        output: impl FnMut(&Sample<T, NQ, NV, NC>) -> R,
    ) -> Result<Statistics, SimulationError>
    where
        M: ForwardDynamics<T, NQ, NV, NC>,
        I: Integrator<T, M, NQ, NV, NC, N, NS>,
        R: Flow,
    {
        let Some((t0, q0, v0)) = self.start else {
            return Err(SimulationError::Incomplete { missing: "a start: .start(t0, &q0, &v0)" });
        };
        if self.times.is_empty() {
            return Err(SimulationError::Incomplete { missing: "output times: .times(&times)" });
        }
        self.mechanism.check_inertia().map_err(SimulationError::Dynamics)?;
        let (arrays, rows) = ws.arrays_and_points();
        match points::<T, NQ, NV, NC>(rows) {
            Some(points) => integrate(self, (t0, q0, v0), arrays, points, output),
            None => on_stack(self, (t0, q0, v0), arrays, output),
        }
    }
}

/// Three points in a work space's rows of scalars, where they fit (see
/// [`POINT_ROWS`](crate::model::workspace::POINT_ROWS)).
fn points<T: Real, const NQ: usize, const NV: usize, const NC: usize>(rows: &mut [T]) -> Option<[&mut Point<T, NQ, NV, NC>; 3]> {
    let scalar = core::mem::size_of::<T>();
    let size = core::mem::size_of::<Point<T, NQ, NV, NC>>() / scalar.max(1);
    if scalar == 0 || 3 * size > rows.len() {
        return None;
    }
    let (a, rest) = rows.split_at_mut(size);
    let (b, rest) = rest.split_at_mut(size);
    let c = &mut rest[..size];
    let point = |s: &mut [T]| {
        // SAFETY: `Point` is `repr(C)` with fields `T` and arrays of `T` only, so its layout is
        // `size` consecutive `T`s with T's alignment and no padding; `s` is exactly that many
        // initialized, aligned `T`s (a sub-slice of the work space's rows), borrowed mutably and
        // apart from the other two for the result's lifetime.
        unsafe { &mut *s.as_mut_ptr().cast::<Point<T, NQ, NV, NC>>() }
    };
    Some([point(a), point(b), point(c)])
}

/// [`integrate`] with the three points on the stack: for a mechanism too small for its work
/// space's rows to hold them ([`POINT_ROWS`](crate::model::workspace::POINT_ROWS), at most a few
/// dozen scalars each), in a frame of its own so that a larger one never reserves them.
#[inline(never)]
fn on_stack<T, M, I, R, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    run: Simulation<'_, T, M, I, NQ, NV>,
    start: (T, &[T; NQ], &[T; NV]),
    ws: &mut WorkArrays<T, NV, NC, N, NS>,
    output: impl FnMut(&Sample<T, NQ, NV, NC>) -> R,
) -> Result<Statistics, SimulationError>
where
    T: Real,
    M: ForwardDynamics<T, NQ, NV, NC>,
    I: Integrator<T, M, NQ, NV, NC, N, NS>,
    R: Flow,
{
    let [mut a, mut b, mut c] = [Point::zero(); 3];
    integrate(run, start, ws, [&mut a, &mut b, &mut c], output)
}

/// [`Simulation::run`]'s loop, from `start` (t0, q0, v0) with the work space's arrays and three
/// points.
fn integrate<T, M, I, R, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    run: Simulation<'_, T, M, I, NQ, NV>,
    (t0, q0, v0): (T, &[T; NQ], &[T; NV]),
    ws: &mut WorkArrays<T, NV, NC, N, NS>,
    [from, to, end]: [&mut Point<T, NQ, NV, NC>; 3],
    output: impl FnMut(&Sample<T, NQ, NV, NC>) -> R,
) -> Result<Statistics, SimulationError>
where
    T: Real,
    M: ForwardDynamics<T, NQ, NV, NC>,
    I: Integrator<T, M, NQ, NV, NC, N, NS>,
    R: Flow,
{
    let Simulation { mechanism, integrator, times, options, events, .. } = run;
    let options = &options;
    check_times(t0, times)?;
    let system = System { mechanism, dynamics: options.dynamics, track_work: options.track_work };
    (from.t, from.work) = (t0, [T::ZERO; 2]);
    from.q.copy_from_slice(q0);
    from.v.copy_from_slice(v0);
    mechanism.normalize_positions(&mut from.q);
    let mut partition = Partition::<NV, NC>::new();
    correct(mechanism, ws, &mut partition, options, t0, &mut from.q, &mut from.v)?;
    system.complete_in(ws.dense(), from)?;
    to.copy_from(from);
    integrator.restart();
    let watching = NC > 0 && options.watch_singular && !integrator.holds_constraints() && matches!(options.correction, Correction::None);
    let mut watch = BranchWatch::new(t0.to_f64());
    if watching {
        watch.observe(mechanism, ws.dense(), t0, &from.q, &from.v, &options.dynamics);
    }
    let out = Sample { point: Point::zero(), energy: energy(mechanism, ws, from), event: None };
    let mut outlet = Outlet { out, stats: Statistics::default(), output };
    outlet.out.point.copy_from(from);
    // Ends the run with what it saw.
    macro_rules! finish {
        () => {{
            outlet.stats.singular = watch.finish();
            outlet.stats.stiffness = integrator.stiffness();
            return Ok(outlet.stats);
        }};
    }
    // Hands a point to the callback (`Outlet::deliver`); ends the run where that ends it.
    macro_rules! deliver {
        ($p:expr, $event:expr) => {
            if outlet.deliver((mechanism, ws), events, $p, $event).is_break() {
                finish!();
            }
        };
    }
    let Some(&t_end) = times.last() else { return Ok(outlet.stats) };
    let mut next = 0;
    // Whether `from` is an event's instant: a change within rounding of it is then that event's
    // (or one simultaneous with it), not a new one.
    let mut at_event = false;
    while next < times.len() && times[next] <= from.t {
        next += 1;
        deliver!(Some(&*from), None);
    }
    let mut time_events = TimeEvents::new(options.locate_switches && M::TIME_SWITCHES > 0);
    while next < times.len() {
        if outlet.stats.steps >= options.max_steps {
            return Err(SimulationError::TooManySteps { t: from.t.to_f64(), steps: outlet.stats.steps });
        }
        let limit = match time_events.ahead(mechanism, from, &times[next..], t_end) {
            Ahead::StepTo(limit) => limit,
            Ahead::Cross { at, which } => {
                cross(&system, integrator, ws, &mut partition, options, at, from)?;
                outlet.stats.events += 1;
                deliver!(Some(&*from), Some(EventHit::Switch(which)));
                at_event = true;
                continue;
            }
        };
        let switches = if options.locate_switches { M::SWITCH_NAMES.len() } else { 0 };
        if let Err(failed) = integrator.step(&system, ws, from, limit, to) {
            let stepping = (&system, &mut *integrator, &mut *ws, &mut partition, options);
            let crossed = cross_jump(stepping, events, (failed, limit, switches), (&mut *from, &mut *to), (times, &mut next), &mut outlet)?;
            if crossed.is_break() {
                finish!();
            }
            at_event = true;
            continue;
        }
        let mut hit = first_event::<T, M, I, NQ, NV, NC, N, NS>(mechanism, integrator, &system, ws, from, to, switches, events, at_event)?;
        if let Some((_, which, located)) = hit.filter(|&(t, _, _)| t <= from.t) {
            // The change is at the step's start: an earlier landing stopped a hair short of it,
            // so `from` is its instant. The run goes on from just past it, on its new side, and
            // delivers that point; the step is taken again from there.
            let limit = times[next].min(to.t);
            onto_new_side(&system, integrator, ws, events, which, (from, to), located, limit, &mut outlet.out.point)?;
            outlet.stats.events += 1;
            integrator.restart();
            deliver!(Some(&*from), Some(which));
            at_event = true;
            continue;
        }
        if let Some((t, which, _)) = hit {
            hit = land(&system, integrator, ws, events, (t, which), from, to)?.then_some((t, which, t));
        }
        outlet.stats.steps += 1;
        // The integrator's own end point, for its dense output; `to` becomes the corrected one.
        end.copy_from(to);
        if !matches!(options.correction, Correction::None) {
            correct_end(&system, integrator, (ws, &mut partition), options, events, hit.map(|h| h.1), (from, end), to)?;
        }
        if watching {
            watch.observe(mechanism, ws.dense(), to.t, &to.q, &to.v, &options.dynamics);
        }
        if next < times.len() && times[next] < end.t {
            integrator.prepare_interpolation(&system, ws, from, end)?;
        }
        let step_end = end.t;
        while next < times.len() && times[next] <= step_end {
            next += 1;
            if times[next - 1] == step_end {
                deliver!(Some(&*to), None);
            } else {
                // The interpolated point, written in the sample's place.
                interpolated(&system, integrator, ws, (from, end), times[next - 1], &mut outlet.out.point)?;
                deliver!(None, None);
            }
        }
        at_event = hit.is_some();
        if let Some((_, which, _)) = hit {
            outlet.stats.events += 1;
            deliver!(Some(&*to), Some(which));
        }
        from.copy_from(to);
    }
    finish!()
}

/// What a run hands its callback: one sample, rewritten for each output (a sample is a point,
/// O(NQ + NV + NC) scalars, made once rather than once per place that delivers one), and the
/// statistics that count them.
struct Outlet<T, F, const NQ: usize, const NV: usize, const NC: usize> {
    out: Sample<T, NQ, NV, NC>,
    stats: Statistics,
    output: F,
}

impl<T: Real, F, const NQ: usize, const NV: usize, const NC: usize> Outlet<T, F, NQ, NV, NC> {
    /// Hands `p` (`None`: the point already in the sample), at `event` if any, to the callback:
    /// `Break` where the run ends there, the callback saying so or `event` a user's event that
    /// stops the run.
    fn deliver<M, R, const N: usize, const NS: usize>(
        &mut self,
        (mechanism, ws): (&M, &mut WorkArrays<T, NV, NC, N, NS>),
        events: &[Event<'_, T, NQ, NV>],
        p: Option<&Point<T, NQ, NV, NC>>,
        event: Option<EventHit>,
    ) -> ControlFlow<()>
    where
        M: ForwardDynamics<T, NQ, NV, NC>,
        R: Flow,
        F: FnMut(&Sample<T, NQ, NV, NC>) -> R,
    {
        if let Some(p) = p {
            self.out.point.copy_from(p);
        }
        self.out.energy = energy(mechanism, ws, &self.out.point);
        self.out.event = event;
        self.stats.samples += 1;
        if (self.output)(&self.out).stops() {
            self.stats.stopped_by_output = true;
            return ControlFlow::Break(());
        }
        match event {
            Some(which @ EventHit::User(k)) if events[k].stop => {
                self.stats.stopped_by = Some(which);
                ControlFlow::Break(())
            }
            _ => ControlFlow::Continue(()),
        }
    }
}

/// After a step from `from` failed (`failed`): a force that jumps where a switch flips (a damped
/// cable's c l̇ as it goes taut) may leave no step across it that the error test accepts, the
/// steps closing in on the switch until they fail. A switch or user's event just ahead (short
/// of `limit`, so never past a time event) is crossed as a time event is, and counts as a step:
/// `from` becomes the point past it, the output times within the sliver crossed and every
/// function that changed are delivered (`Break` where that ends the run). `Err(failed)` where
/// none is just ahead, or where the step failed otherwise than by its size.
fn cross_jump<T, M, I, F, R, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    (system, integrator, ws, partition, options): (
        &System<'_, M, T>,
        &mut I,
        &mut WorkArrays<T, NV, NC, N, NS>,
        &mut Partition<NV, NC>,
        &SimulationOptions<T>,
    ),
    events: &mut [Event<'_, T, NQ, NV>],
    (failed, limit, switches): (SimulationError, T, usize),
    (from, to): (&mut Point<T, NQ, NV, NC>, &mut Point<T, NQ, NV, NC>),
    (times, next): (&[T], &mut usize),
    outlet: &mut Outlet<T, F, NQ, NV, NC>,
) -> Result<ControlFlow<()>, SimulationError>
where
    T: Real,
    M: ForwardDynamics<T, NQ, NV, NC>,
    I: Integrator<T, M, NQ, NV, NC, N, NS>,
    R: Flow,
    F: FnMut(&Sample<T, NQ, NV, NC>) -> R,
{
    let SimulationError::StepSizeTooSmall { step, .. } = failed else { return Err(failed) };
    let mechanism = system.mechanism;
    if !switch_just_ahead(mechanism, events, (&*from, T::from_f64(step), limit), switches, &mut outlet.out.point) {
        return Err(failed);
    }
    // `to` keeps the point before the crossing, to tell which functions changed.
    to.copy_from(from);
    from.q.copy_from_slice(&outlet.out.point.q);
    from.v.copy_from_slice(&outlet.out.point.v);
    cross(system, integrator, ws, partition, options, outlet.out.point.t, from)?;
    outlet.stats.steps += 1;
    // An output time within the few minimum steps crossed is given the point past them (its t
    // is that point's, a few minimum steps after the output time).
    while *next < times.len() && times[*next] <= from.t {
        *next += 1;
        if outlet.deliver((mechanism, &mut *ws), events, Some(from), None).is_break() {
            return Ok(ControlFlow::Break(()));
        }
    }
    let users = events.len();
    for which in (0..switches).map(EventHit::Switch).chain((0..users).map(EventHit::User)) {
        if changed(mechanism, events, which, to, from) {
            outlet.stats.events += 1;
            if outlet.deliver((mechanism, &mut *ws), events, Some(from), Some(which)).is_break() {
                return Ok(ControlFlow::Break(()));
            }
        }
    }
    Ok(ControlFlow::Continue(()))
}

/// The step from `from` straddles event `which` at `t`, where the forces (or the user's event)
/// change law: its dense output does not hold across it. Steps again from the same start to
/// land on the instant; whether it did (an adaptive method may land short, or the interpolant,
/// poor across the switch, put the instant early where the function has not changed sign yet:
/// the next step finds it from nearer).
fn land<T, M, I, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    system: &System<'_, M, T>,
    integrator: &mut I,
    ws: &mut WorkArrays<T, NV, NC, N, NS>,
    events: &mut [Event<'_, T, NQ, NV>],
    (t, which): (T, EventHit),
    from: &Point<T, NQ, NV, NC>,
    to: &mut Point<T, NQ, NV, NC>,
) -> Result<bool, SimulationError>
where
    T: Real,
    M: ForwardDynamics<T, NQ, NV, NC>,
    I: Integrator<T, M, NQ, NV, NC, N, NS>,
{
    integrator.restart();
    match integrator.step(system, ws, from, t, to) {
        Ok(()) => Ok(to.t >= t && changed(system.mechanism, events, which, from, to)),
        // The landing's last step straddles the switch (located on the first step's dense
        // output, it may lie a hair before t on the landing's path), and the force jumps there
        // more than any step error control accepts: step again from the start towards halfway,
        // on the old side (a method that restarts with its last step size goes a short way). The
        // steps that follow close in on the switch and cross it (`switch_just_ahead`).
        Err(SimulationError::StepSizeTooSmall { .. }) => {
            integrator.restart();
            integrator.step(system, ws, from, from.t + (t - from.t) * T::from_f64(0.5), to)?;
            Ok(false)
        }
        Err(failed) => Err(failed),
    }
}

/// Corrects the step's end `to` (the integrator's own is `end`) as `options` say, unless the
/// integrator projected it itself ([`projected`]), and readies the integrator to go on from it.
/// A landing on event `landed` stays on its new side: where the correction moved it back across
/// (it is within rounding of the switch), the run goes on from the step's own end — else the
/// next step found the same change again, an ulp on.
#[allow(clippy::too_many_arguments)]
fn correct_end<T, M, I, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    system: &System<'_, M, T>,
    integrator: &mut I,
    (ws, partition): (&mut WorkArrays<T, NV, NC, N, NS>, &mut Partition<NV, NC>),
    options: &SimulationOptions<T>,
    events: &mut [Event<'_, T, NQ, NV>],
    landed: Option<EventHit>,
    (from, end): (&Point<T, NQ, NV, NC>, &Point<T, NQ, NV, NC>),
    to: &mut Point<T, NQ, NV, NC>,
) -> Result<(), SimulationError>
where
    T: Real,
    M: ForwardDynamics<T, NQ, NV, NC>,
    I: Integrator<T, M, NQ, NV, NC, N, NS>,
{
    if !projected(integrator.projected_end(), options, &to.q) {
        correct(system.mechanism, ws, partition, options, to.t, &mut to.q, &mut to.v)?;
        if landed.is_some_and(|which| !changed(system.mechanism, events, which, from, to)) {
            to.copy_from(end);
        }
    }
    integrator.after_correction(system, ws, to)
}

/// The output times after t0, none before the one before it (NaN fails).
// `!(t >= before)` on purpose: it is also true when either side is NaN.
#[allow(clippy::neg_cmp_op_on_partial_ord)]
fn check_times<T: Real>(t0: T, times: &[T]) -> Result<(), SimulationError> {
    for (i, &t) in times.iter().enumerate() {
        let before = if i == 0 { t0 } else { times[i - 1] };
        if !(t >= before) {
            return Err(SimulationError::TimesNotIncreasing { index: i });
        }
    }
    Ok(())
}

/// The point at `t` within the step from `from` to `end`, from the integrator's dense output;
/// v̇ and λ by forward dynamics there, λ from zero as at any other point (Coulomb friction's
/// first guess of its loads).
fn interpolated<T, M, I, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    system: &System<'_, M, T>,
    integrator: &mut I,
    ws: &mut WorkArrays<T, NV, NC, N, NS>,
    (from, end): (&Point<T, NQ, NV, NC>, &Point<T, NQ, NV, NC>),
    t: T,
    p: &mut Point<T, NQ, NV, NC>,
) -> Result<(), SimulationError>
where
    T: Real,
    M: ForwardDynamics<T, NQ, NV, NC>,
    I: Integrator<T, M, NQ, NV, NC, N, NS>,
{
    integrator.interpolate(system.mechanism, from, end, t, &mut p.q, &mut p.v);
    system.mechanism.normalize_positions(&mut p.q);
    (p.t, p.work) = (t, interpolate_work(from, end, t));
    p.vd.fill(T::ZERO);
    p.lambda.fill(T::ZERO);
    p.power = system.derivatives_in(ws.dense(), t, &p.q, &p.v, &mut p.vd, &mut p.lambda)?;
    Ok(())
}

/// Crosses a time event the run has reached the old side of, to its new side at `at`: the
/// state corrected to the new law there (a driver whose rate jumps moves the velocities at
/// once), its v̇ and λ, and the integrator restarted.
fn cross<T, M, I, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    system: &System<'_, M, T>,
    integrator: &mut I,
    ws: &mut WorkArrays<T, NV, NC, N, NS>,
    partition: &mut Partition<NV, NC>,
    options: &SimulationOptions<T>,
    at: T,
    from: &mut Point<T, NQ, NV, NC>,
) -> Result<(), SimulationError>
where
    T: Real,
    M: ForwardDynamics<T, NQ, NV, NC>,
    I: Integrator<T, M, NQ, NV, NC, N, NS>,
{
    from.t = at;
    correct(system.mechanism, ws, partition, options, at, &mut from.q, &mut from.v)?;
    system.complete_in(ws.dense(), from)?;
    integrator.restart();
    Ok(())
}

/// Whether one of the mechanism's first `switches` switching functions, or of the user's
/// `events`, changes sign within a few steps of `step` ahead of `from` (and before `limit`),
/// where error control failed: `p` then holds the point just past it, by a Taylor step
/// (q ⊕ h (v + h v̇ / 2), v + h v̇), whose error over those few minimum steps is below any
/// tolerance error control can meet.
fn switch_just_ahead<T, M, const NQ: usize, const NV: usize, const NC: usize>(
    mechanism: &M,
    events: &mut [Event<'_, T, NQ, NV>],
    (from, step, limit): (&Point<T, NQ, NV, NC>, T, T),
    switches: usize,
    p: &mut Point<T, NQ, NV, NC>,
) -> bool
where
    T: Real,
    M: ForwardDynamics<T, NQ, NV, NC>,
{
    let mut h = step.max(T::EPSILON * from.t.abs());
    let users = events.len();
    // Up to 2¹⁰ failed steps ahead: the steps stopped within about one of the switch.
    for _ in 0..=10 {
        if from.t + h > limit {
            return false;
        }
        p.copy_from(from);
        p.t = from.t + h;
        let rate: [T; NV] = core::array::from_fn(|k| from.v[k] + h * T::from_f64(0.5) * from.vd[k]);
        mechanism.integrate_positions(&mut p.q, &rate, h);
        p.v = core::array::from_fn(|k| from.v[k] + h * from.vd[k]);
        if (0..switches).map(EventHit::Switch).chain((0..users).map(EventHit::User)).any(|which| changed(mechanism, events, which, from, p))
        {
            return true;
        }
        h = h + h;
    }
    false
}

/// The fewest steps a simulation takes between two time events (or from its start to the
/// first): each piece of an input's law is sampled inside, not only at its ends — a bump in the
/// road that is flat at both its ends is invisible to one step from end to end.
const PIECE_STEPS: u32 = 4;

/// The time events ahead of a run. Found ahead rather than within a step: an input that jumps
/// may leave no step across it that the error test accepts. A step ends on the old side of the
/// next one; the run then crosses to its new side and restarts the integrator.
struct TimeEvents<T> {
    /// The next one ([`next_time_event`]); `None` until sought, `Some(None)` where there is none
    /// ahead (or no time events are located).
    next: Option<Option<(T, T, usize)>>,
    /// Steps taken since the last one.
    piece_steps: u32,
}

/// Where a run's next step may go.
enum Ahead<T> {
    /// Up to this time.
    StepTo(T),
    /// Nowhere yet: first across time event `which`, to its new side at `at`.
    Cross { at: T, which: usize },
}

impl<T: Real> TimeEvents<T> {
    fn new(locate: bool) -> Self {
        Self { next: (!locate).then_some(None), piece_steps: 0 }
    }

    /// From `from`, with the output times `times` ahead: up to `t_end`; or to just before the
    /// next time event, in [`PIECE_STEPS`] steps at least; or across the event it has reached.
    fn ahead<M, const NQ: usize, const NV: usize, const NC: usize>(
        &mut self,
        mechanism: &M,
        from: &Point<T, NQ, NV, NC>,
        times: &[T],
        t_end: T,
    ) -> Ahead<T>
    where
        M: ForwardDynamics<T, NQ, NV, NC>,
    {
        if self.next.is_none() {
            self.next = Some(next_time_event(mechanism, from, times));
        }
        let Some(Some((before, after, which))) = self.next else { return Ahead::StepTo(t_end) };
        if from.t >= before {
            (self.next, self.piece_steps) = (None, 0);
            return Ahead::Cross { at: after, which };
        }
        let mut limit = before.min(t_end);
        if self.piece_steps < PIECE_STEPS {
            limit = from.t + (limit - from.t) / T::from_f64(f64::from(PIECE_STEPS - self.piece_steps));
        }
        self.piece_steps += 1;
        Ahead::StepTo(limit)
    }
}

/// Points of the grid a time event is sought on between two output times
/// ([`next_time_event`]): a function of t that changes side twice between them — a pulse
/// written `abs(t - 1.0) < 0.01`, a square wave — shows it on this finer grid, where the output
/// times alone showed nothing (and a step across the whole pulse missed it). t alone, so cheap:
/// a run with N output times evaluates each time event at most 32 N times.
const TIME_GRID_POINTS: u32 = 32;

/// The first time event after `from.t`: the last instant on its old side and the first on its
/// new side (within a few ulps), and its index among the switching functions. Found on the grid
/// of the output times ahead, each interval cut in [`TIME_GRID_POINTS`]: each function of t
/// alone is sampled there and its first change of side bisected. It does not depend on the
/// state, so the instant holds until the run reaches it. `None` where none changes side between
/// two points of the grid (the step's own search still finds a change within a step).
fn next_time_event<T, M, const NQ: usize, const NV: usize, const NC: usize>(
    mechanism: &M,
    from: &Point<T, NQ, NV, NC>,
    times: &[T],
) -> Option<(T, T, usize)>
where
    T: Real,
    M: ForwardDynamics<T, NQ, NV, NC>,
{
    let n = M::SWITCH_NAMES.len();
    let side = |k: usize, t: T| mechanism.switching_function(k, &from.q, &from.v, t) > T::ZERO;
    let mut first: Option<(T, T, usize)> = None;
    for k in n.saturating_sub(M::TIME_SWITCHES)..n {
        // [a, b]: the first two points of the grid on either side.
        let start = side(k, from.t);
        let (mut a, mut found) = (from.t, None);
        'grid: for &t in times.iter().filter(|&&t| t > from.t) {
            let before = a;
            for j in 1..=TIME_GRID_POINTS {
                let point =
                    if j == TIME_GRID_POINTS { t } else { before + (t - before) * T::from_f64(f64::from(j) / f64::from(TIME_GRID_POINTS)) };
                if side(k, point) != start {
                    found = Some(point);
                    break 'grid;
                }
                a = point;
            }
        }
        let Some(mut b) = found else { continue };
        loop {
            let mid = a + (b - a) * T::from_f64(0.5);
            if mid <= a || mid >= b {
                break;
            }
            if side(k, mid) == start {
                a = mid;
            } else {
                b = mid;
            }
        }
        // At a tie (g = 0) a `>=` already takes its new branch: end the old side one ulp before.
        if mechanism.switching_function(k, &from.q, &from.v, a) == T::ZERO {
            a = a - (b - a);
        }
        if first.is_none_or(|(_, f, _)| b < f) {
            first = Some((a, b, k));
        }
    }
    first
}

/// The value of event `which` at (t, q, v).
fn event_value<T, M, const NQ: usize, const NV: usize, const NC: usize>(
    mechanism: &M,
    events: &mut [Event<'_, T, NQ, NV>],
    which: EventHit,
    t: T,
    q: &[T; NQ],
    v: &[T; NV],
) -> T
where
    T: Real,
    M: ForwardDynamics<T, NQ, NV, NC>,
{
    match which {
        EventHit::Switch(k) => mechanism.switching_function(k, q, v, t),
        EventHit::User(k) => (events[k].function)(t, q, v),
    }
}

/// Whether event `which` is on different sides (g > 0 or not) at the two points.
fn changed<T, M, const NQ: usize, const NV: usize, const NC: usize>(
    mechanism: &M,
    events: &mut [Event<'_, T, NQ, NV>],
    which: EventHit,
    a: &Point<T, NQ, NV, NC>,
    b: &Point<T, NQ, NV, NC>,
) -> bool
where
    T: Real,
    M: ForwardDynamics<T, NQ, NV, NC>,
{
    let ga = event_value(mechanism, events, which, a.t, &a.q, &a.v);
    let gb = event_value(mechanism, events, which, b.t, &b.q, &b.v);
    (ga > T::ZERO) != (gb > T::ZERO)
}

/// The earliest sign change within the step from `from` to `end` of the mechanism's first
/// `switches` switching functions and of the user's `events`, located on the step's dense
/// output: its instant (the first on the new side, to within a few ulps of t), which, and the
/// instant as located (the instant itself but where it is at the start). A
/// change within those ulps of the step's start is at `from.t`, unless `from` is an event's
/// instant already (`at_event`): rounding may undo and redo that event, and a second event
/// within rounding of it is taken as simultaneous (delivered once, so that two chattering
/// switches cannot hold the run at one instant).
#[allow(clippy::too_many_arguments)]
fn first_event<T, M, I, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    mechanism: &M,
    integrator: &mut I,
    system: &System<'_, M, T>,
    ws: &mut WorkArrays<T, NV, NC, N, NS>,
    from: &Point<T, NQ, NV, NC>,
    end: &Point<T, NQ, NV, NC>,
    switches: usize,
    events: &mut [Event<'_, T, NQ, NV>],
    at_event: bool,
) -> Result<Option<(T, EventHit, T)>, SimulationError>
where
    T: Real,
    M: ForwardDynamics<T, NQ, NV, NC>,
    I: Integrator<T, M, NQ, NV, NC, N, NS>,
{
    let h = end.t - from.t;
    let resolution = T::EPSILON * T::from_f64(16.0) * end.t.abs().max(h);
    let mut first: Option<(T, EventHit, T)> = None;
    let mut prepared = false;
    let candidates = (0..switches).map(EventHit::Switch).chain((0..events.len()).map(EventHit::User));
    for which in candidates {
        let ga = event_value(mechanism, events, which, from.t, &from.q, &from.v);
        let gb = event_value(mechanism, events, which, end.t, &end.q, &end.v);
        if (ga > T::ZERO) == (gb > T::ZERO) {
            continue;
        }
        if !prepared {
            integrator.prepare_interpolation(system, ws, from, end)?;
            prepared = true;
        }
        // The interpolated state (the work space's).
        let mut scratch = ws.dense();
        let (q, v) = (scratch.vectors.take::<NQ>(), scratch.vectors.take::<NV>());
        // Illinois: regula falsi that halves the value kept twice in a row, on g(t) of the
        // interpolated state; [a, b] always brackets the change, b on the new side.
        let (mut a, mut b, mut fa, mut fb) = (from.t, end.t, ga, gb);
        let mut kept = 0i8;
        for _ in 0..100 {
            if b - a <= resolution {
                break;
            }
            let secant = b - fb * (b - a) / (fb - fa);
            let t = if secant > a && secant < b { secant } else { (a + b) * T::from_f64(0.5) };
            integrator.interpolate(mechanism, from, end, t, q, v);
            let g = event_value(mechanism, events, which, t, q, v);
            if (g > T::ZERO) == (gb > T::ZERO) {
                (b, fb) = (t, g);
                kept = if kept < 0 { kept - 1 } else { -1 };
                if kept <= -2 {
                    fa *= T::from_f64(0.5);
                }
            } else {
                (a, fa) = (t, g);
                kept = if kept > 0 { kept + 1 } else { 1 };
                if kept >= 2 {
                    fb *= T::from_f64(0.5);
                }
            }
        }
        let located = b;
        if b - from.t <= resolution {
            if at_event {
                continue;
            }
            b = from.t;
        }
        if first.is_none_or(|(t, _, _)| b < t) {
            first = Some((b, which, located));
        }
    }
    Ok(first)
}

/// Moves `from` — on the old side of event `which`, whose change the step to `end` located
/// within rounding after it, at `t` — onto its new side: to the step's dense output at `t`, or
/// failing that at twice, four times … as far from `from.t`, the first point there on the new
/// side before `limit` (`p` to work in), or the step's end. The point is the dense output's (the
/// integrator's), not corrected (as at an output time); `from` stays where none is found.
#[allow(clippy::too_many_arguments)]
fn onto_new_side<T, M, I, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    system: &System<'_, M, T>,
    integrator: &mut I,
    ws: &mut WorkArrays<T, NV, NC, N, NS>,
    events: &mut [Event<'_, T, NQ, NV>],
    which: EventHit,
    (from, end): (&mut Point<T, NQ, NV, NC>, &Point<T, NQ, NV, NC>),
    t: T,
    limit: T,
    p: &mut Point<T, NQ, NV, NC>,
) -> Result<(), SimulationError>
where
    T: Real,
    M: ForwardDynamics<T, NQ, NV, NC>,
    I: Integrator<T, M, NQ, NV, NC, N, NS>,
{
    let mut offset = (t - from.t).max(T::EPSILON * from.t.abs().max(end.t - from.t));
    while from.t + offset < limit {
        interpolated(system, integrator, ws, (from, end), from.t + offset, p)?;
        if changed(system.mechanism, events, which, from, p) {
            from.copy_from(p);
            return Ok(());
        }
        offset = offset + offset;
    }
    // A step within rounding of its start (the change located at its end): the end itself.
    if end.t <= limit && changed(system.mechanism, events, which, from, end) {
        from.copy_from(end);
    }
    Ok(())
}

fn interpolate_work<T: Real, const NQ: usize, const NV: usize, const NC: usize>(
    from: &Point<T, NQ, NV, NC>,
    to: &Point<T, NQ, NV, NC>,
    t: T,
) -> [T; 2] {
    let h = to.t - from.t;
    let theta = if h > T::ZERO { (t - from.t) / h } else { T::ONE };
    core::array::from_fn(|k| hermite(from.work[k], from.power[k], to.work[k], to.power[k], h, theta))
}

/// The energies at a point.
fn energy<
    T: Real,
    M: ForwardDynamics<T, NQ, NV, NC>,
    const NQ: usize,
    const NV: usize,
    const NC: usize,
    const N: usize,
    const NS: usize,
>(
    mechanism: &M,
    ws: &mut WorkArrays<T, NV, NC, N, NS>,
    p: &Point<T, NQ, NV, NC>,
) -> Energy<T> {
    Energy {
        kinetic: kinetic_energy_in(mechanism, &p.q, &p.v, ws.dense().vectors.take()),
        potential: mechanism.potential_energy(&p.q, p.t),
        nonconservative_work: p.work[0],
        constraint_work: p.work[1],
    }
}

/// Whether a step's end the integrator projected from ‖Φ‖∞ = `residual` (`None`: not
/// projected) needs no projection of the run's: `residual` meets the projection's tolerance, as
/// its own loop would stop ([`Integrator::projected_end`]). Partitioning corrects it all the
/// same: it keeps the independent velocities, where the integrator's projection moved them all
/// (in the metric of M).
fn projected<T: Real, const NQ: usize>(residual: Option<T>, options: &SimulationOptions<T>, q: &[T; NQ]) -> bool {
    match (residual, options.correction) {
        (Some(r), Correction::Projection { tolerance, .. }) => r <= tolerance.max(crate::solvers::kinematics::resolution(q)),
        _ => false,
    }
}

/// Applies the drift correction of `options` to (q, v) at t.
fn correct<
    T: Real,
    M: ForwardDynamics<T, NQ, NV, NC>,
    const NQ: usize,
    const NV: usize,
    const NC: usize,
    const N: usize,
    const NS: usize,
>(
    mechanism: &M,
    ws: &mut WorkArrays<T, NV, NC, N, NS>,
    partition: &mut Partition<NV, NC>,
    options: &SimulationOptions<T>,
    t: T,
    q: &mut [T; NQ],
    v: &mut [T; NV],
) -> Result<(), SimulationError> {
    match options.correction {
        Correction::None => Ok(()),
        Correction::Projection { tolerance, max_iterations } => {
            project_in(mechanism, ws.dense(), t, q, v, &options.dynamics, tolerance, max_iterations)
        }
        Correction::Partitioning { tolerance, max_iterations } => {
            partition.correct(mechanism, ws, t, q, v, &options.dynamics, tolerance, max_iterations)
        }
    }
}
