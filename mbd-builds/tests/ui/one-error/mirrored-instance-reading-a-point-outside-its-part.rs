use mbd::prelude::*;

// A new user's mistake (2026-11-25): a mirrored instance of a part that reads a point declared
// outside it (its values are the mechanism's, not reflected). One error, on the point, naming
// the instance; both instances' bodies are still there for `main`.

mechanism! {
    pub Legs {
        gravity [0.0, -9.81];
        point ground.anchor = [0.2, 0.0];
        part leg() {
            body thigh { mass: 1.0, inertia: 0.02, at: [0.45, 0.0, 0.0] }
            revolute ground.anchor ~ thigh[-0.25, 0.0];
        }
        leg left();
        leg right() mirrored x;
    }
}

fn main() {
    let m = Legs::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Legs::workspace(), &mut q, 0.0);
    println!("{} {}", Legs::LEFT_THIGH.x(&q), Legs::RIGHT_THIGH.x(&q));
}
