#!/usr/bin/env bash
# The rule VM's cost, in one table:
#  1. filter evaluation: the VM against the same rules hand-written in C++ and in Lua 5.4, over one
#     stream of contexts (vm_bench; target: within 2x of C++, faster than Lua);
#  2. slicing the Stanford bunny (stl-models, scaled x1000, Y up turned into Z) with
#     bench/rules/realistic50.rules against no rules (target: under 5% more time).
# Runs are interleaved and the best of each is kept: the machine is shared and noisy.
#   bench/bench_vm.sh [BUILD_DIR]          BENCH_RUNS=N (default 5)
set -euo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
runs=${BENCH_RUNS:-5}
for t in vm_bench slice_bench tranche; do
  if [[ ! -x "$build/bench/$t" && ! -x "$build/apps/$t" ]]; then cmake --build "$build" --target "$t" >/dev/null; fi
done
if [[ -x "$build/bench/vm_bench" ]]; then
  "$build/bench/vm_bench" 2000000 "$runs"
else
  echo "vm_bench not built (liblua5.4-dev missing?): filter evaluation skipped"
fi
echo

"$root/scripts/fetch-models.sh" >/dev/null || true
models=${TRANCHE_MODELS_DIR:-${HOME:-/tmp}/.cache/tranche/models}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/tranche-bench-vm-XXXXXX")
trap 'rm -rf "$tmp"' EXIT
if [[ -f "$models/objects/bunny.bin.stl" ]]; then
  "$build/bench/slice_bench" prepare-bunny "$models/objects/bunny.bin.stl" "$tmp/model.stl" >/dev/null
  name="Stanford bunny"
else
  "$build/bench/slice_bench" write-torus "$tmp/model.stl" >/dev/null
  name="torus (no stl-models)"
fi
rules="$here/rules/realistic50.rules"
time_one() {  # time_one OUT [args...] -> seconds
  local out=$1
  shift
  local t0 t1
  t0=$(date +%s.%N)
  "$build/apps/tranche" slice "$tmp/model.stl" -o "$tmp/$out" --quiet "$@" >/dev/null 2>&1
  t1=$(date +%s.%N)
  awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", b - a }'
}
best_plain=1e9 best_rules=1e9
for ((i = 0; i < runs; i++)); do
  t=$(time_one plain.gcode)
  best_plain=$(awk -v a="$t" -v b="$best_plain" 'BEGIN { print (a < b) ? a : b }')
  t=$(time_one rules.gcode --rules "$rules")
  best_rules=$(awk -v a="$t" -v b="$best_rules" 'BEGIN { print (a < b) ? a : b }')
done
lines_plain=$(wc -l <"$tmp/plain.gcode")
lines_rules=$(wc -l <"$tmp/rules.gcode")
printf 'slicing the %s to G-code (best of %d runs)\n' "$name" "$runs"
printf '%-28s %10s %14s\n' "" "seconds" "G-code lines"
printf '%-28s %10.3f %14d\n' "no rules" "$best_plain" "$lines_plain"
printf '%-28s %10.3f %14d\n' "realistic50.rules (50)" "$best_rules" "$lines_rules"
awk -v a="$best_rules" -v b="$best_plain" 'BEGIN { printf "rules overhead: %+.1f%% (target < 5%%)\n", (a / b - 1) * 100 }'
