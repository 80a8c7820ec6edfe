//! Linear models from a mechanism, exact (guide/linearization.md):
//!
//! 1. An inverted pendulum on a cart, linearized about upright with the cart force as input:
//!    the state-space model a controller is designed on, written to CSV and JSON, its unstable
//!    pole against the closed form.
//! 2. The quarter car of `bump.rs` at rest on its tyre: ride and wheel-hop frequencies and
//!    damping ratios, against the 2-DOF model M z̈ + C ż + K z = 0 written out by hand.
//!
//! Run with `cargo run --release --example linear_models`.

// The quarter car is bump.rs's; the showcase and the tests reach bump.rs through here, since a
// file may be a module only once in a crate.
#[path = "bump.rs"]
#[allow(dead_code)] // its `main` is not used here
pub mod bump;

use bump::QuarterCar;
use mbd::nalgebra::{DMatrix, Matrix2};
use mbd::prelude::*;
use mbd::{LinearStability, LinearizeOptions, Linearizer, Output, StaticSolver};

mbd::mechanism! {
    /// A 0.6 m pole (0.2 kg) pinned on a 1 kg cart that a force `push` (N) drives along x.
    pub CartPole {
        params { push: 0.0 }
        gravity [0.0, -9.81];
        body cart { mass: 1.0, inertia: 0.05, at: [0.0, 0.0, 0.0] }
        body pole { mass: 0.2, inertia: 0.006, at: [0.0, 0.3, 1.5707963267948966] }
        translational ground[0.0, 0.0] along [1.0, 0.0] ~ cart[0.0, 0.0] along [1.0, 0.0];
        revolute cart[0.0, 0.0] ~ pole[-0.3, 0.0];
        force cart[0.0, 0.0] = [push, 0.0];
    }
}

/// What the run gives.
#[derive(Debug)]
#[allow(dead_code)] // read by the tests
pub struct Report {
    /// The cart-pole's unstable pole (1/s): mbd's, and the closed form
    /// s² = m g l (M + m) / ((M + m)(J + m l²) − m² l²).
    pub cart_pole_growth: (f64, f64),
    /// The cart-pole's B: ẍ and φ̈ per newton of push (mbd's), and the closed form's.
    pub cart_pole_input: ([f64; 2], [f64; 2]),
    /// The largest difference of [[A, B], [C, D]] between the exact and the finite-difference
    /// linearizations of the cart-pole, relative to its largest entry.
    pub exact_vs_differences: f64,
    /// Ride and wheel-hop natural frequencies (Hz): mbd's, and the hand-written 2-DOF model's.
    pub ride: (f64, f64),
    pub wheel_hop: (f64, f64),
    /// Their damping ratios: mbd's, and the 2-DOF model's.
    pub ride_damping: (f64, f64),
    pub wheel_hop_damping: (f64, f64),
    /// The velocity that dominates each mode (ride, wheel hop).
    pub dominant: (&'static str, &'static str),
}

/// (natural frequency in Hz, damping ratio) of the eigenvalues of a 4 × 4 state matrix, the
/// pair with Im s > 0, lower frequency first.
fn pairs(a: DMatrix<f64>) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = a
        .complex_eigenvalues()
        .iter()
        .filter(|s| s.im > 0.0)
        .map(|s| (s.norm() / (2.0 * std::f64::consts::PI), -s.re / s.norm()))
        .collect();
    out.sort_by(|x, y| x.0.total_cmp(&y.0));
    out
}

