use mbd::prelude::*;

// An option given twice is an error on the second, not a silent overwrite.
mechanism! {
    Slot {
        body block { mass: 1.0, inertia: 0.01 }
        revolute_translational block[0.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0] { distance: 0.1, distance: 0.2 };
    }
}

fn main() {}
