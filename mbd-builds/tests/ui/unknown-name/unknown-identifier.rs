use mbd::prelude::*;

mechanism! {
    Crank {
        params { omega: 6.0 }
        body crank { mass: 1.0, inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ crank[0.0, 0.0];
        drive crank.phi = omgea * t;
    }
}
// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Crank::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Crank::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Crank::NQ, Crank::NC, <Crank as Mechanism>::BODY_NAMES);
}
