use mbd::prelude::*;

// A planar body has x, y and phi.
mechanism! {
    Slider {
        body block { mass: 1.0, inertia: 0.1 }
        fix block.y;
        fix block.theta;
    }
}
// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Slider::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Slider::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Slider::NQ, Slider::NC, <Slider as Mechanism>::BODY_NAMES);
}
