// One mistake, one error, scenes included: the base mechanism has a mistake, and the program
// uses its scene; the scene is generated from the statements without mistakes too.
use mbd::prelude::*;

mechanism! {
    pub Press {
        params { omega: 6.0 }
        gravity [0.0, -9.81];
        body crank { mass: 1.0, inertia: 0.1, at: [0.1, 0.0, 0.0] }
        body ram { mass: 2.0, inertia: 0.2, at: [0.3, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ crank[-0.1, 0.0];
        revolute_revolute crank[0.1, 0.0] ~ ram[0.0, 0.0] { lenght: 0.2 };
        translational ground[0.0, 0.0] along [1.0, 0.0] ~ ram[0.0, 0.0] along [1.0, 0.0];
        drive motor: crank.phi = omega * t;
        scene FreePress without motor;
    }
}

fn main() {
    let m = FreePress::default();
    let mut ws = FreePress::workspace();
    let q = m.initial_positions();
    let mut dopri = Dopri5::new(Dopri5Options::default());
    let _ = Simulation::new(&m, &mut dopri).start(0.0, &q, &[0.0; 6]).times(&[1.0]).run(&mut ws, |s| {
        println!("{} {}", s.point.t, Press::NQ);
    });
}
