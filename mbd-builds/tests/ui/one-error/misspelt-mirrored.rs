use mbd::prelude::*;

// A new user's mistake (2026-11-25): `mirror` for `mirrored`. One error, on the word, with the
// keyword it resembles; the instance is still there for `main`.

mechanism! {
    pub Legs {
        gravity [0.0, -9.81];
        part leg() {
            body thigh { mass: 1.0, inertia: 0.02, at: [0.45, 0.0, 0.0] }
            revolute ground[0.2, 0.0] ~ thigh[-0.25, 0.0];
        }
        leg left();
        leg right() mirror x;
    }
}

fn main() {
    let m = Legs::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Legs::workspace(), &mut q, 0.0);
    println!("{} {}", Legs::LEFT_THIGH.x(&q), Legs::RIGHT_THIGH.x(&q));
}
