// A joint reaction is read from λ in body coordinates only: for a mechanism in joint coordinates
// `cargo check` refuses it (the `BodyCoordinates` bound), and says why.
use mbd::prelude::*;

mechanism! {
    pub Pendulum {
        joint_coordinates;
        gravity [0.0, -9.81];
        body rod { mass: 1.0, inertia: 0.1, at: [0.5, 0.0, 0.0] }
        revolute pin: ground[0.0, 0.0] ~ rod[-0.5, 0.0];
    }
}

fn main() {
    let m = Pendulum::default();
    let q = m.initial_positions();
    let reaction = mbd::joint_reaction(&m, &q, &[[0.0; 1]; 0], &[0.0; 0], Pendulum::PIN);
    println!("{:?}", reaction.is_some());
}
