//! What each effect costs: a suspension and a vehicle built from four corners, each declared once
//! with scenes that leave out one effect at a time (and one that leaves out all of them), timed
//! in the same run. Per scene: the operations of the generated force functions and of one
//! evaluation of the accelerations (from the mechanism's `OP_COUNTS`), the CPU time of that
//! evaluation, and of an RK4 step of 1 ms without and with projection onto the constraints (from
//! the assembled design position at rest; medians of 15 rounds, each timing every scene once).
//!
//! Run: `cargo run --release -p mbd-study --bin scenes` (about 8 s once built; the release build
//! of its 12 generated types, 5 of them the 13-body vehicle, took 5 min 25 s; that build also
//! had a vehicle scene without its tyres, since left out to keep the test run short). Writes
//! `mbd-study/results/scenes.md`.

use std::time::Instant;

use mbd::prelude::*;
use mbd::{ForceInfo, OpCount};
use mbd_study::{
    QuarterCar, QuarterCarBare, QuarterCarNoCoil, QuarterCarNoFriction, QuarterCarNoGravity, QuarterCarNoShock, QuarterCarNoTyre, Vehicle,
    VehicleBare, VehicleNoFriction, VehicleNoShock,
};

/// One scene's costs.
#[derive(Clone, Copy)]
struct Row {
    scene: &'static str,
    leaves_out: &'static str,
    ops: [u32; 4],
    /// CPU time of one evaluation of the accelerations at the assembled design state (µs).
    evaluation_us: f64,
    /// CPU time of an RK4 step without drift correction (µs): four evaluations and the state
    /// updates, the same work at every state.
    step_us: f64,
    /// CPU time of an RK4 step with the default projection onto the constraints (µs): its
    /// Newton iterations depend on how fast the scene moves.
    projected_us: f64,
}

/// The operations (+ − × ÷ and calls) of a generated function.
fn ops(counts: &[OpCount], function: &str) -> u32 {
    let c = counts.iter().find(|c| c.function.starts_with(function)).unwrap_or_else(|| panic!("no op count for {function}"));
    c.add + c.mul + c.div + c.call
}

/// The functions whose operations a scene's row shows.
const FUNCTIONS: [&str; 4] = ["forces", "forces_q", "forces_v", "accelerations"];

/// A function's operations were the elements computed apart: the base's, plus what each
/// element costs alone above it.
fn apart(base: &[OpCount], elements: &[ForceInfo], f: &str) -> u32 {
    ops(base, f) + elements.iter().map(|e| ops(e.op_counts, f) - ops(base, f)).sum::<u32>()
}

/// The force functions whose operations add up element by element.
const FORCES: [&str; 3] = ["forces", "forces_q", "forces_v"];

/// What each force element of `M` costs alone (`ForceInfo::op_counts` above
/// `BASE_FORCE_OP_COUNTS`), their sum, and what `M` generates with its elements together.
fn elements_table<M: Mechanism>(title: &str) -> String {
    let base = M::BASE_FORCE_OP_COUNTS;
    let mut out = format!("**{title}: each force element alone**\n\n| element | forces | forces_q | forces_v |\n|---|---|---|---|\n");
    let row = |name: &str, counts: [u32; 3]| format!("| {name} | {} | {} | {} |\n", counts[0], counts[1], counts[2]);
    out += &row("base (no element)", FORCES.map(|f| ops(base, f)));
    for e in M::FORCE_ELEMENTS {
        out += &row(&format!("`{}`", e.name), FORCES.map(|f| ops(e.op_counts, f) - ops(base, f)));
    }
    out += &row("base + each alone", FORCES.map(|f| apart(base, M::FORCE_ELEMENTS, f)));
    out += &row("generated, the elements together", FORCES.map(|f| ops(M::OP_COUNTS, f)));
    out
}

/// Simulated time per timed run (s) and RK4's step (s).
const RUN: f64 = 0.2;
const STEP: f64 = 1e-3;

