use mbd::prelude::*;

mechanism! {
    Door {
        spatial;
        body door { mass: 20.0, inertia: [2.0, 1.5, 0.5] }
        revolute hinge: ground[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0] ~ door[-0.4, 0.0, 0.0];
    }
}
fn main() {}
