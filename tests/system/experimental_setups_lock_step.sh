#!/usr/bin/env bash
# The worked multi-actuator examples over DDS, one servo node per actuator group, lock-step on
# loopback: the two-actuator column and the three actuators with joint offsets each equal their
# in-process rehearsal bit for bit in every column but timing, the actuators of one site
# pushing against each other the same way in both.
source "$(dirname "$0")/lib.sh"
for example in two-actuator-column three-actuator-joint-offset; do
  $RPSD servo-node "$SRC/examples/nodes/$example-site.yaml" --set dds.domain_id=$DOMAIN \
    --summary "$WORK/$example-node.json" > "$WORK/$example-node.log" 2>&1 &
  PIDS+=($!)
  run() {
    $RPSD run "$SRC/examples/scenarios/$example.yaml" --out "$WORK/$example-$1" --set transport.domain_id=$DOMAIN \
      --set ground_motion.trim.end_s=3 "${@:2}" > "$WORK/$example-$1.log" 2>&1 \
      || { cat "$WORK/$example-$1.log" >&2; fail "$example: the $1 run failed"; }
  }
  run dds --set transport.kind=dds
  run local
  python3 - "$WORK/$example-dds/time_history.csv" "$WORK/$example-local/time_history.csv" <<'PY' \
    || fail "$example: the DDS run differs from the in-process run"
import csv, sys
timing = ("round_trip_s_", "cycle_lateness_s", "feedback_age_periods")
a, b = (list(csv.DictReader(open(f))) for f in sys.argv[1:3])
assert len(a) == len(b) > 3000, (len(a), len(b))
keep = [k for k in a[0] if not k.startswith(timing)]
assert "dof_measured_m_ch0" in keep and "measured_force_n_ch1" in keep, keep
for n, (x, y) in enumerate(zip(a, b)):
    for k in keep:
        assert x[k] == y[k], f"step {n + 1}: {k} {x[k]} over DDS, {y[k]} in process"
# The actuators of the site push against each other at some step: forces of opposite signs.
assert any(float(r["measured_force_n_ch0"]) * float(r["measured_force_n_ch1"]) < -1e6 for r in a)
PY
  [ "$(json "$WORK/$example-dds/summary.json" "j['timing']['over_dds']")" = True ] || fail "$example: not over DDS"
  [ "$(json "$WORK/$example-dds/summary.json" "j['outcome']")" = completed ] || fail "$example: not completed"
  kill "${PIDS[-1]}" 2>/dev/null || true
done
echo "PASS: both examples over DDS equal their in-process rehearsals"
