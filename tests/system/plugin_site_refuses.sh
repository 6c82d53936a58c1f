#!/usr/bin/env bash
# A plugin site that refuses a proposal mid-test stops the test, and says so in its own words:
# the shipped emulator with its limits narrowed to +/-5 mm (the test peaks at 10.5 mm). The
# node latches a fault and keeps the site's refusal; `rpsd run` stops (exit 3), it does not
# hang, with every step it took recorded and none beyond the site's limit; the node's summary
# says the site failed and quotes it, and so does the test's own summary.json (stopped_by.node_says,
# from the node's heartbeat).
source "$(dirname "$0")/plugin_lib.sh"
start_plugin_site --set "plugin_site.control_points=[{name: MDL-00-01, dofs: [{axis: x, limits: [-5, 5], displacement_per_si: 1000, force_per_si: 0.001}]}]"
start_plugin_node
run_plugin_test "$WORK/plugin"
stopped_on_the_nodes_fault "$WORK/plugin"
[ "$(column "$WORK/plugin" measured_m_ch0 "max(abs(x) for x in v) <= 0.005")" = True ] \
  || fail "a measurement beyond the site's 5 mm: $(column "$WORK/plugin" measured_m_ch0 "max(abs(x) for x in v)")"
stop $NODE_PID
stop $SITE_PID
the_site_failed refused propose
words=$(json "$WORK/node.json" "j['plugin_link']['site_message']")
case "$words" in
  ERROR*"MDL-00-01 x displacement "*" is beyond the site's limit "*"5.0000000000E+00 (limits -5.0000000000E+00 to 5.0000000000E+00)") ;;
  *) fail "the site's words are not kept: $words" ;;
esac
[ "$words" = "$(json "$WORK/site.json" "j['last_refusal']")" ] || fail "not the site's words verbatim: $words"
says=$(json "$WORK/plugin/summary.json" "j['stopped_by']['node_says']")
case "$says" in
  "site 1: plugin site refused at propose: ERROR "*"MDL-00-01 x displacement "*" is beyond the site's limit "*) ;;
  *) fail "the test's summary.json does not give the site's words: stopped_by $(json "$WORK/plugin/summary.json" "j['stopped_by']")" ;;
esac
[ "$(json "$WORK/site.json" "j['refused_proposals']")" = 1 ] || fail "site: $(json "$WORK/site.json" "j['refused_proposals']") refused"
echo "PASS: stopped after $(json "$WORK/plugin/summary.json" "j['steps']") steps; the site said: $words"
