// A body's accessor takes the state of its own mechanism, `&[f64; NQ]`: the state of another
// mechanism (a slice, or an array of another size) does not compile, where a slice accessor
// would have read past its end or read the wrong body at run time.
use mbd::prelude::*;

mechanism! {
    pub Pendulum {
        gravity [0.0, -9.81];
        body rod { mass: 1.0, inertia: 0.1, at: [0.0, -0.5, 0.0] }
        revolute ground[0.0, 0.0] ~ rod[0.0, 0.5];
    }
}

mechanism! {
    pub DoublePendulum {
        gravity [0.0, -9.81];
        body upper { mass: 1.0, inertia: 0.1, at: [0.0, -0.5, 0.0] }
        body lower { mass: 1.0, inertia: 0.1, at: [0.0, -1.5, 0.0] }
        revolute ground[0.0, 0.0] ~ upper[0.0, 0.5];
        revolute upper[0.0, -0.5] ~ lower[0.0, 0.5];
    }
}

fn main() {
    let q = Pendulum::default().initial_positions();
    println!("{}", DoublePendulum::LOWER.phi(&q));
}
