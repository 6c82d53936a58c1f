#!/usr/bin/env bash
# DDS Security profile (docs/dds-security.md) on loopback: a lab CA made at test time in the
# test's temporary folder (removed on exit). Servo nodes with valid identities ignore every
# coordinator that is not the lab's coordinator, and run the bridge lock-step with it:
#   1. no identity (the plain loopback configuration), an identity from another CA, a revoked
#      coordinator identity (with the revocation list from before), and the lab's monitor
#      identity with forged permissions (signed by another permissions CA, granting what a
#      coordinator has) never match the nodes: they exit 1 on discovery;
#   2. the lab's monitor identity with its real (read-only) permissions may not create the
#      command writer at all, and a site-1 node identity may not serve site 2;
#   3. the nodes accepted no command from any of them;
#   4. the lab's coordinator runs the test to the end with fresh nodes, under the profile;
#      on the wire (captured on lo), its RTPS messages carry no command or feedback sample
#      and no partition name in clear, while a plain run's do (the capture works).
source "$(dirname "$0")/lib.sh"

skip() { echo "SKIP: $*"; exit 77; }
command -v openssl > /dev/null || skip "openssl not found"
for plugin in auth ac crypto; do
  # Debian's libddsc0debian puts the plugins in a folder of their own, where Cyclone looks.
  compgen -G "/usr/lib/*/libddsc0debian/libdds_security_$plugin.so" > /dev/null \
    || ldconfig -p | grep -q "libdds_security_$plugin.so" \
    || skip "Cyclone DDS security plugin libdds_security_$plugin.so not installed (Debian: libddsc0debian)"
done

LAB=$WORK/lab
ROGUE=$WORK/rogue
bash "$SRC/scripts/make-lab-ca.sh" --lab "rogue lab" "$ROGUE" > "$WORK/rogue.log" 2>&1 &
rogue_ca=$!
# A second coordinator identity, revoked after its host kept the revocation list of before.
bash "$SRC/scripts/make-lab-ca.sh" --identity old-coordinator:coordinator "$LAB" > "$WORK/lab.log" 2>&1 \
  || fail "make-lab-ca.sh failed: $(cat "$WORK/lab.log")"
cp "$LAB/identity_ca.crl.pem" "$WORK/stale.crl.pem"
bash "$SRC/scripts/make-lab-ca.sh" --revoke old-coordinator "$LAB" > "$WORK/revoke.log" 2>&1 \
  || fail "make-lab-ca.sh --revoke failed: $(cat "$WORK/revoke.log")"
REVOKED=$(echo "$LAB"/revoked/old-coordinator-*)
[ -f "$REVOKED/identity_key.pem" ] || fail "no revoked identity in $LAB/revoked"
wait $rogue_ca || fail "make-lab-ca.sh (rogue lab) failed: $(cat "$WORK/rogue.log")"
SECURE_NODE=$SRC/transport/config/security/loopback-secure.xml
PLAIN=$SRC/transport/config/loopback.xml

