#!/usr/bin/env bash
# Killing a servo node mid-test: the coordinator stops within 5 control periods with exit
# code 3 and a clear reason, and every step it took is in the results.
source "$(dirname "$0")/lib.sh"
start_node 1 real_time
start_node 2 real_time
( sleep 3; kill -9 $NODE2_PID ) &
set +e
run_bridge "$WORK/rt" --set transport.kind=dds --set clock.mode=real_time > "$WORK/run.log" 2>&1
code=$?
set -e
cat "$WORK/run.log"
[ $code = 3 ] || fail "exit code $code, expected 3"
grep -q "the servo node stopped answering (newest feedback 5 control periods old" "$WORK/run.log" || fail "no clear reason"
every_step_recorded "$WORK/rt"
steps=$(json "$WORK/rt/summary.json" "j['steps']")
[ "$steps" -gt 100 ] || fail "stopped after $steps steps"
[ "$(column "$WORK/rt" feedback_age_periods 'v[-4:] == [1, 2, 3, 4]')" = True ] || fail "stopped without 4 late steps before"
echo "PASS: stopped 5 periods after the node's last feedback, $steps steps recorded, exit 3"
