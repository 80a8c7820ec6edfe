use mbd::prelude::*;

// Units are not written: numbers are SI. A missing comma before the next field is not a unit.
mechanism! {
    Bob {
        body bob { mass: 2.0 kg, inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ bob[-0.5, 0.0];
    }
}

mechanism! {
    Bob2 {
        body bob { mass: 2.0 inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ bob[-0.5, 0.0];
    }
}

fn main() {}