# secure_node TAG SITE IDENTITY [extra --set ...]: a lock-step bridge node with a lab identity.
secure_node() {
  local tag=$1 site=$2 identity=$3; shift 3
  env RPSD_DDS_SECURITY_DIR="$LAB" RPSD_DDS_IDENTITY="$identity" \
    "$RPSD" servo-node "$SRC/examples/nodes/bridge-pier-site-$site.yaml" --set node.mode=lock_step \
    --set dds.domain_id=$DOMAIN --set dds.config="$SECURE_NODE" --summary "$WORK/$tag.json" "$@" > "$WORK/$tag.log" 2>&1 &
  PIDS+=($!)
  eval "${tag}_PID=$!"
}
# stop_nodes TAG...: SIGTERM to all, then wait for their summaries.
stop_nodes() {
  local tag pid
  for tag in "$@"; do eval "pid=\$${tag}_PID"; kill -TERM "$pid"; done
  for tag in "$@"; do
    eval "pid=\$${tag}_PID"
    wait "$pid" || fail "node $tag exited with $?: $(cat "$WORK/$tag.log")"
  done
}
# coordinator TAG CONFIG [env VAR=... ...] -- [extra --set ...]: the bridge, 1 s of record.
coordinator() {
  local tag=$1 config=$2; shift 2
  local vars=()
  while [ $# -gt 0 ] && [ "$1" != -- ]; do vars+=("$1"); shift; done
  [ $# -gt 0 ] && shift
  env "${vars[@]}" "$RPSD" run "$SRC/examples/scenarios/two-site-bridge.yaml" --out "$WORK/results-$tag" --set transport.kind=dds \
    --set transport.domain_id=$DOMAIN --set transport.dds_config="$config" --set "ground_motion.trim={end_s: 1}" "$@" \
    > "$WORK/$tag.log" 2>&1
}
# expect_refused TAG MESSAGE [EXIT]: the coordinator TAG exited EXIT (default 1) with MESSAGE and
# wrote no results. No node found before the first step is exit 4, not ready.
expect_refused() {
  local tag=$1 message=$2 expected=${3:-1} code
  code=$(cat "$WORK/$tag.code")
  [ "$code" = "$expected" ] || fail "$tag: exit code $code, expected $expected: $(cat "$WORK/$tag.log")"
  grep -qF "$message" "$WORK/$tag.log" || fail "$tag: no \"$message\" in: $(cat "$WORK/$tag.log")"
  [ ! -f "$WORK/results-$tag/time_history.csv" ] || fail "$tag: results written"
}

# sniff TAG: capture this domain's RTPS packets on lo (raw socket: root) in the background
# until $WORK/TAG.stop exists; $WORK/TAG.json then has counts of what was seen in clear.
sniff() {
  local tag=$1 low=$((7400 + 250 * DOMAIN))
  python3 - "$WORK/$tag" $low $((low + 250)) <<'PY' &
import collections, json, os, select, socket, sys
out, low, high = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
seen = collections.Counter()
try:
    s = socket.socket(socket.AF_PACKET, socket.SOCK_RAW, socket.htons(3))  # ETH_P_ALL
    s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 8 << 20)
    s.bind(("lo", 0))
except OSError as e:
    json.dump({"error": str(e)}, open(out + ".json", "w"))
    open(out + ".ready", "w").close()
    sys.exit(0)
open(out + ".ready", "w").close()
# A Command or Feedback of test 7, site 1 or 2, as Cyclone serialises it: CDR little-endian
# encapsulation (00 01 00 00), then test_id and site_id.
samples = [bytes.fromhex("0001000007000000%02x000000" % site) for site in (1, 2)]
while not os.path.exists(out + ".stop"):
    if not select.select([s], [], [], 0.05)[0]:
        continue
    frame, address = s.recvfrom(65535)
    if address[2] == socket.PACKET_OUTGOING or frame[12:14] != b"\x08\x00" or frame[23] != 17:
        continue  # each packet once (lo shows it leaving and arriving); IPv4 UDP only
    udp = 14 + (frame[14] & 15) * 4
    if not low <= int.from_bytes(frame[udp + 2:udp + 4], "big") < high:
        continue  # another domain
    rtps = frame[udp + 8:]
    if rtps[:4] != b"RTPS":
        continue
    seen["messages"] += 1
    seen["secure"] += rtps[20:21] == b"\x33"  # SRTPS_PREFIX: a protected RTPS message
    seen["samples"] += sum(rtps.count(m) for m in samples)
    seen["partitions"] += rtps.count(b"rpsd/test-7/site-")
json.dump(seen, open(out + ".json", "w"))
PY
  SNIFFER=$!
  PIDS+=($SNIFFER)
  for _ in $(seq 100); do [ -f "$WORK/$tag.ready" ] && return; sleep 0.1; done
  fail "the capture did not start"
}
sniffed() { touch "$WORK/$1.stop"; wait $SNIFFER; }

# Forged permissions: the monitor's subject with a coordinator's grant, signed by the rogue
# lab's permissions CA (with its governance), so that the monitor's own process accepts them.
subject=$(openssl x509 -in "$LAB/identities/monitor/identity.pem" -noout -subject -nameopt RFC2253 | sed 's/^subject=//')
sed "s|<subject_name>.*</subject_name>|<subject_name>$subject</subject_name>|" \
  "$LAB/identities/coordinator/permissions.xml" > "$WORK/forged.xml"
openssl smime -sign -text -in "$WORK/forged.xml" -out "$WORK/forged.p7s" \
  -signer "$ROGUE/permissions_ca.pem" -inkey "$ROGUE/ca-private/permissions_ca_key.pem"

# 1-3: nodes with valid identities, and coordinators that must not reach them.
secure_node n1 1 node-site-1
secure_node n2 2 node-site-2
sleep 0.5
refused=(--set transport.discovery_timeout_s=3)
attempts=()
( set +e; coordinator plain "$PLAIN" -- "${refused[@]}"; echo $? > "$WORK/plain.code" ) &
attempts+=($!)
( set +e; coordinator rogue "$SECURE_NODE" RPSD_DDS_SECURITY_DIR="$ROGUE" RPSD_DDS_IDENTITY=coordinator -- "${refused[@]}"
  echo $? > "$WORK/rogue.code" ) &
attempts+=($!)
( set +e; coordinator forged "$SECURE_NODE" RPSD_DDS_IDENTITY_CA="$LAB/identity_ca.pem" \
    RPSD_DDS_IDENTITY_CERT="$LAB/identities/monitor/identity.pem" RPSD_DDS_PRIVATE_KEY="$LAB/identities/monitor/identity_key.pem" \
    RPSD_DDS_IDENTITY_CRL="$LAB/identity_ca.crl.pem" \
    RPSD_DDS_PERMISSIONS_CA="$ROGUE/permissions_ca.pem" RPSD_DDS_GOVERNANCE="$ROGUE/governance.p7s" \
    RPSD_DDS_PERMISSIONS="$WORK/forged.p7s" -- "${refused[@]}"
  echo $? > "$WORK/forged.code" ) &
attempts+=($!)
( set +e; coordinator revoked "$SECURE_NODE" RPSD_DDS_SECURITY_DIR="$LAB" RPSD_DDS_IDENTITY=old-coordinator \
    RPSD_DDS_IDENTITY_CERT="$REVOKED/identity.pem" RPSD_DDS_PRIVATE_KEY="$REVOKED/identity_key.pem" \
    RPSD_DDS_PERMISSIONS="$REVOKED/permissions.p7s" RPSD_DDS_IDENTITY_CRL="$WORK/stale.crl.pem" -- "${refused[@]}"
  echo $? > "$WORK/revoked.code" ) &
attempts+=($!)
( set +e; coordinator monitor "$SECURE_NODE" RPSD_DDS_SECURITY_DIR="$LAB" RPSD_DDS_IDENTITY=monitor -- "${refused[@]}"
  echo $? > "$WORK/monitor.code" ) &
attempts+=($!)
# A site-1 identity standing in for site 2 (its own partition only): refused at start.
set +e
env RPSD_DDS_SECURITY_DIR="$LAB" RPSD_DDS_IDENTITY=node-site-1 "$RPSD" servo-node "$SRC/examples/nodes/bridge-pier-site-2.yaml" \
  --set node.mode=lock_step --set dds.domain_id=$DOMAIN --set dds.config="$SECURE_NODE" --duration 5 > "$WORK/wrong-site.log" 2>&1
code=$?
set -e
[ $code = 1 ] && grep -q "Not Allowed By Security" "$WORK/wrong-site.log" \
  || fail "a site-1 identity served site 2 (exit $code): $(cat "$WORK/wrong-site.log")"
wait "${attempts[@]}"

discovery="no servo node answered for site(s) 1, 2 of test 7"
expect_refused plain "$discovery" 4
expect_refused rogue "$discovery" 4
grep -q "Certificate not valid" "$WORK/rogue.log" || fail "rogue: no failed authentication reported: $(cat "$WORK/rogue.log")"
expect_refused forged "$discovery" 4
expect_refused revoked "$discovery" 4
expect_refused monitor "dds_create_writer: Not Allowed By Security"
# The nodes themselves turned the forged grant and the revoked certificate down (not only
# the coordinators' own checks).
for n in n1 n2; do
  grep -q "Could not get remote participant .* permissions" "$WORK/$n.log" \
    || fail "$n did not report the forged permissions: $(cat "$WORK/$n.log")"
  grep -q "certificate revoked; subject: /O=rpsd lab/OU=coordinator/CN=old-coordinator" "$WORK/$n.log" \
    || fail "$n did not report the revoked certificate: $(cat "$WORK/$n.log")"
done
stop_nodes n1 n2
python3 - "$WORK" <<'PY' || fail "a node heard a coordinator it must ignore"
import json, sys
for n in ("n1", "n2"):
    j = json.load(open(f"{sys.argv[1]}/{n}.json"))
    if j["commands_accepted"] != 0 or sum(j["commands_dropped"].values()) != 0:
        sys.exit(f"{n}: {j['commands_accepted']} commands accepted, dropped {j['commands_dropped']}")
PY

# 4: the lab's coordinator with fresh nodes: the whole (1 s) record, every command accepted,
# nothing readable on the wire. First a short plain run under the same capture, which must
# see the samples: the check of the secured run means something.
sniff wire-plain
for s in 1 2; do
  "$RPSD" servo-node "$SRC/examples/nodes/bridge-pier-site-$s.yaml" --set node.mode=lock_step \
    --set dds.domain_id=$DOMAIN --set dds.config="$PLAIN" > "$WORK/p$s.log" 2>&1 &
  PIDS+=($!)
  eval "p${s}_PID=$!"
done
sleep 0.5
coordinator clear "$PLAIN" -- --set "ground_motion.trim={end_s: 0.25}" || fail "plain run failed: $(cat "$WORK/clear.log")"
kill -TERM $p1_PID $p2_PID
wait $p1_PID $p2_PID || true
sniffed wire-plain
sniff wire-secure
secure_node s1 1 node-site-1
secure_node s2 2 node-site-2
sleep 0.5
coordinator secure "$SECURE_NODE" RPSD_DDS_SECURITY_DIR="$LAB" RPSD_DDS_IDENTITY=coordinator -- \
  --set transport.discovery_timeout_s=10 || fail "secure run failed: $(cat "$WORK/secure.log")"
stop_nodes s1 s2
sniffed wire-secure
python3 - "$WORK" <<'PY' || fail "the secured run is incomplete"
import json, sys
w = sys.argv[1]
run = json.load(open(f"{w}/results-secure/summary.json"))
rows = sum(1 for _ in open(f"{w}/results-secure/time_history.csv")) - 1
steps = run["steps"]
if steps != rows or steps < 1000:
    sys.exit(f"{steps} steps, {rows} rows recorded")
for s in (1, 2):
    node = json.load(open(f"{w}/s{s}.json"))
    if node["commands_accepted"] != steps:
        sys.exit(f"node {s} accepted {node['commands_accepted']} of {steps} commands")
    if run["timing"]["sites"][s - 1]["messages"]["late"] != 0:
        sys.exit(f"late feedback from site {s} in lock-step")
plain = json.load(open(f"{w}/wire-plain.json"))
secure = json.load(open(f"{w}/wire-secure.json"))
if "error" in secure:
    wire = f"wire not checked: no capture ({secure['error']})"
else:
    if plain.get("samples", 0) < 256 or plain.get("partitions", 0) == 0:
        sys.exit(f"the capture of the plain run missed its samples: {plain}")
    if secure.get("samples", 0) != 0 or secure.get("partitions", 0) != 0:
        sys.exit(f"the secured run showed samples or partitions in clear: {secure}")
    if secure.get("secure", 0) < steps:
        sys.exit(f"fewer protected RTPS messages than steps: {secure}")
    wire = (f"on the wire: {plain['samples']} samples in clear in the plain run, none of "
            f"{secure['messages']} messages of the secured run ({secure['secure']} protected)")
p50 = " / ".join("%.0f us" % (1e6 * t["round_trip"]["p50_s"]) for t in run["timing"]["sites"])
print(f"PASS: plain, rogue-CA, revoked and forged-permission coordinators found no node; the monitor and a wrong-site "
      f"node were refused; 0 commands accepted; the lab coordinator ran {steps} steps secured "
      f"(round trip p50 {p50}); {wire}")
PY
