#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (CMake preset `fuzz`, build-fuzz/) and fuzzes each.
#
#   tests/fuzz/run_fuzz.sh            every target, FUZZ_SECONDS each, FUZZ_JOBS at a time
#   make fuzz FUZZ_SECONDS=600        the same through make (after the Debian packages)
#
# Environment:
#   FUZZ_SECONDS    seconds per target (default 15; the engine target gets twice that)
#   FUZZ_JOBS       targets fuzzed at the same time (default: the number of cores)
#   FUZZ_TARGETS    which targets (default: every tests/fuzz/fuzz_*.cpp)
#   FUZZ_CXX        the clang++ to use (default clang++-14, else clang++)
#   FUZZ_REQUIRED   1: no usable clang is an error; 0: say fuzzing was skipped and why, exit 0.
#                   Default 1 as root (make installs clang-14 then) and 0 otherwise.
#
# New inputs that raise coverage go to build-fuzz/fuzz-corpus/TARGET (the committed seeds in
# tests/fuzz/corpus/TARGET are only read). A crash, a failed property, a leak, a timeout or an
# allocation over -malloc_limit_mb stops with the input saved under build-fuzz/fuzz-artifacts/
# and a non-zero exit. Keep a crash as a regression: copy it to tests/fuzz/corpus/TARGET/
# (CTest replays it) and add a unit test named after the bug.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."

seconds=${FUZZ_SECONDS:-15}
jobs=${FUZZ_JOBS:-$(nproc 2>/dev/null || echo 2)}
build_dir=build-fuzz
# The engine target is ~100 times slower per input than the readers (every input is triangulated
# twice, undone, replayed and checked in GMP rationals): it gets twice the time, and starts first.
seconds_for() {
    if [[ $1 == engine ]]; then echo $((seconds * 2)); else echo "$seconds"; fi
}

if [[ -z ${FUZZ_REQUIRED:-} ]]; then
    FUZZ_REQUIRED=$([[ $(id -u) -eq 0 ]] && echo 1 || echo 0)
fi
if [[ -n ${FUZZ_TARGETS:-} ]]; then
    read -r -a targets <<<"$FUZZ_TARGETS"
else
    targets=()
    [[ -f tests/fuzz/fuzz_engine.cpp ]] && targets+=(engine)
    for f in tests/fuzz/fuzz_*.cpp; do
        name=${f#tests/fuzz/fuzz_}
        [[ $name == common.cpp || $name == engine.cpp ]] || targets+=("${name%.cpp}")
    done
fi

skip() {
    echo "fuzz: SKIPPED: $1" >&2
    echo "fuzz: the corpora were still replayed as regression tests (CTest FuzzReplay.*)" >&2
    echo "fuzz: to fuzz, install clang with libFuzzer (as root):" \
        "apt-get install -y --no-install-recommends clang-14 libclang-rt-14-dev" >&2
    if [[ $FUZZ_REQUIRED == 1 ]]; then
        echo "fuzz: FUZZ_REQUIRED=1: failing" >&2
        exit 1
    fi
    exit 0
}

# A clang that can link a libFuzzer program with ASan and UBSan (clang-14 alone is not enough:
# the fuzzer runtime is in libclang-rt-14-dev).
cxx=${FUZZ_CXX:-}
if [[ -z $cxx ]]; then
    for candidate in clang++-14 clang++; do
        if command -v "$candidate" >/dev/null 2>&1; then
            cxx=$candidate
            break
        fi
    done
fi
[[ -n $cxx ]] || skip "no clang++ found (libFuzzer needs clang)"
command -v "$cxx" >/dev/null 2>&1 || skip "FUZZ_CXX=$cxx not found"
probe_dir=$(mktemp -d)
trap 'rm -rf "$probe_dir"' EXIT
printf 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }\n' \
    >"$probe_dir/probe.cpp"
