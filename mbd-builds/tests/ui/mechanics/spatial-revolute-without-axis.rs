use mbd::prelude::*;

mechanism! {
    Door {
        spatial;
        body door { mass: 20.0, inertia: [2.0, 1.5, 0.5] }
        revolute hinge: ground[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0] ~ door[-0.4, 0.0, 0.0];
    }
}
// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Door::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Door::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Door::NQ, Door::NC, <Door as Mechanism>::BODY_NAMES);
}
