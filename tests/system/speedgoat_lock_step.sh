#!/usr/bin/env bash
# A whole earthquake test through OpenFresco's Speedgoat handshake, in lock-step: `rpsd run`
# on examples/scenarios/speedgoat-sdof.yaml reaches `rpsd servo-node` on
# examples/nodes/speedgoat-node.yaml over DDS, which drives `rpsd speedgoat-emulator` on
# examples/nodes/speedgoat-target-emulator.yaml (its transducers read 2.5 mm and 0.4 kN at
# rest), over TCP and then over UDP. Each run completes (exit 0); the node recorded the
# offsets it measured; every step took one whole handshake; the measured displacement tracks
# the command and the measured force is the specimen's k x (offsets removed); the node ended
# the session (newTarget = -1).
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/speedgoat_lib.sh"

for transport in tcp udp; do
  # Lock-step: a handshake may wait as long as a loaded machine needs (the file's 2 ms is the rig's).
  speedgoat_run $transport $transport "" "--set node.mode=lock_step --set actuator.reply_timeout_s=5"
  [ $RUN_CODE = 0 ] || fail "$transport: rpsd run exited with $RUN_CODE"
  every_step_recorded "$WORK/$transport"
  python3 - "$WORK/$transport" "$transport" <<'PY' || fail "$transport: the run through the Speedgoat handshake is wrong"
import csv, json, sys
base, transport = sys.argv[1], sys.argv[2]
summary = json.load(open(f"{base}/summary.json"))
node = json.load(open(f"{base}.node.json"))
target = json.load(open(f"{base}.target.json"))
assert summary["completed"], summary.get("stop_reason")
link = node["speedgoat_link"]
assert link["transport"] == transport, link
# OpenFresco's setup(): the DAQ at rest, its negation for the relative DAQ signals, and the
# relative control signal starting where the DAQ displacement says the piston is.
assert link["offsets"] == {"initial_daq": [2.5, 0.4, 0.0], "daq": [-2.5, -0.4, 0.0], "control": [2.5]}, link["offsets"]
steps = summary["steps"]
assert link["handshakes"] == steps and link["missed_deadlines"] == 0, (steps, link)
assert link["failed_side"] == "none" and not node["faulted"], link
assert target["moves"] == steps + 1 and target["sessions"] == 1 and target["sessions_ended"] == 1, target
rows = list(csv.DictReader(open(f"{base}/time_history.csv")))
command = [float(r["command_m_ch0"]) for r in rows]
measured = [float(r["measured_m_ch0"]) for r in rows]
force = [float(r["measured_force_n_ch0"]) for r in rows]
peak = max(abs(c) for c in command)
error = max(abs(c - m) for c, m in zip(command, measured))
assert peak > 0.005 and error < 0.05 * peak, (peak, error)  # the 1 ms plant lags one period
assert max(abs(f - 700.8e3 * m) for f, m in zip(force, measured)) < 1e-3  # k x, the 0.4 kN at rest removed
print(f"PASS {transport}: {steps} steps, {link['handshakes']} handshakes, peak {peak * 1e3:.2f} mm, "
      f"largest |command - measured| {error * 1e3:.3f} mm, {link['drained_vectors']} vectors drained")
PY
done
echo "PASS: an earthquake test in lock-step through the Speedgoat handshake over TCP and UDP"
