#!/usr/bin/env bash
# A node started at another control rate than the test's: the El Centro SDOF at 1024 Hz over
# DDS against site 1's node at 512 Hz (lock-step) and at 1 Hz (real time; before the check a
# 1 Hz node joined a 1024 Hz coordinator without complaint). Node and coordinator compare
# control periods when they meet (the node's heartbeat states its own): the coordinator
# refuses the run before its first command, exit 3, summary.json outcome "refused: site 1
# runs at R Hz and this test at 1024 Hz (control periods ...)"; the node is sent nothing.
source "$(dirname "$0")/lib.sh"
for case in "lock_step 512 as_fast_as_possible" "real_time 1 real_time"; do
  read -r mode rate clock <<< "$case"
  start_node 1 $mode --set node.control_rate_hz=$rate
  out="$WORK/$mode"
  set +e
  $RPSD run "$SRC/examples/scenarios/elcentro-sdof.yaml" --out "$out" \
    --set "transport={kind: dds, test_id: 7, domain_id: $DOMAIN, dds_config: ../../transport/config/loopback.xml}" \
    --set clock.mode=$clock \
    --set "ground_motion.trim={end_s: 1}" > "$out.log" 2>&1
  code=$?
  set -e
  kill -TERM $NODE1_PID
  wait $NODE1_PID || fail "$mode: the node exited with $?"
  cat "$out.log"
  [ $code = 3 ] || fail "$mode: exit code $code, expected 3"
  outcome=$(json "$out/summary.json" "j['outcome']")
  case "$outcome" in
    "refused: site 1 runs at $rate Hz and this test at 1024 Hz (control periods "*" s and 0.000976562 s): node and coordinator must run at one rate") ;;
    *) fail "$mode: outcome \"$outcome\"" ;;
  esac
  [ "$(json "$out/summary.json" "j['steps']")" = 0 ] || fail "$mode: the refused run took steps"
  [ "$(json "$WORK/node1.json" "j['commands_accepted'] + sum(j['commands_dropped'].values()) + j['end_of_run_commands']")" = 0 ] \
    || { cat "$WORK/node1.json"; fail "$mode: the node was sent commands"; }
  echo "$mode: a node at $rate Hz: $outcome"
done
echo "PASS: a node at another rate refuses the run before its first command, naming both rates"
