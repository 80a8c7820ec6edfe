use mbd::prelude::*;

mechanism! {
    Pendulum {
        body bob { at: [0.0, -0.5, 0.0] }
        revolute ground[0.0, 0.0] ~ bob[0.0, 0.5];
    }
}
fn main() {}
