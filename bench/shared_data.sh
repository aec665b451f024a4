#!/usr/bin/env bash
# The benchmark table on /work/shared/data (issue 7): for every input point set,
# `pdd reconstruct` with default options under /usr/bin/time -v (wall time, peak
# memory), then `pdd compare` against the ground truth and `pdd quality`, in the
# columns of /work/shared/data/README.md so that the rows compare with the peers
# listed there.
#
#   bench/shared_data.sh [PDD] [--domain STRATEGY] [--linear METHOD] [--solver S] [--seed S] [--only REGEX] [--data DIR] [--keep DIR]
#
#   PDD              the pdd binary (default: build/pdd)
#   --domain S       passed to `pdd reconstruct --domain S` (e.g. octree for the
#                    baseline); the table then goes to shared_data_S.md
#   --linear M       passed to `pdd reconstruct --linear M` (e.g. cholmod); the table
#                    then goes to shared_data_linear_M.md
#   --solver S       passed to `pdd reconstruct --solver S` (poisson, spectral); the
#                    table then goes to shared_data_solver_S.md
#   --seed S         passed to `pdd reconstruct --seed S`; the table then goes
#                    to shared_data_seed_S.md (default: pdd's default seed)
#   --only REGEX     only the inputs whose name (e.g. bunny_clean) matches
#   --data DIR       the data folder (default: ../shared/data beside the repository)
#   --keep DIR       keep the output meshes in DIR (default: a temporary folder,
#                    removed at the end)
#
# Writes bench/results/shared_data[_S].md (the table, also printed) and, per
# input, bench/results/shared_data[_S]/<input>.{stats,compare,quality}.json and
# <input>.time.txt. Needs GNU time and jq (scripts/setup.sh installs both).
# Exits 1 when a run failed (its row says so), 2 on bad usage.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
pdd="$root/build/pdd"
domain=""
solver=""
linear=""
seed=""
only=""
data="$root/../shared/data"
keep=""

usage() { sed -n '/^#   bench\/shared_data.sh/,/removed at the end)/s/^# \{0,1\}//p' "${BASH_SOURCE[0]}" >&2; exit "${1:-2}"; }
while [ $# -gt 0 ]; do
  case "$1" in
    --domain) [ $# -ge 2 ] || usage; domain="$2"; shift 2 ;;
    --linear) [ $# -ge 2 ] || usage; linear="$2"; shift 2 ;;
    --solver) [ $# -ge 2 ] || usage; solver="$2"; shift 2 ;;
    --seed) [ $# -ge 2 ] || usage; seed="$2"; shift 2 ;;
    --only) [ $# -ge 2 ] || usage; only="$2"; shift 2 ;;
    --data) [ $# -ge 2 ] || usage; data="$2"; shift 2 ;;
    --keep) [ $# -ge 2 ] || usage; keep="$2"; shift 2 ;;
    -h|--help) usage 0 ;;
    -*) echo "shared_data.sh: unknown option $1" >&2; usage ;;
    *) pdd="$1"; shift ;;
  esac
done

for tool in /usr/bin/time jq; do
  command -v "$tool" >/dev/null || { echo "shared_data.sh: $tool is missing; run scripts/setup.sh" >&2; exit 2; }
done
[ -x "$pdd" ] || { echo "shared_data.sh: $pdd is not an executable (build it, or pass its path)" >&2; exit 2; }
pdd="$(cd "$(dirname "$pdd")" && pwd)/$(basename "$pdd")"

name="shared_data${domain:+_$domain}${linear:+_linear_$linear}${solver:+_solver_$solver}${seed:+_seed_$seed}"
results="$root/bench/results"
details="$results/$name"
table="$results/$name.md"
mkdir -p "$details"
if [ -n "$keep" ]; then
  mkdir -p "$keep"
  work="$keep"
else
  work="$(mktemp -d "${TMPDIR:-/tmp}/pdd_shared_data.XXXXXX")"
  trap 'rm -rf "$work"' EXIT
fi

# --stats is new in `pdd reconstruct`: use it when this binary has it.
stats_flag=0
[[ "$("$pdd" reconstruct --help 2>/dev/null || true)" == *--stats* ]] && stats_flag=1

