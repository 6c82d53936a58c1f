#!/usr/bin/env bash
# Installs, from Debian 12 packages only, exactly what rpsd needs to build, test and plot.
# Idempotent: packages already present are left alone; apt-get update runs only when needed.
set -euo pipefail

packages=(
  build-essential cmake              # compiler and build system
  libeigen3-dev                      # linear algebra (integrators, servo linear analysis)
  libyaml-cpp-dev                    # scenario and parameter files
  libgtest-dev libgmock-dev          # tests (GoogleTest and its matchers)
  libbenchmark-dev                   # bench/
  libcli11-dev                       # the rpsd command line
  nlohmann-json3-dev                 # summary.json and --json output
  gnuplot-nox                        # PNG plots (pngcairo terminal)
  clang libclang-rt-14-dev           # scripts/fuzz.sh: clang, libFuzzer and the sanitizer runtimes
  cyclonedds-dev cyclonedds-tools    # DDS transport (libddsc, idlc) and ddsperf for bench/
  iproute2 nftables                  # system tests: network namespaces, veth links, packet filters
  python3 python3-yaml               # system tests: checks on the results (JSON, CSV, YAML)
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
echo "install-deps: installing ${missing[*]}"
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
