use mbd::prelude::*;

mechanism! {
    PinFriction {
        body rod { mass: 1.0, inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ rod[-0.5, 0.0] { coulomb: 0.2 };
    }
}

// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = PinFriction::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut PinFriction::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", PinFriction::NQ, PinFriction::NC, <PinFriction as Mechanism>::BODY_NAMES);
}
