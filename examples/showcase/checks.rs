//! Every example runs and its result agrees with what physics or geometry says it must be: the
//! showcase's tests (`cargo test` builds the showcase, which holds every example, once, as a test;
//! Cargo.toml's `[[example]] showcase`).
//!
//! Tolerances: the position solves stop at |Φ|∞ ≤ 1e-10 (the solver's default tolerance), and
//! Newton's quadratic convergence usually lands far below it; positions derived from a converged
//! configuration are then exact to about that level times the conditioning of the mechanism
//! (O(1–10) away from singular positions), so positions are checked to 1e-8 m. Velocities and
//! accelerations come from exact linear solves at that configuration; with speeds of O(1–10) m/s
//! and accelerations up to O(100) m/s², they are checked to 1e-7 relative to those scales.
use super::*;

/// The guide's table of examples (`guide/examples.md`). Each figure it quotes from an example is
/// held here to what the example computes ([`quotes`], [`bounds`]), so that none goes stale.
const TABLE: &str = include_str!("../../guide/examples.md");

/// The table's row of `example`.
fn row(example: &str) -> &'static str {
    let start = format!("| `{example}` |");
    TABLE.lines().find(|l| l.starts_with(&start)).unwrap_or_else(|| panic!("guide/examples.md has no row for `{example}`"))
}

/// The first number written in `text` ("lets go at 1.0194 s" → 1.0194, "87 918 N" → 87918,
/// "6e-11 apart" → 6e-11) and its last digit's place (1e-4, 1, 1e-11).
fn number(text: &str) -> (f64, f64) {
    let start = text.find(|c: char| c.is_ascii_digit()).unwrap_or_else(|| panic!("no number in {text:?}"));
    let chars: Vec<char> = text[start..].chars().collect();
    let digit = |i: usize| chars.get(i).is_some_and(|c| c.is_ascii_digit());
    let mut digits = String::new();
    let mut i = 0;
    while let Some(&c) = chars.get(i) {
        if c.is_ascii_digit() || (c == '.' && !digits.contains(['.', 'e'])) {
            digits.push(c);
        } else if matches!(c, ' ' | '\u{202f}' | '\u{a0}') && !digits.contains(['.', 'e']) && (1..=3).all(|k| digit(i + k)) && !digit(i + 4)
        {
            // A thousands separator: between groups of three digits.
        } else if c == 'e' && !digits.contains('e') && (digit(i + 1) || (matches!(chars.get(i + 1), Some('-' | '+')) && digit(i + 2))) {
            digits.push('e');
            if !digit(i + 1) {
                digits.push(chars[i + 1]);
                i += 1;
            }
        } else {
            break;
        }
        i += 1;
    }
    let value: f64 = digits.parse().unwrap_or_else(|_| panic!("{digits:?} in {text:?} is not a number"));
    let (mantissa, exponent) = digits.split_once('e').map_or((digits.as_str(), 0), |(m, e)| (m, e.parse::<i32>().expect("an exponent")));
    let decimals = mantissa.split_once('.').map_or(0, |(_, f)| f.len() as i32);
    (value, 10f64.powi(exponent - decimals))
}

/// The table quotes `text` for `example`, and the first number in it is `value` rounded to the
/// digits it is written with.
fn quotes(example: &str, text: &str, value: f64) {
    assert!(row(example).contains(text), "guide/examples.md's row for `{example}` should quote {text:?}");
    assert!(written_as(text, value), "`{example}` computes {value}, which guide/examples.md quotes as {text:?}");
}

/// The guide's other chapters that quote an example's figure, each held here like the table's.
const PAGES: [(&str, &str); 10] = [
    ("guide/linearization.md", include_str!("../../guide/linearization.md")),
    ("guide/dsl.md", include_str!("../../guide/dsl.md")),
    ("guide/performance.md", include_str!("../../guide/performance.md")),
    ("guide/projects/elliptical.md", include_str!("../../guide/projects/elliptical.md")),
    ("guide/projects/engine.md", include_str!("../../guide/projects/engine.md")),
    ("guide/projects/head-and-neck.md", include_str!("../../guide/projects/head-and-neck.md")),
    ("guide/projects/mountain-bike.md", include_str!("../../guide/projects/mountain-bike.md")),
    ("guide/projects/sled-test.md", include_str!("../../guide/projects/sled-test.md")),
    ("guide/projects/swing.md", include_str!("../../guide/projects/swing.md")),
    ("guide/projects/windshield-wiper.md", include_str!("../../guide/projects/windshield-wiper.md")),
];

/// The text of `page`, one of [`PAGES`].
fn page(page: &str) -> &'static str {
    PAGES.iter().find(|(name, _)| *name == page).unwrap_or_else(|| panic!("{page} is not in PAGES")).1
}

/// The first number in `text` is `value` rounded to the digits it is written with.
fn written_as(text: &str, value: f64) -> bool {
    let (written, place) = number(text);
    (value - written).abs() <= 0.5 * place * (1.0 + 1e-9)
}

/// `name` (one of [`PAGES`]) quotes `text`, and the first number in it is `value` rounded to the
/// digits it is written with; or, with `bound`, the first number bounds `value`.
fn page_quotes(name: &str, text: &str, value: f64, bound: bool) {
    assert!(page(name).contains(text), "{name} should quote {text:?}");
    if bound {
        assert!(value <= number(text).0, "{name} bounds by {text:?} a figure that is {value:e}");
    } else {
        assert!(written_as(text, value), "{name} quotes {text:?} for {value}");
    }
}

/// The table bounds an error of `example` by `≤ bound` (its text), and the error is within it.
fn bounds(example: &str, text: &str, error: f64) {
    assert!(row(example).contains(text) && text.contains('≤'), "guide/examples.md's row for `{example}` should bound the error: {text:?}");
    let (bound, _) = number(text);
    assert!(error <= bound, "`{example}`: an error of {error:e}, which guide/examples.md bounds by {text:?}");
}

#[test]
fn numbers_are_read_as_written() {
    assert_eq!(number("lets go at 1.0194 s"), (1.0194, 1e-4));
    assert_eq!(number("87 918, 13 128 and 7 155 N").0, 87918.0);
    assert_eq!(number("13 128 and 7 155 N").0, 13128.0);
    assert_eq!(number("12 periods").0, 12.0);
    assert_eq!(number("(≤ 1e-11 relative)"), (1e-11, 1e-11));
    assert_eq!(number("2.4e-11 of 169 N"), (2.4e-11, 1e-12));
    assert_eq!(number("bump stop 1.0224–1.0463 s").0, 1.0224);
    assert_eq!(number("1 234 567 N").0, 1234567.0);
    assert_eq!(number("3 each").0, 3.0);
}

#[test]
fn slider_crank_matches_its_closed_form() {
    let r = slider_crank::run(false).expect("slider-crank runs");
    assert_eq!(r.samples, 73);
    assert!(r.position_error < 1e-8, "{r:?}");
    assert!(r.velocity_error < 1e-7, "{r:?}");
    assert!(r.acceleration_error < 1e-5, "{r:?}");
    assert!(r.max_residual <= 1e-10, "{r:?}");
    // stroke of a slider-crank with zero offset is 2r = 0.2 m (sampled every 5° it includes θ = 0 and 180°)
    assert!((r.stroke - 0.2).abs() < 1e-8, "{r:?}");
}

#[test]
fn four_bar_matches_its_closed_form() {
    let r = four_bar::run(false).expect("four-bar runs");
    assert!(r.pin_error < 1e-8, "{r:?}");
    assert!(r.max_residual <= 1e-10, "{r:?}");
    // A crank-rocker: the rocker swings through a finite angle, never a full turn.
    assert!(r.rocker_swing > 0.3 && r.rocker_swing < std::f64::consts::PI, "{r:?}");
    assert!(r.min_transmission_angle > 20.0, "{r:?}");
}

#[test]
fn variable_pendulum_has_the_polar_accelerations() {
    let r = variable_pendulum::run(false).expect("variable pendulum runs");
    assert!(r.position_error < 1e-8, "{r:?}");
    assert!(r.velocity_error < 1e-7, "{r:?}");
    assert!(r.acceleration_error < 1e-6, "{r:?}");
    // 2 L̇ θ̇ peaks at 2 · (2ω·dl) · (θ0·ω) = 2 · 1.257 · 1.571 ≈ 3.9 m/s²: the Coriolis term matters.
    assert!(r.max_coriolis > 1.0, "{r:?}");
}

