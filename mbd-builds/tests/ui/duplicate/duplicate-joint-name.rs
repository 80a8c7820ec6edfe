use mbd::prelude::*;

mechanism! {
    TwoPins {
        body a { mass: 1.0, inertia: 0.1 }
        revolute pin: ground[0.0, 0.0] ~ a[0.0, 0.0];
        revolute_revolute pin: ground[1.0, 0.0] ~ a[1.0, 0.0] { length: 1.0 };
    }
}
// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = TwoPins::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut TwoPins::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", TwoPins::NQ, TwoPins::NC, <TwoPins as Mechanism>::BODY_NAMES);
}
