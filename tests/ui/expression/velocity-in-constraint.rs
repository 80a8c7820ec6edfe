use mbd::prelude::*;

mechanism! {
    Slider {
        body block { mass: 1.0, inertia: 0.1 }
        constraint block.y = 0.1 * block.vx;
    }
}
fn main() {}
