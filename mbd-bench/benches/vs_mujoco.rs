//! One RK4 step of the spatial pendulum chains of 4 and 16 links (`mechanisms/spatial_chain*.rs`,
//! spherical joints), in body and in joint coordinates (`*_joint.rs`), of 64 in joint
//! coordinates, and of planar hinge chains of 4, 16 and 64 links in joint coordinates (below), in
//! mbd against MuJoCo's RK4 on the same physical chain (ball or hinge joints), in the same run: `cargo bench -p mbd-bench --bench vs_mujoco -- --warm-up-time 1 --measurement-time 3`.
//!
//! First, MuJoCo's side: `peers/ensure_env.sh` creates the pinned Python environment
//! (`peers/requirements.txt`, under `target/peers-venv`) on first use, and `peers/mujoco_chain.py`
//! builds each chain for MuJoCo, times its C loop (`mujoco.rollout`) and integrates 0.5 s at
//! h = 1 ms and 0.25 ms. Then criterion times mbd's `Rk4::step` (h = 1 ms, Baumgarte α = β = 5,
//! from a moving state 50 ms into the fall); mbd integrates the same 0.5 s at both step sizes.
//! Last, a table: per-step times, their ratio, and the distance between the two tips at 0.5 s.
//!
//! The two integrate different coordinates in body coordinates (mbd: 7 per body with 3 constraint
//! rows per joint; MuJoCo: a quaternion per ball joint; mbd's joint coordinates are MuJoCo's), so their tips agree to the integration error, which must
//! shrink with the step (RK4: about 256 times from 1 ms to 0.25 ms) — the check that both
//! simulate the same motion. It fails the run if the tips differ by more than 1e-4 m at 1 ms.
use criterion::Criterion;
use mbd::{BodyFrames, Integrator, KinematicSolver, Mechanism, Point, Rk4, Rk4Options, System, Workspace};
use serde_json::Value;
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::SystemTime;

mod common;
use common::{peers_python, repo};

mod spatial_chain4 {
    include!("../mechanisms/spatial_chain4.rs");
}
mod spatial_chain16 {
    include!("../mechanisms/spatial_chain16.rs");
}
mod spatial_chain4_joint {
    include!("../mechanisms/spatial_chain4_joint.rs");
}
mod spatial_chain16_joint {
    include!("../mechanisms/spatial_chain16_joint.rs");
}
use spatial_chain16::SpatialChain16;
use spatial_chain16_joint::SpatialChain16Joint;
use spatial_chain4::SpatialChain4;
use spatial_chain4_joint::SpatialChain4Joint;

/// The ball chain of 64 links in joint coordinates, and the planar hinge chains of 4, 16 and 64:
/// the same links as `mechanisms/spatial_chain*.rs` (0.1 m, 0.1 kg, m L²/12 across), link k
/// along (cos 0.2k, sin 0.2k) from the end of link k − 1, its centre at
/// Σ_{j<k} L (cos 0.2j, sin 0.2j) + L/2 (cos 0.2k, sin 0.2k), the sums in closed form
/// (Σ_{j<k} cos jθ = sin(kθ/2) / sin(θ/2) · cos((k − 1)θ/2)). The plane's gravity is along −y,
/// so the arc falls in its plane, as MuJoCo's hinge chain (`mujoco_chain.py --hinge`).
macro_rules! ball_chain {
    ($name:ident, $n:literal) => {
        mbd::mechanism! {
            /// A free spatial chain of ball joints in joint coordinates (benchmark).
            pub $name {
                spatial;
                joint_coordinates;
                gravity [0.0, 0.0, -9.81];
                for k in 0..$n {
                    body l[k] {
                        mass: 0.1,
                        inertia: [1.0e-6, 8.333333333333336e-5, 8.333333333333336e-5],
                        at: [0.1 * sin(0.1 * k) / sin(0.1) * cos(0.1 * (k - 1)) + 0.05 * cos(0.2 * k),
                             0.1 * sin(0.1 * k) / sin(0.1) * sin(0.1 * (k - 1)) + 0.05 * sin(0.2 * k), 0.0],
                        axis_angle: [0.0, 0.0, 1.0, 0.2 * k]
                    }
                }
                spherical ground[0.0, 0.0, 0.0] ~ l[0][-0.05, 0.0, 0.0];
                for k in 1..$n {
                    spherical l[k - 1][0.05, 0.0, 0.0] ~ l[k][-0.05, 0.0, 0.0];
                }
            }
        }
    };
}
macro_rules! hinge_chain {
    ($name:ident, $n:literal) => {
        mbd::mechanism! {
            /// A free planar chain of hinges in joint coordinates (benchmark).
            pub $name {
                joint_coordinates;
                gravity [0.0, -9.81];
                for k in 0..$n {
                    body l[k] {
                        mass: 0.1,
                        inertia: 8.333333333333336e-5,
                        at: [0.1 * sin(0.1 * k) / sin(0.1) * cos(0.1 * (k - 1)) + 0.05 * cos(0.2 * k),
                             0.1 * sin(0.1 * k) / sin(0.1) * sin(0.1 * (k - 1)) + 0.05 * sin(0.2 * k), 0.2 * k]
                    }
                }
                revolute ground[0.0, 0.0] ~ l[0][-0.05, 0.0];
                for k in 1..$n {
                    revolute l[k - 1][0.05, 0.0] ~ l[k][-0.05, 0.0];
                }
            }
        }
    };
}
ball_chain!(SpatialChain64Joint, 64);
hinge_chain!(PlanarChain4Joint, 4);
hinge_chain!(PlanarChain16Joint, 16);
hinge_chain!(PlanarChain64Joint, 64);

