//! The formulation table: the same mechanisms in body coordinates and in joint coordinates
//! (`joint_coordinates;`), side by side — coordinates, constraint rows, the generated operations
//! of one `accelerations` call (body coordinates: the evaluation before the planned sparse
//! solve, whose own operations are not counted; joint coordinates: that evaluation, the tree's
//! M⁻¹h and M⁻¹Dᵀ — the articulated inertias factored once, then each row's passes — before
//! the dense NC×NC solve), the time of one
//! `accelerations` call at a moving state, of one RK4 step at h = 1 ms and of one DOPRI5 step at
//! its default tolerances (at most 1 ms).
//!
//! Run: `cargo run --release -p mbd-bench --example formulations` (a few seconds; the timings are
//! medians of 7 batches, single thread, and vary by ±20 % between runs on a busy machine).
//!
//! Mechanisms: a 6-revolute arm (link masses 0.8–3 kg, axes alternating z, y as a PUMA-like
//! arm's), the 16-link ball-joint chain of the MuJoCo benchmark, and the examples' planar
//! slider-crank (driven: a closed loop), free four-bar (a loop) and double A-arm suspension (a
//! loop with a coil-over and a tyre), and a hanging ladder of 40 four-bar loops, each compiled
//! both ways from the same text.
use mbd::prelude::*;
use mbd::System;
use std::time::Instant;

macro_rules! arm {
    ($name:ident $($joint:ident)?) => {
        mbd::mechanism! {
            /// A 6-revolute arm (formulation table).
            pub $name {
                spatial;
                $($joint;)?
                gravity [0.0, 0.0, -9.81];
                body l1 { mass: 3.0, inertia: [0.02, 0.02, 0.01], at: [0.0, 0.0, 0.2] }
                body l2 { mass: 2.5, inertia: [0.02, 0.015, 0.01], at: [0.0, 0.0, 0.4] }
                body l3 { mass: 2.0, inertia: [0.015, 0.015, 0.008], at: [0.0, 0.05, 0.6] }
                body l4 { mass: 1.2, inertia: [0.01, 0.012, 0.006], at: [0.05, 0.05, 0.8] }
                body l5 { mass: 1.0, inertia: [0.008, 0.008, 0.004], at: [0.1, 0.05, 0.95] }
                body l6 { mass: 0.8, inertia: [0.005, 0.006, 0.003], at: [0.15, 0.05, 1.05] }
                revolute j1: ground[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0] ~ l1[0.0, 0.0, -0.2] along [0.0, 0.0, 1.0];
                revolute j2: l1[0.0, 0.0, 0.1] along [0.0, 1.0, 0.0] ~ l2[0.0, 0.0, -0.1] along [0.0, 1.0, 0.0];
                revolute j3: l2[0.0, 0.0, 0.1] along [0.0, 0.0, 1.0] ~ l3[0.0, -0.05, -0.1] along [0.0, 0.0, 1.0];
                revolute j4: l3[0.0, 0.0, 0.1] along [0.0, 1.0, 0.0] ~ l4[-0.05, 0.0, -0.1] along [0.0, 1.0, 0.0];
                revolute j5: l4[0.05, 0.0, 0.05] along [0.0, 0.0, 1.0] ~ l5[0.0, 0.0, -0.1] along [0.0, 0.0, 1.0];
                revolute j6: l5[0.0, 0.0, 0.05] along [0.0, 1.0, 0.0] ~ l6[-0.05, 0.0, -0.05] along [0.0, 1.0, 0.0];
            }
        }
    };
}
arm!(ArmBody);
arm!(ArmJoint joint_coordinates);

macro_rules! ladder {
    ($name:ident $($joint:ident)?) => {
        mbd::mechanism! {
            /// A hanging ladder of 40 four-bar loops (as `tests/large.rs`' of 100): 41 rungs
            /// 0.4 m wide, a left rail of 40 links pinned between them, 0.3 m massless links on
            /// the right (one row each), started sheared 0.2 rad.
            pub $name {
                $($joint;)?
                gravity [0.0, -9.81];
                body r[0] { mass: 1.0, inertia: 0.013333333333333334, at: [0.2, 0.0, 0.0] }
                for k in 1..=40 {
                    body r[k] { mass: 1.0, inertia: 0.013333333333333334, at: [0.2 + 0.3 * k * sin(0.2), -0.3 * k * cos(0.2), 0.0] }
                }
                for k in 0..40 {
                    body a[k] { mass: 0.5, inertia: 0.00375, at: [(0.3 * k + 0.15) * sin(0.2), -(0.3 * k + 0.15) * cos(0.2), 0.2 - PI / 2.0] }
                    revolute r[k][-0.2, 0.0] ~ a[k][-0.15, 0.0];
                    revolute a[k][0.15, 0.0] ~ r[k + 1][-0.2, 0.0];
                    revolute_revolute r[k][0.2, 0.0] ~ r[k + 1][0.2, 0.0] { length: 0.3 };
                }
                revolute ground[0.0, 0.0] ~ r[0][-0.2, 0.0];
                revolute_revolute ground[0.4, 0.3] ~ r[0][0.2, 0.0] { length: 0.3 };
            }
        }
    };
}
ladder!(LadderBody);
ladder!(LadderJoint joint_coordinates);

