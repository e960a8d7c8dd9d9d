#!/usr/bin/env bash
# The CTest test of the HTML preview in a real browser: installs puppeteer-core into WORK
# (install.sh; exit 77, skipped, when node, npm, Chromium or the registry cannot be had), writes
# the fixture page with FIXTURE_EXE and runs preview_test.js in headless Chromium.
# --screenshot also saves the page as the README shows it (docs/images/preview.png).
#   run.sh WORK FIXTURE_EXE [--screenshot OUT.png]
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
work=${1:?usage: run.sh WORK FIXTURE_EXE [--screenshot OUT.png]}
fixture=${2:?usage: run.sh WORK FIXTURE_EXE [--screenshot OUT.png]}
shot=""
if [[ "${3:-}" == "--screenshot" ]]; then shot=$(realpath -m "${4:?--screenshot needs a file}"); fi

bash "$here/install.sh" "$work" || exit $?
if ! "$fixture" "$work/fixture.html" "$work/fixture.json"; then
  echo "FAIL: $fixture could not write the fixture page"
  exit 1
fi
args=("$work/node_modules" "$work/fixture.html" "$work/fixture.json")
if [[ -n "$shot" ]]; then args+=("$shot"); fi
exec node "$here/preview_test.js" "${args[@]}"
