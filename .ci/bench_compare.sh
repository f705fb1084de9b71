#!/usr/bin/env bash
# `make bench`: dtlab against CGAL's Delaunay_triangulation_2 (Epick, range insert) on 2^20 points
# of every distribution of dtlab gen that users load (files made by `dtlab gen` with fixed seeds),
# then uniform points at 2^22 and 2^24; a Markdown table of medians, ratios, ns/point, walk steps,
# predicate calls by stage and the peak memory of `dtlab triangulate` and of CGAL's run, and the
# geometric mean of the ratios. Needs jq and /usr/bin/time; ~20 minutes on 2 quiet cores.
#
# usage: bash .ci/bench_compare.sh [BUILD_DIR]      (default: build)
# Environment:
#   BENCH_KINDS         distributions at BENCH_N (default: uniform gaussian clusters
#                       uneven-clusters kuzmin log-radial grid rotated-grid disc-in-box curves,
#                       and the sets that attack the two-core split and join: circle parabola
#                       convex-hull facing-arcs spiral)
#   BENCH_N             their size (default 1048576 = 2^20)
#   BENCH_LARGE         sizes of uniform points after them (default "4194304 16777216"; "" none)
#   BENCH_ROUNDS        alternating rounds at BENCH_N (default 7)
#   BENCH_ROUNDS_LARGE  alternating rounds at the large sizes (default 3)
#   BENCH_SEED          seed of every generated file (default 1)
#   BENCH_MEMORY=0      skip the peak-memory runs
set -euo pipefail

build=${1:-build}
kinds=${BENCH_KINDS:-uniform gaussian clusters uneven-clusters kuzmin log-radial grid rotated-grid disc-in-box curves circle parabola convex-hull facing-arcs spiral}
n=${BENCH_N:-1048576}
large=${BENCH_LARGE-4194304 16777216}
rounds=${BENCH_ROUNDS:-7}
rounds_large=${BENCH_ROUNDS_LARGE:-3}
seed=${BENCH_SEED:-1}
memory=${BENCH_MEMORY:-1}
dtlab=$build/app/dtlab
cgal=$build/app/cgal_baseline
dir=$build/bench

for tool in jq /usr/bin/time "$dtlab"; do
    command -v "$tool" >/dev/null || { echo "bench: $tool not found (run make deps / make build)" >&2; exit 1; }
done
have_cgal=1
[[ -x $cgal ]] || { have_cgal=0; echo "bench: $cgal was not built (apt-get install libcgal-dev): dtlab alone" >&2; }
mkdir -p "$dir"

