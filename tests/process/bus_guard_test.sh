#!/usr/bin/env bash
# Who can reach the bus (docs/security.md). Two network namespaces joined
# by a veth pair stand for this host and another machine on its segment;
# the test makes them and removes them, and no datagram leaves them.
# In each case a fresh simpartner-sim (ttl=0, port 7667) runs in the
# "host" namespace and the "other machine" sends it a datagram on
# SIM_COMMAND to the multicast group (ttl=1) and one straight to the
# host's address; a process on the host itself sends one too. The sim
# reports the first bad message per channel, so each datagram is told
# apart by its size.
#   1. as shipped (ttl=0 only): both of the other machine's datagrams arrive;
#   2. scripts/bus-guard on: neither does, the host's own still does;
#   3. a multicast route on lo instead: the datagram to the host's address
#      still arrives (why the guard is what we ship); whether the group's
#      is kept out is printed, not asserted (here it was not);
#   4. sweep: a guard whose owner process is gone is removed, others stay.
#   bus_guard_test.sh SOURCE_DIR BINARY_DIR
set -euo pipefail
src=$1
bin=$2
if [[ $(id -u) -ne 0 ]]; then
  echo "FAIL: this test creates network namespaces and needs root" >&2
  exit 1
fi
tag=$$
ns_host=spg_host_$tag
ns_other=spg_other_$tag
veth_host=spg${tag}h
veth_other=spg${tag}o
net=10.213.$(( tag % 250 ))
work=$(mktemp -d)
sim_pid=
cleanup() {
  if [[ -n $sim_pid ]]; then kill "$sim_pid" 2>/dev/null || true; wait "$sim_pid" 2>/dev/null || true; fi
  ip netns del "$ns_host" 2>/dev/null || true
  ip netns del "$ns_other" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
in_host() { ip netns exec "$ns_host" "$@"; }
in_other() { ip netns exec "$ns_other" "$@"; }

if ! ip netns add "$ns_host" || ! ip netns add "$ns_other"; then
  echo "FAIL: cannot create network namespaces here (ip netns add refused)" >&2
  exit 1
fi
ip link add "$veth_host" type veth peer name "$veth_other"
ip link set "$veth_host" netns "$ns_host"
ip link set "$veth_other" netns "$ns_other"
in_host ip link set lo up
in_host ip addr add "$net.1/30" dev "$veth_host"
in_host ip link set "$veth_host" up
in_host ip route add 224.0.0.0/4 dev "$veth_host"
in_other ip link set lo up
in_other ip addr add "$net.2/30" dev "$veth_other"
in_other ip link set "$veth_other" up
in_other ip route add 224.0.0.0/4 dev "$veth_other"

# One LCM datagram (small-message header "LC02", sequence number, channel)
# carrying `size` bytes that are no command_t.
send() {  # send NAMESPACE-RUNNER DESTINATION SIZE
  local runner=$1 destination=$2 size=$3
  $runner python3 - "$destination" "$size" <<'PY'
import socket, struct, sys
destination, size = sys.argv[1], int(sys.argv[2])
packet = struct.pack(">II", 0x4C433032, 1) + b"SIM_COMMAND\0" + bytes([7]) * size
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
s.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 1)
for _ in range(3):
    s.sendto(packet, (destination, 7667))
PY
}

starts=0
sim_log=
start_sim() {
  # A log of its own for each sim: the background shell truncates a shared
  # one only when it gets to run, and under load the wait below read the
  # previous sim's "running" and went on.
  starts=$((starts + 1))
  sim_log=$work/sim.$starts.log
  # (ip netns exec becomes the sim, so $! is the sim's own PID.)
  ip netns exec "$ns_host" "$bin/sim_core/simpartner-sim" --params /dev/null --lcm-url 'udpm://239.255.76.67:7667?ttl=0' \
    --environment="$src/models/worlds/flat_ground.xml" --duration=30 >"$sim_log" 2>&1 &
  sim_pid=$!
  for _ in $(seq 1 300); do
    grep -q "simpartner-sim: running" "$sim_log" 2>/dev/null && break
    sleep 0.1
  done
  if ! grep -q "simpartner-sim: running" "$sim_log"; then
    echo "FAIL: simpartner-sim did not start in 30 s:" >&2
    cat "$sim_log" >&2
    exit 1
  fi
  sleep 0.3
}
stop_sim() {
  kill "$sim_pid" 2>/dev/null || true
  wait "$sim_pid" 2>/dev/null || true
  sim_pid=
}
seen() { grep -q "SIM_COMMAND: $1 bytes refused" "$sim_log"; }
failures=0
expect() {  # expect yes|no SIZE WHAT
  if [[ $1 == yes ]] && ! seen "$2"; then
    echo "FAIL: $3 did not reach the sim" >&2; failures=$((failures + 1))
  elif [[ $1 == no ]] && seen "$2"; then
    echo "FAIL: $3 reached the sim" >&2; failures=$((failures + 1))
  else
    echo "ok: $3 $( [[ $1 == yes ]] && echo reached || echo "did not reach") the sim"
  fi
}
# Each case: the other machine's multicast, then (fresh sim) its unicast,
# then (fresh sim) the host's own multicast.
run_case() {  # run_case NAME MULTICAST UNICAST LOCAL
  local name=$1
  echo "== $name"
  start_sim; send in_other 239.255.76.67 11; sleep 0.5; stop_sim
  if [[ $2 == either ]]; then
    echo "note: $name: the other machine's multicast datagram $(seen 11 && echo reached || echo "did not reach") the sim"
  else
    expect "$2" 11 "$name: the other machine's multicast datagram"
  fi
  start_sim; send in_other "$net.1" 12; sleep 0.5; stop_sim
  expect "$3" 12 "$name: the other machine's datagram to the host's address"
  start_sim; send in_host 239.255.76.67 13; sleep 0.5; stop_sim
  expect "$4" 13 "$name: the host's own multicast datagram"
}

run_case "as shipped, ttl=0 only" yes yes yes
in_host "$src/scripts/bus-guard" on 7667
run_case "scripts/bus-guard on" no no yes
in_host "$src/scripts/bus-guard" status 7667
in_host "$src/scripts/bus-guard" off 7667
in_host ip route add 239.255.76.67/32 dev lo
run_case "multicast route on lo" either yes yes

# A guard whose owner is gone (scripts/run killed with -9) is swept; one
# whose owner runs, and one set by hand (no owner), stay.
echo "== sweep"
sleep 300 & owner=$!
sleep 300 & gone=$!
in_host "$src/scripts/bus-guard" on 7681 --owner "$gone" >/dev/null
in_host "$src/scripts/bus-guard" on 7682 --owner "$owner" >/dev/null
in_host "$src/scripts/bus-guard" on 7683 >/dev/null
kill "$gone"; wait "$gone" 2>/dev/null || true
in_host "$src/scripts/bus-guard" sweep
for case in "7681 gone" "7682 kept" "7683 kept"; do
  set -- $case
  if in_host "$src/scripts/bus-guard" status "$1" >/dev/null; then state=kept; else state=gone; fi
  if [[ $state == "$2" ]]; then
    echo "ok: sweep: the guard of port $1 is $state"
  else
    echo "FAIL: sweep: the guard of port $1 is $state, expected $2" >&2; failures=$((failures + 1))
  fi
done
kill "$owner"; wait "$owner" 2>/dev/null || true

if (( failures )); then
  echo "bus_guard_test: $failures failed" >&2
  exit 1
fi
echo "bus_guard_test: every case as expected"
