#!/usr/bin/env bash
# The CTest test of the HTML preview in a real browser: installs puppeteer-core into WORK
# (install.sh; exit 77, skipped, when node, npm, Chromium or the registry cannot be had), writes
# the fixture page with FIXTURE_EXE and runs preview_test.js in headless Chromium; with
# --tranche EXE, also slices a block with EXE (`tranche slice --export-preview`) and runs
# real_slice_test.js on that page.
# --screenshot also saves the page as the README shows it (docs/images/preview.png).
#   run.sh WORK FIXTURE_EXE [--tranche EXE] [--screenshot OUT.png]
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
usage="usage: run.sh WORK FIXTURE_EXE [--tranche EXE] [--screenshot OUT.png]"
work=${1:?$usage}
fixture=${2:?$usage}
shift 2
shot="" tranche=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --screenshot) shot=$(realpath -m "${2:?--screenshot needs a file}"); shift 2 ;;
    --tranche) tranche=$(realpath -m "${2:?--tranche needs the tranche executable}"); shift 2 ;;
    *) echo "$usage"; exit 2 ;;
  esac
done

bash "$here/install.sh" "$work" || exit $?
if ! "$fixture" "$work/fixture.html" "$work/fixture.json"; then
  echo "FAIL: $fixture could not write the fixture page"
  exit 1
fi
args=("$work/node_modules" "$work/fixture.html" "$work/fixture.json")
if [[ -n "$shot" ]]; then args+=("$shot"); fi
node "$here/preview_test.js" "${args[@]}" || exit 1
[[ -z "$tranche" ]] && exit 0

# A real slice: a 20 x 10 x 5 mm block (ASCII STL), a rule that halves the outer wall's speed
# (line 2) and an executor before it (line 3).
real="$work/real"
mkdir -p "$real"
python3 - "$real/block.stl" <<'PY'
import sys
x, y, z = 20.0, 10.0, 5.0
v = [(a * x, b * y, c * z) for a in (0, 1) for b in (0, 1) for c in (0, 1)]
quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
with open(sys.argv[1], "w") as f:
    f.write("solid block\n")
    for a, b, c, d in quads:
        for t in ((a, b, c), (a, c, d)):
            f.write(" facet normal 0 0 0\n  outer loop\n")
            for i in t:
                f.write("   vertex %g %g %g\n" % v[i])
            f.write("  endloop\n endfacet\n")
    f.write("endsolid block\n")
PY
cat >"$real/walls.rules" <<'RULES'
# walls
rule "slow walls" when path.kind == outer_perimeter { speed = speed * 50% }
rule "pa" when path.kind == outer_perimeter { before path { gcode "M900 K0.045" } }
RULES
if ! "$tranche" slice "$real/block.stl" --rules "$real/walls.rules" -o "$real/block.gcode" \
     --export-preview "$real/block.html" --quiet; then
  echo "FAIL: $tranche could not slice the block"
  exit 1
fi
exec node "$here/real_slice_test.js" "$work/node_modules" "$real/block.html" "$real/block.gcode" "$real/walls.rules"
