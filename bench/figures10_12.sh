#!/usr/bin/env bash
# Figures 10-12 of the paper (§4.3): the progressive domain against the
# octree-based one, same SSD solver, on the shared data's inputs of different
# density (Figure 10: clean, sparse, vardens), noise (Figure 11: noise05,
# noise10) and holes (Figure 12), plus the kitten scan (no ground truth).
# Reads the per-input JSONs that bench/shared_data.sh writes for both
# strategies, or runs it first with --run.
#
#   bench/figures10_12.sh [PDD] [--run] [--only REGEX] [--data DIR]
#
#   PDD              the pdd binary for --run (default: build/pdd)
#   --run            first run bench/shared_data.sh PDD and
#                    bench/shared_data.sh PDD --domain octree (about 10 minutes
#                    on 2 cores); otherwise read their existing results
#   --only REGEX     only the inputs whose name (e.g. bunny_sparse) matches
#                    (also passed to shared_data.sh with --run)
#   --data DIR       passed to shared_data.sh with --run
#
# Reads bench/results/shared_data{,_octree}/<input>.{compare,quality}.json and
# writes bench/results/figures10_12.md (also printed). Needs jq. Exits 1 when
# an input lacks a result for one of the strategies or a --run failed, 2 on
# bad usage or when there are no results at all.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
pdd="$root/build/pdd"
run=0
only=""
data_args=()

usage() { sed -n '/^#   bench\/figures10_12.sh/,/passed to shared_data.sh with --run$/s/^# \{0,1\}//p' "${BASH_SOURCE[0]}" >&2; exit "${1:-2}"; }
while [ $# -gt 0 ]; do
  case "$1" in
    --run) run=1; shift ;;
    --only) [ $# -ge 2 ] || usage; only="$2"; shift 2 ;;
    --data) [ $# -ge 2 ] || usage; data_args=(--data "$2"); shift 2 ;;
    -h|--help) usage 0 ;;
    -*) echo "figures10_12.sh: unknown option $1" >&2; usage ;;
    *) pdd="$1"; shift ;;
  esac
done
command -v jq >/dev/null || { echo "figures10_12.sh: jq is missing; run scripts/setup.sh" >&2; exit 2; }

results="$root/bench/results"
failed=0
if [ $run = 1 ]; then
  only_args=()
  [ -n "$only" ] && only_args=(--only "$only")
  "$root/bench/shared_data.sh" "$pdd" "${only_args[@]}" "${data_args[@]}" >/dev/null || failed=1
  "$root/bench/shared_data.sh" "$pdd" --domain octree "${only_args[@]}" "${data_args[@]}" >/dev/null || failed=1
fi

progressive="$results/shared_data"
octree="$results/shared_data_octree"
table="$results/figures10_12.md"

# The figure of the paper an input's variant illustrates.
figure() {
  case "$1" in
    *_clean|*_sparse|*_vardens) echo 10 ;;
    *_noise*) echo 11 ;;
    *_holes) echo 12 ;;
    kitten_scan) echo "10 (scan)" ;;
    *) echo "–" ;;
  esac
}
# jq's value of an expression on a file, with printf format $1; "–" when
# the file or the value is missing.
value() {
  [ -f "$3" ] || { printf -- "–"; return; }
  jq -r "$2 // \"null\"" "$3" | awk -v f="$1" '$0 == "null" || $0 == "" { printf "–"; next } { printf f, $0 }'
}
# "progressive", "octree" or "tie" for the smaller of two numbers ("n/a" if one is missing).
smaller() {
  awk -v p="$1" -v o="$2" 'BEGIN {
    if (p !~ /^[0-9.]+$/ || o !~ /^[0-9.]+$/) { print "n/a"; exit }
    print (p + 0 < o + 0) ? "progressive" : (o + 0 < p + 0) ? "octree" : "tie" }'
}
# Bold for the better (smaller) of two numbers.
pair() {
  local better
  better="$(smaller "$1" "$2")"
  case "$better" in
    progressive) printf '**%s** | %s' "$1" "$2" ;;
    octree) printf '%s | **%s**' "$1" "$2" ;;
    *) printf '%s | %s' "$1" "$2" ;;
  esac
}

