use mbd::prelude::*;

mechanism! {
    Quarter {
        gravity [0.0, -9.81];
        body chassis { mass: 250.0, inertia: 10.0, at: [0.0, 0.6, 0.0] }
        body wheel { mass: 30.0, inertia: 1.0, at: [0.0, 0.3, 0.0] }
        translational ground[0.0, 0.0] along [0.0, 1.0] ~ chassis[0.0, 0.0] along [0.0, 1.0];
        translational chassis[0.0, 0.0] along [0.0, 1.0] ~ wheel[0.0, 0.0] along [0.0, 1.0];
        tyre wheel[0.0, 0.0] ~ chassis[0.0, 0.0] { radius: 0.3, k: 2.0e5 };
    }
}
// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Quarter::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Quarter::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Quarter::NQ, Quarter::NC, <Quarter as Mechanism>::BODY_NAMES);
}
