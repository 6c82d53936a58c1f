#!/usr/bin/env bash
# A full disk does not pass for success: on a 1 MB tmpfs a 600 s synthetic record fills the
# disk within seconds. The run must stop with exit 5, name the file and the reason, and leave
# a summary.json that says the results are not whole (written over the space reserved for it
# when the run began), never a 0-byte summary or "completed".
source "$(dirname "$0")/lib.sh"
[ "$(id -u)" = 0 ] || { echo "SKIPPED: mounting a tmpfs needs root"; exit 77; }
disk="$WORK/disk"
mkdir -p "$disk"
mount -t tmpfs -o size=1m tmpfs "$disk"
NETNS_CLEANUP="umount '$disk'"

set +e
"$RPSD" run "$SRC/examples/scenarios/synthetic-sdof.yaml" --out "$disk/run" \
  --set ground_motion.synthetic.duration_s=600 >"$WORK/out.txt" 2>&1
code=$?
set -e
cat "$WORK/out.txt"
[ "$code" = 5 ] || fail "exit $code, expected 5"
grep -q "time_history.csv: No space left on device" "$WORK/out.txt" || fail "the reason is not printed"
python3 - "$disk/run/summary.json" <<'PY' || fail "summary.json does not say the results are not whole"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["result"] == "results_not_written", s["result"]
assert s["completed"] is False
assert "No space left on device" in s["outcome"], s["outcome"]
assert s["steps"] > 0
PY
echo "PASS: full disk -> exit 5, summary says results_not_written"
