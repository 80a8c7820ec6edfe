use mbd::prelude::*;

// A new user's mistake (2026-11-25): a scene actuating a misspelt driver. One error, on the
// name, with the driver it resembles; the free scene's force parameter is still there for `main`.

mechanism! {
    pub Crank {
        gravity [0.0, -9.81];
        body crank { mass: 2.0, inertia: 0.02, at: [0.05, 0.0, 0.0] }
        revolute bearing: ground[0.0, 0.0] ~ crank[-0.05, 0.0];
        drive motor: crank.phi = 6.0 * t;
        scene Free actuating motr;
    }
}

fn main() {
    let m = Free { motor_force: 1.5 };
    let q = m.initial_positions();
    let (mut vd, mut lambda) = ([0.0; Free::NV], [0.0; Free::NC]);
    let _ = m.accelerations(&q, &[0.0; Free::NV], 0.0, &DynamicsOptions::default(), &mut vd, &mut lambda);
    println!("{vd:?}");
}
