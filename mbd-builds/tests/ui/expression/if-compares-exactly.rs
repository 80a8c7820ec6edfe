use mbd::prelude::*;

mechanism! {
    Ram {
        body ram { mass: 1.0, inertia: 0.1 }
        translational ground[0.0, 0.0] along [1.0, 0.0] ~ ram[0.0, 0.0] along [1.0, 0.0];
        force ram[0.0, 0.0] = [if ram.x == 0.5 { -100.0 } else { 0.0 }, 0.0];
    }
}
// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Ram::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Ram::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Ram::NQ, Ram::NC, <Ram as Mechanism>::BODY_NAMES);
}
