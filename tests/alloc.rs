//! A counting global allocator shows that a 10 000-point kinematic sweep of the slider-crank
//! and 10 000 steps of each integrator (with projection, work tracking and an output every
//! step) make no heap allocation after set-up (the work space is made once, before counting).
//! Only the test's own thread is counted: the harness's other threads allocate when they
//! please (counting them failed about one run in four).
use mbd_examples::slider_crank;
/// The examples this test uses (from mbd-examples, where they are compiled once) and the shared
/// generator (`tests/common/`).
mod common {
    pub(crate) use super::slider_crank;
}

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    /// Allocations made by this thread (a `const` thread-local: reading it never allocates).
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

fn count() {
    // `try_with`: during thread teardown the counter may be gone; such allocations are not
    // the test's.
    let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
}

// SAFETY: forwards to the system allocator unchanged; only counts.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn kinematic_sweep_does_not_allocate() {
    use common::slider_crank::SliderCrank;
    use mbd::{KinematicSolver, Kinematics};
    let m = SliderCrank::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = SliderCrank::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0).expect("assembles");
    let mut checksum = 0.0;
    let mut points = 0usize;

    let before = allocations();
    let times = (0..10_000).map(|k| k as f64 * 1e-4);
    let result = solver.sweep(&m, &mut ws, &mut q, times, |_, q, v, vd| {
        checksum += q[6] + v[6] + vd[6];
        points += 1;
    });
    let after = allocations();

    assert!(result.is_ok(), "sweep failed: {result:?}");
    assert_eq!(points, 10_000, "every point was visited");
    assert!(checksum.is_finite());
    assert_eq!(after - before, 0, "heap allocations during the sweep");

    integrators_do_not_allocate();
}

mbd::mechanism! {
    /// A damped free four-bar under gravity.
    pub FreeFourBar {
        gravity [0.0, -9.81];
        body crank   { mass: 0.5, inertia: 5.0e-4, at: [0.05, 0.0, 0.0] }
        body coupler { mass: 1.2, inertia: 9.0e-3, at: [0.18, 0.12, 0.97] }
        body rocker  { mass: 1.0, inertia: 5.2e-3, at: [0.28, 0.12, 1.70] }
        revolute ground[0.0, 0.0] ~ crank[-0.05, 0.0];
        revolute crank[0.05, 0.0] ~ coupler[-0.15, 0.0];
        revolute coupler[0.15, 0.0] ~ rocker[0.125, 0.0];
        revolute rocker[-0.125, 0.0] ~ ground[0.3, 0.0];
        spring ground[0.0, 0.3] ~ coupler[0.0, 0.0] { k: 60.0, length: 0.1, c: 0.3 };
    }
}

fn integrators_do_not_allocate() {
    use mbd::prelude::*;
    use mbd::Sample;
    let m = FreeFourBar::default();
    let mut q = m.initial_positions();
    let mut ws = FreeFourBar::workspace();
    KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0).expect("assembles");
    let mut times = [0.0; 10_000];
    for (k, t) in times.iter_mut().enumerate() {
        *t = (k + 1) as f64 * 1e-3;
    }
    let options = SimulationOptions::default().with_correction(Correction::projection()).with_track_work(true);
    let partitioned = options.with_correction(Correction::partitioning());
    let mut rk4 = Rk4::new(Rk4Options::default().with_step(1e-3));
    let mut dopri = Dopri5::new(Dopri5Options::default().with_max_step(1e-3));
    let mut alpha = FreeFourBar::generalized_alpha(GeneralizedAlphaOptions::default());
    let mut samples = 0u64;
    let mut energy = 0.0;

    let before = allocations();
    let mut steps = 0;
    let mut collect = |s: &Sample<f64, 9, 9, 8>| {
        samples += 1;
        energy += s.energy.balance();
    };
    steps += Simulation::new(&m, &mut rk4)
        .start(0.0, &q, &[0.0; 9])
        .times(&times)
        .options(options)
        .run(&mut ws, &mut collect)
        .expect("RK4")
        .steps;
    steps += Simulation::new(&m, &mut dopri)
        .start(0.0, &q, &[0.0; 9])
        .times(&times)
        .options(options)
        .run(&mut ws, &mut collect)
        .expect("DOPRI5")
        .steps;
    steps += Simulation::new(&m, &mut alpha)
        .start(0.0, &q, &[0.0; 9])
        .times(&times)
        .options(options)
        .run(&mut ws, &mut collect)
        .expect("generalized-α")
        .steps;
    steps += Simulation::new(&m, &mut Rk4::new(Rk4Options::default().with_step(1e-3)))
        .start(0.0, &q, &[0.0; 9])
        .times(&times)
        .options(partitioned)
        .run(&mut ws, &mut collect)
        .expect("partitioning")
        .steps;
    let after = allocations();

    assert!(steps >= 40_000, "{steps} steps");
    assert_eq!(samples, 40_000, "every output was delivered");
    assert!(energy.is_finite());
    assert_eq!(after - before, 0, "heap allocations during 10 000 steps of each integrator");
}
