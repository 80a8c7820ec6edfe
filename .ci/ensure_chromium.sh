#!/usr/bin/env bash
# Installs headless Chromium from Debian's packages for tests/animation.rs (idempotent) and
# prints the path of its binary.
set -euo pipefail
find_chromium() {
    for name in chromium chromium-browser; do
        if command -v "$name" >/dev/null 2>&1; then
            command -v "$name"
            return 0
        fi
    done
    return 1
}
if ! find_chromium >/dev/null; then
    if [ "$(id -u)" = 0 ]; then
        apt_get=(apt-get)
    else
        apt_get=(sudo -n apt-get)
    fi
    "${apt_get[@]}" update -qq >&2
    DEBIAN_FRONTEND=noninteractive "${apt_get[@]}" install -y -qq --no-install-recommends chromium fonts-dejavu-core >&2
fi
find_chromium
