//! Times every call of `side/lib.rs` in six builds — three of the base commit, three of the head —
//! interleaved, and prints per call the time of each side, the median, quartiles and a 95 %
//! interval of the per-round ratio head / base, and how far the three builds of one commit differ.
//!
//! The three builds of a commit are the same source under different crate names, which moves
//! their code to other addresses: identical code has been seen to differ by up to 7 % between two
//! such builds here (alignment of loops and calls), so one build per side can show a "regression"
//! that is only layout. Each side's time in a round is the geometric mean of its three builds.
//!
//! One round times every call once in each build, in a random order of calls and a random order
//! of the six builds within each call; a sample is `iters` back-to-back calls (`iters` calibrated
//! once, on base1, to about `--sample-ms`, then the same for all). Drift of the machine slower
//! than a round's six samples of one call cancels in the per-round ratio; the median over rounds
//! discards the rounds a neighbour's burst hit.
//!
//! Usage: `ab-driver [--rounds N] [--sample-ms MS] [--filter TEXT] [--csv PATH] [--seed N]`, or
//! `ab-driver --summarize RUN.csv…` for one table over several runs. Each process gets its own
//! address-space layout (ASLR), which moves stack and heap alignment: between processes the same
//! binary's ratios have been seen to move by a few per cent, so run several and summarize.
use std::io::Write;
use std::time::Instant;

struct Args {
    rounds: usize,
    sample_ms: f64,
    filter: Option<String>,
    csv: Option<String>,
    seed: u64,
}

fn parse_args() -> Args {
    let mut a = Args { rounds: 100, sample_ms: 5.0, filter: None, csv: None, seed: 0 };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let mut value = || it.next().unwrap_or_else(|| panic!("{flag} needs a value"));
        match flag.as_str() {
            "--rounds" => a.rounds = value().parse().expect("--rounds N"),
            "--sample-ms" => a.sample_ms = value().parse().expect("--sample-ms MS"),
            "--filter" => a.filter = Some(value()),
            "--csv" => a.csv = Some(value()),
            "--seed" => a.seed = value().parse().expect("--seed N"),
            other => panic!("unknown argument {other}; see the doc comment of driver/src/main.rs"),
        }
    }
    if a.seed == 0 {
        a.seed = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).unwrap().as_nanos() as u64;
    }
    a
}

/// splitmix64: enough randomness to shuffle an order, with no dependency.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn shuffle<T>(&mut self, v: &mut [T]) {
        for i in (1..v.len()).rev() {
            v.swap(i, self.below(i + 1));
        }
    }
}

/// A uniform interface over both sides' `Case`, which are different types.
struct Side {
    names: Vec<String>,
    run: Vec<Box<dyn FnMut(u64)>>,
    output: Vec<Box<dyn FnMut() -> Vec<f64>>>,
}

macro_rules! side {
    ($krate:ident) => {{
        let cases = $krate::cases();
        let mut s = Side { names: vec![], run: vec![], output: vec![] };
        for c in cases {
            s.names.push(c.name);
            s.run.push(c.run);
            s.output.push(c.output);
        }
        s
    }};
}

macro_rules! ops {
    ($krate:ident) => {
        $krate::op_counts()
            .into_iter()
            .map(|o| (format!("{}::{}", o.mechanism, o.function), [o.add, o.mul, o.div, o.call]))
            .collect::<Vec<_>>()
    };
}

/// Nanoseconds per call over one sample of `iters` calls.
fn sample(run: &mut dyn FnMut(u64), iters: u64) -> f64 {
    let start = Instant::now();
    run(iters);
    start.elapsed().as_nanos() as f64 / iters as f64
}

/// The `p`-quantile of sorted data, linearly interpolated.
fn quantile(sorted: &[f64], p: f64) -> f64 {
    let x = p * (sorted.len() - 1) as f64;
    let (i, f) = (x.floor() as usize, x.fract());
    if i + 1 < sorted.len() {
        sorted[i] * (1.0 - f) + sorted[i + 1] * f
    } else {
        sorted[i]
    }
}

