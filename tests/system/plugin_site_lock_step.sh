#!/usr/bin/env bash
# A whole earthquake test in lock-step against a NEES/LabVIEW plugin site: the shipped plugin
# site emulator, `rpsd servo-node` on the shipped nees_plugin node file and `rpsd run` on the
# shipped scenario, as separate processes over TCP and DDS on loopback. The run completes,
# every step recorded, equal to the same test run in one process to the wire's 11 digits; the
# node proposed, executed and read each step once and closed its session at its end.
source "$(dirname "$0")/plugin_lib.sh"
start_plugin_site
start_plugin_node
run_plugin_test "$WORK/plugin"
[ "$RUN_EXIT" = 0 ] || fail "rpsd run exited $RUN_EXIT: $(tail -3 "$WORK/plugin.log")"
[ "$(json "$WORK/plugin/summary.json" "j['result']")" = completed ] || fail "not completed"
every_step_recorded "$WORK/plugin"
steps=$(json "$WORK/plugin/summary.json" "j['steps']")
[ "$steps" = 1000 ] || fail "$steps steps, not the 1000 of 10 s at 100 Hz"
run_plugin_test "$WORK/local" --set transport.kind=in_process
[ "$RUN_EXIT" = 0 ] || fail "the in-process run exited $RUN_EXIT"
python3 - "$WORK/plugin/time_history.csv" "$WORK/local/time_history.csv" <<'PY' || fail "the plugin site run differs from the in-process one"
import csv, sys
a = list(csv.DictReader(open(sys.argv[1])))
b = list(csv.DictReader(open(sys.argv[2])))
assert len(a) == len(b) == 1000
worst = max(abs(float(x["measured_m_ch0"]) - float(y["measured_m_ch0"])) for x, y in zip(a, b))
peak = max(abs(float(y["measured_m_ch0"])) for y in b)
assert peak > 0.005, peak                 # the test moved the specimen (10.5 mm)
assert worst < 1e-9, worst                # %.10E in mm: 11 digits
print(f"peak {peak * 1e3:.3f} mm, largest difference {worst:.2e} m")
PY
stop $NODE_PID
stop $SITE_PID
link="j['plugin_link']"
[ "$(json "$WORK/node.json" "$link['steps']")" = 1001 ] || fail "node: $(json "$WORK/node.json" "$link['steps']") steps, not the start's and 1000"
[ "$(json "$WORK/node.json" "$link['failed_side']")" = none ] || fail "node: the link failed: $(json "$WORK/node.json" "$link")"
[ "$(json "$WORK/node.json" "j['faulted']")" = False ] || fail "node faulted"
[ "$(json "$WORK/site.json" "j['executes']")" = 1001 ] || fail "site: $(json "$WORK/site.json" "j['executes']") executes"
[ "$(json "$WORK/site.json" "j['closed_sessions']")" = 1 ] || fail "site: the node did not close its session"
[ "$(json "$WORK/site.json" "j['refused_proposals']")" = 0 ] || fail "site refused a proposal"
echo "PASS: 1000 steps over the plugin site, 1001 transactions"
