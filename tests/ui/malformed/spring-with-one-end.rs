use mbd::prelude::*;

mechanism! {
    Crank {
        body crank { mass: 1.0, inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ crank[0.0, 0.0];
        spring crank[0.1, 0.0] { k: 10.0, length: 0.1 };
    }
}
fn main() {}
