# A network namespace of the test's own, sourced before lib.sh: the script runs again inside a
# fresh, unnamed namespace (no other run can share it) with only its own loopback up, so no
# process outside the test can reach the ports it picks. Needs root (`unshare --net`); without
# it the test exits 77 (skipped) with a message.
if [ -z "${RPSD_OWN_NETNS:-}" ]; then
  if [ "$(id -u)" -ne 0 ]; then
    echo "SKIP: $(basename "$0") runs in a network namespace of its own, which needs root"
    exit 77
  fi
  RPSD_OWN_NETNS=1 exec unshare --net bash "$0" "$@"
fi
ip link set lo up
