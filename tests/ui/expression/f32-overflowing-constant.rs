use mbd::prelude::*;

// A constant beyond f32's range once `scalar f32;` is declared: an error, not a macro panic.
mechanism! {
    Heavy {
        scalar f32;
        params { k: 1.0e39 }
        body bob { mass: 1.0, inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ bob[-0.5, 0.0];
        torque bob = k * bob.phi;
    }
}

mechanism! {
    Heavier {
        scalar f32;
        body bob { mass: 2.0e38 * 3.0, inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ bob[-0.5, 0.0];
    }
}

fn main() {}
