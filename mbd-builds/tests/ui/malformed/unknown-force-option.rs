use mbd::prelude::*;

mechanism! {
    Bouncer {
        body mass { mass: 1.0, inertia: 0.1 }
        damper ground[0.0, 1.0] ~ mass[0.0, 0.0] { c: 2.0, stiffness: 3.0 };
    }
}
// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Bouncer::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Bouncer::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Bouncer::NQ, Bouncer::NC, <Bouncer as Mechanism>::BODY_NAMES);
}
