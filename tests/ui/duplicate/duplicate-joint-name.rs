use mbd::prelude::*;

mechanism! {
    TwoPins {
        body a { mass: 1.0, inertia: 0.1 }
        revolute pin: ground[0.0, 0.0] ~ a[0.0, 0.0];
        revolute_revolute pin: ground[1.0, 0.0] ~ a[1.0, 0.0] { length: 1.0 };
    }
}
fn main() {}