#[test]
fn filmstrip_claw_follows_its_closed_form() {
    let r = filmstrip::run(false).expect("filmstrip runs");
    assert!(r.tip_error < 1e-8, "{r:?}");
    // The loop's size, from the closed form sampled finely when the example was designed: 40.13 mm
    // along the film and 24.99 mm across it. The 97 sampled crank angles see slightly less of it.
    assert!((r.stroke - 0.04013).abs() < 2e-4, "{r:?}");
    assert!((r.lift - 0.02499).abs() < 2e-4, "{r:?}");
}

#[test]
fn web_cutter_knife_rides_level() {
    let r = web_cutter::run(false).expect("web cutter runs");
    assert!(r.knife_error < 1e-8, "{r:?}");
    // Chebyshev's linkage: ~86 mm of travel within about half a millimetre of a straight line
    // (computed independently by the closed form when this example was designed).
    assert!(r.travel > 0.08 && r.travel < 0.09, "{r:?}");
    assert!(r.straightness < 1e-3, "{r:?}");
    assert!(r.mid_speed > 0.0, "{r:?}");
}

#[test]
fn double_a_arm_sweeps_its_travel() {
    let r = double_a_arm::run(false).expect("double A-arm runs");
    assert_eq!(r.samples, 65);
    assert!(r.link_length_error < 1e-8, "{r:?}");
    // Short-long arms: the camber changes over ±80 mm, by degrees, not tens of degrees.
    assert!(r.camber_max - r.camber_min > 0.5 && r.camber_max - r.camber_min < 15.0, "{r:?}");
    assert!(r.spring_max > r.spring_min);
    // The spring sits between pivot and ball joint: it is compressed in bump, less than the wheel moves.
    assert!(r.motion_ratio > 0.1 && r.motion_ratio < 1.0, "{r:?}");
    // A short upper arm over a long lower one: the wheel's top leans inward in bump (negative camber gain).
    assert!(r.camber_min < -1.0, "{r:?}");
}

#[test]
fn macpherson_strut_sweeps_its_travel() {
    let r = macpherson::run(false).expect("MacPherson runs");
    assert_eq!(r.samples, 65);
    assert!(r.axis_error < 1e-8, "{r:?}");
    assert!(r.camber_max - r.camber_min > 0.1 && r.camber_max - r.camber_min < 15.0, "{r:?}");
    // The strut runs nearly in line with the wheel's vertical travel: it is compressed in bump by
    // a little less than the wheel moves.
    assert!(r.motion_ratio > 0.5 && r.motion_ratio <= 1.0, "{r:?}");
    assert!(r.strut_max - r.strut_min > 0.1, "{r:?}");
}

/// The power balance P_drive + P_gas + P_gravity = dT/dt holds at every sample; over a revolution
/// at constant speed T and V return to their start, and their rates are smooth and periodic, so
/// the midpoint mean of dT/dt and of gravity's power vanishes to rounding: the mean drive power
/// must cancel the mean gas power to 1e-9 relative.
#[test]
fn engine_drive_power_balances_gas_work() {
    let r = flywheel_engine::slider_crank_inverse::run(false).expect("inverse dynamics runs");
    assert_eq!(r.samples, 360);
    assert!((r.drive_power + r.gas_power).abs() <= 1e-9 * r.gas_power.abs(), "{r:?}");
    assert!(r.gas_power > 100.0, "{r:?}");
    // The drive brakes during expansion: the torque on the crank is then negative, and the
    // bearing carries about the peak gas force.
    assert!(r.torque_min < -50.0 && r.bearing_max > 1500.0, "{r:?}");
}

/// The free engine settles at the design speed the inverse dynamics sized its generator for,
/// and its speed fluctuation is the one the inverse dynamics predicts (to first order in δ:
/// δ ≈ 0.05, so a few per cent of δ).
#[test]
fn flywheel_engine_runs_at_the_speed_its_inverse_dynamics_predicts() {
    let r = flywheel_engine::run(false).expect("the engine runs");
    assert!((r.omega_mean - r.omega_design).abs() < 0.01 * r.omega_design, "{r:?}");
    assert!(r.delta > 0.01 && (r.delta - r.delta_predicted).abs() < 0.05 * r.delta_predicted, "{r:?}");
    quotes("flywheel_engine", "δ 0.0486", r.delta);
    quotes("flywheel_engine", "vs 0.0486", r.delta_predicted);
}

/// The variable-length pendulum pumped at twice its swing frequency: the swing grows (parametric
/// resonance), follows the hand-derived reduced model, and the length driver's work is the
/// energy gained.
///
/// Tolerances: DOPRI5 at rtol 1e-10 with projection over 12 periods (~3600 steps): local errors
/// of ~1e-10 rad accumulate to ~1e-8 at worst, so 1e-7 rad on θ; the reduced model's RK4 error is
/// below 1e-12. Energies: the work integral and T + V carry rtol · E ≈ 1e-9 J per step, so a
/// random-walk drift of ~1e-7 J at worst: 1e-6 J, against the ~4 J the driver pumps in.
#[test]
fn pumped_pendulum_follows_its_reduced_model() {
    let r = pumped_pendulum::run(false).expect("the pumped pendulum runs");
    assert!(r.amplitude_end > 3.0 * r.amplitude_start, "the swing is pumped up: {r:?}");
    assert!(r.angle_error < 1e-7, "{r:?}");
    assert!(r.driver_work > 1.0, "{r:?}");
    assert!((r.driver_work - r.energy_gain_reduced).abs() < 1e-6, "{r:?}");
    assert!(r.balance_drift < 1e-6, "{r:?}");
    // The driver holds the rod against gravity and the centrifugal force: at least m g.
    assert!(r.peak_pull > 9.81, "{r:?}");
    quotes("pumped_pendulum", "pumped up 5×", r.amplitude_end / r.amplitude_start);
    bounds("pumped_pendulum", "(≤ 1e-8 rad)", r.angle_error);
    quotes("pumped_pendulum", "4.028918 J both", r.driver_work);
    quotes("pumped_pendulum", "4.028918 J both", r.energy_gain_reduced);
}

/// Nikravesh's project 15.8 (guide/projects/swing.md): a small swing grows at the rate the
/// averaged small-amplitude model gives, (ω/4)(α + β), within 3 % — the model is first order in
/// the pumping's relative size α + β ≈ 0.028 and in the amplitude (0.02–0.03 rad: a frequency
/// shift of a²/16 ≈ 6e-5), measured 0.1 %; over every period of both runs the driver's work
/// equals the change of T + V written by hand, within 1e-5 J (the work is integrated with the
/// motion by DOPRI5 at rtol 1e-10, on energies up to ~700 J: its truncation error, up to ~7e-8 J
/// a step, over ~10³ steps a period; measured 1.8e-6 J); the full stroke pumps the swing from
/// 0.1 rad past 80° in period 7 before the steady rhythm falls out of phase; the chains stay
/// taut; and the peak crossbar load compares with a designer's estimate by hand within the size
/// of the terms that estimate leaves out (a comparison, not a bound: it also leaves out the
/// energy exchanged over the last half-swing; measured 34 N apart against 159 N).
#[test]
fn swing_grows_at_the_averaged_models_rate() {
    let r = swing::run(false).expect("the swing runs");
    assert!((r.growth_rate - r.growth_rate_closed_form).abs() < 0.03 * r.growth_rate_closed_form, "{r:?}");
    assert!(r.balance_error < 1e-5, "{r:?}");
    let largest = r.amplitudes.iter().fold(0.0f64, |a, &b| a.max(b));
    assert!(largest > 80f64.to_radians() && largest < std::f64::consts::FRAC_PI_2, "{r:?}");
    assert_eq!(r.amplitudes[6], largest, "the largest swing in period 7: {r:?}");
    assert!(r.pumping_periods >= 5 && r.pumping_periods < r.amplitudes.len(), "{r:?}");
    assert!((r.peak_crossbar_force - r.crossbar_estimate).abs() <= r.omitted, "{r:?}");
    assert!(r.least_chain_tension > 0.0, "{r:?}");
    quotes("swing", "γ = 0.01740 1/s", r.growth_rate);
    quotes("swing", "0.01738 1/s", r.growth_rate_closed_form);
    quotes("swing", "85.5° in period 7", largest.to_degrees());
    quotes("swing", "852 N", r.peak_crossbar_force);
    quotes("swing", "818 N", r.crossbar_estimate);
    bounds("swing", "(≤ 1e-5 J)", r.balance_error);
    // The project's page quotes the rest: each period's amplitude and energy, the power, forces.
    let page = "guide/projects/swing.md";
    for (k, (a, w)) in r.amplitudes.iter().zip(&r.energy_per_cycle).enumerate() {
        let row = format!("| {} | {:.2} | {:.2} |", k + 1, a.to_degrees(), w).replace('-', "−");
        assert!(self::page(page).contains(&row), "{page} should have the row {row:?}");
    }
    page_quotes(page, "about 1.55× a period", r.amplitudes[1] / r.amplitudes[0], false);
    page_quotes(page, "24.0 W on average", r.pumping_power, false);
    page_quotes(page, "up to 663 N", r.peak_leg_force, false);
    page_quotes(page, "2.71 × the child's weight", r.peak_leg_force / (25.0 * 9.81), false);
    page_quotes(page, "up to 852 N", r.peak_crossbar_force, false);
    page_quotes(page, "2.83 × the weight", r.peak_crossbar_force / r.weight, false);
    page_quotes(page, "818 N by hand", r.crossbar_estimate, false);
    page_quotes(page, "up to 159 N", r.omitted, false);
    page_quotes(page, "at least 128 N", r.least_chain_tension, false);
    page_quotes(page, "within 1.8e-6 J", r.balance_error, false);
    page_quotes(page, "asserted ≤ 1e-5 J", r.balance_error, true);
    page_quotes(page, "ω = 2.4946 rad/s", r.omega, false);
}

