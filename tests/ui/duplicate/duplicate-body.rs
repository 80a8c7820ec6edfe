use mbd::prelude::*;

mechanism! {
    TwoLinks {
        body link { mass: 1.0, inertia: 0.1 }
        body link { mass: 2.0, inertia: 0.2 }
    }
}
fn main() {}
