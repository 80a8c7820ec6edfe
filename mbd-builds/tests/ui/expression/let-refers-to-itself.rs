use mbd::prelude::*;

mechanism! {
    Pendulum {
        params { k: 2.0 }
        body bob { mass: 1.0, inertia: 0.1, at: [0.0, -1.0, 0.0] }
        revolute ground[0.0, 0.0] ~ bob[0.0, 1.0];
        let stiffness = k * lever;
        let lever = 1.0 + stiffness;
        torque spring: bob = -stiffness * bob.phi;
    }
}
// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Pendulum::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Pendulum::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Pendulum::NQ, Pendulum::NC, <Pendulum as Mechanism>::BODY_NAMES);
}
