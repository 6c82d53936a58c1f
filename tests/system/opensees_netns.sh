#!/usr/bin/env bash
# OpenSees, rpsd's site server and its servo node on three hosts (network namespaces joined by
# veth links through a switch, tests/system/netns.sh): host A (198.18.0.1) runs the real
# OpenSees with examples/opensees/sdof-generic-client.tcl (El Centro 180 x 0.15, 5 s), which
# connects over TCP to host B (198.18.0.2), where `rpsd site-server` serves its genericClient
# element (tests/system/data/opensees-sdof-site-dds.yaml); B commands the perfect simulated
# actuator of `rpsd servo-node` on host C (198.18.0.3, tests/system/data/opensees-sdof-node.yaml)
# over DDS with the lab-LAN profile, lock-step. A perfect actuator over DDS changes nothing:
# OpenSees' displacements equal sdof-reference.tcl's (the spring as a plain element), run here.
# nftables counters on A and C show that the TCP and DDS traffic crossed the hosts' links.
# Needs OPENSEES (the OpenSees interpreter) and root; otherwise exit 77 (skipped).
if [ -z "${OPENSEES:-}" ]; then
  echo "skipped: OPENSEES is not set (the path to the OpenSees interpreter, e.g. OPENSEES=/opt/opensees/bin/OpenSees)"
  exit 77
fi
[ -x "$OPENSEES" ] || { echo "skipped: OPENSEES=$OPENSEES is not an executable"; exit 77; }
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/netns.sh"
# A signal (ctest's timeout) ends the test through lib.sh's EXIT trap too: hosts and processes go.
trap 'exit 143' TERM
trap 'exit 130' INT
NS_A=$NS_COORD NS_B=$NS_SITE1 NS_C=$NS_SITE2
A=198.18.0.1 B=198.18.0.2 C=198.18.0.3
DATA=$SRC/tests/system/data
RECORD=$SRC/data/ground-motions/I-ELC180.AT2
SCALE=0.15 DURATION=5
LAN_CONFIG=../../../transport/config/lab-lan.xml

# count_traffic NS NAME RULE: an nftables counter on NS's output for packets matching RULE.
count_traffic() {
  ip netns exec "$1" nft -f - <<NFT
table inet rpsd_count {
  chain out {
    type filter hook output priority 0; policy accept;
    $3 counter comment "$2"
  }
}
NFT
}
# counted NS: packets the counter of count_traffic on NS saw.
counted() {
  ip netns exec "$1" nft -j list table inet rpsd_count | python3 -c '
import json, sys
for item in json.load(sys.stdin)["nftables"]:
    rule = item.get("rule")
    if rule:
        print(next(e["counter"]["packets"] for e in rule["expr"] if "counter" in e))'
}
count_traffic "$NS_A" opensees-to-site "ip daddr $B tcp dport != 0"
count_traffic "$NS_C" node-to-site "ip daddr $B udp dport != 0"

# Host C: the servo node, lock-step, a domain of its own for this run. Started with
# `ip netns exec` itself (not in_host, a function) so that $! is the node, for SIGTERM.
ip netns exec "$NS_C" "${LAN_ENV[@]}" $RPSD servo-node "$DATA/opensees-sdof-node.yaml" --set dds.domain_id=$DOMAIN \
  --set dds.config=$LAN_CONFIG --summary "$WORK/node.json" > "$WORK/node.log" 2>&1 &
NODE_PID=$!
PIDS+=($NODE_PID)
# Host B: the site server, listening on B's address (a free port, which it prints) for A's
# OpenSees only (the file's listen.allowed_clients).
ip netns exec "$NS_B" "${LAN_ENV[@]}" $RPSD site-server "$DATA/opensees-sdof-site-dds.yaml" --out "$WORK/site" \
  --set listen.address=$B --set "listen.allowed_clients=[$A]" --set listen.port=0 --set transport.domain_id=$DOMAIN \
  --set transport.dds_config=$LAN_CONFIG \
  > "$WORK/site.log" 2>&1 &
