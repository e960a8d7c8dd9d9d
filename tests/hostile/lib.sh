# Shared by the hostile suites (tests/hostile/*.sh): a scratch folder, fixtures written by the
# tests themselves, and checks that every case ends in a clean error or a valid result.
# Usage in a suite: source lib.sh TRANCHE RULEC; then `case_ ...` lines; then `finish`.
set -u
TRANCHE=$(realpath "$1")
RULEC=$(realpath "$2")
T=$(mktemp -d "${TMPDIR:-/tmp}/tranche-hostile-XXXXXX")
BG=()
cleanup() {
  for p in "${BG[@]}"; do kill "$p" 2>/dev/null; done
  wait 2>/dev/null
  rm -rf "$T"
}
trap cleanup EXIT
cd "$T" || exit 1
PASS=0 FAIL=0 SKIP=0
OUT="" ERR="" RC=0

# A closed box, binary STL: box NAME [X Y Z] (mm).
box() {
  python3 - "$@" <<'PY'
import struct, sys
name = sys.argv[1]
sx, sy, sz = (float(a) for a in (sys.argv[2:5] if len(sys.argv) > 4 else (10, 10, 5)))
v = [(x * sx, y * sy, z * sz) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
f = [(0, 2, 1), (1, 2, 3), (4, 5, 6), (5, 7, 6), (0, 1, 4), (1, 5, 4),
     (2, 6, 3), (3, 6, 7), (0, 4, 2), (2, 4, 6), (1, 3, 5), (3, 7, 5)]
b = bytearray(b"box".ljust(80, b" ")) + struct.pack("<I", len(f))
for t in f:
    b += struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *v[i]) for i in t) + b"\0\0"
open(name, "wb").write(b)
PY
}

# run [timeout-seconds] CMD...: runs CMD, keeping its exit status, stdout and stderr.
run() {
  local limit=60
  [[ $1 =~ ^[0-9]+$ ]] && { limit=$1; shift; }
  timeout -k 5 "$limit" "$@" >"$T/.out" 2>"$T/.err"
  RC=$?
  OUT=$(cat "$T/.out")
  ERR=$(cat "$T/.err")
}

pass() { PASS=$((PASS + 1)); echo "ok    $1"; }
fail() { FAIL=$((FAIL + 1)); echo "FAIL  $1"; echo "      exit $RC; stderr: ${ERR:0:600}"; }
skip() { SKIP=$((SKIP + 1)); echo "skip  $1 ($2)"; }

# expect_error NAME TEXT...: the last run exited with 1 and its stderr holds every TEXT.
expect_error() {
  local name=$1 t
  shift
  if [[ $RC -ne 1 ]]; then fail "$name (wanted exit 1)"; return 1; fi
  for t in "$@"; do
    if [[ $ERR != *"$t"* ]]; then fail "$name (no '$t' in the message)"; return 1; fi
  done
  pass "$name"
}

# expect_ok NAME: the last run exited with 0.
expect_ok() {
  if [[ $RC -ne 0 ]]; then fail "$1 (wanted exit 0)"; return 1; fi
  pass "$1"
}

# check NAME CONDITION...: a further check (a shell test) of the case.
check() {
  local name=$1
  shift
  if "$@"; then pass "$name"; else fail "$name"; fi
}

# No hidden temporary file of an output anywhere in the scratch folder.
no_temp_files() { [[ -z $(find "$T" -name '.*.tmp-*' -print -quit) ]]; }

root() { [[ $(id -u) -eq 0 ]]; }

# An endless writer into FIFO (zeros, or a repeated line): feed FIFO [TEXT].
feed() {
  local fifo=$1 text=${2:-}
  if [[ -z $text ]]; then
    (cat /dev/zero >"$fifo" 2>/dev/null) &
  else
    (yes "$text" >"$fifo" 2>/dev/null) &
  fi
  BG+=($!)
}

finish() {
  echo "hostile: $PASS passed, $FAIL failed, $SKIP skipped"
  [[ $FAIL -eq 0 ]]
}