fn measure<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    m: &M,
    scene: &'static str,
    leaves_out: &'static str,
    ws: &mut Workspace<f64, NV, NC, N, NS>,
) -> Row
where
    M: ForwardDynamics<f64, NQ, NV, NC>,
{
    let mut q = m.initial_positions();
    KinematicSolver::default().assemble(m, ws, &mut q, 0.0).unwrap_or_else(|e| panic!("{scene} assembles: {e}"));
    let v = [0.0; NV];
    let evaluation_us = {
        let (mut vd, mut lambda) = ([0.0; NV], [0.0; NC]);
        let start = Instant::now();
        for _ in 0..EVALUATIONS {
            m.accelerations(std::hint::black_box(&q), &v, 0.0, &DynamicsOptions::default(), &mut vd, &mut lambda)
                .unwrap_or_else(|e| panic!("{scene}: {e}"));
            std::hint::black_box(&vd);
        }
        start.elapsed().as_secs_f64() * 1e6 / EVALUATIONS as f64
    };
    let mut step = |correction: Correction<f64>| {
        let options = SimulationOptions::default().with_correction(correction);
        let mut rk4 = Rk4::new(Rk4Options::default().with_step(STEP));
        let start = Instant::now();
        let stats = Simulation::new(m, &mut rk4)
            .start(0.0, &q, &v)
            .times(&[RUN])
            .options(options)
            .run(ws, |s| {
                assert!(s.point.q.iter().all(|x| x.is_finite()), "{scene}: finite");
            })
            .unwrap_or_else(|e| panic!("{scene} runs: {e}"));
        start.elapsed().as_secs_f64() * 1e6 / stats.steps as f64
    };
    let step_us = step(Correction::None);
    let projected_us = step(SimulationOptions::default().correction);
    Row { scene, leaves_out, ops: FUNCTIONS.map(|f| ops(M::OP_COUNTS, f)), evaluation_us, step_us, projected_us }
}

/// Evaluations per timed batch.
const EVALUATIONS: u32 = 2000;

/// Rounds of timing: each round times every scene once, so that a slow phase of the machine
/// falls on all scenes alike, and each time is the median over the rounds.
const ROUNDS: usize = 15;

/// Each scene's row with its times the medians of [`ROUNDS`] rounds of `round`.
fn rounds(round: impl Fn() -> Vec<Row>) -> Vec<Row> {
    let all: Vec<Vec<Row>> = (0..ROUNDS).map(|_| round()).collect();
    let median = |k: usize, time: fn(&Row) -> f64| {
        let mut times: Vec<f64> = all.iter().map(|r| time(&r[k])).collect();
        times.sort_by(f64::total_cmp);
        times[ROUNDS / 2]
    };
    (0..all[0].len())
        .map(|k| Row {
            evaluation_us: median(k, |r| r.evaluation_us),
            step_us: median(k, |r| r.step_us),
            projected_us: median(k, |r| r.projected_us),
            ..all[0][k]
        })
        .collect()
}

fn quarter_car() -> Vec<Row> {
    let mut ws = QuarterCar::workspace();
    vec![
        measure(&QuarterCar::default(), "QuarterCar", "—", &mut ws),
        measure(&QuarterCarNoFriction::default(), "QuarterCarNoFriction", "friction", &mut ws),
        measure(&QuarterCarNoShock::default(), "QuarterCarNoShock", "shock", &mut ws),
        measure(&QuarterCarNoCoil::default(), "QuarterCarNoCoil", "coil", &mut ws),
        measure(&QuarterCarNoTyre::default(), "QuarterCarNoTyre", "tyre", &mut ws),
        measure(&QuarterCarNoGravity::default(), "QuarterCarNoGravity", "gravity", &mut ws),
        measure(&QuarterCarBare::default(), "QuarterCarBare", "all five", &mut ws),
    ]
}

fn vehicle() -> Vec<Row> {
    let mut ws = Vehicle::workspace();
    vec![
        measure(&Vehicle::default(), "Vehicle", "—", &mut ws),
        measure(&VehicleNoFriction::default(), "VehicleNoFriction", "friction", &mut ws),
        measure(&VehicleNoShock::default(), "VehicleNoShock", "shock (×4)", &mut ws),
        measure(&VehicleBare::default(), "VehicleBare", "all five", &mut ws),
    ]
}

