#!/usr/bin/env bash
# The two-site bridge across three hosts (network namespaces joined by veth links through a
# switch): coordinator on one, a servo node on each of the others, found by DDS discovery
# with the lab-LAN configuration. Lock-step, it equals the single-process run bit for bit.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/netns.sh"
for site in 1 2; do
  ns_var=NS_SITE$site
  in_host ${!ns_var} $RPSD servo-node "$SRC/examples/nodes/bridge-pier-site-$site.yaml" --set node.mode=lock_step \
    --set dds.config=../../transport/config/lab-lan.xml --summary "$WORK/node$site.json" > "$WORK/node$site.log" 2>&1 &
  PIDS+=($!)
done
in_host $NS_COORD $RPSD run "$SRC/examples/scenarios/two-site-bridge.yaml" --out "$WORK/dds" --set transport.kind=dds \
  --set transport.dds_config=../../transport/config/lab-lan.xml
run_bridge "$WORK/local"
cmp <(cut -d, -f1-30 "$WORK/dds/time_history.csv") <(cut -d, -f1-30 "$WORK/local/time_history.csv") \
  || fail "the three-host run differs from the in-process run"
echo "PASS: three hosts, $(json "$WORK/dds/summary.json" "j['steps']") steps identical to one process;" \
  "p50 round trip site 1 $(json "$WORK/dds/summary.json" "j['timing']['sites'][0]['round_trip']['p50_s']") s"
