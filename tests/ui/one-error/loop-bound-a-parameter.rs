use mbd::prelude::*;

// A new user's program (2026-11-25) with one mistake. A loop bounded by a parameter: `Rig::W_1`, which the loop makes, is still there.

mechanism! {
    /// A crank-rocker four-bar with a return spring, two coupler weights and a counterweight.
    pub Rig {
        params { n_w: 2.0, omega: 2.0 * PI, a: 0.1, b: 0.3, c: 0.25, d: 0.3, k_ret: 500.0 }
        gravity [0.0, -9.81];
        body crank   { mass: 0.5, inertia: 0.0005, at: [0.05, 0.0, 0.0] }
        body coupler { mass: 1.0, inertia: 0.0075, at: [0.184, 0.124, 0.973] }
        body rocker  { mass: 0.8, inertia: 0.0042, at: [0.284, 0.124, 1.696] }
        point coupler.P = [0.05, 0.04];
        revolute base: ground[0.0, 0.0] ~ crank[-a / 2.0, 0.0];
        revolute crank[a / 2.0, 0.0] ~ coupler[-b / 2.0, 0.0];
        revolute coupler[b / 2.0, 0.0] ~ rocker[c / 2.0, 0.0];
        revolute rocker[-c / 2.0, 0.0] ~ ground[d, 0.0];
        drive motor: crank.phi = omega * t;
        spring ret: ground[0.45, 0.3] ~ rocker[0.0, 0.0] { k: k_ret, length: 0.15, c: 2.0 };
        for i in 0..n_w {
            particle w[i] { mass: 0.1, at: [0.1 + 0.1 * i, 0.06 * i] }
            revolute coupler[-0.1 + 0.2 * i, 0.0] ~ w[i][0.0, 0.0];
        }
        part counterweight(host, len) {
            body bob { mass: 0.3, inertia: 0.0001, at: [0.0, 0.0, 0.0] }
            rigid host[-len, 0.0] ~ bob[0.0, 0.0];
        }
        counterweight cw(host: crank, len: 0.1);
        scene FreeRig without motor;
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let m = Rig::default();
    println!("NQ = {}, NC = {}, DOF = {} bodies {:?}", Rig::NQ, Rig::NC, Rig::DOF, Rig::BODY_NAMES);
    let solver = KinematicSolver::default();
    let mut ws = Rig::workspace();
    let mut q = m.initial_positions();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let p = m.coupler_p();
    let times: Vec<f64> = (0..=10).map(|k| k as f64 * 0.1).collect();
    solver.sweep(&m, &mut ws, &mut q, times.iter().copied(), |t, q, qd, _qdd| {
        let pos = p.position(q);
        let rocker = Rig::ROCKER.phi(q).to_degrees();
        let bob = Rig::CW_BOB.x(q);
        let w1 = Rig::W_1.y(q);
        println!("{t:.2} s: P = ({:.4}, {:.4}) m, |v_P| = {:.4} m/s, rocker {rocker:.2} deg, bob x {bob:.4}, w[1] y {w1:.4}",
            pos.x, pos.y, p.velocity(q, qd).norm());
    })?;
    println!("motor joint index {}", Rig::MOTOR);

    // The free scene: let it fall for 0.2 s.
    let f = FreeRig::default();
    let mut fws = FreeRig::workspace();
    let mut fq = f.initial_positions();
    solver.assemble(&f, &mut fws, &mut fq, 0.0)?;
    let mut rk4 = Rk4::new(1e-3);
    let ftimes: Vec<f64> = (0..=4).map(|k| k as f64 * 0.05).collect();
    simulate(&f, &mut fws, &mut rk4, 0.0, &fq, &[0.0; FreeRig::NV], &ftimes, &SimulationOptions::default(), |s| {
        println!("free {:.2} s: crank {:.4} rad, energy {:.6} J", s.point.t, FreeRig::CRANK.phi(&s.point.q), s.energy.kinetic + s.energy.potential);
    })?;
    Ok(())
}