/// Nikravesh's project 15.1 (guide/projects/windshield-wiper.md): over one turn of the motor
/// both blades follow the four-bars' closed forms (within 1e-8 rad: the kinematic solver's
/// tolerance, measured 3.9e-9), their sweeps the limit positions' (within 1e-3 rad: the samples
/// are 1° of crank apart, and near a reversal a blade's angle is within ½ (½°)² × its
/// curvature of the extreme; measured 1.6e-5), the transmission angles their closed form at
/// every sample and the first's least the closed form's with the crank pointing at the pivot
/// (within 1e-3 rad, the samples' spacing as above); both blades reverse at the closed-form
/// limit positions (within 1° of crank, the samples' spacing); the motor's torque meets virtual
/// power at every sample (1e-9 of the peak power: rounding of the inverse dynamics) and its mean
/// power the friction the blades' sweeps take by hand, 2 (T_f1 Δψ₁ + T_f2 Δψ₂)/T (within 1 %:
/// the friction's regularization below 0.01 rad/s and the midpoint rule's error on a power with
/// kinks at the reversals are both small; measured 3e-5).
#[test]
fn windshield_wiper_follows_its_closed_forms() {
    let r = windshield_wiper::run(false).expect("the wiper runs");
    assert_eq!(r.samples, 360);
    assert!(r.angle_error < 1e-8 && r.transmission_error < 1e-8, "{r:?}");
    assert!((r.sweep1 - r.sweep1_closed_form).abs() < 1e-3 && (r.sweep2 - r.sweep2_closed_form).abs() < 1e-3, "{r:?}");
    assert!((r.transmission1 - r.transmission1_closed_form).abs() < 1e-3, "{r:?}");
    for k in 0..2 {
        use std::f64::consts::{PI, TAU};
        let apart = |a: f64, b: f64| ((a - b + PI).rem_euclid(TAU) - PI).abs();
        assert!(apart(r.reversals1[k], r.limit_positions[k]) <= 1f64.to_radians(), "{r:?}");
        assert!(apart(r.reversals2[k], r.limit_positions[k]) <= 1f64.to_radians(), "{r:?}");
    }
    assert!(r.power_error < 1e-9 * r.peak_power, "{r:?}");
    assert!((r.mean_power - r.mean_power_closed_form).abs() < 1e-2 * r.mean_power_closed_form, "{r:?}");
    quotes("windshield_wiper", "driver's blade 90.44°", r.sweep1_closed_form.to_degrees());
    quotes("windshield_wiper", "passenger's 75.93°", r.sweep2_closed_form.to_degrees());
    quotes("windshield_wiper", "at least 33.3°", r.transmission1_closed_form.to_degrees());
    quotes("windshield_wiper", "and 50.9°", r.transmission2.to_degrees());
    quotes("windshield_wiper", "mean power 3.420 W both", r.mean_power);
    quotes("windshield_wiper", "mean power 3.420 W both", r.mean_power_closed_form);
    bounds("windshield_wiper", "(≤ 1e-8 rad)", r.angle_error);
    let page = "guide/projects/windshield-wiper.md";
    page_quotes(page, "up to 1.478 N·m", r.torque_max, false);
    page_quotes(page, "3.420 W", r.mean_power, false);
    page_quotes(page, "angles 2.6° and 178.8°", r.limit_positions[0].to_degrees(), false);
    page_quotes(page, "and 178.8°", r.limit_positions[1].to_degrees(), false);
    page_quotes(page, "by 14.5°", (r.relative_max - r.relative_min).to_degrees(), false);
    page_quotes(page, "least 33.3°", r.transmission1.to_degrees(), false);
    page_quotes(page, "33.29° by the closed form", r.transmission1_closed_form.to_degrees(), false);
    page_quotes(page, "within 3.9e-9 rad", r.angle_error, false);
    page_quotes(page, "within 3.4e-9 rad", r.transmission_error, false);
    page_quotes(page, "within 2.2e-15 W", r.power_error, false);
    page_quotes(page, "of 6.97 W", r.peak_power, false);
    page_quotes(page, "least −0.003 N·m", -r.torque_min, false);
}

