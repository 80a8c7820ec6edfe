use mbd::prelude::*;

mechanism! {
    Bouncer {
        body mass { mass: 1.0, inertia: 0.1 }
        damper ground[0.0, 1.0] ~ mass[0.0, 0.0] { c: 2.0, stiffness: 3.0 };
    }
}
fn main() {}
