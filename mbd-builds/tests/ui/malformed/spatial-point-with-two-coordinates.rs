use mbd::prelude::*;

mechanism! {
    Top {
        spatial;
        body top { mass: 1.0, inertia: [0.005, 0.005, 0.002] }
        spherical ground[0.0, 0.0] ~ top[0.0, 0.0, -0.1];
    }
}
// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Top::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Top::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Top::NQ, Top::NC, <Top as Mechanism>::BODY_NAMES);
}
