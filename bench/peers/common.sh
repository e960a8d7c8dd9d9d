# Shared by bench_quality.sh and bench_peers.sh: matched settings for tranche and its peers,
# benchmark models, and the command line of each slicer. Source it; then `bench_setup BUILD`.
# shellcheck shell=bash

PEERS_DIR=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
BENCH_DIR=$(dirname "$PEERS_DIR")
ROOT=$(dirname "$BENCH_DIR")
CACHE=${TRANCHE_CACHE:-${HOME:-/tmp}/.cache/tranche}

# The benchmark settings, as tranche --set options (see prusaslicer.ini and cura.settings).
TRANCHE_SETS=(
  --set layer_height=0.2 --set first_layer_height=0.2 --set width=0.45 --set nozzle_diameter=0.4
  --set filament_diameter=1.75 --set perimeters=2 --set infill_density=20% --set top_layers=3
  --set bottom_layers=3 --set skirt_loops=0 --set infill_overlap=25% --set relative_e=false
  --set nozzle_temp=200 --set bed_temp=0 --set retract_length=2 --set retract_speed=40
  --set retract_before_travel=2 --set bed_size_x=200 --set bed_size_y=200
)

bench_setup() {
  local build=${1:-build}
  TRANCHE="$build/apps/tranche"
  BENCH_MODELS="$build/bench/bench_models"
  if [[ ! -x "$TRANCHE" || ! -x "$BENCH_MODELS" ]]; then
    cmake --build "$build" --target tranche bench_models >/dev/null || return 1
  fi
  mkdir -p "$CACHE/bench"
}

# Writes the generated models into $CACHE/bench (once) and prints NAME PATH lines for $1 (a
# space-separated list of names, or "all").
# gcheck for the quality columns: GCHECK (default: the workplace's copy), which `bench_need_gcheck
# NAME` requires (a message naming the bench and exit 1 when it is missing).
GCHECK=${GCHECK:-/work/shared/tools/gcheck/gcheck.py}
bench_need_gcheck() {
  [[ -f $GCHECK ]] || { echo "$1: gcheck not found (set GCHECK=path/to/gcheck.py)"; exit 1; }
}

# A bench's folder for its files: $OUT (kept) or a temporary one removed on exit, with SUBDIR
# made in it; sets `out` and `rows` (an empty $out/rows.tsv) and LC_ALL=C for the number
# formats. bench_workdir NAME [SUBDIR]
bench_workdir() {
  out=${OUT:-$(mktemp -d "${TMPDIR:-/tmp}/tranche-$1-XXXXXX")}
  [[ -n ${OUT:-} ]] || trap 'rm -rf "$out"' EXIT
  mkdir -p "$out/${2:-}"
  export LC_ALL=C
  rows="$out/rows.tsv"
  : >"$rows"
}

# Runs "${CMD[@]}" (set by peer_cmd) for model NAME with slicer S, writing G-code G, its output in
# $out/NAME.S.log; when G comes out empty, a "failed" row goes to $rows and it returns 1.
# bench_run NAME S G [TIMEOUT_S]
bench_run() {
  local rc
  env -u DISPLAY timeout "${4:-600}" "${CMD[@]}" </dev/null >"$out/$1.$2.log" 2>&1
  rc=$?
  [[ -s $3 ]] && return 0
  printf '%s\t%s\tfailed (exit %s: %s)\n' "$1" "$2" "$rc" "$(grep -v '^\s*$' "$out/$1.$2.log" | tail -1 | cut -c1-60)" >>"$rows"
  return 1
}

bench_models() {
  local want=${1:-all} d="$CACHE/bench"
  "$ROOT/scripts/fetch-models.sh" >/dev/null 2>&1 || true
  local stl_models=${TRANCHE_MODELS_DIR:-$CACHE/models}
  # Made again when bench_models is newer than the file (its recipe may have changed).
  fresh() { [[ -f $1 && ! $BENCH_MODELS -nt $1 ]]; }
  fresh "$d/plate_holes.stl" || "$BENCH_MODELS" plate "$d/plate_holes.stl" >/dev/null
  fresh "$d/torus819k.stl" || "$BENCH_MODELS" torus "$d/torus819k.stl" >/dev/null
  if ! fresh "$d/stanford_bunny.stl" && [[ -f "$stl_models/objects/bunny.bin.stl" ]]; then
    "$BENCH_MODELS" bunny "$stl_models/objects/bunny.bin.stl" "$d/stanford_bunny.stl" >/dev/null
  fi
  if ! fresh "$d/stanford_bunny_closed.stl" && [[ -f "$stl_models/objects/bunny.bin.stl" ]]; then
    "$BENCH_MODELS" bunny_closed "$stl_models/objects/bunny.bin.stl" "$d/stanford_bunny_closed.stl" >/dev/null
  fi
  local m
  for m in mushroom ledge span slope; do fresh "$d/$m.stl" || "$BENCH_MODELS" $m "$d/$m.stl" >/dev/null; done
  local shapes=/usr/share/PrusaSlicer/shapes
  local name path
  while read -r name path; do
    if [[ $want == all || " $want " == *" $name "* ]]; then
      if [[ -f $path ]]; then echo "$name $path"; else echo "bench: $name ($path) missing, skipped" >&2; fi
    fi
  done <<EOM
bunny $shapes/bunny.stl
torus $shapes/torus.stl
M3_hex_nut $shapes/M3_hex_nut.stl
M3x10_screw $shapes/M3x10_screw.stl
sphere $shapes/sphere.stl
cone $shapes/cone.stl
stanford_bunny $d/stanford_bunny.stl
stanford_bunny_closed $d/stanford_bunny_closed.stl
plate_holes $d/plate_holes.stl
torus819k $d/torus819k.stl
mushroom $d/mushroom.stl
ledge $d/ledge.stl
span $d/span.stl
slope $d/slope.stl
EOM
}