mod chain16 {
    include!("../mechanisms/spatial_chain16.rs");
}
mod chain16_joint {
    include!("../mechanisms/spatial_chain16_joint.rs");
}

/// Median of 7 batches of `n` calls, in µs per call.
fn median_micros(n: usize, mut f: impl FnMut()) -> f64 {
    let mut runs: Vec<f64> = (0..7)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..n {
                f();
            }
            start.elapsed().as_secs_f64() / n as f64 * 1e6
        })
        .collect();
    runs.sort_by(f64::total_cmp);
    runs[3]
}

/// One row: sizes, ops, the accelerations' and an RK4 step's times, from a moving state (100 RK4
/// steps of 1 ms after assembly at rest).
fn row<M: ForwardDynamics<f64, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize>(m: &M, label: &str, coordinates: &str) {
    let mut q = m.initial_positions();
    let mut ws = Workspace::<f64, NV, NC, 0>::boxed();
    KinematicSolver::default().assemble(m, &mut ws, &mut q, 0.0).expect("assembles");
    let system = System::new(m);
    let mut rk4 = Rk4::new(Rk4Options::default().with_step(1e-3));
    let mut p = system.point(0.0, q, [0.0; NV], [0.0; 2]).expect("forward dynamics");
    let mut next = p;
    for _ in 0..100 {
        rk4.step(&system, &mut ws, &p, f64::INFINITY, &mut next).expect("a step");
        p = next;
    }
    // the generated operations of one call: the evaluation before the solve, and in joint
    // coordinates the tree's M⁻¹h and M⁻¹Dᵀ (the factors shared by the rows, then each row's
    // passes; a tree without rows: M⁻¹h, which holds h, alone)
    let ops_of = |name: &str| M::OP_COUNTS.iter().find(|o| o.function == name).map_or(0, |o| (o.add + o.mul + o.div + o.call) as u64);
    let evaluation = ops_of("accelerations (evaluation, before the solve)");
    let ops = match (ops_of("free_accelerations"), NC) {
        (0, _) => evaluation,
        (free, 0) => free,
        (free, nc) => evaluation + free + ops_of("solve_mass_rows (shared)") + nc as u64 * ops_of("solve_mass_rows (each row)"),
    };
    let options = DynamicsOptions::default();
    let (mut vd, mut lambda) = ([0.0; NV], [0.0; NC]);
    let accelerations = median_micros(20_000, || {
        m.accelerations(std::hint::black_box(&p.q), &p.v, p.t, &options, &mut vd, &mut lambda).expect("accelerations");
    });
    let step = median_micros(5_000, || {
        rk4.step(&system, &mut ws, std::hint::black_box(&p), f64::INFINITY, &mut next).expect("a step");
    });
    // DOPRI5 at its default tolerances, each call one step (its size adapted from the last)
    let mut dopri = Dopri5::new(Dopri5Options::default());
    let dopri_step = median_micros(5_000, || {
        dopri.step(&system, &mut ws, std::hint::black_box(&p), p.t + 1e-3, &mut next).expect("a step");
    });
    println!("| {label} | {coordinates} | {NQ} | {NV} | {NC} | {ops} | {accelerations:.2} µs | {step:.2} µs | {dopri_step:.2} µs |");
}

fn main() {
    println!("| mechanism | coordinates | NQ | NV | NC | ops | accelerations | RK4 step | DOPRI5 step |");
    println!("|---|---|---|---|---|---|---|---|---|");
    row(&ArmBody::default(), "6-revolute arm", "body");
    row(&ArmJoint::default(), "6-revolute arm", "joint");
    row(&chain16::SpatialChain16::default(), "16-link ball chain", "body");
    row(&chain16_joint::SpatialChain16Joint::default(), "16-link ball chain", "joint");
    row(&mbd_examples::slider_crank::SliderCrank::default(), "slider-crank (driven)", "body");
    row(&mbd_examples::joint::slider_crank_0::SliderCrank::default(), "slider-crank (driven)", "joint");
    row(&mbd_examples::free_four_bar::FreeFourBar::default(), "free four-bar", "body");
    row(&mbd_examples::joint::free_four_bar_0::FreeFourBar::default(), "free four-bar", "joint");
    row(&mbd_examples::suspension_dynamics::DoubleAArmRide::default(), "double A-arm ride", "body");
    row(&mbd_examples::joint::suspension_dynamics_0::DoubleAArmRide::default(), "double A-arm ride", "joint");
    row(&LadderBody::default(), "40-loop ladder", "body");
    row(&LadderJoint::default(), "40-loop ladder", "joint");
    let ops_of = |name: &str| LadderJoint::OP_COUNTS.iter().find(|o| o.function == name).map_or(0, |o| o.add + o.mul + o.div + o.call);
    println!(
        "\n40-loop ladder in joint coordinates: M⁻¹Dᵀ's shared factors {} ops, each row {} ops; one M⁻¹x alone {} ops",
        ops_of("solve_mass_rows (shared)"),
        ops_of("solve_mass_rows (each row)"),
        ops_of("solve_mass")
    );
}
