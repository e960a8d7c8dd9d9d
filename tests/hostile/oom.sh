#!/usr/bin/env bash
# Hostile cases, out of memory at any point: both tools under a series of address-space caps
# (ulimit -v), from the smallest they start with upwards. Every run is a valid result or exit 1
# with the out-of-memory message; never an abort or another signal. (glibc aborted once, "libgcc_s.so.1
# must be installed for unwinding to work", when its first load of the unwinder came after the
# memory had run out; the tools load it at start: base/memory.h, load_unwinder().)
# Usage: oom.sh TRANCHE RULEC. Exit 77 (skipped) where ulimit -v cannot be set.
source "$(dirname "$0")/lib.sh"

if ! (ulimit -v 4000000) 2>/dev/null; then
  echo "skip: ulimit -v is not available here"
  exit 77
fi

# --- the unwinder is loaded at start ----------------------------------------------------------
# glibc's loader tells each dlopen() with LD_DEBUG=files: libgcc_s is opened before anything
# could run out (--help allocates next to nothing and never throws).
for tool in "$TRANCHE" "$RULEC"; do
  name=$(basename "$tool")
  run env LD_DEBUG=files "$tool" --help
  if [[ $ERR != *"needed by"* ]]; then
    skip "$name loads the unwinder at start" "no LD_DEBUG output: not glibc's loader"
  else
    check "$name loads the unwinder at start" grep -q "opening file=.*libgcc_s" <<<"$ERR"
  fi
done

# --- caps from the smallest that starts -------------------------------------------------------
# smallest_cap TOOL: the smallest cap, in 2 MB steps, under which `TOOL --help` runs (the loader
# maps the shared libraries first; below that nothing of ours runs).
smallest_cap() {
  local kb
  for ((kb = 8000; kb <= 400000; kb += 2000)); do
    if (ulimit -v $kb && exec "$1" --help) >/dev/null 2>&1; then
      echo $kb
      return
    fi
  done
  echo 0
}

# sweep NAME FROM STEP COUNT OOM_REGEX CMD...: runs CMD under COUNT caps FROM, FROM+STEP, ... KB.
# Each run: exit 0, or exit 1 with a message naming the lack of memory (matching OOM_REGEX);
# anything else fails the case.
sweep() {
  local name=$1 from=$2 step=$3 count=$4 text=$5 kb i ok=0 oom=0 bad=""
  shift 5
  for ((i = 0; i < count; i++)); do
    kb=$((from + i * step))
    run 60 bash -c 'ulimit -v $0 && exec "$@"' "$kb" "$@"
    if [[ $RC -eq 0 ]]; then
      ok=$((ok + 1))
    elif [[ $RC -eq 1 && $ERR =~ $text ]]; then
      oom=$((oom + 1))
    else
      bad+=" ${kb}KB:exit$RC:${ERR:0:160}"
    fi
  done
  echo "      $name: $ok valid results, $oom out-of-memory errors of $count runs"
  if [[ -n $bad ]]; then
    RC=1 ERR="failed runs:$bad"
    fail "$name: every run a valid result or the out-of-memory error"
  else
    pass "$name: every run a valid result or the out-of-memory error"
  fi
}

# sweep_tool NAME STEP_KB COUNT PATTERN COMMAND...: `sweep` from the smallest cap the command's
# program starts under (NAME is its name and verb), or a skip when it cannot start under 400 MB.
sweep_tool() {
  local name=$1 step=$2 count=$3 pattern=$4
  shift 4
  local start
  start=$(smallest_cap "$1")
  if [[ $start -eq 0 ]]; then
    skip "${name%% *} under caps" "${name%% *} does not start under 400 MB of address space"
  else
    sweep "$name, ${start} KB and up" "$start" "$step" "$count" "$pattern" "$@"
  fi
}

box m.stl 30 30 20
# The preview is kept whole until the end, so the memory grows layer by layer: the caps end the
# run while loading, at the threads' start, in the layers or at the end.
sweep_tool "tranche slice" 5000 20 "error: (out of memory while|m.stl: not enough memory to load the model)" \
  "$TRANCHE" slice m.stl -o m.gcode --export-preview m.html -q --set layer_height=0.1 --set infill_density=40%

python3 -c '
for i in range(2000):
    print("rule \"r%d\" when layer.index == %d { speed = %d mm/s }" % (i, i, 20 + i % 50))' >big.rules
# The parser lets std::bad_alloc through to the tool's own message (it said "E0004 the parser
# failed: std::bad_alloc", a syntax error, before).
sweep_tool "rulec check" 1500 16 \
  "(out of memory while compiling|not enough memory to read the rules file)" \
  "$RULEC" check big.rules

finish
