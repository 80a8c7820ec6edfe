use mbd::prelude::*;

// A planar body has x, y and phi.
mechanism! {
    Slider {
        body block { mass: 1.0, inertia: 0.1 }
        fix block.y;
        fix block.theta;
    }
}
fn main() {}
