#!/usr/bin/env bash
# `make bench`: dtlab against CGAL's Delaunay_triangulation_2 on 2^20 uniform points in the
# paper's 1600x1600 box, then dtlab's peak memory (GNU time). Needs jq and /usr/bin/time.
#
# usage: bash .ci/bench_compare.sh [BUILD_DIR]      (default: build)
# Environment: BENCH_N (points, default 1048576), BENCH_REPEAT (default 7), BENCH_SEED (default 1).
set -euo pipefail

build=${1:-build}
n=${BENCH_N:-1048576}
repeat=${BENCH_REPEAT:-7}
seed=${BENCH_SEED:-1}
dtlab=$build/app/dtlab
cgal=$build/app/cgal_baseline
dir=$build/bench
if [[ $n == 1048576 ]]; then input=$dir/uniform_1m.node; else input=$dir/uniform_$n.node; fi

for tool in jq /usr/bin/time "$dtlab"; do
    command -v "$tool" >/dev/null || { echo "bench: $tool not found (run make deps / make build)" >&2; exit 1; }
done
mkdir -p "$dir"

if [[ -s $input ]]; then
    echo "bench: reusing $input"
else
    echo "bench: generating $input"
    "$dtlab" gen uniform "$n" --seed "$seed" -o "$input"
fi

# The last JSON value a tool printed on stdout (pretty or on one line); fails unless an object.
json_of() { jq -ces 'last | if type == "object" then . else error("no JSON object") end' <<<"$1"; }
field() { jq -r --arg k "$2" '.[$k] // "n/a"' <<<"$1"; }

echo
echo "== dtlab bench --input $input --repeat $repeat --json"
dt_out=$("$dtlab" bench --input "$input" --repeat "$repeat" --json)
dt_json=$(json_of "$dt_out")
echo "$dt_json"

cg_json=""
if [[ -x $cgal ]]; then
    echo
    echo "== cgal_baseline $input --repeat $repeat --json"
    cg_out=$("$cgal" "$input" --repeat "$repeat" --json)
    cg_json=$(json_of "$cg_out")
    echo "$cg_json"
else
    echo
    echo "bench: $cgal was not built (CGAL not found: apt-get install libcgal-dev); no comparison"
fi

echo
echo "== summary (n = $(field "$dt_json" n), median of $repeat runs)"
printf '%-8s %12s %10s %14s %16s %20s\n' tool median_ms min_ms ns_per_point flips_per_point walk_steps_per_point
printf '%-8s %12s %10s %14s %16s %20s\n' dtlab "$(field "$dt_json" median_ms)" "$(field "$dt_json" min_ms)" \
    "$(field "$dt_json" ns_per_point)" "$(field "$dt_json" flips_per_point)" \
    "$(field "$dt_json" walk_steps_per_point)"
if [[ -n $cg_json ]]; then
    printf '%-8s %12s %10s %14s %16s %20s\n' cgal "$(field "$cg_json" median_ms)" "$(field "$cg_json" min_ms)" \
        "$(field "$cg_json" ns_per_point)" "-" "-"
    awk -v a="$(field "$dt_json" median_ms)" -v b="$(field "$cg_json" median_ms)" \
        -v am="$(field "$dt_json" min_ms)" -v bm="$(field "$cg_json" min_ms)" 'BEGIN {
        if (b + 0 > 0) printf "ratio dtlab/cgal (median): %.2f\n", a / b;
        else print "ratio dtlab/cgal: n/a";
        if (bm + 0 > 0) printf "ratio dtlab/cgal (min):    %.2f\n", am / bm;
    }'
fi

echo
echo "== peak memory: dtlab triangulate $input -o $dir/out"
timelog=$dir/time_triangulate.txt
/usr/bin/time -v -o "$timelog" "$dtlab" triangulate "$input" -o "$dir/out" >/dev/null
rss_kb=$(awk -F': *' '/Maximum resident set size/ { print $2 }' "$timelog")
wall=$(awk -F': ' '/Elapsed \(wall clock\) time/ { print $2 }' "$timelog")
awk -v kb="$rss_kb" -v n="$n" -v wall="$wall" 'BEGIN {
    printf "dtlab triangulate: Maximum resident set size %d kB (%.1f MiB, %.0f bytes/point), wall %s\n",
           kb, kb / 1024, kb * 1024 / n, wall;
}'
if [[ -x $cgal ]]; then
    /usr/bin/time -v -o "$dir/time_cgal.txt" "$cgal" "$input" --repeat 1 >/dev/null
    awk -F': *' -v n="$n" '/Maximum resident set size/ {
        printf "cgal_baseline --repeat 1 (for scale; no output written): Maximum resident set size %d kB (%.1f MiB, %.0f bytes/point)\n",
               $2, $2 / 1024, $2 * 1024 / n;
    }' "$dir/time_cgal.txt"
fi
