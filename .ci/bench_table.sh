#!/usr/bin/env bash
# The scaling table: for n = 2^10 ... 2^20 uniform points in the paper's 1600x1600 box,
# dtlab bench's ns/point, flips/point and walk steps/point on one core (--threads 1) with the
# default options (exact boundary, brio order, walk locator) and with the paper's baseline
# (--locate naive --order input), as a Markdown table; then the CGAL comparison
# (.ci/bench_compare.sh), which has the two-core column.
#
# The naive walk costs O(sqrt n) steps per point: each size's time is estimated from the sizes
# before it, and a size whose estimate is over BENCH_TABLE_LIMIT_S is not run (the table says so).
#
# usage: bash .ci/bench_table.sh [BUILD_DIR]      (default: build)
# Environment: BENCH_TABLE_FROM, BENCH_TABLE_TO (exponents, default 10 and 20),
#   BENCH_TABLE_LIMIT_S (default 120), BENCH_SEED (default 1),
#   BENCH_COMPARE=0 (skip the CGAL comparison), BENCH_ROUNDS etc. (passed on to bench_compare.sh).
set -euo pipefail

build=${1:-build}
from=${BENCH_TABLE_FROM:-10}
to=${BENCH_TABLE_TO:-20}
limit_s=${BENCH_TABLE_LIMIT_S:-120}
seed=${BENCH_SEED:-1}
dtlab=$build/app/dtlab
dir=$build/bench
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)

for tool in jq "$dtlab"; do
    command -v "$tool" >/dev/null || { echo "bench_table: $tool not found (run make deps / make build)" >&2; exit 1; }
done
mkdir -p "$dir"

# The input of size n (the files bench_compare.sh makes and uses).
input_for() { echo "$dir/uniform_$1.node"; }

# Timed runs: enough for a stable median at small sizes, few at large ones.
repeats_for() {
    if (( $1 <= 16384 )); then echo 21; elif (( $1 <= 131072 )); then echo 11; else echo 7; fi
}

# One row's cells from a dtlab bench JSON object: ns/point of the median and of the fastest run
# (this VM's load makes the minimum the steadier figure), flips/point, walk steps/point.
cells() {
    jq -r '[.ns_per_point, .min_ms * 1e6 / .n, .flips_per_point, .walk_steps_per_point] | @tsv' <<<"$1" |
        awk -F'\t' '{ printf "%.1f | %.1f | %.3f | %.2f", $1, $2, $3, $4 }'
}

model=$(lscpu 2>/dev/null | awk -F: '/^Model name/ { sub(/^[ \t]+/, "", $2); print $2; exit }')
build_type=$(awk -F= '/^CMAKE_BUILD_TYPE:/ { print $2 }' "$build/CMakeCache.txt" 2>/dev/null || true)
echo "Machine: ${model:-unknown CPU}, $(nproc) cores; build ${build_type:-?}; $(date -u +%Y-%m-%d)"
echo "dtlab bench: triangulation only (no I/O), median and fastest of the timed runs after a warm-up."
echo "One core (--threads 1). default = exact boundary, brio order, walk locator; paper = --locate naive --order input."
echo
echo "| n | default ns/point | (min) | flips/point | walk steps/point | paper ns/point | (min) | flips/point | walk steps/point |"
echo "|---:|---:|---:|---:|---:|---:|---:|---:|---:|"

naive_prev_ms=""   # the paper baseline's median at the previous size
naive_growth=4     # time ratio per doubling of n, measured as soon as two sizes exist
for (( e = from; e <= to; ++e )); do
    n=$(( 1 << e ))
    input=$(input_for "$n")
    [[ -s $input ]] || "$dtlab" gen uniform "$n" --seed "$seed" -o "$input" >/dev/null
    repeat=$(repeats_for "$n")
    def=$("$dtlab" bench --input "$input" --repeat "$repeat" --threads 1 --json)

    # The paper baseline: estimate before running; slow sizes get one timed run, no warm-up.
    paper="skipped | | | "
    est_ms=""
    if [[ -n $naive_prev_ms ]]; then
        est_ms=$(awk -v m="$naive_prev_ms" -v g="$naive_growth" 'BEGIN { printf "%.0f", m * g }')
    fi
    warm=1
    prep=$repeat
    if [[ -n $est_ms ]] && (( est_ms > 2000 )); then
        warm=0
        prep=$(( 20000 / est_ms )); (( prep >= 1 )) || prep=1; (( prep <= 5 )) || prep=5
    fi
    if [[ -n $est_ms ]] && (( est_ms * (warm + prep) > limit_s * 1000 )); then
        paper="not run: about $(( est_ms * (warm + prep) / 1000 )) s estimated (limit ${limit_s} s) | | | "
        naive_prev_ms=$est_ms   # later sizes only grow
    else
        pj=$("$dtlab" bench --input "$input" --repeat "$prep" --warmup "$warm" --locate naive --order input --json)
        paper=$(cells "$pj")
        ms=$(jq -r '.median_ms' <<<"$pj")
        if [[ -n $naive_prev_ms ]]; then
            naive_growth=$(awk -v a="$ms" -v b="$naive_prev_ms" 'BEGIN { g = b > 0 ? a / b : 4; if (g < 2) g = 2; if (g > 8) g = 8; printf "%.3f", g }')
        fi
        naive_prev_ms=$ms
    fi
    echo "| 2^$e = $n | $(cells "$def") | $paper |"
done

if [[ ${BENCH_COMPARE:-1} != 0 ]]; then
    echo
    echo "## CGAL comparison (.ci/bench_compare.sh)"
    BENCH_SEED=$seed bash "$here/bench_compare.sh" "$build"
fi
