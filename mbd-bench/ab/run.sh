#!/usr/bin/env bash
# A/B timing of mbd's planar generated code at two commits, interleaved in one process; three
# builds of each commit, so that code-layout luck averages out and shows its size (guide/performance.md).
# Every setting is an environment variable:
#   AB_REPO      the mbd git repository          (default: the repository holding this script, else /work/main)
#   AB_BASE      the earlier commit, side "base" (default: 810f85d, the last commit before the seam)
#   AB_HEAD      the later commit, side "head"   (default: HEAD of AB_REPO)
#   AB_PROCESSES driver processes, run one after another (default: 6); each has its own
#                address-space layout, which moves a ratio by a few per cent at times
#   AB_ROUNDS    rounds in each process          (default: 70)
#   AB_SAMPLE_MS milliseconds per sample         (default: 4)
#   AB_FILTER    only calls whose name contains this (default: all)
#   AB_OUT       folder for the results          (default: results/ beside this script)
#   CARGO_TARGET_DIR                             (default: target/ beside this script)
#   CARGO_BUILD_JOBS                             (default: 1)
# Snapshots go to .snap/{base,head}{1,2,3} beside this script, by git archive, so the repository's
# work tree and worktree list are untouched. Each copy's packages get the version suffix
# "-ab<side><copy>" so that all six mbd's can sit in one Cargo dependency graph; the copies then
# differ only in names, which is enough to move their code around in the binary.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="${AB_REPO:-$(git -C "$here" rev-parse --show-toplevel 2>/dev/null || echo /work/main)}"
base="${AB_BASE:-810f85d}"
head="${AB_HEAD:-HEAD}"
rounds="${AB_ROUNDS:-70}"
processes="${AB_PROCESSES:-6}"
sample_ms="${AB_SAMPLE_MS:-4}"
out="${AB_OUT:-$here/results}"
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$here/target}"
export CARGO_BUILD_JOBS="${CARGO_BUILD_JOBS:-1}"

base_rev="$(git -C "$repo" rev-parse --verify "$base^{commit}")"
head_rev="$(git -C "$repo" rev-parse --verify "$head^{commit}")"

# snapshot NAME REV: .snap/NAME holds REV with its versions suffixed -abNAME; prints the cargo
# feature that selects that snapshot's API: `workspace` if its runtime has src/workspace.rs
# (e12cd84 and later: solvers take the caller's work space), else `nv` if it has const NV.
snapshot() {
    local dir="$here/.snap/$1" v
    if [ "$(cat "$dir/.rev" 2>/dev/null)" != "$2" ]; then
        rm -rf "$dir" && mkdir -p "$dir"
        git -C "$repo" archive "$2" | tar -x -m -C "$dir"  # -m: files dated now, so cargo sees them as changed
        v="$(sed -n '/^\[workspace.package\]/,/^\[/s/^version = "\([^"]*\)"/\1/p' "$dir/Cargo.toml")"
        find "$dir" -name Cargo.toml -not -path '*/tests/*' -print0 | xargs -0 sed -i -E \
            -e "/^\[workspace.package\]/,/^\[/s/^version = \"$v\"/version = \"$v-ab$1\"/" \
            -e "/^mbd[-a-z]* = \{.*path/s/version = \"$v\"/version = \"$v-ab$1\"/"
        echo "$2" > "$dir/.rev"
    fi
    local ws="$dir/mbd-runtime/src/workspace.rs"
    [ -f "$ws" ] || ws="$dir/mbd-runtime/src/model/workspace.rs"  # 2026-11-29 and later
    if grep -qs "const NS: usize" "$ws"; then echo "--features ab-$1/storage"
    elif [ -f "$ws" ]; then echo "--features ab-$1/workspace"
    elif grep -rqs "const NV: usize" "$dir/mbd-runtime/src"; then echo "--features ab-$1/nv"; fi
}
features=""
for i in 1 2 3; do
    features+=" $(snapshot "base$i" "$base_rev") $(snapshot "head$i" "$head_rev")"
done
# Dependency versions as the head pins them, on the first run.
[ -f "$here/Cargo.lock" ] || cp "$here/.snap/head1/Cargo.lock" "$here/Cargo.lock" 2>/dev/null || true

mkdir -p "$out"
stamp="$(date -u +%Y%m%dT%H%M%SZ)"
log="$out/$stamp.md"
{
    echo "# mbd A/B $stamp"
    echo
    echo "- base: $base = $base_rev"
    echo "- head: $head = $head_rev"
    echo "- machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(uname -sr)"
    echo "- $(rustc --version), profile release (opt-level 3, codegen-units 16, no LTO, debug off: the project's bench profile)"
    echo "- load before the build: $(uptime)"
} | tee "$log"

( cd "$here" && cargo build --release -p ab-driver $features )
echo "- load before the rounds: $(uptime)" | tee -a "$log"
mkdir -p "$out/$stamp"
csvs=()
for p in $(seq 1 "$processes"); do
    "$CARGO_TARGET_DIR/release/ab-driver" --rounds "$rounds" --sample-ms "$sample_ms" --csv "$out/$stamp/p$p.csv" \
        ${AB_FILTER:+--filter "$AB_FILTER"} > "$out/$stamp/p$p.md"
    csvs+=("$out/$stamp/p$p.csv")
    echo "process $p/$processes done: $(uptime)"
done
# Operation counts and the cross-check from the first process, then the table over all.
sed -n '/^## Operation counts/,/^## Times and ratios/{/^## Times and ratios/!p}' "$out/$stamp/p1.md" | tee -a "$log"
"$CARGO_TARGET_DIR/release/ab-driver" --summarize "${csvs[@]}" | tee -a "$log"
echo "- load after: $(uptime)" | tee -a "$log"
echo "results: $log; each process's output and samples in $out/$stamp/"
