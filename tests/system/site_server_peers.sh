#!/usr/bin/env bash
# Only the configured OpenSees hosts may command a site server's actuators. Three hosts in
# network namespaces on one switch (198.18.0.0/24): A (198.18.0.1) the lab's OpenSees host,
# B (198.18.0.2) the site server, C (198.18.0.3) another host on the network. genericClient
# has no authentication, so:
#  1. a site file that listens on B's LAN address without listen.allowed_clients is refused
#     when it is read (exit 2, naming listen.address), and nothing is written;
#  2. listening on every address (0.0.0.0) for A only, a genericClient on C that tries 3000
#     steps toward 50 mm is closed before any command, the server says so, and A's client is
#     then served to its end: `completed`, A's steps only, C named in summary.json.
# The clients are tests/site_server/generic_client.py. Needs root; otherwise exit 77 (skipped).
source "$(dirname "$0")/lib.sh"
trap 'exit 143' TERM
trap 'exit 130' INT
# The three hosts and their switch (netns.sh; it skips without root): A, B, C as .1, .2, .3.
source "$(dirname "$0")/netns.sh"
NS_A=$NS_COORD NS_B=$NS_SITE1 NS_C=$NS_SITE2
A=198.18.0.1 B=198.18.0.2 C=198.18.0.3
SITE=$SRC/examples/opensees/sdof-site-perfect.yaml
CLIENT=$SRC/tests/site_server/generic_client.py

# 1. B's LAN address and no allow-list: refused as the file is read.
rc=0
ip netns exec $NS_B $RPSD site-server "$SITE" --out "$WORK/open" --set listen.address=$B --set listen.port=0 \
  --set listen.accept_timeout_s=5 > "$WORK/open.log" 2>&1 || rc=$?
[ $rc -eq 2 ] || fail "a site server on $B without an allow-list exited $rc, not 2: $(tail -3 "$WORK/open.log")"
grep -q "listen.address: $B is not a loopback address" "$WORK/open.log" \
  || fail "the refusal does not name listen.address: $(tail -3 "$WORK/open.log")"
[ ! -e "$WORK/open" ] || fail "the refused server created its --out folder"

# 2. Every address of B, for A only.
ip netns exec $NS_B $RPSD site-server "$SITE" --out "$WORK/site" --set listen.address=0.0.0.0 \
  --set "listen.allowed_clients=[$A]" --set listen.port=0 --set listen.accept_timeout_s=60 > "$WORK/site.log" 2>&1 &
SITE_PID=$!
PIDS+=($SITE_PID)
PORT=""
for _ in $(seq 300); do
  PORT=$(sed -n "s/^rpsd site-server: .* listening on 0\.0\.0\.0:\([0-9]*\) for .*/\1/p" "$WORK/site.log" 2>/dev/null || true)
  [ -n "$PORT" ] && break
  kill -0 $SITE_PID 2>/dev/null || break
  sleep 0.1
done
[ -n "$PORT" ] || fail "the site server did not start listening: $(cat "$WORK/site.log")"
grep -q "listening on 0.0.0.0:$PORT for .*; clients allowed: $A\$" "$WORK/site.log" \
  || fail "the start line does not say who may connect: $(head -2 "$WORK/site.log")"

intruder=$(ip netns exec $NS_C timeout 60 python3 "$CLIENT" steps $B "$PORT" 3000 --displacement-m 0.05)
[ "${intruder%% (*}" = "steps 3000 answered 0 nan 0 closed 1" ] || fail "the client on C got: $intruder"
grep -q "refused a connection from $C:" "$WORK/site.log" || fail "the server did not name C: $(cat "$WORK/site.log")"
allowed=$(ip netns exec $NS_A timeout 60 python3 "$CLIENT" steps $B "$PORT" 200 --displacement-m 0.001)
[ "$allowed" = "steps 200 answered 200 nan 0 closed 0" ] || fail "the client on A got: $allowed"
rc=0
wait $SITE_PID || rc=$?
[ $rc -eq 0 ] || fail "the site server exited $rc: $(tail -3 "$WORK/site.log")"

summary=$WORK/site/summary.json
[ "$(json "$summary" "j['result']")" = completed ] || fail "result $(json "$summary" "j['result']")"
[ "$(json "$summary" "j['exchanges']")" = 200 ] || fail "$(json "$summary" "j['exchanges']") steps, not A's 200"
peer=$(json "$summary" "j['client']['peer']")
[ "${peer%:*}" = $A ] || fail "the client served was $peer, not A"
[ "$(json "$summary" "j['listen']['allowed_clients']")" = $A ] || fail "listen: $(json "$summary" "j['listen']")"
[ "$(json "$summary" "j['listen']['refused_connections']")" = 1 ] || fail "listen: $(json "$summary" "j['listen']")"
refused=$(json "$summary" "j['listen']['refused_peers'][0]")
[ "${refused%:*}" = $C ] || fail "the refused peer is $refused, not C"
peak=$(json "$summary" "j['channels'][0]['peak_measured_m']")
python3 -c "import sys; sys.exit(0 if $peak <= 0.001 + 1e-12 else 1)" \
  || fail "the actuator reached $peak m: more than A's 1 mm (C asked for 50 mm)"
echo "PASS: unprotected LAN address refused (exit 2); on 0.0.0.0 for $A only, $C was closed before any" \
  "command ($intruder), $A was served 200 steps (peak $peak m)"