/// A distribution-free 95 % interval of the median: the order statistics at n/2 ∓ 0.98 √n.
fn median_interval(sorted: &[f64]) -> (f64, f64) {
    let n = sorted.len() as f64;
    let half = 0.98 * n.sqrt();
    let lo = ((n / 2.0 - half).floor().max(0.0)) as usize;
    let hi = ((n / 2.0 + half).ceil() as usize).min(sorted.len() - 1);
    (sorted[lo], sorted[hi])
}

fn fmt_ns(ns: f64) -> String {
    if ns >= 1e6 {
        format!("{:.3} ms", ns / 1e6)
    } else if ns >= 1e3 {
        format!("{:.3} µs", ns / 1e3)
    } else {
        format!("{:.1} ns", ns)
    }
}

const LABELS: [&str; 6] = ["base1", "base2", "base3", "head1", "head2", "head3"];
const BASE: [usize; 3] = [0, 1, 2];
const HEAD: [usize; 3] = [3, 4, 5];

fn geomean(x: impl Iterator<Item = f64>) -> f64 {
    let (mut s, mut n) = (0.0, 0.0);
    for v in x {
        s += v.ln();
        n += 1.0;
    }
    (s / n).exp()
}

fn sorted(mut v: Vec<f64>) -> Vec<f64> {
    v.sort_by(f64::total_cmp);
    v
}

