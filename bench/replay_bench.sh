#!/usr/bin/env bash
# How fast can lcm-logplayer replay a recorded run into simpartner-logger
# before the logger loses states? Records SECONDS s of gen3 on flat ground
# (the shipped world, SIM_STATE at 1 kHz) with lcm-logger, then replays the
# file at each SPEED into a fresh database of a private MariaDB server.
# Prints the states lcm-logger kept and, per speed, the steps logged of
# those, LogGap's missing steps and the replay's wall time. LCM ttl=0, a
# port of its own.
#   bench/replay_bench.sh BINARY_DIR [SECONDS [SPEED...]]
#   e.g. bench/replay_bench.sh build 10 1 5 20 100
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:?usage: bench/replay_bench.sh BINARY_DIR [SECONDS [SPEED...]]}
seconds=${2:-10}
shift $(( $# >= 2 ? 2 : 1 ))
speeds=("$@")
(( ${#speeds[@]} )) || speeds=(1 5 20 100)
work=$(mktemp -d /tmp/sp_replay_XXXX)
url="udpm://239.255.76.67:$(( 20000 + ($$ * 17) % 20000 ))?ttl=0"
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; wait "$pid" 2>/dev/null || true; done
  "$src/scripts/mariadb" stop --datadir "$work/db" >/dev/null 2>&1 || true
  rm -rf "$work"
}
trap cleanup EXIT
sql() {  # sql DATABASE QUERY
  mariadb --defaults-file="$work/db/admin.cnf" -N -B -D "$1" -e "$2" 2>/dev/null || echo -1
}
"$src/scripts/mariadb" start --datadir "$work/db" >"$work/mariadb.log" 2>&1

lcm-logger --quiet --force --lcm-url="$url&recv_buf_size=8388608" "$work/run.lcmlog" \
  >"$work/lcm-logger.log" 2>&1 &
pids+=($!)
sleep 0.5
"$bin/sim_core/simpartner-sim" --params /dev/null \
  --environment="$src/models/worlds/flat_ground.xml" --lcm-url="$url" --duration="$seconds" \
  >"$work/sim.log" 2>&1
sleep 0.5
kill -INT "${pids[0]}"; wait "${pids[0]}" >/dev/null 2>&1 || true
pids=()
# SIM_STATE events in the file (LCM log format: sync word, event number,
# time, channel length, data length, channel, data): what lcm-logger kept.
recorded=$(python3 - "$work/run.lcmlog" <<'PY'
import struct, sys
n = 0
with open(sys.argv[1], "rb") as f:
    while True:
        head = f.read(28)
        if len(head) < 28:
            break
        sync, _, _, clen, dlen = struct.unpack(">IqqII", head)
        if sync != 0xEDA1DA01:
            sys.exit("bad sync word")
        n += f.read(clen) == b"SIM_STATE"
        f.seek(dlen, 1)
print(n)
PY
)
steps=$(( seconds * 1000 ))
echo "recorded $seconds s of flat_ground.xml (gen3): $(du -m "$work/run.lcmlog" | cut -f1) MB," \
  "$recorded of the sim's $steps states (lcm-logger's own loss)"
printf "%8s %16s %10s %12s\n" speed "steps logged" "LogGap" "replay [s]"
for speed in "${speeds[@]}"; do
  db="simpartner_replay_${speed//./_}"
  "$bin/logger/simpartner-logger" --params /dev/null --lcm-url="$url" --dbname="$db" \
    --db-options "$work/db/logger.cnf" --spool "$work/spool_$db" >"$work/logger_$db.log" 2>&1 &
  logger=$!
  pids=("$logger")
  for _ in $(seq 300); do grep -q ": logging udpm://" "$work/logger_$db.log" && break; sleep 0.1; done
  start=$(date +%s.%N)
  lcm-logplayer --speed="$speed" --lcm-url="$url" "$work/run.lcmlog" >/dev/null 2>&1
  took=$(echo "$(date +%s.%N) - $start" | bc)
  for _ in $(seq 600); do
    [[ $(sql "$db" "SELECT COUNT(*) FROM Simulation WHERE endTime IS NOT NULL") == 1 ]] && break
    sleep 0.1
  done
  kill -TERM "$logger" 2>/dev/null || true
  status=0
  wait "$logger" || status=$?
  pids=()
  if (( status != 0 )); then
    echo "speed $speed: simpartner-logger exited with status $status; its log ends:" >&2
    tail -5 "$work/logger_$db.log" >&2
  fi
  printf "%8s %16s %10s %12.1f\n" "$speed" \
    "$(sql "$db" "SELECT COUNT(*) FROM SimulationRow") of $recorded" \
    "$(sql "$db" "SELECT COALESCE(SUM(missing), 0) FROM LogGap")" "$took"
done
