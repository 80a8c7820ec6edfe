use mbd::prelude::*;

mechanism! {
    Ball {
        gravity [0.0, -9.81];
        body ball { mass: 0.5, inertia: 0.002, at: [0.0, 1.0, 0.0] }
        contact ball[0.0, -0.1] ~ ground[0.0, 0.0] { k: 1.0e5 };
    }
}
fn main() {}