fn table(title: &str, rows: &[Row]) -> String {
    let mut out = format!(
        "**{title}**\n\n| scene | leaves out | forces | forces_q | forces_v | accelerations | evaluation (µs) | RK4 step (µs) | \
         with projection (µs) |\n|---|---|---|---|---|---|---|---|---|\n"
    );
    for r in rows {
        let [h, h_q, h_v, a] = r.ops;
        out += &format!(
            "| `{}` | {} | {h} | {h_q} | {h_v} | {a} | {:.2} | {:.2} | {:.2} |\n",
            r.scene, r.leaves_out, r.evaluation_us, r.step_us, r.projected_us
        );
    }
    out
}

fn main() {
    let quarter = rounds(quarter_car);
    let vehicle = rounds(vehicle);
    let report = format!(
        "{}\n{}\nOperations: + − × ÷ and calls of each generated function (`OP_COUNTS`); `accelerations` is the fused \
         evaluation of Φ, D, γ, h and M before the sparse solve. Evaluation: one call of `accelerations` at the \
         assembled design position at rest (a batch of {EVALUATIONS}). RK4 step: a run of {RUN} s at {STEP} s from \
         there, without drift correction and with the default projection (whose Newton iterations depend on how fast \
         the scene moves). Each time is the median of {ROUNDS} rounds, each round timing every scene once.\n\n{}\n{}\n\
         Each element alone: what the force functions would count above the base were it the mechanism's only element \
         (`ForceInfo::op_counts`, equal to what a scene keeping only it generates). The elements together cost less \
         than the base and each alone: common subexpressions are computed once (a coil and a shock on one strut share \
         its length and direction; the vehicle's elements on the chassis share its orientation); `forces` has one \
         addition more wherever two elements' terms meet in one entry.\n",
        table(&format!("Planar double A-arm corner ({} bodies, {} constraint rows)", QuarterCar::N_BODIES, QuarterCar::NC), &quarter),
        table(
            &format!("Vehicle of four double-wishbone corners ({} spatial bodies, {} constraint rows)", Vehicle::N_BODIES, Vehicle::NC),
            &vehicle
        ),
        elements_table::<QuarterCar>("Planar double A-arm corner"),
        elements_table::<Vehicle>("Vehicle"),
    );
    print!("{report}");
    let out = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("results/scenes.md");
    std::fs::write(&out, &report).unwrap_or_else(|e| panic!("writing {}: {e}", out.display()));
    eprintln!("wrote {}", out.display());
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The vehicle is a sane model: at rest under gravity its tyres carry its weight, its left and
    /// right corners are mirror images, and its chassis sits within 2 cm of its design height.
    #[test]
    fn the_vehicle_rests_on_its_four_tyres_symmetrically() {
        let m = Vehicle::default();
        let mut ws = Vehicle::workspace();
        let mut q = m.initial_positions();
        let mut lambda = [0.0; Vehicle::NC];
        StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut lambda).expect("the vehicle has a rest state");
        type Body = mbd::SpatialBody<{ Vehicle::NQ }, { Vehicle::NV }>;
        let z = |b: Body| b.position(&q).z;
        let uprights = [Vehicle::FRONT_LEFT_UPRIGHT, Vehicle::FRONT_RIGHT_UPRIGHT, Vehicle::REAR_LEFT_UPRIGHT, Vehicle::REAR_RIGHT_UPRIGHT];
        let tyres: f64 = uprights.iter().map(|&u| m.k_t * (m.radius - z(u))).sum();
        let weight: f64 = (0..Vehicle::N_BODIES).map(|k| m.mass_of(Body::new(k, "")) * 9.81).sum();
        // The tyre forces balance the weight to the static solver's tolerance (1e-10 relative).
        assert!((tyres - weight).abs() <= 1e-6 * weight, "tyres {tyres} N, weight {weight} N");
        // Mirror images (`mirrored y`): the same heights and opposite y left and right, to the
        // solver's tolerance.
        let y = |b: Body| b.position(&q).y;
        assert!((z(uprights[0]) - z(uprights[1])).abs() < 1e-9 && (z(uprights[2]) - z(uprights[3])).abs() < 1e-9);
        assert!((y(uprights[0]) + y(uprights[1])).abs() < 1e-9 && (y(uprights[2]) + y(uprights[3])).abs() < 1e-9);
        assert!(y(uprights[0]) > 0.7, "the left wheel centres at y = 0.76 m: {}", y(uprights[0]));
        let chassis = z(Vehicle::CHASSIS);
        assert!((chassis - 0.55).abs() < 0.02, "chassis at {chassis} m");
        assert_eq!(Vehicle::BODY_NAMES[1], "front_left.lower", "names read as written");
    }

    /// Nothing is paid for what a scene leaves out: every function of every scene costs at most
    /// the base's operations and at least those of the scene that leaves out everything, and
    /// every effect costs something somewhere. (How the costs add up, element by element, is
    /// `a_scene_costs_its_base_and_each_element_alone_less_what_they_share`.) The planar corner
    /// without its five effects has no force operations left.
    #[test]
    fn a_scene_costs_the_base_less_its_effects() {
        let quarter = [
            QuarterCarNoFriction::OP_COUNTS,
            QuarterCarNoShock::OP_COUNTS,
            QuarterCarNoCoil::OP_COUNTS,
            QuarterCarNoTyre::OP_COUNTS,
            QuarterCarNoGravity::OP_COUNTS,
        ];
        let vehicle = [VehicleNoFriction::OP_COUNTS, VehicleNoShock::OP_COUNTS];
        // (the base's counts, each single-effect scene's, the bare scene's)
        type Counts = &'static [OpCount];
        let cases: [(Counts, &[Counts], Counts); 2] =
            [(QuarterCar::OP_COUNTS, &quarter, QuarterCarBare::OP_COUNTS), (Vehicle::OP_COUNTS, &vehicle, VehicleBare::OP_COUNTS)];
        for (base, singles, bare) in cases {
            for f in FUNCTIONS {
                let (all, none) = (ops(base, f), ops(bare, f));
                for s in singles {
                    assert!(none <= ops(s, f) && ops(s, f) <= all, "{f}: {none} ≤ {} ≤ {all}", ops(s, f));
                }
                assert!(none < all, "{f}: the effects cost something");
            }
            for (k, s) in singles.iter().enumerate() {
                assert!(FUNCTIONS.iter().any(|f| ops(s, f) < ops(base, f)), "effect {k} costs something");
            }
        }
        for f in ["forces", "forces_q", "forces_v"] {
            assert_eq!(ops(QuarterCarBare::OP_COUNTS, f), 0, "{f}");
        }
    }

    /// The additions of `forces` where the terms of two elements meet: on each velocity, one per
    /// element beyond the first that reaches it.
    fn meets(elements: &[ForceInfo]) -> u32 {
        let mut on = std::collections::BTreeMap::new();
        for e in elements {
            for &v in e.velocities {
                *on.entry(v).or_insert(0u32) += 1;
            }
        }
        on.values().map(|k| k - 1).sum()
    }

    /// A scene's force functions cost its base (what the scene leaving out every effect
    /// generates), plus each element's cost alone (`ForceInfo::op_counts`, what a scene keeping
    /// only it generates: `tests/scenes.rs`), plus one addition wherever two elements' terms meet,
    /// less what elements share — exactly, in every scene of the corner:
    /// - each element costs the same in every scene that keeps it, and every scene's base is
    ///   the bare scene's count;
    /// - `forces` adds up exactly where no two elements read a common subexpression: the
    ///   coil, the tyre and the pivot friction act on different bodies or read only velocities
    ///   and parameters, and gravity's terms are constants;
    /// - where the coil and the shock, on the same two points, are both kept, they share the
    ///   strut's length and direction, and the scene costs less than the sum (measured 21 of
    ///   77 operations of `forces`);
    /// - in the scene without the shock the elements' derivatives fill disjoint entries (the
    ///   coil's on the lower arm, the tyre's on the knuckle, the pivots' constant ∂/∂v), so
    ///   `forces_q` and `forces_v` add up exactly too.
    ///
    /// The vehicle's base is its gyroscopic terms, and its elements share the chassis'
    /// orientation, so its scenes cost less than the sum.
    #[test]
    fn a_scene_costs_its_base_and_each_element_alone_less_what_they_share() {
        type Scene = (&'static str, &'static [OpCount], &'static [OpCount], &'static [ForceInfo]);
        let corner: [Scene; 7] = [
            ("QuarterCar", QuarterCar::OP_COUNTS, QuarterCar::BASE_FORCE_OP_COUNTS, QuarterCar::FORCE_ELEMENTS),
            (
                "QuarterCarNoFriction",
                QuarterCarNoFriction::OP_COUNTS,
                QuarterCarNoFriction::BASE_FORCE_OP_COUNTS,
                QuarterCarNoFriction::FORCE_ELEMENTS,
            ),
            ("QuarterCarNoShock", QuarterCarNoShock::OP_COUNTS, QuarterCarNoShock::BASE_FORCE_OP_COUNTS, QuarterCarNoShock::FORCE_ELEMENTS),
            ("QuarterCarNoCoil", QuarterCarNoCoil::OP_COUNTS, QuarterCarNoCoil::BASE_FORCE_OP_COUNTS, QuarterCarNoCoil::FORCE_ELEMENTS),
            ("QuarterCarNoTyre", QuarterCarNoTyre::OP_COUNTS, QuarterCarNoTyre::BASE_FORCE_OP_COUNTS, QuarterCarNoTyre::FORCE_ELEMENTS),
            (
                "QuarterCarNoGravity",
                QuarterCarNoGravity::OP_COUNTS,
                QuarterCarNoGravity::BASE_FORCE_OP_COUNTS,
                QuarterCarNoGravity::FORCE_ELEMENTS,
            ),
            ("QuarterCarBare", QuarterCarBare::OP_COUNTS, QuarterCarBare::BASE_FORCE_OP_COUNTS, QuarterCarBare::FORCE_ELEMENTS),
        ];
        let vehicle: [Scene; 4] = [
            ("Vehicle", Vehicle::OP_COUNTS, Vehicle::BASE_FORCE_OP_COUNTS, Vehicle::FORCE_ELEMENTS),
            ("VehicleNoFriction", VehicleNoFriction::OP_COUNTS, VehicleNoFriction::BASE_FORCE_OP_COUNTS, VehicleNoFriction::FORCE_ELEMENTS),
            ("VehicleNoShock", VehicleNoShock::OP_COUNTS, VehicleNoShock::BASE_FORCE_OP_COUNTS, VehicleNoShock::FORCE_ELEMENTS),
            ("VehicleBare", VehicleBare::OP_COUNTS, VehicleBare::BASE_FORCE_OP_COUNTS, VehicleBare::FORCE_ELEMENTS),
        ];
        for scenes in [&corner[..], &vehicle[..]] {
            let (_, bare, _, _) = scenes[scenes.len() - 1];
            let full = scenes[0].3;
            for &(scene, counts, base, elements) in scenes {
                for f in FORCES {
                    assert_eq!(ops(base, f), ops(bare, f), "{scene}: {f} of the base");
                    let (sum, total) = (apart(base, elements, f) + if f == "forces" { meets(elements) } else { 0 }, ops(counts, f));
                    eprintln!("{scene} {f}: {total} operations, {sum} were its elements apart");
                    if f == "forces" {
                        assert!(total <= sum, "{scene}: sharing only saves");
                    }
                }
                for e in elements {
                    let same = full.iter().find(|b| b.name == e.name).unwrap_or_else(|| panic!("{scene}: {} not in the base", e.name));
                    assert_eq!(e.op_counts, same.op_counts, "{scene}: {} costs what it costs in the base", e.name);
                }
            }
        }
        let strut = |elements: &[ForceInfo]| ["coil", "shock"].iter().all(|n| elements.iter().any(|e| e.name == *n));
        for &(scene, counts, base, elements) in &corner {
            let (sum, total) = (apart(base, elements, "forces") + meets(elements), ops(counts, "forces"));
            if strut(elements) {
                assert!(total < sum, "{scene}: the coil and the shock share the strut: {total} < {sum}");
            } else {
                assert_eq!(total, sum, "{scene}: forces add up where nothing is shared");
            }
        }
        for f in ["forces_q", "forces_v"] {
            let (_, counts, base, elements) = corner[2];
            assert_eq!(ops(counts, f), apart(base, elements, f), "QuarterCarNoShock {f}: disjoint entries add up");
        }
        // The vehicle's base is its gyroscopic terms; they cost in forces and forces_v.
        assert!(ops(Vehicle::BASE_FORCE_OP_COUNTS, "forces") > 0 && ops(Vehicle::BASE_FORCE_OP_COUNTS, "forces_v") > 0);
    }
}
