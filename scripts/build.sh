#!/usr/bin/env bash
# Configures and builds rpsd (Release) in ./build. Extra arguments go to cmake's configure step;
# RPSD_BUILD_TARGETS names the targets to build (default: everything, the tests included).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DRPSD_WARNINGS_AS_ERRORS=ON -DCMAKE_EXPORT_COMPILE_COMMANDS=ON "$@" >/dev/null
targets=()
for t in ${RPSD_BUILD_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build build -j "$jobs" "${targets[@]}"
