# Helpers for the system tests: real rpsd processes on loopback or in network namespaces.
# Every test runs in its own temporary folder and kills what it started, whatever happens.
set -euo pipefail

RPSD=${RPSD:?path to the rpsd binary}
SRC=${RPSD_SOURCE_DIR:?source tree}
WORK=$(mktemp -d /tmp/rpsd-system.XXXXXX)
PIDS=()
cleanup() {
  for p in "${PIDS[@]:-}"; do [ -n "$p" ] && kill "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
  if [ -n "${NETNS_CLEANUP:-}" ]; then eval "$NETNS_CLEANUP"; fi
  rm -rf "$WORK"
}
trap cleanup EXIT

fail() { echo "FAIL: $*" >&2; exit 1; }
# A domain per test run keeps parallel tests apart on one machine.
DOMAIN=$(( 1 + $$ % 200 ))

# json FILE EXPR: evaluate a Python expression on the parsed JSON as `j`.
json() { python3 -c "import json,sys; j=json.load(open('$1')); print($2)"; }

# start_node SITE MODE [extra --set ...]: a bridge pier node in the background.
start_node() {
  local site=$1 mode=$2; shift 2
  $RPSD servo-node "$SRC/scenarios/nodes/bridge-pier-site-$site.yaml" --set node.mode=$mode \
    --set dds.domain_id=$DOMAIN --summary "$WORK/node$site.json" "$@" > "$WORK/node$site.log" 2>&1 &
  PIDS+=($!)
  eval "NODE${site}_PID=$!"
}

# The bridge scenario with the given extra --set options.
run_bridge() {
  local out=$1; shift
  $RPSD run "$SRC/scenarios/two-site-bridge.yaml" --out "$out" --set transport.domain_id=$DOMAIN "$@"
}
