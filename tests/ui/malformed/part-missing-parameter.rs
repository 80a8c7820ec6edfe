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

fn main() {}