/// Tip positions of mbd and MuJoCo at 0.5 s closer than this (m) at h = 1 ms count as the same
/// motion: 1e-4 m is 6e-5 of the 16-link chain's length, far above what either RK4 leaves
/// (measured: 5e-8 m for 4 links, 1.4e-6 m for 16) and far below what a different model would
/// move the tip.
const SAME_MOTION: f64 = 1e-4;

/// The simulated time of the tip comparison (s).
const TIP_TIME: f64 = 0.5;

/// MuJoCo's measurements: runs `peers/ensure_env.sh`, then `peers/mujoco_chain.py 4 16 64` and
/// `peers/mujoco_chain.py --hinge 4 16 64`; their chains together.
fn mujoco() -> Value {
    let peers = repo().join("mbd-bench/peers");
    let python = peers_python();
    let mut all = Vec::new();
    let mut version = Value::Null;
    for args in [&["4", "16", "64"][..], &["--hinge", "4", "16", "64"]] {
        let out = Command::new(&python).arg(peers.join("mujoco_chain.py")).args(args).output().expect("the peers' Python runs");
        eprint!("{}", String::from_utf8_lossy(&out.stderr));
        assert!(out.status.success(), "peers/mujoco_chain.py failed");
        let json: Value = serde_json::from_slice(&out.stdout).expect("mujoco_chain.py prints JSON");
        version = json["mujoco"].clone();
        all.extend(json["chains"].as_array().expect("chains").iter().cloned());
    }
    serde_json::json!({ "mujoco": version, "chains": all })
}

/// The tip of mbd's chain after `TIP_TIME` of RK4 at step h from the mechanism's initial
/// positions at rest, and the largest |Φ| on the way.
fn mbd_tip<M, const NQ: usize, const NV: usize, const NC: usize>(m: &M, h: f64, tip: impl Fn(&[f64; NQ]) -> [f64; 3]) -> ([f64; 3], f64)
where
    M: mbd::ForwardDynamics<f64, NQ, NV, NC>,
{
    let mut q = m.initial_positions();
    // Kinematics and RK4 use no saddle-point work space: N = 0.
    let mut ws = Workspace::<f64, NV, NC, 0>::boxed();
    KinematicSolver::default().assemble(m, &mut ws, &mut q, 0.0).expect("the chain assembles");
    let system = System::new(m);
    let mut rk4 = Rk4::new(Rk4Options::default().with_step(h));
    let mut p: Point<f64, NQ, NV, NC> = system.point(0.0, q, [0.0; NV], [0.0; 2]).expect("forward dynamics");
    let mut next = p;
    let (mut drift, mut phi) = (0.0f64, [0.0; NC]);
    for _ in 0..(TIP_TIME / h).round() as usize {
        rk4.step(&system, &mut ws, &p, f64::INFINITY, &mut next).expect("step");
        p = next;
        m.constraints(&p.q, p.t, &mut phi);
        drift = phi.iter().fold(drift, |a, x| a.max(x.abs()));
    }
    (tip(&p.q), drift)
}

/// A moving state: 50 RK4 steps of 1 ms from rest.
fn moving_state<M, const NQ: usize, const NV: usize, const NC: usize>(m: &M) -> Point<f64, NQ, NV, NC>
where
    M: mbd::ForwardDynamics<f64, NQ, NV, NC>,
{
    let mut q = m.initial_positions();
    // Kinematics and RK4 use no saddle-point work space: N = 0.
    let mut ws = Workspace::<f64, NV, NC, 0>::boxed();
    KinematicSolver::default().assemble(m, &mut ws, &mut q, 0.0).expect("the chain assembles");
    let system = System::new(m);
    let mut rk4 = Rk4::new(Rk4Options::default().with_step(1e-3));
    let mut p = system.point(0.0, q, [0.0; NV], [0.0; 2]).expect("forward dynamics");
    let mut next = p;
    for _ in 0..50 {
        rk4.step(&system, &mut ws, &p, f64::INFINITY, &mut next).expect("step");
        p = next;
    }
    p
}

/// criterion's median (s) of `group/function` from its estimates file, if this run wrote it.
fn median(dir: &Path, group: &str, function: &str, since: SystemTime) -> Option<f64> {
    let path = dir.join(group).join(function).join("new/estimates.json");
    let fresh = std::fs::metadata(&path).and_then(|m| m.modified()).is_ok_and(|t| t >= since);
    if !fresh {
        return None;
    }
    let estimates: Value = serde_json::from_slice(&std::fs::read(&path).ok()?).ok()?;
    Some(estimates["median"]["point_estimate"].as_f64()? * 1e-9)
}

