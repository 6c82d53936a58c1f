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
stopped_on_the_nodes_fault "$WORK/plugin"
steps=$(json "$WORK/plugin/summary.json" "j['steps']")
[ "$steps" -ge 299 ] && [ "$steps" -le 300 ] || fail "stopped after $steps steps, not at step 300"
stop $NODE_PID
stop $SITE_PID
the_site_failed no_answer_in_time propose
[ "$(json "$WORK/node.json" "j['plugin_link']['steps']")" = 300 ] || fail "node: not the start's and 299 steps"
[ "$(json "$WORK/plugin/summary.json" "j['stopped_by']['node_says']")" = "site 1: plugin site no_answer_in_time at propose" ] \
  || fail "the test's summary.json does not say what failed: stopped_by $(json "$WORK/plugin/summary.json" "j['stopped_by']")"
[ "$(json "$WORK/site.json" "j['executes']")" = 300 ] || fail "site: $(json "$WORK/site.json" "j['executes']") executes"
[ "$(json "$WORK/site.json" "j['unanswered'] >= 1")" = True ] || fail "site: nothing left unanswered"
echo "PASS: stopped after $steps steps on the node's fault; the site executed 300"
