#!/usr/bin/env bash
# Times `rulec check` on generated rule sets of realistic rules (per-layer tweaks, z bands,
# path kinds, island sizes, hooks with templates, replacers, loops, inherited values) and
# prints a table. Usage: bench/bench_rules_check.sh [BUILD_DIR] [RUNS]
set -euo pipefail
build=${1:-build}
runs=${2:-5}
rulec="$build/apps/rulec"
[[ -x "$rulec" ]] || { echo "bench_rules_check: $rulec not built (cmake --build $build --target rulec)"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

generate() {  # generate N FILE
  /usr/bin/python3 "$(dirname "$0")/rules/generate_rules.py" "$1" "$2"
}

# Wall time is what a user waits; CPU time (user + system) is less disturbed by other load.
printf '| rules | lines | KiB | wall, best of %s | wall, median | CPU, best | diagnostics |\n' "$runs"
printf '|---:|---:|---:|---:|---:|---:|---:|\n'
for n in 200 2000 10000; do
  f="$work/rules-$n.rules"
  generate "$n" "$f"
  walls=() cpus=()
  for ((k = 0; k < runs; k++)); do
    /usr/bin/time -f "%e %U %S" -o "$work/time" "$rulec" check "$f" >/dev/null 2>&1 || true
    read -r wall user sys <"$work/time"
    walls+=("$(awk -v w="$wall" 'BEGIN { printf "%d", w * 1000 }')")
    cpus+=("$(awk -v u="$user" -v s="$sys" 'BEGIN { printf "%d", (u + s) * 1000 }')")
  done
  w=($(printf '%s\n' "${walls[@]}" | sort -n))
  c=($(printf '%s\n' "${cpus[@]}" | sort -n))
  diags=$("$rulec" check --format json "$f" 2>/dev/null | wc -l)
  printf '| %d | %d | %d | %d ms | %d ms | %d ms | %d |\n' "$n" "$(wc -l <"$f")" "$(( $(wc -c <"$f") / 1024 ))" \
    "${w[0]}" "${w[$(( runs / 2 ))]}" "${c[0]}" "$diags"
done
echo
echo "phases of the 2000-rule check (rulec check --time):"
generate 2000 "$work/phases.rules"
"$rulec" check --time "$work/phases.rules" 2>&1 >/dev/null | grep -E '^rulec: [a-z ]+ +[0-9.]+ ms' || true
