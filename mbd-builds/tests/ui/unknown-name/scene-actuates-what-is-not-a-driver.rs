use mbd::prelude::*;

// A scene may actuate only a labelled driver: a joint's label is not one. The error points at
// the name and lists the drivers.
mechanism! {
    Press {
        gravity [0.0, -9.81];
        body crank { mass: 2.0, inertia: 0.02, at: [0.05, 0.0, 0.0] }
        revolute bearing: ground[0.0, 0.0] ~ crank[-0.05, 0.0];
        drive motor: crank.phi = 6.0 * t;
        scene Free actuating bearing;
    }
}

// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Press::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Press::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Press::NQ, Press::NC, <Press as Mechanism>::BODY_NAMES);
}