SITE_PID=$!
PIDS+=($SITE_PID)
# OpenSees does not retry: connecting before the server listens kills it (segfault).
PORT=""
for _ in $(seq 300); do
  # (the log may not exist yet: the background shell opens it)
  PORT=$(sed -n "s/^rpsd site-server: .* listening on $B:\([0-9]*\) for .*/\1/p" "$WORK/site.log" 2>/dev/null || true)
  [ -n "$PORT" ] && break
  kill -0 $SITE_PID 2>/dev/null || break
  sleep 0.1
done
[ -n "$PORT" ] || fail "the site server did not start listening on $B: $(cat "$WORK/site.log")"

# Host A: OpenSees. If the server dropped the connection OpenSees would spin forever: timeout.
rc=0
ip netns exec "$NS_A" timeout 90 "$OPENSEES" "$SRC/examples/opensees/sdof-generic-client.tcl" "$WORK/client" "$RECORD" \
  $SCALE $DURATION "$PORT" $B > "$WORK/opensees.log" 2>&1 || rc=$?
[ $rc -eq 0 ] || fail "OpenSees on host A exited $rc: $(tail -5 "$WORK/opensees.log")"
rc=0
wait $SITE_PID || rc=$?
[ $rc -eq 0 ] || fail "the site server exited $rc: $(tail -5 "$WORK/site.log")"
kill -TERM $NODE_PID
rc=0
wait $NODE_PID || rc=$?
[ $rc -eq 0 ] || fail "the servo node exited $rc after SIGTERM: $(tail -5 "$WORK/node.log")"

summary=$WORK/site/summary.json
[ "$(json "$summary" "j['outcome']")" = completed ] || fail "site server outcome $(json "$summary" "j['outcome']")"
peer=$(json "$summary" "j['client']['peer']")
[ "${peer%:*}" = $A ] || fail "the site server's client was $peer, not OpenSees on host A ($A)"
exchanges=$(json "$summary" "j['exchanges']")
[ "$exchanges" -gt 5000 ] || fail "only $exchanges exchanges for $DURATION s at 1024 Hz"
grep -q "$exchanges commands applied, 0 dropped" "$WORK/node.log" \
  || fail "the node did not apply the site server's $exchanges commands: $(tail -2 "$WORK/node.log")"
# Every exchange is a command to C and its feedback back to B: at least one packet each way.
tcp_packets=$(counted "$NS_A") udp_packets=$(counted "$NS_C")
[ "$tcp_packets" -ge "$exchanges" ] || fail "only $tcp_packets TCP packets from A to B for $exchanges exchanges"
[ "$udp_packets" -ge "$exchanges" ] || fail "only $udp_packets UDP packets from C to B for $exchanges exchanges"

# The reference: the same model with the spring as a plain element, all in OpenSees, here.
"$OPENSEES" "$SRC/examples/opensees/sdof-reference.tcl" "$WORK/reference" "$RECORD" $SCALE $DURATION \
  > "$WORK/reference.log" 2>&1 || fail "sdof-reference.tcl failed: $(tail -5 "$WORK/reference.log")"
python3 - "$WORK/client/displacement.out" "$WORK/reference/displacement.out" <<'PY' || fail "OpenSees' displacements differ from the reference"
import sys
rows = [[list(map(float, line.split())) for line in open(f) if line.strip()] for f in sys.argv[1:3]]
client, reference = rows
assert len(client) == len(reference) > 5000, f"{len(client)} client rows, {len(reference)} reference rows"
peak = max(abs(r[1]) for r in reference)
worst = max(abs(c[1] - r[1]) for c, r in zip(client, reference))
assert all(c[0] == r[0] for c, r in zip(client, reference)), "the time columns differ"
assert worst <= 1e-9 * peak, f"worst difference {worst:.3e} m, peak {peak:.6e} m"
print(f"{len(client)} steps, peak {peak * 1e3:.4f} mm, worst difference {worst:.3e} m")
PY
echo "PASS: OpenSees on $A, site server on $B:$PORT, servo node on $C: $exchanges exchanges ($tcp_packets TCP packets" \
  "A->B, $udp_packets UDP packets C->B), displacements equal sdof-reference.tcl's"
