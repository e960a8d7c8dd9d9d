#!/usr/bin/env bash
# Makes puppeteer-core (package-lock.json) available in WORK/node_modules for the preview's
# browser test and benchmark, with `npm ci`, reused while package-lock.json is unchanged.
# Exits 77 with a message when node (18+), npm, Chromium or the npm registry cannot be had.
#   install.sh WORK          (Chromium: /usr/bin/chromium, or $CHROMIUM)
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
work=${1:?usage: install.sh WORK}
chromium=${CHROMIUM:-/usr/bin/chromium}

for tool in node npm; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "skipped: $tool not found (install Node.js and npm to run the preview in a browser)"
    exit 77
  fi
done
major=$(node -e 'console.log(process.versions.node.split(".")[0])' 2>/dev/null || echo 0)
if [[ "$major" -lt 18 ]]; then
  echo "skipped: node $(node --version 2>/dev/null) is too old (18 or later needed by puppeteer-core)"
  exit 77
fi
if [[ ! -x "$chromium" ]]; then
  echo "skipped: no Chromium at $chromium (apt-get install chromium, or set CHROMIUM)"
  exit 77
fi

mkdir -p "$work"
cp "$here/package.json" "$here/package-lock.json" "$work/"
stamp="$work/node_modules/.tranche-lock"
if ! cmp -s "$here/package-lock.json" "$stamp" 2>/dev/null; then
  echo "installing puppeteer-core with npm ci in $work"
  # PUPPETEER_SKIP_DOWNLOAD: Debian's Chromium is used; no browser is fetched.
  if ! (cd "$work" && PUPPETEER_SKIP_DOWNLOAD=1 timeout 300 npm ci --no-audit --no-fund --loglevel=error \
          --fetch-retries=1 --fetch-retry-mintimeout=2000 --fetch-retry-maxtimeout=5000 --fetch-timeout=30000 >npm.log 2>&1); then
    echo "skipped: npm ci failed (is the npm registry reachable?); last lines of $work/npm.log:"
    tail -5 "$work/npm.log" | sed 's/^/  /'
    exit 77
  fi
  cp "$here/package-lock.json" "$stamp"
fi