# CuraEngine needs fdmprinter.def.json, which Debian ships in the `cura` package (not
# cura-engine): downloaded once into the cache, never into the checkout.
cura_defs() {
  local d="$CACHE/cura"
  if [[ ! -f "$d/definitions/fdmprinter.def.json" ]]; then
    local tmp
    tmp=$(mktemp -d) || return 1
    (cd "$tmp" && apt-get download cura >/dev/null 2>&1 && dpkg -x cura_*.deb x) || { rm -rf "$tmp"; return 1; }
    mkdir -p "$d"
    rm -rf "$d/definitions"
    mv "$tmp/x/usr/share/cura/resources/definitions" "$d/definitions"
    rm -rf "$tmp"
  fi
  if [[ ! -f "$d/args" || "$PEERS_DIR/cura.settings" -nt "$d/args" ]]; then
    /usr/bin/python3 "$BENCH_DIR/cura_settings.py" "$d/definitions" "$PEERS_DIR/cura.settings" >"$d/args" || return 1
  fi
  CURA_DEFS="$d/definitions"
  mapfile -d '' -t CURA_ARGS <"$d/args"
}

# cura_variant NAME 'key = value'...: CURA_VARIANT_ARGS, the arguments of cura.settings with these
# lines after it (the last value of a key wins, and the settings whose formulas read it follow),
# cached as args.NAME until the lines or cura.settings change. CURA_ARGS stays the plain set.
cura_variant() {
  [[ -n ${CURA_DEFS:-} ]] || cura_defs || return 1
  local name=$1 d="$CACHE/cura"
  shift
  { cat "$PEERS_DIR/cura.settings"; printf '%s\n' "$@"; } >"$d/settings.$name.new"
  if [[ -f "$d/args.$name" ]] && cmp -s "$d/settings.$name.new" "$d/settings.$name"; then
    rm -f "$d/settings.$name.new"
  else
    mv "$d/settings.$name.new" "$d/settings.$name"
    /usr/bin/python3 "$BENCH_DIR/cura_settings.py" "$d/definitions" "$d/settings.$name" >"$d/args.$name" ||
      { rm -f "$d/args.$name"; return 1; }
  fi
  mapfile -d '' -t CURA_VARIANT_ARGS <"$d/args.$name"
}

# After `peer_cmd SLICER MODEL OUT`, CMD holds the command line (SLICER: tranche, tranche_comb,
# tranche_classic, tranche_variable, prusa, cura, cura_tree).
peer_cmd() {
  local slicer=$1 model=$2 out=$3
  case $slicer in
    tranche) CMD=("$TRANCHE" slice "$model" -o "$out" --quiet "${TRANCHE_SETS[@]}") ;;
    # The wall generators by name (docs/language.md, "Walls"): tranche is the default's.
    tranche_classic | tranche_variable)
      CMD=("$TRANCHE" slice "$model" -o "$out" --quiet "${TRANCHE_SETS[@]}" --set "wall_generator=${slicer#tranche_}") ;;
    # CuraEngine's combing policy (no distance limit): retract only when a travel leaves the part.
    tranche_comb)
      CMD=("$TRANCHE" slice "$model" -o "$out" --quiet "${TRANCHE_SETS[@]}" --set retract_long_travel=10000) ;;
    prusa) CMD=(prusa-slicer --export-gcode --load "$PEERS_DIR/prusaslicer.ini" --center 100,100 -o "$out" "$model") ;;
    cura)
      [[ -n ${CURA_DEFS:-} ]] || cura_defs || { echo "bench: cannot get Cura's definitions (apt-get download cura)" >&2; return 1; }
      CMD=(CuraEngine slice -j "$CURA_DEFS/fdmprinter.def.json" "${CURA_ARGS[@]}" -l "$model" -o "$out") ;;
    # Cura's tree support, at tranche's support defaults (45°, 0.2 mm above, 0.5 mm beside).
    cura_tree)
      cura_variant tree "support_enable = True" "support_structure = tree" "support_angle = 45" \
        "support_z_distance = 0.2" "support_xy_distance = 0.5" ||
        { echo "bench: cannot get Cura's definitions (apt-get download cura)" >&2; return 1; }
      CMD=(CuraEngine slice -j "$CURA_DEFS/fdmprinter.def.json" "${CURA_VARIANT_ARGS[@]}" -l "$model" -o "$out") ;;
    *) echo "bench: unknown slicer $slicer" >&2; return 1 ;;
  esac
}
