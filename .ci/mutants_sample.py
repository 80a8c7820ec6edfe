#!/usr/bin/env python3
"""Mutation testing of mbd-runtime on a systematic sample, judged by the tests that use it.

    python3 .ci/mutants_sample.py 0/80      # shard 0 of 80: every 80th of cargo-mutants' list
    python3 .ci/mutants_sample.py 0/80 --retest-missed   # only the shard's mutants missed before

cargo-mutants generates the mutants (`cargo mutants -p mbd-runtime --list --diff`); this script
applies each one in a git worktree of HEAD and runs the tests that exercise the runtime. Those
live in the `mbd` package (generated code calling the runtime), which cargo-mutants 27.1 does not
run for a mutant of `mbd-runtime` here (`--test-package` and `--test-workspace` are ignored when
`-p` is given), hence this driver. The tests run are every integration test of `mbd` except the
trybuild, CasADi-oracle ones (they check the macro's output, never the runtime) plus the
runtime's own unit tests. A mutant is *caught* when a test fails or it runs past the time limit
(a mutant that loops forever), *missed* when every test passes, *unviable* when it does not build.

The full list is 2218 mutants at about 3 minutes each on 2 cores (every test binary is rebuilt,
since the generic solvers are instantiated in each), so a complete run takes days; a round-robin
shard is a systematic sample spread over every file. Results go to target/mutants-sample/.
Needs cargo-mutants (`cargo install cargo-mutants`).
"""
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
EXCLUDED_TESTS = {"ui", "oracle", "oracle_spatial"}
LIMIT_S = 900


def main():
    shard = sys.argv[1] if len(sys.argv) > 1 else "0/80"
    retest = "--retest-missed" in sys.argv[2:]
    out_dir = ROOT / "target" / "mutants-sample"
    out_dir.mkdir(parents=True, exist_ok=True)
    listing = subprocess.run(
        ["cargo", "mutants", "-p", "mbd-runtime", "--list", "--json", "--diff", "--shard", shard, "--sharding", "round-robin"],
        cwd=ROOT, check=True, capture_output=True, text=True).stdout
    mutants = json.loads(listing)
    results = out_dir / f"results-{shard.replace('/', 'of')}.tsv"
    if retest:
        missed = {line.split("\t")[2] for line in results.read_text().splitlines()[1:] if line.startswith("missed")}
        mutants = [m for m in mutants if m["name"] in missed]
        results = out_dir / f"retest-{shard.replace('/', 'of')}.tsv"
    tests = sorted(p.stem for p in (ROOT / "tests").glob("*.rs") if p.stem not in EXCLUDED_TESTS)
    command = ["cargo", "test", "-q", "-p", "mbd", "-p", "mbd-runtime", "--lib"]
    command += [f"--test={t}" for t in tests]
    tree = pathlib.Path(tempfile.mkdtemp()) / "tree"
    subprocess.run(["git", "worktree", "add", "--detach", str(tree), "HEAD"], cwd=ROOT, check=True)
    env = dict(os.environ, CARGO_PROFILE_DEV_DEBUG="0", CARGO_TARGET_DIR=str(out_dir / "target"))
    try:
        baseline = subprocess.run(command, cwd=tree, env=env, capture_output=True, text=True)
        if baseline.returncode != 0:
            sys.exit("the unmutated tree fails its tests:\n" + baseline.stdout[-4000:] + baseline.stderr[-4000:])
        with results.open("w") as f:
            f.write("outcome\tseconds\tmutant\n")
        for k, m in enumerate(mutants):
            name = m["name"]
            patch = fix_header(m["diff"], m["file"])
            subprocess.run(["patch", "-p0", "-s"], cwd=tree, input=patch, text=True, check=True)
            start = time.monotonic()
            try:
                build = subprocess.run(command + ["--no-run"], cwd=tree, env=env, capture_output=True, text=True)
                if build.returncode != 0:
                    outcome = "unviable"
                else:
                    run = subprocess.run(command, cwd=tree, env=env, capture_output=True, text=True,
                                         timeout=LIMIT_S)
                    outcome = "caught" if run.returncode != 0 else "missed"
            except subprocess.TimeoutExpired:
                outcome = "caught (time limit)"
            finally:
                subprocess.run(["patch", "-p0", "-s", "-R"], cwd=tree, input=patch, text=True, check=True)
            seconds = time.monotonic() - start
            with results.open("a") as f:
                f.write(f"{outcome}\t{seconds:.0f}\t{name}\n")
            print(f"[{k + 1}/{len(mutants)}] {outcome:<20} {name}", flush=True)
    finally:
        subprocess.run(["git", "worktree", "remove", "--force", str(tree)], cwd=ROOT)
    summarize(results)


def fix_header(diff, file):
    """cargo-mutants names the mutation on the `+++` line; patch needs the file there."""
    lines = diff.splitlines(keepends=True)
    lines[1] = f"+++ {file}\n"
    return "".join(lines)


def summarize(results):
    rows = [line.split("\t") for line in results.read_text().splitlines()[1:]]
    caught = sum(r[0].startswith("caught") for r in rows)
    missed = [r[2] for r in rows if r[0] == "missed"]
    viable = caught + len(missed)
    print(f"{caught}/{viable} viable mutants caught ({100 * caught / max(viable, 1):.0f} %); missed:")
    for m in missed:
        print("  " + m)


if __name__ == "__main__":
    main()
