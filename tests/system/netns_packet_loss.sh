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
#   is old). Only 5 periods without any newer feedback stop the test (exit 3).
# Results, asserted: at 1 % the test completes with every step recorded, some late steps, and
#   no node holds before the end of the test (holds == 1: the hold after the last command)
#   unless commands really stopped for 5 periods: 4 late steps in a row, or the coordinator
#   itself woken 3 periods late (each such event may explain one hold). At 5 % the same, or
#   the safe stop: exit 3 with its reason, every step recorded, the node holding within 4
#   ticks of its last command. A run the host stalled (site 1, which loses nothing, late in
#   the same steps, or the coordinator woken 2 periods late, or stopped before the loss began)
#   is not the loss's doing: such a stopped run is repeated, up to 3 runs in all per rate (two
#   stalled in a row once in CI). Measured: 2 of 24 runs at 5 % stopped; at 1 %, 2 of
#   about 12 did, both with site 1 late in the same steps (host stalls).
#   Each lost command makes one late step, or two when the next command reaches the node
#   just after the tick the node made without it (the node's missed-period ticks fall in
#   phase with the commands, and a command right after a tick waits 3/4 of a period), so
#   fewer than 5 commands lost in a row can stop the test; stalls of the host add to it.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/netns.sh"
report=""
# host_stall OUT: True when the last steps of a stopped run show the host stalling rather
# than site 2's link: site 1 late too (2 of the last 4 steps), or the coordinator woken 2
# periods late.
host_stall() {
  python3 - "$1/time_history.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))[-8:]
period = 1 / 1024
# Site 1 loses nothing: its feedback past the receive window (0.8 T) in 2 of the last 4
# steps means the link or the host was slow, not lossy.
site1_late = sum(float(r["round_trip_s_ch0"]) > 0.8 * period for r in rows[-4:]) >= 2
print(site1_late or max(float(r["cycle_lateness_s"]) for r in rows) >= 2 * period)
PY
}
# hold_reasons OUT: steps where commands may have stopped for 5 periods: the 4th late step
# in a row, or a cycle woken 3 periods late.
hold_reasons() {
  python3 - "$1/time_history.csv" <<'PY'
import csv, sys
period = 1 / 1024
print(sum(1 for r in csv.DictReader(open(sys.argv[1]))
          if int(r["feedback_age_periods"]) == 4 or float(r["cycle_lateness_s"]) >= 3 * period))
PY
}
for percent in 1 5; do
  for attempt in 1 2 3; do
    out="$WORK/loss$percent-$attempt"
    start_host_node 1 real_time
    start_host_node 2 real_time
    drop_coordinator_traffic 2 0
    ip netns exec $NS_COORD "${LAN_ENV[@]}" $RPSD run "$SRC/scenarios/two-site-bridge.yaml" --out "$out" --set transport.kind=dds \
      --set transport.dds_config=../transport/config/lab-lan.xml --set clock.mode=real_time \
      --set ground_motion.trim.end_s=6 > "$out.log" 2>&1 &
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
    # A stop before any packet was dropped, or with the host's stall signs, is not the loss's
    # doing: run again (the last run is judged whatever it shows).
    if [ $code = 3 ] && [ $attempt -lt 3 ] && { [ "$dropped_in" = 0 ] || [ "$(host_stall "$out")" = True ]; }; then
      echo "$percent %: stopped by the host (a stall), not by the loss: once more"
      continue
    fi
    break
  done
  every_step_recorded "$out"
  [ "$dropped_in" -gt 0 ] && [ "$dropped_out" -gt 0 ] || fail "$percent %: nftables dropped $dropped_in packets in, $dropped_out out"
  steps=$(json "$out/summary.json" "j['steps']")
  late=$(json "$out/summary.json" "j['timing']['late_feedback']")
  late2=$(json "$out/summary.json" "j['timing']['sites'][1]['messages']['late']")
  max_age=$(column "$out" feedback_age_periods 'int(max(v))')
  reasons=$(hold_reasons "$out")
  for s in 1 2; do [ "$(json "$WORK/node$s.json" "j['faulted']")" = False ] || fail "$percent %: node $s faulted"; done
  if [ $code = 0 ]; then
    [ "$steps" = "$(json "$out/summary.json" "j['steps_planned']")" ] || fail "$percent %: $steps steps"
    [ "$late2" -gt 0 ] || fail "$percent %: no late feedback from site 2 although packets were lost"
    for s in 1 2; do
      holds=$(json "$WORK/node$s.json" "j['holds']")
      [ "$holds" -ge 1 ] && [ $((holds - 1)) -le "$reasons" ] \
        || { cat "$WORK/node$s.json"; fail "$percent %: node $s held $holds times; commands may have stopped $reasons times"; }
    done
    outcome="completed"
  elif [ $code = 3 ] && [ $percent = 5 ]; then
    grep -q "the servo node stopped answering (newest feedback 5 control periods old" "$out.log" || fail "no clear reason"
    [ "$(column "$out" feedback_age_periods 'v[-4:] == [1, 2, 3, 4]')" = True ] || fail "5 %: stopped without 4 late steps before"
    ticks=$(json "$WORK/node2.json" "(j['hold_after_last_command'] or {}).get('periods_after_last_command', -1)")
    [ "$ticks" -ge 1 ] && [ "$ticks" -le 4 ] || fail "5 %: node 2 held $ticks ticks after its last command"
    outcome="stopped safely after $steps steps (5 exchanges in a row without new feedback)"
  else
    fail "$percent %: exit code $code"
  fi
  line="$percent % loss: $outcome; $dropped_in packets to site 2 and $dropped_out from it dropped;"
  line+=" late feedback $late steps (site 2: $late2), largest feedback age $max_age periods;"
  line+=" node 2: $(json "$WORK/node2.json" "j['commands_accepted']") commands, $(json "$WORK/node2.json" "j['holds']") holds"
  echo "$line"
  report+="$line"$'\n'
done
echo "PASS:"
printf '%s' "$report"
