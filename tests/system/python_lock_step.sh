#!/usr/bin/env bash
# rpsd.run from Python over DDS: the coordinator in a Python process, the two bridge pier nodes
# as processes of their own on loopback, lock-step. The Python run equals the command line's
# in-process run bit for bit, says it ran over DDS, and hands Python every step it recorded.
source "$(dirname "$0")/lib.sh"
PYTHON=${RPSD_PYTHON:?the Python the rpsd module is built for}
export PYTHONPATH=${RPSD_PYTHONPATH:?the folder holding the built rpsd package}
start_node 1 lock_step
start_node 2 lock_step
"$PYTHON" - "$SRC/examples/scenarios/two-site-bridge.yaml" "$WORK/python" "$DOMAIN" <<'PY' || fail "the Python run over DDS failed"
import csv, sys
import rpsd
scenario, out, domain = sys.argv[1], sys.argv[2], int(sys.argv[3])
r = rpsd.run(scenario, out=out, overrides={"transport.kind": "dds", "transport.domain_id": domain}, format="csv")
assert r.summary["timing"]["over_dds"] is True, "not over DDS"
with open(f"{out}/time_history.csv") as f:
    rows = list(csv.DictReader(f))
measured = r.test["measured_m_ch0"]
assert len(measured) == len(rows) > 0, (len(measured), len(rows))
assert all(float(row["measured_m_ch0"]) == m for row, m in zip(rows, measured)), "arrays differ from the CSV"
print(f"python: {len(rows)} steps over DDS")
PY
run_bridge "$WORK/local"
cmp <(cut -d, -f1-30 "$WORK/python/time_history.csv") <(cut -d, -f1-30 "$WORK/local/time_history.csv") \
  || fail "the Python run over DDS differs from the in-process run"
for s in 0 1; do
  [ "$(json "$WORK/python/summary.json" "j['timing']['sites'][$s]['messages']['late']")" = 0 ] || fail "late feedback in lock-step"
done
echo "PASS: $(wc -l < "$WORK/python/time_history.csv") rows identical to the in-process run"
