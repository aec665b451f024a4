#!/usr/bin/env bash
# Table 1 of the paper (§4.2) on two real scans: the four ways of building the
# domain (`pdd reconstruct --domain octree|input|direct|progressive`, same SSD
# solver and parameters) against a reference isosurface computed with the same
# solver on a dense domain, built as §4.2 describes by table1_reference
# (bench/table1_reference.cpp: octree-based SSD, its isosurface sampled densely
# and offset both ways, both layers in a Delaunay triangulation, SSD).
#
#   bench/table1.sh [PDD] [--only REGEX] [--cgal-data TARBALL] [--keep DIR]
#
#   PDD              the pdd binary (default: build/pdd); table1_reference is
#                    taken from the same folder (cmake --build B --target
#                    pdd table1_reference)
#   --only REGEX     only the scans whose name (kitten, hippo) matches
#   --cgal-data T    CGAL's data set (default: /usr/share/doc/libcgal-dev/data.tar.gz,
#                    from the Debian package libcgal-demo, see scripts/setup.sh)
#   --keep DIR       keep the meshes in DIR (default: a temporary folder,
#                    removed at the end)
#
# Scans: kitten = data/kitten_scan.ply (5210 points), pdd's default sizing;
# hippo = CGAL's data/points_3/hippo1.ply (6104 points with normals, one view
# of a range scan, read as it is), target edge 1.5 x its average spacing (the
# default gives 266k triangles and 3.5 GB for progressive alone). The
# reference samples its layers at 0.7 x the target edge. The hippo is a
# partial scan: every method invents its back and may run to the domain's
# boundary, so its distances are measured on the scanned part (faces within
# one target edge of an input point, `table1_reference crop`), and on the
# whole surfaces in extra rows.
# Writes bench/results/table1.md (the tables, also printed) and, per scan and
# method, bench/results/table1/<scan>.<method>.{stats,compare,quality}.json
# (partial scans: also .compare_whole.json) and .time.txt. Needs GNU time and jq. Exits 1 when a run failed (its column
# says so), 2 on bad usage or missing inputs.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
pdd="$root/build/pdd"
only=""
cgal_data="/usr/share/doc/libcgal-dev/data.tar.gz"
keep=""

usage() { sed -n '/^#   bench\/table1.sh/,/removed at the end)/s/^# \{0,1\}//p' "${BASH_SOURCE[0]}" >&2; exit "${1:-2}"; }
while [ $# -gt 0 ]; do
  case "$1" in
    --only) [ $# -ge 2 ] || usage; only="$2"; shift 2 ;;
    --cgal-data) [ $# -ge 2 ] || usage; cgal_data="$2"; shift 2 ;;
    --keep) [ $# -ge 2 ] || usage; keep="$2"; shift 2 ;;
    -h|--help) usage 0 ;;
    -*) echo "table1.sh: unknown option $1" >&2; usage ;;
    *) pdd="$1"; shift ;;
  esac
done

for tool in /usr/bin/time jq; do
  command -v "$tool" >/dev/null || { echo "table1.sh: $tool is missing; run scripts/setup.sh" >&2; exit 2; }
done
[ -x "$pdd" ] || { echo "table1.sh: $pdd is not an executable (build it, or pass its path)" >&2; exit 2; }
pdd="$(cd "$(dirname "$pdd")" && pwd)/$(basename "$pdd")"
reference_tool="$(dirname "$pdd")/table1_reference"
[ -x "$reference_tool" ] || { echo "table1.sh: $reference_tool is missing (cmake --build $(dirname "$pdd") --target table1_reference)" >&2; exit 2; }

results="$root/bench/results"
details="$results/table1"
table="$results/table1.md"
mkdir -p "$details"
if [ -n "$keep" ]; then
  mkdir -p "$keep"
  work="$keep"
else
  work="$(mktemp -d "${TMPDIR:-/tmp}/pdd_table1.XXXXXX")"
  trap 'rm -rf "$work"' EXIT
fi

# name | input (a path, or cgal:<member of the data set>) | target edge / average spacing
# ("" = pdd's default) | partial (compare the scanned parts) or ""
scans=(
  "kitten|$root/data/kitten_scan.ply||"
  "hippo|cgal:data/points_3/hippo1.ply|1.5|partial"
)
reference_ratio=0.7  # the reference's sample spacing / the target edge
methods=(octree input direct progressive reference)

to_seconds() { awk -F: '{ s = 0; for (i = 1; i <= NF; ++i) s = s * 60 + $i; printf "%.2f", s }'; }
time_field() { sed -n "s/^[[:space:]]*$1: //p" "$2" | tail -1; }
# jq's value of an expression, formatted with printf format $1 ("–" when missing).
value() { jq -r "$2 // \"null\"" "$3" 2>/dev/null | awk -v f="$1" '$0 == "null" || $0 == "" { printf "–"; next } { printf f, $0 }'; }

