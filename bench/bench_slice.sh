#!/usr/bin/env bash
# Slicing speed against Slic3r: loads and slices (a) the Stanford bunny from stl-models (scaled
# ×1000, Y up turned into Z up) and (b) a generated torus of 819 200 triangles at 0.2 mm layers,
# printing our time per stage and peak memory, then Slic3r's time to load and slice the same STL
# to SVG (`slic3r --export-svg`), and the ratio.
#   bench/bench_slice.sh [BUILD_DIR]        BENCH_RUNS=N: best of N runs of ours (default 3)
set -euo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
runs=${BENCH_RUNS:-3}
bench="$build/bench/slice_bench"
if [[ ! -x "$bench" ]]; then
  cmake --build "$build" --target slice_bench >/dev/null
fi

"$root/scripts/fetch-models.sh" >/dev/null || true
models=${TRANCHE_MODELS_DIR:-${HOME:-/tmp}/.cache/tranche/models}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/tranche-bench-XXXXXX")
trap 'rm -rf "$tmp"' EXIT

names=()
if [[ -f "$models/objects/bunny.bin.stl" ]]; then
  "$bench" prepare-bunny "$models/objects/bunny.bin.stl" "$tmp/bunny.stl" >/dev/null
  names+=(bunny)
else
  echo "bench_slice: $models/objects/bunny.bin.stl missing (npm unreachable?); bunny skipped"
fi
"$bench" write-torus "$tmp/torus.stl" >/dev/null
names+=(torus)

# Ours: best total of $runs runs (the machine is shared), with its per-stage row.
echo "tranche (seconds; svg = --export-svg, json = --export-layers; maxrss = peak resident memory):"
"$bench" header
declare -A ours
for n in "${names[@]}"; do
  best=""
  for ((i = 0; i < runs; i++)); do
    row=$("$bench" run --name "$n" --svg "$tmp/$n.svg" --json "$tmp/$n.json" "$tmp/$n.stl")
    # Comparable with Slic3r's --export-svg: load + plan + slice + union + svg.
    t=$(awk '{ printf "%.3f", $5 + $6 + $7 + $8 + $9 }' <<<"$row")
    if [[ -z "$best" ]] || awk -v a="$t" -v b="$best" 'BEGIN { exit !(a < b) }'; then best=$t; bestrow=$row; fi
  done
  echo "$bestrow"
  ours[$n]=$best
done

echo
if ! command -v slic3r >/dev/null 2>&1; then
  echo "slic3r not installed (scripts/install-deps.sh --with-peers); no comparison"
  exit 0
fi
printf '%-8s %16s %14s %12s %8s\n' model "tranche to SVG" "slic3r to SVG" "slic3r maxrss" ratio
for n in "${names[@]}"; do
  /usr/bin/time -f "%e %M" -o "$tmp/time" slic3r --no-gui --export-svg --layer-height 0.2 --first-layer-height 0.2 \
    -o "$tmp/$n-slic3r.svg" "$tmp/$n.stl" >/dev/null 2>&1 || { echo "$n: slic3r failed"; continue; }
  read -r secs kb <"$tmp/time"
  awk -v n="$n" -v o="${ours[$n]}" -v s="$secs" -v kb="$kb" \
    'BEGIN { printf "%-8s %14.3f s %12.2f s %10d MB %7.1fx\n", n, o, s, kb / 1024, s / o }'
done
