#!/usr/bin/env bash
# `make bench`: dtlab against CGAL's Delaunay_triangulation_2 on 2^20 uniform points in the
# paper's 1600x1600 box, then dtlab's peak memory (GNU time). Needs jq and /usr/bin/time.
#
# usage: bash .ci/bench_compare.sh [BUILD_DIR]      (default: build)
# Environment: BENCH_N (points, default 1048576), BENCH_ROUNDS (alternating rounds, default 7),
# BENCH_SEED (default 1).
set -euo pipefail

build=${1:-build}
n=${BENCH_N:-1048576}
rounds=${BENCH_ROUNDS:-7}
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

# The VM's load drifts from second to second: the two tools run in alternation, one timed run
# each per round (after each process's own warm-up run), so that both medians cover the same
# span of time. A ratio from two back-to-back blocks of runs swung by +-20% here.
median_min() {
    printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END {
        m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2; printf "%.1f %.1f", m, v[1] }'
}

have_cgal=0
if [[ -x $cgal ]]; then have_cgal=1; else
    echo "bench: $cgal was not built (CGAL not found: apt-get install libcgal-dev); no comparison"
fi
echo
echo "== $rounds rounds: dtlab bench --input $input --repeat 1 --json; cgal_baseline $input --repeat 1 --json"
dt_ms=()
cg_ms=()
dt_json=""
for (( r = 1; r <= rounds; ++r )); do
    dt_json=$(json_of "$("$dtlab" bench --input "$input" --repeat 1 --json)")
    dt_ms+=("$(field "$dt_json" median_ms)")
    line=$(printf 'round %d: dtlab %9.1f ms' "$r" "${dt_ms[-1]}")
    if (( have_cgal )); then
        cg_json=$(json_of "$("$cgal" "$input" --repeat 1 --json)")
        cg_ms+=("$(field "$cg_json" median_ms)")
        line+=$(printf '   cgal %9.1f ms   ratio %.2f' "${cg_ms[-1]}" "$(awk -v a="${dt_ms[-1]}" -v b="${cg_ms[-1]}" 'BEGIN { print a / b }')")
    fi
    echo "$line"
done
echo "dtlab (last round): $dt_json"

read -r dt_med dt_min <<<"$(median_min "${dt_ms[@]}")"
echo
echo "== summary (n = $(field "$dt_json" n), $rounds alternating rounds)"
printf '%-8s %12s %10s %14s %16s %20s\n' tool median_ms min_ms ns_per_point flips_per_point walk_steps_per_point
printf '%-8s %12s %10s %14.1f %16.3f %20.3f\n' dtlab "$dt_med" "$dt_min" \
    "$(awk -v m="$dt_med" -v n="$n" 'BEGIN { print m * 1e6 / n }')" \
    "$(field "$dt_json" flips_per_point)" "$(field "$dt_json" walk_steps_per_point)"
if (( have_cgal )); then
    read -r cg_med cg_min <<<"$(median_min "${cg_ms[@]}")"
    printf '%-8s %12s %10s %14.1f %16s %20s\n' cgal "$cg_med" "$cg_min" \
        "$(awk -v m="$cg_med" -v n="$n" 'BEGIN { print m * 1e6 / n }')" "-" "-"
    awk -v a="$dt_med" -v b="$cg_med" -v am="$dt_min" -v bm="$cg_min" 'BEGIN {
        printf "ratio dtlab/cgal (median): %.2f\n", a / b;
        printf "ratio dtlab/cgal (min):    %.2f\n", am / bm;
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
