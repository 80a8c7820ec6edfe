use mbd::prelude::*;

mechanism! {
    Pendulum {
        body bob { mass: 1.0, inertia: 0.1 }
        point bob.top = [0.0, 0.5];
        revolute ground[0.0, 0.0] ~ bob.tip;
    }
}
fn main() {}
