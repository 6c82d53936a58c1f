#!/usr/bin/env bash
# Issue 30, calibration over DDS: the two-actuator column over DDS takes each actuator's reading
# and load cell at rest from its node's heartbeat (summary: calibration measured, with the
# node's readings), and a node whose actuator rests 3 mm off the stroke the geometry predicts
# (beyond max_offset_m, 2 mm) is refused before any command: exit 4 naming the actuator, the
# node never moving.
source "$(dirname "$0")/lib.sh"
example=two-actuator-column
# node NAME STROKES: the example's node with its actuators at rest at STROKES (m).
node() {
  $RPSD servo-node "$SRC/examples/nodes/$example-site.yaml" --set dds.domain_id=$DOMAIN \
    --set "actuator.initial_displacement_m=$2" --summary "$WORK/$1-node.json" > "$WORK/$1-node.log" 2>&1 &
  PIDS+=($!)
  NODE_PID=$!
}
# coordinator NAME: the example over DDS, 3 s of its record; its exit code in RC.
coordinator() {
  RC=0
  $RPSD run "$SRC/examples/scenarios/$example.yaml" --out "$WORK/$1" --set transport.domain_id=$DOMAIN \
    --set transport.kind=dds --set ground_motion.trim.end_s=3 > "$WORK/$1.log" 2>&1 || RC=$?
}
stop_node() {
  kill -TERM "$NODE_PID"
  wait "$NODE_PID" || { cat "$WORK/$1-node.log" >&2; fail "$1: the node exited with $?"; }
}

# At its reference, 1 mm and -0.5 mm off (within the 2 mm): measured, the node's readings.
node within "[0.001, -0.0005]"
coordinator within
stop_node within
[ "$RC" = 0 ] || { cat "$WORK/within.log" >&2; fail "within: the run failed ($RC)"; }
python3 - "$WORK/within/summary.json" <<'PY' || fail "within: the calibration is not the node's readings"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["outcome"] == "completed", j["outcome"]
cal = j["experimental_setups"][0]["calibration"]
assert cal["measured"] is True, cal
assert cal["predicted_stroke_m"] == [0.0, 0.0], cal
for got, want in zip(cal["reading_m"], [0.001, -0.0005]):
    assert abs(got - want) < 1e-12, cal
for got, want in zip(cal["offset_m"], [0.001, -0.0005]):
    assert abs(got - want) < 1e-12, cal
# The column bent by the offsets loads both load cells, as the node measured them at rest.
assert cal["force_at_rest_measured"] is True, cal
assert all(abs(f) > 100.0 for f in cal["force_at_rest_n"]), cal
PY

# 3 mm off on the column-top actuator: refused before any command, exit 4, naming it.
node off "[0.003, 0]"
coordinator off
sleep 0.5  # the node would have taken a command by now, were one sent
stop_node off
[ "$RC" = 4 ] || { cat "$WORK/off.log" >&2; fail "off: exit $RC, not 4"; }
grep -q "site 1, actuator_1 (channel 0): its reading 0.003 m at the start is 0.003 m from the stroke 0 m" "$WORK/off.log" \
  || { cat "$WORK/off.log" >&2; fail "off: the refusal does not name the actuator and its offset"; }
[ "$(json "$WORK/off/summary.json" "j['result']")" = not_ready ] || fail "off: the summary's result is not not_ready"
python3 - "$WORK/off-node.json" <<'PY' || fail "off: the node moved"
import json, sys
n = json.load(open(sys.argv[1]))
assert n["commands_accepted"] == 0 and n["commands_applied"] == 0 and n["runs"] == 0, n
PY
echo "PASS: over DDS the calibration is the node's readings, and an actuator 3 mm off refuses the start"
