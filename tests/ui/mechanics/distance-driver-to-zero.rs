use mbd::prelude::*;

mechanism! {
    Lift {
        body ram { mass: 1.0, inertia: 0.1, at: [0.0, 1.0, 0.0] }
        translational ground[0.0, 0.0] along [0.0, 1.0] ~ ram[0.0, 0.0] along [0.0, 1.0];
        drive distance(ground[0.0, 0.0], ram[0.0, 0.0]) = 0.0 * t;
    }
}
fn main() {}
