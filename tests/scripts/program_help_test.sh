#!/usr/bin/env bash
# Each program's --help lists the parameters it reads and not the others
# (parameters.txt is shared, but the viewer has no use for the stepper).
#   tests/scripts/program_help_test.sh BINARY_DIR
set -uo pipefail
bin=$1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# program | keys its help must list | keys it must not list
cases=(
  "sim_core/simpartner-sim|stepsize= contactMu= speed= environment= lcmUrl=|dbname= logInterval="
  "viewer/simpartner-viewer|lcmUrl=|stepsize= dbname= speed= environment="
  "logger/simpartner-logger|dbname= logInterval= lcmUrl=|stepsize= contactMu= speed="
  "logger/simpartner-query|dbname= dbserver=|stepsize= lcmUrl= speed="
  "validate/simpartner-validate|stepsize= contactMu= environment=|dbname= lcmUrl= statusPeriod="
)
for c in "${cases[@]}"; do
  IFS='|' read -r program wanted unwanted <<<"$c"
  # --help ends before any window, socket or leak-prone library start-up.
  out=$(ASAN_OPTIONS=detect_leaks=0 timeout 20 "$bin/$program" --help 2>&1); status=$?
  [[ $status -eq 0 ]] || { fail "$program --help exited $status: $out"; continue; }
  for key in $wanted; do
    [[ $out == *"    $key"* ]] || fail "$program --help does not list $key"
  done
  for key in $unwanted; do
    [[ $out != *"    $key"* ]] || fail "$program --help lists $key, which it does not read"
  done
done
if (( failures > 0 )); then
  echo "$failures failure(s)"
  exit 1
fi
echo "all ${#cases[@]} programs list only their own parameters"
