#!/usr/bin/env bash
# The cost of provenance (issue 16): the Stanford bunny and the 819k torus sliced to G-code alone,
# and with --export-preview (provenance recorded, the preview encoded and written), median user
# time of RUNS runs each (user time: these machines are shared); with OLD_TRANCHE set (a build
# from before provenance existed), also that build without a preview, so the cost of the code
# when nobody asks for a preview is measured in the same run.
#   bench/bench_provenance.sh [BUILD_DIR]      env: RUNS=5, MODELS="stanford_bunny torus819k", OLD_TRANCHE
set -uo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
. "$here/peers/common.sh"
bench_setup "$build" || { echo "bench_provenance: cannot build tranche"; exit 1; }
RUNS=${RUNS:-5}
out=$(mktemp -d "${TMPDIR:-/tmp}/tranche-prov-XXXXXX")
trap 'rm -rf "$out"' EXIT
median() { sort -n | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
user_time() {  # median user seconds of RUNS runs of "$@"
  for _ in $(seq "$RUNS"); do
    /usr/bin/time -f "%U" "$@" 2>&1 >/dev/null | tail -1
  done | median
}
printf '%-16s %12s %14s %10s %14s %10s\n' model "G-code (s)" "+preview (s)" ratio "old build (s)" ratio
while read -r name model; do
  base=$(user_time "$TRANCHE" slice "$model" -o "$out/a.gcode" --quiet "${TRANCHE_SETS[@]}")
  prev=$(user_time "$TRANCHE" slice "$model" -o "$out/b.gcode" --export-preview "$out/b.html" --quiet "${TRANCHE_SETS[@]}")
  old="-" oldr="-"
  if [[ -n ${OLD_TRANCHE:-} ]]; then
    old=$(user_time "$OLD_TRANCHE" slice "$model" -o "$out/c.gcode" --quiet "${TRANCHE_SETS[@]}")
    oldr=$(awk -v a="$base" -v b="$old" 'BEGIN {printf "%.3f", a / b}')
  fi
  printf '%-16s %12s %14s %10s %14s %10s\n' "$name" "$base" "$prev" "$(awk -v a="$prev" -v b="$base" 'BEGIN {printf "%.3f", a / b}')" "$old" "$oldr"
  echo "  preview size: $(stat -c %s "$out/b.html") bytes" >&2
done < <(bench_models "${MODELS:-stanford_bunny torus819k}")