/// Nikravesh's project 15.2 (guide/projects/engine.md): at constant speed the crank torque and
/// the main-bearing, crank-pin and piston-pin loads, the side thrust and the shaking force agree
/// at every sample with a force analysis by hand from the slider-crank's closed-form kinematics,
/// the gas force taken at the closed form's piston position (within 1e-7 of the peak torque and
/// of the peak load: the position solve stops at |Φ| ≤ 1e-10 m, and the gas force changes by
/// ~2e6 N/m near TDC, so a 1e-10 m difference in the piston's position is ~2e-4 N, ~1.5e-8 of the
/// 14 kN peak; measured 3e-9 and 2e-9); the mean torque is the cycle's work by quadrature over
/// 4π (within 1e-6 relative: Simpson's rule on 7200 intervals against the midpoint rule on 720
/// samples of a torque that is C¹ where the valve opens; measured 3e-9), and that work is the
/// datasheet's 11.0 N·m × 4π by the calibration of r_p (a check of the calibration, not of the
/// model); the shaking force along the cylinder is the reciprocating mass's at TDC, m_rec r ω²
/// (1 + λ − b), and, with full balance, λ/√(1 − λ²) of it at 90°, and across it b m_rec r ω², for
/// each balance b (within 1 N: the samples are ½° from TDC and from 90°, where each is largest;
/// 1 − cos ½° ≈ 4e-5); and the free engine, started at the steady speed for the firing TDC with
/// the flywheel sized for δ = 0.04, fluctuates by that δ (within 5 %: the sizing is first order
/// in δ; measured 0.5 %) about the design speed (within 5 rpm: the mean speed is the design's to
/// second order in δ, δ² ≈ 0.2 %; measured 0.2 rpm).
#[test]
fn engine_meets_its_hand_analysis() {
    let r = engine::run(false).expect("the engine runs");
    assert!(r.torque_error < 1e-7 * r.torque_max, "{r:?}");
    let peak_load = r.main_max.0.max(r.crank_pin_max.0).max(r.piston_pin_max.0);
    assert!(r.load_error < 1e-7 * peak_load, "{r:?}");
    assert!((r.torque_mean - r.torque_by_hand).abs() < 1e-6 * r.torque_by_hand, "{r:?}");
    assert!((r.torque_by_hand - 11.0).abs() < 1e-9, "the calibration of r_p: {r:?}");
    // The reciprocating mass (piston and the rod's small-end share) and λ = r/l, as in the model.
    let (m_rec, lambda, r_omega2) = (0.18 + 0.12 * 0.025 / 0.080, 0.0225 / 0.080, 0.0225 * (2500.0 * std::f64::consts::PI / 30.0).powi(2));
    for (b, along, across) in r.shaking {
        // Along the cylinder: largest at TDC, (1 + λ − b) m_rec r ω², at these balances; at b = 1
        // only the rod's angularity is left, largest at 90°, where the piston's acceleration is
        // r ω² λ/√(1 − λ²) exactly.
        let along_closed_form =
            if b < 1.0 { m_rec * r_omega2 * (1.0 + lambda - b) } else { m_rec * r_omega2 * lambda / (1.0 - lambda * lambda).sqrt() };
        assert!((along - along_closed_form).abs() < 1.0, "balance {b}: {along} N against {along_closed_form} N");
        assert!((across - b * m_rec * r_omega2).abs() < 1.0, "balance {b}: {across} N across");
    }
    assert!((r.delta - 0.04).abs() < 0.05 * 0.04, "{r:?}");
    assert!((r.rpm_mean - 2500.0).abs() < 5.0, "{r:?}");
    assert_eq!(r.cycles, 60);
    quotes("engine", "mean torque 11.0000 N·m", r.torque_mean);
    quotes("engine", "δ = 0.0402", r.delta);
    quotes("engine", "cylinder 430 N", r.shaking[0].1);
    quotes("engine", "262 N (half)", r.shaking[1].1);
    quotes("engine", "98 N (all)", r.shaking[2].1);
    bounds("engine", "(≤ 1e-7 of the peak)", (r.torque_error / r.torque_max).max(r.load_error / peak_load));
    let page = "guide/projects/engine.md";
    page_quotes(page, "ratio of 3.664", r.rp, false);
    page_quotes(page, "pressure of 39.8 bar", r.peak_pressure / 1e5, false);
    page_quotes(page, "at 16.6° after TDC", r.peak_pressure_at, false);
    page_quotes(page, "work of 138.23 J", r.work, false);
    page_quotes(page, "mean of 11.0000 N·m", r.torque_mean, false);
    page_quotes(page, "largest 149.5 N·m", r.torque_max, false);
    page_quotes(page, "at 28.5° after", r.torque_max_at, false);
    page_quotes(page, "least −35.2 N·m", -r.torque_min, false);
    page_quotes(page, "at 24.5° before", -r.torque_min_at, false);
    page_quotes(page, "13.6 times the mean", r.torque_max / r.torque_mean, false);
    page_quotes(page, "up to 13 911 N", r.main_max.0, false);
    page_quotes(page, "up to 13 612 N", r.crank_pin_max.0, false);
    page_quotes(page, "up to 13 798 N", r.piston_pin_max.0, false);
    for at in [r.main_max.1, r.crank_pin_max.1, r.piston_pin_max.1] {
        page_quotes(page, "at 16.5° after the firing TDC", at, false);
    }
    page_quotes(page, "up to 1 508 N", r.side_max, false);
    page_quotes(page, "at most 554 N", r.open_valves_max, false);
    page_quotes(page, "by 148.6 J", r.energy_swing, false);
    page_quotes(page, "J = 0.0542 kg·m²", r.crank_inertia + r.reduced, false);
    page_quotes(page, "add 9.61e-5 kg·m²", r.reduced, false);
    page_quotes(page, "c = 0.04202 N·m·s", r.c_load, false);
    page_quotes(page, "2499.8 rpm over its 60th cycle", r.rpm_mean, false);
    page_quotes(page, "δ = 0.0402.", r.delta, false);
    page_quotes(page, "within 1e-6 N·m of torque", r.torque_error, true);
    page_quotes(page, "and 1e-4 N of load", r.load_error, true);
    page_quotes(page, "11.0000 N·m both", r.torque_by_hand, false);
    for (k, text) in ["| none | 430 N | 0 N |", "| half (the design) | 262 N | 168 N |", "| all | 98 N | 335 N |"].into_iter().enumerate() {
        let (_, along, across) = r.shaking[k];
        let row = text.split('|').map(str::trim).collect::<Vec<_>>();
        assert!(self::page(page).contains(text), "{page} should hold the row {text:?}");
        assert!(written_as(row[2], along) && written_as(row[3], across), "{page}: {text:?} against {along} N and {across} N");
    }
}

/// Nikravesh's project 15.7 (guide/projects/elliptical.md): over one stride the left pedal
/// follows the four-bar's closed form (within 1e-8 m: the kinematic solver's tolerance; measured
/// 3.5e-11), its stride and lift the closed form's extent on a 0.01° grid (within 1e-3 m: the
/// samples are 1° of crank apart, and near an extreme the path is within ½ (½°)² × its
/// curvature of it), the transmission angle its closed form at every sample (1e-8 rad) and its
/// least the closed form's at the extremes of the pin's distance from the arm's pivot (within
/// 1e-3 rad, the samples' spacing as above); the crank torque meets virtual power at every sample
/// (1e-9 of the peak power: rounding of the inverse dynamics) and its mean power the brake's
/// c ω² by hand (1e-6 relative: the kinetic and potential energies return over the stride, and
/// the midpoint rule's mean of their smooth periodic rates is exact to rounding).
#[test]
fn elliptical_follows_its_closed_forms() {
    let r = elliptical::run(false).expect("the elliptical runs");
    assert_eq!(r.samples, 360);
    assert!(r.path_error < 1e-8 && r.transmission_error < 1e-8, "{r:?}");
    assert!((r.stride - r.stride_closed_form).abs() < 1e-3 && (r.lift - r.lift_closed_form).abs() < 1e-3, "{r:?}");
    assert!((r.transmission - r.transmission_closed_form).abs() < 1e-3, "{r:?}");
    assert!(r.power_error < 1e-9 * r.peak_power, "{r:?}");
    assert!((r.mean_power - r.brake_power).abs() < 1e-6 * r.brake_power, "{r:?}");
    assert!(r.torque_min > 0.0 && r.push_force > 0.0, "{r:?}");
    quotes("elliptical", "stride 0.4682 m", r.stride);
    quotes("elliptical", "lift 0.1254 m", r.lift);
    quotes("elliptical", "at least 47.5°", r.transmission.to_degrees());
    quotes("elliptical", "mean power 150.000 W", r.mean_power);
    bounds("elliptical", "(≤ 1e-8 m)", r.path_error);
    let page = "guide/projects/elliptical.md";
    page_quotes(page, "stride of 0.4682 m", r.stride, false);
    page_quotes(page, "0.4682 m by the closed form", r.stride_closed_form, false);
    page_quotes(page, "lift of 0.1254 m", r.lift, false);
    page_quotes(page, "0.1254 m by the closed form", r.lift_closed_form, false);
    page_quotes(page, "through 24.8°", r.tilt.to_degrees(), false);
    page_quotes(page, "at least 47.5°", r.transmission.to_degrees(), false);
    page_quotes(page, "47.45° by the closed form", r.transmission_closed_form.to_degrees(), false);
    page_quotes(page, "from 18.71 N·m", r.torque_min, false);
    page_quotes(page, "to 29.95 N·m", r.torque_max, false);
    page_quotes(page, "up to 188.2 W", r.peak_power, false);
    page_quotes(page, "150.000 W both", r.mean_power, false);
    page_quotes(page, "150.000 W both", r.brake_power, false);
    page_quotes(page, "up to 420 N", r.push_force, false);
    page_quotes(page, "at least 0.38 m/s", r.push_speed_min, false);
    page_quotes(page, "within 1e-8 m", r.path_error, true);
    page_quotes(page, "within 1e-8 rad", r.transmission_error, true);
    page_quotes(page, "within 1e-9 of the peak power", r.power_error / r.peak_power, true);
}

