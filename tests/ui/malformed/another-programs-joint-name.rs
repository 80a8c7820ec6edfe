use mbd::prelude::*;

// Another program's name of a joint gets ours.
mechanism! {
    Slide {
        body block { mass: 1.0, inertia: 0.01 }
        prismatic block[0.0, 0.0] along [1.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0];
    }
}

fn main() {}
