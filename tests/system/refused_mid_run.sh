#!/usr/bin/env bash
# A run refused while under way, over DDS in lock-step: coordinator A runs the El Centro SDOF
# against site 1's node and is frozen (SIGSTOP) mid-run; the node, hearing nothing for its
# release_after_silence_s (5 s), frees itself; coordinator B takes the node; A is thawed while
# B runs. A must stop at its next step, exit 3, its summary.json outcome "refused: site 1 is
# serving another run (run B; this run is A) ...", every step it took recorded and none after;
# B completes untouched; the node took A, freed it after silence, took B and ended it, and
# applied no command of A's after B took it.
source "$(dirname "$0")/lib.sh"
start_node 1 lock_step
# 59 s of record (a few seconds in lock-step): long enough to be frozen and thawed mid-run.
long=(--set "ground_motion.trim={end_s: 39}" --set ground_motion.pad_after_s=20)
a="$WORK/a"
# rpsd_of PID: the rpsd process a function run in the background (the subshell PID) started.
rpsd_of() {
  local p
  for _ in $(seq 200); do
    p=$(pgrep -P "$1" -x rpsd) && { echo "$p"; return 0; }
    sleep 0.05
  done
  fail "no rpsd process under $1"
}
set +e
sdof_over_dds "$a" lock_step "${long[@]}" > "$a.log" 2>&1 &
pa=$!
PIDS+=($pa)
coordinator_a=$(rpsd_of $pa)
PIDS+=($coordinator_a)
wait_for_rows "$a/time_history.csv" 200 $pa
kill -STOP $coordinator_a
kill -0 $pa 2>/dev/null || fail "A ended before it could be frozen"
# Beyond the node's 5 s of silence before it frees a run (it logs run events only when it
# stops, so there is nothing to watch). A B refused because the node still served A (a slow
# host) is tried again a second later, up to 20 times, each in a folder of its own.
sleep 6
for attempt in $(seq 20); do
  b="$WORK/b$attempt"
  sdof_over_dds "$b" lock_step "${long[@]}" > "$b.log" 2>&1 &
  pb=$!
  PIDS+=($pb)
  wait_for_rows "$b/time_history.csv" 200 $pb
  kill -0 $pb 2>/dev/null && break
  wait $pb
  grep -q "serving another run" "$b.log" || break  # B ended for another reason: judged below
  sleep 1
done
kill -0 $pb 2>/dev/null || fail "B ended before A was thawed"
kill -CONT $coordinator_a
wait $pa
ca=$?
wait $pb
cb=$?
set -e
[ $ca = 3 ] || { cat "$a.log"; fail "A exited with $ca, expected 3 (refused)"; }
[ $cb = 0 ] || { cat "$b.log"; fail "B exited with $cb, expected 0"; }
run_a=$(json "$a/summary.json" "j['run_id']") run_b=$(json "$b/summary.json" "j['run_id']")
outcome=$(json "$a/summary.json" "j['outcome']")
case "$outcome" in
  "refused: site 1 is serving another run (run $run_b; this run is $run_a)"*) ;;
  *) cat "$a.log"; fail "A's outcome is \"$outcome\"" ;;
esac
[ "$(json "$a/summary.json" "200 <= j['steps'] < j['steps_planned']")" = True ] || fail "A did not stop mid-run"
every_step_recorded "$a"
[ "$(json "$b/summary.json" "j['completed'] and j['steps'] == j['steps_planned']")" = True ] || fail "B did not take every step"
every_step_recorded "$b"
kill -TERM $NODE1_PID
wait $NODE1_PID || fail "the node exited with $?"
python3 - "$WORK/node1.json" "$run_a" "$run_b" "$(json "$a/summary.json" "j['steps']")" \
  "$(json "$b/summary.json" "j['steps']")" <<'PY' || { cat "$WORK/node1.log"; fail "the node's runs are not A freed, then B"; }
import json, sys
node = json.load(open(sys.argv[1]))
run_a, run_b, steps_a, steps_b = sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
events = [(e["event"], e["run_id"]) for e in node["run_events"] if e["event"] != "refused"]
assert events == [("took run", run_a), ("freed after silence", run_a), ("took run", run_b), ("run ended", run_b)], events
# Lock-step: one accepted command per step taken, and A's command in flight when frozen at most.
accepted = node["commands_accepted"]
assert steps_a + steps_b <= accepted <= steps_a + 1 + steps_b, (accepted, steps_a, steps_b)
# A thawed learns from B's feedback or the node's heartbeat, before or after sending its next
# command: a command it sent was refused as another run's, never applied (the count above).
print(f"node: took {run_a}, freed it, took {run_b}; refused {node['commands_dropped']['another run']} of A's commands")
PY
echo "PASS: A stopped at step $(json "$a/summary.json" "j['steps']") of $(json "$a/summary.json" "j['steps_planned']"): $outcome"
