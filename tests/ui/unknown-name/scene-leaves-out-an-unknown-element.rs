use mbd::prelude::*;

// A scene may leave out only what the mechanism has: a labelled statement, `gravity` or
// `friction`. The error points at the unknown name, suggests the nearest label and lists them.
mechanism! {
    Press {
        gravity [0.0, -9.81];
        body crank { mass: 2.0, inertia: 0.02, at: [0.05, 0.0, 0.0] }
        revolute bearing: ground[0.0, 0.0] ~ crank[-0.05, 0.0];
        torque motor: crank = 1.5;
        scene Unpowered without motr;
    }
}

fn main() {}
