#!/usr/bin/env bash
# The HTML preview's size and speed against the issue's limits (under 10 MB, loaded and drawn in
# under 2 s), and the thumbnails' cost, on:
#  - a made-up print of the Stanford bunny's size (800 layers, 5000 paths, 1M points), and
#  - the toolpaths of Tranche's own G-code for the Stanford bunny (stl-models) and the 819k
#    torus, read back from the G-code (until `tranche slice --export-preview` writes them).
# Load time: Chromium headless (puppeteer-core, installed as the browser test does), best of
# BENCH_RUNS loads, from navigation to the top layer drawn with the stack below it.
#   bench/bench_preview.sh [BUILD_DIR]          BENCH_RUNS=N (default 3)
set -euo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
runs=${BENCH_RUNS:-3}
for t in preview_bench slice_bench tranche; do
  if [[ ! -x "$build/bench/$t" && ! -x "$build/apps/$t" ]]; then cmake --build "$build" --target "$t" >/dev/null; fi
done
tmp=$(mktemp -d "${TMPDIR:-/tmp}/tranche-bench-preview-XXXXXX")
trap 'rm -rf "$tmp"' EXIT

declare -a names pages stats
add() {  # add NAME PAGE STATS
  names+=("$1"); pages+=("$2"); stats+=("$3")
}
add "synthetic (800 layers)" "$tmp/synthetic.html" "$("$build/bench/preview_bench" synthetic "$tmp/synthetic.html")"
"$root/scripts/fetch-models.sh" >/dev/null 2>&1 || true
models=${TRANCHE_MODELS_DIR:-${HOME:-/tmp}/.cache/tranche/models}
if [[ -f "$models/objects/bunny.bin.stl" ]]; then
  "$build/bench/slice_bench" prepare-bunny "$models/objects/bunny.bin.stl" "$tmp/bunny.stl" >/dev/null
  "$build/apps/tranche" slice "$tmp/bunny.stl" -o "$tmp/bunny.gcode" --quiet >/dev/null 2>&1
  add "Stanford bunny" "$tmp/bunny.html" "$("$build/bench/preview_bench" gcode "$tmp/bunny.gcode" "$tmp/bunny.html")"
fi
"$build/bench/slice_bench" write-torus "$tmp/torus.stl" >/dev/null
"$build/apps/tranche" slice "$tmp/torus.stl" -o "$tmp/torus.gcode" --quiet >/dev/null 2>&1
add "torus (819k triangles)" "$tmp/torus.html" "$("$build/bench/preview_bench" gcode "$tmp/torus.gcode" "$tmp/torus.html")"

loads=""
if bash "$root/tests/geometry/preview/browser/install.sh" "$build/preview-browser-test" >"$tmp/install.log"; then
  loads=$(node "$here/preview_load.js" "$build/preview-browser-test/node_modules" "$runs" "${pages[@]}")
else
  echo "load times skipped: $(tail -1 "$tmp/install.log")"
fi

printf '%-24s %7s %7s %9s %9s %8s %9s %9s %8s\n' "print" "layers" "paths" "points" "size MB" "% of 10" "load ms" "% of 2 s" "step ms"
for i in "${!names[@]}"; do
  read -r layers paths points bytes encode thumbs outlines <<<"${stats[$i]}"
  load="-" decode="-" step="-"
  if [[ -n "$loads" ]]; then read -r _ load decode step < <(grep -F "${pages[$i]} " <<<"$loads"); fi
  awk -v n="${names[$i]}" -v l="$layers" -v p="$paths" -v q="$points" -v b="$bytes" -v t="$load" -v s="$step" 'BEGIN {
    mb = b / 1e6
    printf "%-24s %7d %7d %9d %9.2f %7.0f%% %9s %8s%% %8s\n", n, l, p, q, mb, mb / 10 * 100, t, (t == "-" ? "-" : sprintf("%.0f", t / 20)), s
  }'
done
echo
echo "thumbnails: 16x16 QOI + 300x300 PNG, rendered from the toolpaths or from the outlines (islands)"
printf '%-24s %10s %16s %16s\n' "print" "encode s" "toolpaths s" "outlines s"
for i in "${!names[@]}"; do
  read -r _ _ _ _ encode thumbs outlines <<<"${stats[$i]}"
  printf '%-24s %10s %16s %16s\n' "${names[$i]}" "$encode" "$thumbs" "$outlines"
done
