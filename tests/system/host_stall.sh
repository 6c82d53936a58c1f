#!/usr/bin/env bash
# A host that stalls every process of a real-time test for longer than the DDS liveliness
# lease (1 s), as this shared VM does at times: the coordinator and both servo nodes are
# stopped together for 1.5 s (SIGSTOP) once 1 s of the run is recorded, then continued. On waking, the
# coordinator's Cyclone finds the nodes' leases lapsed before their next sample arrives; the
# feedback is only a few periods old, so the test must go on to the end, every step recorded,
# not stop as if the nodes had died (kill_node.sh is that case).
source "$(dirname "$0")/lib.sh"
# The stall is this test's own doing: a failed check fails at once, whatever host_starved says.
fail() { echo "FAIL: $*" >&2; exit 1; }
start_node 1 real_time
start_node 2 real_time
set +e
# Not through run_bridge: $! must be rpsd itself, not a subshell running the function.
$RPSD run "$SRC/examples/scenarios/two-site-bridge.yaml" --out "$WORK/rt" --set transport.domain_id=$DOMAIN --set transport.kind=dds \
  --set clock.mode=real_time --set clock.max_feedback_age_periods=$RT_AGE > "$WORK/run.log" 2>&1 &
COORDINATOR_PID=$!
PIDS+=($COORDINATOR_PID)
# Stall once the run has begun (its first rows are written), not during discovery.
wait_for_rows "$WORK/rt/time_history.csv" 1024 $COORDINATOR_PID
kill -STOP $COORDINATOR_PID $NODE1_PID $NODE2_PID
sleep 1.5
kill -CONT $NODE1_PID $NODE2_PID $COORDINATOR_PID
wait $COORDINATOR_PID
code=$?
set -e
cat "$WORK/run.log"
[ $code = 0 ] || fail "exit code $code, expected 0: the stall stopped the test"
every_step_recorded "$WORK/rt"
[ "$(json "$WORK/rt/summary.json" "j['steps'] == j['steps_planned']")" = True ] || fail "the run did not take every planned step"
kill -TERM $NODE1_PID $NODE2_PID
wait $NODE1_PID $NODE2_PID || true
# Proof that the stall happened: the coordinator lost at least a second of deadlines. (Its
# wake-up lateness shows the stall only when the stop caught it asleep; stopped mid-step, its
# pacer counts the lost deadlines as skipped. The nodes' lateness shows it only when no
# command was waiting as they woke.)
skipped=$(json "$WORK/rt/summary.json" "j['timing']['skipped_deadlines']")
[ "$skipped" -ge 1024 ] || fail "the coordinator skipped only $skipped deadlines: no stall happened"
echo "PASS: a 1.5 s stall of all three processes (the coordinator skipped $skipped deadlines);" \
  "the test went on, every step recorded;" \
  "oldest feedback $(column "$WORK/rt" feedback_age_periods 'int(max(v))') periods;" \
  "node holds $(json "$WORK/node1.json" "j['holds']") and $(json "$WORK/node2.json" "j['holds']")"
