#!/usr/bin/env bash
# Every script in scripts/ answers --help (exit 0, its own description) and
# refuses a misspelled option or command with exit 2 and the nearest name.
# Nothing here installs, builds or starts anything: --help and a refused
# option end before any of that.
#   tests/scripts/scripts_cli_test.sh SOURCE_DIR
set -uo pipefail
source_dir=$1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# script | a line of its help | a misspelling | the name it must suggest
cases=(
  "mariadb|A private MariaDB server|strat|start"
  "mariadb|A private MariaDB server|start --prot=5|--port"
  "build|Configures and builds one build directory|--hepl|--help"
  "deps|Installs the Debian packages|--hlep|--help"
  "fuzz|Fuzzes the XML loader|--secnds|--seconds"
  "bus-guard|Closes the LCM bus to other machines|of|off"
  "lcm-spy|lcm-spy with SimPartner's message types|--lcm-ulr=x|--lcm-url"
  "test|The whole test suite|--no-sanitise|--no-sanitize"
)
for c in "${cases[@]}"; do
  IFS='|' read -r script help_line wrong suggestion <<<"$c"
  path=$source_dir/scripts/$script
  out=$("$path" --help 2>&1); status=$?
  [[ $status -eq 0 ]] || fail "$script --help exited $status: $out"
  [[ $out == *"$help_line"* ]] || fail "$script --help does not say '$help_line': $out"
  # shellcheck disable=SC2086  # $wrong may be a command and an option
  out=$("$path" $wrong 2>&1 </dev/null); status=$?
  [[ $status -eq 2 ]] || fail "$script $wrong exited $status (want 2): $out"
  [[ $out == *"did you mean '$suggestion'?"* ]] || fail "$script $wrong: no did-you-mean '$suggestion': $out"
done
# scripts/run's help needs no build (it used to build first, which takes
# many minutes on a fresh clone): its own options, and a note where the
# sim's are when there is no build.
out=$(timeout 20 "$source_dir/scripts/run" --help --bin /nonexistent 2>&1); status=$?
[[ $status -eq 0 && $out == *"The main job, supervised"* && $out == *"build first"* ]] ||
  fail "run --help without a build: $status $out"

# Far from anything: no guess, the list of what it takes.
out=$("$source_dir/scripts/fuzz" --zzz 2>&1); status=$?
[[ $status -eq 2 && $out == *"it takes: --seconds --help"* ]] || fail "fuzz --zzz: $status $out"

if (( failures > 0 )); then
  echo "$failures failure(s)"
  exit 1
fi
echo "all ${#cases[@]} scripts answer --help and refuse misspellings"
