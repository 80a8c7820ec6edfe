//! The driver: [`simulate`] integrates with any [`Integrator`] to a list of output times,
//! corrects drift after each step ([`Correction`]: the mass-weighted [`project`]ion, or
//! coordinate partitioning, Nikravesh 13.6.2), interpolates each output with the step's dense
//! output and hands its [`Sample`] (state, v̇, λ and energies) to a callback; its
//! [`SimulationOptions`] and [`Statistics`].
//!
//! The initial state is corrected first (initial-condition correction, Nikravesh 14.3).

use super::{hermite, Energy, Integrator, Point, Sample, SimulationError, System};
use crate::dynamics::kinetic_energy;
use crate::kinematics::name;
use crate::partition::Partition;
use crate::{DynamicsOptions, ForwardDynamics, Real, Workspace};

/// What brings the state back onto the constraint manifold after each step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Correction<T> {
    /// Nothing (Baumgarte stabilization, if set, still acts through the accelerations).
    None,
    /// Mass-weighted projection (Newton on Φ = 0 with steps q ⊕ (−M⁻¹DᵀS⁻¹Φ), then the exact
    /// velocity projection), to ‖Φ‖∞ ≤ `tolerance`.
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
    let tolerance = tolerance.max(crate::kinematics::resolution(q));
    let mut iterations = 0;
    loop {
        if iterations == max_iterations {
            // No step left: measure where the last one ended.
            let mut phi = [T::ZERO; NC];
            mechanism.constraints(q, t, &mut phi);
            let worst = phi.iter().enumerate().fold((0, T::ZERO), |w, (i, v)| if v.abs() > w.1 { (i, v.abs()) } else { w });
            if worst.1 <= tolerance {
                break;
            }
            return Err(SimulationError::NotConverged {
                t: t.to_f64(),
                iterations,
                worst_row: name(M::CONSTRAINT_NAMES, worst.0),
                residual: worst.1.to_f64(),
            });
        }
        let residual = mechanism.project_positions_step(q, t, options)?;
        if residual <= tolerance {
            // The step just taken was below tolerance too: keep it (it only helps).
            break;
        }
        iterations += 1;
    }
    mechanism.project_velocities(q, v, t, options)?;
    Ok(())
}

/// Statistics of a [`simulate`] run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Statistics {
    /// Steps taken (accepted).
    pub steps: u64,
    /// Samples handed to the callback.
    pub samples: u64,
}

/// Options of [`simulate`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SimulationOptions<T> {
    /// Baumgarte α, β and the pivot rule of the forward-dynamics solve. Default
    /// [`DynamicsOptions::without_stabilization`]: the projection after each step holds the
    /// constraints, and Baumgarte's terms would only make the equations stiffer (DOPRI5 at rtol
    /// 1e-8 took 40 % more steps with them for a 20× larger error on a parallelogram chain).
    pub dynamics: DynamicsOptions<T>,
    /// Drift correction after each step. Default [`Correction::projection`]: the constraints
    /// to 1e-10 at every step, which also keeps a mechanism on its assembly branch where two
    /// branches cross (a parallelogram lying flat) — Baumgarte stabilization alone drifts onto
    /// the other branch there.
    pub correction: Correction<T>,
    /// Accumulate work for the energy balance. Default off.
    pub track_work: bool,
    /// Step budget. Default 100 million.
    pub max_steps: u64,
}

impl<T: Real> Default for SimulationOptions<T> {
    fn default() -> Self {
        Self {
            dynamics: DynamicsOptions::without_stabilization(),
            correction: Correction::projection(),
            track_work: false,
            max_steps: 100_000_000,
        }
    }
}

