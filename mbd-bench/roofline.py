#!/usr/bin/env python3
"""The roofline of mbd's kernels as medians over several processes (issue 41, item 5).

    python3 mbd-bench/roofline.py [PROCESSES]          # default 5
    RUSTFLAGS="-C target-cpu=native" CARGO_TARGET_DIR=target/native python3 mbd-bench/roofline.py

Builds the `vs_casadi` benchmark once (release, as `cargo bench` does), then runs it PROCESSES
times, each a process of its own (its own address-space layout, which moves a kernel's time by a
few per cent at times), with a filter that skips the criterion groups, so that only the peaks and
the `roofline …` lines are printed (about 30 s a process). Prints one markdown table: per kernel
its operations, the median time over the processes with the fastest and slowest, the median
share of peak, and a mark where the slowest is more than 1.2 times the fastest (a kernel whose
time is not one figure: say which when quoting it). The peaks' own medians come first.
"""
import re
import statistics
import subprocess
import sys

ROOFLINE = re.compile(r"roofline (\S+) (.+?): (\d+) operations .*? in ([\d.]+) ns, [\d.]+/ns; at the peaks ([\d.]+) ns")
PEAK = re.compile(r"(add and mul together|add|mul|div|sin_cos|FMA) ([\d.]+)/ns")


def main():
    processes = int(sys.argv[1]) if len(sys.argv) > 1 else 5
    subprocess.run(["cargo", "bench", "-p", "mbd-bench", "--bench", "vs_casadi", "--no-run"], check=True)
    kernels, peaks, isa = {}, {}, ""
    for _ in range(processes):
        out = subprocess.run(
            ["cargo", "bench", "-q", "-p", "mbd-bench", "--bench", "vs_casadi", "--", "no criterion group"],
            check=True, capture_output=True, text=True).stdout
        for line in out.splitlines():
            if line.startswith("instruction set"):
                isa = line
            elif line.startswith("peaks"):
                for name, rate in PEAK.findall(line.split(": ", 1)[1]):
                    peaks.setdefault(name, []).append(float(rate))
            elif (m := ROOFLINE.match(line)):
                key = (m.group(1), m.group(2))
                k = kernels.setdefault(key, {"ops": int(m.group(3)), "time": [], "floor": []})
                k["time"].append(float(m.group(4)))
                k["floor"].append(float(m.group(5)))
    print(f"{isa}; {processes} processes")
    print("peaks (medians): " + ", ".join(f"{n} {statistics.median(v):.3g}/ns" for n, v in peaks.items()))
    print()
    print("| mechanism | kernel | operations | median | fastest – slowest | share of peak (median) |")
    print("|---|---|---|---|---|---|")
    for (mechanism, kernel), k in kernels.items():
        t, lo, hi = statistics.median(k["time"]), min(k["time"]), max(k["time"])
        share = 100 * statistics.median(f / x for f, x in zip(k["floor"], k["time"]))
        mark = " (spread)" if hi > 1.2 * lo else ""
        print(f"| {mechanism} | {kernel} | {k['ops']} | {t:.1f} ns | {lo:.1f} – {hi:.1f} ns{mark} | {share:.0f} % |")


if __name__ == "__main__":
    main()
