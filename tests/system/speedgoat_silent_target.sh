#!/usr/bin/env bash
# A Speedgoat target that goes silent in the middle of an earthquake test (lock-step):
# `rpsd speedgoat-emulator` stops answering after 500 moves. The node reports no reply for
# max_missed_replies (3) commands, then latches a fault on the 4th, ends the session
# (newTarget = -1 twice: the emulator counts it) and says in its summary that the target
# failed and why; the coordinator stops the test (exit 3) with every step it took recorded,
# and its summary.json says what the node said (stopped_by.node_says).
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/speedgoat_lib.sh"
# 50 ms per handshake: long for a loaded machine's lock-step, short beside the test's timeouts.
speedgoat_run run tcp "--set target.silent_after_moves=500" \
  "--set node.mode=lock_step --set actuator.reply_timeout_s=0.05"
[ $RUN_CODE = 3 ] || fail "rpsd run exited with $RUN_CODE, not 3 (stopped)"
grep -q "the servo node reported a fault" "$WORK/run.run.log" || fail "the run does not say the node faulted"
every_step_recorded "$WORK/run"
python3 - "$WORK/run" <<'PY' || fail "the silent target was not handled as it should be"
import json, sys
run = sys.argv[1]
node, target, summary = (json.load(open(run + suffix)) for suffix in (".node.json", ".target.json", "/summary.json"))
link = node["speedgoat_link"]
assert node["faulted"], node
assert link["failed_side"] == "target", link
assert "did not finish a handshake in time" in link["failure"], link
assert link["handshakes"] == 499 and link["missed_deadlines"] == 4, link  # 500 moves, the first at start
assert node["actuator_no_replies"] == 3, node
assert target["moves"] == 500 and target["sessions_ended"] == 1, target
assert not summary["completed"] and summary["steps"] < summary["steps_planned"], summary
# The test's own summary says what faulted the node, from the node's heartbeat.
assert summary["stopped_by"]["node_says"].startswith("site 1: the target did not finish a handshake in time"), summary["stopped_by"]
print(f"PASS: silent after 500 moves; the node faulted after {link['missed_deadlines']} late handshakes "
      f"({link['failure']}); the run stopped at step {summary['steps']} of {summary['steps_planned']}")
PY
