#!/usr/bin/env bash
# Every program answers --help in the one layout (docs/command_line.md),
# lists the parameters it reads and not the others (parameters.txt is
# shared, but the viewer has no use for the stepper), and refuses a
# misspelled option with exit 2 and the nearest name.
#   tests/scripts/program_help_test.sh BINARY_DIR
set -uo pipefail
bin=$1
source "$(dirname "$0")/../support/checks.sh"

# program | keys its help must list | keys it must not list | a misspelling | its suggestion
cases=(
  "sim_core/simpartner-sim|stepsize= contactMu= speed= environment= lcmUrl=|dbname= logInterval=|--chek|--check"
  "viewer/simpartner-viewer|lcmUrl=|stepsize= dbname= speed= environment=|--widht=800|--width"
  "camera/simpartner-camera|lcmUrl=|stepsize= dbname= speed= environment=|--quit-aftr=1|--quit-after"
  "logger/simpartner-logger|dbname= logInterval= lcmUrl=|stepsize= contactMu= speed=|--spol=x|--spool"
  "logger/simpartner-query|dbname= dbserver=|stepsize= lcmUrl= speed=|--bdy=x|--body"
  "validate/simpartner-validate|stepsize= contactMu= environment=|dbname= lcmUrl= statusPeriod=|--lst|--list"
  "client/simpartner-cmd|lcmUrl=|stepsize= dbname=|--timout=1|--timeout"
  "convert/simpartner-convert|stepsize= contactMu=|dbname= lcmUrl= speed=|--mesh-as-bx|--mesh-as-box"
  "sequencer/simpartner-sequencer||lcmUrl= stepsize=|--quite|--quiet"
  "teleop/simpartner-teleop||lcmUrl= stepsize=|--lst|--list"
  "teleop/simpartner-teleop-vpad||lcmUrl= stepsize=|--scrpt=x|--script"
  "batch/simpartner-batch||lcmUrl= stepsize=|--paralel=2|--parallel"
)
for c in "${cases[@]}"; do
  IFS='|' read -r program wanted unwanted wrong suggestion <<<"$c"
  name=$(basename "$program")
  # --help ends before any window, socket or leak-prone library start-up.
  run env ASAN_OPTIONS=detect_leaks=0 "$bin/$program" --help
  [[ $status -eq 0 ]] || { fail "$program --help exited $status: $out"; continue; }
  [[ $out == "Usage: $name [options]"* ]] || fail "$program --help does not start with the usage line: $out"
  [[ $out == *$'\nOptions:\n'* && $out == *"  -h, --help "* ]] || fail "$program --help: not the common layout: $out"
  for key in $wanted; do
    [[ $out == *"    $key"* ]] || fail "$program --help does not list $key"
  done
  for key in $unwanted; do
    [[ $out != *"    $key"* ]] || fail "$program --help lists $key, which it does not read"
  done
  run env ASAN_OPTIONS=detect_leaks=0 "$bin/$program" "$wrong"
  [[ $status -eq 2 ]] || fail "$program $wrong exited $status (want 2): $out"
  [[ $out == "$name: unknown option '$wrong' (did you mean '$suggestion'?)"* ]] ||
    fail "$program $wrong: no did-you-mean '$suggestion': $out"
done
finish "all ${#cases[@]} programs answer --help alike, list only their own parameters and refuse misspellings"
