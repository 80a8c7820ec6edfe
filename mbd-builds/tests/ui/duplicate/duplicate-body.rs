use mbd::prelude::*;

mechanism! {
    TwoLinks {
        body link { mass: 1.0, inertia: 0.1 }
        body link { mass: 2.0, inertia: 0.2 }
    }
}
// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = TwoLinks::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut TwoLinks::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", TwoLinks::NQ, TwoLinks::NC, <TwoLinks as Mechanism>::BODY_NAMES);
}