# "h:mm:ss" or "m:ss.ss" (GNU time's elapsed) -> seconds.
to_seconds() { awk -F: '{ s = 0; for (i = 1; i <= NF; ++i) s = s * 60 + $i; printf "%.2f", s }'; }
# The value of a field of GNU time -v's report.
time_field() { sed -n "s/^[[:space:]]*$1: //p" "$2" | tail -1; }
# jq's value of a path ("null" when missing).
field() { jq -r "$1" "$2"; }
# printf with a format, or "–" for a missing value.
fmt() { if [ "$2" = null ] || [ -z "$2" ]; then printf -- "–"; else awk -v f="$1" -v v="$2" 'BEGIN { printf f, v }'; fi; }
yes_no() { [ "$1" = true ] && printf yes || printf no; }

rows=()
stages=()
failed=0
# A row for a run that failed: the reason in the second column, the others empty.
fail() {
  echo "shared_data.sh: $1 failed: $2" >&2
  rows+=("| $1 | failed: ${2//|/\\|} | | | | | | | | | | | |")
  failed=1
}
sum_time=0
max_peak=0
runs=0
# The same over the inputs drawn from 20k samples (all but the sparse ones and
# the kitten scan; holes and vardens then lost some): the issue's targets.
sum_time_20k=0
max_peak_20k=0
runs_20k=0
right=0
with_truth=0

