#!/usr/bin/env bash
# Adds the Cortex-M4F target that tests/embedded.rs builds for (idempotent).
set -euo pipefail
rustup target add thumbv7em-none-eabihf >&2
