//! The free slider-crank's forward dynamics in single precision, without the standard library,
//! as a C function a firmware can call: `mbd_accelerations(q, v, t, vd)` writes v̇ for the state
//! (q, v) and returns 0, or 1 where the forward-dynamics solve fails (a singular position).
//!
//! And the modal analysis without the standard library (feature `alloc`: nalgebra's dense
//! matrices on the heap): `mbd_pendulum_frequency(l)` linearizes a hanging pendulum in double
//! precision and returns its natural frequency in Hz. The heap is the firmware's; here a bump
//! allocator over a static arena stands in for it.
#![no_std]

extern crate alloc;

use core::alloc::{GlobalAlloc, Layout};
use core::cell::UnsafeCell;
use core::sync::atomic::{AtomicUsize, Ordering};

use mbd::{DynamicsOptions, ForwardDynamics, Kinematics, Linearizer};

mbd::mechanism! {
    /// Free slider-crank under gravity, single precision.
    pub FreeSliderCrank {
        scalar f32;
        params { r: 0.1, l: 0.3 }
        gravity [0.0, -9.81];
        body crank  { mass: 1.0, inertia: 0.002, at: [0.0433, 0.025, 0.5236] }
        body rod    { mass: 2.0, inertia: 0.015, at: [0.2345, 0.025, -0.1674] }
        body slider { mass: 0.5, inertia: 0.001, at: [0.3823, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ crank[-r / 2.0, 0.0];
        revolute crank[r / 2.0, 0.0] ~ rod[-l / 2.0, 0.0];
        revolute rod[l / 2.0, 0.0] ~ slider[0.0, 0.0];
        translational slider[0.0, 0.0] along [1.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0];
    }
}

/// v̇ of the free slider-crank at (q, v, t), with the default Baumgarte stabilization.
///
/// # Safety
/// `q`, `v` and `vd` point to 9 `f32` each.
#[no_mangle]
pub unsafe extern "C" fn mbd_accelerations(q: *const [f32; 9], v: *const [f32; 9], t: f32, vd: *mut [f32; 9]) -> i32 {
    let m = FreeSliderCrank { r: 0.1, l: 0.3 };
    let mut lambda = [0.0f32; 8];
    match m.accelerations(&*q, &*v, t, &DynamicsOptions::default(), &mut *vd, &mut lambda) {
        Ok(_) => 0,
        Err(_) => 1,
    }
}

mbd::mechanism! {
    /// A rod hanging from a pin at its top, double precision.
    pub Pendulum {
        params { l: 0.5 }
        gravity [0.0, -9.81];
        body rod { mass: 1.0, inertia: 0.02, at: [0.0, -l, 0.0] }
        revolute ground[0.0, 0.0] ~ rod[0.0, l];
    }
}

/// Natural frequency (Hz) of the pendulum whose centre of mass hangs `l` m below its pin, from
/// its exact linearization about the hanging equilibrium; −1 where there is none (l ≤ 0, or the
/// analysis fails).
#[no_mangle]
pub extern "C" fn mbd_pendulum_frequency(l: f64) -> f64 {
    ARENA.reset();
    let m = Pendulum { l };
    let q = m.initial_positions();
    match Linearizer::default().linearize(&m, &q, &[0.0; 3], 0.0) {
        Ok(lin) => lin.modes().first().map_or(-1.0, |mode| mode.natural_frequency),
        Err(_) => -1.0,
    }
}

/// The heap: 64 KiB, handed out upwards and given back all at once by [`Arena::reset`] at the
/// start of each call (nothing outlives a call).
struct Arena {
    memory: UnsafeCell<[u8; 1 << 16]>,
    used: AtomicUsize,
}

// SAFETY: the offset is claimed atomically, so no two allocations overlap.
unsafe impl Sync for Arena {}

impl Arena {
    fn reset(&self) {
        self.used.store(0, Ordering::Relaxed);
    }
}

unsafe impl GlobalAlloc for Arena {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let base = self.memory.get() as usize;
        let mut start = 0;
        let claimed = self.used.fetch_update(Ordering::Relaxed, Ordering::Relaxed, |used| {
            start = (base + used).next_multiple_of(layout.align()) - base;
            (start + layout.size() <= 1 << 16).then_some(start + layout.size())
        });
        match claimed {
            Ok(_) => (base + start) as *mut u8,
            Err(_) => core::ptr::null_mut(),
        }
    }

    unsafe fn dealloc(&self, _: *mut u8, _: Layout) {}
}

#[global_allocator]
static ARENA: Arena = Arena { memory: UnsafeCell::new([0; 1 << 16]), used: AtomicUsize::new(0) };

#[cfg(not(test))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}
