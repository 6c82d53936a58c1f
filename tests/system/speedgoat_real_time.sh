#!/usr/bin/env bash
# The earthquake test of speedgoat_lock_step.sh paced in real time at 1024 Hz: the
# coordinator (clock.mode real_time) and the node (mode real_time, the example file's own)
# each on their clock, the node driving `rpsd speedgoat-emulator` over TCP once a period. A
# handshake that misses its period is resumed on the next (max_missed_replies raised: this
# shared VM stalls now and then; the file's 3 is the rig's). The run completes every planned
# step; the node never faulted and finished most handshakes in their period; the recorded
# measurement tracks the command and the force is the specimen's k x.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/speedgoat_lib.sh"
speedgoat_run rt tcp "" "--set actuator.max_missed_replies=1000" --set clock.mode=real_time \
  --set clock.max_feedback_age_periods=$RT_AGE
[ $RUN_CODE = 0 ] || fail "rpsd run exited with $RUN_CODE"
every_step_recorded "$WORK/rt"
python3 - "$WORK" <<'PY' || fail "the real-time run through the Speedgoat handshake is wrong"
import csv, json, sys
base = sys.argv[1]
summary = json.load(open(f"{base}/rt/summary.json"))
node = json.load(open(f"{base}/rt.node.json"))
target = json.load(open(f"{base}/rt.target.json"))
assert summary["completed"] and summary["steps"] == summary["steps_planned"], summary.get("stop_reason")
assert node["mode"] == "real_time" and not node["faulted"], node
link = node["speedgoat_link"]
assert link["failed_side"] == "none", link
assert link["handshakes"] >= 0.9 * summary["steps"], link  # the node ticks on past the run's end too
assert target["sessions"] == 1 and target["sessions_ended"] == 1, target
rows = list(csv.DictReader(open(f"{base}/rt/time_history.csv")))
command = [float(r["command_m_ch0"]) for r in rows]
measured = [float(r["measured_m_ch0"]) for r in rows]
force = [float(r["measured_force_n_ch0"]) for r in rows]
peak = max(abs(c) for c in command)
# Feedback may be a few periods old in real time: compare within a window of 8 periods.
error = max(min(abs(measured[i] - command[j]) for j in range(max(0, i - 8), i + 1)) for i in range(len(rows)))
assert peak > 0.005 and error < 0.05 * peak, (peak, error)
assert max(abs(f - 700.8e3 * m) for f, m in zip(force, measured)) < 1e-3
print(f"PASS: {summary['steps']} steps in real time at 1024 Hz, {link['handshakes']} handshakes, "
      f"{link['missed_deadlines']} missed and resumed, measured within {error * 1e3:.3f} mm of a recent command "
      f"(peak {peak * 1e3:.2f} mm)")
PY
