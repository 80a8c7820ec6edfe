use mbd::prelude::*;

// A loop's bound must be an integer expression of numbers and enclosing loop variables; the
// error points at the bound.
mechanism! {
    Chain {
        params { n: 4.0 }
        for i in 0..n {
            body l[i] { mass: 0.1, inertia: 8.3e-5, at: [0.1 * i, 0.0, 0.0] }
        }
    }
}

fn main() {}
