#!/usr/bin/env bash
# docs/convert.md's MuJoCo tools on what simpartner-convert writes:
# mujoco-compile (Debian's libmujoco-samples, which scripts/deps installs)
# compiles each shipped world's MJCF into a binary model. The converter
# runs in another directory with the world's bare name, as a user types
# it: it finds the shipped world like every program finds its data.
#   tests/convert/mujoco_tools_test.sh SOURCE_DIR BINARY_DIR
set -uo pipefail
src=$1 bin=$2
source "$(dirname "$0")/../support/checks.sh"
command -v mujoco-compile >/dev/null || {
  echo "FAIL: mujoco-compile not found (scripts/deps installs libmujoco-samples)"; exit 1; }
dir=$(mktemp -d); trap 'rm -rf "$dir"' EXIT
for world in gen4_flat pole_task test_track; do
  mjcf=$dir/$world.mjcf.xml
  if ! converted=$(cd "$dir" && "$bin/convert/simpartner-convert" "$world.xml" -o "$mjcf" 2>&1); then
    fail "simpartner-convert $world.xml in $dir: $converted"; continue
  fi
  out=$(cd "$dir" && timeout 60 mujoco-compile "$mjcf" "$dir/$world.mjb" 2>&1); status=$?
  # A compiled gen3/gen4 world is hundreds of kB; an empty file is a failure
  # mujoco-compile could still report as done.
  size=$(stat -c %s "$dir/$world.mjb" 2>/dev/null || echo 0)
  if (( status != 0 )) || [[ $out != *Done* ]] || (( size < 10000 )); then
    fail "mujoco-compile $world: status $status, $size bytes: $out"
  else
    echo "ok: $world.xml, found from $dir, -> MJCF -> $size-byte binary model"
  fi
done
finish "every world compiled by mujoco-compile"
