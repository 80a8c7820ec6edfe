//! The free slider-crank's forward dynamics in single precision, without the standard library,
//! as a C function a firmware can call: `mbd_accelerations(q, v, t, vd)` writes v̇ for the state
//! (q, v) and returns 0, or 1 where the forward-dynamics solve fails (a singular position).
#![no_std]

use mbd::{DynamicsOptions, ForwardDynamics};

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

#[cfg(not(test))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}
