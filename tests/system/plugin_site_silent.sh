#!/usr/bin/env bash
# A plugin site that stops answering mid-test: the shipped emulator falls silent after 300
# steps (the node's start and 299 of the test). The node waits its reply_timeout_s (here
# 2 s, within the scenario's 45 s feedback timeout), latches a fault and holds: `rpsd run`
# stops (exit 3) on the node's fault, not on silence, with every step recorded, and the
# node's summary says the site failed to answer a proposal.
source "$(dirname "$0")/plugin_lib.sh"
start_plugin_site --set "plugin_site.fault={kind: stop_answering, after_steps: 300}"
start_plugin_node --set actuator.reply_timeout_s=2
run_plugin_test "$WORK/plugin"
[ "$RUN_EXIT" = 3 ] || fail "rpsd run exited $RUN_EXIT, not 3: $(tail -3 "$WORK/plugin.log")"
grep -q "the servo node reported a fault" "$WORK/plugin.log" || fail "no reason: $(tail -3 "$WORK/plugin.log")"
s="$WORK/plugin/summary.json"
[ "$(json "$s" "j['stopped_by']['kind']")" = node_fault ] || fail "stopped by $(json "$s" "j['stopped_by']")"
every_step_recorded "$WORK/plugin"
steps=$(json "$s" "j['steps']")
[ "$steps" -ge 299 ] && [ "$steps" -le 300 ] || fail "stopped after $steps steps, not at step 300"
stop $NODE_PID
stop $SITE_PID
link="j['plugin_link']"
[ "$(json "$WORK/node.json" "j['faulted']")" = True ] || fail "the node did not fault"
[ "$(json "$WORK/node.json" "$link['failed_side']")" = site ] || fail "failed side: $(json "$WORK/node.json" "$link")"
[ "$(json "$WORK/node.json" "$link['failure']")" = no_answer_in_time ] || fail "failure: $(json "$WORK/node.json" "$link['failure']")"
[ "$(json "$WORK/node.json" "$link['failed_stage']")" = propose ] || fail "stage: $(json "$WORK/node.json" "$link['failed_stage']")"
[ "$(json "$WORK/node.json" "$link['steps']")" = 300 ] || fail "node: $(json "$WORK/node.json" "$link['steps']") steps"
[ "$(json "$WORK/site.json" "j['executes']")" = 300 ] || fail "site: $(json "$WORK/site.json" "j['executes']") executes"
[ "$(json "$WORK/site.json" "j['unanswered'] >= 1")" = True ] || fail "site: nothing left unanswered"
echo "PASS: stopped after $steps steps on the node's fault; the site executed 300"
