#!/usr/bin/env bash
# A Speedgoat target that goes silent in the middle of an earthquake test (lock-step):
# `rpsd speedgoat-emulator` stops answering after 500 moves. The node reports no reply for
# max_missed_replies (3) commands, then latches a fault on the 4th, ends the session
# (newTarget = -1 twice: the emulator counts it) and says in its summary that the target
# failed and why; the coordinator stops the test (exit 3) with every step it took recorded.
source "$(dirname "$0")/lib.sh"
port=$(python3 -c "import socket; s = socket.socket(); s.bind(('127.0.0.1', 0)); print(s.getsockname()[1])")
"$RPSD" speedgoat-emulator "$SRC/examples/nodes/speedgoat-target-emulator.yaml" --set target.port=$port \
  --set target.silent_after_moves=500 --summary "$WORK/target.json" > "$WORK/target.log" 2>&1 &
target=$!
PIDS+=($target)
for _ in $(seq 100); do grep -q "serving node" "$WORK/target.log" && break; sleep 0.1; done
# 50 ms per handshake: long for a loaded machine's lock-step, short beside the test's timeouts.
"$RPSD" servo-node "$SRC/examples/nodes/speedgoat-node.yaml" --set node.mode=lock_step --set dds.domain_id=$DOMAIN \
  --set actuator.port=$port --set actuator.reply_timeout_s=0.05 --summary "$WORK/node.json" > "$WORK/node.log" 2>&1 &
node=$!
PIDS+=($node)
for _ in $(seq 100); do grep -q "Speedgoat target" "$WORK/node.log" && break; sleep 0.1; done
code=0
# A hang guard: the run stops within a second when the node faults.
timeout 120 "$RPSD" run "$SRC/examples/scenarios/speedgoat-sdof.yaml" --out "$WORK/run" --set transport.domain_id=$DOMAIN \
  > "$WORK/run.log" 2>&1 || code=$?
kill -TERM $node 2>/dev/null || true
wait $node || true
kill -TERM $target 2>/dev/null || true
wait $target || true
cat "$WORK/target.log" "$WORK/node.log" "$WORK/run.log"
[ $code = 3 ] || fail "rpsd run exited with $code, not 3 (stopped)"
grep -q "the servo node reported a fault" "$WORK/run.log" || fail "the run does not say the node faulted"
every_step_recorded "$WORK/run"
python3 - "$WORK" <<'PY' || fail "the silent target was not handled as it should be"
import json, sys
base = sys.argv[1]
node = json.load(open(f"{base}/node.json"))
target = json.load(open(f"{base}/target.json"))
summary = json.load(open(f"{base}/run/summary.json"))
link = node["speedgoat_link"]
assert node["faulted"], node
assert link["failed_side"] == "target", link
assert "did not finish a handshake in time" in link["failure"], link
assert link["handshakes"] == 499 and link["missed_deadlines"] == 4, link  # 500 moves, the first at start
assert node["actuator_no_replies"] == 3, node
assert target["moves"] == 500 and target["sessions_ended"] == 1, target
assert not summary["completed"] and summary["steps"] < summary["steps_planned"], summary
print(f"PASS: silent after 500 moves; the node faulted after {link['missed_deadlines']} late handshakes "
      f"({link['failure']}); the run stopped at step {summary['steps']} of {summary['steps_planned']}")
PY
