# Three hosts in network namespaces on one switch (a bridge in a fourth namespace), each with
# eth0 on 198.18.0.0/24 (RFC 2544 test addresses): coordinator .1, site 1 .2, site 2 .3.
# Sourced after lib.sh. Needs root; without it the test exits 77 (skipped) with a message.
if [ "$(id -u)" -ne 0 ]; then
  echo "SKIP: network namespaces need root (run the suite as root to include the multi-host tests)"
  exit 77
fi
TAG=$$
NS_SWITCH=rpsd-sw-$TAG NS_COORD=rpsd-co-$TAG NS_SITE1=rpsd-s1-$TAG NS_SITE2=rpsd-s2-$TAG
# Whatever still runs in a host is killed first: a process outlives its namespace's name, and a
# real-time node left behind would keep a core busy for the tests after this one.
NETNS_CLEANUP="for n in $NS_COORD $NS_SITE1 $NS_SITE2 $NS_SWITCH; do ip netns pids \$n 2>/dev/null | xargs -r kill -9 2>/dev/null; ip netns del \$n 2>/dev/null || true; done"
ip netns add $NS_SWITCH
ip -n $NS_SWITCH link add br0 type bridge
ip -n $NS_SWITCH link set br0 up
host=1
for ns in $NS_COORD $NS_SITE1 $NS_SITE2; do
  ip netns add $ns
  ip link add eth0 netns $ns type veth peer name port$host netns $NS_SWITCH
  ip -n $ns addr add 198.18.0.$host/24 dev eth0
  ip -n $ns link set eth0 up
  ip -n $ns link set lo up
  ip -n $NS_SWITCH link set port$host master br0 up
  host=$((host + 1))
done
# Cyclone's LAN profile on every host: eth0, unicast discovery of the three addresses.
LAN_ENV=(env RPSD_DDS_INTERFACE=eth0 RPSD_DDS_PEER_1=198.18.0.1 RPSD_DDS_PEER_2=198.18.0.2 RPSD_DDS_PEER_3=198.18.0.3)
in_host() {
  local ns=$1; shift
  ip netns exec "$ns" "${LAN_ENV[@]}" "$@"
}

# start_host_node SITE MODE [extra --set ...]: the bridge pier node of SITE on its own host.
start_host_node() {
  local site=$1 mode=$2; shift 2
  local ns_var=NS_SITE$site
  # Not through in_host: started directly, $! is the node itself (a signal reaches it).
  ip netns exec "${!ns_var}" "${LAN_ENV[@]}" $RPSD servo-node "$SRC/examples/nodes/bridge-pier-site-$site.yaml" --set node.mode=$mode \
    --set dds.config=../../transport/config/lab-lan.xml --summary "$WORK/node$site.json" "$@" > "$WORK/node$site.log" 2>&1 &
  PIDS+=($!)
  eval "NODE${site}_PID=$!"
}

# drop_coordinator_traffic SITE PERCENT: nftables on the host of SITE drops PERCENT % of the
# packets from the coordinator (input) and to it (output), each packet drawn on its own;
# 100 is a partition. Replaces the rules of an earlier call.
drop_coordinator_traffic() {
  local ns_var=NS_SITE$1 match=""
  [ "$2" -lt 100 ] && match="numgen random mod 100 < $2"
  ip netns exec "${!ns_var}" nft -f - <<NFT
table inet rpsd_fault {}
delete table inet rpsd_fault
table inet rpsd_fault {
  chain in {
    type filter hook input priority 0; policy accept;
    ip saddr 198.18.0.1 $match counter drop
  }
  chain out {
    type filter hook output priority 0; policy accept;
    ip daddr 198.18.0.1 $match counter drop
  }
}
NFT
}

# dropped_packets SITE: "IN OUT", the packets the rules of drop_coordinator_traffic dropped.
dropped_packets() {
  local ns_var=NS_SITE$1
  ip netns exec "${!ns_var}" nft -j list table inet rpsd_fault | python3 -c '
import json, sys
counts = {}
for item in json.load(sys.stdin)["nftables"]:
    rule = item.get("rule")
    if rule:
        counts[rule["chain"]] = next(e["counter"]["packets"] for e in rule["expr"] if "counter" in e)
print(counts.get("in", 0), counts.get("out", 0))'
}
