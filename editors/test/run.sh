#!/usr/bin/env bash
# The CTest tests of editor support: installs the npm packages of package-lock.json
# (vscode-textmate, vscode-oniguruma, vscode-jsonrpc) into WORK with `npm ci`, then runs
# test-grammar.js, or TEST with its ARGS (test-lsp.js RULEC drives the language server).
# Exits 77 (CTest: skipped) with a message when node or npm is missing or the npm registry
# cannot be reached; WORK is reused while package-lock.json is unchanged.
#   editors/test/run.sh [WORK [TEST ARGS...]]   (default WORK: $TRANCHE_BINARY_DIR/editors-test, else editors/test)
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
work=${1:-${TRANCHE_BINARY_DIR:+$TRANCHE_BINARY_DIR/editors-test}}
work=${work:-$here}
test=${2:-test-grammar.js}
shift 2 2>/dev/null || shift $#

for tool in node npm; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "skipped: $tool not found (install Node.js and npm to test the editor grammar)"
    exit 77
  fi
done
major=$(node -e 'console.log(process.versions.node.split(".")[0])' 2>/dev/null || echo 0)
if [[ "$major" -lt 16 ]]; then
  echo "skipped: node $(node --version 2>/dev/null) is too old (16 or later needed)"
  exit 77
fi

mkdir -p "$work"
if [[ "$work" != "$here" ]]; then
  cp "$here/package.json" "$here/package-lock.json" "$work/"
fi
stamp="$work/node_modules/.tranche-lock"
if ! cmp -s "$here/package-lock.json" "$stamp" 2>/dev/null; then
  echo "installing the packages of editors/test/package-lock.json with npm ci in $work"
  if ! (cd "$work" && timeout 300 npm ci --no-audit --no-fund --loglevel=error --fetch-retries=1 \
          --fetch-retry-mintimeout=2000 --fetch-retry-maxtimeout=5000 --fetch-timeout=30000 >npm.log 2>&1); then
    echo "skipped: npm ci failed (is the npm registry reachable?); last lines of $work/npm.log:"
    tail -5 "$work/npm.log" | sed 's/^/  /'
    exit 77
  fi
  cp "$here/package-lock.json" "$stamp"
fi
exec node "$here/$test" "$work/node_modules" "$@"
