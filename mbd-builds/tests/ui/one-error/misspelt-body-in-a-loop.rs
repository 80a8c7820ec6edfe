use mbd::prelude::*;

// A chain of 40 links whose loop names the previous link `cc` instead of `c`: the loop is
// unrolled, so the mistake is found in each of its 39 iterations, at the same token. It is one
// mistake, and one error.
mechanism! {
    Chain {
        gravity [0.0, -9.81];
        body c[0] { mass: 0.1, inertia: 8.3e-5, at: [0.05, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ c[0][-0.05, 0.0];
        for k in 1..40 {
            body c[k] { mass: 0.1, inertia: 8.3e-5, at: [0.05 + 0.1 * k, 0.0, 0.0] }
            revolute cc[k - 1][0.05, 0.0] ~ c[k][-0.05, 0.0];
        }
    }
}

// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Chain::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Chain::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Chain::NQ, Chain::NC, <Chain as Mechanism>::BODY_NAMES);
}
