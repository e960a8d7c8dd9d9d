#!/usr/bin/env bash
# Installs Tranche's build and test dependencies from Debian packages.
# Idempotent: packages already present are skipped; sudo is used only when not root.
set -euo pipefail

PKGS=(
  build-essential cmake ninja-build ccache pkg-config git
  libfmt-dev doctest-dev libeigen3-dev libtbb-dev libpolyclipping-dev libcgal-dev libgmp-dev libmpfr-dev
  libboost-dev
  antlr4 libantlr4-runtime-dev default-jre-headless
  pybind11-dev python3-dev
  libpugixml-dev
  zlib1g-dev libpng-dev libdeflate-dev libisal-dev
  nlohmann-json3-dev
  lib3mf-dev libtinyobjloader-dev libcli11-dev
  liblua5.4-dev
  clang libclang-rt-dev
  python3-shapely python3-numpy python3-matplotlib
  chromium
)
# Peers for side-by-side comparison in bench/ (optional; `--with-peers`).
PEERS=(prusa-slicer cura-engine slic3r time)

want=("${PKGS[@]}")
# zlib: the preview's data and PNG thumbnails; libpng: the tests decode the thumbnails with it.
# libdeflate: inflating 3MF packages (a whole ZIP entry at once, about twice as fast as zlib).
# libisal-dev (ISA-L): inflating a 3MF's model part in a stream the mesh scanner reads as it comes
# (as fast as libdeflate, without the whole part in memory).
# chromium: the preview's browser test (tests/geometry/preview/browser) runs it headless.
# npm fetches test models (stl-models); a machine whose Node.js already bundles npm keeps it.
if ! command -v npm >/dev/null 2>&1; then want+=(npm); fi
if [[ "${1:-}" == "--with-peers" ]]; then want+=("${PEERS[@]}"); fi

missing=()
for p in "${want[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#want[@]} packages present"
  exit 0
fi

SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
