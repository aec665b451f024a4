#!/usr/bin/env bash
# pdd at scale (issue 15): real and virtual scans of 100k points and more,
# with default options, beside PoissonRecon in the same run.
#
#   bench/scale.sh [--points 100000,300000,1000000] [--shapes fandisk_large,refined_elephant]
#                  [--no-building] [--depths 8,9,10,11] [--out bench/results/scale.md]
#                  [--pdd-args "--trim 2"]
#
# Inputs: CGAL's real scan data/points_3/building.ply (100k points), and
# multi-view virtual scans (../shared/tools/virtual_scan.py: occlusion holes,
# an unseen base, density and noise from the rays) of CGAL's meshes at each
# --points count, cached under build/scale_inputs/. For each input, in this
# order: pdd reconstruct under /usr/bin/time -v (wall time, peak memory,
# per-stage seconds, final domain, triangles; each multigrid solve's unknowns,
# CG iterations and setup + CG seconds), then PoissonRecon at each
# --depth; the row names the depth whose output size is nearest pdd's and the
# time ratio at that depth. Needs scripts/setup.sh --bench (installed here),
# the peers in ../shared/anchors/bin and a build in build/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
points="100000,300000,1000000"
shapes="fandisk_large,refined_elephant"
depths="8,9,10,11"
building=1
out="bench/results/scale.md"
pdd_args=""
while [ $# -gt 0 ]; do
  case "$1" in
    --points) points="$2"; shift 2 ;;
    --shapes) shapes="$2"; shift 2 ;;
    --depths) depths="$2"; shift 2 ;;
    --no-building) building=0; shift ;;
    --out) out="$2"; shift 2 ;;
    --pdd-args) pdd_args="$2"; shift 2 ;;
    *) echo "scale.sh: unknown option $1" >&2; exit 2 ;;
  esac
done

bash scripts/setup.sh --bench
[ -x build/pdd ] || bash scripts/build.sh
peer="$root/../shared/anchors/bin/PoissonRecon"
scanner="$root/../shared/tools/virtual_scan.py"
[ -x "$peer" ] || { echo "scale.sh: $peer is missing" >&2; exit 2; }
cgal_data="build/scale_inputs/cgal"
if [ ! -d "$cgal_data/data" ]; then
  mkdir -p "$cgal_data"
  tar -xzf /usr/share/doc/libcgal-dev/data.tar.gz -C "$cgal_data" data/points_3/building.ply \
    data/meshes
fi

inputs=()
[ "$building" = 1 ] && inputs+=("$cgal_data/data/points_3/building.ply")
IFS=, read -ra shape_list <<< "$shapes"
IFS=, read -ra point_list <<< "$points"
for shape in "${shape_list[@]}"; do
  for n in "${point_list[@]}"; do
    scan="build/scale_inputs/${shape}_${n}.ply"
    if [ ! -s "$scan" ]; then
      /usr/bin/python3 "$scanner" "$cgal_data/data/meshes/$shape.off" "$scan" --points "$n" \
        --seed 1 > /dev/null
    fi
    inputs+=("$scan")
  done
done

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# Wall seconds and peak MB of a /usr/bin/time -v log.
seconds() {
  awk -F': ' '/Elapsed/ { n = split($2, t, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + t[i]; print s }' "$1"
}
peak_mb() { awk -F': ' '/Maximum resident/ { printf "%.0f", $2 / 1024 }' "$1"; }
faces() { /usr/bin/python3 -c "
import sys
with open(sys.argv[1], 'rb') as f:
    for line in f:
        if line.startswith(b'element face'): print(int(line.split()[2])); break
        if line.startswith(b'end_header'): break" "$1"; }

{
  echo "# bench/scale.sh ${pdd_args:+(pdd $pdd_args) }$(date -u '+%Y-%m-%d %H:%M UTC'), commit $(git rev-parse --short HEAD), $(nproc) cores"
  echo
  echo "| input | points | pdd s | peak MB | domain vertices | triangles | s / 100k triangles | solve / optimize / refine / contour / clean-up (with the trim) s | budget | PoissonRecon depth | PR triangles | PR s | PR MB | pdd / PR time | multigrid solves: unknowns, CG iterations, setup + CG s |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
} > "$work/table.md"
cat "$work/table.md"

for input in "${inputs[@]}"; do
  name="$(basename "$input" .ply)"
  n_points="$(/usr/bin/python3 -c "
import sys
with open(sys.argv[1], 'rb') as f:
    for line in f:
        if line.startswith(b'element vertex'): print(int(line.split()[2])); break" "$input")"
  # shellcheck disable=SC2086  # the extra options split into words
  /usr/bin/time -v build/pdd reconstruct "$input" -o "$work/pdd.ply" --quiet \
    --stats "$work/$name.json" $pdd_args > "$work/pdd.out" 2> "$work/pdd.time" || {
    echo "| $name | $n_points | FAILED: $(grep -v '^\s' "$work/pdd.time" | head -1) |" | tee -a "$work/table.md"
    continue
  }
  t_pdd="$(seconds "$work/pdd.time")"
  m_pdd="$(peak_mb "$work/pdd.time")"
  stages="$(jq -r '[.iterations[].seconds] | [map(.solve) , map(.optimize), map(.refine), map(.contour), map(.cleanup)] | map(add | . * 10 | round / 10) | map(tostring) | join(" / ")' "$work/$name.json")"
  vertices="$(jq -r .vertices "$work/$name.json")"
  triangles="$(jq -r .triangles "$work/$name.json")"
  solves="$(jq -r '[.iterations[] | select(.solver_method == "cg+multigrid") | "\(.vertices / 1000 | round)k \(.solver_iterations) \((.seconds.solve_factorize + .seconds.solve_linear) * 10 | round / 10)"] | join("; ")' "$work/$name.json")"
  budget="$(jq -r '.memory_budget | if .coarsening > 1 then "coarsened \(.coarsening * 100 | round / 100)x" elif .refinement_stopped then "stopped" else "-" end' "$work/$name.json")"
  best="" best_gap=""
  IFS=, read -ra depth_list <<< "$depths"
  for d in "${depth_list[@]}"; do
    /usr/bin/time -v "$peer" --in "$input" --out "$work/pr$d.ply" --depth "$d" \
      > /dev/null 2> "$work/pr$d.time" || continue
    f="$(faces "$work/pr$d.ply")"
    gap="$(awk -v a="$f" -v b="$triangles" 'BEGIN { g = a / b; if (g < 1) g = 1 / g; print g }')"
    if [ -z "$best" ] || awk -v g="$gap" -v b="$best_gap" 'BEGIN { exit !(g < b) }'; then
      best="$d" best_gap="$gap"
    fi
    echo "  $name: PoissonRecon depth $d: $f triangles, $(seconds "$work/pr$d.time") s" >&2
  done
  t_pr="$(seconds "$work/pr$best.time")"
  row="| $name | $n_points | $t_pdd | $m_pdd | $vertices | $triangles | $(awk -v t="$t_pdd" -v n="$triangles" 'BEGIN { printf "%.1f", t / n * 1e5 }') | $stages | $budget | $best | $(faces "$work/pr$best.ply") | $t_pr | $(peak_mb "$work/pr$best.time") | $(awk -v a="$t_pdd" -v b="$t_pr" 'BEGIN { printf "%.1f", a / b }') | $solves |"
  echo "$row" | tee -a "$work/table.md"
done
mkdir -p "$(dirname "$out")"
cp "$work/table.md" "$out"
echo "written to $out"
