//! The UR5 and the Panda (fingers locked at 0.02 m each), written in the DSL from the URDFs of
//! `example-robot-data` by `peers/robots/urdf_to_mbd.py` (`mechanisms/ur5.rs`, `panda.rs`, joint
//! coordinates), against Pinocchio 4.1.0 at 20 random states each (`peers/robots/fixtures.py` →
//! `ur5.json`, `panda.json`; q ∈ U(−π, π), v ∈ U(−2, 2), v̇ ∈ U(−5, 5)): the mass matrix (CRBA),
//! h (−NLE), forward dynamics at zero torque (ABA), inverse dynamics (RNEA) and what each joint
//! transmits (RNEA's f_i against `mbd::joint_reaction_at`). These are the numbers the
//! `vs_pinocchio` benchmark times; they must agree before anything is timed.
//!
//! Map (the converter's rule): Pinocchio's joint k is mbd's coordinate `<urdf joint>.angle`,
//! θ_mbd = θ0 + q_pin with θ0 = `initial_positions()` (the URDF's zero pose as the bodies' `at:`
//! poses), v and v̇ as they are (both markers of a joint are written along the URDF axis).
//!
//! Tolerance 1e-10, norm-wise relative (‖Δ‖∞/‖reference‖∞): both sides evaluate the same rigid
//! bodies in double precision, differing by rounding (measured ≤ 6e-15 on 2026-11-29); the
//! converter's zeroing of entries below 1e-15 moves M by less than 1e-14. A wrong frame, offset
//! or inertia product is O(1e-2) or more (a flipped product of inertia: 4e-2 in M).

use mbd::prelude::*;
use mbd::JointLoads;
use serde_json::Value;

mod ur5 {
    include!("../mechanisms/ur5.rs");
}
mod panda {
    include!("../mechanisms/panda.rs");
}

const TOLERANCE: f64 = 1e-10;

fn floats(v: &Value) -> Vec<f64> {
    v.as_array().expect("an array").iter().map(|x| x.as_f64().expect("a number")).collect()
}

/// ‖x − y‖∞ / ‖y‖∞.
fn relative(x: &[f64], y: &[f64]) -> f64 {
    let d = x.iter().zip(y).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    d / y.iter().map(|b| b.abs()).fold(0.0, f64::max)
}

/// Checks mechanism `m` against `peers/robots/<robot>.json`; returns the largest errors of M, h,
/// forward dynamics, inverse dynamics and the joint loads.
fn check<M, const N: usize>(m: &M, robot: &str) -> [f64; 5]
where
    M: Dynamics<f64, N, N, 0> + JointLoads<f64, N, N, 0>,
{
    let path = format!("{}/peers/robots/{robot}.json", env!("CARGO_MANIFEST_DIR"));
    let fixture: Value = serde_json::from_str(&std::fs::read_to_string(&path).expect("the fixture")).expect("JSON");
    // Pinocchio's joint k → mbd's coordinate and its joint in `JOINTS`.
    let joints: Vec<&str> = fixture["joints"].as_array().expect("joints").iter().map(|j| j.as_str().expect("a name")).collect();
    assert_eq!(joints.len(), N, "{robot}: one coordinate per joint");
    let index: Vec<usize> = joints
        .iter()
        .map(|j| M::COORDINATE_NAMES.iter().position(|c| *c == format!("{j}.angle")).unwrap_or_else(|| panic!("{robot}: no {j}.angle")))
        .collect();
    let joint: Vec<usize> = joints.iter().map(|j| M::JOINTS.iter().position(|info| info.name == *j).expect("the joint")).collect();
    let theta0 = m.initial_positions();
    let to_mbd = |x: &[f64], offset: bool| -> [f64; N] {
        let mut out = if offset { theta0 } else { [0.0; N] };
        for (k, &i) in index.iter().enumerate() {
            out[i] += x[k];
        }
        out
    };
    let to_pinocchio = |x: &[f64; N]| -> Vec<f64> { index.iter().map(|&i| x[i]).collect() };
    let mut worst = [0.0f64; 5];
    let states = fixture["states"].as_array().expect("states");
    assert_eq!(states.len(), 20);
    for state in states {
        let (q, v, vd) = (to_mbd(&floats(&state["q"]), true), to_mbd(&floats(&state["v"]), false), to_mbd(&floats(&state["a"]), false));
        let mut mass = [[0.0; N]; N];
        m.add_mass_matrix(&q, 1.0, &mut mass);
        let mass: Vec<f64> = index.iter().flat_map(|&i| index.iter().map(move |&j| (i, j))).map(|(i, j)| mass[i][j]).collect();
        let reference: Vec<f64> = state["M"].as_array().expect("M").iter().flat_map(floats).collect();
        worst[0] = worst[0].max(relative(&mass, &reference));
        let mut h = [0.0; N];
        m.forces(&q, &v, 0.0, &mut h);
        let nle: Vec<f64> = floats(&state["nle"]).iter().map(|x| -x).collect();
        worst[1] = worst[1].max(relative(&to_pinocchio(&h), &nle));
        let mut accelerations = [0.0; N];
        assert_eq!(m.free_accelerations(&q, &v, 0.0, &mut accelerations), Some(Ok(())), "{robot}: the articulated-body solve");
        worst[2] = worst[2].max(relative(&to_pinocchio(&accelerations), &floats(&state["aba"])));
        let mut torques = [0.0; N];
        m.inverse_forces(&q, &v, &vd, 0.0, &mut torques);
        worst[3] = worst[3].max(relative(&to_pinocchio(&torques), &floats(&state["rnea"])));
        // the provided M v̇ − h agrees with the recursion
        let mut inertia = [0.0; N];
        m.mass_times(&q, &vd, &mut inertia);
        let by_parts: [f64; N] = core::array::from_fn(|i| inertia[i] - h[i]);
        worst[3] = worst[3].max(relative(&to_pinocchio(&by_parts), &floats(&state["rnea"])));
        // each joint's load on its child, the moment moved to the joint's origin
        for (k, load) in state["joint_loads"].as_array().expect("joint loads").iter().enumerate() {
            let on_child = joint_reaction_at(m, &q, &v, &vd, 0.0, &[], joint[k]).and_then(|r| r.on_j).expect("a tree joint's load");
            let origin = floats(&load["origin"]);
            let moment = on_child.moment_at([origin[0], origin[1], origin[2]]);
            let ours: Vec<f64> = on_child.force.iter().chain(&moment).copied().collect();
            let theirs: Vec<f64> = floats(&load["force"]).into_iter().chain(floats(&load["moment"])).collect();
            worst[4] = worst[4].max(relative(&ours, &theirs));
        }
    }
    for (what, error) in ["M", "h", "forward dynamics", "inverse dynamics", "joint loads"].iter().zip(worst) {
        assert!(error < TOLERANCE, "{robot}: {what} differs from Pinocchio's by {error:.1e} (relative)");
    }
    worst
}

#[test]
fn the_ur5_and_the_panda_agree_with_pinocchio() {
    let ur5 = check::<_, 6>(&ur5::Ur5::default(), "ur5");
    let panda = check::<_, 7>(&panda::Panda::default(), "panda");
    println!("largest relative differences from Pinocchio (M, h, ABA, RNEA, joint loads): UR5 {ur5:?}, Panda {panda:?}");
}
