#!/usr/bin/env bash
# How much the progressive domain's result depends on the seed of its
# probabilistic bisection (§3.4), against the octree-based domain, whose grid
# does not depend on it: bench/shared_data.sh once per seed, then per input the
# Chamfer-L1 distance to the ground truth of every seed, their mean and range,
# the octree's, and the worst triangle quality and topology over the seeds.
#
#   bench/seed_spread.sh [PDD] [--seeds N] [--only REGEX] [--data DIR]
#
#   PDD          the pdd binary (default: build/pdd)
#   --seeds N    seeds 0 .. N-1 (default 5)
#   --only REGEX only the inputs whose name matches (passed to shared_data.sh)
#   --data DIR   the data folder (passed to shared_data.sh)
#
# Needs bench/results/shared_data_octree/ (bench/shared_data.sh --domain
# octree) for the octree column; runs it first when it is missing. Writes
# bench/results/seed_spread.md (also printed). Exits 1 when a run failed.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
pdd="$root/build/pdd"
seeds=5
pass=()

usage() { sed -n '/^#   bench\/seed_spread.sh/,/^#   --data/s/^# \{0,1\}//p' "${BASH_SOURCE[0]}" >&2; exit "${1:-2}"; }
while [ $# -gt 0 ]; do
  case "$1" in
    --seeds) [ $# -ge 2 ] || usage; seeds="$2"; shift 2 ;;
    --only|--data) [ $# -ge 2 ] || usage; pass+=("$1" "$2"); shift 2 ;;
    -h|--help) usage 0 ;;
    -*) echo "seed_spread.sh: unknown option $1" >&2; usage ;;
    *) pdd="$1"; shift ;;
  esac
done
[[ "$seeds" =~ ^[1-9][0-9]*$ ]] || { echo "seed_spread.sh: --seeds wants a positive integer, got $seeds" >&2; exit 2; }

results="$root/bench/results"
failed=0
if [ ! -d "$results/shared_data_octree" ]; then
  "$root/bench/shared_data.sh" "$pdd" --domain octree "${pass[@]}" >/dev/null || failed=1
fi
for ((s = 0; s < seeds; ++s)); do
  "$root/bench/shared_data.sh" "$pdd" --seed "$s" "${pass[@]}" >/dev/null || failed=1
done

# A number of a JSON file, or "null".
value() { [ -f "$2" ] && jq -r "$1" "$2" || echo null; }
chamfer() { value '.chamfer_l1_relative * 1000' "$1"; }

header="| input |"
rule="|---|"
for ((s = 0; s < seeds; ++s)); do header+=" seed $s |"; rule+="---|"; done
header+=" mean | range | octree | seeds better than octree | worst mean min angle (°) | worst < 20° (%) | topology right |"
rule+="---|---|---|---|---|---|---|"
rows=()
for compare in "$results/shared_data_seed_0"/*.compare.json; do
  base="$(basename "$compare" .compare.json)"
  row="| $base |"
  values=()
  angles=()
  below=()
  right=0
  for ((s = 0; s < seeds; ++s)); do
    dir="$results/shared_data_seed_$s"
    c="$(chamfer "$dir/$base.compare.json")"
    values+=("$c")
    row+=" $(awk -v v="$c" 'BEGIN { printf (v == "null" ? "–" : "%.3f"), v }') |"
    quality="$dir/$base.quality.json"
    angles+=("$(value .triangles.mean_min_angle "$quality")")
    below+=("$(value '.triangles.fraction_min_angle_below_20 * 100' "$quality")")
    [ "$(value '.surface.closed and .surface.manifold and .surface.components == 1 and .surface.genus == 0' "$quality")" = true ] &&
      right=$((right + 1))
  done
  octree="$(chamfer "$results/shared_data_octree/$base.compare.json")"
  row+="$(printf '%s\n' "${values[@]}" | awk -v o="$octree" '
    $1 != "null" { n++; s += $1; if (n == 1 || $1 < lo) lo = $1; if (n == 1 || $1 > hi) hi = $1; if (o != "null" && $1 <= o) w++ }
    END { if (n == 0) { printf " – | – | – | – |"; exit }
          printf " %.3f | %.3f-%.3f | %s | %d of %d |", s / n, lo, hi, (o == "null" ? "–" : sprintf("%.3f", o)), w, n }')"
  row+=" $(printf '%s\n' "${angles[@]}" | awk '$1 != "null" && (n++ == 0 || $1 < m) { m = $1 } END { printf (n ? "%.1f" : "–"), m }') |"
  row+=" $(printf '%s\n' "${below[@]}" | awk '$1 != "null" && (n++ == 0 || $1 > m) { m = $1 } END { printf (n ? "%.1f" : "–"), m }') |"
  row+=" $right of $seeds |"
  rows+=("$row")
done

{
  echo "# Chamfer-L1 (1e-3 of the diagonal) of the progressive domain over seeds 0-$((seeds - 1)), against the octree-based domain"
  echo
  echo "$(date -u '+%Y-%m-%d %H:%M UTC'); commit $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo ?)$(git -C "$root" diff --quiet 2>/dev/null || echo "+local changes"); other options default."
  echo
  echo "$header"
  echo "$rule"
  printf '%s\n' "${rows[@]}"
} >"$results/seed_spread.md"
cat "$results/seed_spread.md"
exit $failed
