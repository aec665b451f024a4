#!/usr/bin/env bash
# How close `--target-faces N` lands (issue 19): output triangles against N on
# every input of ../shared/data/points, and on the 100k-point virtual scan of
# bench/scale.sh when it is cached, uniform and adaptive sizing.
#   bench/target_faces.sh [--faces 10000,50000,200000]
# Writes bench/results/target_faces.md. The counts are deterministic; no timing.
set -euo pipefail
cd "$(dirname "$0")/.."
faces="10000,50000,200000"
[ "${1:-}" = "--faces" ] && faces="$2"
pdd=build/pdd
out=bench/results/target_faces.md
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
inputs=(../shared/data/points/*.ply)
[ -f build/scale_inputs/fandisk_large_100000.ply ] && inputs+=(build/scale_inputs/fandisk_large_100000.ply)
{
  echo "# --target-faces: output triangles / N (bench/target_faces.sh, commit $(git rev-parse --short HEAD))"
  echo
  header="| input | sizing |"
  rule="| --- | --- |"
  for n in ${faces//,/ }; do header+=" N = $n |"; rule+=" --- |"; done
  echo "$header"
  echo "$rule"
} > "$out"
ratios=()
for input in "${inputs[@]}"; do
  for sizing in uniform adaptive; do
    row="| $(basename "$input" .ply) | $sizing |"
    for n in ${faces//,/ }; do
      triangles=$($pdd reconstruct "$input" -o "$scratch/out.ply" --sizing "$sizing" \
        --target-faces "$n" --quiet --stats "$scratch/s.json" >/dev/null 2>&1 &&
        jq '.iterations[-1].triangles' "$scratch/s.json")
      ratio=$(awk -v t="$triangles" -v n="$n" 'BEGIN { printf "%.2f", t / n }')
      ratios+=("$ratio")
      row+=" $ratio ($triangles) |"
    done
    echo "$row" | tee -a "$out"
  done
done
printf '%s\n' "${ratios[@]}" | sort -n | awk '{ a[NR] = $1 } END {
  printf "\nAll %d runs: ratio from %s to %s, median %s\n", NR, a[1], a[NR], a[int((NR + 1) / 2)] }' | tee -a "$out"
