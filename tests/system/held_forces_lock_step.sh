#!/usr/bin/env bash
# A held force over DDS, lock-step on loopback (examples/scenarios/column-axial-load.yaml and
# its node file): the column's axial load held in force control on its site's node channel 1
# beside the lateral actuator equals its in-process rehearsal bit for bit in every column but
# timing, the held force's included, and the summary reports it. A node whose file leaves
# that channel in displacement control refuses the force command, and the coordinator's
# outcome names the held force it was sent for.
source "$(dirname "$0")/lib.sh"
node() {
  $RPSD servo-node "$SRC/examples/nodes/column-axial-load-site.yaml" --set dds.domain_id=$DOMAIN \
    --summary "$WORK/node-$1.json" "${@:2}" > "$WORK/node-$1.log" 2>&1 &
  PIDS+=($!)
}
run() {
  $RPSD run "$SRC/examples/scenarios/column-axial-load.yaml" --out "$WORK/$1" --set transport.domain_id=$DOMAIN \
    --set ground_motion.trim.end_s=5 "${@:3}" > "$WORK/$1.log" 2>&1
  local code=$?
  [ "$code" = "$2" ] || { cat "$WORK/$1.log" >&2; fail "the $1 run exited $code, not $2"; }
}
set +e
node force
run dds 0 --set transport.kind=dds
run local 0
python3 - "$WORK/dds/time_history.csv" "$WORK/local/time_history.csv" <<'PY' \
  || fail "the DDS run differs from the in-process run"
import csv, sys
timing = ("round_trip_s_", "cycle_lateness_s", "feedback_age_periods")
a, b = (list(csv.DictReader(open(f))) for f in sys.argv[1:3])
assert len(a) == len(b) > 5000, (len(a), len(b))
keep = [k for k in a[0] if not k.startswith(timing)]
for column in ("held_force_command_n_ch1", "held_measured_m_ch1", "held_measured_force_n_ch1"):
    assert column in keep, (column, keep)
for n, (x, y) in enumerate(zip(a, b)):
    for k in keep:
        assert x[k] == y[k], f"step {n + 1}: {k} {x[k]} over DDS, {y[k]} in process"
# Held: the load cell near -30 kN at the end (a proportional force loop: within 10 % of the rig).
assert abs(float(a[-1]["held_measured_force_n_ch1"]) + 30.0e3) < 15.6e3, a[-1]["held_measured_force_n_ch1"]
PY
[ "$(json "$WORK/dds/summary.json" "j['timing']['over_dds']")" = True ] || fail "not over DDS"
[ "$(json "$WORK/dds/summary.json" "j['outcome']")" = completed ] || fail "not completed"
[ "$(json "$WORK/dds/summary.json" "j['held_forces'][0]['name'] + ' ' + str(j['held_forces'][0]['channel'])")" = "axial 1" ] \
  || fail "the summary does not report the held force"
kill "${PIDS[-1]}" 2>/dev/null || true

# The node's file leaves channel 1 in displacement control: it refuses the force command.
node displacement --set "actuator.control=[displacement, displacement]"
run refused 3 --set transport.kind=dds
outcome=$(json "$WORK/refused/summary.json" "j['outcome']")
grep -q "control mode" <<< "$outcome" || fail "the outcome does not say the node refused the control mode: $outcome"
grep -q "site 1 held force axial" <<< "$outcome" || fail "the outcome does not name the held force: $outcome"
echo "PASS: the held force over DDS equals its rehearsal; a node that does not hold it is named"
