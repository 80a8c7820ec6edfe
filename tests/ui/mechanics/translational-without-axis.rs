use mbd::prelude::*;

mechanism! {
    Slider {
        body block { mass: 1.0, inertia: 0.1 }
        translational block[0.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0];
    }
}
fn main() {}