fn distance(a: &[f64; 3], b: &Value) -> f64 {
    let b: Vec<f64> = b.as_array().expect("a position").iter().map(|x| x.as_f64().expect("a number")).collect();
    (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt()
}

fn micros(s: f64) -> String {
    format!("{:.2} µs", s * 1e6)
}

struct Row {
    joint: &'static str,
    links: usize,
    coordinates: &'static str,
    group: &'static str,
    mujoco_step: f64,
    tips: Vec<(f64, f64)>,
    drift: f64,
}

macro_rules! chain {
    ($c:expr, $peers:expr, $group:literal, $ty:ty, $joint:literal, $coordinates:literal) => {{
        const NV: usize = <$ty>::NV;
        const NC: usize = <$ty>::NC;
        let m = <$ty>::default();
        let links = <$ty>::BODY_NAMES.len();
        let peer = $peers["chains"]
            .as_array()
            .expect("chains")
            .iter()
            .find(|c| c["links"] == links && c["joint"] == $joint)
            .expect("MuJoCo measured this chain");
        assert!(peer["finite"].as_bool() == Some(true), "MuJoCo's timed rollout of the chain of {links} blew up");
        let mut tips = Vec::new();
        let mut worst_drift = 0.0f64;
        for run in peer["tips"].as_array().expect("tips") {
            let h = run["h"].as_f64().expect("h");
            // the free end of the last link
            let (tip, drift) = mbd_tip(&m, h, |q| m.body_pose(links - 1, q).expect("the last link").point([0.05, 0.0, 0.0]));
            worst_drift = worst_drift.max(drift);
            tips.push((h, distance(&tip, &run["tip"])));
        }
        assert!(tips[0].1 < SAME_MOTION, "chain of {links}: mbd's and MuJoCo's tips differ by {:e} m at 0.5 s", tips[0].1);
        let system = System::new(&m);
        let mut rk4 = Rk4::new(Rk4Options::default().with_step(1e-3));
        let p = moving_state(&m);
        let mut next = p;
        let _: (&[f64; NV], &[f64; NC]) = (&p.v, &p.lambda);
        let mut ws = Workspace::<f64, NV, NC, 0>::boxed();
        let mut g = $c.benchmark_group($group);
        g.bench_function("mbd_rk4_step", |b| b.iter(|| rk4.step(&system, &mut ws, black_box(&p), f64::INFINITY, &mut next)));
        g.finish();
        Row {
            joint: $joint,
            links,
            coordinates: $coordinates,
            group: $group,
            mujoco_step: peer["step_seconds"].as_f64().expect("step_seconds"),
            tips,
            drift: worst_drift,
        }
    }};
}

fn main() {
    let peers = mujoco();
    let target = std::env::var_os("CARGO_TARGET_DIR").map(PathBuf::from).unwrap_or_else(|| repo().join("target"));
    let output = target.join("criterion");
    let started = SystemTime::now();
    let mut c = Criterion::default().output_directory(&output).configure_from_args();
    let rows = [
        chain!(c, peers, "vs_mujoco_chain4", SpatialChain4, "ball", "body"),
        chain!(c, peers, "vs_mujoco_chain4_joint", SpatialChain4Joint, "ball", "joint"),
        chain!(c, peers, "vs_mujoco_chain16", SpatialChain16, "ball", "body"),
        chain!(c, peers, "vs_mujoco_chain16_joint", SpatialChain16Joint, "ball", "joint"),
        chain!(c, peers, "vs_mujoco_chain64_joint", SpatialChain64Joint, "ball", "joint"),
        chain!(c, peers, "vs_mujoco_hinge4_joint", PlanarChain4Joint, "hinge", "joint"),
        chain!(c, peers, "vs_mujoco_hinge16_joint", PlanarChain16Joint, "hinge", "joint"),
        chain!(c, peers, "vs_mujoco_hinge64_joint", PlanarChain64Joint, "hinge", "joint"),
    ];
    c.final_summary();

    println!();
    println!("Pendulum chains, one RK4 step at h = 1 ms (MuJoCo {}):", peers["mujoco"].as_str().unwrap_or("?"));
    println!(
        "| joints | links | mbd's coordinates | mbd | MuJoCo | mbd / MuJoCo | tip apart at 0.5 s, h = 1 ms | h = 0.25 ms | mbd's max |Φ| |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for r in &rows {
        let (mbd, ratio) = match median(&output, r.group, "mbd_rk4_step", started) {
            Some(s) => (micros(s), format!("{:.2}", s / r.mujoco_step)),
            None => ("not timed in this run".into(), "—".into()),
        };
        let apart: Vec<String> = r.tips.iter().map(|(_, d)| format!("{d:.1e} m")).collect();
        println!(
            "| {} | {} | {} | {mbd} | {} | {ratio} | {} | {} | {:.1e} m |",
            r.joint,
            r.links,
            r.coordinates,
            micros(r.mujoco_step),
            apart[0],
            apart[1],
            r.drift
        );
    }
}
