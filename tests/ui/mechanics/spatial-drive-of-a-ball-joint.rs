use mbd::prelude::*;

mechanism! {
    Pendulum {
        spatial;
        body bob { mass: 1.0, inertia: [0.1, 0.1, 0.1] }
        spherical pivot: ground[0.0, 0.0, 0.0] ~ bob[0.0, 0.0, 0.5];
        drive pivot.angle = t;
    }
}
fn main() {}
