#!/usr/bin/env bash
# Hostile cases, limits: memory caps (--max-memory, ulimit -v in a subshell), the rule count,
# the G-code size, option values past their limits, slow scripts, and runs killed in the middle
# of writing. Every case must be a clean error or a valid result; nothing is lost.
# Usage: limits.sh TRANCHE RULEC
source "$(dirname "$0")/lib.sh"

box m.stl
box tall.stl 60 60 60

# --- memory -------------------------------------------------------------------------------
# The preview is kept whole until the end: a job whose memory grows layer by layer.
big_job=(tall.stl --export-preview oom.html -o oom.gcode -q --set layer_height=0.05 --set infill_density=100%)
printf 'previous\n' >oom.gcode
run 120 "$TRANCHE" slice "${big_job[@]}" --max-memory 64
expect_error "--max-memory 64 on a growing job" "out of memory while slicing" "--max-memory 64 MB" \
  "try a larger layer height or a smaller model"
check "the previous G-code is intact after running out of memory" test "$(cat oom.gcode)" = previous
check "no preview was written" test ! -e oom.html
for kb in 30000 50000 90000 130000 250000; do
  run 120 bash -c "ulimit -v $kb && exec '$TRANCHE' slice ${big_job[*]}"
  # The smallest cap runs out either while loading the model or while slicing, by a few hundred
  # KB of address space (the rules compiled before the load take some): either is a clean error.
  if [[ $RC -eq 0 ]]; then
    pass "ulimit -v $kb: a valid result"
  elif [[ $ERR == *"not enough memory to load the model"* ]]; then
    expect_error "ulimit -v $kb: a clean error" "not enough memory to load the model" "close other programs"
  else
    expect_error "ulimit -v $kb: a clean error" "out of memory while"
  fi
  check "ulimit -v $kb: the G-code is the previous one or a whole one" \
    bash -c "[[ \$(cat oom.gcode) == previous ]] || tail -c 2000 oom.gcode | grep -q 'filament used'"
done
run "$TRANCHE" slice m.stl -o x.gcode --max-memory 10
check "--max-memory below 64 MB is a usage error" test $RC -eq 2
run "$TRANCHE" slice m.stl -o x.gcode --max-memory lots
check "--max-memory needs a number" test $RC -eq 2

# --- rules, G-code, options -----------------------------------------------------------------
python3 -c '
for i in range(100000):
    print("rule \"r%d\" when layer.index == %d { speed = 20 mm/s }" % (i, i))' >many.rules
start=$(date +%s)
run 60 "$TRANCHE" slice m.stl --rules many.rules -o many.gcode -q
expect_error "100 000 rules are refused" "too many rules" "100000" "65535"
check "... within 10 seconds" test $(($(date +%s) - start)) -le 10
run 60 "$RULEC" check many.rules
expect_error "rulec check of 100 000 rules" "E0013"

printf 'previous\n' >cap.gcode
run 120 "$TRANCHE" slice tall.stl -o cap.gcode -q --max-gcode-size 1 --set layer_height=0.05
expect_error "a G-code over --max-gcode-size" "the G-code would be larger than 1 MiB" "--max-gcode-size 1"
check "the previous G-code is intact" test "$(cat cap.gcode)" = previous
printf 'rule "loud" { before path { gcode """%s""" } }\n' "$(head -c 4000 /dev/zero | tr '\0' 'x')" >loud.rules
run 120 "$TRANCHE" slice tall.stl --rules loud.rules -o loud.gcode -q --max-gcode-size 2
expect_error "a hook that floods the G-code" "would be larger than 2 MiB"
run "$TRANCHE" slice m.stl -o x.gcode --max-gcode-size -5
check "--max-gcode-size -5 is a usage error" test $RC -eq 2

printf '<svg xmlns="http://www.w3.org/2000/svg" width="10mm" height="10mm"><rect width="5" height="5"/></svg>\n' >d.svg
run "$TRANCHE" slice d.svg -o d.gcode --svg-layers 1000000000
check "--svg-layers 1000000000 names the limit" test $RC -eq 2 -a -n "$(grep -F 'at most 100000 layers' <<<"$ERR")"
run "$TRANCHE" slice d.svg -o d.gcode --svg-height 1e9
check "--svg-height 1e9 names the limit" test $RC -eq 2 -a -n "$(grep -F 'at most 100000 mm' <<<"$ERR")"

# --- the Python hook --------------------------------------------------------------------------
printf 'def fill_angle(ctx):\n    while ctx.layer_index >= 2:\n        pass\n    return 0\n' >loop.py
run 60 "$TRANCHE" slice m.stl --fill-angle-script loop.py --script-timeout 1 -o py.gcode -q
if [[ $ERR == *"built without Python"* ]]; then
  skip "the script timeout" "no Python in this build"
else
  expect_error "a script in an endless loop is stopped" "took longer than 1 s on layer 2, island 0" "--script-timeout"
  printf 'import time\ndef fill_angle(ctx):\n    time.sleep(600)\n    return 0\n' >sleep.py
  start=$(date +%s)
  run 60 "$TRANCHE" slice m.stl --fill-angle-script sleep.py --script-timeout 1 -o py.gcode -q
  expect_error "a script stuck in time.sleep is ended" "could not be interrupted" "layer 0, island 0"
  check "... within 10 seconds" test $(($(date +%s) - start)) -le 10
  check "no G-code was written for a stopped script" test ! -e py.gcode
  # A Python whose start never ends (a sitecustomize module that loops; out of memory, CPython's
  # start can spin the same way): stopped at the start's deadline, 10 s at least.
  mkdir spin && printf 'while True:\n    pass\n' >spin/sitecustomize.py
  start=$(date +%s)
  run 60 env PYTHONPATH="$T/spin" "$TRANCHE" slice m.stl --fill-angle-script loop.py --script-timeout 1 -o spin.gcode -q
  expect_error "a Python start that never ends is stopped" "loop.py: Python did not start within 10 s" \
    "nothing was written"
  check "... within 20 seconds" test $(($(date +%s) - start)) -le 20
  check "no G-code was written for a Python that did not start" test ! -e spin.gcode
fi

# --- killed while writing ---------------------------------------------------------------------
# A job long enough to be caught writing (a few seconds of G-code and exports): once the G-code's
# temporary file exists, the signal.
box wide.stl 180 180 60
kill_during_write() {
  local sig=$1
  printf 'previous G-code\n' >killed.gcode
  cp killed.gcode killed.keep
  rm -f killed.svg killed.json
  # Job control on: a background job of a script would otherwise start with SIGINT ignored.
  set -m
  "$TRANCHE" slice wide.stl -o killed.gcode --export-svg killed.svg --export-layers killed.json -q \
    --set layer_height=0.02 --set infill_density=100% >/dev/null 2>&1 &
  local pid=$! waited=0
  set +m
  while [[ -z $(find "$T" -maxdepth 1 -name '.killed.gcode.tmp-*' -print -quit) ]] && ((waited < 3000)); do
    sleep 0.01
    waited=$((waited + 1))
  done
  sleep 0.2  # in the middle of writing
  kill -"$sig" "$pid"
  wait "$pid"
  RC=$?
  check "SIG$sig while writing: the process ends by the signal (exit $RC)" test $RC -eq $((128 + $(kill -l "$sig")))
  check "SIG$sig while writing: the previous G-code is intact, byte for byte" cmp -s killed.gcode killed.keep
  check "SIG$sig while writing: no export was written" test ! -e killed.svg -a ! -e killed.json
  check "SIG$sig while writing: no temporary file is left" no_temp_files
}
kill_during_write INT
kill_during_write TERM

finish
