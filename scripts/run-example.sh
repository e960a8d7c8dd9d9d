#!/usr/bin/env bash
# Runs one example of examples/: generates its model, checks its rules (no warnings allowed),
# slices it and writes the G-code and a layer preview (SVG) into the output folder.
#   scripts/run-example.sh BUILD NAME [OUTDIR]      (OUTDIR defaults to out/NAME)
#   make example NAME=temperature-tower             (the same, after building)
#
# An example folder holds a README.md, one .rules file, a model (make_model.py, which writes
# model.stl into the output folder, or a hand-written .svg) and example.env, sourced here:
#   MODEL=model.stl            the model: made by make_model.py, else a file of the folder
#   ARGS="--printer ender3"    options for every `tranche slice` of the example
#   RUNS="a b"                 several slices (default: one, named after the example), each
#   ARGS_a="--overlap boolean"   with its own extra options (ARGS_<run>, other characters than
#                              letters, digits and _ written as _)
#   EXPLAIN=("layer.index=0, path.kind=outer_perimeter" ...)   `rulec explain --at` contexts,
#                              written to explain.txt
set -euo pipefail

if [[ $# -lt 2 || -z "$2" ]]; then
  echo "usage: scripts/run-example.sh BUILD NAME [OUTDIR]   (NAME: a folder of examples/)" >&2
  echo "examples:" $(cd "$(dirname "$0")/../examples" && for d in */; do [[ -f "$d/example.env" ]] && printf '%s ' "${d%/}"; done) >&2
  exit 2
fi
root=$(cd "$(dirname "$0")/.." && pwd)
build=$1
name=$2
[[ "$build" = /* ]] || build="$root/$build"
src="$root/examples/$name"
out=${3:-"$root/out/$name"}
[[ "$out" = /* ]] || out="$PWD/$out"
tranche="$build/apps/tranche"
rulec="$build/apps/rulec"

if [[ ! -f "$src/example.env" ]]; then
  echo "run-example: no example '$name' (no examples/$name/example.env)" >&2
  exit 2
fi
for exe in "$tranche" "$rulec"; do
  [[ -x "$exe" ]] || { echo "run-example: $exe not found: build first (make build)" >&2; exit 2; }
done
python=${PYTHON:-python3}

MODEL=model.stl
ARGS=""
RUNS=""
EXPLAIN=()
# shellcheck source=/dev/null
source "$src/example.env"
RUNS=${RUNS:-$name}

shopt -s nullglob
rules=("$src"/*.rules)
shopt -u nullglob
if [[ ${#rules[@]} -ne 1 ]]; then
  echo "run-example: examples/$name must hold exactly one .rules file" >&2
  exit 2
fi
rules=${rules[0]}

mkdir -p "$out"
if [[ -f "$src/make_model.py" ]]; then
  echo "== model: $python examples/$name/make_model.py $out/$MODEL"
  "$python" "$src/make_model.py" "$out/$MODEL"
  model="$out/$MODEL"
else
  model="$src/$MODEL"
fi

echo "== rulec check -W error examples/$name/$(basename "$rules")"
"$rulec" check -W error --stdlib "$root/stdlib" "$rules"

if [[ ${#EXPLAIN[@]} -gt 0 ]]; then
  : >"$out/explain.txt"
  for at in "${EXPLAIN[@]}"; do
    echo "== rulec explain $(basename "$rules") --at \"$at\"" | tee -a "$out/explain.txt"
    "$rulec" explain --stdlib "$root/stdlib" "$rules" --at "$at" 2>&1 | tee -a "$out/explain.txt"
    echo | tee -a "$out/explain.txt"
  done
fi

for run in $RUNS; do
  extra_var="ARGS_${run//[^A-Za-z0-9_]/_}"
  extra=${!extra_var:-}
  # Relative paths in ARGS (a script, a bundle) are relative to the example's folder.
  echo "== tranche slice $(basename "$model") -o $run.gcode --rules $(basename "$rules") $ARGS $extra"
  # shellcheck disable=SC2086
  (cd "$src" && "$tranche" slice "$model" -o "$out/$run.gcode" --export-svg "$out/$run.svg" \
     --stdlib "$root/stdlib" --rules "$rules" $ARGS $extra --quiet)
done

echo
echo "example $name: output in $out/"
for run in $RUNS; do
  echo "  G-code: $out/$run.gcode    preview (open in a browser): $out/$run.svg"
done
[[ ${#EXPLAIN[@]} -gt 0 ]] && echo "  rulec explain: $out/explain.txt"
echo "  what to look for: examples/$name/README.md"
