#!/usr/bin/env bash
# The polygon stage (overlap resolution + monotone decomposition, geometry/polygon) against slicing
# on PrusaSlicer's test shapes, the Stanford bunny (stl-models, via scripts/fetch-models.sh) and a
# generated plate with 48 holes: layers, islands, cells per island (mean, max), slicing time,
# resolution and decomposition time per layer, and the stage's share of the slicing time.
#   bench/bench_polygon.sh [BUILD_DIR]        BENCH_RUNS=N: best of N runs (default 3)
set -euo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
runs=${BENCH_RUNS:-3}
bench="$build/bench/polygon_bench"
if [[ ! -x "$bench" ]]; then
  cmake --build "$build" --target polygon_bench >/dev/null
fi
tmp=$(mktemp -d "${TMPDIR:-/tmp}/tranche-bench-XXXXXX")
trap 'rm -rf "$tmp"' EXIT

"$bench" header
shopt -s nullglob
for stl in /usr/share/PrusaSlicer/shapes/*.stl; do
  "$bench" run --runs "$runs" "$stl" || echo "$(basename "$stl"): failed"
done
[[ -e /usr/share/PrusaSlicer/shapes ]] || echo "(PrusaSlicer's shapes not installed: scripts/install-deps.sh --with-peers)"

"$root/scripts/fetch-models.sh" >/dev/null || true
models=${TRANCHE_MODELS_DIR:-${HOME:-/tmp}/.cache/tranche/models}
if [[ -f "$models/objects/bunny.bin.stl" ]]; then
  "$bench" run --runs "$runs" --name bunny --y-up-metres "$models/objects/bunny.bin.stl"
else
  echo "bunny: $models/objects/bunny.bin.stl missing (npm unreachable?); skipped"
fi
"$bench" write-plate "$tmp/plate.stl"
"$bench" run --runs "$runs" --name "plate 48 holes" "$tmp/plate.stl"
