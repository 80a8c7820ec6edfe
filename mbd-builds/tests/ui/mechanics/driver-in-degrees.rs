// Warnings are errors here, so that trybuild shows them.
#![deny(deprecated)]
use mbd::prelude::*;

mechanism! {
    Crank {
        params { omega: 6.0 }
        body crank { mass: 1.0, inertia: 0.1 }
        body wheel { mass: 1.0, inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ crank[0.0, 0.0];
        revolute ground[1.0, 0.0] ~ wheel[0.0, 0.0];
        // one turn a second, written in degrees
        drive crank.phi = 360 * t;
        // 1000 rev/s
        drive wheel.phi = 1000.0 * 2.0 * PI * t;
    }
}

mechanism! {
    /// Nothing to say: a radian rate and degrees made explicit.
    Fine {
        params { omega: 6.0 }
        body crank { mass: 1.0, inertia: 0.1 }
        body wheel { mass: 1.0, inertia: 0.1 }
        revolute ground[0.0, 0.0] ~ crank[0.0, 0.0];
        revolute ground[1.0, 0.0] ~ wheel[0.0, 0.0];
        drive crank.phi = omega * t;
        drive wheel.phi = deg(360) * t;
    }
}
// The program uses the mechanism's type as a user would: the mistake above is its one error.
fn main() {
    let m = Crank::default();
    let mut q = m.initial_positions();
    let _ = KinematicSolver::default().assemble(&m, &mut Crank::workspace(), &mut q, 0.0);
    println!("{} {} {:?}", Crank::NQ, Crank::NC, <Crank as Mechanism>::BODY_NAMES);
}
