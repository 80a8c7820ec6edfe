use mbd::prelude::*;

// A reference into a part's instance names something the part does not declare: the error is on
// the name after the instance's, says what the instance has, and names the instance as written.
mechanism! {
    Axle {
        part corner(side) {
            body wheel { mass: 10.0, inertia: 0.4, at: [side, 0.3, 0.0] }
            revolute hub: ground[side, 0.3] ~ wheel[0.0, 0.0];
        }
        for i in 0..2 {
            corner c[i](side: 2.0 * i - 1.0);
        }
        fix c[1].whel.y;
    }
}

// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Axle::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Axle::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Axle::NQ, Axle::NC, <Axle as Mechanism>::BODY_NAMES);
}
