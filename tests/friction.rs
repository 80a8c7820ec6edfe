//! Coulomb friction in joints (Nikravesh 4.5.3, 14.6): the normal load comes from the joint's
//! reaction λ, the law μ N v/√(v² + v_s²) is regularized below the slip velocity v_s.
//!
//! Checked against closed forms: a block sliding down an incline (a = g (sin θ − μ cos θ), load
//! m g cos θ), a block held by friction (μ > tan θ: it creeps at about v_s only), a pendulum's
//! pin friction torque μ R |F_pin|, and the energy balance with friction's work.
//! Tolerances: at |v| = 1 m/s and v_s = 1e-4 the regularized law differs from the sharp one by
//! a factor 1 − √(1 + (v_s/v)²)⁻¹ ≈ 5e-9; the fixed-point iteration stops at 1e-10 relative.
use mbd::prelude::*;

mechanism! {
    /// A block on a 30° incline with Coulomb friction μ.
    pub Incline {
        params { mu: 0.3, theta: PI / 6.0 }
        gravity [0.0, -9.81];
        body block { mass: 2.0, inertia: 0.05, at: [0.0, 0.0, theta] }
        translational ground[0.0, 0.0] along [cos(theta), sin(theta)] ~ block[0.0, 0.0] along [1.0, 0.0]
            { coulomb: mu, slip_velocity: 1.0e-4 };
    }
}

mechanism! {
    /// A rod pinned at one end with pin friction (radius 1 cm).
    pub FrictionPendulum {
        params { mu: 0.2 }
        gravity [0.0, -9.81];
        body rod { mass: 1.5, inertia: 0.125, at: [0.5, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ rod[-0.5, 0.0] { coulomb: mu, radius: 0.01, slip_velocity: 1.0e-3 };
    }
}

fn incline_state(m: &Incline, s: f64, v: f64) -> ([f64; 3], [f64; 3]) {
    let (sin, cos) = m.theta.sin_cos();
    ([s * cos, s * sin, m.theta], [v * cos, v * sin, 0.0])
}

#[test]
fn a_sliding_block_decelerates_by_mu_times_its_normal_load() {
    let m = Incline::default();
    let (sin, cos) = m.theta.sin_cos();
    for v in [-1.0, 1.0] {
        let (q, qd) = incline_state(&m, 0.3, v);
        let (mut qdd, mut lambda) = ([0.0; 3], [0.0; 2]);
        m.accelerations(&q, &qd, 0.0, &DynamicsOptions::default(), &mut qdd, &mut lambda).unwrap();
        let along = qdd[0] * cos + qdd[1] * sin;
        // Sliding down (v < 0) friction pushes up the slope, sliding up it pushes down.
        let expected = -9.81 * sin - v.signum() * m.mu * 9.81 * cos;
        assert!((along - expected).abs() < 1e-6 * expected.abs(), "v = {v}: a = {along} vs {expected}");
        assert!((lambda[0].abs() - 2.0 * 9.81 * cos).abs() < 1e-6, "normal load {} vs m g cos θ", lambda[0].abs());
    }
    assert!(Incline::EFFECTS.contains(&"Coulomb joint friction"));
}

#[test]
fn friction_holds_a_block_on_a_shallow_slope() {
    // μ = 0.8 > tan 30° ≈ 0.577: released at rest, the block creeps at about v_s only.
    let m = Incline { mu: 0.8, ..Incline::default() };
    let (q, qd) = incline_state(&m, 0.0, 0.0);
    let options = SimulationOptions { correction: Correction::projection(), ..SimulationOptions::default() };
    let mut last = q;
    let mut dopri = Dopri5::new(Dopri5Options { rtol: 1e-8, atol: 1e-10, ..Dopri5Options::default() });
    simulate(&m, &mut dopri, 0.0, &q, &qd, &[1.0], &options, |s| last = s.point.q).unwrap();
    let moved = (last[0] * last[0] + last[1] * last[1]).sqrt();
    // Creep speed v = v_s · r/√(1 − r²), r = tan θ / μ = 0.72: about 1.04 v_s.
    assert!(moved < 2e-4, "moved {moved} m in 1 s");
    // A slope steeper than the friction angle slides: 1 s at g (sin θ − μ cos θ).
    let slippery = Incline { mu: 0.3, ..Incline::default() };
    simulate(&slippery, &mut Dopri5::default(), 0.0, &q, &qd, &[1.0], &options, |s| last = s.point.q).unwrap();
    let moved = (last[0] * last[0] + last[1] * last[1]).sqrt();
    let (sin, cos) = slippery.theta.sin_cos();
    let expected = 0.5 * 9.81 * (sin - 0.3 * cos);
    assert!((moved - expected).abs() < 1e-3 * expected, "slid {moved} m, expected {expected}");
}

#[test]
fn pin_friction_torque_is_mu_r_times_the_pin_force() {
    let m = FrictionPendulum::default();
    let (theta, omega) = (-0.4_f64, 2.0);
    let (s, c) = theta.sin_cos();
    let q = [0.5 * c, 0.5 * s, theta];
    let qd = [-0.5 * s * omega, 0.5 * c * omega, omega];
    let (mut qdd, mut lambda) = ([0.0; 3], [0.0; 2]);
    m.accelerations(&q, &qd, 0.0, &DynamicsOptions::default(), &mut qdd, &mut lambda).unwrap();
    let pin = (lambda[0] * lambda[0] + lambda[1] * lambda[1]).sqrt();
    // Moments about the pin: J_O θ̈ = −m g l cos θ − μ R |F| (ω > 0, v_s ≪ ω).
    let j_o = 0.125 + 1.5 * 0.25;
    let torque = 0.2 * 0.01 * pin * omega / (omega * omega + 1e-6).sqrt();
    let expected = (-1.5 * 9.81 * 0.5 * c - torque) / j_o;
    assert!((qdd[2] - expected).abs() < 1e-9, "θ̈ = {} vs {expected}", qdd[2]);
    // The pin force itself: m a_G = F + m g.
    let fx = 1.5 * qdd[0];
    let fy = 1.5 * qdd[1] + 1.5 * 9.81;
    assert!(((fx * fx + fy * fy).sqrt() - pin).abs() < 1e-9);

}

#[test]
fn friction_work_closes_the_energy_balance() {
    let m = FrictionPendulum { mu: 0.3 };
    let q = [0.5, 0.0, 0.0];
    let options = SimulationOptions { correction: Correction::projection(), track_work: true, ..SimulationOptions::default() };
    let times: Vec<f64> = (0..=40).map(|k| k as f64 * 0.05).collect();
    let mut first = None;
    let mut worst: f64 = 0.0;
    let mut lost = 0.0;
    let mut dopri = Dopri5::new(Dopri5Options { rtol: 1e-10, atol: 1e-12, ..Dopri5Options::default() });
    simulate(&m, &mut dopri, 0.0, &q, &[0.0; 3], &times, &options, |s| {
        let b = s.energy.balance();
        let b0 = *first.get_or_insert(b);
        worst = worst.max((b - b0).abs());
        lost = -s.energy.nonconservative_work;
    })
    .unwrap();
    assert!(lost > 0.01, "friction dissipates: {lost} J");
    assert!(worst < 1e-7, "energy balance drift {worst:e} J");
}
