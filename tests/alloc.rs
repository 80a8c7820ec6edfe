//! A counting global allocator shows that a 10 000-point kinematic sweep of the slider-crank
//! makes no heap allocation after set-up. This binary holds this one test only, so no other
//! test's thread allocates while it counts.
mod common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;
static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

// SAFETY: forwards to the system allocator unchanged; only counts.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
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
    solver.assemble(&m, &mut q, 0.0).expect("assembles");
    let mut checksum = 0.0;
    let mut points = 0usize;

    let before = ALLOCATIONS.load(Ordering::SeqCst);
    let times = (0..10_000).map(|k| k as f64 * 1e-4);
    let result = solver.sweep(&m, &mut q, times, |_, q, qd, qdd| {
        checksum += q[6] + qd[6] + qdd[6];
        points += 1;
    });
    let after = ALLOCATIONS.load(Ordering::SeqCst);

    assert!(result.is_ok(), "sweep failed: {result:?}");
    assert_eq!(points, 10_000, "every point was visited");
    assert!(checksum.is_finite());
    assert_eq!(after - before, 0, "heap allocations during the sweep");
}
