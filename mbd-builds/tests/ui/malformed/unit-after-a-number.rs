use mbd::prelude::*;

// Units are not written: numbers are SI. A missing comma before the next field is not a unit.
mechanism! {
    Bob {
        body bob { mass: 2.0 kg, inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ bob[-0.5, 0.0];
    }
}

mechanism! {
    Bob2 {
        body bob { mass: 2.0 inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ bob[-0.5, 0.0];
    }
}

// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Bob::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Bob::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Bob::NQ, Bob::NC, <Bob as Mechanism>::BODY_NAMES);
    let m = Bob2::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Bob2::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Bob2::NQ, Bob2::NC, <Bob2 as Mechanism>::BODY_NAMES);
}
