use mbd::prelude::*;

mechanism! {
    Crank {
        body crank { mass: 1.0, inertia: 0.1 }
        revolut ground[0.0, 0.0] ~ crank[0.0, 0.0];
    }
}
fn main() {}
