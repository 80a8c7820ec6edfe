use mbd::prelude::*;

mechanism! {
    Ball {
        gravity [0.0, -9.81];
        body ball { mass: 0.5, inertia: 0.002, at: [0.0, 1.0, 0.0] }
        contact ball[0.0, -0.1] ~ ground[0.0, 0.0] { k: 1.0e5 };
    }
}
// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Ball::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Ball::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Ball::NQ, Ball::NC, <Ball as Mechanism>::BODY_NAMES);
}
