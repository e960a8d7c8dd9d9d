#!/usr/bin/env bash
# The HTML preview's size and speed against the issue's limits (under 10 MB, loaded and drawn in
# under 2 s), and the thumbnails' cost, on:
#  - a made-up print of the Stanford bunny's size (800 layers, 5000 paths, 1M points), and
#  - the pages `tranche slice --export-preview` writes for the Stanford bunny (stl-models, through
#    bench/peers/common.sh's bench_models) and the 819k torus, with the benchmark settings.
# Load time: Chromium headless (puppeteer-core, installed as the browser test does), best of
# BENCH_RUNS loads, from navigation to the top layer drawn with the stack below it. `slice s` and
# `+preview s`: the slice to G-code alone and with the preview (provenance recorded, the page
# encoded and written), wall time of one run. Thumbnails: rendered from the toolpaths read back
# from the G-code, or from the outer walls as islands (preview_bench).
#   bench/bench_preview.sh [BUILD_DIR]          BENCH_RUNS=N (default 3)
set -euo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
runs=${BENCH_RUNS:-3}
. "$here/peers/common.sh"
bench_setup "$build" || { echo "bench_preview: cannot build tranche"; exit 1; }
[[ -x "$build/bench/preview_bench" ]] || cmake --build "$build" --target preview_bench >/dev/null
tmp=$(mktemp -d "${TMPDIR:-/tmp}/tranche-bench-preview-XXXXXX")
trap 'rm -rf "$tmp"' EXIT

# "layers paths points bytes" of a page, from its data's counts.
page_stats() {
  python3 - "$1" <<'PY'
import json, os, re, sys
html = open(sys.argv[1], encoding="utf-8").read()
data = json.loads(re.search(r'<script type="application/json" id="tranche-data">(.*?)</script>', html, re.S).group(1))
print(len(data["layers"]), data["counts"]["paths"], data["counts"]["points"], os.path.getsize(sys.argv[1]))
PY
}
wall() {  # seconds of one run of "$@"
  local t0 t1
  t0=$(date +%s.%N); "$@" >/dev/null 2>&1; t1=$(date +%s.%N)
  awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.2f", b - a}'
}

declare -a names pages stats slices thumbs
read -r l p q b enc th ol <<<"$("$build/bench/preview_bench" synthetic "$tmp/synthetic.html")"
names+=("synthetic (800 layers)"); pages+=("$tmp/synthetic.html"); stats+=("$l $p $q $b")
slices+=("- -"); thumbs+=("$enc $th $ol")
while read -r name model; do
  base=$(wall "$TRANCHE" slice "$model" -o "$tmp/$name.gcode" --quiet "${TRANCHE_SETS[@]}")
  with=$(wall "$TRANCHE" slice "$model" -o "$tmp/$name.gcode" --export-preview "$tmp/$name.html" --quiet "${TRANCHE_SETS[@]}")
  read -r _ _ _ _ enc th ol <<<"$("$build/bench/preview_bench" gcode "$tmp/$name.gcode" "$tmp/$name-gcode.html")"
  names+=("$name"); pages+=("$tmp/$name.html"); stats+=("$(page_stats "$tmp/$name.html")")
  slices+=("$base $with"); thumbs+=("$enc $th $ol")
done < <(bench_models "stanford_bunny torus819k")

loads=""
if bash "$root/tests/geometry/preview/browser/install.sh" "$build/preview-browser-test" >"$tmp/install.log"; then
  loads=$(node "$here/preview_load.js" "$build/preview-browser-test/node_modules" "$runs" "${pages[@]}")
else
  echo "load times skipped: $(tail -1 "$tmp/install.log")"
fi

printf '%-24s %7s %7s %9s %9s %8s %9s %9s %8s %8s %10s\n' "print" "layers" "paths" "points" "size MB" "% of 10" \
  "load ms" "% of 2 s" "step ms" "slice s" "+preview s"
for i in "${!names[@]}"; do
  read -r layers paths points bytes <<<"${stats[$i]}"
  read -r base with <<<"${slices[$i]}"
  load="-" step="-"
  if [[ -n "$loads" ]]; then read -r _ load _ step < <(grep -F "${pages[$i]} " <<<"$loads"); fi
  awk -v n="${names[$i]}" -v l="$layers" -v p="$paths" -v q="$points" -v b="$bytes" -v t="$load" -v s="$step" \
      -v sb="$base" -v sw="$with" 'BEGIN {
    mb = b / 1e6
    printf "%-24s %7d %7d %9d %9.2f %7.0f%% %9s %8s%% %8s %8s %10s\n", n, l, p, q, mb, mb / 10 * 100, t,
      (t == "-" ? "-" : sprintf("%.0f", t / 20)), s, sb, sw
  }'
done
echo
echo "thumbnails: 16x16 QOI + 300x300 PNG, rendered from the toolpaths or from the outlines (islands)"
printf '%-24s %10s %16s %16s\n' "print" "encode s" "toolpaths s" "outlines s"
for i in "${!names[@]}"; do
  read -r enc th ol <<<"${thumbs[$i]}"
  printf '%-24s %10s %16s %16s\n' "${names[$i]}" "$enc" "$th" "$ol"
done