/// Nikravesh's project 15.4 (guide/projects/head-and-neck.md): the seated posture is the hand
/// statics' (1e-10 rad: the static solver's tolerance; measured 1.8e-14); a pulse 1e-4 as strong
/// without gravity moves every body as the small-angle model by hand (1e-3 of the head's
/// rotation: the neglected terms are of the order of the amplitude, 2.2e-4 rad, relative, and both
/// integrations are far tighter; measured 1.6e-5); the upper neck's force and moment are
/// Newton–Euler of the head by hand at every sample (1e-8 N and N·m, rounding of loads of up to
/// 1 400 N; measured 1.3e-12). A closer restraint touches the head sooner and holds its rotation
/// lower.
#[test]
fn head_neck_meets_its_hand_models() {
    let r = head_neck::run(false).expect("the head and neck run");
    assert!(r.posture_error < 1e-10 && r.small_error < 1e-3, "{r:?}");
    let [none, far, mid, near] = [r.cases[0], r.cases[1], r.cases[2], r.cases[3]];
    for c in &r.cases {
        assert!(c.force_error < 1e-8 && c.moment_error < 1e-8, "{c:?}");
    }
    assert!(none.contact_at.is_none() && none.contact_force == 0.0, "{none:?}");
    assert!(none.rotation > far.rotation && far.rotation > mid.rotation && mid.rotation > near.rotation, "{r:?}");
    let touch = |c: head_neck::Case| c.contact_at.expect("the head touches its restraint");
    assert!(touch(near) < touch(mid) && touch(mid) < touch(far), "{r:?}");
    quotes("head_neck", "flexed 7.14°", -r.posture);
    quotes("head_neck", "31.9° at 40 mm", near.rotation);
    quotes("head_neck", "110.2° without one", none.rotation);
    bounds("head_neck", "(≤ 1e-3 of its rotation)", r.small_error);
    let page = "guide/projects/head-and-neck.md";
    page_quotes(page, "flexed 7.14°", -r.posture, false);
    page_quotes(page, "within 1e-10 rad", r.posture_error, true);
    page_quotes(page, "within 1e-3 of", r.small_error, true);
    page_quotes(page, "turns 2.22e-4 rad", r.small_rotation, false);
    page_quotes(page, "within 1e-8 N", none.force_error.max(far.force_error).max(mid.force_error).max(near.force_error), true);
    for (c, cells) in [
        (none, ["| 110.2° |", "| 124.5 ms |", "| 24.9 |", "| 955 N |", "| 837 N |", "| 95.1 N·m |"]),
        (far, ["| 81.0° |", "| 102.5 ms |", "| 39.5 |", "| 756 N |", "| 1 362 N |", "| 75.7 N·m |"]),
        (mid, ["| 53.5° |", "| 95.5 ms |", "| 23.3 |", "| 250 N |", "| 460 N |", "| 27.7 N·m |"]),
        (near, ["| 31.9° |", "| 90.5 ms |", "| 12.7 |", "| 152 N |", "| 283 N |", "| 13.2 N·m |"]),
    ] {
        let values = [c.rotation, 1e3 * c.rotation_at, c.nic, c.shear, c.axial, c.moment];
        for (cell, value) in cells.iter().zip(values) {
            page_quotes(page, cell, value, false);
        }
    }
    for (c, contact, force) in
        [(far, "| 74.6 ms |", "| 1 188 N |"), (mid, "| 63.4 ms |", "| 1 520 N |"), (near, "| 48.5 ms |", "| 1 336 N |")]
    {
        page_quotes(page, contact, 1e3 * touch(c), false);
        page_quotes(page, force, c.contact_force, false);
    }
}

/// Nikravesh's project 15.3 (guide/projects/sled-test.md): the seated dummy's weight is the
/// seat's contact forces by hand, force and moment (1e-8 N and N·m: the static solver balances to
/// 1e-9; measured 1e-12); in the crash Σ m a is the external forces by hand and Σ (r × m a + J α)
/// their moment at every sample (1e-9 of the peak force, and of it times 2.5 m, the reach of the
/// moment arms as the sled moves 2 m: rounding; measured 5e-15 and 6e-13 relative). The cushion
/// never unloads below its seated force during the pulse (to 0.1 %); the lap belt carries the
/// most.
#[test]
fn sled_test_balances_by_hand() {
    let r = sled_test::run(false).expect("the sled test runs");
    assert!(r.seated_force_error < 1e-8 && r.seated_moment_error < 1e-8, "{r:?}");
    assert!(r.force_error < 1e-9 * r.force_peak && r.moment_error < 1e-9 * r.force_peak * 2.5, "{r:?}");
    assert!(r.cushion_least > 0.999 * r.seated_cushion, "the cushion unloads: {r:?}");
    assert!(r.lap.0 > r.shoulder_upper.0 && r.shoulder_upper.0 > r.shoulder_lower.0, "{r:?}");
    assert!(r.chest_clip <= r.chest_peak.0 && r.hic15 > 0.0, "{r:?}");
    quotes("sled_test", "chest 28.0 g", r.chest_peak.0);
    quotes("sled_test", "HIC₁₅ 117", r.hic15);
    quotes("sled_test", "lap belt 13.3 kN", r.lap.0 / 1e3);
    let page = "guide/projects/sled-test.md";
    page_quotes(page, "cushion carries 709.7 N", r.seated_cushion, false);
    page_quotes(page, "seat back 162.8 N", r.seated_back, false);
    page_quotes(page, "within 1e-8 N", r.seated_force_error, true);
    page_quotes(page, "| 36.8 g | 72.4 ms |", r.head_peak.0, false);
    page_quotes(page, "| 72.4 ms |", 1e3 * r.head_peak.1, false);
    page_quotes(page, "| 117 |", r.hic15, false);
    page_quotes(page, "| 258 mm |", 1e3 * r.head_excursion, false);
    page_quotes(page, "| 28.0 g | 75.0 ms |", r.chest_peak.0, false);
    page_quotes(page, "| 75.0 ms |", 1e3 * r.chest_peak.1, false);
    page_quotes(page, "is 28.0 g, the peak", r.chest_clip, false);
    for (cell, time, (force, at)) in [
        ("| 13 333 N |", "| 81.2 ms |", r.lap),
        ("| 7 654 N |", "| 71.7 ms |", r.shoulder_upper),
        ("| 3 726 N |", "| 72.5 ms |", r.shoulder_lower),
        ("| 6 230 N |", "| 64.5 ms |", r.cushion_peak),
    ] {
        page_quotes(page, cell, force, false);
        page_quotes(page, time, 1e3 * at, false);
    }
    page_quotes(page, "within 1e-9 of the peak force", r.force_error / r.force_peak, true);
    page_quotes(page, "peak force (22 kN)", r.force_peak / 1e3, false);
}

/// Nikravesh's project 15.5 (guide/projects/mountain-bike.md): each rest state's shock force and
/// rear tyre load are the free bodies by hand (1e-5 N: the static solver stops at a residual of
/// 1e-9, and the springs' laws turn what its last step leaves of the positions into force at
/// 75–120 kN/m — 1e-5 N is 1e-10 m; measured 1.5e-7); pedalling, the bike's speed is its closed
/// form (1e-8 m/s: DOPRI5 at rtol 1e-8 of speeds of 2.4 m/s; measured 7e-14); the bob's mean is
/// the rest state pedalling at the mean torque (0.05 mm: what the geometry's nonlinearity leaves
/// of a linear response's mean; measured 0.01); the energy over the bump is its balance by hand
/// (1e-4 of the kinetic energy: the trapezoid over 1 ms samples; measured 3.9e-5). The squat
/// falls as the anti-squat rises and changes sign past 100 %, nearly nothing at 99 %; the bob is
/// least there; the rider's sag is the 30 % the shock was set for, to what the geometry turns
/// meanwhile (1 %); the shock extends fully while the rear wheel is off the ground.
#[test]
fn mountain_bike_balances_by_hand() {
    let r = mountain_bike::run(false).expect("the mountain bike runs");
    let [low, mid, high] = [r.pivots[0], r.pivots[1], r.pivots[2]];
    for p in &r.pivots {
        assert!(p.rest_error < 1e-5 && p.speed_error < 1e-8, "{p:?}");
        assert!((p.bob_mean - p.sag_pedalling).abs() < 0.05, "{p:?}");
        assert!((p.sag - 16.5).abs() < 0.01 * 16.5, "{p:?}");
    }
    assert!(r.energy_error < 1e-4, "{r:?}");
    assert!(low.anti_squat < 100.0 && low.squat > 0.5, "{low:?}");
    assert!((mid.anti_squat - 100.0).abs() < 5.0 && mid.squat > 0.0 && mid.squat < 0.2 * low.squat, "{mid:?}");
    assert!(high.anti_squat > 100.0 && high.squat < -0.5, "{high:?}");
    assert!(mid.bob < low.bob && mid.bob < high.bob, "{r:?}");
    assert!(r.bump_stroke < 55.0 && r.least_stroke.abs() < 0.05, "the shock within its stroke, and fully out in the air: {r:?}");
    quotes("mountain_bike", "1.48 mm peak to peak", mid.bob);
    quotes("mountain_bike", "2.60 mm at 58 %", low.bob);
    quotes("mountain_bike", "3.99 mm at 154 %", high.bob);
    quotes("mountain_bike", "37.7 mm of its 55", r.bump_stroke);
    bounds("mountain_bike", "(≤ 1e-4 of the kinetic energy)", r.energy_error);
    let page = "guide/projects/mountain-bike.md";
    page_quotes(page, "within 1e-5 N", r.pivots.iter().map(|p| p.rest_error).fold(0.0, f64::max), true);
    page_quotes(page, "within 1e-8 m/s", r.pivots.iter().map(|p| p.speed_error).fold(0.0, f64::max), true);
    page_quotes(page, "within 0.05 mm", r.pivots.iter().map(|p| (p.bob_mean - p.sag_pedalling).abs()).fold(0.0, f64::max), true);
    page_quotes(page, "within 1e-4 of the kinetic energy", r.energy_error, true);
    page_quotes(page, "mean crank torque 24.8 N·m", r.torque, false);
    page_quotes(page, "207 W", r.power, false);
    page_quotes(page, "2.37 m/s", r.speed, false);
    page_quotes(page, "swings 0.117 m/s", low.speed_swing, false);
    page_quotes(page, "75.0 N/mm", 1e-3 * mid.k_shock, false);
    page_quotes(page, "leverage at sag 2.38", low.leverage, false);
    for (p, cells) in [
        (low, ["| 58 % |", "| 16.52 mm |", "| 17.49 mm |", "| 1.05 mm |", "| 2.60 mm |"]),
        (mid, ["| 99 % |", "| 16.55 mm |", "| 16.59 mm |", "| 0.12 mm |", "| 1.48 mm |"]),
        (high, ["| 154 % |", "| 16.60 mm |", "| 15.38 mm |", "| −1.14 mm |", "| 3.99 mm |"]),
    ] {
        // (the number's sign is in the text: `number` reads its digits)
        let values = [p.anti_squat, p.sag, p.sag_pedalling, p.squat.abs(), p.bob];
        for (cell, value) in cells.iter().zip(values) {
            page_quotes(page, cell, value, false);
        }
    }
    page_quotes(page, "a stroke of 37.7 mm", r.bump_stroke, false);
    page_quotes(page, "5 122 N", r.bump_force, false);
    page_quotes(page, "fork 113.3 mm", r.fork_stroke, false);
    page_quotes(page, "rear wheel 245 ms", 1e3 * r.rear_airborne, false);
    page_quotes(page, "front 297 ms", 1e3 * r.front_airborne, false);
}

