# Three hosts in network namespaces on one switch (a bridge in a fourth namespace), each with
# eth0 on 198.18.0.0/24 (RFC 2544 test addresses): coordinator .1, site 1 .2, site 2 .3.
# Sourced after lib.sh. Needs root; without it the test exits 77 (skipped) with a message.
if [ "$(id -u)" -ne 0 ]; then
  echo "SKIP: network namespaces need root (run the suite as root to include the multi-host tests)"
  exit 77
fi
TAG=$$
NS_SWITCH=rpsd-sw-$TAG NS_COORD=rpsd-co-$TAG NS_SITE1=rpsd-s1-$TAG NS_SITE2=rpsd-s2-$TAG
NETNS_CLEANUP="for n in $NS_COORD $NS_SITE1 $NS_SITE2 $NS_SWITCH; do ip netns del \$n 2>/dev/null || true; done"
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
in_host() {
  local ns=$1; shift
  ip netns exec "$ns" env RPSD_DDS_INTERFACE=eth0 RPSD_DDS_PEER_1=198.18.0.1 RPSD_DDS_PEER_2=198.18.0.2 \
    RPSD_DDS_PEER_3=198.18.0.3 "$@"
}
