#!/usr/bin/env bash
# Operator commands under the DDS Security profile (docs/operator-commands.md, docs/dds-security.md)
# on loopback: the two-site bridge runs lock-step with its nodes under the lab's identities, its
# scenario not enabling operator commands (with security on, the permissions decide). The lab's
# operator holds it (so that it cannot end on its own meanwhile); then none of these can stop it:
#   - the lab's monitor identity (read-only grant): refused at once, exit 7, by its own permissions;
#   - an operator identity of another lab (a stranger's CA): never authenticated, no answer, exit 8;
#   - a participant without security (the plain loopback configuration): no answer, exit 8;
# the test is still there and carries on when the operator resumes it. The lab's operator then
# stops it: exit 0 for `rpsd stop`, exit 3 for the run, summary.json operator_stop naming the
# operator, and the coordinator heard no command but the operator's.
source "$(dirname "$0")/lib.sh"

skip() { echo "SKIP: $*"; exit 77; }
command -v openssl > /dev/null || skip "openssl not found"
for plugin in auth ac crypto; do
  compgen -G "/usr/lib/*/libddsc0debian/libdds_security_$plugin.so" > /dev/null \
    || ldconfig -p | grep -q "libdds_security_$plugin.so" \
    || skip "Cyclone DDS security plugin libdds_security_$plugin.so not installed (Debian: libddsc0debian)"
done

LAB=$WORK/lab
ROGUE=$WORK/rogue
bash "$SRC/scripts/make-lab-ca.sh" --lab "rogue lab" "$ROGUE" > "$WORK/rogue.log" 2>&1 \
  || fail "make-lab-ca.sh (rogue lab) failed: $(cat "$WORK/rogue.log")"
bash "$SRC/scripts/make-lab-ca.sh" "$LAB" > "$WORK/lab.log" 2>&1 || fail "make-lab-ca.sh failed: $(cat "$WORK/lab.log")"
[ -f "$LAB/identities/operator/permissions.p7s" ] || fail "make-lab-ca.sh made no operator identity"
grep -q "rpsd_OperatorCommand" "$LAB/identities/monitor/permissions.xml" \
  && fail "the monitor's grant names the operator command topic"
SECURE=$SRC/transport/config/security/loopback-secure.xml
TEST_ID=$(( 500 + $$ % 200 ))

for site in 1 2; do
  env RPSD_DDS_SECURITY_DIR="$LAB" RPSD_DDS_IDENTITY=node-site-$site \
    "$RPSD" servo-node "$SRC/examples/nodes/bridge-pier-site-$site.yaml" --set node.mode=lock_step \
    --set node.test_id=$TEST_ID --set dds.domain_id=$DOMAIN --set dds.config="$SECURE" \
    --summary "$WORK/node$site.json" > "$WORK/node$site.log" 2>&1 &
  PIDS+=($!)
  eval "NODE${site}_PID=$!"
done
env RPSD_DDS_SECURITY_DIR="$LAB" RPSD_DDS_IDENTITY=coordinator \
  "$RPSD" run "$SRC/examples/scenarios/two-site-bridge.yaml" --out "$WORK/dds" --set transport.kind=dds \
  --set transport.domain_id=$DOMAIN --set transport.test_id=$TEST_ID --set transport.dds_config="$SECURE" \
  --set "ground_motion.trim={end_s: 30}" > "$WORK/dds.log" 2>&1 &
RUN_PID=$!
PIDS+=($RUN_PID)

# stop_as NAME DIR IDENTITY CONFIG [rpsd stop options]: rpsd stop with an identity; its exit code.
stop_as() {
  local name=$1 dir=$2 identity=$3 config=$4; shift 4
  set +e
  env RPSD_DDS_SECURITY_DIR="$dir" RPSD_DDS_IDENTITY="$identity" "$RPSD" stop --test-id $TEST_ID --domain $DOMAIN \
    --dds-config "$config" --sender "$name" "$@" > "$WORK/$name.out" 2>&1
  echo $?
  set -e
}
rows() { cat "$WORK/dds/time_history.csv" 2>/dev/null | wc -l; }

wait_for_rows "$WORK/dds/time_history.csv" 200 $RUN_PID
kill -0 $RUN_PID 2>/dev/null || fail "the secured run ended before the first command: $(cat "$WORK/dds.log")"
code=$(stop_as lab-operator "$LAB" operator "$SECURE" --hold --timeout 20)
[ "$code" = 0 ] || fail "the lab's operator could not hold the test: exit $code: $(cat "$WORK/lab-operator.out")"
code=$(stop_as monitor "$LAB" monitor "$SECURE" --timeout 5)
[ "$code" = 7 ] || fail "the monitor identity: exit $code, expected 7: $(cat "$WORK/monitor.out")"
grep -q "DDS Security does not let this identity send operator commands" "$WORK/monitor.out" \
  || fail "the monitor's refusal does not say why: $(cat "$WORK/monitor.out")"
code=$(stop_as stranger "$ROGUE" operator "$SECURE" --timeout 5)
[ "$code" = 8 ] || fail "a stranger's operator identity: exit $code, expected 8: $(cat "$WORK/stranger.out")"
code=$(stop_as plain "$LAB" none "$SRC/transport/config/loopback.xml" --timeout 3)
[ "$code" = 8 ] || fail "a participant without security: exit $code, expected 8: $(cat "$WORK/plain.out")"
kill -0 $RUN_PID 2>/dev/null || fail "the held run ended: $(cat "$WORK/dds.log")"
code=$(stop_as lab-operator "$LAB" operator "$SECURE" --resume --timeout 20)
[ "$code" = 0 ] || fail "the lab's operator could not resume the test: exit $code: $(cat "$WORK/lab-operator.out")"
before=$(rows)
wait_for_rows "$WORK/dds/time_history.csv" $((before + 200)) $RUN_PID
kill -0 $RUN_PID 2>/dev/null || fail "the run did not carry on after the refused commands: $(cat "$WORK/dds.log")"
code=$(stop_as lab-operator "$LAB" operator "$SECURE" --timeout 20)
[ "$code" = 0 ] || fail "the lab's operator: exit $code, expected 0: $(cat "$WORK/lab-operator.out")"
set +e
wait $RUN_PID
code=$?
set -e
[ $code -eq 3 ] || fail "the stopped run exited $code, expected 3: $(cat "$WORK/dds.log")"
every_step_recorded "$WORK/dds"
kill -TERM $NODE1_PID $NODE2_PID
wait $NODE1_PID $NODE2_PID || fail "a node failed: $(cat "$WORK/node1.log" "$WORK/node2.log")"
python3 - "$WORK" <<'PY' || fail "the secured run's operator record is wrong"
import json, sys
w = sys.argv[1]
run = json.load(open(f"{w}/dds/summary.json"))
s = run["stopped_by"]
assert s["kind"] == "operator_stop" and s["operator"]["sender"] == "lab-operator", s
heard = [(c["sender"], c["action"], c["status"]) for c in run["operator_commands"]]
assert heard == [("lab-operator", a, "done") for a in ("hold", "resume", "stop")], heard
for site in (1, 2):
    node = json.load(open(f"{w}/node{site}.json"))
    assert node["commands_accepted"] == run["steps"], (site, node["commands_accepted"], run["steps"])
print(f"PASS: the monitor (exit 7), a stranger's operator and a plain participant (exit 8) could not stop the "
      f"secured test; the lab's operator held, resumed and stopped it after step {run['steps']} of "
      f"{run['steps_planned']} (exit 3)")
PY
