use mbd::prelude::*;

mechanism! {
    Chain {
        for i in 0..2 {
            body link[i] { mass: 1.0, inertia: 0.1, at: [0.5 + i, 0.0, 0.0] }
            let lever = 0.5 * (i + 1);
        }
        revolute ground[0.0, 0.0] ~ link[0][-0.5, 0.0];
        revolute link[0][0.5, 0.0] ~ link[1][-0.5, 0.0];
    }
}
// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Chain::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Chain::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Chain::NQ, Chain::NC, <Chain as Mechanism>::BODY_NAMES);
}
