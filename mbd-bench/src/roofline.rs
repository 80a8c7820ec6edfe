//! A roofline for mbd's generated kernels (issue 41, item 3): this processor's measured peak
//! throughput for each kind of operation the kernels are made of, and how close a kernel of a
//! given operation mix comes to it.
//!
//! **The peaks** are measured by microbenchmarks of independent operations, 8 to [`LANES`]
//! chains at once and the best rate kept (enough chains to hide each operation's latency behind
//! the others, few enough to stay in registers, at either vector width: an adder with a latency
//! of 3–4 cycles on 2 pipes needs 6–8 vectors in flight), which the compiler vectorizes as it
//! vectorizes the kernels (SSE2's 2 lanes at baseline x86-64, AVX2's 4 at native): additions, multiplications, the two interleaved 1:1, divisions, fused
//! multiply-adds (where the instruction set has them), and `sin_cos` of independent angles
//! within ±π/4 (a library call, not vectorized, at its fastest path; the kernels call it once
//! per planar angle).
//!
//! **A kernel's floor** for its operation counts ([`mbd::OpCount`]: a additions, m
//! multiplications, d divisions, c elementary-function calls) is
//!
//! ```text
//! t_floor = max(a / P_add, m / P_mul, (a + m) / P_add+mul) + d / P_div + c / P_sin_cos
//! ```
//!
//! — additions and multiplications overlap as far as the interleaved microbenchmark shows they
//! can (on separate pipes it is twice either alone; on this project's Intel Xeon, whose two
//! pipes each do both, it equals either alone), divisions and calls are added (the divider is
//! one unit; a call's latency stalls the code that waits on it). The fraction of
//! peak is t_floor over the kernel's measured time: 100 % is a kernel that does nothing but its
//! arithmetic, at the machine's full width. Loads, stores, shuffles and spills are what the
//! difference is made of (the performance guide's `objdump` counts).
use std::hint::black_box;
use std::time::Instant;

/// The most independent chains a microbenchmark runs at once (it tries 8, 16, 24 and this).
pub const LANES: usize = 32;

/// Operations per chain in one timed call of a microbenchmark.
const REPEATS: usize = 1000;

/// The fastest of `rounds` rounds of `calls` calls of `f`, per call (ns): the fastest, not the
/// median, so that the machine's other load and its clock changes count against nothing.
pub fn fastest_ns(rounds: usize, calls: usize, mut f: impl FnMut()) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..rounds {
        let start = Instant::now();
        for _ in 0..calls {
            f();
        }
        best = best.min(start.elapsed().as_secs_f64() * 1e9 / calls as f64);
    }
    best
}

/// Measured peak throughputs (operations per ns) of this processor at the instruction set this
/// crate is compiled for.
#[derive(Clone, Copy, Debug)]
pub struct Peaks {
    /// Additions.
    pub add: f64,
    /// Multiplications.
    pub mul: f64,
    /// Additions and multiplications interleaved 1:1 (both counted).
    pub add_mul: f64,
    /// Divisions.
    pub div: f64,
    /// `sin_cos` calls.
    pub sin_cos: f64,
    /// Fused multiply-adds (each one operation), where the instruction set has them.
    pub fma: Option<f64>,
}

#[inline(never)]
fn adds<const L: usize>(acc: &mut [f64; L], c: f64) {
    for _ in 0..REPEATS {
        for a in acc.iter_mut() {
            *a += c;
        }
    }
}

#[inline(never)]
fn muls<const L: usize>(acc: &mut [f64; L], c: f64) {
    for _ in 0..REPEATS {
        for a in acc.iter_mut() {
            *a *= c;
        }
    }
}

#[inline(never)]
fn adds_and_muls<const L: usize>(sum: &mut [f64; L], product: &mut [f64; L], c: f64) {
    for _ in 0..REPEATS {
        for (s, p) in sum.iter_mut().zip(product.iter_mut()) {
            *s += c;
            *p *= c;
        }
    }
}

#[inline(never)]
fn divs<const L: usize>(acc: &mut [f64; L], c: f64) {
    // x ← c / x alternates between two finite values: the chain never overflows.
    for _ in 0..REPEATS {
        for a in acc.iter_mut() {
            *a = c / *a;
        }
    }
}

#[cfg(target_feature = "fma")]
#[inline(never)]
fn fmas<const L: usize>(acc: &mut [f64; L], b: f64, c: f64) {
    for _ in 0..REPEATS {
        for a in acc.iter_mut() {
            *a = a.mul_add(b, c);
        }
    }
}

/// The highest rate (operations per ns) of a microbenchmark over 8, 16, 24 and 32 independent
/// chains: enough of them to hide the latency, few enough to stay in registers, whichever the
/// vector width (`run(lanes)` runs one call and returns its operation count).
fn best_rate(mut run: impl FnMut(usize) -> f64) -> f64 {
    [8, 16, 24, LANES]
        .into_iter()
        .map(|lanes| {
            let mut ops = 0.0;
            let ns = fastest_ns(100, 1, || ops = run(lanes));
            ops / ns
        })
        .fold(0.0, f64::max)
}

