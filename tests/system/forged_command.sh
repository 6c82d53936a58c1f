#!/usr/bin/env bash
# Forged commands during a lock-step run (DDS security off): while the two-site bridge runs
# over DDS, an intruder (rpsd_forge_command) writes to site 1's node from a DDS writer of its
# own: a command of a made-up run with step 9 x 10^18 (before run ids this one command took
# the node over: it refused every real command after it and the coordinator blamed the node
# for silence), the served run's id copied from the node's heartbeat with step 9 x 10^18, the
# same with the next step and 20 mm, and the served run's end of run.
# Node 1: refuses the first as another run's and the next two as an unknown writer's (it
#   follows the writer that began the run), ignores the forged end, names the intruder's runs
#   and writer in its log and counts each by reason in its summary; it keeps serving the run.
# Coordinator: the run completes (exit 0) and equals the run in one process bit for bit: no
#   forged command moved an actuator.
source "$(dirname "$0")/lib.sh"
FORGE=${RPSD_FORGE_COMMAND:?path to rpsd_forge_command}
start_node 1 lock_step
start_node 2 lock_step
$FORGE --domain $DOMAIN --dds-config "$SRC/transport/config/loopback.xml" --test 7 --site 1 \
  --summary "$WORK/forged.json" > "$WORK/forge.log" 2>&1 &
forger=$!
PIDS+=($forger)
run_bridge "$WORK/dds" --set transport.kind=dds > "$WORK/run.log" 2>&1 || { cat "$WORK/run.log"; fail "the run failed"; }
wait $forger || { cat "$WORK/forge.log"; fail "the intruder sent nothing (it found no run)"; }
kill -TERM $NODE1_PID $NODE2_PID
wait $NODE1_PID $NODE2_PID || fail "a node exited with $?"
cat "$WORK/forge.log"
run_bridge "$WORK/local" > /dev/null
cmp <(cut -d, -f1-30 "$WORK/dds/time_history.csv") <(cut -d, -f1-30 "$WORK/local/time_history.csv") \
  || fail "the run over DDS differs from the run in one process: a forged command moved an actuator"
served=$(json "$WORK/forged.json" "j['served_run_id']")
[ "$served" = "$(json "$WORK/dds/summary.json" "j['run_id']")" ] || fail "the intruder copied run $served, not the coordinator's"
foreign=$(json "$WORK/forged.json" "j['forged'][0]['run_id']")
n1="$WORK/node1.json"
python3 - "$n1" "$served" "$foreign" "$(json "$WORK/dds/summary.json" "j['steps']")" <<'PY' || { cat "$WORK/node1.log"; fail "node 1 did not refuse the forged commands as such"; }
import json, sys
node, served, foreign, steps = json.load(open(sys.argv[1])), sys.argv[2], sys.argv[3], int(sys.argv[4])
dropped = node["commands_dropped"]
assert dropped["another run"] == 1 and dropped["unknown writer"] == 2, dropped
assert sum(dropped.values()) == 3, dropped
assert node["commands_accepted"] == steps and node["last_command_step"] == steps - 1, node  # every real command
events = [(e["event"], e["run_id"], e.get("reason")) for e in node["run_events"]]
assert events == [("took run", served, None), ("refused", foreign, "another run"),
                  ("refused", served, "unknown writer"), ("run ended", served, None)], events
assert node["runs"] == 1, node["runs"]
PY
grep -q "refused a command of run $foreign (another run, step 9000000000000000000" "$WORK/node1.log" \
  || fail "node 1's log does not name the foreign run"
grep -q "refused a command of run $served (unknown writer, step 9000000000000000000" "$WORK/node1.log" \
  || fail "node 1's log does not name the unknown writer"
[ "$(json "$WORK/node2.json" "sum(j['commands_dropped'].values())")" = 0 ] || fail "node 2 dropped commands"
echo "PASS: run $served completed as in one process; node 1 refused the forged commands:" \
  "$(json "$n1" "{k: v for k, v in j['commands_dropped'].items() if v}")"
grep "refused" "$WORK/node1.log"
