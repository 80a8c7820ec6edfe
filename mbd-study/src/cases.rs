//! The study's mechanisms: one of each kind a user brings (a machine with a flywheel, a chaotic
//! linkage, chains of growing size, a suspension on a stiff tyre, a four-bar through its
//! singular position, a fast top, a spatial linkage).

use mbd::prelude::*;

include!(concat!(env!("OUT_DIR"), "/chains.rs"));
include!("../../mbd-bench/mechanisms/free_spatial_slider_crank.rs");

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
    /// A double A-arm suspension corner on its coil-over and a stiff tyre (200 kN/m under an
    /// 18 kg knuckle), driven over a 3 cm bump at 0.5 s (examples/suspension_dynamics.rs).
    pub Suspension {
        params { k_s: 30000.0, free_length: 0.61, c_s: 1500.0, k_t: 200000.0, c_t: 100.0, bump: 0.03, t_bump: 0.5, width: 0.03 }
        gravity [0.0, -9.81];
        body lower   { mass: 4.0, inertia: 0.05, at: [0.375, 0.14, 0.0] }
        body upper   { mass: 2.5, inertia: 0.02, at: [0.41, 0.46, 0.0] }
        body knuckle { mass: 18.0, inertia: 0.60, at: [0.62, 0.30, 0.0] }
        point lower.inner = [-0.175, 0.01];
        point lower.outer = [0.175, -0.01];
        point lower.spring = [0.1, 0.0];
        point upper.inner = [-0.11, -0.01];
        point upper.outer = [0.11, 0.01];
        point knuckle.lower_ball = [-0.07, -0.17];
        point knuckle.upper_ball = [-0.10, 0.17];
        point knuckle.contact = [0.0, -0.30];
        revolute ground[0.20, 0.15] ~ lower.inner;
        revolute ground[0.30, 0.45] ~ upper.inner;
        revolute lower.outer ~ knuckle.lower_ball;
        revolute upper.outer ~ knuckle.upper_ball;
        spring coil_over: lower.spring ~ ground[0.45, 0.60] { k: k_s, length: free_length, c: c_s };
        force tyre: knuckle.contact = [0.0, k_t * (bump * exp(-((t - t_bump) / width) ^ 2) - (knuckle.y - 0.3 * cos(knuckle.phi)))
                                          - c_t * knuckle.vy];
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

mechanism! {
    /// A heavy symmetric top on a ball pivot, tilted 0.5 rad, spinning at 50 rev/s about its
    /// axis (examples/gyroscope.rs): a fast rotation and a slow precession.
    pub HeavyTop {
        spatial;
        gravity [0.0, 0.0, -9.81];
        body rotor {
            mass: 0.5, inertia: [2.0e-4, 2.0e-4, 4.0e-4],
            at: [0.0, -0.05 * sin(0.5), 0.05 * cos(0.5)], axis_angle: [1.0, 0.0, 0.0, 0.5],
            omega: [0.0, 0.0, 314.1592653589793]
        }
        spherical pivot: ground[0.0, 0.0, 0.0] ~ rotor[0.0, 0.0, -0.05];
    }
}
