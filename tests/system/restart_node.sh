#!/usr/bin/env bash
# Fault: a servo node is killed (SIGKILL) mid-test and started again; real time at 1024 Hz on
# loopback. Three parts.
# 1. Restarted 0.3 s later: site 2 goes silent, so the test stops RT_AGE + 1 control periods
#    (lib.sh; 99 ms) after its last feedback with exit code 3 and the reason; every step taken
#    is recorded. A test does not resume: the restarted node starts at its
#    initial position and waits; it is sent no command (commands are volatile: a node that
#    joins gets no earlier command from DDS, and the stopped coordinator sends no new one).
# 2. Restarted at once, with a coordinator that tolerates feedback up to 1000 periods
#    (about 1 s) old: the coordinator carries on with site 2's last measurement while the
#    node restarts, so the restarted node is sent live commands of a test it did not see
#    begin (steps near 1000, where the specimen is displaced). It drops every one ("joined
#    mid-test") and its actuator stays at its initial position; the coordinator stops with
#    exit 3 once site 2's feedback is 1001 periods old. Before the node refused such a test,
#    it took the test over from its own initial position and the test ran on to exit 0.
# 3. Killed and started again before the coordinator starts: the test completes, every step
#    recorded, the restarted node followed every command and dropped none.
source "$(dirname "$0")/lib.sh"
start_node 1 real_time
start_node 2 real_time
$RPSD run "$SRC/examples/scenarios/two-site-bridge.yaml" --out "$WORK/rt" --set transport.domain_id=$DOMAIN \
  --set transport.kind=dds --set clock.mode=real_time --set clock.max_feedback_age_periods=$RT_AGE > "$WORK/run.log" 2>&1 &
coordinator=$!
PIDS+=($coordinator)
wait_for_rows "$WORK/rt/time_history.csv" 1024 $coordinator
kill -9 $NODE2_PID
wait $NODE2_PID 2>/dev/null || true
sleep 0.3
mv "$WORK/node2.log" "$WORK/node2-killed.log"
start_node 2 real_time
set +e
wait $coordinator
code=$?
set -e
sleep 0.5
kill -TERM $NODE1_PID $NODE2_PID
wait $NODE1_PID $NODE2_PID || true
cat "$WORK/run.log"
[ $code = 3 ] || fail "exit code $code, expected 3"
stopped_on_silence "$WORK/rt" "$WORK/run.log"
every_step_recorded "$WORK/rt"
n2="$WORK/node2.json"
[ "$(json "$n2" "j['commands_accepted'], j['commands_applied'], j['first_command_tick'], j['holds'], j['faulted']")" = "0 0 -1 0 False" ] \
  || { cat "$n2"; fail "the restarted node took a command"; }
[ "$(json "$n2" "sum(j['commands_dropped'].values())")" = 0 ] || { cat "$n2"; fail "the restarted node was sent commands"; }
[ "$(json "$n2" "j['ticks'] > 0")" = True ] || fail "the restarted node did not run"
echo "part 1: exit 3 after $(json "$WORK/rt/summary.json" "j['steps']") steps; the restarted node ran" \
  "$(json "$n2" "j['ticks']") ticks and was sent no command"

# Part 2: the coordinator tolerates site 2's silence while the node restarts.
start_node 1 real_time
start_node 2 real_time
$RPSD run "$SRC/examples/scenarios/two-site-bridge.yaml" --out "$WORK/tolerant" --set transport.domain_id=$DOMAIN \
  --set transport.kind=dds --set clock.mode=real_time --set clock.max_feedback_age_periods=1000 \
  --set ground_motion.trim.end_s=4 > "$WORK/run-tolerant.log" 2>&1 &
coordinator=$!
PIDS+=($coordinator)
wait_for_rows "$WORK/tolerant/time_history.csv" 1024 $coordinator
kill -9 $NODE2_PID
wait $NODE2_PID 2>/dev/null || true
start_node 2 real_time
set +e
wait $coordinator
code=$?
set -e
kill -TERM $NODE1_PID $NODE2_PID
wait $NODE1_PID $NODE2_PID || true
cat "$WORK/run-tolerant.log"
[ $code = 3 ] || fail "part 2: exit code $code, expected 3"
grep -q "the servo node stopped answering (newest feedback 1001 control periods old" "$WORK/run-tolerant.log" || fail "part 2: no clear reason"
every_step_recorded "$WORK/tolerant"
[ "$(json "$n2" "j['commands_accepted'], j['commands_applied'], j['holds'], j['faulted']")" = "0 0 0 False" ] \
  || { cat "$n2"; fail "part 2: the restarted node took a command"; }
refused=$(json "$n2" "j['commands_dropped']['joined mid-test']")
[ "$refused" -gt 0 ] && [ "$(json "$n2" "sum(j['commands_dropped'].values())")" = "$refused" ] \
  || { cat "$n2"; fail "part 2: the restarted node was sent no command of the running test"; }
echo "part 2: the restarted node refused $refused commands of the running test; exit 3 after" \
  "$(json "$WORK/tolerant/summary.json" "j['steps']") steps"

# Part 3: killed and restarted before the test starts (the first 3 s of the record).
start_node 1 real_time
start_node 2 real_time
sleep 0.5
kill -9 $NODE2_PID
wait $NODE2_PID 2>/dev/null || true
start_node 2 real_time
set +e
run_bridge "$WORK/rt2" --set transport.kind=dds --set clock.mode=real_time --set clock.max_feedback_age_periods=$RT_AGE \
  --set ground_motion.trim.end_s=3 > "$WORK/run2.log" 2>&1
code=$?
set -e
kill -TERM $NODE1_PID $NODE2_PID
wait $NODE1_PID $NODE2_PID || true
cat "$WORK/run2.log"
[ $code = 0 ] || fail "part 3: exit code $code"
every_step_recorded "$WORK/rt2"
steps=$(json "$WORK/rt2/summary.json" "j['steps']")
[ "$steps" = "$(json "$WORK/rt2/summary.json" "j['steps_planned']")" ] || fail "part 3: $steps steps"
# Holds: the one after the last command, and any the host's delays explain (lib.sh).
[ "$(json "$n2" "j['last_command_step'] == $steps - 1 and sum(j['commands_dropped'].values()) == 0 \
  and 1 <= j['holds'] <= 1 + $(hold_reasons "$WORK/rt2")")" = True ] || { cat "$n2"; fail "part 3: the restarted node did not follow the test"; }
echo "PASS: a node restarted mid-test takes no command of the test (exit 3 either way); one restarted" \
  "before the test serves all $steps steps"
