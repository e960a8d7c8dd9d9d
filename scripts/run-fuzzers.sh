#!/usr/bin/env bash
# Runs every libFuzzer target in BUILD/fuzz for SECONDS each, starting from its seed corpus
# (fuzz/corpus/<name>/, or generated: fuzz/make_3mf_corpus.py, fuzz/make_stl_corpus.py). Fails if a target crashes, leaks,
# times out on one input or runs out of memory.
set -euo pipefail
build=${1:-build-fuzz}
seconds=${2:-30}
root=$(cd "$(dirname "$0")/.." && pwd)
# Absolute, because each target runs from its own scratch directory.
build=$(cd "$build" 2>/dev/null && pwd) || { echo "fuzz: no build directory ${1:-build-fuzz} (run make fuzz-build)"; exit 1; }
status=0
# Leaks in third-party libraries (lib3mf's libzip) are not ours to fix: fuzz/lsan.supp.
export LSAN_OPTIONS="suppressions=$root/fuzz/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
shopt -s nullglob
for bin in "$build"/fuzz/fuzz_*; do
  [[ -x "$bin" && -f "$bin" ]] || continue
  name=$(basename "$bin"); name=${name#fuzz_}
  work=$(mktemp -d)
  seeds="$root/fuzz/corpus/$name"
  [[ $name == bundle ]] && seeds="$root/fuzz/corpus/rules"  # rule texts, compiled by the target
  mkdir -p "$work/corpus"
  [[ -d "$seeds" ]] && cp -r "$seeds"/. "$work/corpus/" 2>/dev/null || true
  # 3MF seeds are generated (no third-party file is committed).
  [[ $name == 3mf ]] && python3 "$root/fuzz/make_3mf_corpus.py" "$work/corpus"
  [[ $name == stl ]] && python3 "$root/fuzz/make_stl_corpus.py" "$work/corpus"
  # Input size caps: STL up to 1 MiB, so that the large-file paths (welding in several chunks of
  # 2048 triangles, long ASCII files) are reached; a whole slice stays small to stay fast.
  case $name in
    stl) max_len=1048576 ;;
    slice) max_len=512 ;;
    *) max_len=65536 ;;
  esac
  echo "fuzz: $name for ${seconds}s (inputs up to $max_len bytes)"
  if ! (cd "$work" && "$bin" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=$max_len \
        -print_final_stats=0 corpus >"$work/log" 2>&1); then
    echo "fuzz: $name FAILED; last lines of its log:"; tail -40 "$work/log"
    mkdir -p "$build/fuzz-failures"; cp "$work"/crash-* "$work"/timeout-* "$work"/oom-* "$work"/leak-* \
      "$build/fuzz-failures/" 2>/dev/null || true
    echo "fuzz: inputs that failed are in $build/fuzz-failures/"
    status=1
  else
    grep -E '^#[0-9]+.*DONE|^Done [0-9]+ runs' "$work/log" | tail -2 || true
  fi
  rm -rf "$work"
done
exit $status
