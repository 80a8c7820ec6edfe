use mbd::prelude::*;

// An instance must give every parameter of its part a value: the error is on the instance's name
// and says what to add.
mechanism! {
    Axle {
        part corner(x0, side) {
            body wheel { mass: 10.0, inertia: 0.4, at: [x0, side, 0.0] }
            revolute hub: ground[x0, side] ~ wheel[0.0, 0.0];
        }
        corner front(x0: 1.2);
    }
}

// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Axle::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Axle::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Axle::NQ, Axle::NC, <Axle as Mechanism>::BODY_NAMES);
}
