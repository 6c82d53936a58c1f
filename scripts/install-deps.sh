#!/usr/bin/env bash
# Installs, from Debian 12 packages only, what rpsd needs to build, run and test.
#   scripts/install-deps.sh          what a user needs: build, run, plot, test
#   scripts/install-deps.sh --team   also what only the team needs: clang and the fuzzing
#                                    runtimes, clang-format and clang-tidy, Google Benchmark
# Idempotent: packages already present are left alone; apt-get update runs only when needed.
set -euo pipefail

packages=(
  build-essential cmake              # compiler and build system
  libeigen3-dev                      # linear algebra (integrators, substructures, servo analysis)
  libspectra-dev                     # sparse eigen-solver: the lowest modes of large models (header only)
  libyaml-cpp-dev                    # scenario and parameter files
  libcli11-dev                       # the rpsd command line
  nlohmann-json3-dev                 # summary.json and --json output
  libssl-dev                         # SHA-256 of every input file in summary.json (OpenSSL)
  zlib1g-dev                         # rpsd host-check reads the kernel configuration (/proc/config.gz)
  gnuplot-nox                        # PNG plots (pngcairo terminal)
  cyclonedds-dev cyclonedds-tools    # DDS transport (libddsc; idlc generates the message types)
  libgtest-dev libgmock-dev          # the tests (GoogleTest and its matchers)
  iproute2 nftables                  # system tests: network namespaces, veth links, packet filters
  python3 python3-yaml               # test checks on the results (JSON, CSV, YAML)
  pkg-config                         # finds cpp-httplib (it has no CMake package)
  libcpp-httplib-dev                 # rpsd monitor's HTTP server (Server-Sent Events)
  chromium                           # the monitor's browser tests (headless)
  libhdf5-dev hdf5-tools             # results.h5 (docs/results-format.md); h5dump and h5clear
  python3-h5py python3-pytest        # results.h5 read as a user would, by the pytest tests
  python3-dev pybind11-dev           # the Python module rpsd (python/, docs/python.md)
  python3-numpy                      # its arrays; with python3-h5py and python3-yaml, what it needs to run
  python3-matplotlib                 # examples/python/figure8.py (and its test)
)
# The browser tests' driver (playwright-core, from npm by the test command) needs node >= 18 and
# npm: Debian's nodejs and npm, unless a node with its npm is installed already.
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  packages+=(nodejs npm)
fi
if [ "${1:-}" = "--team" ]; then
  packages+=(
    clang libclang-rt-14-dev         # scripts/fuzz.sh: clang, libFuzzer and the sanitizer runtimes
    clang-format clang-tidy          # scripts/lint.sh: the house style
    libbenchmark-dev                 # bench/ (Google Benchmark)
  )
elif [ $# -gt 0 ]; then
  echo "install-deps: unknown option $1 (only --team)" >&2
  exit 2
fi

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
