#!/usr/bin/env bash
# Killing a servo node mid-test: the coordinator stops once the node's feedback is RT_AGE + 1
# control periods old (lib.sh), with exit code 3 and a clear reason, and every step it took is
# in the results.
source "$(dirname "$0")/lib.sh"
start_node 1 real_time
start_node 2 real_time
( sleep 3; kill -9 $NODE2_PID ) &
set +e
run_bridge "$WORK/rt" --set transport.kind=dds --set clock.mode=real_time --set clock.max_feedback_age_periods=$RT_AGE > "$WORK/run.log" 2>&1
code=$?
set -e
cat "$WORK/run.log"
[ $code = 3 ] || fail "exit code $code, expected 3"
stopped_on_silence "$WORK/rt" "$WORK/run.log"
every_step_recorded "$WORK/rt"
steps=$(json "$WORK/rt/summary.json" "j['steps']")
[ "$steps" -gt 500 ] || fail "stopped after $steps steps"
echo "PASS: stopped $((RT_AGE + 1)) periods after the node's last feedback, $steps steps recorded, exit 3"