shopt -s nullglob
inputs=()
for f in "$progressive"/*.quality.json "$octree"/*.quality.json; do
  base="$(basename "$f" .quality.json)"
  if [ -n "$only" ] && ! [[ "$base" =~ $only ]]; then continue; fi
  inputs+=("$base")
done
[ ${#inputs[@]} -gt 0 ] || { echo "figures10_12.sh: no results in $progressive or $octree (run with --run)" >&2; exit 2; }
mapfile -t inputs < <(printf '%s\n' "${inputs[@]}" | sort -u)

rows=()
compared=0 chamfer_wins=0 hausdorff_wins=0 angle_wins=0 fewer_faces=0
for base in "${inputs[@]}"; do
  for dir in "$progressive" "$octree"; do
    if [ ! -f "$dir/$base.quality.json" ]; then
      echo "figures10_12.sh: no $dir/$base.quality.json" >&2
      failed=1
    fi
  done
  cp="$(value %.3f '.chamfer_l1_relative * 1000' "$progressive/$base.compare.json")"
  co="$(value %.3f '.chamfer_l1_relative * 1000' "$octree/$base.compare.json")"
  hp="$(value %.2f '.hausdorff_relative * 100' "$progressive/$base.compare.json")"
  ho="$(value %.2f '.hausdorff_relative * 100' "$octree/$base.compare.json")"
  ap="$(value %.1f '.triangles.mean_min_angle' "$progressive/$base.quality.json")"
  ao="$(value %.1f '.triangles.mean_min_angle' "$octree/$base.quality.json")"
  bp="$(value %.1f '.triangles.fraction_min_angle_below_20 * 100' "$progressive/$base.quality.json")"
  bo="$(value %.1f '.triangles.fraction_min_angle_below_20 * 100' "$octree/$base.quality.json")"
  fp="$(value %d '.faces' "$progressive/$base.quality.json")"
  fo="$(value %d '.faces' "$octree/$base.quality.json")"
  by_chamfer="$(smaller "$cp" "$co")"
  by_hausdorff="$(smaller "$hp" "$ho")"
  if [ "$by_chamfer" = n/a ]; then
    verdict="n/a (no ground truth)"
  else
    compared=$((compared + 1))
    [ "$by_chamfer" = progressive ] && chamfer_wins=$((chamfer_wins + 1))
    [ "$by_hausdorff" = progressive ] && hausdorff_wins=$((hausdorff_wins + 1))
    if [ "$by_chamfer" = "$by_hausdorff" ]; then verdict="$by_chamfer"
    else verdict="$by_chamfer (Chamfer), $by_hausdorff (Hausdorff)"; fi
  fi
  # The larger mean min angle is better: smaller() with the octree's value first.
  [ "$(smaller "$ao" "$ap")" = progressive ] && angle_wins=$((angle_wins + 1))
  [ "$(smaller "$fp" "$fo")" = progressive ] && fewer_faces=$((fewer_faces + 1))
  rows+=("| $base | $(figure "$base") | $(pair "$cp" "$co") | $(pair "$hp" "$ho") | $ap | $ao | $bp | $bo | $fp | $fo | $verdict |")
done
# The run line of a shared_data table (its date, pdd and commit).
provenance() { [ -f "$1" ] && sed -n '3p' "$1" || echo "(no $1)"; }
{
  echo "# Figures 10-12 (§4.3): progressive against octree-based domain, same SSD solver"
  echo
  echo "Progressive: $(provenance "$results/shared_data.md")"
  echo "Octree: $(provenance "$results/shared_data_octree.md")"
  echo
  echo "From \`bench/shared_data.sh\` (default options) and \`bench/shared_data.sh --domain octree\`. Distances by"
  echo "\`pdd compare OUT GT\` relative to the ground truth's bounding-box diagonal: Chamfer-L1 in 1e-3, Hausdorff"
  echo "in %; **bold** = the better of the two. Triangles by \`pdd quality\`. \"More accurate\" by Chamfer-L1, and by"
  echo "Hausdorff when the two disagree. Figure: 10 = density (clean, sparse, variable), 11 = noise, 12 = holes."
  echo
  echo "| input | figure | Chamfer-L1 progressive | Chamfer-L1 octree | Hausdorff progressive | Hausdorff octree | mean min angle (°) progressive | mean min angle (°) octree | < 20° (%) progressive | < 20° (%) octree | faces progressive | faces octree | more accurate |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
  echo
  echo "Progressive is more accurate on $chamfer_wins of $compared inputs with a ground truth by Chamfer-L1 and on" \
    "$hausdorff_wins of $compared by Hausdorff; it has the larger mean min angle on $angle_wins of ${#inputs[@]}" \
    "inputs and fewer faces on $fewer_faces of ${#inputs[@]}."
} >"$table"
cat "$table"
exit $failed
