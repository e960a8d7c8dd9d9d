#!/usr/bin/env bash
# The plate: load time of a 3MF of 10 objects and 2 000 000 triangles against the same meshes as
# 10 STL files (goal: within 1.5×; the 3MF is inflated by libdeflate, its objects read and welded
# in parallel: the CPU-time column, all threads, is the cost on a machine others share, where the
# wall time waits for cores), and the arrangement of 50 objects on a 250 × 210 mm bed
# (limit: 1 s) with its packing density against PrusaSlicer's --arrange on the same objects
# (goal: within 10%; skipped without prusa-slicer, scripts/install-deps.sh --with-peers).
# The loads are timed twice: repeated in one process (best of N), and once per fresh process (the
# load `tranche slice` does).
#   bench/bench_plate.sh [BUILD_DIR]        BENCH_RUNS=N: best of N loads (default 3)
set -euo pipefail
build=${1:-build}
bench="$build/bench/plate_bench"
if [[ ! -x "$bench" ]]; then
  cmake --build "$build" --target plate_bench >/dev/null
fi
tmp=$(mktemp -d "${TMPDIR:-/tmp}/tranche-bench-XXXXXX")
trap 'rm -rf "$tmp"' EXIT

"$bench" load "$tmp/load" "${BENCH_RUNS:-3}"
# The same files loaded once by a fresh process, as `tranche slice` loads them (no memory or cache
# left warm by an earlier load): best of the runs, STL and 3MF taking turns.
best_stl=""; best_3mf=""
for ((i = 0; i < ${BENCH_RUNS:-3}; i++)); do
  read -r w c < <("$bench" read 1 "$tmp"/load/torus*.stl)
  best_stl=$(awk -v a="$best_stl" -v w="$w" -v c="$c" 'BEGIN { split(a, p, " "); if (a == "" || w < p[1]) print w, c; else print a }')
  read -r w c < <("$bench" read 1 "$tmp/load/ten.3mf")
  best_3mf=$(awk -v a="$best_3mf" -v w="$w" -v c="$c" 'BEGIN { split(a, p, " "); if (a == "" || w < p[1]) print w, c; else print a }')
done
awk -v s="$best_stl" -v t="$best_3mf" 'BEGIN {
  split(s, a, " "); split(t, b, " ");
  printf "first load in a fresh process:  10 STL %.3f s (CPU %.3f)   3MF %.3f s (CPU %.3f)   %.2f x (CPU %.2f x)\n",
         a[1], a[2], b[1], b[2], b[1] / a[1], b[2] / a[2] }'
echo
"$bench" write-objects "$tmp/objects" >/dev/null
peer=""
if command -v prusa-slicer >/dev/null 2>&1; then
  # --merge arranges the models (min_object_distance 6 mm) and exports them as one 3MF plate.
  start=$(date +%s%N)
  if prusa-slicer --export-3mf --merge --bed-shape 0x0,250x0,250x210,0x210 -o "$tmp/prusa.3mf" \
       "$tmp"/objects/obj*.stl >"$tmp/prusa.log" 2>&1; then
    peer="$tmp/prusa.3mf"
    echo "(prusa-slicer's whole run, loading and export included: $((($(date +%s%N) - start) / 1000000)) ms)"
  else
    echo "prusa-slicer failed:"; tail -5 "$tmp/prusa.log"
  fi
else
  echo "(prusa-slicer not installed: scripts/install-deps.sh --with-peers; density not compared)"
fi
"$bench" arrange "$tmp/objects" $peer
