#!/usr/bin/env bash
# Fuzzes the ground-motion readers and the scenario parser with libFuzzer (clang, -fsanitize=fuzzer,address,undefined).
#   scripts/fuzz.sh [seconds-per-target]      (default 20)
# Configures a separate clang build in build-fuzz/ from fuzz/CMakeLists.txt (the default gcc
# build never needs clang), builds only the fuzz targets, seeds the corpora from the shared
# records (copied into build-fuzz/, never into the repository; whole records are cut to
# -max_len for fuzz_at2, so short valid copies are seeded too) and runs each target for the
# given time with a per-input timeout, one target per core at a time. Exits non-zero on any
# crash, hang, leak or sanitizer report; reproducers are left in build-fuzz/artifacts/.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-20}
per_input_timeout=10
build=build-fuzz
records=data/ground-motions

command -v clang++ >/dev/null || { echo "fuzz: clang++ not found (bash scripts/install-deps.sh)" >&2; exit 2; }
# Each library one translation unit (RPSD_UNITY_BUILD): its headers compiled once, not per source.
# -O1 and line tables only, as OSS-Fuzz builds: a sanitizer's report needs no more, and a
# library's unit compiles in about 40 s instead of 50 s at -O2 -g. -O0 compiled in 25 s but ran
# 2.5-6 times fewer inputs a second (docs/architecture.md).
cmake -S fuzz -B "$build" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" -DRPSD_UNITY_BUILD=ON >/dev/null
cmake --build "$build" -j 2 >/dev/null

