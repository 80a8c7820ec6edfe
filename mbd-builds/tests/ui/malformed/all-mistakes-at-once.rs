use mbd::prelude::*;

// Three independent mistakes: all three are reported in one compile, and the type `Broken` with
// its parameter `k` still exists, so the code below it adds no error of its own.
mechanism! {
    Broken {
        params { k: 2.0 }
        body a { mass: 0.0, inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ b[0.0, 0.0];
        drive a.phi = k * tt;
    }
}

fn main() {
    let m = Broken::default();
    let _ = m.k;
}
