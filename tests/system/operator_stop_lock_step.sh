#!/usr/bin/env bash
# Operator commands over DDS (docs/operator-commands.md), without DDS Security: the two-site
# bridge, lock-step with its servo nodes as separate processes, its scenario enabling operator
# commands. `rpsd stop --hold` holds it for longer than a node's release_after_silence_s (5 s)
# and the run carries on after `--resume` with both nodes still serving it (the coordinator
# kept the run alive); `rpsd stop` ends it: exit 3, summary.json `operator_stop` naming the
# sender, every step recorded and identical to the unheld in-process run's, each node
# having accepted exactly the steps taken. A test id with no run answers nothing (exit 8).
source "$(dirname "$0")/lib.sh"
TEST_ID=$(( 300 + $$ % 200 ))
start_node 1 lock_step --set node.test_id=$TEST_ID
start_node 2 lock_step --set node.test_id=$TEST_ID
run_bridge "$WORK/dds" --set transport.kind=dds --set transport.test_id=$TEST_ID \
  --set "ground_motion.trim={end_s: 30}" --set "operator_commands={enabled: true}" > "$WORK/dds.log" 2>&1 &
RUN_PID=$!
PIDS+=($RUN_PID)
CONFIG=$SRC/transport/config/loopback.xml
# Each command says on the test's stderr (fd 3, whatever op's own output goes to) when it went,
# in seconds since the start: a slow failure shows where its time went.
exec 3>&2
op() {
  echo "[${SECONDS} s] rpsd stop $*" >&3
  "$RPSD" stop --test-id $TEST_ID --domain $DOMAIN --dds-config "$CONFIG" --sender "operator@system-test" "$@"
}
rows() { cat "$WORK/dds/time_history.csv" 2>/dev/null | wc -l; }

wait_for_rows "$WORK/dds/time_history.csv" 300 $RUN_PID
kill -0 $RUN_PID 2>/dev/null || fail "the run ended before it could be held: $(cat "$WORK/dds.log")"
op --hold --timeout 20 > "$WORK/hold.out" 2>&1 || fail "hold: exit $?: $(cat "$WORK/hold.out")"
grep -q "done: hold" "$WORK/hold.out" || fail "hold: $(cat "$WORK/hold.out")"
sleep 1  # the step under way, if any, is recorded by now
held_rows=$(rows)
sleep 6.5  # longer than release_after_silence_s: only the coordinator's word keeps the run
[ "$(rows)" = "$held_rows" ] || fail "steps were taken while held: $held_rows rows, then $(rows)"
op --hold --timeout 20 > "$WORK/hold2.out" 2>&1 && fail "a second hold was not refused"
[ $? -eq 7 ] || fail "a second hold: exit $?, expected 7 (refused): $(cat "$WORK/hold2.out")"
op --resume --timeout 20 > "$WORK/resume.out" 2>&1 || fail "resume: exit $?: $(cat "$WORK/resume.out")"
wait_for_rows "$WORK/dds/time_history.csv" $((held_rows + 300)) $RUN_PID
kill -0 $RUN_PID 2>/dev/null || fail "the run did not carry on after the resume: $(cat "$WORK/dds.log")"
op --timeout 20 > "$WORK/stop.out" 2>&1 || fail "stop: exit $?: $(cat "$WORK/stop.out")"
set +e
wait $RUN_PID
code=$?
set -e
[ $code -eq 3 ] || fail "the stopped run exited $code, expected 3: $(cat "$WORK/dds.log")"
grep -q "operator command stop from \"operator@system-test\"" "$WORK/dds.log" || fail "the stop is not logged on stderr"
every_step_recorded "$WORK/dds"
# Under `set -e` a failed kill or run would end the test without a word: each says why.
kill -TERM $NODE1_PID $NODE2_PID || fail "a node had ended before it was stopped: $(cat "$WORK/node1.log" "$WORK/node2.log")"
wait $NODE1_PID $NODE2_PID || fail "a node failed: $(cat "$WORK/node1.log" "$WORK/node2.log")"
# No run of this test id any more: no answer.
set +e
op --timeout 1 > "$WORK/none.out" 2>&1
code=$?
set -e
[ $code -eq 8 ] || fail "a stop to no run: exit $code, expected 8: $(cat "$WORK/none.out")"

run_bridge "$WORK/local" --set "ground_motion.trim={end_s: 30}" > "$WORK/local.log" 2>&1 \
  || fail "the in-process run exited $?: $(tail -n 20 "$WORK/local.log")"
python3 - "$WORK" "$held_rows" <<'PY' || fail "the operator's run is not what it should be"
import json, sys
w, held_rows = sys.argv[1], int(sys.argv[2])
run = json.load(open(f"{w}/dds/summary.json"))
s = run["stopped_by"]
assert run["result"] == "stopped" and s["kind"] == "operator_stop", (run["result"], s)
assert s["operator"] == {"action": "stop", "sender": "operator@system-test"}, s
assert run["outcome"].startswith("operator stop"), run["outcome"]
assert run["steps"] < run["steps_planned"], (run["steps"], run["steps_planned"])
held = run["held"]
assert len(held) == 1 and held[0]["after_step"] == held_rows - 1, (held, held_rows)
assert held[0]["held_by"] == held[0]["resumed_by"] == "operator@system-test", held
assert held[0]["held_s"] > 6.5, held
actions = [(c["action"], c["status"]) for c in run["operator_commands"]]
assert actions == [("hold", "done"), ("hold", "refused"), ("resume", "done"), ("stop", "done")], actions
for site in (1, 2):
    node = json.load(open(f"{w}/node{site}.json"))
    assert node["commands_accepted"] == run["steps"], (site, node["commands_accepted"], run["steps"])
# The held run's history is the unheld in-process run's, step for step (the columns both have).
dds = [l.split(",")[:30] for l in open(f"{w}/dds/time_history.csv")]
local = [l.split(",")[:30] for l in open(f"{w}/local/time_history.csv")][:len(dds)]
assert dds == local, "the held run's history differs from the in-process run's"
print(f"PASS: held {held[0]['held_s']:.1f} s after step {held[0]['after_step']} and resumed, stopped after step "
      f"{run['steps']} of {run['steps_planned']}: exit 3, operator_stop, every step identical to the unheld run")
PY
