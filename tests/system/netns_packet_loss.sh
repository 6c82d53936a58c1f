#!/usr/bin/env bash
# Fault: packet loss between the coordinator and site 2, 1 % and then 5 %. The two-site bridge
# runs in real time at 1024 Hz across three hosts (network namespaces), the first 6 s of its
# record; one second in, nftables on site 2's host drops each packet from the coordinator
# (input) and each packet to it (output) with that probability, drawn per packet.
# Node 2: a lost command is a missed control period (the node ticks on its own deadline with
#   the command it has); 4 in a row would make it hold.
# Coordinator: a lost command or feedback makes that step's feedback late: the step goes on
#   with site 2's newest measurement, counted (summary.json timing.late_feedback and
#   sites[].messages.late) and flagged (time_history.csv feedback_age_periods, the periods it
#   is old). Only feedback more than RT_AGE periods old (lib.sh) would stop the test.
# Results, asserted at both rates: the test completes with every step recorded and some late
#   steps of site 2, and no node holds before the end of the test (holds == 1: the hold after
#   the last command) unless commands really stopped for a while: each stretch of steps with
#   feedback 3 or more periods old, or a cycle of the coordinator woken 2 periods late, may
#   explain one hold (a lost command costs one period or two, as the node's missed-period
#   ticks fall in phase with the commands; a late host adds to it), and so may each tick the
#   node itself woke a period or more late (summary late_wakeups: its host stalled it).
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/netns.sh"
report=""
for percent in 1 5; do
  out="$WORK/loss$percent"
  start_host_node 1 real_time
  start_host_node 2 real_time
  drop_coordinator_traffic 2 0
  ip netns exec $NS_COORD "${LAN_ENV[@]}" $RPSD run "$SRC/examples/scenarios/two-site-bridge.yaml" --out "$out" --set transport.kind=dds \
    --set transport.dds_config=../../transport/config/lab-lan.xml --set clock.mode=real_time \
    --set clock.max_feedback_age_periods=$RT_AGE --set ground_motion.trim.end_s=6 > "$out.log" 2>&1 &
  coordinator=$!
  PIDS+=($coordinator)
  wait_for_rows "$out/time_history.csv" 1024 $coordinator
  drop_coordinator_traffic 2 $percent
  set +e
  wait $coordinator
  code=$?
  set -e
  read -r dropped_in dropped_out <<< "$(dropped_packets 2)"
  kill -TERM $NODE1_PID $NODE2_PID
  wait $NODE1_PID $NODE2_PID || true
  cat "$out.log"
  [ $code = 0 ] || fail "$percent %: exit code $code"
  every_step_recorded "$out"
  [ "$dropped_in" -gt 0 ] && [ "$dropped_out" -gt 0 ] || fail "$percent %: nftables dropped $dropped_in packets in, $dropped_out out"
  steps=$(json "$out/summary.json" "j['steps']")
  late=$(json "$out/summary.json" "j['timing']['late_feedback']")
  late2=$(json "$out/summary.json" "j['timing']['sites'][1]['messages']['late']")
  max_age=$(column "$out" feedback_age_periods 'int(max(v))')
  reasons=$(hold_reasons "$out")
  for s in 1 2; do [ "$(json "$WORK/node$s.json" "j['faulted']")" = False ] || fail "$percent %: node $s faulted"; done
  [ "$steps" = "$(json "$out/summary.json" "j['steps_planned']")" ] || fail "$percent %: $steps steps"
  [ "$late2" -gt 0 ] || fail "$percent %: no late feedback from site 2 although packets were lost"
  for s in 1 2; do
    holds=$(json "$WORK/node$s.json" "j['holds']")
    stalls=$(json "$WORK/node$s.json" "j['late_wakeups']")
    [ "$holds" -ge 1 ] && [ $((holds - 1)) -le $((reasons + stalls)) ] \
      || { cat "$WORK/node$s.json"; fail "$percent %: node $s held $holds times; commands may have stopped $reasons times, the node stalled $stalls times"; }
  done
  line="$percent % loss: completed; $dropped_in packets to site 2 and $dropped_out from it dropped;"
  line+=" late feedback $late steps (site 2: $late2), largest feedback age $max_age periods;"
  line+=" node 2: $(json "$WORK/node2.json" "j['commands_accepted']") commands, $(json "$WORK/node2.json" "j['holds']") holds"
  echo "$line"
  report+="$line"$'\n'
done
echo "PASS:"
printf '%s' "$report"
