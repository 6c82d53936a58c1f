#!/usr/bin/env bash
# Coordinator and two servo nodes as separate processes on loopback, lock-step over DDS:
# the distributed bridge test equals the single-process one bit for bit.
source "$(dirname "$0")/lib.sh"
start_node 1 lock_step
start_node 2 lock_step
run_bridge "$WORK/dds" --set transport.kind=dds
run_bridge "$WORK/local"
cmp <(cut -d, -f1-30 "$WORK/dds/time_history.csv") <(cut -d, -f1-30 "$WORK/local/time_history.csv") \
  || fail "the DDS run differs from the in-process run"
[ "$(json "$WORK/dds/summary.json" "j['timing']['over_dds']")" = True ] || fail "not over DDS"
# Lock-step over DDS keeps the CPUs awake (root only); in process it leaves them alone.
if [ "$(id -u)" = 0 ]; then
  [ "$(json "$WORK/dds/summary.json" "j['timing']['cpus_kept_awake']")" = True ] || fail "lock-step over DDS did not keep the CPUs awake"
fi
[ "$(json "$WORK/local/summary.json" "'cpus_kept_awake' in j['timing']")" = False ] || fail "an in-process run reported keeping the CPUs awake"
for s in 0 1; do
  [ "$(json "$WORK/dds/summary.json" "j['timing']['sites'][$s]['messages']['late']")" = 0 ] || fail "late feedback in lock-step"
  [ "$(json "$WORK/dds/summary.json" "j['timing']['sites'][$s]['round_trip']['p50_s'] > 0")" = True ] || fail "no round trip measured"
done
echo "PASS: $(wc -l < "$WORK/dds/time_history.csv") rows identical; p50 round trip $(json "$WORK/dds/summary.json" "j['timing']['sites'][0]['round_trip']['p50_s']") s"
