#!/usr/bin/env bash
# Regenerates the CasADi C of the spatial benchmark mechanisms (mbd-bench/mechanisms/) from the
# oracle's spatial rebuild of their model JSON: `bash mbd-bench/casadi/generate_spatial.sh`.
# The model JSON comes from the mechanisms' MODEL_JSON (examples/model_json.rs); CasADi from the
# oracle's pinned environment (tests/oracle/ensure_env.sh). The planar files were made the same
# way from the oracle's samples files (see src/lib.rs).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
target="${CARGO_TARGET_DIR:-$repo/target}"
python="$("$repo/tests/oracle/ensure_env.sh" | tail -n 1)"
models="$target/spatial-models"
(cd "$repo" && cargo run --quiet --release -p mbd-bench --example model_json -- "$models")
cd "$repo/tests/oracle"
"$python" -m mbd_oracle.codegen "$models/spatial_slider_crank.json" spatial_slider_crank "$here/spatial_slider_crank.c"
"$python" -m mbd_oracle.codegen "$models/spatial_chain16.json" spatial_chain16 "$here/spatial_chain16.c"
"$python" -m mbd_oracle.codegen --dynamics "$models/free_spatial_slider_crank.json" free_spatial_slider_crank "$here/free_spatial_slider_crank_dynamics.c"
"$python" -m mbd_oracle.codegen --dynamics "$models/spatial_chain16.json" spatial_chain16 "$here/spatial_chain16_dynamics.c"
