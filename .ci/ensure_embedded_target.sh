#!/usr/bin/env bash
# Adds the Cortex-M4F target that mbd-builds/tests/builds/main.rs builds for (idempotent).
set -euo pipefail
rustup target add thumbv7em-none-eabihf >&2
