#!/usr/bin/env bash
# Fault: a network partition between the coordinator and site 2 mid-test. The two-site bridge
# runs in real time at 1024 Hz across three hosts (network namespaces); one second into the
# run, nftables on site 2's host drops every packet from and to the coordinator.
# Node 2: no command arrives; its watchdog holds the actuator where the last command put it,
#   4 ticks after that command (5 control periods, 4.9 ms).
# Coordinator: site 2's newest feedback gets one period older each step (the late steps go on
#   with it, counted); when it is RT_AGE + 1 periods old (lib.sh) the test stops with exit
#   code 3 and the reason "the servo node stopped answering (newest feedback N control periods
#   old ...)". Node 1 then holds as well, within 4 ticks of its last command.
# Results: every step taken is in time_history.csv (steps 1..n, n = summary.json steps); its
#   last rows carry feedback_age_periods ..., RT_AGE - 1, RT_AGE (lib.sh: stopped_on_silence).
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/netns.sh"
start_host_node 1 real_time
start_host_node 2 real_time
ip netns exec $NS_COORD "${LAN_ENV[@]}" $RPSD run "$SRC/examples/scenarios/two-site-bridge.yaml" --out "$WORK/rt" --set transport.kind=dds \
  --set transport.dds_config=../../transport/config/lab-lan.xml --set clock.mode=real_time --set clock.max_feedback_age_periods=$RT_AGE > "$WORK/run.log" 2>&1 &
coordinator=$!
PIDS+=($coordinator)
# Partition once the test has run for a second (1024 steps recorded).
wait_for_rows "$WORK/rt/time_history.csv" 1024 $coordinator
drop_coordinator_traffic 2 100
set +e
wait $coordinator
code=$?
set -e
cat "$WORK/run.log"
kill -TERM $NODE1_PID $NODE2_PID
wait $NODE1_PID $NODE2_PID || true
[ $code = 3 ] || { cat "$WORK"/node*.log; fail "exit code $code, expected 3"; }
stopped_on_silence "$WORK/rt" "$WORK/run.log"
every_step_recorded "$WORK/rt"
steps=$(json "$WORK/rt/summary.json" "j['steps']")
[ "$steps" -gt 1024 ] && [ "$steps" -lt "$(json "$WORK/rt/summary.json" "j['steps_planned']")" ] || fail "stopped after $steps steps"
read -r dropped_in dropped_out <<< "$(dropped_packets 2)"
[ "$dropped_in" -gt 0 ] || fail "nftables dropped no packet to site 2"
for s in 1 2; do
  ticks=$(json "$WORK/node$s.json" "(j['hold_after_last_command'] or {}).get('periods_after_last_command', -1)")
  [ "$ticks" -ge 1 ] && [ "$ticks" -le 4 ] || { cat "$WORK/node$s.json"; fail "node $s: hold $ticks ticks after the last command"; }
  [ "$(json "$WORK/node$s.json" "j['faulted']")" = False ] || fail "node $s faulted"
done
echo "PASS: partition of site 2 after $steps steps: coordinator stopped $((RT_AGE + 1)) periods after site 2's last feedback" \
  "(exit 3), node 2 held $(json "$WORK/node2.json" "j['hold_after_last_command']['periods_after_last_command']") ticks" \
  "after its last command, node 1 $(json "$WORK/node1.json" "j['hold_after_last_command']['periods_after_last_command']");" \
  "nftables dropped $dropped_in packets in, $dropped_out out"
