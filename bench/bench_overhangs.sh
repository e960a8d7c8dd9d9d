#!/usr/bin/env bash
# Overhanging walls (issue 14): the overhang speed steps of stdlib/defaults.rules and what gcheck
# says of overhangs. Models (overhang_models.py): cups flaring 45° and 70° from vertical, a flat
# shelf hanging 10 mm out on two sides; and the Stanford bunny (bench/peers/common.sh), where the
# question is whether the steps flip the speed back and forth on a curved surface. Each sliced by
# tranche with the steps (the default), without them (--set overhang_speeds=false), and by
# PrusaSlicer 2.5 (bench/peers settings; it has no dynamic overhang speeds, it prints overhanging
# wall pieces as "Overhang perimeter" at its bridge speed). Both with no slowdown for short layers,
# so that every slower wall move is an overhang's. One table (bench/overhang_row.py): gcheck's
# verdict, coverage, band coverage and unsupported area (the generated models), the wall length
# printed slower than the wall's speed, the feed-rate changes and the extruding moves.
# Measured (2026-11-26, this machine, `OUT=/tmp/o bench/bench_overhangs.sh build`): Stanford
# bunny 16265 feed-rate changes with the steps, 12815 without (+27%; PrusaSlicer 26152), on 1.13 M
# extruding moves; the walls' mean speed 34.6 against 34.9 mm/s. The 70° cup's walls 19.9 mm/s
# with the steps, 34.8 without (every layer hangs 0.55 mm out: outer wall wholly in the air, inner
# half); the 45° cup unchanged (0.2 mm a layer, 44% of the bead: the first step is 25 mm/s, the
# outer wall's own speed); the shelf's first layer's walls slowed (34.6 → 34.1 mm/s over the print).
# gcheck's unsupported area is the same with or without the steps and for PrusaSlicer (flares
# 0 mm²: 0.55 mm a layer is within its allowance of nozzle/2 + layer height once opened by half a
# nozzle; the shelf 191 mm² against PrusaSlicer's 197 on its first layer): it counts where plastic
# is laid over air, not how, so it cannot tell a bridged shelf from loops in the air.
# So the last four columns (bench/overhang_anchor.py) follow each extruding path: a point of it
# rests on the layer below when the model's slice there lies within half a bead of it; air_mm is
# the extrusion that does not (wall_air: of it, in walls), span_max and span_p95 the longest
# unanchored span (along the path from the last point resting on the layer below to the next)
# and the one within which 95% of air_mm lies. Models: also `ledges`, a plate hanging 3 mm out
# on one side and 15 mm on the other. Slicers: tranche (overhang_walls = bridge, the default),
# tranche_loops (overhang_walls = loops), tranche_nosteps, PrusaSlicer, CuraEngine.
# Measured (2026-11-26, `OUT=/tmp/o MODELS="flare_45 flare_70 shelf ledges" SLICERS="tranche
# tranche_loops prusa cura" bench/bench_overhangs.sh build`): shelf air 468 / 506 / 446 / 440 mm
# (tranche / loops / PrusaSlicer / Cura), walls in the air 0 / 112 / 111 / 111 mm, longest span
# 19.5 / 109.5 / 170.6 / 28.7 mm; ledges walls in the air 0 / 104 / 102 / 103 mm, longest span
# 29.5 / 232 / 255 / 24.1 mm (a zig-zag's line out and back over the 15 mm ledge; Cura lays its
# bridge lines one by one). gcheck's coverage, band and unsupported area within 0.001 / 0.001 /
# 0.6 mm² of the loops'. The flares are unchanged (their walls lean out less than a bead a layer:
# every slicer leaves the 70° cup's outer wall in the air, 1313-1376 mm, spans of a whole loop).
# The Stanford bunny's anchoring is slow to compute (ANCHOR_BUNNY=1 to include it; about 9
# minutes a file). Capped bunny (stanford_bunny_closed), bench settings, bridge / loops: air
# 12678 / 12863 mm, walls in the air 5283 / 6256 mm, span_max 247 / 247, span_p95 90 / 92 mm
# (8 layers bridged: the belly's 9th and 24th-30th; its first layers lie over too little to
# hold 80% of a bridge's lines and keep their loops). gcheck there: band mean 0.980 / 0.981,
# min 0.926 / 0.926, skin 0.998 / 0.998, overflow 0.95 / 0.32 mm² in all, no layer flagged.
#   bench/bench_overhangs.sh [BUILD_DIR]
#   env: MODELS="flare_45 flare_70 shelf ledges stanford_bunny" (default: all), SLICERS="tranche
#        tranche_loops tranche_nosteps prusa cura", GCHECK=path/to/gcheck.py, OUT=dir to keep files,
#        ANCHOR_BUNNY=1 to measure the bunny's anchoring too.
set -uo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
. "$here/peers/common.sh"
bench_setup "$build" || { echo "bench_overhangs: cannot build tranche"; exit 1; }
SLICERS=${SLICERS:-tranche tranche_loops tranche_nosteps prusa cura}
bench_workdir overhangs models
while read -r name model; do
  [[ -n ${MODELS:-} && " $MODELS " != *" $name "* ]] && continue
  [[ -f $model ]] || continue
  for s in $SLICERS; do
    g="$out/$name.$s.gcode"
    case $s in
      tranche) peer_cmd tranche "$model" "$g" && CMD+=(--set min_layer_time=0) || continue ;;
      tranche_nosteps) peer_cmd tranche "$model" "$g" && CMD+=(--set min_layer_time=0 --set overhang_speeds=false) || continue ;;
      tranche_loops) peer_cmd tranche "$model" "$g" && CMD+=(--set min_layer_time=0 --set overhang_walls=loops) || continue ;;
      prusa)
        command -v prusa-slicer >/dev/null || continue
        peer_cmd prusa "$model" "$g" && CMD+=(--slowdown-below-layer-time 0) || continue ;;
      cura)
        command -v CuraEngine >/dev/null || continue
        peer_cmd cura "$model" "$g" || continue ;;
      *) echo "bench_overhangs: unknown slicer $s" >&2; continue ;;
    esac
    bench_run "$name" "$s" "$g" || continue
    js=-
    off=$(/usr/bin/python3 "$here/quality_row.py" --offset "$model" 100,100)
    if [[ $name != stanford_bunny && -f $GCHECK ]]; then
      /usr/bin/python3 "$GCHECK" "$model" "$g" --offset="$off" --json "$out/$name.$s.json" >"$out/$name.$s.gcheck" 2>&1 &&
        js="$out/$name.$s.json"
    fi
    anchor=("$model" "$off")
    [[ $name == stanford_bunny && -z ${ANCHOR_BUNNY:-} ]] && anchor=()
    /usr/bin/python3 "$here/overhang_row.py" "$name" "$s" "$g" "$js" "${anchor[@]}" >>"$rows"
  done
done < <(/usr/bin/python3 "$here/overhang_models.py" "$out/models"; bench_models stanford_bunny)
/usr/bin/python3 "$here/overhang_row.py" --table "$rows"
[[ -n ${OUT:-} ]] && echo "files kept in $out"
