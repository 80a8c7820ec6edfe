use mbd::prelude::*;

mechanism! {
    Crank {
        body crank { mass: 1.0, inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ crank[0.0, 0.0];
        drive crank.phi = 2.0 * t;
        drive crank.phi = 3.0 * t;
    }
}
// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Crank::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Crank::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Crank::NQ, Crank::NC, <Crank as Mechanism>::BODY_NAMES);
}