fn main() {
    let argv: Vec<String> = std::env::args().skip(1).collect();
    if argv.first().map(String::as_str) == Some("--summarize") {
        summarize(&argv[1..]);
        return;
    }
    let args = parse_args();
    let mut sides = [side!(ab_base1), side!(ab_base2), side!(ab_base3), side!(ab_head1), side!(ab_head2), side!(ab_head3)];
    for s in &sides[1..] {
        assert_eq!(s.names, sides[0].names, "every side must define the same cases in the same order");
    }
    let names = sides[0].names.clone();
    let chosen: Vec<usize> = (0..names.len()).filter(|&i| args.filter.as_deref().map_or(true, |f| names[i].contains(f))).collect();
    println!(
        "# mbd A/B: head / base, 3 builds each, {} calls, {} rounds, ~{} ms a sample, seed {}",
        chosen.len(),
        args.rounds,
        args.sample_ms,
        args.seed
    );

    // Operation counts (the generated functions' OP_COUNTS): the differing rows only.
    let (oa, ob) = (ops!(ab_base1), ops!(ab_head1));
    let same = oa.iter().filter(|(k, c)| ob.iter().any(|(x, d)| x == k && d == c)).count();
    println!("\n## Operation counts (OP_COUNTS: add, mul, div, call)\n");
    println!("{same} of {} base functions have the same counts in the head ({} head functions). The others:\n", oa.len(), ob.len());
    println!("| function | base | head |");
    println!("|---|---|---|");
    let show = |c: Option<&[u32; 4]>| c.map_or("—".to_string(), |c| format!("{} {} {} {}", c[0], c[1], c[2], c[3]));
    for (k, c) in &oa {
        let d = ob.iter().find(|(x, _)| x == k).map(|(_, d)| d);
        if d != Some(c) {
            println!("| {k} | {} | {} |", show(Some(c)), show(d));
        }
    }
    for (k, d) in &ob {
        if !oa.iter().any(|(x, _)| x == k) {
            println!("| {k} | — | {} |", show(Some(d)));
        }
    }

    // The same numbers: each call once in each build, against base1.
    println!("\n## Cross-check: largest |x − base1| / max(1, |base1|) over everything one call writes\n");
    println!("| call | values | base2, base3 | head1, head2, head3 |");
    println!("|---|---|---|---|");
    for &i in &chosen {
        let outs: Vec<Vec<f64>> = sides.iter_mut().map(|s| (s.output[i])()).collect();
        let diff = |x: &Vec<f64>| {
            if x.len() != outs[0].len() {
                f64::NAN
            } else {
                outs[0].iter().zip(x).map(|(p, q)| (p - q).abs() / p.abs().max(1.0)).fold(0.0, f64::max)
            }
        };
        let d: Vec<String> = outs.iter().map(|x| format!("{:.1e}", diff(x))).collect();
        println!("| {} | {} | {}, {} | {}, {}, {} |", names[i], outs[0].len(), d[1], d[2], d[3], d[4], d[5]);
    }

    // Calibration on base1, then one warm-up sample in each build.
    let target_ns = args.sample_ms * 1e6;
    let mut iters = vec![1u64; names.len()];
    for &i in &chosen {
        let mut n = 1u64;
        loop {
            let ns = sample(&mut *sides[0].run[i], n) * n as f64;
            if ns >= target_ns / 4.0 || n >= 1 << 40 {
                iters[i] = ((n as f64) * target_ns / ns).ceil().max(1.0) as u64;
                break;
            }
            n *= 2;
        }
        for s in sides.iter_mut() {
            sample(&mut *s.run[i], iters[i]);
        }
    }

    // Rounds: t[side][call] is the list of ns per call, one per round.
    let mut rng = Rng(args.seed);
    let mut t = vec![vec![Vec::new(); names.len()]; 6];
    let mut csv = args.csv.as_ref().map(|p| {
        let mut f = std::io::BufWriter::new(std::fs::File::create(p).expect("create the CSV file"));
        writeln!(f, "round,call,build,position,iters,ns_per_call").unwrap();
        f
    });
    let started = Instant::now();
    for round in 0..args.rounds {
        let mut order = chosen.clone();
        rng.shuffle(&mut order);
        for &i in &order {
            let mut which = [0usize, 1, 2, 3, 4, 5];
            rng.shuffle(&mut which);
            for (pos, &s) in which.iter().enumerate() {
                let ns = sample(&mut *sides[s].run[i], iters[i]);
                t[s][i].push(ns);
                if let Some(f) = csv.as_mut() {
                    writeln!(f, "{round},\"{}\",{},{pos},{},{ns}", names[i], LABELS[s], iters[i]).unwrap();
                }
            }
        }
        if (round + 1) % 20 == 0 {
            eprintln!("round {}/{} ({:.0} s)", round + 1, args.rounds, started.elapsed().as_secs_f64());
        }
    }

    let timed: Vec<(String, [Vec<f64>; 6])> =
        chosen.iter().map(|&i| (names[i].clone(), std::array::from_fn(|s| t[s][i].clone()))).collect();
    table(&[timed]);
    println!("\n{:.0} s of rounds.", started.elapsed().as_secs_f64());
}

