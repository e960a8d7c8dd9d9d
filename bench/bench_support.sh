#!/usr/bin/env bash
# Support material against PrusaSlicer's: each model with overhangs (generated: a mushroom, a
# bracket's ledge, a slab spanning 30 mm, a 53° funnel; PrusaSlicer's bunny; the capped Stanford
# bunny) sliced by tranche without support, with support=normal and support=tree, by PrusaSlicer with
# --support-material --support-material-auto, and by CuraEngine with its tree support (cura_tree, at
# tranche's 45°, 0.2 mm and 0.5 mm gaps), all on the benchmark settings (bench/peers/). gcheck
# measures what each lays on air (its `unsupported` line); support_row.py the support's plastic
# and trips; time is user seconds. One table, then tranche's ratios to PrusaSlicer, and its tree's
# to Cura's.
# tranche_touch is support=normal with stdlib/features/support-touching-near-bed.rules: support
# also touches what hangs less than support_z_gap above the bed (no support with a gap fits
# there), as PrusaSlicer's first support layer does; tranche and tranche_tree keep the gap
# everywhere, so such an overhang (a flared foot's second layer) counts in their air.
# "fused" (support_fused.py) is the support that touches the part: closer than support_xy_gap
# less half a bead beside it, or under it closer than support_z_gap (mm², slivers under half a
# bead wide left out); issue 12 wants none of it by default.
#   bench/bench_support.sh [BUILD_DIR]      env: MODELS, GCHECK=path/to/gcheck.py, OUT=dir to keep files
set -uo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
. "$here/peers/common.sh"
bench_setup "$build" || { echo "bench_support: cannot build tranche"; exit 1; }
bench_need_gcheck bench_support
MODELS=${MODELS:-mushroom ledge span slope bunny stanford_bunny_closed}
bench_workdir support
while read -r name model; do
  for s in tranche_none tranche tranche_tree tranche_touch prusa cura_tree; do
    g="$out/$name.$s.gcode"
    case $s in
      tranche_none) peer_cmd tranche "$model" "$g" ;;
      tranche) peer_cmd tranche "$model" "$g"; CMD+=(--set support=normal) ;;
      tranche_tree) peer_cmd tranche "$model" "$g"; CMD+=(--set support=tree) ;;
      tranche_touch) peer_cmd tranche "$model" "$g"
        CMD+=(--set support=normal --rules "$here/../stdlib/features/support-touching-near-bed.rules") ;;
      cura_tree) command -v CuraEngine >/dev/null || continue
        peer_cmd cura_tree "$model" "$g" || continue ;;
      prusa) command -v prusa-slicer >/dev/null || continue
        peer_cmd prusa "$model" "$g"; CMD=("${CMD[@]:0:1}" --support-material --support-material-auto "${CMD[@]:1}") ;;
    esac
    env -u DISPLAY /usr/bin/time -f %U -o "$out/$name.$s.time" timeout 900 "${CMD[@]}" </dev/null >"$out/$name.$s.log" 2>&1
    t=$(tail -1 "$out/$name.$s.time" 2>/dev/null)
    if [[ ! -s $g ]]; then
      printf '%s\t%s\tfailed\n' "$name" "$s" >>"$rows"
      continue
    fi
    off=$(/usr/bin/python3 "$here/quality_row.py" --offset "$model" 100,100)
    /usr/bin/python3 "$GCHECK" "$model" "$g" --offset="$off" --json "$out/$name.$s.json" >"$out/$name.$s.gcheck" 2>&1
    fused=""
    [[ $s != tranche_none ]] && fused=$(/usr/bin/python3 "$here/support_fused.py" "$g")
    /usr/bin/python3 "$here/support_row.py" "$name" "$s" "$out/$name.$s.json" "$g" "$t" "$fused" >>"$rows"
  done
done < <(bench_models "$MODELS")
/usr/bin/python3 "$here/support_row.py" --table "$rows"
[[ -n ${OUT:-} ]] && echo "files kept in $out"
