#!/usr/bin/env bash
# Two tests at once on one DDS domain, without DDS Security: test 7 (1 s of record) and
# test 8 (0.5 s), each with its own two lock-step nodes. The test id partitions
# (rpsd/test-<id>/site-<id>) keep them apart: every node accepts exactly its own
# coordinator's commands and no other command even reaches it (no drop for a wrong test
# id), and each coordinator receives exactly its own nodes' feedback.
source "$(dirname "$0")/lib.sh"

# plain_node TAG TEST SITE: a lock-step bridge node of test TEST (loopback configuration).
plain_node() {
  local tag=$1 test=$2 site=$3
  "$RPSD" servo-node "$SRC/examples/nodes/bridge-pier-site-$site.yaml" --set node.mode=lock_step \
    --set node.test_id=$test --set dds.domain_id=$DOMAIN --summary "$WORK/$tag.json" > "$WORK/$tag.log" 2>&1 &
  PIDS+=($!)
  NODES+=($!)
}
NODES=()
plain_node t7s1 7 1
plain_node t7s2 7 2
plain_node t8s1 8 1
plain_node t8s2 8 2
sleep 0.5
run_bridge "$WORK/t7" --set transport.kind=dds --set transport.test_id=7 --set "ground_motion.trim={end_s: 1}" \
  > "$WORK/t7.log" 2>&1 &
run7=$!
run_bridge "$WORK/t8" --set transport.kind=dds --set transport.test_id=8 --set "ground_motion.trim={end_s: 0.5}" \
  > "$WORK/t8.log" 2>&1 &
run8=$!
wait $run7 || fail "test 7 failed: $(cat "$WORK/t7.log")"
wait $run8 || fail "test 8 failed: $(cat "$WORK/t8.log")"
kill -TERM "${NODES[@]}"
for pid in "${NODES[@]}"; do wait "$pid" || fail "a node exited with $?"; done

python3 - "$WORK" <<'PY' || fail "the two tests were not kept apart"
import json, sys
w = sys.argv[1]
steps = {}
for test in (7, 8):
    run = json.load(open(f"{w}/t{test}/summary.json"))
    steps[test] = run["steps"]
    if not run["completed"] or run["steps"] != run["steps_planned"]:
        sys.exit(f"test {test} did not complete: {run['steps']} of {run['steps_planned']} steps")
    for site in run["timing"]["sites"]:
        m = site["messages"]
        if m["sent"] != run["steps"] or m["received"] != run["steps"] or m["dropped_wrong_test_or_site"] != 0:
            sys.exit(f"test {test} site {site['site_id']}: {m}")
if steps[7] == steps[8]:
    sys.exit("the two tests must differ in length to tell their commands apart")
for test in (7, 8):
    for site in (1, 2):
        node = json.load(open(f"{w}/t{test}s{site}.json"))
        if node["test_id"] != test or node["commands_accepted"] != steps[test]:
            sys.exit(f"node of test {node['test_id']} site {site}: {node['commands_accepted']} commands accepted, "
                     f"test {test} sent {steps[test]}")
        if sum(node["commands_dropped"].values()) != 0:
            sys.exit(f"node of test {test} site {site} received foreign commands: {node['commands_dropped']}")
print(f"PASS: test 7 ({steps[7]} steps) and test 8 ({steps[8]} steps) ran at once on one domain; "
      "each node accepted exactly its own test's commands and dropped none")
PY