/// Integrates from `initial` (t, q, v) and calls `output` at each of `times` (non-decreasing,
/// not before the initial time) with the interpolated state, its v̇ and λ, and its energies.
///
/// The initial q is normalized ([`Kinematics::normalize_positions`](crate::Kinematics::normalize_positions))
/// and the initial state corrected when a [`Correction`] is set (initial-condition correction,
/// Nikravesh 14.3); interpolated outputs are normalized too. Nothing allocates: storage for the
/// samples is the caller's.
///
/// # Errors
/// The first [`SimulationError`] met; the samples before it have been delivered.
#[allow(clippy::too_many_arguments)]
// `!(t >= before)` on purpose: it is also true when either side is NaN.
#[allow(clippy::neg_cmp_op_on_partial_ord)]
pub fn simulate<T, M, I, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
    mechanism: &M,
    ws: &mut Workspace<T, NV, NC, N>,
    integrator: &mut I,
    t0: T,
    q0: &[T; NQ],
    v0: &[T; NV],
    times: &[T],
    options: &SimulationOptions<T>,
    mut output: impl FnMut(&Sample<T, NQ, NV, NC>),
) -> Result<Statistics, SimulationError>
where
    T: Real,
    M: ForwardDynamics<T, NQ, NV, NC>,
    I: Integrator<T, M, NQ, NV, NC, N>,
{
    for (i, &t) in times.iter().enumerate() {
        let before = if i == 0 { t0 } else { times[i - 1] };
        if !(t >= before) {
            return Err(SimulationError::TimesNotIncreasing { index: i });
        }
    }
    let system = System { mechanism, dynamics: options.dynamics, track_work: options.track_work };
    let (mut q, mut v) = (*q0, *v0);
    mechanism.normalize_positions(&mut q);
    let mut partition = Partition::<NV, NC>::new();
    correct(mechanism, ws, &mut partition, options, t0, &mut q, &mut v)?;
    let mut from = system.point(t0, q, v, [T::ZERO; 2])?;
    let mut to = from;
    integrator.restart();
    let mut stats = Statistics::default();
    let t_end = match times.last() {
        Some(&t) => t,
        None => return Ok(stats),
    };
    let mut next = 0;
    while next < times.len() && times[next] <= from.t {
        output(&sample(mechanism, &from));
        stats.samples += 1;
        next += 1;
    }
    while next < times.len() {
        if stats.steps >= options.max_steps {
            return Err(SimulationError::TooManySteps { t: from.t.to_f64(), steps: stats.steps });
        }
        integrator.step(&system, ws, &from, t_end, &mut to)?;
        stats.steps += 1;
        // The integrator's own end point, for its dense output; `to` becomes the corrected one.
        let end = to;
        if !matches!(options.correction, Correction::None) {
            let (mut q, mut v) = (to.q, to.v);
            correct(mechanism, ws, &mut partition, options, to.t, &mut q, &mut v)?;
            to = integrator.after_correction(&system, &end, q, v)?;
        }
        if next < times.len() && times[next] < end.t {
            integrator.prepare_interpolation(&system, &from, &end)?;
        }
        while next < times.len() && times[next] <= end.t {
            if times[next] == end.t {
                output(&sample(mechanism, &to));
            } else {
                let (mut q, mut v) = ([T::ZERO; NQ], [T::ZERO; NV]);
                integrator.interpolate(mechanism, &from, &end, times[next], &mut q, &mut v);
                mechanism.normalize_positions(&mut q);
                let work = interpolate_work(&from, &end, times[next]);
                output(&sample(mechanism, &system.point(times[next], q, v, work)?));
            }
            stats.samples += 1;
            next += 1;
        }
        from = to;
    }
    Ok(stats)
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

/// A point with its energies.
fn sample<T: Real, M: ForwardDynamics<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize>(
    mechanism: &M,
    p: &Point<T, NQ, NV, NC>,
) -> Sample<T, NQ, NV, NC> {
    let energy = Energy {
        kinetic: kinetic_energy(mechanism, &p.q, &p.v),
        potential: mechanism.potential_energy(&p.q, p.t),
        nonconservative_work: p.work[0],
        constraint_work: p.work[1],
    };
    Sample { point: *p, energy }
}

/// Applies the drift correction of `options` to (q, v) at t.
fn correct<T: Real, M: ForwardDynamics<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
    mechanism: &M,
    ws: &mut Workspace<T, NV, NC, N>,
    partition: &mut Partition<NV, NC>,
    options: &SimulationOptions<T>,
    t: T,
    q: &mut [T; NQ],
    v: &mut [T; NV],
) -> Result<(), SimulationError> {
    match options.correction {
        Correction::None => Ok(()),
        Correction::Projection { tolerance, max_iterations } => project(mechanism, t, q, v, &options.dynamics, tolerance, max_iterations),
        Correction::Partitioning { tolerance, max_iterations } => partition.correct(mechanism, ws, t, q, v, tolerance, max_iterations),
    }
}
