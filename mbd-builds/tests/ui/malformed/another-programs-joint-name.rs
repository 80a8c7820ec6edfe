use mbd::prelude::*;

// Another program's name of a joint gets ours.
mechanism! {
    Slide {
        body block { mass: 1.0, inertia: 0.01 }
        prismatic block[0.0, 0.0] along [1.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0];
    }
}

// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Slide::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Slide::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Slide::NQ, Slide::NC, <Slide as Mechanism>::BODY_NAMES);
}
