#!/usr/bin/env bash
# Hostile cases, inputs: endless and huge inputs (FIFOs fed without end, device nodes made in the
# scratch folder, sparse files) for every kind of file the tools read. Each must be refused with
# a clear message within seconds, never read until memory runs out.
# Usage: inputs.sh TRANCHE RULEC
source "$(dirname "$0")/lib.sh"

box m.stl
printf 'rule "slow" when layer.index < 2 { speed = 20 mm/s }\n' >my.rules

# An endless FIFO for each input; a fresh one per case (a FIFO's writer ends with its reader).
endless() {
  rm -f "$1"
  mkfifo "$1"
  feed "$1" "${2:-}"
}

endless rules.fifo
run 60 "$TRANCHE" slice m.stl --rules rules.fifo -o out.gcode -q
expect_error "--rules: an endless FIFO of zeros" "a pipe or FIFO gave more than 16 MiB" "rules.fifo"
endless rules.fifo 'rule { speed = 20 mm/s }'
run 60 "$TRANCHE" slice m.stl --rules rules.fifo -o out.gcode -q
expect_error "--rules: an endless FIFO of rules" "more than 16 MiB"
endless script.fifo
run 60 "$TRANCHE" slice m.stl --fill-angle-script script.fifo -o out.gcode -q
expect_error "--fill-angle-script: an endless FIFO" "the fill-angle script"
endless printer.fifo
run 60 "$TRANCHE" slice m.stl --printer ./printer.fifo -o out.gcode -q
expect_error "--printer: an endless FIFO" "more than 16 MiB"
endless model.fifo
run 60 "$TRANCHE" slice model.fifo -o out.gcode -q
expect_error "a model: an endless FIFO of zeros stops at its header" "header says 0 triangles"
endless drawing.svg '<svg xmlns="http://www.w3.org/2000/svg"><rect width="1" height="1"/>'
run 60 "$TRANCHE" slice drawing.svg -o out.gcode -q
expect_error "an SVG drawing: an endless FIFO" "more than 256 MiB" "the SVG drawing"
endless check.fifo
run 60 "$RULEC" check check.fifo
expect_error "rulec check: an endless FIFO" "more than 16 MiB"
endless text.fifo 'facet normal 0 0 1 outer loop vertex 0 0 0 vertex 1 0 0 vertex 0 1 0 endloop endfacet'
run 120 bash -c "ulimit -v 1000000 && exec '$TRANCHE' slice text.fifo -o out.gcode -q"
expect_error "a model: an endless FIFO of text under ulimit -v 1 GB" "the model"
check "no G-code was written for refused inputs" test ! -e out.gcode

if root; then
  mknod zero c 1 5
  run 30 "$TRANCHE" slice m.stl --rules zero -o out.gcode -q
  expect_error "--rules: a zero device" "a character device gave more than"
  run 30 "$TRANCHE" slice zero -o out.gcode -q
  expect_error "a model: a zero device" "header says 0 triangles"
  run 30 "$TRANCHE" slice m.stl --fill-angle-script zero -o out.gcode -q
  expect_error "--fill-angle-script: a zero device" "the fill-angle script"
  run 30 "$RULEC" fmt zero
  expect_error "rulec fmt: a zero device" "more than 16 MiB"
else
  skip "zero devices as inputs" "mknod needs root"
fi

# Huge regular files: refused from their size, at once.
truncate -s 2G sparse.stl
run 20 "$TRANCHE" slice sparse.stl -o out.gcode -q
expect_error "a 2 GB sparse STL is refused from its header" "header says 0 triangles"
python3 -c 'import sys; sys.stdout.buffer.write(open("m.stl","rb").read())' >tail.stl
truncate -s 2G tail.stl
run 60 bash -c "ulimit -v 1500000 && exec '$TRANCHE' slice tail.stl -o tail.gcode -q"
expect_ok "a binary STL followed by a 2 GB hole is read to its last triangle only"
truncate -s 20M big.rules
run 20 "$TRANCHE" slice m.stl --rules big.rules -o out.gcode -q
expect_error "--rules: a 20 MB file" "more than the 16 MiB read at most"
truncate -s 300M big.bundle
run 20 "$TRANCHE" slice m.stl --rules big.bundle -o out.gcode -q
expect_error "--rules: a 300 MB file" "more than"
truncate -s 20M big.py
run 20 "$TRANCHE" slice m.stl --fill-angle-script big.py -o out.gcode -q
expect_error "--fill-angle-script: a 20 MB file" "more than the 16 MiB"
# A Python that cannot start (its standard library missing; too little memory does the same): the
# script's error, not an internal one.
printf 'def fill_angle(ctx):\n    return 0\n' >ok.py
run 60 env PYTHONHOME="$T/no-python-here" "$TRANCHE" slice m.stl --fill-angle-script ok.py -o out.gcode -q
if [[ $ERR == *"built without Python"* ]]; then
  skip "--fill-angle-script: Python cannot start" "no Python in this build"
else
  expect_error "--fill-angle-script: Python cannot start" "ok.py: cannot start Python for the script" \
    "or a broken Python installation"
  check "... no internal error" test -z "$(grep -F 'internal error' <<<"$ERR")"
fi

# Inputs that are no files at all.
mkdir dir.rules
run "$TRANCHE" slice m.stl --rules dir.rules -o out.gcode -q
expect_error "--rules: a folder" "is a directory"
run "$TRANCHE" slice m.stl --rules missing.rules -o out.gcode -q
expect_error "--rules: a missing file" "No such file or directory"
: >empty.stl
run "$TRANCHE" slice empty.stl -o out.gcode -q
expect_error "an empty model" "empty"

finish
