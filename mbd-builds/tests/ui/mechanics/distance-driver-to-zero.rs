use mbd::prelude::*;

mechanism! {
    Lift {
        body ram { mass: 1.0, inertia: 0.1, at: [0.0, 1.0, 0.0] }
        translational ground[0.0, 0.0] along [0.0, 1.0] ~ ram[0.0, 0.0] along [0.0, 1.0];
        drive distance(ground[0.0, 0.0], ram[0.0, 0.0]) = 0.0 * t;
    }
}
// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Lift::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Lift::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Lift::NQ, Lift::NC, <Lift as Mechanism>::BODY_NAMES);
}
