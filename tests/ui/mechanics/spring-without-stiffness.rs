use mbd::prelude::*;

mechanism! {
    Bouncer {
        gravity [0.0, -9.81];
        body mass { mass: 1.0, inertia: 0.1 }
        spring ground[0.0, 1.0] ~ mass[0.0, 0.0] { length: 0.5, c: 2.0 };
    }
}
fn main() {}
