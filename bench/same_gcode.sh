#!/usr/bin/env bash
# Refactoring check: slices the benchmark models (bench_quality.sh's set and the 819k torus,
# with the benchmark settings and with the default profile), every example (its rules, options
# and runs), every stdlib feature and bench/rules/realistic50.rules with two builds of tranche,
# and compares the G-code byte for byte. Prints one line per case and a count; exit 1 when any
# G-code differs (the first differing lines are shown).
#   bench/same_gcode.sh OLD_TRANCHE NEW_TRANCHE [OUT_DIR]
#   env: MODELS="bunny sphere ..." (default: all), CASES="bench defaults examples features" (default: all)
# OLD_TRANCHE may be a binary kept from before the change (`cp build/apps/tranche /tmp/old`); it
# reads the stdlib of this checkout (--stdlib), so a change that edits stdlib/ is compared too.
set -uo pipefail
if [[ $# -lt 2 ]]; then
  echo "usage: bench/same_gcode.sh OLD_TRANCHE NEW_TRANCHE [OUT_DIR]" >&2
  exit 2
fi
old=$(readlink -f "$1")
new=$(readlink -f "$2")
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
. "$here/peers/common.sh"
build=${BUILD:-$root/build}
bench_setup "$build" || { echo "same_gcode: cannot build bench_models"; exit 1; }
out=${3:-$(mktemp -d "${TMPDIR:-/tmp}/tranche-same-XXXXXX")}
mkdir -p "$out/old" "$out/new" "$out/models"
CASES=${CASES:-bench defaults examples features}
want() { [[ " $CASES " == *" $1 "* ]]; }
same=0
differ=0
failed=0

# run NAME DIR ARGS...: slices with both binaries from DIR, compares.
run() {
  local name=$1 dir=$2
  shift 2
  local rc_old rc_new
  (cd "$dir" && "$old" slice "$@" -o "$out/old/$name.gcode" --stdlib "$root/stdlib" --quiet) >"$out/old/$name.log" 2>&1
  rc_old=$?
  (cd "$dir" && "$new" slice "$@" -o "$out/new/$name.gcode" --stdlib "$root/stdlib" --quiet) >"$out/new/$name.log" 2>&1
  rc_new=$?
  if [[ $rc_old -ne 0 || $rc_new -ne 0 ]]; then
    if [[ $rc_old -ne $rc_new ]]; then
      printf '%-40s FAILED (exit %s before, %s now)\n' "$name" "$rc_old" "$rc_new"
      failed=$((failed + 1))
    else
      printf '%-40s both exit %s\n' "$name" "$rc_old"
      same=$((same + 1))
    fi
    return
  fi
  if cmp -s "$out/old/$name.gcode" "$out/new/$name.gcode"; then
    printf '%-40s same (%s bytes)\n' "$name" "$(stat -c %s "$out/new/$name.gcode")"
    same=$((same + 1))
  else
    printf '%-40s DIFFERENT\n' "$name"
    diff "$out/old/$name.gcode" "$out/new/$name.gcode" | head -8 | sed 's/^/    /'
    differ=$((differ + 1))
  fi
}

if want bench || want defaults; then
  while read -r name model; do
    want bench && run "bench-$name" "$root" "$model" "${TRANCHE_SETS[@]}"
    want defaults && [[ $name != torus819k ]] && run "default-$name" "$root" "$model"
  done < <(bench_models "${MODELS:-all}")
fi

if want examples; then
  for env in "$root"/examples/*/example.env; do
    dir=$(dirname "$env")
    ex=$(basename "$dir")
    MODEL=model.stl ARGS="" RUNS="" EXPLAIN=()
    # shellcheck source=/dev/null
    source "$env"
    RUNS=${RUNS:-$ex}
    rules=("$dir"/*.rules)
    model="$dir/$MODEL"
    if [[ -f "$dir/make_model.py" ]]; then
      model="$out/models/$ex.stl"
      [[ -f $model ]] || python3 "$dir/make_model.py" "$model" >/dev/null
    fi
    for r in $RUNS; do
      extra_var="ARGS_${r//[^A-Za-z0-9_]/_}"
      # shellcheck disable=SC2086
      run "example-$ex-$r" "$dir" "$model" --rules "${rules[0]}" $ARGS ${!extra_var:-}
    done
  done
fi

if want features; then
  model=/usr/share/PrusaSlicer/shapes/bunny.stl
  [[ -f $model ]] || model="$root/examples/models/demo.stl"
  for f in "$root"/stdlib/features/*.rules; do
    run "feature-$(basename "$f" .rules)" "$root" "$model" --rules "$f"
  done
  run "realistic50" "$root" "$model" --rules "$here/rules/realistic50.rules"
fi

echo "same: $same  different: $differ  failed: $failed   (files in $out)"
[[ $differ -eq 0 && $failed -eq 0 ]]
