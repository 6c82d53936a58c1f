#!/usr/bin/env bash
# An operator's stop from `rpsd stop` ends an in-process lock-step rehearsal (the two-site bridge,
# its nodes in the coordinator's process; operator commands enabled, the return to start at
# 20 mm/s, the whole record at 2048 Hz): held first so that it cannot end on its own (the hold is
# sent as the run starts: `rpsd stop` waits for the run's listener), then stopped. `rpsd run` exits 3,
# summary.json says operator_stop with the sender, every step taken is recorded, and
# return_to_start.csv ends with every channel's target at its start position (0).
source "$(dirname "$0")/lib.sh"
TEST_ID=$(( 700 + $$ % 200 ))
op() {
  "$RPSD" stop --test-id $TEST_ID --domain $DOMAIN --dds-config "$SRC/transport/config/loopback.xml" \
    --sender "rehearsal@system-test" --timeout 20 "$@"
}
op --hold > "$WORK/hold.out" 2>&1 &
HOLD_PID=$!
PIDS+=($HOLD_PID)
run_bridge "$WORK/run" --set transport.test_id=$TEST_ID --set "ground_motion.trim={end_s: 39.9}" \
  --set clock.control_rate_hz=2048 \
  --set "operator_commands={enabled: true, return_to_start: true, return_velocity_m_per_s: 0.02}" > "$WORK/run.log" 2>&1 &
RUN_PID=$!
PIDS+=($RUN_PID)
wait $HOLD_PID || fail "hold: exit $?: $(cat "$WORK/hold.out") $(cat "$WORK/run.log")"
kill -0 $RUN_PID 2>/dev/null || fail "the run ended before the hold: $(cat "$WORK/run.log")"
op > "$WORK/stop.out" 2>&1 || fail "stop: exit $?: $(cat "$WORK/stop.out")"
grep -q "return to their start positions at 0.02 m/s" "$WORK/stop.out" || fail "the reply: $(cat "$WORK/stop.out")"
set +e
wait $RUN_PID
code=$?
set -e
[ $code -eq 3 ] || fail "the stopped rehearsal exited $code, expected 3: $(cat "$WORK/run.log")"
grep -q "^rpsd: test operator stop: the test ended in order" "$WORK/run.log" || fail "no reason printed: $(cat "$WORK/run.log")"
every_step_recorded "$WORK/run"
python3 - "$WORK/run" <<'PY' || fail "the stopped rehearsal's record is wrong"
import csv, json, sys
d = sys.argv[1]
run = json.load(open(d + "/summary.json"))
assert run["stopped_by"]["kind"] == "operator_stop", run["stopped_by"]
assert run["stopped_by"]["operator"]["sender"] == "rehearsal@system-test", run["stopped_by"]
assert run["return_to_start"]["reached_start"] is True, run["return_to_start"]
rows = list(csv.DictReader(open(d + "/return_to_start.csv")))
assert len(rows) == run["return_to_start"]["exchanges"] > 0, (len(rows), run["return_to_start"])
targets = [k for k in rows[0] if k.startswith("target_")]
assert targets and all(float(rows[-1][k]) == 0.0 for k in targets), rows[-1]
print(f"PASS: stopped after step {run['steps']} of {run['steps_planned']} (exit 3, operator_stop), "
      f"returned to start in {len(rows)} exchanges")
PY
