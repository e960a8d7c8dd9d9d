#!/usr/bin/env bash
# Lightning infill's plastic against its density, ours and PrusaSlicer's: each model sliced with
# --set infill_pattern=lightning --set infill_density=D% by tranche and with --fill-pattern
# lightning --fill-density D% by PrusaSlicer, all on the benchmark settings (bench/peers/). The
# sparse infill's filament (mm, the moves under ;TYPE:Internal infill, bench/infill_row.py) per
# density, ours / PrusaSlicer's, and whether ours grows with the density (as PrusaSlicer's: a
# denser lightning holds the tops at more points).
#   bench/bench_lightning_density.sh [BUILD_DIR]   env: MODELS (default: bunny sphere),
#       DENSITIES (default: 20 35 50 65 80 95), OUT=dir to keep the files
set -uo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
. "$here/peers/common.sh"
bench_setup "$build" || { echo "bench_lightning_density: cannot build tranche"; exit 1; }
MODELS=${MODELS:-bunny sphere}
DENSITIES=${DENSITIES:-20 35 50 65 80 95}
bench_workdir lightning_density
filament() {
  /usr/bin/python3 -c 'import sys; sys.path.insert(0, sys.argv[1]); import infill_row; print("%.1f" % infill_row.infill_filament(sys.argv[2]))' "$here" "$1"
}
echo "| model | density | infill mm (ours / prusa) | ratio | ours grows |"
echo "|---|---|---|---|---|"
while read -r name model; do
  last=
  for d in $DENSITIES; do
    ours=nan prusa=nan
    g="$out/$name.$d.tranche.gcode"
    peer_cmd tranche "$model" "$g"
    CMD+=(--set infill_pattern=lightning --set "infill_density=$d%")
    timeout 900 "${CMD[@]}" </dev/null >"$out/$name.$d.tranche.log" 2>&1 && [[ -s $g ]] && ours=$(filament "$g")
    if command -v prusa-slicer >/dev/null; then
      g="$out/$name.$d.prusa.gcode"
      peer_cmd prusa "$model" "$g"
      CMD=("${CMD[@]:0:1}" --fill-pattern lightning --fill-density "$d%" "${CMD[@]:1}")
      env -u DISPLAY timeout 900 "${CMD[@]}" </dev/null >"$out/$name.$d.prusa.log" 2>&1 && [[ -s $g ]] && prusa=$(filament "$g")
    fi
    grows=-
    [[ -n $last && $ours != nan ]] && grows=$(awk -v a="$ours" -v b="$last" 'BEGIN { print (a > b ? "yes" : "NO") }')
    ratio=$(awk -v a="$ours" -v b="$prusa" 'BEGIN { print (a == "nan" || b == "nan" || b <= 0) ? "nan" : sprintf("%.3f", a / b) }')
    echo "| $name | $d% | $ours / $prusa | $ratio | $grows |"
    last=$ours
  done
done < <(bench_models "$MODELS")
[[ -n ${OUT:-} ]] && echo "files kept in $out"
exit 0
