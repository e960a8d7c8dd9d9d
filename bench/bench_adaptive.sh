#!/usr/bin/env bash
# Adaptive layer heights against PrusaSlicer's, on PrusaSlicer's sphere and the closed Stanford
# bunny: tranche with adaptive_layers at adaptive_quality 50% (min 0.07, max 0.3 mm), tranche at
# 0.2 mm, PrusaSlicer at 0.2 mm, and PrusaSlicer's adaptive layers at its quality 0.5 with the
# same bounds and its 0.2 mm layer height. prusa-slicer's command line cannot turn adaptive
# layers on (a GUI button makes the profile), so adaptive_cusp.py computes that profile from
# PrusaSlicer's formula (see its header) and writes it into a 3MF, as the GUI saves it, which
# prusa-slicer then slices. For each: the layer
# count, the largest and the mean cusp height (from the mesh's facet normals and the layer
# tops of the G-code, first layer left out: adaptive_cusp.py), and gcheck's verdict on the
# G-code. Goal: fewer layers than PrusaSlicer's adaptive at the same or a smaller largest cusp.
# A row at adaptive_quality 75% shows the trade-off (more layers, smaller cusps), one without
# smoothing (adaptive_smoothing=0) what the smoothing costs in layers; "max step" is the largest
# change of height between neighbouring layers.
#   bench/bench_adaptive.sh [BUILD_DIR]      env: MODELS, GCHECK=path/to/gcheck.py, OUT=dir to keep files
set -uo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
. "$here/peers/common.sh"
bench_setup "$build" || { echo "bench_adaptive: cannot build tranche"; exit 1; }
bench_need_gcheck bench_adaptive
MODELS=${MODELS:-sphere stanford_bunny_closed}
bench_workdir adaptive
ADAPTIVE=(--set adaptive_layers=true --set adaptive_quality=50% --set min_layer_height=0.07 --set max_layer_height=0.3)
# gcheck's verdict for MODEL GCODE. gcheck expects height / 0.2 mm layers (its --layer-height,
# which also bounds the per-layer thicknesses it accepts: 0.04 to 0.4 mm, within which it uses
# each layer's own); when that count is its only remark, the verdict is shown as OK with it.
verdict() {
  local off
  off=$(/usr/bin/python3 "$here/quality_row.py" --offset "$1" 100,100)
  /usr/bin/python3 "$GCHECK" "$1" "$2" --offset="$off" --json "$2.json" >"$2.gcheck" 2>&1
  /usr/bin/python3 - "$2.json" <<'EOP' 2>/dev/null || echo failed
import json, sys
v = json.load(open(sys.argv[1]))["summary"].get("verdict", "?")
head, _, why = v.partition(":")
reasons = [r.strip() for r in why.split(";") if r.strip()]
if head.strip() == "SUSPECT" and reasons and all(r.startswith("layer count") for r in reasons):
    print("OK (" + reasons[0] + ")")
else:
    print(head.strip())
EOP
}
while read -r name model; do
  for s in tranche_adaptive tranche_adaptive_s0 tranche_adaptive75 tranche prusa prusa_adaptive; do
    g="$out/$name.$s.gcode"
    case $s in
      tranche_adaptive)  # the benchmark's --set layer_height would decide every layer: left out
        label="tranche adaptive q=0.5"; peer_cmd tranche "$model" "$g"
        keep=()
        for a in "${CMD[@]}"; do [[ $a == layer_height=* ]] && unset 'keep[-1]' || keep+=("$a"); done
        CMD=("${keep[@]}" "${ADAPTIVE[@]}") ;;
      tranche_adaptive_s0)  # the same without smoothing: what adaptive_smoothing costs and buys
        label="tranche adaptive q=0.5 unsmoothed"; peer_cmd tranche "$model" "$g"
        keep=()
        for a in "${CMD[@]}"; do [[ $a == layer_height=* ]] && unset 'keep[-1]' || keep+=("$a"); done
        CMD=("${keep[@]}" "${ADAPTIVE[@]}" --set adaptive_smoothing=0) ;;
      tranche_adaptive75)
        label="tranche adaptive q=0.75"; peer_cmd tranche "$model" "$g"
        keep=()
        for a in "${CMD[@]}"; do [[ $a == layer_height=* ]] && unset 'keep[-1]' || keep+=("$a"); done
        CMD=("${keep[@]}" "${ADAPTIVE[@]}" --set adaptive_quality=75%) ;;
      tranche) label="tranche 0.2 mm"; peer_cmd tranche "$model" "$g" ;;
      prusa) label="prusa 0.2 mm"; command -v prusa-slicer >/dev/null || continue; peer_cmd prusa "$model" "$g" ;;
      prusa_adaptive)  # the profile its GUI's button would make, in a 3MF its command line slices
        label="prusa adaptive q=0.5"; command -v prusa-slicer >/dev/null || continue
        /usr/bin/python3 "$here/adaptive_cusp.py" prusa-plan "$model" 0.5 0.07 0.3 0.2 0.2 >"$out/$name.plan.txt"
        env -u DISPLAY prusa-slicer --export-3mf -o "$out/$name.3mf" "$model" >"$out/$name.3mf.log" 2>&1
        /usr/bin/python3 "$here/adaptive_cusp.py" prusa-3mf "$out/$name.3mf" "$out/$name.plan.txt" "$out/$name.profile.3mf"
        peer_cmd prusa "$out/$name.profile.3mf" "$g" ;;
    esac
    env -u DISPLAY timeout 900 "${CMD[@]}" </dev/null >"$out/$name.$s.log" 2>&1
    if [[ ! -s $g ]]; then
      printf '%s\t%s\t0\t0\t0\tfailed\n' "$name" "$label" >>"$rows"
      continue
    fi
    /usr/bin/python3 "$here/adaptive_cusp.py" row "$name" "$label" "$model" "$g" "$(verdict "$model" "$g")" >>"$rows"
  done
done < <(bench_models "$MODELS")
/usr/bin/python3 "$here/adaptive_cusp.py" table "$rows"
[[ -n ${OUT:-} ]] && echo "files kept in $out"
