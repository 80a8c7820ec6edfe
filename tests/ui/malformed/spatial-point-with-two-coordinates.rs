use mbd::prelude::*;

mechanism! {
    Top {
        spatial;
        body top { mass: 1.0, inertia: [0.005, 0.005, 0.002] }
        spherical ground[0.0, 0.0] ~ top[0.0, 0.0, -0.1];
    }
}
fn main() {}
