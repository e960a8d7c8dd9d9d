#!/usr/bin/env bash
# Hostile cases, outputs: special files as outputs (made inside a scratch folder, never the real
# /dev), symlinks, modes, and outputs that are inputs of the run. Every case must end in a clean
# error (exit 1 and a message) or a valid result, and destroy nothing.
# Usage: outputs.sh TRANCHE RULEC
source "$(dirname "$0")/lib.sh"

box m.stl
printf 'rule "slow" when layer.index < 2 { speed = 20 mm/s }\n' >my.rules
cp my.rules keep.rules

# --- devices and FIFOs ---------------------------------------------------------------------
if root; then
  mknod null c 1 3
  run "$TRANCHE" slice m.stl -o null -q
  expect_ok "-o a character device (our own null) is written"
  check "the device is still a device" test -c null
else
  skip "-o a character device" "mknod needs root"
fi

mkfifo job.fifo
(cat job.fifo >received.gcode) &
BG+=($!)
run "$TRANCHE" slice m.stl -o job.fifo -q
expect_ok "-o a FIFO with a reader"
wait "${BG[-1]}" 2>/dev/null
check "the reader got the whole G-code" grep -q '^; estimated printing time' received.gcode
check "the FIFO is still a FIFO" test -p job.fifo

run 20 "$TRANCHE" slice m.stl -o job.fifo -q
expect_error "-o a FIFO nobody reads: an error, not a hang" "no reader"

(cat job.fifo >export.svg) &
BG+=($!)
run "$TRANCHE" slice m.stl --export-svg job.fifo -q
expect_ok "--export-svg to a FIFO with a reader"
wait "${BG[-1]}" 2>/dev/null
check "the SVG came through the FIFO" grep -q '</svg>' export.svg

(cat job.fifo >piped.bundle) &
BG+=($!)
run "$RULEC" build my.rules -o job.fifo
expect_ok "rulec build -o a FIFO with a reader"
wait "${BG[-1]}" 2>/dev/null
run "$RULEC" disasm piped.bundle
expect_ok "the bundle that came through the FIFO is valid"

python3 -c 'import socket; s = socket.socket(socket.AF_UNIX); s.bind("sock")'
run "$TRANCHE" slice m.stl -o sock -q
expect_error "-o a socket is refused" "is a socket"

# --- links, folders, modes -----------------------------------------------------------------
mkdir -p share
printf 'old\n' >share/x.gcode
ln -s share/x.gcode latest.gcode
run "$TRANCHE" slice m.stl -o latest.gcode -q
expect_ok "-o a symlink"
check "the link is still a link" test -L latest.gcode
check "the link's target holds the new G-code" grep -q '^G1' share/x.gcode

ln -s share/new.gcode dangling.gcode
run "$TRANCHE" slice m.stl -o dangling.gcode -q
expect_ok "-o a link to a missing file"
check "the missing file is created where the link points" test -f share/new.gcode -a -L dangling.gcode

mkdir folder.gcode
run "$TRANCHE" slice m.stl -o folder.gcode -q
expect_error "-o a folder" "is a folder"
run "$TRANCHE" slice m.stl -o no/such/folder/x.gcode -q
expect_error "-o in a missing folder" "does not exist"

printf 'old\n' >private.gcode
chmod 600 private.gcode
run "$TRANCHE" slice m.stl -o private.gcode -q
expect_ok "-o over a private file"
check "the file keeps its mode 600" test "$(stat -c %a private.gcode)" = 600
run bash -c "umask 077 && '$TRANCHE' slice m.stl -o umask.gcode -q"
expect_ok "a new file under umask 077"
check "the new file's mode honours the umask (600)" test "$(stat -c %a umask.gcode)" = 600
if ! root; then
  printf 'keep\n' >ro.gcode
  chmod 444 ro.gcode
  run "$TRANCHE" slice m.stl -o ro.gcode -q
  expect_error "-o a read-only file is refused" "read-only"
else
  skip "-o a read-only file" "root may write anything"
fi

# --- outputs that are inputs -----------------------------------------------------------------
cp m.stl orig.stl
run "$TRANCHE" slice m.stl -o m.stl -q
expect_error "-o the model" "refusing to write the G-code" "a model of this run ('m.stl')"
check "the model is unchanged" cmp -s m.stl orig.stl
ln -s m.stl alias.stl
run "$TRANCHE" slice m.stl -o alias.stl -q
expect_error "-o a link to the model" "refusing to write"
check "the link and the model are unchanged" cmp -s m.stl orig.stl
run "$TRANCHE" slice m.stl --export-svg m.stl -q
expect_error "--export-svg the model" "refusing to write the SVG export"
run "$TRANCHE" slice m.stl --rules my.rules -o my.rules -q
expect_error "-o the --rules file" "a --rules file of this run ('my.rules')"
check "the rules are unchanged" cmp -s my.rules keep.rules
printf 'use "printers/generic-marlin"\n' >printer.rules
cp printer.rules printer.keep
run "$TRANCHE" slice m.stl --printer ./printer.rules -o ./printer.rules -q
expect_error "-o the printer profile" "the printer profile"
check "the profile is unchanged" cmp -s printer.rules printer.keep
printf 'use "materials/pla"\n' >mat.rules
run "$TRANCHE" slice m.stl --material ./mat.rules --export-layers ./mat.rules -q
expect_error "--export-layers the material profile" "the material profile"
printf 'use "./my"\n' >uses.rules
run "$TRANCHE" slice m.stl --rules uses.rules --export-preview my.rules -q
expect_error "--export-preview a file the rules use" "refusing to write the preview" "my.rules"
check "the used file is unchanged" cmp -s my.rules keep.rules
printf 'def fill_angle(ctx):\n    return 0\n' >angle.py
run "$TRANCHE" slice m.stl --fill-angle-script angle.py -o angle.py -q
expect_error "-o the fill-angle script" "the fill-angle script"
run "$TRANCHE" slice m.stl -o same.out --export-svg same.out -q
expect_error "two outputs in one file" "already written to this file"
check "nothing was written for a refused run" test ! -e same.out

run "$RULEC" build my.rules -o my.rules
expect_error "rulec build -o its rules file" "refusing to write the bundle" "a rules file of this run"
check "the rules are unchanged" cmp -s my.rules keep.rules
run "$RULEC" build uses.rules -o my.rules
expect_error "rulec build -o a file its rules use" "refusing to write the bundle"
check "the used file is unchanged" cmp -s my.rules keep.rules
run "$RULEC" build my.rules -o my.bundle
expect_ok "rulec build"
cp my.bundle keep.bundle
run "$TRANCHE" slice m.stl --rules my.bundle -o my.bundle -q
expect_error "-o the bundle" "refusing to write the G-code"
check "the bundle is unchanged" cmp -s my.bundle keep.bundle

check "no temporary file was left anywhere" no_temp_files
finish
