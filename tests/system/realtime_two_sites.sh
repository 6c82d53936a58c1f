#!/usr/bin/env bash
# Coordinator and two servo nodes as separate processes on loopback, all in real time at
# 1024 Hz: the distributed bridge test runs to completion, records every step, and differs
# from the single-process run only as much as the transport's measured delays explain
# (transport_effect_bound.py: late feedback and node ticks off the command timeline).
source "$(dirname "$0")/lib.sh"
start_node 1 real_time
start_node 2 real_time
set +e
# This test is about the result, not about stall detection (kill_node.sh, netns_partition.sh):
# this VM stalls every thread for several milliseconds now and then (cyclictest: worst wake-up
# 0.2-0.4 s), which would otherwise stop one run in five. A stall's stale feedback is counted
# in the bound below like any late step.
run_bridge "$WORK/dds" --set transport.kind=dds --set clock.mode=real_time --set clock.max_feedback_age_periods=100 > "$WORK/run.log" 2>&1
code=$?
set -e
cat "$WORK/run.log"
# The nodes write their summaries when they stop.
kill -TERM $NODE1_PID $NODE2_PID
wait $NODE1_PID $NODE2_PID || true
[ $code = 0 ] || { cat "$WORK"/node*.log; fail "exit code $code"; }
run_bridge "$WORK/local" > /dev/null
every_step_recorded "$WORK/dds"
[ "$(json "$WORK/dds/summary.json" "j['steps'] == j['steps_planned']")" = True ] || fail "the run did not take every planned step"
# Run as root, every process kept the CPUs out of slow idle states while it ran.
if [ "$(id -u)" = 0 ]; then
  [ "$(json "$WORK/dds/summary.json" "j['timing']['cpus_kept_awake']")" = True ] || fail "the coordinator did not keep the CPUs awake"
  for n in 1 2; do
    [ "$(json "$WORK/node$n.json" "j['cpus_kept_awake']")" = True ] || fail "node $n did not keep the CPUs awake"
  done
fi
# The rig's response delay (Eq. 12) is the time constant of the plant's lag.
tau=$($RPSD analyze "$SRC/examples/servo/paper-mts-244.yaml" --json | python3 -c "import json,sys; print(json.load(sys.stdin)['response_delay_ms'] / 1e3)")
python3 "$(dirname "$0")/transport_effect_bound.py" "$WORK/local" "$WORK/dds" "$tau" "$WORK/node1.json" "$WORK/node2.json"
echo "PASS: real time over DDS; round trip p50/p99 $(json "$WORK/dds/summary.json" \
  "', '.join('%.3f/%.3f ms' % (1e3*s['round_trip']['p50_s'], 1e3*s['round_trip']['p99_s']) for s in j['timing']['sites'])")"