/// The results table from one or more processes' samples: `procs[p]` lists, per call, the ns per
/// call of each of the six builds, one entry per round.
fn table(procs: &[Vec<(String, [Vec<f64>; 6])>]) {
    let rounds: usize = procs.iter().map(|p| p.first().map_or(0, |c| c.1[0].len())).sum();
    println!("\n## Times and ratios ({} process(es), {rounds} rounds in all)\n", procs.len());
    println!("Base and head: geometric mean over the three builds of each build's median time per call.");
    println!("Ratio: per round, the geometric mean of the head builds' times over that of the base builds';");
    println!("its median over all rounds, quartiles and a distribution-free 95 % interval of the median.");
    println!("Per process: the lowest and highest of the processes' median ratios (each process has its own");
    println!("address-space layout). Per build: the median head_k / base_k ratio of each pairing. Layout:");
    println!("slowest over fastest build median of the same commit.\n");
    println!("| call | base | head | head / base | IQR | 95 % interval | per process | per build (1, 2, 3) | layout base | layout head |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for (c, (name, _)) in procs[0].iter().enumerate() {
        let pooled = |s: usize| -> Vec<f64> { procs.iter().flat_map(|p| p[c].1[s].iter().copied()).collect() };
        let med: Vec<f64> = (0..6).map(|s| quantile(&sorted(pooled(s)), 0.5)).collect();
        let ratios = |p: &(String, [Vec<f64>; 6])| -> Vec<f64> {
            (0..p.1[0].len()).map(|k| geomean(HEAD.iter().map(|&s| p.1[s][k])) / geomean(BASE.iter().map(|&s| p.1[s][k]))).collect()
        };
        let r = sorted(procs.iter().flat_map(|p| ratios(&p[c])).collect());
        let per_proc = sorted(procs.iter().map(|p| quantile(&sorted(ratios(&p[c])), 0.5)).collect());
        let per_build: Vec<String> = (0..3)
            .map(|b| {
                let pr = sorted(
                    procs
                        .iter()
                        .flat_map(|p| p[c].1[HEAD[b]].iter().zip(&p[c].1[BASE[b]]).map(|(h, a)| h / a).collect::<Vec<_>>())
                        .collect(),
                );
                format!("{:.3}", quantile(&pr, 0.5))
            })
            .collect();
        let spread = |idx: [usize; 3]| {
            let v: Vec<f64> = idx.iter().map(|&s| med[s]).collect();
            v.iter().cloned().fold(0.0, f64::max) / v.iter().cloned().fold(f64::INFINITY, f64::min)
        };
        let m = quantile(&r, 0.5);
        let (lo, hi) = median_interval(&r);
        let flag = if per_proc[0] > 1.05 {
            " **> 1.05**"
        } else if m > 1.05 {
            " (> 1.05 in some processes)"
        } else {
            ""
        };
        println!(
            "| {name} | {} | {} | {m:.3}{flag} | {:.3}–{:.3} | {lo:.3}–{hi:.3} | {:.3}–{:.3} | {} | {:.3} | {:.3} |",
            fmt_ns(geomean(BASE.iter().map(|&s| med[s]))),
            fmt_ns(geomean(HEAD.iter().map(|&s| med[s]))),
            quantile(&r, 0.25),
            quantile(&r, 0.75),
            per_proc[0],
            per_proc[per_proc.len() - 1],
            per_build.join(", "),
            spread(BASE),
            spread(HEAD)
        );
    }
}

/// Reads the CSV files of several runs (`--csv` of each) back for [`table`].
fn summarize(paths: &[String]) {
    let mut procs = Vec::new();
    for path in paths {
        let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
        let mut calls: Vec<(String, [Vec<f64>; 6])> = Vec::new();
        for line in text.lines().skip(1) {
            // round,"call",build,position,iters,ns_per_call — the call's name may hold commas.
            let mut parts = line.split('"');
            let (_, name, rest) = (parts.next(), parts.next().expect("a quoted call"), parts.next().expect("fields after the call"));
            let f: Vec<&str> = rest.trim_start_matches(',').split(',').collect();
            let build = LABELS.iter().position(|l| *l == f[0]).unwrap_or_else(|| panic!("unknown build {}", f[0]));
            let ns: f64 = f[3].parse().expect("ns_per_call");
            let c = match calls.iter().position(|(n, _)| n == name) {
                Some(c) => c,
                None => {
                    calls.push((name.to_string(), Default::default()));
                    calls.len() - 1
                }
            };
            calls[c].1[build].push(ns);
        }
        // The order of the case list (the CSV holds them in each round's random order).
        let order: Vec<String> = ab_base1::cases().into_iter().map(|c| c.name).collect();
        calls.sort_by_key(|(n, _)| order.iter().position(|o| o == n).unwrap_or(usize::MAX));
        procs.push(calls);
    }
    for p in &procs[1..] {
        assert!(p.iter().map(|c| &c.0).eq(procs[0].iter().map(|c| &c.0)), "the runs must time the same calls in the same order");
    }
    table(&procs);
}
