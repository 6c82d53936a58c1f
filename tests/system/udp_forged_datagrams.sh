#!/usr/bin/env bash
# The UDP controller link against another process on the host (issue 25). Before, a command
# with sequence 10^12 and x = 0.2 m and a query with sequence 0 from any local socket moved
# the emulated piston to 0.2 m (3 of 3 tries; the node only flagged a clamp).
# A servo node (real time, 200 Hz, no coordinator: it holds 0 m) drives `rpsd
# controller-emulator` over protocol version 2 with a shared key; meanwhile an intruder
# (udp_forge.py, its own process and socket) sends the emulator the reported datagrams three
# times, plus the command as a version 2 datagram with a made-up tag, and sends the node
# replies it never asked for. The emulator refuses every one as foreign and the piston stays at
# 0 m; the intruder gets no reply; the node counts the forged replies and does not fault.
# Then the same over version 1, which a file must ask for: both start lines warn that the link
# is unauthenticated, and the address check alone still refuses the intruder.
# And a key file that group or others may read: both commands exit 2 naming file and key.
# It runs in a network namespace of its own (own_netns.sh): its ports, picked by binding port 0
# and closing, were reachable on the host's loopback, and once a process outside the test sent
# the emulator 3 datagrams more than the intruder did (12 foreign, not 9).
source "$(dirname "$0")/own_netns.sh"
source "$(dirname "$0")/lib.sh"
FORGE="$(dirname "$0")/udp_forge.py"
read -r EMU_PORT NODE_PORT < <(python3 -c '
import socket
s = [socket.socket(socket.AF_INET, socket.SOCK_DGRAM) for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')
head -c 32 /dev/urandom > "$WORK/lab.key"
chmod 600 "$WORK/lab.key"

# write_files VERSION_LINES: the emulator's and the node's file in $WORK, with these link keys.
write_files() {
  cat > "$WORK/emulator.yaml" <<YAML
udp:
  bind_host: 127.0.0.1
  port: $EMU_PORT
  node_host: 127.0.0.1
  node_port: $NODE_PORT
$1
actuator:
  channels: 1
  servo: {kind: ideal_delay, delay_s: 0.002, rig: {stroke_m: 0.25, force_n: 1.0e6, velocity_m_per_s: 1.0}}
YAML
  cat > "$WORK/node.yaml" <<YAML
node: {test_id: 7, site_id: 1, mode: real_time, control_rate_hz: 200, lock_memory: false, fifo_priority: 0,
       keep_cpus_awake: false}
dds: {domain_id: $DOMAIN, config: $SRC/transport/config/loopback.xml}
actuator:
  kind: udp_controller
  channels: 1
  host: 127.0.0.1
  port: $EMU_PORT
  local_host: 127.0.0.1
  local_port: $NODE_PORT
  reply_timeout_s: 0.5
  max_missed_replies: 20
$1
  rig: {stroke_m: 0.25, force_n: 1.0e6, velocity_m_per_s: 1.0}
limits: {max_stroke_m: [0.05]}
YAML
}

# forged_run NAME: emulator and node serve while the intruder sends; results in $WORK/NAME.*.
forged_run() {
  local name=$1
  "$RPSD" controller-emulator "$WORK/emulator.yaml" --summary "$WORK/$name.emulator.json" > "$WORK/$name.emulator.log" 2>&1 &
  local emulator=$!
  PIDS+=($emulator)
  for _ in $(seq 100); do grep -q "taking datagrams from node" "$WORK/$name.emulator.log" && break; sleep 0.1; done
  "$RPSD" servo-node "$WORK/node.yaml" --duration 4 --summary "$WORK/$name.node.json" > "$WORK/$name.node.log" 2>&1 &
  local node=$!
  PIDS+=($node)
  for _ in $(seq 100); do grep -q "UDP controller" "$WORK/$name.node.log" && break; sleep 0.1; done
  sleep 0.5  # the node ticking
  python3 "$FORGE" --controller "127.0.0.1:$EMU_PORT" --node "127.0.0.1:$NODE_PORT" --tries 3 > "$WORK/$name.forge.json"
  wait $node || { cat "$WORK/$name.node.log"; fail "$name: the node exited with $?"; }
  kill -TERM $emulator
  wait $emulator || { cat "$WORK/$name.emulator.log"; fail "$name: the emulator exited with $?"; }
  cat "$WORK/$name.emulator.log" "$WORK/$name.node.log" "$WORK/$name.forge.json"
  python3 - "$WORK/$name" <<'PY' || fail "$name: a forged datagram was taken"
import json, sys
base = sys.argv[1]
emulator, node, forge = (json.load(open(f"{base}.{k}.json")) for k in ("emulator", "node", "forge"))
# 9 to the emulator, 6 to the node, no answer; each counts exactly what the intruder sent it.
assert forge["sent_to_controller"] == 9 and forge["sent_to_node"] == 6 and forge["replies"] == [], forge
assert emulator["foreign_datagrams"] == forge["sent_to_controller"], (emulator, forge)
assert emulator["sessions"] == 1 and emulator["commands_applied"] > 0, emulator  # the node's own
assert abs(emulator["position_m"][0]) < 1e-9, emulator["position_m"]  # held at 0 m, not 0.2 m
assert node["udp_link"]["foreign_datagrams"] == forge["sent_to_node"], (node["udp_link"], forge)
assert node["udp_link"]["missed_replies"] == 0 and not node["faulted"], node
assert node["limits"]["stroke"]["activations"] == 0, node["limits"]
print(f"PASS {base}: {emulator['foreign_datagrams']} forged datagrams refused by the emulator, "
      f"{node['udp_link']['foreign_datagrams']} by the node; piston at {emulator['position_m'][0]} m after "
      f"{emulator['commands_applied']} commands of the node")
PY
}

# A key that others may read is refused before anything binds a socket.
write_files "  key_file: lab.key"
chmod 644 "$WORK/lab.key"
for cmd in servo-node controller-emulator; do
  file=$([ $cmd = servo-node ] && echo node || echo emulator)
  key=$([ $cmd = servo-node ] && echo actuator.key_file || echo udp.key_file)
  code=0
  "$RPSD" $cmd "$WORK/$file.yaml" --duration 1 > "$WORK/open-key.log" 2>&1 || code=$?
  [ $code = 2 ] || { cat "$WORK/open-key.log"; fail "$cmd with a key others may read exited with $code, not 2"; }
  grep -q "$file\.yaml:[0-9]*:[0-9]*: $key: $WORK/lab.key: the key file's mode is 0644" "$WORK/open-key.log" \
    || { cat "$WORK/open-key.log"; fail "$cmd did not name the key file and its key"; }
done
chmod 600 "$WORK/lab.key"

forged_run v2
grep -q "protocol version 2 (HMAC-SHA-256" "$WORK/v2.node.log" || fail "the node does not say it authenticates"

write_files "  protocol_version: 1"
forged_run v1
grep -q "protocol version 1: WARNING: the link is unauthenticated" "$WORK/v1.node.log" || fail "the node did not warn"
grep -q "protocol version 1: WARNING: the link is unauthenticated" "$WORK/v1.emulator.log" || fail "the emulator did not warn"
echo "PASS: forged datagrams refused over protocol versions 2 and 1; an open key file refused (exit 2)"
