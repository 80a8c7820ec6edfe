//! The stack a solve takes, measured by painting it: a large region below the current frame is
//! filled with a byte pattern, the solve runs, and the lowest byte that no longer holds the
//! pattern is how deep it went. Two planar ladders of four-bar loops (51 and 201 bodies, the
//! second `tests/large.rs`'s) through assembly, every integrator for two steps of 1 ms, DOPRI5
//! with coordinate partitioning, and statics.
//!
//! `cargo run --release` (or `cargo run` for a debug build) in this folder; `frames.py` lists
//! the largest frames of the binary (`objdump -d --no-show-raw-insn target/release/mbd-stack >
//! dis.txt && python3 frames.py dis.txt 4000`).
use mbd::prelude::*;

include!("../../../tests/common/ladder.rs");

ladder! {
    /// The ladder with 25 loops.
    Ladder51, 25
}
ladder! {
    /// `tests/large.rs`' ladder of 100 loops.
    Ladder201, 100
}

/// Bytes painted below the caller's frame: more than any solve here takes.
const PAINT: usize = 48 << 20;
const PATTERN: u8 = 0xA5;

/// Fills the `PAINT` bytes below its caller's frame with the pattern.
#[inline(never)]
fn paint() {
    let mut region = core::mem::MaybeUninit::<[u8; PAINT]>::uninit();
    let start = region.as_mut_ptr().cast::<u8>();
    for k in 0..PAINT {
        // SAFETY: `start` points to PAINT bytes of this frame's own local.
        unsafe { start.add(k).write_volatile(PATTERN) }
    }
    std::hint::black_box(&region);
}

/// An address in the caller's frame.
#[inline(never)]
fn frame_address() -> usize {
    let local = 0u8;
    std::hint::black_box(&local) as *const u8 as usize
}

/// Bytes below `top` that no longer hold the pattern (the stack grows down).
#[inline(never)]
fn used_below(top: usize) -> usize {
    let mut address = top - PAINT + 4096;
    // SAFETY: every address from top − PAINT + 4096 up to `top` is in this thread's stack, which
    // `paint` has just written (the 4 KiB margin is below `paint`'s own frame).
    while address < top && unsafe { (address as *const u8).read_volatile() } == PATTERN {
        address += 1;
    }
    top - address
}

/// Runs `f` on painted stack and prints how deep it went.
fn measure<R>(name: &str, f: impl FnOnce() -> R) -> R {
    let top = frame_address();
    paint();
    let result = f();
    println!("{name:46} {:8.1} KiB", used_below(top) as f64 / 1024.0);
    result
}

macro_rules! every_analysis {
    ($M:ident) => {{
        let m = $M::default();
        let mut ws = $M::workspace();
        let mut q = m.initial_positions();
        println!("== {} (NV {}, NC {})", stringify!($M), $M::NV, $M::NC);
        measure("assembly", || KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0).expect("assembles"));
        let (v0, times) = ([0.0; $M::NV], [1e-3, 2e-3]);
        let mut last = [0.0; $M::NQ];
        // The integrators are boxed (made here, outside the measurement): their own arrays are
        // their value's, wherever the caller puts it.
        macro_rules! run {
            ($label:expr, $integrator:expr, $options:expr) => {{
                let mut integrator = Box::new($integrator);
                let bytes = std::mem::size_of_val(&*integrator) as f64 / 1024.0;
                measure(&format!("{} (its value {bytes:.0} KiB)", $label), || {
                    Simulation::new(&m, &mut *integrator)
                        .start(0.0, &q, &v0)
                        .times(&times)
                        .options($options)
                        .run(&mut ws, |s| last = s.point.q)
                        .expect($label)
                });
            }};
        }
        let options = SimulationOptions::default();
        run!("RK4", Rk4::default(), options);
        run!("DOPRI5", Dopri5::default(), options);
        run!("DOP853", Dop853::default(), options);
        run!("generalized-α", $M::generalized_alpha(GeneralizedAlphaOptions::default()), options);
        run!("BDF", Bdf::new(BdfOptions::default()), options);
        run!("Radau5", Radau5::default(), options);
        run!("Auto", Auto::default(), options);
        run!("DOPRI5 with partitioning", Dopri5::default(), options.with_correction(Correction::partitioning()));
        let mut lambda = [0.0; $M::NC];
        measure("statics", || StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut lambda).expect("statics"));
    }};
}

fn main() {
    // A thread with room for the painted region.
    std::thread::Builder::new()
        .stack_size(64 << 20)
        .spawn(|| {
            every_analysis!(Ladder51);
            every_analysis!(Ladder201);
        })
        .expect("spawn")
        .join()
        .expect("the analyses ran");
}