/// Both suspensions come to rest on their tyres, ride the 30 mm bump with a travel of the
/// bump's order, settle (c = 1500 N·s/m damps the wheel hop within 0.7 s), and keep the energy
/// balance to 1e-8 of the ~300 J stored in the springs (DOPRI5 at rtol 1e-9).
#[test]
fn suspensions_settle_on_their_tyres_and_ride_a_bump() {
    let [a, b] = suspension_dynamics::run(false).expect("both suspensions run");
    for r in [a, b] {
        assert!(r.static_height > 0.27 && r.static_height < 0.30, "{r:?}");
        assert!(r.static_tyre_load > 2000.0 && r.static_tyre_load < 4000.0, "{r:?}");
        assert!(r.peak_travel > 0.02 && r.peak_travel < 0.05, "{r:?}");
        assert!(r.peak_tyre_load > r.static_tyre_load, "{r:?}");
        assert!(r.residual_motion < 1e-4, "{r:?}");
        assert!(r.bump_energy > 1.0, "{r:?}");
        assert!(r.energy_drift < 1e-5, "{r:?}");
        bounds("suspension_dynamics", "drift ≤ 3e-6 J", r.energy_drift);
    }
}

/// The work-precision runs of the free four-bar: errors fall with the step (RK4 by ~16 per
/// halving, generalized-α by ~4) and with DOPRI5's tolerance, and the energy drift with them.
#[test]
fn free_four_bar_errors_fall_at_each_method_s_order() {
    let runs = free_four_bar::run(false).expect("all runs succeed");
    let of = |method: &str| runs.iter().filter(|r| r.method == method).collect::<Vec<_>>();
    // Only where the finer run's error stays above the floor of 1e-10 rad that the projection
    // tolerance and the reference set: from 1e-8, a 16× fall still lands at 6e-10.
    for pair in of("RK4 (h)").windows(2).filter(|pair| pair[0].error > 1e-8) {
        let ratio = pair[0].error / pair[1].error;
        assert!(ratio > 10.0, "RK4 error ratio {ratio}: {pair:?}");
    }
    assert!(of("RK4 (h)").iter().filter(|r| r.error > 1e-8).count() >= 2, "two RK4 steps above the floor: {runs:?}");
    for pair in of("generalized-α (h)").windows(2) {
        let ratio = pair[0].error / pair[1].error;
        assert!(ratio > 2.5, "generalized-α error ratio {ratio}: {pair:?}");
    }
    for pair in of("DOPRI5 (rtol)").windows(2) {
        assert!(pair[1].error < pair[0].error && pair[1].energy_drift < pair[0].energy_drift, "{pair:?}");
    }
    assert!(of("DOPRI5 (rtol)").last().unwrap().error < 1e-9);
    // The work-precision table of guide/performance.md: each row's steps, error and energy drift
    // (its times are the release build's, measured, not asserted).
    let rows = [
        ("| RK4 | h = 4 ms |", "RK4 (h)", 4e-3),
        ("| RK4 | h = 1 ms |", "RK4 (h)", 1e-3),
        ("| RK4 | h = 0.5 ms |", "RK4 (h)", 5e-4),
        ("| DOPRI5 | rtol 1e-6 |", "DOPRI5 (rtol)", 1e-6),
        ("| DOPRI5 | rtol 1e-8 |", "DOPRI5 (rtol)", 1e-8),
        ("| DOPRI5 | rtol 1e-10 |", "DOPRI5 (rtol)", 1e-10),
        ("| generalized-α (ρ∞ = 0.9) | h = 1 ms |", "generalized-α (h)", 1e-3),
    ];
    for (start, method, setting) in rows {
        let line = page("guide/performance.md").lines().find(|l| l.starts_with(start)).unwrap_or_else(|| panic!("no row {start}"));
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        let run = runs.iter().find(|r| r.method == method && r.setting == setting).unwrap_or_else(|| panic!("no run {method} {setting}"));
        let (steps, error, drift) = (cells[3], cells[5], cells[6]);
        assert!(
            steps == run.steps.to_string() && written_as(error, run.error) && written_as(drift, run.energy_drift),
            "guide/performance.md's row {line} quotes, for {run:?}, steps {steps}, error {error} and drift {drift}"
        );
    }
}

/// The heavy top against the Lagrange top's closed forms. Steady precession: DOPRI5 at rtol
/// 1e-10 over ~700 steps keeps the global error near 1e-9 relative (measured 6e-12), so both
/// roots of A cos θ Ω² − C ω3 Ω + m g l = 0 to 1e-8. Nutation, measured from 400 samples per
/// period: the period from mid-level crossings by linear interpolation (at θ's steepest point,
/// an error of the crossing time of ~ε ω h²/8 ≈ 2e-8 s at worst, divided by 20 periods), the
/// amplitude from the parabola through the largest sample (O(h³) of 0.02 rad), the mean
/// precession over whole periods: 1e-6 relative for all three. The fast-top approximations
/// are their leading terms in ε = 0.045: off by percents, which the exact forms are not.
#[test]
fn gyroscope_precesses_and_nutates_as_the_lagrange_top() {
    let r = gyroscope::run(false).expect("the top runs");
    let rel = |x: f64, y: f64| ((x - y) / y).abs();
    assert!(rel(r.slow_rate, r.slow_exact) < 1e-8, "{r:?}");
    assert!(rel(r.fast_rate, r.fast_exact) < 1e-8, "{r:?}");
    assert!(r.fast_exact > 40.0 * r.slow_exact, "two distinct roots: {r:?}");
    assert!(r.tilt_drift < 1e-8, "{r:?}");
    assert!(r.periods >= 19, "{r:?}");
    assert!(rel(r.nutation_period, r.nutation_period_exact) < 1e-6, "{r:?}");
    assert!(rel(r.nutation_amplitude, r.nutation_amplitude_exact) < 1e-6, "{r:?}");
    assert!(rel(r.mean_precession, r.mean_precession_exact) < 1e-6, "{r:?}");
    for (approx, exact) in [
        (r.nutation_period_fast_top, r.nutation_period_exact),
        (r.nutation_amplitude_fast_top, r.nutation_amplitude_exact),
        (r.mean_precession_fast_top, r.mean_precession_exact),
    ] {
        assert!(rel(approx, exact) > 0.01 && rel(approx, exact) < 0.1, "the fast-top value is an O(ε) approximation: {r:?}");
    }
    bounds("gyroscope", "(≤ 1e-11 relative)", rel(r.slow_rate, r.slow_exact).max(rel(r.fast_rate, r.fast_exact)));
    let nutation = [
        rel(r.nutation_period, r.nutation_period_exact),
        rel(r.nutation_amplitude, r.nutation_amplitude_exact),
        rel(r.mean_precession, r.mean_precession_exact),
    ];
    bounds("gyroscope", "(≤ 1e-10 relative)", nutation.into_iter().fold(0.0, f64::max));
    quotes("gyroscope", "off by 4 %", 100.0 * rel(r.nutation_period_fast_top, r.nutation_period_exact));
    quotes("gyroscope", "6 % and", 100.0 * rel(r.nutation_amplitude_fast_top, r.nutation_amplitude_exact));
    quotes("gyroscope", "2 %)", 100.0 * rel(r.mean_precession_fast_top, r.mean_precession_exact));
}

