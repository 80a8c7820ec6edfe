use mbd::prelude::*;

// Each moment of inertia is positive, but the product Jxy = 0.2 makes a principal moment
// negative (0.1 − 0.2): no body has such a tensor, and M would not be invertible.
mechanism! {
    Pendulum {
        spatial;
        body bob { mass: 1.0, inertia: [0.1, 0.1, 0.2, 0.2, 0.0, 0.0] }
        spherical pivot: ground[0.0, 0.0, 0.0] ~ bob[0.0, 0.0, 0.5];
    }
}
// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Pendulum::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Pendulum::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Pendulum::NQ, Pendulum::NC, <Pendulum as Mechanism>::BODY_NAMES);
}
