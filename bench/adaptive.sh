#!/usr/bin/env bash
# Adaptive sizing against the uniform default (issue 19, §3.4): on every input
# of ../shared/data/points, both sizings with default options in alternation,
# output triangles, Chamfer-L1 and Hausdorff to the ground truth
# (../shared/data/gt), mean min angle and wall time; the totals' ratios.
#   bench/adaptive.sh [extra pdd reconstruct options for both runs]
# Writes bench/results/adaptive.md.
set -euo pipefail
cd "$(dirname "$0")/.."
pdd=build/pdd
out=bench/results/adaptive.md
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
{
  echo "# Adaptive against uniform sizing (bench/adaptive.sh $*, commit $(git rev-parse --short HEAD), $(nproc) cores)"
  echo
  echo "| input | sizing | triangles | Chamfer-L1 | Hausdorff | mean min angle | seconds |"
  echo "| --- | --- | --- | --- | --- | --- | --- |"
} > "$out"
for input in ../shared/data/points/*.ply; do
  name=$(basename "$input" .ply)
  gt=../shared/data/gt/${name%%_*}.ply
  [ -f "$gt" ] || continue  # no ground truth (kitten_scan)
  for sizing in uniform adaptive; do
    start=$(date +%s.%N)
    $pdd reconstruct "$input" -o "$scratch/$sizing.ply" --sizing "$sizing" --quiet "$@" >/dev/null 2>&1
    seconds=$(awk -v s="$start" -v e="$(date +%s.%N)" 'BEGIN { printf "%.1f", e - s }')
    q=$($pdd quality "$scratch/$sizing.ply" --json)
    c=$($pdd compare "$scratch/$sizing.ply" "$gt" --json)
    echo "| $name | $sizing | $(jq '.triangles.count' <<< "$q") | $(jq '.chamfer_l1' <<< "$c") | $(jq '.hausdorff' <<< "$c") | $(jq '.triangles.mean_min_angle * 100 | round / 100' <<< "$q") | $seconds |" | tee -a "$out"
  done
done
awk -F'|' '/\| (uniform|adaptive) \|/ { s = $3; gsub(/ /, "", s); t[s] += $4; c[s] += $5; w[s] += $8 }
  END { printf "\nTotals, adaptive / uniform: triangles %.2f, Chamfer-L1 (sum) %.2f, seconds %.2f\n",
        t["adaptive"] / t["uniform"], c["adaptive"] / c["uniform"], w["adaptive"] / w["uniform"] }' "$out" | tee -a "$out"
