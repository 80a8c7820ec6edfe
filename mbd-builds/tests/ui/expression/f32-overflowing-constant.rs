use mbd::prelude::*;

// A constant beyond f32's range once `scalar f32;` is declared: an error, not a macro panic.
mechanism! {
    Heavy {
        scalar f32;
        params { k: 1.0e39 }
        body bob { mass: 1.0, inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ bob[-0.5, 0.0];
        torque bob = k * bob.phi;
    }
}

mechanism! {
    Heavier {
        scalar f32;
        body bob { mass: 2.0e38 * 3.0, inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ bob[-0.5, 0.0];
    }
}

// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Heavy::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Heavy::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Heavy::NQ, Heavy::NC, <Heavy as Mechanism>::BODY_NAMES);
    let m = Heavier::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Heavier::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Heavier::NQ, Heavier::NC, <Heavier as Mechanism>::BODY_NAMES);
}
