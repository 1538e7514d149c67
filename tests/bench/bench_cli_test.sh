#!/usr/bin/env bash
# Every bench program answers --help (exit 0, usage and what it measures)
# and refuses a misspelled option, a malformed value or a stray argument
# with exit 2 and, for an option, the nearest name. No bench runs for real:
# each of these ends while reading its command line (a timeout catches one
# that starts anyway).
#   tests/bench/bench_cli_test.sh SOURCE_DIR BINARY_DIR
set -uo pipefail
source_dir=$1
binary_dir=$2
source "$(dirname "$0")/../support/checks.sh"

# bench | a line of its help | a misspelling | the option it must suggest
cases=(
  "sim_bench|Microseconds per step|--stpes 10|--steps"
  "latency_bench|one-way latency|--cout 10|--count"
  "stepper_survey|Which stepper keeps WorkPartner stable|--seconds-scal 1|--seconds-scale"
  "drift_bench|drifted from wall time|--secnds 5|--seconds"
  "logger_bench|Figures of the database logger|--skp 1|--skip"
  "logged_read_bench|is read back from a|--datdir x|--datadir"
  "viewer_bench|How fast simpartner-viewer draws|--widht 640|--width"
  "camera_bench|What simpartner-camera keeps up with|--widht 640|--width"
  "flood_bench|floods|--rat 5|--rate"
  "peer_bench|MuJoCo 2.2|--stnad 3|--stand"
  "multi_host_bench|Needs root|--rte 5|--rate"
  "lockstep_bench|What lock-step costs|--tikcs 5|--ticks"
  "sensor_bench|without its field sensors|--rouns 5|--rounds"
  "soil_bench|on rigid ground (the first world) and on soil|--rouns 5|--rounds"
  "gait_slip|Plays a gen1 gait on ice|--gati rolking|--gait"
)
listed=" "
for c in "${cases[@]}"; do
  IFS='|' read -r bench help_line wrong suggestion <<<"$c"
  listed+="$bench "
  [[ -f $source_dir/bench/$bench.cpp ]] || continue  # not in this tree
  path=$binary_dir/bench/$bench
  if [[ ! -x $path ]]; then
    fail "$bench: $path is not built"
    continue
  fi
  expect_help "$bench" "$help_line" "$path" --help
  [[ $out == *"$suggestion"* ]] || fail "$bench --help does not list $suggestion: $out"
  # shellcheck disable=SC2086  # $wrong is an option and its value
  expect_misspelling "$bench $wrong" "$suggestion" "$path" $wrong
done

# Every bench program in bench/ has a case above (a new one must answer too).
for source in "$source_dir"/bench/*.cpp; do
  grep -q '^int main' "$source" || continue
  bench=$(basename "$source" .cpp)
  [[ $listed == *" $bench "* ]] || fail "bench/$bench.cpp has no case in $0"
done

# The parser every program shares (common/include/simpartner/command_line.h).
expect_refusal() {  # expected text, then the command line
  local want=$1; shift
  run "$binary_dir/bench/$1" "${@:2}"
  [[ $status -eq 2 && $out == *"$want"* ]] || fail "$*: exited $status, want 2 and '$want': $out"
}
expect_refusal "--steps: value 'many' is not a whole number" sim_bench --steps many
expect_refusal "--set: 'Axle1Motor=1000' is not NAME=FMAX,VELOCITY" sim_bench --set Axle1Motor=1000
expect_refusal "--set: 'Axle1Motor=1000' is not NAME=FMAX,VELOCITY" soil_bench --set Axle1Motor=1000
expect_refusal "--seconds: value 'x' is not a number" logger_bench --seconds x
expect_refusal "--count needs a value (--count N)" latency_bench --count
expect_refusal "unexpected argument 'world.xml' (it takes no arguments)" logger_bench world.xml
expect_refusal "unexpected argument 'b.xml' (it takes [world.xml])" latency_bench a.xml b.xml
expect_refusal "--kind: value 'flood' is not refused or garbage" flood_bench --kind flood
# Far from anything: no guess, the list of what it takes.
expect_refusal "unknown option '--zzzzzzzz'; it takes: --count --lcm-url --help" latency_bench --zzzzzzzz

# bench/run_all, the commands behind docs/benchmarks.md: its help, a
# misspelled option and figure name refused before anything runs, and each
# of its names given on the page as the way to rerun that section.
run_all=$source_dir/bench/run_all
expect_help run_all "Reruns the commands behind the figures" "$run_all" --help
expect_misspelling "run_all --onyl" "--only" "$run_all" --onyl soil
expect_misspelling "run_all --only camra" "camera" "$run_all" --only camra
run "$run_all" --list --build /nonexistent
[[ $status -eq 0 && $out == *"/nonexistent/bench/sim_bench --steps 3000"* ]] ||
  fail "run_all --list exited $status or does not name the build tree's sim_bench: $out"
page=$(<"$source_dir/docs/benchmarks.md")
for name in $(awk '{print $1}' <<<"$out" | sort -u); do
  [[ $page == *"--only $name"* || $page == *"--only "*",$name"* ]] ||
    fail "run_all's $name is not named on docs/benchmarks.md (bench/run_all --only $name)"
done

finish "all bench command lines answered as expected"
