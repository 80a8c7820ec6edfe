use mbd::prelude::*;

// An option given twice is an error on the second, not a silent overwrite.
mechanism! {
    Slot {
        body block { mass: 1.0, inertia: 0.01 }
        revolute_translational block[0.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0] { distance: 0.1, distance: 0.2 };
    }
}

// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Slot::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Slot::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Slot::NQ, Slot::NC, <Slot as Mechanism>::BODY_NAMES);
}
