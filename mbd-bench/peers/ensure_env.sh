#!/usr/bin/env bash
# Creates (once) the peer benchmarks' pinned Python environment (MuJoCo, NumPy and Pinocchio,
# requirements.txt beside this script) and prints its interpreter's path on the last line of
# stdout. Reinstalls only when requirements.txt changes. Fails loudly: a missing python3, venv or
# pip, or a failed install, is an error, never a skip. Same scheme as tests/oracle/ensure_env.sh.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
venv="${MBD_PEERS_VENV:-$repo/target/peers-venv}"
requirements="$here/requirements.txt"
stamp="$venv/.requirements.sha256"

command -v python3 >/dev/null 2>&1 || { echo "ensure_env.sh: python3 is not installed; the peer benchmarks need Python 3" >&2; exit 1; }
want="$(sha256sum "$requirements" | cut -d' ' -f1)"
if [ ! -x "$venv/bin/python" ] || [ "$(cat "$stamp" 2>/dev/null)" != "$want" ]; then
    echo "ensure_env.sh: creating the peer benchmarks' Python environment in $venv" >&2
    rm -rf "$venv"
    python3 -m venv "$venv" >&2 || { echo "ensure_env.sh: python3 -m venv failed (install python3-venv)" >&2; exit 1; }
    "$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r "$requirements" >&2 \
        || { echo "ensure_env.sh: pip install -r $requirements failed" >&2; exit 1; }
    echo "$want" > "$stamp"
fi
"$venv/bin/python" -c "import mujoco, numpy, pinocchio" >&2 || { echo "ensure_env.sh: mujoco, numpy or pinocchio does not import in $venv" >&2; exit 1; }
echo "$venv/bin/python"
