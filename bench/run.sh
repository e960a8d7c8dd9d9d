#!/usr/bin/env bash
# Runs every benchmark script in bench/ (bench_*.sh) against the build in $1.
set -euo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
shopt -s nullglob
for b in "$here"/bench_*.sh; do
  echo "== $(basename "$b")"
  "$b" "$build"
done
