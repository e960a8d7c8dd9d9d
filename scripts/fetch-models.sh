#!/usr/bin/env bash
# Fetches the npm package `stl-models` (real models and a broken/ folder of malformed STL files)
# for the STL corpus test. Idempotent; exits 0 with a message when npm or the registry is unreachable.
#   TRANCHE_MODELS_DIR  where to put it (default $HOME/.cache/tranche/models)
set -uo pipefail
dest=${TRANCHE_MODELS_DIR:-${HOME:-/tmp}/.cache/tranche/models}
pkg=stl-models
if [[ -f "$dest/.complete" ]]; then
  echo "fetch-models: $pkg already in $dest"
  exit 0
fi
if ! command -v npm >/dev/null 2>&1; then
  echo "fetch-models: npm not found; the STL corpus test will be skipped (install npm: scripts/install-deps.sh)"
  exit 0
fi
mkdir -p "$(dirname "$dest")" || { echo "fetch-models: cannot create $(dirname "$dest"); corpus test will be skipped"; exit 0; }
work=$(mktemp -d "$(dirname "$dest")/.fetch-XXXXXX") || exit 0
trap 'rm -rf "$work"' EXIT
# npm pack prints the tarball name last; --silent keeps warnings about the user's npmrc out of it.
if ! tarball=$(cd "$work" && timeout 120 npm pack "$pkg" --silent --fetch-retries=1 \
     --fetch-retry-mintimeout=2000 --fetch-retry-maxtimeout=5000 --fetch-timeout=30000 2>"$work/npm.log" | tail -1) || [[ -z "$tarball" ]] \
   || [[ ! -f "$work/$tarball" ]]; then
  echo "fetch-models: could not download $pkg from the npm registry (offline?); the STL corpus test will be skipped"
  tail -3 "$work/npm.log" 2>/dev/null | sed 's/^/fetch-models:   /'
  exit 0
fi
mkdir -p "$work/unpacked"
if ! tar -xzf "$work/$tarball" -C "$work/unpacked"; then
  echo "fetch-models: $tarball is not a readable tarball; the STL corpus test will be skipped"
  exit 0
fi
# Swap in the complete folder at once so an interrupted run never leaves a half-unpacked corpus.
touch "$work/unpacked/package/.complete"
rm -rf "$dest"
mv "$work/unpacked/package" "$dest"
echo "fetch-models: $pkg ($tarball) unpacked into $dest"
