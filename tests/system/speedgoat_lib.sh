# What the Speedgoat system tests share (sourced after lib.sh): one earthquake test through
# OpenFresco's Speedgoat handshake with the example files.
#   speedgoat_run NAME TRANSPORT "TARGET --set ..." "NODE --set ..." [rpsd run options...]
# starts `rpsd speedgoat-emulator` on examples/nodes/speedgoat-target-emulator.yaml and
# `rpsd servo-node` on examples/nodes/speedgoat-node.yaml (over TRANSPORT, on a free port),
# runs examples/scenarios/speedgoat-sdof.yaml into $WORK/NAME (a hang guard of 300 s), stops
# both (their summaries: $WORK/NAME.target.json, $WORK/NAME.node.json), prints the three
# logs and leaves rpsd run's exit code in RUN_CODE.
speedgoat_run() {
  local name=$1 transport=$2 target_sets=$3 node_sets=$4
  shift 4
  local kind=STREAM
  [ "$transport" = udp ] && kind=DGRAM
  local port target attempt
  # A port free a moment ago may be taken before the emulator binds it (it takes no port 0):
  # then its process ends, and another free port is tried, three times at most.
  for attempt in 1 2 3; do
    port=$(python3 -c "import socket; s = socket.socket(socket.AF_INET, socket.SOCK_$kind); s.bind(('127.0.0.1', 0)); print(s.getsockname()[1])")
    # shellcheck disable=SC2086 # the --set lists split into words
    "$RPSD" speedgoat-emulator "$SRC/examples/nodes/speedgoat-target-emulator.yaml" --set target.transport=$transport \
      --set target.port=$port $target_sets --summary "$WORK/$name.target.json" > "$WORK/$name.target.log" 2>&1 &
    target=$!
    PIDS+=($target)
    for _ in $(seq 100); do
      grep -q "serving node" "$WORK/$name.target.log" && break
      kill -0 $target 2>/dev/null || break
      sleep 0.1
    done
    grep -q "serving node" "$WORK/$name.target.log" && break
    echo "speedgoat_lib.sh: attempt $attempt: the emulator did not start on port $port:" >&2
    cat "$WORK/$name.target.log" >&2
  done
  # shellcheck disable=SC2086
  "$RPSD" servo-node "$SRC/examples/nodes/speedgoat-node.yaml" --set dds.domain_id=$DOMAIN \
    --set actuator.transport=$transport --set actuator.port=$port $node_sets \
    --summary "$WORK/$name.node.json" > "$WORK/$name.node.log" 2>&1 &
  local node=$!
  PIDS+=($node)
  for _ in $(seq 100); do grep -q "Speedgoat target" "$WORK/$name.node.log" && break; sleep 0.1; done
  RUN_CODE=0
  timeout 300 "$RPSD" run "$SRC/examples/scenarios/speedgoat-sdof.yaml" --out "$WORK/$name" \
    --set transport.domain_id=$DOMAIN "$@" > "$WORK/$name.run.log" 2>&1 || RUN_CODE=$?
  kill -TERM $node 2>/dev/null || true
  wait $node || true
  kill -TERM $target 2>/dev/null || true
  wait $target || true
  cat "$WORK/$name.target.log" "$WORK/$name.node.log" "$WORK/$name.run.log"
}
