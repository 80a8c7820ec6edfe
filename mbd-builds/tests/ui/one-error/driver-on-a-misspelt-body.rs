// One mistake, one error: the README's program with its driver labelled `motor` and written on
// a misspelt body. The mechanism is still generated from its other statements, and its labels
// with it: `SliderCrank::MOTOR`, which the program reads, is not a second error.
use mbd::prelude::*;

mechanism! {
    pub SliderCrank {
        params { omega: 2.0 * PI, r: 0.1, l: 0.3 }
        body crank  { mass: 1.0, inertia: 0.002, at: [0.05, 0.0, 0.0] }
        body rod    { mass: 2.0, inertia: 0.015, at: [0.25, 0.0, 0.0] }
        body slider { mass: 0.5, inertia: 0.001, at: [0.4, 0.0, 0.0] }
        point slider.pin = [0.0, 0.0];
        revolute ground[0.0, 0.0] ~ crank[-r / 2.0, 0.0];
        revolute crank[r / 2.0, 0.0] ~ rod[-l / 2.0, 0.0];
        revolute rod[l / 2.0, 0.0] ~ slider.pin;
        translational slider.pin along [1.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0];
        drive motor: crnk.phi = omega * t;
    }
}

fn main() -> Result<(), KinematicError> {
    let m = SliderCrank { omega: 4.0, ..Default::default() };
    let solver = KinematicSolver::default();
    let mut ws = SliderCrank::workspace();
    let mut q = m.initial_positions();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let pin = m.slider_pin();
    solver.sweep(&m, &mut ws, &mut q, (0..100).map(|k| k as f64 * 0.01), |t, q, v, vd| {
        let (x, xd, xdd) = (pin.position(q).x, pin.velocity(q, v).x, pin.acceleration(q, v, vd).x);
        let rod = SliderCrank::ROD.phi(q).to_degrees();
        println!("{t:.2} s: slider at {x:.4} m, {xd:.4} m/s, {xdd:.3} m/s²; rod at {rod:.2}° of {}", SliderCrank::NQ);
    })?;
    println!("the motor is constraint row {}", SliderCrank::MOTOR);
    Ok(())
}
