#!/usr/bin/env bash
# scripts/lcm-spy's per-field view and plots: under a private
# Xvfb, with a real simpartner-sim on its own port (ttl=0), lcm-spy lists
# SIM_STATE; a double click on that row opens its per-field view, a click
# on the sparkline of bodies[0].position[0] opens a jchart2d chart of it.
# Fails when a window does not appear or lcm-spy prints an exception (a
# jar missing from its class path shows as NoClassDefFoundError).
#   lcm_spy_test.sh SOURCE_DIR BINARY_DIR
set -euo pipefail
src=$1
bin=$2
work=$(mktemp -d)
xvfb_pid= sim_pid= spy_pid=
cleanup() {
  for pid in $spy_pid $sim_pid $xvfb_pid; do
    kill "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
  done
  rm -rf "$work"
}
trap cleanup EXIT
fail() {
  echo "FAIL: $*" >&2
  echo "--- lcm-spy output:" >&2; cat "$work/spy.log" >&2 || true
  echo "--- sim output (tail):" >&2; tail -5 "$work/sim.log" >&2 || true
  exit 1
}
# Waits up to ${2:-20} s for a window named exactly $1; prints its id.
wait_window() {
  local id
  for _ in $(seq $(( ${2:-20} * 5 ))); do
    id=$(xdotool search --name "^$1\$" 2>/dev/null | head -1 || true)
    [[ -n $id ]] && { echo "$id"; return 0; }
    sleep 0.2
  done
  return 1
}

Xvfb -displayfd 3 -screen 0 1280x900x24 3>"$work/display" >"$work/xvfb.log" 2>&1 &
xvfb_pid=$!
for _ in $(seq 50); do [[ -s $work/display ]] && break; sleep 0.1; done
[[ -s $work/display ]] || fail "Xvfb did not start: $(cat "$work/xvfb.log")"
export DISPLAY=:$(<"$work/display")

url=$("$bin/tests/sp_test_bus_url" 0)
"$bin/sim_core/simpartner-sim" --params /dev/null \
  --environment="$src/models/worlds/flat_ground.xml" --lcm-url="$url" --duration=120 \
  >"$work/sim.log" 2>&1 &
sim_pid=$!
SP_LCM_JAR="$bin/lcmtypes/simpartner_lcmtypes.jar" "$src/scripts/lcm-spy" --lcm-url="$url" \
  >"$work/spy.log" 2>&1 &
spy_pid=$!

spy=$(wait_window "LCM Spy" 60) || fail "no 'LCM Spy' window within 60 s"
# No window manager: every window is at 0,0. The rows are SIM_MODEL,
# SIM_SENSOR (the shipped gen3's IMU, GNSS, encoders and lidar), SIM_STATE,
# SIM_STATUS, once each has come, 16 pixels apart; SIM_STATE's is at y 59. On a
# loaded machine a row can come late, so a click that opened nothing is
# tried again (4 times).
view=
for _ in 1 2 3 4; do
  sleep 3
  xdotool mousemove --window "$spy" 40 59 click --repeat 2 --delay 100 1
  view=$(wait_window "SIM_STATE" 8) && break
done
[[ -n $view ]] || fail "a double click on SIM_STATE opened no per-field view"
chart=
for _ in 1 2 3 4; do
  sleep 1
  # The sparkline of bodies[0].position[0], right of its value.
  xdotool mousemove --window "$view" 600 189 click 1
  chart=$(wait_window "position\\[0\\]" 8) && break
done
[[ -n $chart ]] || fail "a click on position[0]'s sparkline opened no chart"
sleep 2
kill -0 "$spy_pid" 2>/dev/null || fail "lcm-spy exited"
if grep -E "Exception|Error|NoClassDef" "$work/spy.log" >/dev/null; then
  fail "lcm-spy printed an exception"
fi
echo "lcm-spy: per-field view and chart opened, no exception"
