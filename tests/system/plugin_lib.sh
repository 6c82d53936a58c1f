# Helpers for the plugin site tests: the shipped plugin site emulator, its node and the
# lock-step scenario (examples/), on a free loopback port and a DDS domain of this test.
source "$(dirname "$0")/lib.sh"
PLUGIN_PORT=$(python3 -c "import socket; s = socket.socket(); s.bind(('127.0.0.1', 0)); print(s.getsockname()[1])")

# wait_for_line FILE TEXT PID: returns once FILE holds TEXT; fails if PID ends or 30 s pass.
wait_for_line() {
  for _ in $(seq 300); do
    grep -q "$2" "$1" 2>/dev/null && return 0
    kill -0 "$3" 2>/dev/null || fail "$(basename "$1" .log) ended: $(cat "$1")"
    sleep 0.1
  done
  fail "$1 never said \"$2\""
}

# start_plugin_site [--set ...]: the emulator of examples/nodes/plugin-site-emulator.yaml.
start_plugin_site() {
  $RPSD plugin-site-emulator "$SRC/examples/nodes/plugin-site-emulator.yaml" --set plugin_site.port=$PLUGIN_PORT \
    --summary "$WORK/site.json" "$@" > "$WORK/site.log" 2>&1 &
  SITE_PID=$!
  PIDS+=($SITE_PID)
  wait_for_line "$WORK/site.log" "listening on tcp" $SITE_PID
}

# start_plugin_node [--set ...]: examples/nodes/plugin-site-node.yaml, once in session with the site.
start_plugin_node() {
  $RPSD servo-node "$SRC/examples/nodes/plugin-site-node.yaml" --set actuator.port=$PLUGIN_PORT \
    --set dds.domain_id=$DOMAIN --summary "$WORK/node.json" "$@" > "$WORK/node.log" 2>&1 &
  NODE_PID=$!
  PIDS+=($NODE_PID)
  wait_for_line "$WORK/node.log" "NEES plugin site" $NODE_PID
}

# run_plugin_test OUT [--set ...]: examples/scenarios/plugin-site-sdof.yaml; its exit code in RUN_EXIT.
# `timeout` only guards against a hang: a run that works ends long before.
run_plugin_test() {
  local out=$1
  shift
  RUN_EXIT=0
  timeout 300 $RPSD run "$SRC/examples/scenarios/plugin-site-sdof.yaml" --out "$out" \
    --set transport.domain_id=$DOMAIN "$@" > "$out.log" 2>&1 || RUN_EXIT=$?
}

# stop PID: SIGINT, then wait for it to write its summary and end.
stop() {
  kill -INT "$1" 2>/dev/null || true
  wait "$1" 2>/dev/null || true
}

# stopped_on_the_nodes_fault DIR: `rpsd run` into DIR stopped (exit 3) because the node
# faulted, not on silence, with every step it took recorded.
stopped_on_the_nodes_fault() {
  [ "$RUN_EXIT" = 3 ] || fail "rpsd run exited $RUN_EXIT, not 3: $(tail -3 "$1.log")"
  grep -q "the servo node reported a fault" "$1.log" || fail "no reason: $(tail -3 "$1.log")"
  [ "$(json "$1/summary.json" "j['result']")" = stopped ] || fail "summary: $(json "$1/summary.json" "j['result']")"
  [ "$(json "$1/summary.json" "j['stopped_by']['kind']")" = node_fault ] \
    || fail "stopped by $(json "$1/summary.json" "j['stopped_by']")"
  every_step_recorded "$1"
}

# the_site_failed FAILURE STAGE: the node's summary says it faulted because the site failed so.
the_site_failed() {
  local link="j['plugin_link']"
  [ "$(json "$WORK/node.json" "j['faulted']")" = True ] || fail "the node did not fault"
  [ "$(json "$WORK/node.json" "$link['failed_side']")" = site ] || fail "failed side: $(json "$WORK/node.json" "$link")"
  [ "$(json "$WORK/node.json" "$link['failure']")" = "$1" ] || fail "failure: $(json "$WORK/node.json" "$link['failure']")"
  [ "$(json "$WORK/node.json" "$link['failed_stage']")" = "$2" ] || fail "stage: $(json "$WORK/node.json" "$link['failed_stage']")"
}
