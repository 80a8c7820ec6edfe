use mbd::prelude::*;

// A loop that pins each link to the next one reaches one past the last link: `l[i + 1]` is the
// body `l[3]` at i = 2, which does not exist. The error points at `l` inside the loop and names
// the body as the loop made it, as it would be written.
mechanism! {
    Chain {
        revolute ground[0.0, 0.0] ~ l[0][-0.05, 0.0];
        for i in 0..3 {
            body l[i] { mass: 0.1, inertia: 8.3e-5, at: [0.05 + 0.1 * i, 0.0, 0.0] }
            revolute l[i][0.05, 0.0] ~ l[i + 1][-0.05, 0.0];
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