# Seed corpora, rebuilt on every run.
seeds="$build/seeds"
rm -rf "$seeds"
mkdir -p "$seeds/at2" "$seeds/text" "$build/corpus/at2" "$build/corpus/text" "$build/artifacts"
for record in "$records"/*.AT2; do
  [ -f "$record" ] || continue
  name=$(basename "$record" .AT2)
  cp "$record" "$seeds/at2/"
  # A short valid copy (NPTS = 20, four data lines) that fits under -max_len.
  { head -n 3 "$record"
    sed -n 4p "$record" | sed -E 's/^([[:space:]]*)[0-9]+([[:space:]])/\120\2/; s/NPTS=[[:space:]]*[0-9]+/NPTS=   20/'
    sed -n 5,8p "$record"; } >"$seeds/at2/$name-short.AT2"
done
printf 'PEER NGA STRONG MOTION DATABASE RECORD\nEVENT\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=    3, DT=   .0050 SEC,\n  1.0E-03 -2.0E-03  3.0D-03\n' \
  >"$seeds/at2/west2.AT2"
printf 'Peknold\n8F10.5\nThe units are (g)\nNPTS=     9, DT= .02000 SEC\n   0.00630   0.00364   0.00099   0.00428   0.00758   0.01087   0.00682   0.00277\n  -0.00128\n' \
  >"$seeds/at2/peknold.AT2"
# Text seeds: the first byte picks the reader (see fuzz/fuzz_text_readers.cpp).
if [ -f "$records/STM090.AT2" ]; then
  # sed reads whole files: a `head` closing a pipe early would kill the script under pipefail.
  { printf '\x00'; sed -n '5,44p' "$records/STM090.AT2"; } >"$seeds/text/plain-5-per-line"
  { printf '\x03'; sed -n '5,44p' "$records/STM090.AT2" | tr -s ' ' '\n' | sed '/^$/d' |
      awk '{ printf "%.3f,%s\n", (NR - 1) * 0.02, $1 }'; } >"$seeds/text/time-acceleration.csv"
fi
{ printf '\x12'; printf '# t ns ew\n0.00 0.1 0.2\n0.01 0.3 0.4\n0.02 0.5 0.6\n'; } >"$seeds/text/table"
{ printf '\x43'; printf 't,a\n0,1\n0.5,2\n1.0,3\n'; } >"$seeds/text/csv-with-header"

# Scenario seeds: the shipped scenarios and the test scenarios.
mkdir -p "$seeds/scenario" "$build/corpus/scenario"
cp examples/scenarios/*.yaml tests/coordinator/data/*.yaml tests/hybrid_test/data/*.yaml "$seeds/scenario/"

status=0
fuzz_one() {
  local target=$1 corpus=$2 extra=("${@:3}")
  echo "fuzz: $target for ${seconds} s"
  if ! "$build/$target" -max_total_time="$seconds" -timeout="$per_input_timeout" \
      -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$build/artifacts/$target-" \
      "${extra[@]}" "$build/corpus/$corpus" "$seeds/$corpus" >"$build/$target.log" 2>&1; then
    echo "fuzz: $target FAILED (log: $build/$target.log, reproducers: $build/artifacts/)" >&2
    grep -E "ERROR|SUMMARY|runtime error|deadly signal|timeout" "$build/$target.log" | head -20 >&2 || true
    return 1
  fi
  grep -E "^stat::number_of_executed_units|^stat::peak_rss_mb|cov:" "$build/$target.log" | tail -3 |
    sed "s/^/fuzz: $target: /"  # two targets run at once: each line says whose it is
}
# One target per core at a time (a libFuzzer process uses one): each still gets its whole
# time, and the targets take half as long on two cores.
cores=$(nproc 2>/dev/null || echo 2)
running=0
finish_one() {
  wait -n || status=1
  running=$((running - 1))
}
run() {
  [ "$running" -lt "$cores" ] || finish_one
  fuzz_one "$@" &
  running=$((running + 1))
}
run fuzz_at2 at2 -dict=fuzz/at2.dict -max_len=16384
run fuzz_text_readers text
# Short inputs keep every case fast: a long matrix would only measure dense algebra.
run fuzz_scenario scenario -max_len=2048
# Datagrams from the network: valid commands, queries and replies of both versions
# (docs/udp-controller-protocol.md),
# little-endian, so the fuzzer starts past the magic, size and version checks and mutates the
# fields the decoders judge (channel count, flags, period, non-finite values).
mkdir -p "$seeds/udp" "$build/corpus/udp"
python3 - "$seeds/udp" <<'PY'
import struct, sys
out = sys.argv[1]
def command(channels, flags, sequence, period, values, version=1):
    values = list(values) + [0.0] * (8 - len(values))
    return b"RPSC" + struct.pack("<HBBQd8d", version, channels, flags, sequence, period, *values)
def reply(channels, status, sequence, displacements, forces, version=1):
    d = list(displacements) + [0.0] * (8 - len(displacements))
    f = list(forces) + [0.0] * (8 - len(forces))
    return b"RPSR" + struct.pack("<HBBQ8d8d", version, channels, status, sequence, *d, *f)
# Version 2's content before its tag: the packet, then the session's two 16-byte nonces (the
# target tags it with its test key, so the fuzzer reaches past the tag check).
session = bytes(range(32))
seeds = {
    "command-1ch": command(1, 0, 1, 1 / 1024, [0.001]),
    "command-8ch": command(8, 0, 2**40, 1 / 4096, [0.001 * c for c in range(8)]),
    "query": command(2, 1, 7, 0.0, []),
    "reply-ok": reply(1, 0, 1, [0.001], [700.8]),
    "reply-fault": reply(3, 1, 9, [0.0, 0.01, -0.01], [1.0, -2.0, 3.0]),
    "v2-command": command(2, 0, 3, 1 / 2048, [0.002, -0.002], version=2) + session,
    "v2-hello": command(1, 2, 0, 0.0, [], version=2) + bytes(16) + bytes(16),
    "v2-reply": reply(2, 0, 3, [0.002, -0.002], [10.0, -10.0], version=2) + session,
}
for name, packet in seeds.items():
    open(f"{out}/{name}", "wb").write(packet)
PY
run fuzz_udp_protocol udp -max_len=256
# Plugin site answers: OpenFresco-style lines, a refusal, CR LF, a rotation and a moment.
mkdir -p "$seeds/plugin" "$build/corpus/plugin"
printf 'OK\t0\tOPFTransaction20261126181701n7\tMDL-00-01\tx\tdisplacement\t1.2345678901E-02\tx\tforce\t-3.2E+03\n' \
  >"$seeds/plugin/reading"
printf 'ERROR\tT\tproposal refused: beyond the limit\n' >"$seeds/plugin/refusal"
printf 'OK\t1\tT\tLBCB2\tz\trotation\t+1.5e-3\tz\tmoment\t42\r\n' >"$seeds/plugin/rotation"
run fuzz_nees_plugin plugin -max_len=2048
# Commands into a node's controller: no seeds needed, every byte string is a command stream.
mkdir -p "$seeds/node" "$build/corpus/node"
printf '\x01\x00' >"$seeds/node/one-command-one-tick"
run fuzz_node_commands node -max_len=1024
# Parameter files: the first byte picks the reader (0 servo parameters, 1 node, 2 emulator,
# 3 plugin site emulator).
mkdir -p "$seeds/params" "$build/corpus/params"
{ printf '\x00'; cat examples/servo/paper-mts-244.yaml; } >"$seeds/params/servo-parameters"
for f in examples/nodes/*.yaml; do { printf '\x01'; cat "$f"; } >"$seeds/params/node-$(basename "$f")"; done
{ printf '\x03'; cat examples/nodes/plugin-site-emulator.yaml; } >"$seeds/params/plugin-site-emulator"
run fuzz_parameter_files params -max_len=4096
# A genericClient's byte stream into the site server's session: seeded with a client's setup
# (2 basic DOFs, 11-double messages) and one step (trial, force request, commit, die).
mkdir -p "$seeds/opensees" "$build/corpus/opensees"
python3 - "$seeds/opensees" <<'PY'
import struct, sys
out = sys.argv[1]
def message(*values):
    return struct.pack("<11d", *(list(values) + [0.0] * (11 - len(values))))
setup = struct.pack("<11i", 2, 2, 2, 0, 1, 0, 0, 0, 2, 0, 11)
step = message(3, 0.001, 0.002, 0, 0, 0, 0, 0.01) + message(10) + message(12) + message(5)
open(f"{out}/one-step", "wb").write(setup + step + message(99))
open(f"{out}/beyond-the-limit", "wb").write(setup + message(3, 2.0) + message(10) + message(10) + message(99))
PY
run fuzz_opensees_session opensees -max_len=4096
while [ "$running" -gt 0 ]; do finish_one; done
exit $status
