use mbd::prelude::*;

mechanism! {
    Slider {
        spatial;
        body block { mass: 1.0, inertia: [0.1, 0.1, 0.1] }
        fix block.z;
        fix block.e1;
    }
}
fn main() {}
