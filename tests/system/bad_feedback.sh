#!/usr/bin/env bash
# Fault: a node sends the coordinator bad feedback: a sample of another test, one claiming
# another site, one with a wrong channel count, one of an older step, a duplicated answer,
# (in real time) an answer 3 ms late, and finally NaN displacements (a failed transducer, from
# one step on). Each comes with the first command at or after its step (in real time a
# command may be lost). rpsd_fault_node stands
# in for both sites of the bridge (a perfect actuator: x = u) and does this on site 2. Every
# bad sample carries 1 m, a displacement the coordinator must never use.
# Coordinator: drops and counts the foreign, malformed and older samples (summary.json
#   timing.sites[].messages); a duplicate of the newest step is taken again (the same step
#   re-reported, never older); a late answer makes late steps that go on with the newest
#   measurement; the NaN stops the test at once (RpsdLoop: kNonFinite), exit code 3 with the
#   reason "a non-finite measurement arrived (at step n, t = ...)". Detection: in lock-step
#   the step the first NaN answers, before it is used; in real time the step that first
#   holds a NaN answer (the link holds one even when newer answers came with it), at most
#   RT_AGE periods later.
# Results: every step before the detecting one is recorded (1..n-1), and
#   no recorded measurement is one of the bad samples' 1 m; summary.json's stopped_by says
#   kind non_finite at that step. Run lock-step (as fast as possible) and in real time at
#   1024 Hz. Then, lock-step, site 2's node reports a fault from step 300 on (its status
#   flag, and its heartbeat with what faulted it): the test stops there, exit 3, stopped_by
#   kind node_fault at step 301, its node_says the node's words.
source "$(dirname "$0")/lib.sh"
FAULT_NODE=${RPSD_FAULT_NODE:?path to rpsd_fault_node}
# run_against_fault_node NAME OUT "FAULT-NODE OPTIONS" RUN OPTIONS...: the bridge over DDS
# against rpsd_fault_node; sets code to rpsd run's exit code and shows its log.
run_against_fault_node() {
  local name=$1 out=$2 faults=$3
  shift 3
  # shellcheck disable=SC2086 # the fault node's options are words
  $FAULT_NODE --domain $DOMAIN --dds-config "$SRC/transport/config/loopback.xml" --summary "$WORK/fault-$name.json" \
    $faults > "$WORK/fault-$name.log" 2>&1 &
  local fault=$!
  PIDS+=($fault)
  set +e
  run_bridge "$out" --set transport.kind=dds "$@" > "$WORK/run-$name.log" 2>&1
  code=$?
  set -e
  kill -TERM $fault
  wait $fault || true
  cat "$WORK/run-$name.log"
}
for mode in lock_step real_time; do
  out="$WORK/$mode"
  # Lock-step waits for every step's feedback; in real time, a step goes on with feedback up
  # to RT_AGE periods old (lib.sh).
  if [ $mode = lock_step ]; then
    nan=1000 clock=as_fast_as_possible rt=0 age=()
  else
    nan=2048 clock=real_time rt=1 age=(--set clock.max_feedback_age_periods=$RT_AGE)
  fi
  run_against_fault_node $mode "$out" "--real-time $rt --wrong-test 100 --wrong-site 200 --wrong-channels 300 --older 400 --duplicate 500 --late 1500 --late-ms 3 --nan $nan" \
    --set clock.mode=$clock "${age[@]}"
  [ $code = 3 ] || fail "$mode: exit code $code, expected 3"
  # The command step the first NaN answered (0-based), and the step that stopped on it (1-based).
  sent=$(json "$WORK/fault-$mode.json" "j['sites']['2']['fault_sent_at_step'].get('nan', 'none')")
  stop=$(sed -n 's/.*test aborted: a non-finite measurement arrived (at step \([0-9]*\),.*/\1/p' "$WORK/run-$mode.log")
  [ -n "$stop" ] || fail "$mode: no clear reason"
  if [ $mode = lock_step ]; then
    [ "$sent $stop" = "$nan $((nan + 1))" ] || fail "lock-step: NaN sent with step $sent, stopped at $stop; expected $nan, $((nan + 1))"
  else
    [ "$sent" -ge $nan ] && [ "$stop" -gt "$sent" ] && [ $((stop - 1 - sent)) -le $RT_AGE ] \
      || fail "real time: NaN sent with step $sent, stopped at step $stop"
  fi
  every_step_recorded "$out"
  [ "$(json "$out/summary.json" "j['stopped_by']['kind'], j['stopped_by']['step']")" = "non_finite $stop" ] \
    || fail "$mode: stopped_by $(json "$out/summary.json" "j['stopped_by']"), expected kind non_finite at step $stop"
  [ "$(json "$out/summary.json" "j['steps']")" = $((stop - 1)) ] || fail "$mode: $(json "$out/summary.json" "j['steps']") steps, expected $((stop - 1))"
  [ "$(column "$out" measured_m_ch1 'max(abs(x) for x in v) < 0.1')" = True ] || fail "$mode: a bad sample's measurement was used"
  m="j['timing']['sites'][1]['messages']"
  dropped=$(json "$out/summary.json" "$m['dropped_wrong_test_or_site'], $m['dropped_wrong_channels'], $m['dropped_older_step']")
  if [ $mode = lock_step ]; then
    [ "$dropped" = "2 1 1" ] || fail "lock-step: site 2 dropped $(json "$out/summary.json" "$m")"
  else
    # Best effort: a bad sample may be lost on the way (on 2026-11-21 this VM lost up to
    # 2.4 % of the answers on loopback, 6 runs), so each is counted at most once.
    [ "$(json "$out/summary.json" "$m['dropped_wrong_test_or_site'] <= 2 and $m['dropped_wrong_channels'] <= 1 and $m['dropped_older_step'] <= 1")" = True ] \
      || fail "real time: site 2 dropped $(json "$out/summary.json" "$m")"
  fi
  [ "$(json "$out/summary.json" "j['timing']['sites'][0]['messages']")" = \
    "$(json "$out/summary.json" "{'dropped_impossible_step': 0, 'dropped_no_run': 0, 'dropped_older_step': 0, 'dropped_other_run': 0, 'dropped_unknown_writer': 0, 'dropped_wrong_channels': 0, 'dropped_wrong_test_or_site': 0, 'late': 0, 'received': $stop, 'sent': $stop}")" ] \
    || [ $mode = real_time ] || fail "$mode: site 1 $(json "$out/summary.json" "j['timing']['sites'][0]['messages']")"
  faults=$(json "$WORK/fault-$mode.json" "j['sites']['2']['fault_sent_at_step']")
  if [ $mode = lock_step ]; then
    # Every answer once, the duplicate once more; nothing late in lock-step.
    [ "$(json "$out/summary.json" "$m['received'], $m['sent'], $m['late']")" = "$((nan + 2)) $((nan + 1)) 0" ] \
      || fail "lock-step: site 2 $(json "$out/summary.json" "$m")"
  else
    late=$(json "$out/summary.json" "$m['late']")
    [ "$late" -ge 1 ] && [ "$(column "$out" feedback_age_periods 'max(v) >= 1')" = True ] || fail "real time: the late answer made no late step"
  fi
  echo "$mode: exit 3 at step $stop (NaN), $((stop - 1)) steps recorded; site 2 sent faults with command steps $faults; coordinator: $(json "$out/summary.json" "$m")"