# The last JSON value a tool printed on stdout; fails unless it is an object.
json_of() { jq -ces 'last | if type == "object" then . else error("no JSON object") end' <<<"$1"; }
field() { jq -r --arg k "$2" '.[$k] // "n/a"' <<<"$1"; }
median() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { printf "%.1f", NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
calc() { awk "BEGIN { printf \"$1\", $2 }"; }

# Predicate calls per point that the floating-point filter left, by the stage that decided them,
# from dtlab bench's "predicates_past_filter" object ({"orient2d": {"zero-tail": calls,
# "stage-b": calls, ...}, "incircle": {...}}, counts of one timed run); "n/a" when absent.
predicates() {
    jq -r --argjson n "$2" '(.predicates_past_filter) as $p | if ($p | type) != "object" then "n/a" else
        [$p | to_entries[] | select(.value | type == "object") |
         "\(.key) " + ([.value | to_entries[] | select(.value | type == "number") |
                       "\(.key) \(.value / $n * 1000 | round / 1000)"] | join(", "))] | join("; ")
        end' <<<"$1"
}

# Peak resident set of one command in MiB (GNU time), its output thrown away.
peak_mib() {
    local log=$dir/time.txt
    /usr/bin/time -v -o "$log" "$@" >/dev/null
    awk -F': *' '/Maximum resident set size/ { printf "%.0f", $2 / 1024 }' "$log"
}

input_for() { echo "$dir/$1_$2.node"; }

# One row: alternating rounds (dtlab first in odd rounds, CGAL first in even ones: the VM's load
# drifts, so both medians cover the same span of time), then the peak memory of each tool.
ratios=()
ratios2=()
ratios21=()
bench_row() {
    local kind=$1 size=$2 nrounds=$3 input dt_json="" dt2_json="" cg_json="" dt_ms=() dt2_ms=() cg_ms=() r
    input=$(input_for "$kind" "$size")
    [[ -s $input ]] || "$dtlab" gen "$kind" "$size" --seed "$seed" -o "$input" >/dev/null
    for (( r = 1; r <= nrounds; ++r )); do
        if (( have_cgal && r % 2 == 0 )); then
            cg_json=$(json_of "$("$cgal" "$input" --repeat 1 --json)")
            cg_ms+=("$(field "$cg_json" median_ms)")
        fi
        dt_json=$(json_of "$("$dtlab" bench --input "$input" --repeat 1 --threads 1 --json)")
        dt_ms+=("$(field "$dt_json" median_ms)")
        dt2_json=$(json_of "$("$dtlab" bench --input "$input" --repeat 1 --threads 2 --json)")
        dt2_ms+=("$(field "$dt2_json" median_ms)")
        if (( have_cgal && r % 2 == 1 )); then
            cg_json=$(json_of "$("$cgal" "$input" --repeat 1 --json)")
            cg_ms+=("$(field "$cg_json" median_ms)")
        fi
        if (( have_cgal )); then
            echo "  $kind $size round $r: dtlab ${dt_ms[-1]} ms (2 cores ${dt2_ms[-1]}), cgal ${cg_ms[-1]} ms" >&2
        else
            echo "  $kind $size round $r: dtlab ${dt_ms[-1]} ms" >&2
        fi
    done
    local dt dt2 cg="n/a" ratio="n/a" ratio2="n/a" dt_mem="-" cg_mem="-" count
    count=$(field "$dt_json" n)
    dt=$(median "${dt_ms[@]}")
    dt2=$(median "${dt2_ms[@]}")
    if (( have_cgal )); then
        cg=$(median "${cg_ms[@]}")
        ratio=$(calc "%.2f" "$dt / $cg")
        ratio2=$(calc "%.2f" "$dt2 / $cg")
        ratios+=("$size $ratio")
        ratios2+=("$size $ratio2")
        ratios21+=("$size $(calc "%.2f" "$dt2 / $dt") $kind")
        # Every run must have made a triangulation of the same size (CGAL counts finite faces).
        for json in "$dt_json" "$dt2_json"; do
            if [[ $(field "$json" triangles) != $(field "$cg_json" faces) ]]; then
                echo "bench: $kind: dtlab (threads $(field "$json" threads)) made $(field "$json" triangles) triangles, CGAL $(field "$cg_json" faces)" >&2
            fi
        done
    fi
    if [[ $memory != 0 ]]; then
        dt_mem=$(peak_mib "$dtlab" triangulate "$input" -o "$dir/out" -q)
        rm -f "$dir/out".{node,ele,neigh}
        (( have_cgal )) && cg_mem=$(peak_mib "$cgal" "$input" --repeat 1)
    fi
    local paths
    paths=$(jq -r 'if .one_core_because then "one core" else "two" end' <<<"$dt2_json")
    printf '| %s | %s | %s | %s | %s | %s | **%s** | %s | %s | %s | %s | %s | %s |\n' "$kind" "$count" "$dt" "$cg" "$ratio" "$dt2" "$ratio2" "$(calc "%.2f" "$dt2 / $dt") ($paths)" \
        "$(calc "%.0f" "$dt * 1e6 / $count")" "$(calc "%.2f" "$(field "$dt_json" walk_steps_per_point)")" \
        "$(predicates "$dt_json" "$count")" "$dt_mem" "$cg_mem"
}

model=$(lscpu 2>/dev/null | awk -F: '/^Model name/ { sub(/^[ \t]+/, "", $2); print $2; exit }')
build_type=$(awk -F= '/^CMAKE_BUILD_TYPE:/ { print $2 }' "$build/CMakeCache.txt" 2>/dev/null || true)
small=$(input_for uniform 1024)
[[ -s $small ]] || "$dtlab" gen uniform 1024 --seed "$seed" -o "$small" >/dev/null
cgal_version="no CGAL"
(( have_cgal )) && cgal_version="CGAL $(field "$(json_of "$("$cgal" "$small" --repeat 1 --json)")" cgal_version)"
echo "Machine: ${model:-unknown CPU}, $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg); build ${build_type:-?}; $(date -u +%Y-%m-%d)"
echo "Triangulation only (no I/O): dtlab bench (exact boundary, brio order, walk; one core with --threads 1, and two with"
echo "the default --threads 2) and $cgal_version"
echo "Delaunay_triangulation_2<Epick> range insert, one warm-up and one timed run per process;"
echo "medians of $rounds alternating rounds at n = $n ($rounds_large at larger n). Peak memory:"
echo "dtlab triangulate IN -o BASE (read, triangulate on two cores, write) and cgal_baseline IN --repeat 1."
echo
echo "| distribution | n | dtlab 1 core ms | CGAL ms | 1 core/CGAL | dtlab 2 cores ms | 2 cores/CGAL | 2 cores/1 core (path) | dtlab ns/point | walk steps/point | predicate calls/point past the filter, by stage | dtlab peak MiB | CGAL peak MiB |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|"
for kind in $kinds; do bench_row "$kind" "$n" "$rounds"; done
for size in $large; do bench_row uniform "$size" "$rounds_large"; done

if (( have_cgal )) && (( ${#ratios[@]} )); then
    echo
    printf '%s\n' "${ratios[@]}" | awk -v n="$n" '
        $1 == n { s += log($2); c += 1; if ($2 > worst) worst = $2 }
        END { if (c) printf "Geometric mean of dtlab (one core)/CGAL over the %d distributions at n = %d: %.2f (worst %.2f)\n", c, n, exp(s / c), worst }'
    printf '%s\n' "${ratios2[@]}" | awk -v n="$n" '
        $1 == n { s += log($2); c += 1; if ($2 > worst) worst = $2 }
        END { if (c) printf "The same with --threads 2 (two halves at once, joined; CGAL on one core): %.2f (worst %.2f)\n", exp(s / c), worst }'
    printf '%s\n' "${ratios21[@]}" | awk -v n="$n" '
        $1 == n { if ($2 > worst) { worst = $2; which = $3 } }
        END { if (which != "") printf "Worst of --threads 2 against --threads 1 at n = %d: %.2f (%s)\n", n, worst, which }'
fi
