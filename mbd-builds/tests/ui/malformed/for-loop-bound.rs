use mbd::prelude::*;

// A loop's bound must be an integer expression of numbers and enclosing loop variables; the
// error points at the bound.
mechanism! {
    Chain {
        params { n: 4.0 }
        for i in 0..n {
            body l[i] { mass: 0.1, inertia: 8.3e-5, at: [0.1 * i, 0.0, 0.0] }
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
