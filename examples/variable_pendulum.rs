//! Variable-length pendulum (Nikravesh, *Planar Multibody Dynamics*): a rod slides through a
//! collar pinned to ground; the swing angle and the length are both driven, so the analysis is
//! kinematic. The bob (the rod's centre of mass, at its lower end) has, in polar coordinates,
//! radial acceleration L̈ − L θ̇² and transverse acceleration L θ̈ + 2 L̇ θ̇ (Coriolis): both are
//! compared with the generated solution.
//!
//! Run: `cargo run --release --example variable_pendulum`
use mbd::nalgebra::Vector2;
use mbd::prelude::*;

mechanism! {
    /// Pendulum whose length L(t) = L0 + dl sin 2ωt and swing θ(t) = θ0 sin ωt are driven.
    pub VariablePendulum {
        params { l0: 1.0, dl: 0.2, theta0: 0.5, omega: PI }
        body collar { mass: 0.2, inertia: 1.0e-3, at: [0.0, 0.0, -PI / 2.0] }
        body rod    { mass: 1.0, inertia: 0.05, at: [0.0, -1.0, -PI / 2.0] }
        point rod.bob = [0.0, 0.0];
        revolute ground[0.0, 0.0] ~ collar[0.0, 0.0];
        translational collar[0.0, 0.0] along [1.0, 0.0] ~ rod.bob along [1.0, 0.0];
        drive collar.phi = -PI / 2.0 + theta0 * sin(omega * t);
        drive distance(ground[0.0, 0.0], rod.bob) = l0 + dl * sin(2.0 * omega * t);
    }
}

#[derive(Debug, Clone, Copy)]
pub struct Report {
    pub samples: usize,
    /// max |r − r_exact| of the bob (m).
    pub position_error: f64,
    /// max |v − v_exact| (m/s).
    pub velocity_error: f64,
    /// max |a − a_exact| (m/s²), Coriolis term included.
    pub acceleration_error: f64,
    /// Largest Coriolis acceleration 2 L̇ θ̇ met (m/s²): shows the check is not trivial.
    pub max_coriolis: f64,
}

/// Exact bob position, velocity and acceleration from the polar form.
pub fn exact(p: &VariablePendulum, t: f64) -> ([f64; 2], [f64; 2], [f64; 2], f64) {
    let w = p.omega;
    let th = p.theta0 * (w * t).sin();
    let thd = p.theta0 * w * (w * t).cos();
    let thdd = -p.theta0 * w * w * (w * t).sin();
    let l = p.l0 + p.dl * (2.0 * w * t).sin();
    let ld = 2.0 * w * p.dl * (2.0 * w * t).cos();
    let ldd = -4.0 * w * w * p.dl * (2.0 * w * t).sin();
    // e_r = (sin θ, −cos θ), e_θ = (cos θ, sin θ)
    let (s, c) = th.sin_cos();
    let (er, et) = ([s, -c], [c, s]);
    let ar = ldd - l * thd * thd;
    let coriolis = 2.0 * ld * thd;
    let at = l * thdd + coriolis;
    (
        [l * er[0], l * er[1]],
        [ld * er[0] + l * thd * et[0], ld * er[1] + l * thd * et[1]],
        [ar * er[0] + at * et[0], ar * er[1] + at * et[1]],
        coriolis,
    )
}

fn dist(a: [f64; 2], b: Vector2<f64>) -> f64 {
    ((a[0] - b.x).powi(2) + (a[1] - b.y).powi(2)).sqrt()
}

pub fn run(print: bool) -> Result<Report, KinematicError> {
    let m = VariablePendulum::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = VariablePendulum::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let mut r = Report { samples: 0, position_error: 0.0, velocity_error: 0.0, acceleration_error: 0.0, max_coriolis: 0.0 };
    if print {
        println!("Variable-length pendulum: L = {} + {} sin 2ωt m, θ = {} sin ωt rad, ω = {:.4} rad/s", m.l0, m.dl, m.theta0, m.omega);
        println!(
            "{:>6} {:>9} {:>9} {:>10} {:>10} {:>10} {:>10} {:>10}",
            "t (s)", "x (m)", "y (m)", "vx (m/s)", "vy (m/s)", "ax (m/s²)", "ay (m/s²)", "Coriolis"
        );
    }
    let times = (0..=80).map(|k| 2.0 * k as f64 / 80.0);
    let bob = m.rod_bob();
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, v, vd| {
        let (p, velocity, a, cor) = exact(&m, t);
        let (bob_p, bob_v, bob_a) = (bob.position(q).coords, bob.velocity(q, v), bob.acceleration(q, v, vd));
        r.position_error = r.position_error.max(dist(p, bob_p));
        r.velocity_error = r.velocity_error.max(dist(velocity, bob_v));
        r.acceleration_error = r.acceleration_error.max(dist(a, bob_a));
        r.max_coriolis = r.max_coriolis.max(cor.abs());
        r.samples += 1;
        if print && r.samples % 8 == 1 {
            println!(
                "{:>6.3} {:>9.5} {:>9.5} {:>10.5} {:>10.5} {:>10.4} {:>10.4} {:>10.4}",
                t, bob_p.x, bob_p.y, bob_v.x, bob_v.y, bob_a.x, bob_a.y, cor
            );
        }
    })?;
    if print {
        println!(
            "max error vs polar closed form: r {:.1e} m, v {:.1e} m/s, a {:.1e} m/s² (Coriolis up to {:.3} m/s²)",
            r.position_error, r.velocity_error, r.acceleration_error, r.max_coriolis
        );
    }
    Ok(r)
}

/// One period of the swing, for the showcase's pictures: a kinematic sweep of 80 steps.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let m = VariablePendulum::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = VariablePendulum::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let mut animation =
        mbd::Animation::new::<VariablePendulum>(&m.params()).title("Variable-length pendulum, one swing period").trace("rod.bob");
    let period = 2.0 * PI / m.omega;
    let times = (0..=80).map(|k| period * k as f64 / 80.0);
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, _, _| animation.frame(t, q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("variable_pendulum: {e}");
        std::process::exit(1);
    }
}
