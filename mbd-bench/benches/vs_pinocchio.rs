//! The UR5 and the Panda (fingers locked) in mbd's joint coordinates (`mechanisms/ur5.rs`,
//! `panda.rs`, from the URDFs by `peers/robots/urdf_to_mbd.py`; agreement with Pinocchio to 1e-14
//! is `tests/robots.rs`) against Pinocchio 4.1.0's C++ in the same run:
//! `cargo bench -p mbd-bench --bench vs_pinocchio`.
//!
//! Pinocchio's side: `peers/ensure_env.sh` provides pip's libpinocchio with its headers (Eigen,
//! Boost, urdfdom); `peers/robots/pinocchio_bench.cpp` is compiled twice — against the library's
//! precompiled algorithms, and from the headers with -O3 -march=native — and each times CRBA,
//! RNEA, NLE and ABA. mbd's side, timed the same way (the mean ns per call over 1000 random
//! states, q ∈ U(−π, π), v ∈ U(−2, 2), v̇ ∈ U(−5, 5); the median of 301 passes): M by
//! `add_mass_matrix` on a zeroed matrix (against CRBA), h by `forces` (NLE), M v̇ − h by
//! `inverse_forces` (RNEA), and M⁻¹h by `free_accelerations` (ABA at zero torque).
//! mbd is built for baseline x86-64, as the workspace builds it. The table gives each time, its
//! ratio to the faster Pinocchio, and mbd's operation counts (`Mechanism::OP_COUNTS`).
//!
//! Then one RK4 step (h = 1 ms) against MuJoCo's (`peers/robots/mujoco_robot.py`: the same URDFs,
//! checked there against the Pinocchio fixtures to 1e-14; its C loop timed by `mujoco.rollout`),
//! both from the same state (the fixture's state 0, half its velocity) and timed the same way (the
//! median of 7 runs of 10 000 steps). Both integrate 0.5 s at h = 1 ms: the same method on the
//! same equations in the same coordinates, their joint angles must agree to 1e-6 rad (measured
//! 2026-11-29: below 1e-9) — the check that both simulate the same motion.
use mbd::{Dynamics, ForwardDynamics, Integrator, Mechanism, Point, Rk4, Rk4Options, System, Workspace};
use serde_json::Value;
use std::hint::black_box;
use std::path::Path;
use std::process::Command;
use std::time::Instant;

mod common;
use common::{peers_python, repo};

mod ur5 {
    include!("../mechanisms/ur5.rs");
}
mod panda {
    include!("../mechanisms/panda.rs");
}

/// States per pass and passes, as `pinocchio_bench.cpp` has them.
const STATES: usize = 1000;
const PASSES: usize = 301;

/// The median over `PASSES` of the mean ns per call of `f` over `states` (10 passes to warm up);
/// the outputs summed into a checksum, so that nothing is optimized away.
fn time<S>(states: &[S], mut f: impl FnMut(&S) -> f64) -> f64 {
    let mut checksum = 0.0;
    for _ in 0..10 {
        for s in states {
            checksum += f(black_box(s));
        }
    }
    let mut per_call: Vec<f64> = (0..PASSES)
        .map(|_| {
            let start = Instant::now();
            for s in states {
                checksum += f(black_box(s));
            }
            start.elapsed().as_nanos() as f64 / states.len() as f64
        })
        .collect();
    black_box(checksum);
    per_call.sort_by(f64::total_cmp);
    per_call[PASSES / 2]
}