shopt -s nullglob
inputs=("$data"/points/*.ply)
[ ${#inputs[@]} -gt 0 ] || { echo "shared_data.sh: no $data/points/*.ply" >&2; exit 2; }

for input in "${inputs[@]}"; do
  base="$(basename "$input" .ply)"
  if [ -n "$only" ] && ! [[ "$base" =~ $only ]]; then continue; fi
  shape="${base%%_*}"
  truth="$data/gt/$shape.ply"
  mesh="$work/$base.ply"
  timelog="$details/$base.time.txt"
  echo "shared_data.sh: $base ..." >&2

  args=(reconstruct "$input" -o "$mesh")
  [ $stats_flag = 1 ] && args+=(--stats "$details/$base.stats.json")
  [ -n "$domain" ] && args+=(--domain "$domain")
  [ -n "$solver" ] && args+=(--solver "$solver")
  [ -n "$linear" ] && args+=(--linear "$linear")
  [ -n "$seed" ] && args+=(--seed "$seed")
  code=0
  /usr/bin/time -v -o "$timelog" "$pdd" "${args[@]}" 2>"$work/$base.stderr.txt" || code=$?
  if [ $code -ne 0 ]; then
    reason="$(grep -m1 'error' "$work/$base.stderr.txt" || tail -1 "$work/$base.stderr.txt")"
    fail "$base" "reconstruct exit $code, $(echo "$reason" | sed 's/^[[:space:]]*//')"
    continue
  fi

  seconds="$(time_field 'Elapsed (wall clock) time (h:mm:ss or m:ss)' "$timelog" | to_seconds)"
  peak_kb="$(time_field 'Maximum resident set size (kbytes)' "$timelog")"
  peak_mb="$(awk -v k="$peak_kb" 'BEGIN { printf "%.0f", k / 1024 }')"
  runs=$((runs + 1))
  sum_time="$(awk -v a="$sum_time" -v b="$seconds" 'BEGIN { print a + b }')"
  [ "$peak_mb" -gt "$max_peak" ] && max_peak="$peak_mb"
  if [[ "$base" != *_sparse && "$shape" != kitten ]]; then
    runs_20k=$((runs_20k + 1))
    sum_time_20k="$(awk -v a="$sum_time_20k" -v b="$seconds" 'BEGIN { print a + b }')"
    [ "$peak_mb" -gt "$max_peak_20k" ] && max_peak_20k="$peak_mb"
  fi

  quality="$details/$base.quality.json"
  if ! "$pdd" quality "$mesh" --json >"$quality" 2>"$work/$base.stderr.txt"; then
    fail "$base" "quality: $(tail -1 "$work/$base.stderr.txt")"
    continue
  fi
  faces="$(field .faces "$quality")"
  angle="$(fmt %.1f "$(field .triangles.mean_min_angle "$quality")")"
  below20="$(fmt %.1f "$(jq -r '.triangles.fraction_min_angle_below_20 * 100' "$quality")")"
  closed="$(field .surface.closed "$quality")"
  manifold="$(field .surface.manifold "$quality")"
  components="$(field .surface.components "$quality")"
  genus="$(field .surface.genus "$quality")"

  chamfer="–" hausdorff="–" fscore="–" topology="n/a (no ground truth)"
  if [ -f "$truth" ]; then
    compare="$details/$base.compare.json"
    if ! "$pdd" compare "$mesh" "$truth" --json >"$compare" 2>"$work/$base.stderr.txt"; then
      fail "$base" "compare: $(tail -1 "$work/$base.stderr.txt")"
      continue
    fi
    chamfer="$(fmt %.3f "$(jq -r '.chamfer_l1_relative * 1000' "$compare")")"
    hausdorff="$(fmt %.2f "$(jq -r '.hausdorff_relative * 100' "$compare")")"
    fscore="$(fmt %.3f "$(field .fscore "$compare")")"
    # Both ground truths (bunny, fandisk) are one closed manifold component of genus 0.
    with_truth=$((with_truth + 1))
    if [ "$closed" = true ] && [ "$manifold" = true ] && [ "$components" = 1 ] && [ "$genus" = 0 ]; then
      topology=yes
      right=$((right + 1))
    else
      topology=no
    fi
  fi
  [ "$genus" = null ] && genus="–"
  rows+=("| $base | $seconds | $peak_mb | $faces | $chamfer | $hausdorff | $fscore | $angle | $below20 | $(yes_no "$closed")/$(yes_no "$manifold") | $components | $genus | $topology |")
  stats="$details/$base.stats.json"
  if [ $stats_flag = 1 ] && [ -f "$stats" ]; then
    stages+=("$(jq -r '
      def total(f): [.iterations[] | f] | add;
      def s: . * 100 | round / 100;
      "| \(input_filename | split("/") | last | rtrimstr(".stats.json")) | \(.seconds | s) | " +
      "\(total(.seconds.solve_assembly) | s) | \(total(.seconds.solve_factorize) | s) | " +
      "\(total(.seconds.solve_linear) | s) | \(total(.seconds.optimize) | s) | " +
      "\(total(.seconds.refine) | s) | \(total(.seconds.contour) | s) | " +
      "\(total(.seconds.cleanup) | s) | \(.iterations | length) | \(.vertices) | " +
      "\(total(.solver_iterations)) |"' "$stats")")
  fi
done

{
  echo "# pdd on the shared data: domain ${domain:-progressive}, solver ${solver:-ssd}, linear solves ${linear:-multigrid}, seed ${seed:-default} (other options default)"
  echo
  echo "$(date -u '+%Y-%m-%d %H:%M UTC'); $("$pdd" --version 2>/dev/null || echo "pdd ?"), commit" \
    "$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo ?)$(git -C "$root" diff --quiet 2>/dev/null || echo "+local changes");" \
    "$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1), $(nproc) cores."
  [ $stats_flag = 1 ] || echo "This pdd has no \`reconstruct --stats\`: no per-stage statistics."
  echo
  echo "Time and peak memory (maximum resident set, MB = 2^20 bytes) of \`pdd reconstruct\` from \`/usr/bin/time -v\`."
  echo "Distances by \`pdd compare OUT GT\`: 200k area-uniform samples per surface, relative to the ground truth's"
  echo "bounding-box diagonal; Chamfer-L1 = mean of the two one-sided means; F-score at 0.5% of the diagonal."
  echo "Triangles by \`pdd quality\`. Topology right: closed, manifold, 1 component, genus 0 (both ground truths)."
  echo
  echo "| input | time s | peak MB | faces | Chamfer-L1 (1e-3) | Hausdorff (%) | F-score@0.5% | mean min angle (°) | triangles < 20° (%) | closed/manifold | components | genus | topology right |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
  echo
  if [ $runs -gt 0 ]; then
    echo "Mean time $(awk -v s="$sum_time" -v n="$runs" 'BEGIN { printf "%.2f", s / n }') s and largest peak memory" \
      "$max_peak MB over $runs runs; topology right on $right of $with_truth inputs with a ground truth."
  fi
  if [ $runs_20k -gt 0 ]; then
    echo "Over the $runs_20k inputs drawn from 20k samples (all but sparse and the kitten): mean time" \
      "$(awk -v s="$sum_time_20k" -v n="$runs_20k" 'BEGIN { printf "%.2f", s / n }') s, largest peak memory $max_peak_20k MB."
  fi
  if [ ${#stages[@]} -gt 0 ]; then
    echo
    echo "Seconds per stage, summed over the iterations (\`--stats\`): the solves' assembly, factorization"
    echo "(CHOLMOD, or the multigrid setup) and linear solve (CG / triangular solves), the optimizer, the"
    echo "refiner, marching tetrahedra, the final clean-up; iterations, final domain vertices, CG iterations."
    echo
    echo "| input | total | solve: assembly | solve: factorize | solve: linear | optimize | refine | contour | clean-up | iterations | final vertices | CG iterations |"
    echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
    printf '%s\n' "${stages[@]}"
  fi
} >"$table"
cat "$table"
exit $failed
