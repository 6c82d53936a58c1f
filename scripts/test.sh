#!/usr/bin/env bash
# The README's test command: installs what is missing (Debian packages; the browser tests'
# driver from npm, pinned by its package-lock.json), builds with warnings as errors, runs every
# test. Extra arguments go to cmake's configure step (scripts/build.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
(cd tests/monitor/browser && npm ci --no-audit --no-fund --loglevel=error)
bash scripts/build.sh "$@"
cd build
ctest --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" --timeout 900
