#!/usr/bin/env bash
# Every script in scripts/ answers --help (exit 0, its own description) and
# refuses a misspelled option or command with exit 2 and the nearest name.
# Nothing here installs, builds or starts anything: --help and a refused
# option end before any of that.
#   tests/scripts/scripts_cli_test.sh SOURCE_DIR
set -uo pipefail
source_dir=$1
source "$(dirname "$0")/../support/checks.sh"

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
  expect_help "$script" "$help_line" "$path" --help
  # shellcheck disable=SC2086  # $wrong may be a command and an option
  expect_misspelling "$script $wrong" "$suggestion" "$path" $wrong
done
# scripts/run's help needs no build (it used to build first, which takes
# many minutes on a fresh clone): its own options, and a note where the
# sim's are when there is no build.
run "$source_dir/scripts/run" --help --bin /nonexistent
[[ $status -eq 0 && $out == *"The main job, supervised"* && $out == *"build first"* ]] ||
  fail "run --help without a build: $status $out"

# Far from anything: no guess, the list of what it takes.
run "$source_dir/scripts/fuzz" --zzz
[[ $status -eq 2 && $out == *"it takes: --seconds --build-only --help"* ]] || fail "fuzz --zzz: $status $out"

finish "all ${#cases[@]} scripts answer --help and refuse misspellings"