done

# A node's fault flag stops the test at the step that carries it, and says so.
out="$WORK/node_fault"
run_against_fault_node node-fault "$out" "--real-time 0 --node-fault 300" --set clock.mode=as_fast_as_possible
[ $code = 3 ] || fail "node fault: exit code $code, expected 3"
[ "$(json "$out/summary.json" "j['result'], j['stopped_by']['kind'], j['stopped_by']['step']")" = "stopped node_fault 301" ] \
  || fail "node fault: summary $(json "$out/summary.json" "j['result'], j['stopped_by']"), expected stopped, node_fault at step 301"
# What faulted the node, in the words its heartbeat gives, reaches the summary and the outcome.
[ "$(json "$out/summary.json" "j['stopped_by']['node_says']")" = "site 2: the lab controller says: proposal refused (rpsd_fault_node)" ] \
  || fail "node fault: stopped_by $(json "$out/summary.json" "j['stopped_by']"), expected node_says with the node's words"
grep -q "proposal refused (rpsd_fault_node)" <<< "$(json "$out/summary.json" "j['outcome']")" || fail "node fault: the outcome does not say what the node said"
every_step_recorded "$out"
echo "node fault: exit 3, stopped_by $(json "$out/summary.json" "j['stopped_by']")"
echo "PASS: bad feedback dropped and counted by reason, the NaN stops the test with every step before it recorded, a node's fault stops it and summary.json names each"