/// mbd's times (ns) of M, h, M v̇ − h and M⁻¹h.
fn mbd_times<M: Dynamics<f64, N, N, 0>, const N: usize>(m: &M) -> [f64; 4] {
    // xorshift64*, uniform in [−r, r]
    let mut seed = 0x2026_1130_u64;
    let mut uniform = |r: f64| {
        seed ^= seed >> 12;
        seed ^= seed << 25;
        seed ^= seed >> 27;
        let u = (seed.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64;
        r * (2.0 * u - 1.0)
    };
    let states: Vec<([f64; N], [f64; N], [f64; N])> = (0..STATES)
        .map(|_| {
            let q = core::array::from_fn(|_| uniform(std::f64::consts::PI));
            let v = core::array::from_fn(|_| uniform(2.0));
            (q, v, core::array::from_fn(|_| uniform(5.0)))
        })
        .collect();
    let mass = time(&states, |(q, _, _)| {
        let mut a = [[0.0; N]; N];
        m.add_mass_matrix(q, 1.0, &mut a);
        a[0][0] + a[N - 2][N - 1]
    });
    let forces = time(&states, |(q, v, _)| {
        let mut h = [0.0; N];
        m.forces(q, v, 0.0, &mut h);
        h[0] + h[N - 1]
    });
    let inverse = time(&states, |(q, v, vd)| {
        let mut tau = [0.0; N];
        m.inverse_forces(q, v, vd, 0.0, &mut tau);
        tau[0] + tau[N - 1]
    });
    let forward = time(&states, |(q, v, _)| {
        let mut vd = [0.0; N];
        let solved = m.free_accelerations(q, v, 0.0, &mut vd);
        debug_assert_eq!(solved, Some(Ok(())));
        vd[0] + vd[N - 1]
    });
    [mass, forces, inverse, forward]
}

/// Pinocchio's times by robot: the pip library's and the headers' (-O3 -march=native), each
/// `{"robot", "crba", "rnea", "nle", "aba"}` in ns.
fn pinocchio(python: &str) -> [Vec<Value>; 2] {
    let purelib = Command::new(python).args(["-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"]).output().expect("python");
    let prefix = Path::new(String::from_utf8_lossy(&purelib.stdout).trim()).join("cmeel.prefix");
    let source = repo().join("mbd-bench/peers/robots/pinocchio_bench.cpp");
    let target = std::env::var_os("CARGO_TARGET_DIR").map(Into::into).unwrap_or_else(|| repo().join("target")).join("peers");
    std::fs::create_dir_all(&target).expect("target/peers");
    let include = |dir: &str| format!("-I{}", prefix.join(dir).display());
    let common: Vec<String> = ["-std=c++17", "-O3", "-DNDEBUG"]
        .into_iter()
        .map(String::from)
        .chain(["include", "include/eigen3", "include/urdfdom_headers", "include/urdfdom"].map(include))
        .chain(
            [
                "-DBOOST_MPL_LIMIT_LIST_SIZE=30",
                "-DBOOST_MPL_LIMIT_VECTOR_SIZE=30",
                "-DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS",
                "-DBOOST_FUSION_INVOKE_MAX_ARITY=12",
            ]
            .map(String::from),
        )
        .collect();
    let lib = prefix.join("lib");
    let link = [
        format!("-L{}", lib.display()),
        format!("-Wl,-rpath,{}", lib.display()),
        "-lpinocchio_parsers".into(),
        "-lpinocchio_default".into(),
        "-lurdfdom_model".into(),
    ];
    let variants: [(&str, &[&str]); 2] = [
        // the precompiled algorithms of pip's libpinocchio_default.so
        ("pinocchio_library", &["-DPINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION"]),
        // the header templates compiled here for this CPU (alignment kept at the library's 16 bytes)
        (
            "pinocchio_headers",
            &["-march=native", "-DEIGEN_MAX_ALIGN_BYTES=16", "-DEIGEN_MALLOC_ALREADY_ALIGNED=1", "-Wno-stringop-overread"],
        ),
    ];
    let robots = prefix.join("share/example-robot-data/robots");
    variants.map(|(name, flags)| {
        let binary = target.join(name);
        let modified = |p: &Path| std::fs::metadata(p).and_then(|m| m.modified()).ok();
        if modified(&binary) < modified(&source) {
            eprintln!("vs_pinocchio: compiling {} ({name})", source.display());
            let status = Command::new("g++")
                .args(&common)
                .args(flags)
                .arg(&source)
                .arg("-o")
                .arg(&binary)
                .args(&link)
                .status()
                .expect("g++ runs (install g++)");
            assert!(status.success(), "compiling {} failed", source.display());
        }
        let out = Command::new(&binary).arg(&robots).arg("0.02").output().expect("the Pinocchio driver runs");
        assert!(out.status.success(), "{name} failed: {}", String::from_utf8_lossy(&out.stderr));
        String::from_utf8_lossy(&out.stdout).lines().map(|line| serde_json::from_str(line).expect("one JSON object per robot")).collect()
    })
}

/// The summed operations of a generated function (`Mechanism::OP_COUNTS`), if counted.
fn ops<M: Mechanism>(function: &str) -> Option<u64> {
    M::OP_COUNTS.iter().find(|o| o.function == function).map(|o| u64::from(o.add + o.mul + o.div + o.call))
}

/// MuJoCo's side: `peers/robots/mujoco_robot.py`'s JSON, by robot.
fn mujoco(python: &str) -> Vec<Value> {
    let script = repo().join("mbd-bench/peers/robots/mujoco_robot.py");
    let out = Command::new(python).arg(&script).output().expect("the peers' Python runs");
    eprint!("{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "{} failed", script.display());
    let all: Value = serde_json::from_slice(&out.stdout).expect("mujoco_robot.py prints JSON");
    all["robots"].as_array().expect("robots").clone()
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array().expect("an array").iter().map(|x| x.as_f64().expect("a number")).collect()
}

/// mbd's RK4 step (ns) from MuJoCo's initial state of `robot`, and the largest difference of
/// the joint angles from MuJoCo's after 0.5 s at h = 1 ms (rad).
fn mbd_rk4<M: ForwardDynamics<f64, N, N, 0>, const N: usize>(m: &M, robot: &Value) -> (f64, f64) {
    let joints: Vec<&str> = robot["joints"].as_array().expect("joints").iter().map(|j| j.as_str().expect("a name")).collect();
    let index: Vec<usize> =
        joints.iter().map(|j| M::COORDINATE_NAMES.iter().position(|c| *c == format!("{j}.angle")).expect("the joint's angle")).collect();
    // θ_mbd = θ0 + q_MuJoCo (the converter's rule, `tests/robots.rs`)
    let (theta0, q0, v0) = (m.initial_positions(), floats(&robot["q0"]), floats(&robot["v0"]));
    let (mut q, mut v) = (theta0, [0.0; N]);
    for (k, &i) in index.iter().enumerate() {
        q[i] += q0[k];
        v[i] = v0[k];
    }
    let system = System::new(m);
    let mut ws = Workspace::<f64, N, 0, 0>::boxed();
    let mut rk4 = Rk4::new(Rk4Options::default().with_step(1e-3));
    let start: Point<f64, N, N, 0> = system.point(0.0, q, v, [0.0; 2]).expect("forward dynamics");
    let mut run = |steps: usize| {
        let (mut p, mut next) = (start, start);
        for _ in 0..steps {
            rk4.step(&system, &mut ws, black_box(&p), f64::INFINITY, &mut next).expect("an RK4 step");
            p = next;
        }
        p
    };
    let end = run(500);
    let theirs = floats(&robot["finals"][0]["q"]);
    let difference = index.iter().enumerate().map(|(k, &i)| (end.q[i] - theta0[i] - theirs[k]).abs()).fold(0.0, f64::max);
    let mut runs: Vec<f64> = (0..7)
        .map(|_| {
            let started = Instant::now();
            black_box(run(10_000));
            started.elapsed().as_nanos() as f64 / 10_000.0
        })
        .collect();
    runs.sort_by(f64::total_cmp);
    (runs[3], difference)
}

fn main() {
    let python = peers_python();
    let [library, headers] = pinocchio(&python);
    let arms = mujoco(&python);
    let arm = |name: &str| arms.iter().find(|r| r["robot"] == name).expect("MuJoCo's robot").clone();
    let (ur5, panda) = (ur5::Ur5::default(), panda::Panda::default());
    // each robot's name, mbd's times of M, h, M v̇ − h and M⁻¹h, their operations, its RK4 step
    type Measured = (&'static str, [f64; 4], [Option<u64>; 4], (f64, f64));
    let robots: [Measured; 2] = [
        ("ur5", mbd_times(&ur5), counts::<ur5::Ur5, 6>(), mbd_rk4(&ur5, &arm("ur5"))),
        ("panda", mbd_times(&panda), counts::<panda::Panda, 7>(), mbd_rk4(&panda, &arm("panda"))),
    ];
    println!("\n| robot | function | Pinocchio library | Pinocchio headers (-march=native) | mbd | mbd / faster Pinocchio | mbd ops |");
    println!("|---|---|---|---|---|---|---|");
    for (robot, times, counts, _) in &robots {
        let of = |set: &[Value], key: &str| set.iter().find(|r| r["robot"] == *robot).and_then(|r| r[key].as_f64()).expect("a time");
        for (k, (function, key)) in
            [("M (CRBA)", "crba"), ("h (NLE)", "nle"), ("inverse dynamics (RNEA)", "rnea"), ("forward dynamics (ABA)", "aba")]
                .into_iter()
                .enumerate()
        {
            let (lib, hdr) = (of(&library, key), of(&headers, key));
            let count = counts[k].map_or("–".into(), |c| c.to_string());
            println!(
                "| {robot} | {function} | {lib:.0} ns | {hdr:.0} ns | {:.0} ns | {:.2} | {count} |",
                times[k],
                times[k] / lib.min(hdr)
            );
        }
    }
    println!("\n| robot | MuJoCo RK4 step | mbd RK4 step | mbd / MuJoCo | joint angles at 0.5 s, largest difference |");
    println!("|---|---|---|---|---|");
    for (robot, _, _, (step, difference)) in &robots {
        let theirs = arm(robot)["step_us"].as_f64().expect("MuJoCo's step") * 1e3;
        println!("| {robot} | {:.2} µs | {:.2} µs | {:.2} | {difference:.1e} rad |", theirs * 1e-3, step * 1e-3, step / theirs);
    }
    for (robot, _, _, (_, difference)) in &robots {
        assert!(*difference < 1e-6, "{robot}: mbd and MuJoCo end 0.5 s of RK4 {difference:.1e} rad apart: not the same motion");
    }
}

/// The operations of mbd's four calls: M (by the composite-rigid-body algorithm, else NV
/// products M e_c), h, M v̇ − h (recursive Newton–Euler), M⁻¹h.
fn counts<M: Mechanism, const N: usize>() -> [Option<u64>; 4] {
    let matrix = ops::<M>("add_mass_matrix").or(ops::<M>("mass_times").map(|m| m * N as u64));
    [matrix, ops::<M>("forces"), ops::<M>("inverse_forces"), ops::<M>("free_accelerations")]
}
