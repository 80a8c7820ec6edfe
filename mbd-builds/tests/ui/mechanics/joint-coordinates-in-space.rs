// Joint coordinates are planar so far: stated with `spatial;` they are refused.
use mbd::prelude::*;

mechanism! {
    pub Top {
        spatial;
        joint_coordinates;
        body top { mass: 1.0, inertia: [0.1, 0.1, 0.2], at: [0.0, 0.0, 0.5] }
        spherical ground[0.0, 0.0, 0.0] ~ top[0.0, 0.0, -0.5];
    }
}

fn main() {
    let m = Top::default();
    println!("{} coordinate(s)", m.initial_positions().len());
}
