use mbd::prelude::*;

// In the plane a driver acts on a body's coordinate or between two bodies: a joint's label with
// `.angle` (the spatial form, and the name joint coordinates give the coordinate) is one error
// saying so, not an unknown body and an unknown coordinate.
mechanism! {
    Crank {
        joint_coordinates;
        body crank { mass: 1.0, inertia: 0.01, at: [0.1, 0.0, 0.0] }
        revolute hinge: ground[0.0, 0.0] ~ crank[-0.1, 0.0];
        drive hinge.angle = 2.0 * t;
    }
}
// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Crank::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Crank::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Crank::NQ, Crank::NC, <Crank as Mechanism>::BODY_NAMES);
}
