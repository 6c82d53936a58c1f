#!/usr/bin/env bash
# A servo node at a very slow control rate still stops when asked. Its loop wakes at least
# every 50 ms to look at the stop flag and the duration, whatever the period (before, a node
# at 1e-300 Hz ignored SIGTERM, SIGINT and --duration: only SIGKILL ended it).
# 1. 1e-300 Hz: refused when the node starts (exit 2, naming control_rate_hz): its watchdog's
#    timeout, command_timeout_periods control periods, would be beyond any bound (10 s).
# 2. 0.1 Hz with a watchdog of one period (10 s, within the bound): the first tick is 20 s
#    away, yet the node stops on SIGTERM and on SIGINT (real time and lock-step) and after
#    --duration 1, each within a hang bound of 10 s (`timeout`), exit 0 with its summary.
source "$(dirname "$0")/lib.sh"
node_file="$SRC/examples/nodes/bridge-pier-site-1.yaml"
set +e
timeout 20 $RPSD servo-node "$node_file" --set node.control_rate_hz=1e-300 --set dds.domain_id=$DOMAIN \
  > "$WORK/tiny.log" 2>&1
code=$?
set -e
cat "$WORK/tiny.log"
[ $code = 2 ] || fail "1e-300 Hz: exit code $code, expected 2 (refused)"
grep -q "control_rate_hz" "$WORK/tiny.log" || fail "1e-300 Hz: the refusal does not name control_rate_hz"

# The slowest rate of 0.1 and 1 Hz the node file reader accepts (a range on control_rate_hz
# may exclude 0.1 Hz; the loop must stop whatever it is).
SLOW_HZ=
for rate in 0.1 1; do
  if timeout 30 $RPSD servo-node "$node_file" --set node.control_rate_hz=$rate --set watchdog.command_timeout_periods=1 \
    --set dds.domain_id=$DOMAIN --duration 0.01 > "$WORK/probe.log" 2>&1; then
    SLOW_HZ=$rate
    break
  fi
done
[ -n "$SLOW_HZ" ] || { cat "$WORK/probe.log"; fail "the node refuses 0.1 Hz and 1 Hz"; }
echo "slow rate: $SLOW_HZ Hz"

# slow_node TAG MODE ARGS...: a node at SLOW_HZ in the background, once it says it serves.
slow_node() {
  local tag=$1 mode=$2; shift 2
  timeout -s KILL 60 $RPSD servo-node "$node_file" --set node.control_rate_hz=$SLOW_HZ \
    --set watchdog.command_timeout_periods=1 --set node.mode=$mode --set dds.domain_id=$DOMAIN \
    --summary "$WORK/$tag.json" "$@" > "$WORK/$tag.log" 2>&1 &
  SLOW_PID=$!
  PIDS+=($SLOW_PID)
  for _ in $(seq 200); do grep -q "rpsd servo-node: test" "$WORK/$tag.log" 2>/dev/null && break; sleep 0.05; done
  grep -q "rpsd servo-node: test" "$WORK/$tag.log" || { cat "$WORK/$tag.log"; fail "$tag: the node did not start"; }
  sleep 0.5  # in its loop, waiting for a deadline 20 s away
}

# stopped_within TAG PID: PID ended within 10 s with exit 0 and wrote its summary.
stopped_within() {
  local tag=$1 pid=$2 code
  for _ in $(seq 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  kill -0 "$pid" 2>/dev/null && { kill -KILL "$pid"; fail "$tag: still running 10 s later"; }
  set +e
  wait "$pid"
  code=$?
  set -e
  [ $code = 0 ] || { cat "$WORK/$tag.log"; fail "$tag: exit code $code"; }
  [ -s "$WORK/$tag.json" ] || fail "$tag: no summary"
  echo "$tag: stopped, exit 0, $(json "$WORK/$tag.json" "j['ticks']") ticks"
}

for mode in real_time lock_step; do
  for signal in TERM INT; do
    slow_node "$mode-$signal" $mode
    kill -$signal $SLOW_PID
    stopped_within "$mode-$signal" $SLOW_PID
  done
done
slow_node duration real_time --duration 1
stopped_within duration $SLOW_PID
echo "PASS: a 1e-300 Hz node is refused at start; a $SLOW_HZ Hz node stops on SIGTERM, SIGINT and --duration"
