#!/usr/bin/env bash
# Infill patterns against PrusaSlicer's same pattern: each model sliced by tranche with
# --set infill_pattern=P and by PrusaSlicer with --fill-pattern P (our zigzag against its
# rectilinear), all on the benchmark settings (bench/peers/, 20 % infill). infill_row.py counts
# the sparse infill's plastic (;TYPE:Internal infill), trips and retractions per layer; time is
# user seconds (ours: the median of RUNS runs, default 3), compared to our own zigzag on the
# same model; gcheck's verdict on our G-code
# (when gcheck is found: GCHECK=path/to/gcheck.py). One table, then the geometric means per
# pattern.
#   bench/bench_infill.sh [BUILD_DIR]   env: MODELS (default: sphere cone bunny plate_holes),
#                                           PATTERNS (default: all), RUNS (default 3), OUT=dir to keep the files,
#                                           GCHECK (default: /work/shared/tools/gcheck/gcheck.py)
set -uo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
. "$here/peers/common.sh"
bench_setup "$build" || { echo "bench_infill: cannot build tranche"; exit 1; }
MODELS=${MODELS:-sphere cone bunny plate_holes}
PATTERNS=${PATTERNS:-zigzag grid triangles cubic gyroid honeycomb concentric lightning}
bench_workdir infill
while read -r name model; do
  for p in $PATTERNS; do
    for s in tranche prusa; do
      g="$out/$name.$p.$s.gcode"
      if [[ $s == tranche ]]; then
        peer_cmd tranche "$model" "$g"
        CMD+=(--set "infill_pattern=$p")
      else
        command -v prusa-slicer >/dev/null || continue
        peer_cmd prusa "$model" "$g"
        pp=$p
        [[ $p == zigzag ]] && pp=rectilinear
        CMD=("${CMD[@]:0:1}" --fill-pattern "$pp" "${CMD[@]:1}")
      fi
      # Our runs are short (a tenth of a second on the small models): each is run RUNS times and
      # the median user time kept, measured to the microsecond (usertime.py).
      runs=1
      [[ $s == tranche ]] && runs=${RUNS:-3}
      : >"$out/$name.$p.$s.times"
      for ((r = 0; r < runs; r++)); do
        env -u DISPLAY /usr/bin/python3 "$here/usertime.py" "$out/$name.$p.$s.time" timeout 900 "${CMD[@]}" \
          </dev/null >"$out/$name.$p.$s.log" 2>&1
        tail -1 "$out/$name.$p.$s.time" >>"$out/$name.$p.$s.times"
      done
      sort -g "$out/$name.$p.$s.times" | sed -n "$(((runs + 1) / 2))p" >"$out/$name.$p.$s.time"
      if [[ ! -s $g ]]; then
        echo "bench_infill: $s failed on $name with $p (see $out/$name.$p.$s.log)" >&2
        continue
      fi
      verdict=-
      if [[ $s == tranche && -f $GCHECK ]]; then
        off=$(/usr/bin/python3 "$here/quality_row.py" --offset "$model" 100,100)
        /usr/bin/python3 "$GCHECK" "$model" "$g" --offset="$off" >"$out/$name.$p.$s.gcheck" 2>&1
        verdict=$(sed -n 's/^ *verdict *: *\([A-Z]*\).*/\1/p' "$out/$name.$p.$s.gcheck")
      fi
      /usr/bin/python3 "$here/infill_row.py" "$name" "$p" "$s" "$g" "$(tail -1 "$out/$name.$p.$s.time")" \
        "${verdict:-?}" >>"$rows"
    done
  done
done < <(bench_models "$MODELS")
/usr/bin/python3 "$here/infill_row.py" --table "$rows"
[[ -n ${OUT:-} ]] && echo "files kept in $out"
exit 0
