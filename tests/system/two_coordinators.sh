#!/usr/bin/env bash
# Two coordinators with one test id started at once against one servo node (site 1 of test 7,
# the El Centro SDOF over DDS), in lock-step and in real time, three trials each on the same
# node. A node serves one run at a time, and every run has an identity of its own (a random
# run id on every command and feedback sample): the node takes the first run it sees and
# refuses the other's commands; the other coordinator learns from the node (its feedback or
# heartbeat names the run it serves) and stops at once.
# Each trial: exactly one run completes (exit 0, every planned step); the other exits 3 having
#   taken no step, its summary.json outcome "refused: site 1 is serving another run (run R; ...)"
#   naming the winner's run id R (not "stopped answering"). The node took exactly the winners'
#   runs, in order, and accepted no command of a loser; the winner's end of run freed the node
#   for the next trial. Before run ids, the second run took the first run's measurements as
#   its own (2,727 identical values) and completed too.
source "$(dirname "$0")/lib.sh"
TRIALS=3

for mode in lock_step real_time; do
  start_node 1 $mode
  winners=() steps=()
  for trial in $(seq $TRIALS); do
    a="$WORK/$mode-$trial-a" b="$WORK/$mode-$trial-b"
    set +e
    sdof_over_dds "$a" $mode > "$a.log" 2>&1 &
    pa=$!
    sdof_over_dds "$b" $mode > "$b.log" 2>&1 &
    pb=$!
    wait $pa
    ca=$?
    wait $pb
    cb=$?
    set -e
    # Exactly one completed; the other was refused.
    if [ $ca = 0 ] && [ $cb = 3 ]; then
      win=$a lose=$b
    elif [ $ca = 3 ] && [ $cb = 0 ]; then
      win=$b lose=$a
    else
      cat "$a.log" "$b.log"
      fail "$mode trial $trial: exit codes $ca and $cb, expected one 0 and one 3"
    fi
    run=$(json "$win/summary.json" "j['run_id']")
    [ "$(json "$win/summary.json" "j['completed'] and j['steps'] == j['steps_planned']")" = True ] \
      || fail "$mode trial $trial: the winner did not take every step"
    every_step_recorded "$win"
    outcome=$(json "$lose/summary.json" "j['outcome']")
    case "$outcome" in
      "refused: site 1 is serving another run (run $run; this run is $(json "$lose/summary.json" "j['run_id']")): a node serves one run at a time") ;;
      *) cat "$lose.log"; fail "$mode trial $trial: the loser's outcome is \"$outcome\"" ;;
    esac
    grep -q "test refused: site 1 is serving another run (run $run" "$lose.log" || fail "$mode trial $trial: no reason printed"
    # Refused at once: the loser took no step, so it used no measurement at all (the winner's
    # least of all).
    [ "$(json "$lose/summary.json" "j['steps']")" = 0 ] || fail "$mode trial $trial: the loser took steps"
    [ "$(wc -l < "$lose/time_history.csv")" -le 1 ] || fail "$mode trial $trial: the loser recorded steps"
    winners+=("$run")
    steps+=("$(json "$win/summary.json" "j['steps']")")
    echo "$mode trial $trial: run $run completed $(json "$win/summary.json" "j['steps']") steps;" \
      "the other: $outcome"
    sleep 0.3  # the node's heartbeat says it is free again before the next pair looks
  done
  kill -TERM $NODE1_PID
  wait $NODE1_PID || fail "the node exited with $?"
  n="$WORK/node1.json"
  # The node took the winners' runs, in order, and nothing of the losers.
  python3 - "$n" "$mode" "${steps[*]}" "${winners[@]}" <<'PY' || { cat "$WORK/node1.log"; fail "$mode: the node served other runs"; }
import json, sys
node = json.load(open(sys.argv[1]))
mode, steps, winners = sys.argv[2], [int(s) for s in sys.argv[3].split()], sys.argv[4:]
took = [e["run_id"] for e in node["run_events"] if e["event"] == "took run"]
ended = [e["run_id"] for e in node["run_events"] if e["event"] == "run ended"]
assert took == winners, f"took {took}, the winners were {winners}"
assert ended == winners, f"ended {ended}: each winner's end of run frees the node"
assert node["runs"] == len(winners), node["runs"]
# A loser that passed the start check before the winner's first command sent commands: the
# node refused them as another run's (never applied). Lock-step: every command accepted is a
# winner's, one per step.
others = {k: v for k, v in node["commands_dropped"].items() if k != "another run" and v}
if mode == "lock_step":
    assert not others, f"dropped for other reasons: {others}"
    assert node["commands_accepted"] == sum(steps), f"accepted {node['commands_accepted']}, the winners took {steps}"
print(f"{mode}: the node took runs {' '.join(took)}; refused {node['commands_dropped']['another run']} commands of the others")
PY
  mv "$WORK/node1.json" "$WORK/node1-$mode.json"
  mv "$WORK/node1.log" "$WORK/node1-$mode.log"
done
echo "PASS: $TRIALS trials in lock-step and $TRIALS in real time: one run completed, the other was refused at once" \
  "naming the run the node served"