if ! "$cxx" -fsanitize=fuzzer,address,undefined "$probe_dir/probe.cpp" -o "$probe_dir/probe" \
    >"$probe_dir/log" 2>&1; then
    skip "$cxx cannot link -fsanitize=fuzzer,address,undefined: $(grep -m1 -i error "$probe_dir/log" || head -n1 "$probe_dir/log")"
fi
cc=${cxx/clang++/clang}

echo "fuzz: $cxx, ${#targets[@]} targets (${targets[*]}), ${seconds} s each (engine $(seconds_for engine) s), $jobs at a time"
cmake --preset fuzz -B "$build_dir" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_C_COMPILER="$cc" >"$probe_dir/configure.log" 2>&1 ||
    { cat "$probe_dir/configure.log"; exit 1; }
if ! cmake --build "$build_dir" --target fuzz_targets -j "$jobs"; then
    echo "fuzz: FAILED: the clang build of the fuzz targets failed (see above); every file in" \
        "core/ must also compile with $cxx (C++20 as clang 14 implements it)" >&2
    exit 1
fi

# Per-target input size limits: text formats need room for several lines, the engine's decoder
# stops at 160 points anyway.
max_len() {
    case $1 in
        engine) echo 2048 ;;
        trace) echo 8192 ;;
        *) echo 4096 ;;
    esac
}

export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
logs=$build_dir/fuzz-logs
mkdir -p "$logs"

fuzz_one() {
    local t=$1
    local exe=$build_dir/tests/fuzz/fuzz_$t
    local work=$build_dir/fuzz-corpus/$t
    local artifacts=$build_dir/fuzz-artifacts/$t/
    local dict=() status
    [[ -f tests/fuzz/dict/$t.dict ]] && dict=(-dict="tests/fuzz/dict/$t.dict")
    mkdir -p "$work" "$artifacts"
    rm -f "$logs/$t.status"
    "$exe" -max_total_time="$(seconds_for "$t")" -timeout=25 -rss_limit_mb=2048 -malloc_limit_mb=256 \
        -max_len="$(max_len "$t")" -print_final_stats=1 -artifact_prefix="$artifacts" \
        "${dict[@]}" "$work" "tests/fuzz/corpus/$t" >"$logs/$t.log" 2>&1 && status=0 || status=$?
    echo "$status" >"$logs/$t.status"
}

declare -A pid_of
for t in "${targets[@]}"; do
    [[ -f tests/fuzz/fuzz_$t.cpp ]] || { echo "fuzz: no target '$t'" >&2; exit 2; }
    while (($(jobs -rp | wc -l) >= jobs)); do wait -n || true; done
    fuzz_one "$t" &
    pid_of[$t]=$!
done

failed=0
total_runs=0
for t in "${targets[@]}"; do
    wait "${pid_of[$t]}" || true
    status=$(cat "$logs/$t.status" 2>/dev/null || echo 1)
    log=$logs/$t.log
    runs=$(grep -o 'stat::number_of_executed_units: [0-9]*' "$log" | awk '{print $2}' | tail -n1)
    runs=${runs:-0}
    total_runs=$((total_runs + runs))
    corpus=$(find "$build_dir/fuzz-corpus/$t" "tests/fuzz/corpus/$t" -type f | wc -l)
    if ((status == 0)); then
        printf 'fuzz: %-10s ok     %9d runs, %d corpus files\n' "$t" "$runs" "$corpus"
    else
        failed=1
        artifact=$(grep -o "Test unit written to .*" "$log" | tail -n1 | sed 's/Test unit written to //')
        printf 'fuzz: %-10s FAILED (exit %d) after %d runs\n' "$t" "$status" "$runs" >&2
        grep -m3 -E 'fuzz property failed|ERROR: |runtime error|out-of-memory|timeout' "$log" | sed 's/^/fuzz:   /' >&2 || true
        echo "fuzz:   log: $log" >&2
        if [[ -n $artifact ]]; then
            echo "fuzz:   input: $artifact" >&2
            echo "fuzz:   reproduce: $build_dir/tests/fuzz/fuzz_$t $artifact" >&2
        fi
    fi
done
echo "fuzz: $total_runs runs in total"
exit $failed
