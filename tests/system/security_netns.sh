#!/usr/bin/env bash
# The DDS Security profile deployed as docs/dds-security.md says, across three hosts (network
# namespaces, tests/system/netns.sh) with transport/config/security/lab-lan-secure.xml: the
# CA machine (a folder) makes the material; the site-2 host makes its own key and sends only
# a certificate request; each host gets the shared public files and its own identity, never
# the CA keys. The secured two-site bridge (1 s of record, lock-step) equals the
# single-process run bit for bit.
source "$(dirname "$0")/lib.sh"
command -v openssl > /dev/null || { echo "SKIP: openssl not found"; exit 77; }
for plugin in auth ac crypto; do
  compgen -G "/usr/lib/*/libddsc0debian/libdds_security_$plugin.so" > /dev/null \
    || ldconfig -p | grep -q "libdds_security_$plugin.so" \
    || { echo "SKIP: Cyclone DDS security plugin libdds_security_$plugin.so not installed (Debian: libddsc0debian)"; exit 77; }
done
source "$(dirname "$0")/netns.sh"

CA=$WORK/ca-machine
# The site-2 host: its key stays there; the CA machine gets the request only.
mkdir -p "$WORK/host-site2/identities/node-site-2" "$CA/identities/node-site-2"
openssl genpkey -algorithm EC -pkeyopt ec_paramgen_curve:P-256 -out "$WORK/host-site2/identities/node-site-2/identity_key.pem" 2> /dev/null
openssl req -new -key "$WORK/host-site2/identities/node-site-2/identity_key.pem" -out "$CA/identities/node-site-2/identity.csr" \
  -subj "/O=rpsd lab/OU=node/CN=node-site-2"
bash "$SRC/scripts/make-lab-ca.sh" "$CA" > "$WORK/ca.log" 2>&1 || fail "make-lab-ca.sh failed: $(cat "$WORK/ca.log")"
[ ! -e "$CA/identities/node-site-2/identity_key.pem" ] || fail "the CA machine made a key for the site-2 host"

# deploy HOST IDENTITY: the shared public files and the host's own certificate and grant (and
# its key, where the CA machine made it).
deploy() {
  local host=$WORK/$1 name=$2
  mkdir -p "$host/identities/$name"
  cp "$CA/identity_ca.pem" "$CA/permissions_ca.pem" "$CA/identity_ca.crl.pem" "$CA/governance.p7s" "$host/"
  cp "$CA/identities/$name/identity.pem" "$CA/identities/$name/permissions.p7s" "$host/identities/$name/"
  [ -f "$host/identities/$name/identity_key.pem" ] || cp "$CA/identities/$name/identity_key.pem" "$host/identities/$name/"
}
deploy host-coordinator coordinator
deploy host-site1 node-site-1
deploy host-site2 node-site-2
CONFIG=$SRC/transport/config/security/lab-lan-secure.xml
# The nodes are started with `ip netns exec` itself, not through in_host (a shell function,
# so a subshell in the background): $! must be the node, for SIGTERM and its summary.
for site in 1 2; do
  ns_var=NS_SITE$site
  ip netns exec ${!ns_var} env RPSD_DDS_INTERFACE=eth0 RPSD_DDS_PEER_1=198.18.0.1 RPSD_DDS_PEER_2=198.18.0.2 \
    RPSD_DDS_PEER_3=198.18.0.3 RPSD_DDS_SECURITY_DIR="$WORK/host-site$site" RPSD_DDS_IDENTITY=node-site-$site \
    "$RPSD" servo-node "$SRC/examples/nodes/bridge-pier-site-$site.yaml" --set node.mode=lock_step \
    --set dds.config="$CONFIG" --summary "$WORK/node$site.json" > "$WORK/node$site.log" 2>&1 &
  PIDS+=($!)
  eval "NODE${site}_PID=$!"
done
trim=(--set "ground_motion.trim={end_s: 1}")
in_host $NS_COORD env RPSD_DDS_SECURITY_DIR="$WORK/host-coordinator" RPSD_DDS_IDENTITY=coordinator \
  "$RPSD" run "$SRC/examples/scenarios/two-site-bridge.yaml" --out "$WORK/dds" --set transport.kind=dds \
  --set transport.dds_config="$CONFIG" --set transport.discovery_timeout_s=10 "${trim[@]}" > "$WORK/dds.log" 2>&1 \
  || fail "the secured three-host run failed: $(cat "$WORK/dds.log")"
kill -TERM $NODE1_PID $NODE2_PID
wait $NODE1_PID $NODE2_PID || fail "a node failed: $(cat "$WORK/node1.log" "$WORK/node2.log")"
run_bridge "$WORK/local" "${trim[@]}" > /dev/null
cmp <(cut -d, -f1-30 "$WORK/dds/time_history.csv") <(cut -d, -f1-30 "$WORK/local/time_history.csv") \
  || fail "the secured three-host run differs from the in-process run"
python3 - "$WORK" <<'PY' || fail "the nodes did not follow every step"
import json, sys
w = sys.argv[1]
run = json.load(open(f"{w}/dds/summary.json"))
for site in (1, 2):
    node = json.load(open(f"{w}/node{site}.json"))
    if node["commands_accepted"] != run["steps"]:
        sys.exit(f"node {site} accepted {node['commands_accepted']} of {run['steps']} commands")
p50 = " / ".join("%.0f us" % (1e6 * s["round_trip"]["p50_s"]) for s in run["timing"]["sites"])
print(f"PASS: three hosts secured (site 2's key made on its host), {run['steps']} steps identical to one "
      f"process; round trip p50 {p50}")
PY