/// The RSSR four-bar against its closed form. Positions: the coupler's row is ½(|d|² − L²) ≤
/// 1e-10 m², i.e. |d| − L ≤ 1e-10/L ≈ 7e-10 m, which moves the rocker by up to that over b times
/// the transmission index (≥ 0.83): ≈ 8e-9 rad, so 1e-8 rad; rates and accelerations from exact
/// solves at that configuration (ψ̇ up to 7.5 rad/s, ψ̈ up to 124 rad/s²): 1e-7 and 1e-5. The
/// drive torque (peak 0.185 N·m) against virtual power: errors of ψ̈ of 1e-7 rad/s² times
/// J_O ψ̇/ω ≈ 1e-3 kg·m²: 1e-8 N·m. The mean drive power over a turn is the integral of a smooth
/// periodic function sampled evenly (exact to rounding), Δ(T + V) = 0: 1e-8 W.
#[test]
fn rssr_output_and_drive_torque_match_closed_forms() {
    let r = rssr::run(false).expect("the RSSR runs");
    assert_eq!(r.samples, 360);
    assert!(r.angle_error < 1e-8, "{r:?}");
    assert!(r.rate_error < 1e-7, "{r:?}");
    assert!(r.acceleration_error < 1e-5, "{r:?}");
    assert!(r.peak_acceleration > 100.0, "{r:?}");
    // A crank-rocker: the rocker swings about 61°, never a full turn.
    assert!(r.swing > 1.0 && r.swing < 1.2, "{r:?}");
    assert!((r.min_transmission - r.min_transmission_exact).abs() < 1e-8 && r.min_transmission > 0.8, "{r:?}");
    assert!(r.peak_torque > 0.1 && r.torque_error < 1e-8, "{r:?}");
    assert!(r.mean_drive_power.abs() < 1e-8, "{r:?}");
    assert!(r.peak_coupler_force > 1.0, "{r:?}");
    bounds("rssr", "(≤ 1e-8 rad)", r.angle_error);
    bounds("rssr", "(≤ 1e-10 of 0.185 N·m)", r.torque_error);
    quotes("rssr", "of 0.185 N·m", r.peak_torque);
}

/// The offset spatial slider-crank against its closed forms (tolerances as for the planar
/// slider-crank: positions 1e-8 m, speeds 1e-7 m/s, accelerations up to 250 m/s² to 1e-5). The
/// dead centres are closed-form crank angles: there x is the closed-form extreme to 1e-8 m and
/// ẋ vanishes to 1e-8 m/s. Torque (peak 28 N·m) and rod force (peak 935 N) against virtual
/// work and the slider's equation: ẍ errors of 1e-7 m/s² times m s′ ≈ 0.04 kg·m and m/ê_x ≈ 1 kg
/// give 1e-7 N·m and 1e-5 N. The mean powers of drive and load cancel over a turn (the slider's
/// kinetic energy returns) to the rounding of 360 sums: 1e-6 W of 65 W.
#[test]
fn spatial_slider_crank_matches_its_closed_forms() {
    let r = spatial_slider_crank::run(false).expect("the spatial slider-crank runs");
    assert_eq!(r.samples, 360);
    assert!(r.position_error < 1e-8, "{r:?}");
    assert!(r.velocity_error < 1e-7, "{r:?}");
    assert!(r.acceleration_error < 1e-5, "{r:?}");
    assert!((r.stroke - r.stroke_exact).abs() < 1e-8 && r.stroke > 0.1, "{r:?}");
    assert!(r.dead_centre_speed < 1e-8, "{r:?}");
    // The offset makes the strokes unequal: a quick return, a few per cent.
    assert!(r.time_ratio > 1.01 && r.time_ratio < 1.1, "{r:?}");
    assert!(r.peak_torque > 10.0 && r.torque_error < 1e-7, "{r:?}");
    assert!(r.peak_rod_force > 500.0 && r.rod_force_error < 1e-5, "{r:?}");
    assert!(r.load_power > 10.0 && (r.drive_power + r.load_power).abs() < 1e-6, "{r:?}");
    bounds("spatial_slider_crank", "(≤ 1e-11 m)", (r.stroke - r.stroke_exact).abs());
    bounds("spatial_slider_crank", "(≤ 1e-8 of 28 N·m)", r.torque_error);
    quotes("spatial_slider_crank", "of 28 N·m", r.peak_torque);
    bounds("spatial_slider_crank", "(≤ 1e-7 of 935 N)", r.rod_force_error);
    quotes("spatial_slider_crank", "of 935 N", r.peak_rod_force);
}

/// The 3D double wishbone. Layout A moves in the front-view plane (the example's argument), so
/// its toe stays zero and its camber and wheel-centre track are those of the planar four-bar in
/// closed form: to the position solve's 1e-10 m over lever arms of ≥ 0.1 m, 1e-9 rad and 1e-9 m.
/// Its camber changes by degrees (short upper arm over a long lower one: negative camber gain
/// in bump). Layout B's inclined pivots steer the wheel by tenths of a degree: A's zero is the
/// geometry's, not the solver's.
#[test]
fn double_wishbone_3d_bump_steer_and_camber() {
    let r = double_wishbone_3d::run(false).expect("both layouts sweep");
    assert_eq!(r.parallel.travel.len(), 33);
    assert!(r.parallel_bump_steer < 1e-9, "{r:?}");
    assert!(r.camber_error < 1e-9 && r.track_error < 1e-9, "{r:?}");
    let (first, last) = (r.parallel.camber[0], r.parallel.camber[32]);
    assert!(first > 0.01 && last < -0.02, "rebound camber {first} rad, bump camber {last} rad");
    let toe_b = r.inclined.toe.iter().fold(0.0f64, |a, t| a.max(t.abs()));
    assert!(toe_b > 1e-3 && toe_b < 0.02, "layout B's bump steer {toe_b} rad");
    bounds("double_wishbone_3d", "bump steer ≤ 1e-12 rad", r.parallel_bump_steer);
    bounds("double_wishbone_3d", "in closed form (≤ 1e-13 rad)", r.camber_error);
}

/// The Stewart platform: the pose Newton finds from the six strokes is the commanded one, and the
/// leg lengths of that pose are the inverse kinematics', to the position tolerance (1e-10 m;
/// Newton lands far below it): 1e-9. Statics at every pose: the stroke drivers' reactions and
/// the example's 6×6 solve are two solutions of the same well-conditioned equilibrium, equal to
/// rounding (cond · ε · |f| ≈ 1e3 · 2e-16 · 170 N ≈ 3e-11 N): 1e-8 N. The vertical components
/// carry the whole load.
#[test]
fn stewart_platform_pose_lengths_and_statics() {
    let r = stewart_platform::run(false).expect("the Stewart platform runs");
    assert_eq!(r.samples, 49);
    assert!(r.position_error < 1e-9 && r.rotation_error < 1e-9, "{r:?}");
    assert!(r.length_error < 1e-9, "{r:?}");
    // ±50 mm of heave and ±5° of roll change the legs by about ±60 mm.
    assert!(r.length_max - r.length_min > 0.1, "{r:?}");
    assert!(r.static_peak > 50.0 && r.static_error < 1e-8, "{r:?}");
    assert!((r.static_vertical - r.static_load).abs() < 1e-9 * r.static_load, "{r:?}");
    // The actuators hold the platform and the legs up (pushing), more in the lower poses.
    assert!(r.force_min > 50.0 && r.force_max < 200.0, "{r:?}");
    bounds("stewart_platform", "(≤ 1e-11 rad", r.rotation_error);
    bounds("stewart_platform", "≤ 1e-12 m)", r.position_error);
    bounds("stewart_platform", "(≤ 1e-9 of 169 N)", r.static_error);
    quotes("stewart_platform", "of 169 N", r.static_peak);
}