pub fn run(print: bool) -> Result<Report, Box<dyn std::error::Error>> {
    // 1. The cart-pole about upright.
    let m = CartPole::default();
    let q = m.initial_positions();
    let options = || {
        LinearizeOptions::default()
            .with_inputs(&["push"])
            .with_independent(&["cart.x", "pole.phi"])
            .with_output(Output::Displacement("cart.x"))
            .with_output(Output::Displacement("pole.phi"))
            .with_output(Output::Multiplier("revolute cart~pole: x"))
    };
    let lin = Linearizer::new(options()).linearize(&m, &q, &[0.0; 6], 0.0)?;
    let fd = Linearizer::new(options()).finite_differences(&m, &q, &[0.0; 6], 0.0)?;
    // [[A, B], [C, D]] entry by entry, against its largest entry.
    let system = |l: &mbd::Linearization| {
        let (n, i, o) = (l.a.nrows(), l.b.ncols(), l.c.nrows());
        let mut s = DMatrix::zeros(n + o, n + i);
        s.view_mut((0, 0), (n, n)).copy_from(&l.a);
        s.view_mut((0, n), (n, i)).copy_from(&l.b);
        s.view_mut((n, 0), (o, n)).copy_from(&l.c);
        s.view_mut((n, n), (o, i)).copy_from(&l.d);
        s
    };
    let (exact, differences) = (system(&lin), system(&fd));
    let difference = (&exact - &differences).amax() / exact.amax();
    let growth = match lin.stability() {
        LinearStability::Unstable { growth, .. } => growth,
        other => return Err(format!("the upright cart-pole should be unstable, found {other:?}").into()),
    };
    let (cart, pole, l, j, g) = (1.0, 0.2, 0.3, 0.006, 9.81);
    let det = (cart + pole) * (j + pole * l * l) - pole * pole * l * l;
    let closed = (pole * g * l * (cart + pole) / det).sqrt();
    // B: ẍ = (J + m l²)/det · F and φ̈ = m l/det · F: a push to +x leaves the pole's top behind,
    // turning it counter-clockwise (+φ).
    let closed_input = [(j + pole * l * l) / det, pole * l / det];
    let input = [lin.b[(2, 0)], lin.b[(3, 0)]];

    // 2. The quarter car at rest on its tyre.
    let car = QuarterCar::default();
    let mut qc = car.initial_positions();
    let mut ws = QuarterCar::workspace();
    StaticSolver::default().solve(&car, &mut ws, &mut qc, 0.0, &mut [0.0; 4])?;
    let car_lin =
        Linearizer::new(LinearizeOptions::default().with_independent(&["chassis.y", "wheel.y"])).linearize(&car, &qc, &[0.0; 6], 0.0)?;
    let modes = car_lin.modes();
    // The 2-DOF model by hand: z = (chassis height, wheel height).
    let (ms, mu, ks, cs, kt, ct) = (250.0, 35.0, 2.0e4, 1500.0, 2.0e5, 200.0);
    let mm = Matrix2::new(ms, 0.0, 0.0, mu);
    let kk = Matrix2::new(ks, -ks, -ks, ks + kt);
    let cc = Matrix2::new(cs, -cs, -cs, cs + ct);
    let mi = mm.try_inverse().ok_or("M is regular")?;
    let mut a = DMatrix::zeros(4, 4);
    a.view_mut((0, 2), (2, 2)).fill_with_identity();
    a.view_mut((2, 0), (2, 2)).copy_from(&(-mi * kk));
    a.view_mut((2, 2), (2, 2)).copy_from(&(-mi * cc));
    let hand = pairs(a);
    if modes.len() != 2 || hand.len() != 2 {
        return Err(format!("two oscillating modes expected: {modes:?}, {hand:?}").into());
    }
    let report = Report {
        cart_pole_growth: (growth, closed),
        cart_pole_input: (input, closed_input),
        exact_vs_differences: difference,
        ride: (modes[0].natural_frequency, hand[0].0),
        wheel_hop: (modes[1].natural_frequency, hand[1].0),
        ride_damping: (modes[0].damping_ratio, hand[0].1),
        wheel_hop_damping: (modes[1].damping_ratio, hand[1].1),
        dominant: (modes[0].dominant, modes[1].dominant),
    };
    if print {
        println!("Inverted pendulum on a cart, linearized about upright (states {:?}, input push):", lin.state_names);
        println!("A = {:.6}B = {:.6}", lin.a, lin.b);
        println!("unstable pole s = {growth:.12} 1/s (closed form {closed:.12})");
        println!("exact against finite differences: {difference:.1e} relative");
        let dir = std::path::Path::new("target/linear_models/cart_pole");
        lin.write_csv(dir)?;
        std::fs::write(dir.join("model.json"), lin.to_json())?;
        println!("A, B, C, D written to {}/ (CSV and model.json)", dir.display());
        println!("\nQuarter car at rest on its tyre:");
        for (mode, name) in modes.iter().zip(["ride", "wheel hop"]) {
            println!(
                "  {name:9}: {:.4} Hz, damping ratio {:.4}, dominant {} (chassis {:+.3}, wheel {:+.3})",
                mode.natural_frequency, mode.damping_ratio, mode.dominant, mode.shape[1].re, mode.shape[4].re
            );
        }
        println!("  2-DOF model by hand: ride {:.4} Hz / {:.4}, wheel hop {:.4} Hz / {:.4}", hand[0].0, hand[0].1, hand[1].0, hand[1].1);
    }
    Ok(report)
}

/// The cart-pole of part 1 released 0.01 rad off upright, for the showcase's pictures: the
/// instability its linear model's pole predicts, simulated (nonlinear) over 2 s, 201 frames.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let m = CartPole::default();
    // q: cart (x, y, φ), pole (x, y, φ), the pole's centre 0.3 m from the pin along its axis.
    let mut q = m.initial_positions();
    let phi = q[5] + 0.01;
    (q[3], q[4], q[5]) = (q[0] + 0.3 * phi.cos(), q[1] + 0.3 * phi.sin(), phi);
    let mut ws = CartPole::workspace();
    let times: Vec<f64> = (0..=200).map(|k| 0.01 * k as f64).collect();
    let mut animation = mbd::Animation::new::<CartPole>(&m.params()).title("Cart-pole released 0.01 rad off upright");
    Simulation::new(&m, &mut Dopri5::default())
        .start(0.0, &q, &[0.0; 6])
        .times(&times)
        .run(&mut ws, |s| animation.frame(s.point.t, &s.point.q))?;
    Ok(animation)
}

#[allow(dead_code)] // the showcase includes this file and calls `run`
fn main() {
    if let Err(e) = run(true) {
        eprintln!("linear_models: {e}");
        std::process::exit(1);
    }
}