# One row of scan $name: one measure, one column per method (the paper's
# layout); the best of the four methods in bold (smallest distance, largest
# parsimony).
row() {  # label, jq expression, file kind (compare|stats|quality|time), printf format, best (min|max|"")
  local label="$1" expr="$2" kind="$3" format="$4" best="$5" line="| $1 |" values=() v m file
  for m in "${methods[@]}"; do
    file="$details/$name.$m.$kind.json"
    if [ -f "$work/$name.$m.failed" ]; then v="failed ($(cat "$work/$name.$m.failed"))"
    elif [ "$kind" = time ]; then
      file="$details/$name.$m.time.txt"
      case "$expr" in
        wall) v="$(time_field 'Elapsed (wall clock) time (h:mm:ss or m:ss)' "$file" | to_seconds)" ;;
        peak) v="$(awk -v k="$(time_field 'Maximum resident set size (kbytes)' "$file")" 'BEGIN { printf "%.0f", k / 1024 }')" ;;
      esac
    elif [ -f "$file" ]; then v="$(value "$format" "$expr" "$file")"
    else v="–"; fi
    values+=("$v")
  done
  local target=""
  if [ -n "$best" ]; then
    target="$(printf '%s\n' "${values[@]:0:4}" | grep -E '^[0-9.]+$' | sort -g | sed -n "$([ "$best" = min ] && echo 1p || echo '$p')" || true)"
  fi
  for v in "${values[@]:0:4}"; do
    if [ -n "$target" ] && [ "$v" = "$target" ]; then line+=" **$v** |"; else line+=" $v |"; fi
  done
  line+=" ${values[4]} |"
  echo "$line"
}

