#!/usr/bin/env bash
# Runs the process tests N times in a row with a busy loop on each core:
# the load under which a test that waits for time rather than for events,
# or reads the bus too slowly, fails. Each pass's ctest output goes to
# $TMPDIR/process_loop_<i>.log; one line per pass says how it went.
# usage: tests/process/run_under_load.sh BUILD_DIR N [REGEX]
set -u
dir=$1; n=$2
regex=${3:-"BusExposureTest|HostileFilesTest|HostileProcessTest|HostileSimTest|InstalledLoggingTest|InstalledSimTest|LockStepEngineTest|LockStepProcessTest|MultiHostTest|SignedBusTest|SimProcess|SoilProcessTest|SupervisedRunTest|BatchProcessTest|CameraProcess|ClientProcessTest|LoggerProcessTest|CheckProcess|SequencerProcessTest|TeleopProcessTest|ViewerProcessTest"}
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
busy=()
for _ in $(seq "$(nproc)"); do ( while :; do :; done ) & busy+=($!); done
trap 'kill "${busy[@]}" 2>/dev/null' EXIT
for i in $(seq "$n"); do
  log=${TMPDIR:-/tmp}/process_loop_$i.log
  start=$(date +%s)
  (cd "$dir" && ctest -R "$regex" -j "$(( $(nproc) + 1 ))" --timeout 900 --output-on-failure >"$log" 2>&1)
  rc=$?
  echo "pass $i: rc $rc, $(( $(date +%s) - start )) s, $(grep -E 'tests passed|tests failed' "$log")"
  grep -A3 "The following tests FAILED" "$log"
done
