#!/usr/bin/env bash
# Latency of `rulec lsp` for one edit of a generated rule file, as an editor sees it (bench_lsp.py).
# Usage: bench/bench_lsp.sh [BUILD_DIR] [RULES...]
set -euo pipefail
build=${1:-build}
shift || true
rulec="$build/apps/rulec"
[[ -x "$rulec" ]] || { echo "bench_lsp: $rulec not built (cmake --build $build --target rulec)"; exit 1; }
exec /usr/bin/python3 "$(dirname "$0")/bench_lsp.py" "$rulec" "$@"