failed=0
sections=()
for scan in "${scans[@]}"; do
  IFS='|' read -r name source edge_ratio partial <<<"$scan"
  if [ -n "$only" ] && ! [[ "$name" =~ $only ]]; then continue; fi
  echo "table1.sh: $name ..." >&2
  input="$source"
  if [[ "$source" == cgal:* ]]; then
    member="${source#cgal:}"
    [ -f "$cgal_data" ] || { echo "table1.sh: $cgal_data is missing: install libcgal-demo (scripts/setup.sh) or pass --cgal-data" >&2; exit 2; }
    input="$work/$name.${member##*.}"
    tar -xzf "$cgal_data" -O "$member" >"$input" || { echo "table1.sh: no $member in $cgal_data" >&2; exit 2; }
  fi
  [ -f "$input" ] || { echo "table1.sh: $input is missing" >&2; exit 2; }
  points="$(head -c 2000 "$input" | sed -n '/^element vertex /{s///p;q}' || true)"

  spacing="$("$reference_tool" spacing "$input")"
  edge_args=()
  edge="$("$reference_tool" default-edge "$input")"
  if [ -n "$edge_ratio" ]; then
    edge="$(awk -v s="$spacing" -v r="$edge_ratio" 'BEGIN { printf "%.10g", s * r }')"
    edge_args=(--target-edge "$edge")
  fi
  reference_edge="$(awk -v e="$edge" -v r="$reference_ratio" 'BEGIN { printf "%.10g", e * r }')"
  ref_mesh="$work/$name.reference.ply"

  for method in reference octree input direct progressive; do
    mesh="$work/$name.$method.ply"
    stats="$details/$name.$method.stats.json"
    timelog="$details/$name.$method.time.txt"
    rm -f "$stats" "$details/$name.$method".{compare,compare_whole,quality}.json "$work/$name.$method.failed"
    if [ "$method" = reference ]; then
      command=("$reference_tool" build "$input" "$mesh" "$stats" --edge "$reference_edge")
    else
      command=("$pdd" reconstruct "$input" -o "$mesh" --domain "$method" --stats "$stats" --quiet "${edge_args[@]}")
    fi
    echo "table1.sh:   $method" >&2
    code=0
    /usr/bin/time -v -o "$timelog" "${command[@]}" >"$work/$name.$method.stdout.txt" 2>"$work/$name.$method.stderr.txt" || code=$?
    if [ $code -ne 0 ]; then
      reason="$(grep -m1 -i 'error' "$work/$name.$method.stderr.txt" || tail -1 "$work/$name.$method.stderr.txt")"
      echo "table1.sh: $name $method failed (exit $code): $reason" >&2
      echo "exit $code" >"$work/$name.$method.failed"
      failed=1
      continue
    fi
    "$pdd" quality "$mesh" --json >"$details/$name.$method.quality.json" 2>/dev/null || true
    # Partial scans: the scanned parts (crop) against each other, and the whole surfaces.
    if [ -n "$partial" ] && ! "$reference_tool" crop "$mesh" "$input" "$edge" "$work/$name.$method.crop.ply" 2>"$work/$name.$method.stderr.txt"; then
      echo "table1.sh: $name $method: crop failed: $(tail -1 "$work/$name.$method.stderr.txt")" >&2
      failed=1
    fi
    if [ "$method" != reference ] && [ -f "$ref_mesh" ]; then
      pairs=("compare|$mesh|$ref_mesh")
      [ -n "$partial" ] && pairs=("compare|$work/$name.$method.crop.ply|$work/$name.reference.crop.ply" "compare_whole|$mesh|$ref_mesh")
      for pair in "${pairs[@]}"; do
        IFS='|' read -r kind a b <<<"$pair"
        if ! "$pdd" compare "$a" "$b" --json >"$details/$name.$method.$kind.json" 2>"$work/$name.$method.stderr.txt"; then
          echo "table1.sh: $name $method: $kind failed: $(tail -1 "$work/$name.$method.stderr.txt")" >&2
          rm -f "$details/$name.$method.$kind.json"
          failed=1
        fi
      done
    fi
  done

  section="$(
    echo "### $name: ${points} points; $( [ -n "$edge_ratio" ] && echo "target edge $edge_ratio x the average spacing $(printf '%.4g' "$spacing") = $(printf '%.4g' "$edge")" || echo "pdd's default sizing (the average spacing $(printf '%.4g' "$spacing"), or finer when it is over 1 % of the diagonal: target edge $(printf '%.4g' "$edge"))" ); reference layers $(printf '%.4g' "$reference_edge") apart"
    if [ -n "$partial" ]; then
      echo
      echo "A partial scan: the first five distances compare the scanned parts (faces whose centroid is within"
      echo "$(printf '%.4g' "$edge") of an input point); the \"whole surfaces\" rows compare everything, invented parts included."
    fi
    echo
    echo "| measure | octree | input | direct | progressive | reference |"
    echo "|---|---|---|---|---|---|"
    row "Hausdorff (%)" '.hausdorff_relative * 100' compare %.3f min
    row "Mean, method → ref (%)" '.mean_a_to_b_relative * 100' compare %.4f min
    row "Mean, ref → method (%)" '.mean_b_to_a_relative * 100' compare %.4f min
    row "RMS, method → ref (%)" '.rms_a_to_b_relative * 100' compare %.4f min
    row "RMS, ref → method (%)" '.rms_b_to_a_relative * 100' compare %.4f min
    if [ -n "$partial" ]; then
      row "Whole surfaces: Hausdorff (%)" '.hausdorff_relative * 100' compare_whole %.3f min
      row "Whole surfaces: mean, method → ref (%)" '.mean_a_to_b_relative * 100' compare_whole %.4f min
      row "Whole surfaces: mean, ref → method (%)" '.mean_b_to_a_relative * 100' compare_whole %.4f min
    fi
    row "Time (s)" wall time "" ""
    row "Peak memory (MB)" peak time "" ""
    row "# Isovertices (1)" '.iterations[-1].isovertices' stats %d ""
    row "# Vertices around iso (2)" '.iterations[-1].vertices_near_isosurface' stats %d ""
    row "# Vertices (3)" '.iterations[-1].vertices' stats %d ""
    row "Parsimony (4) = (2)/(3)" '.iterations[-1].parsimony' stats %.3f max
    row "Output closed / genus" '"\(if .surface.closed then "yes" else "no" end) / \(.surface.genus // "–")"' quality %s ""
  )"
  sections+=("$section")
done

[ ${#sections[@]} -gt 0 ] || { echo "table1.sh: no scan matches '$only'" >&2; exit 2; }
{
  echo "# Table 1 (§4.2): domain strategies against a dense reference"
  echo
  echo "$(date -u '+%Y-%m-%d %H:%M UTC'); $("$pdd" --version 2>/dev/null || echo "pdd ?"), commit" \
    "$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo ?)$(git -C "$root" diff --quiet 2>/dev/null || echo "+local changes");" \
    "$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1), $(nproc) cores."
  echo
  echo "Distances by \`pdd compare METHOD REFERENCE\` (200k area-uniform samples per surface), in % of the"
  echo "reference's bounding-box diagonal; **bold** = best of the four methods. Time and peak memory of the whole"
  echo "run from \`/usr/bin/time -v\`. (1)-(4) from the last entry of the \`--stats\` JSON: isosurface vertices,"
  echo "domain vertices of the tets the isosurface crosses, all domain vertices, (2)/(3)."
  for s in "${sections[@]}"; do
    echo
    echo "$s"
  done
} >"$table"
cat "$table"
exit $failed