/// The excavator is one declaration with three scenes: held by its cylinders as stiff springs
/// (statics), driven by their lengths (inverse dynamics) and pushed by their forces (forward
/// dynamics). Held still at the held pose's
/// cylinder lengths, the driven arm needs the forces the springs exert there: two independent
/// computations (a trust-region energy minimum; the drivers' multipliers) agree to 1e-8
/// relative (measured 6e-11; the statics stops at a force residual of 1e-9 N on forces of
/// 1e4–1e5 N). The boom cylinder pushes (negative tension) with about the arm's weight moment
/// over its lever, and the pose moved from the design by the oil columns' compression only
/// (k = 2e7 N/m: the 28 kN beyond its constant 60 kN push shortens the boom cylinder 1.4 mm,
/// turning the boom 0.24°).
#[test]
fn excavator_scenes_agree_on_the_cylinder_forces() {
    let r = excavator::run(false).expect("the excavator's scenes run");
    assert!(r.disagreement < 1e-8, "{r:?}");
    assert!(r.held_tensions[0] < -5e4 && r.held_tensions[0] > -1.5e5, "boom cylinder pushes: {r:?}");
    let design = [40.0, -75.0, -130.0];
    for (angle, design) in r.held_angles.iter().zip(design) {
        assert!((angle - design).abs() < 1.5, "within 1.5° of the design angle {design}: {r:?}");
    }
    // Lifting changes the boom cylinder's force smoothly (a few percent over 2 s at 0.1 m/s).
    assert!(r.lifting.iter().all(|f| (f / r.lifting[0] - 1.0).abs() < 0.1), "{r:?}");
    // The third scene, the cylinders as actuators pushed by those forces, accelerates as the
    // driven arm: 1e-8 relative, the driven state's Φ residue acted on by Baumgarte.
    assert!(r.free_mismatch < 1e-8, "{r:?}");
    quotes("excavator", "87 918", r.held_tensions[0].abs());
    quotes("excavator", "13 128", r.held_tensions[1].abs());
    quotes("excavator", "7 155 N", r.held_tensions[2].abs());
    bounds("excavator", "≤ 1e-10 apart", r.disagreement);
    bounds("excavator", "(≤ 1e-10 relative)", r.free_mismatch);
    page_quotes("guide/dsl.md", "the driven arm to within 1e-10 relative", r.free_mismatch, true);
}

/// The quarter car sits on the road with the tyre compressed by (m + M) g / k (statics to its
/// 1e-10 residual: 1e-9 m). Over the bump, events come in the physical order: the road falls away
/// after the bump's crest (x = 20.25 m, t = 1.0125 s) faster than the wheel follows, so the tyre
/// lets go before the bump ends (t = 1.025 s); the wheel, thrown up, hits its bump stop, leaves
/// it, and lands again. Nothing switches on the flat road before. The road's profile changes law
/// where the bump starts and ends (its time events).
#[test]
fn the_quarter_car_leaves_the_road_and_hits_its_bump_stop() {
    let r = bump::run(false).expect("the quarter car runs");
    let (compression, expected) = r.static_compression;
    assert!((compression - expected).abs() < 1e-9, "{r:?}");
    let order: Vec<(&str, bool)> = r.events.iter().map(|e| (e.1, e.2)).collect();
    assert_eq!(order, [("road", false), ("bump_stop", true), ("bump_stop", false), ("road", true)], "{r:?}");
    assert!(r.events[0].0 > 1.0125 && r.events[0].0 < 1.025, "the tyre lets go at {} s", r.events[0].0);
    // The bump's start and end, located as time events to within the event search's resolution.
    assert!(r.road_changes.len() == 2 && (r.road_changes[0] - 1.0).abs() < 1e-12 && (r.road_changes[1] - 1.025).abs() < 1e-12, "{r:?}");
    assert!(r.airborne > 0.02 && r.airborne < 0.2, "{r:?}");
    bounds("bump", "off by ≤ 1e-9 m", (compression - expected).abs());
    quotes("bump", "lets go at 1.0194 s", r.events[0].0);
    quotes("bump", "bump stop 1.0224", r.events[1].0);
    quotes("bump", "1.0463 s", r.events[2].0);
    quotes("bump", "lands at 1.0820 s", r.events[3].0);
    quotes("bump", "62.6 ms in the air", r.airborne * 1e3);
}

/// The cart-pole's unstable pole and input column against their closed forms (1e-12: a 4 × 4
/// eigenproblem and one saddle-point solve), the exact and finite-difference models to 1e-8 of
/// the system's largest entry (measured 2e-11), and the quarter car's ride and wheel-hop
/// frequencies and damping ratios against the 2-DOF model written out by hand (1e-9: the static
/// equilibrium is found to 1e-9 N, and the tyre's stiffness is constant in contact).
#[test]
fn linear_models_match_their_closed_forms() {
    let r = linear_models::run(false).expect("linear models run");
    let close = |(a, b): (f64, f64), tol: f64| (a - b).abs() <= tol * b.abs();
    assert!(close(r.cart_pole_growth, 1e-12), "{r:?}");
    for k in 0..2 {
        assert!(close((r.cart_pole_input.0[k], r.cart_pole_input.1[k]), 1e-12), "{r:?}");
    }
    assert!(r.exact_vs_differences < 1e-8, "{r:?}");
    for pair in [r.ride, r.wheel_hop, r.ride_damping, r.wheel_hop_damping] {
        assert!(close(pair, 1e-9), "{r:?}");
    }
    assert_eq!(r.dominant, ("chassis.y", "wheel.y"));
    // A soft car: about 1.4 Hz ride, 12 Hz wheel hop.
    assert!(r.ride.0 > 1.0 && r.ride.0 < 2.0 && r.wheel_hop.0 > 10.0 && r.wheel_hop.0 < 15.0, "{r:?}");
    quotes("linear_models", "unstable pole 5.294201680005 1/s", r.cart_pole_growth.0);
    quotes("linear_models", "ride 1.3810 Hz", r.ride.0);
    quotes("linear_models", "ζ 0.2944", r.ride_damping.0);
    quotes("linear_models", "wheel hop 12.4019 Hz", r.wheel_hop.0);
    quotes("linear_models", "ζ 0.3174", r.wheel_hop_damping.0);
    bounds("linear_models", "finite differences to ≤ 1e-10", r.exact_vs_differences);
    let relative = |(a, b): (f64, f64)| (a - b).abs() / b.abs();
    let cart_pole = (0..2).map(|k| relative((r.cart_pole_input.0[k], r.cart_pole_input.1[k]))).fold(relative(r.cart_pole_growth), f64::max);
    page_quotes("guide/linearization.md", "unstable pole and input column (1e-12)", cart_pole, true);
    let quarter_car = [r.ride, r.wheel_hop, r.ride_damping, r.wheel_hop_damping].map(relative).into_iter().fold(0.0, f64::max);
    page_quotes("guide/linearization.md", "hand-written 2-DOF model (1e-9)", quarter_car, true);
    page_quotes("guide/linearization.md", "ride mode at 1.381 Hz", r.ride.0, false);
    page_quotes("guide/linearization.md", "wheel hop at 12.40 Hz", r.wheel_hop.0, false);
}

/// Every example's animation (what the showcase writes to `target/showcase/`) holds a motion and
/// draws as an animated SVG: one frame group per frame, up to the SVG's 240.
#[test]
fn every_example_animates() {
    for (name, animate) in ANIMATIONS {
        let animation = animate().unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(animation.len() >= 2, "{name}: {} frames", animation.len());
        let svg = animation.to_svg().unwrap_or_else(|e| panic!("{name}: {e}"));
        let groups = svg.matches("<g visibility=").count();
        assert!(if animation.len() <= 240 { groups == animation.len() } else { groups <= 240 }, "{name}: {groups} frames drawn");
    }
}
