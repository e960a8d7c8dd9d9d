#!/usr/bin/env bash
# Output quality as a user would check it: slices each model with tranche and its peers on the
# same settings (bench/peers/), checks every G-code with gcheck (an independent checker that
# re-slices the STL), and prints one table: gcheck's verdict and coverages, plastic volume
# against PrusaSlicer's, travel moves and retractions, and tranche's ratios to each peer.
#   bench/bench_quality.sh [BUILD_DIR]
#   env: MODELS="torus cone ..." (default: PrusaSlicer's shapes, the Stanford bunny as published
#        (its base open) and with its holes capped (bench_models bunny_closed), a plate with
#        holes), SLICERS="tranche tranche_comb prusa cura", GCHECK=path/to/gcheck.py, OUT=dir to
#        keep files. tranche_comb (tranche with CuraEngine's retraction policy) is only counted;
#        tranche_classic and tranche_variable are tranche with that wall_generator.
set -uo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
. "$here/peers/common.sh"
bench_setup "$build" || { echo "bench_quality: cannot build tranche"; exit 1; }
bench_need_gcheck bench_quality
SLICERS=${SLICERS:-tranche tranche_comb prusa cura}
MODELS=${MODELS:-bunny torus M3_hex_nut M3x10_screw sphere cone stanford_bunny stanford_bunny_closed plate_holes}
bench_workdir quality
while read -r name model; do
  for s in $SLICERS; do
    [[ $s == prusa ]] && ! command -v prusa-slicer >/dev/null && continue
    [[ $s == cura ]] && ! command -v CuraEngine >/dev/null && continue
    g="$out/$name.$s.gcode"
    peer_cmd "$s" "$model" "$g" || continue
    bench_run "$name" "$s" "$g" 900 || continue
    if [[ $s == tranche_comb ]]; then
      /usr/bin/python3 "$here/quality_row.py" "$name" "$s" - "$g" >>"$rows"
      continue
    fi
    # Every slicer centres the model's bounding box on the bed's centre: tell gcheck, instead of
    # letting it guess from the first layer (a speck on the Stanford bunny) or sampled layers.
    off=$(/usr/bin/python3 "$here/quality_row.py" --offset "$model" 100,100)
    /usr/bin/python3 "$GCHECK" "$model" "$g" --offset="$off" --json "$out/$name.$s.json" \
      >"$out/$name.$s.gcheck" 2>&1
    /usr/bin/python3 "$here/quality_row.py" "$name" "$s" "$out/$name.$s.json" "$g" >>"$rows"
  done
done < <(bench_models "$MODELS")
/usr/bin/python3 "$here/quality_row.py" --table "$rows"
[[ -n ${OUT:-} ]] && echo "files kept in $out"