/// Runs `$f::<L>` on fresh accumulators for the `lanes` given at run time, returning its
/// operation count (`$per` per chain and repeat).
macro_rules! with_lanes {
    ($lanes:expr, $per:expr, |$acc:ident, $other:ident| $call:expr) => {{
        fn run<const L: usize>() -> f64 {
            let (mut $acc, mut $other) = ([1.0; L], [1.0; L]);
            $call;
            black_box((&$acc, &$other));
            ($per * L * REPEATS) as f64
        }
        match $lanes {
            8 => run::<8>(),
            16 => run::<16>(),
            24 => run::<24>(),
            _ => run::<LANES>(),
        }
    }};
}

/// `Real::sin_cos`, the one the generated kernels call (the libm crate's in f64 since
/// 2026-12-07; the platform's before).
#[inline(never)]
fn sin_coses(angles: &[f64; LANES], out: &mut [(f64, f64); LANES]) {
    for (x, out) in angles.iter().zip(out) {
        *out = mbd::Real::sin_cos(*x);
    }
}

impl Peaks {
    /// Measures them: for each microbenchmark the fastest of 100 rounds at each number of
    /// chains, the best of those (about 0.5 s in all).
    pub fn measure() -> Self {
        // A factor near 1 and a small increment keep every chain finite and normal.
        const C: f64 = 1.0 + 1e-9;
        const SMALL: f64 = 1e-12;
        let add = best_rate(|lanes| with_lanes!(lanes, 1, |acc, _other| adds(black_box(&mut acc), black_box(SMALL))));
        let mul = best_rate(|lanes| with_lanes!(lanes, 1, |acc, _other| muls(black_box(&mut acc), black_box(C))));
        let add_mul =
            best_rate(|lanes| with_lanes!(lanes, 2, |acc, other| adds_and_muls(black_box(&mut acc), black_box(&mut other), black_box(C))));
        let div = best_rate(|lanes| with_lanes!(lanes, 1, |acc, _other| divs(black_box(&mut acc), black_box(C))));
        #[cfg(target_feature = "fma")]
        let fma = Some(best_rate(|lanes| with_lanes!(lanes, 1, |acc, _other| fmas(black_box(&mut acc), black_box(C), black_box(SMALL)))));
        #[cfg(not(target_feature = "fma"))]
        let fma = None;
        // Angles within ±π/4, which the library reduces no further: its fastest path, so a
        // peak (on 0.1 … 11.6 rad it took 11 ns a call here, on ±0.8 rad 6.6 ns).
        let angles: [f64; LANES] = core::array::from_fn(|i| -0.775 + 0.05 * i as f64);
        let mut out = [(0.0, 0.0); LANES];
        let sin_cos = LANES as f64 / fastest_ns(200, 100, || sin_coses(black_box(&angles), black_box(&mut out)));
        Peaks { add, mul, add_mul, div, sin_cos, fma }
    }

    /// The time (ns) a kernel with these operation counts takes at the peaks (module docs).
    pub fn floor_ns(&self, o: &mbd::OpCount) -> f64 {
        let (a, m) = (o.add as f64, o.mul as f64);
        (a / self.add).max(m / self.mul).max((a + m) / self.add_mul) + o.div as f64 / self.div + o.call as f64 / self.sin_cos
    }
}

impl core::fmt::Display for Peaks {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "add {:.2}/ns, mul {:.2}/ns, add and mul together {:.2}/ns, div {:.2}/ns, sin_cos {:.3}/ns, ",
            self.add, self.mul, self.add_mul, self.div, self.sin_cos
        )?;
        match self.fma {
            Some(fma) => write!(f, "FMA {fma:.2}/ns"),
            None => write!(f, "no FMA instruction at this instruction set"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Peaks;

    /// The floor takes the slower of the add and multiply pipes (or of both together), and adds
    /// divisions and calls: hand-computed for made-up peaks.
    #[test]
    fn the_floor_of_a_mix() {
        let p = Peaks { add: 4.0, mul: 2.0, add_mul: 5.0, div: 0.5, sin_cos: 0.1, fma: None };
        let ops = |add, mul, div, call| mbd::OpCount { function: "k", add, mul, div, call };
        // Multiplications bound: 40 / 2 = 20 ns (adds 40 / 4 = 10, both 80 / 5 = 16).
        assert_eq!(p.floor_ns(&ops(40, 40, 0, 0)), 20.0);
        // Both together bound: 80 / 5 = 16 ns (adds 60 / 4 = 15, muls 20 / 2 = 10).
        assert_eq!(p.floor_ns(&ops(60, 20, 0, 0)), 16.0);
        // Plus 2 divisions (4 ns) and one call (10 ns).
        assert_eq!(p.floor_ns(&ops(60, 20, 2, 1)), 30.0);
    }
}
