//! The study's mechanisms: one of each kind a user brings (a machine with a flywheel, a chaotic
//! linkage, chains of growing size, a suspension on a stiff tyre, a four-bar through its
//! singular position, a fast top, a spatial linkage, and a stiff spinning linkage: issue 39's
//! case A); two come from the examples.

use mbd::prelude::*;

/// A free pendulum chain of `$n` links (0.1 m, 0.1 kg each), pinned end to end and to ground,
/// horizontal at the start; `$scalar` is an optional `scalar f32;`.
macro_rules! chain {
    ($name:ident, $n:literal $(, $scalar:ident)?) => {
        mechanism! {
            #[doc = concat!("A free pendulum chain of ", stringify!($n), " links, horizontal at the start.")]
            pub $name {
                $(scalar $scalar;)?
                gravity [0.0, -9.81];
                revolute ground[0.0, 0.0] ~ l[0][-0.05, 0.0];
                for i in 0..$n {
                    body l[i] { mass: 0.1, inertia: 8.3333e-5, at: [0.05 + 0.1 * i, 0.0, 0.0] }
                }
                for i in 1..$n {
                    revolute l[i - 1][0.05, 0.0] ~ l[i][-0.05, 0.0];
                }
            }
        }
    };
}

chain!(Chain4, 4);
chain!(Chain16, 16);
chain!(Chain64, 64);
chain!(Chain16F32, 16, f32);
include!("../../mbd-bench/mechanisms/free_spatial_slider_crank.rs");
include!("../../mbd-bench/mechanisms/stiff_flywheel.rs");
include!("../../mbd-bench/mechanisms/heavy_top_benchmark.rs");
include!("../../mbd-bench/mechanisms/bump_stop_quarter_car.rs");

/// The suspension of the examples: a double A-arm corner on its coil-over and a stiff tyre
/// (200 kN/m under an 18 kg knuckle) driven over a 3 cm bump at 0.5 s (`DoubleAArmRide`).
#[allow(dead_code)] // the example's own report and main
#[path = "../../examples/suspension_dynamics.rs"]
pub mod suspension;

/// The heavy top of the examples (`Gyroscope`: 0.5 kg, tilted 0.5 rad on a ball pivot), spun
/// by the study at 50 rev/s: a fast rotation and a slow precession.
#[allow(dead_code)]
#[path = "../../examples/gyroscope.rs"]
pub mod gyroscope;

mechanism! {
    /// A slider-crank with a 2 kg·m² flywheel on its crank, spinning at 5 rev/s under gravity.
    pub FlywheelSliderCrank {
        gravity [0.0, -9.81];
        body crank  { mass: 5.0, inertia: 2.0, at: [0.0, 0.0, 0.0], velocity: [0.0, 0.0, 31.41592653589793] }
        body rod    { mass: 0.8, inertia: 3.0e-3, at: [0.15, 0.0, 0.0] }
        body piston { mass: 0.5, inertia: 1.0e-4, at: [0.25, 0.0, 0.0] }
        revolute bearing: ground[0.0, 0.0] ~ crank[0.0, 0.0];
        revolute crankpin: crank[0.05, 0.0] ~ rod[-0.1, 0.0];
        revolute wristpin: rod[0.1, 0.0] ~ piston[0.0, 0.0];
        translational bore: piston[0.0, 0.0] along [1.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0];
    }
}

mechanism! {
    /// A double pendulum of two rods released horizontal (chaotic).
    pub DoublePendulum {
        gravity [0.0, -9.81];
        body a { mass: 1.0, inertia: 0.0208, at: [0.25, 0.0, 0.0] }
        body b { mass: 0.5, inertia: 0.0104, at: [0.75, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ a[-0.25, 0.0];
        revolute a[0.25, 0.0] ~ b[-0.25, 0.0];
    }
}

mechanism! {
    /// A change-point four-bar (crank 0.2, coupler 0.5, rocker 0.3, ground 0.6 m: a + d = b + c)
    /// whose crank turns freely at about 10 rad/s through the flat position, where its
    /// Jacobian loses rank (mbd-long/tests/singular.rs).
    pub ChangePointFourBar {
        body crank { mass: 1.0, inertia: 0.003, at: [0.1, 0.0, 0.0], velocity: [0.0, 1.0, 10.0] }
        body coupler { mass: 1.0, inertia: 0.02, at: [0.4, 0.15, 0.643501108793284] }
        body rocker { mass: 1.0, inertia: 0.008, at: [0.6, 0.15, -1.5707963267948966] }
        point coupler.pin = [0.25, 0.0];
        revolute ground[0.0, 0.0] ~ crank[-0.1, 0.0];
        revolute crank[0.1, 0.0] ~ coupler[-0.25, 0.0];
        revolute coupler.pin ~ rocker[-0.15, 0.0];
        revolute rocker[0.15, 0.0] ~ ground[0.6, 0.0];
    }
}
