// Coulomb friction reads its joint's normal load from λ; in joint coordinates a joint the tree
// carries has no multiplier, so friction on one is refused, naming the joint.
use mbd::prelude::*;

mechanism! {
    pub Pendulum {
        joint_coordinates;
        gravity [0.0, -9.81];
        body arm { mass: 1.0, inertia: 0.1, at: [0.5, 0.0, 0.0] }
        revolute pin: ground[0.0, 0.0] ~ arm[-0.5, 0.0] { coulomb: 0.2, radius: 0.01 };
    }
}

fn main() {
    let m = Pendulum::default();
    println!("{} coordinate(s)", m.initial_positions().len());
}
