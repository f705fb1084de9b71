#!/usr/bin/env bash
# Mutation testing of the geometry engine: plants each change of mutations.txt, one at a time, in
# a copy of the working tree under /tmp, builds the engine's test executable (dlab_core_tests:
# predicates, inserter and journal, regressions, orders) with DLAB_ASSERT checks on, and runs it.
# A mutant is killed when a test fails, the run crashes or aborts on a DLAB_ASSERT, the mutant
# does not compile, or the run times out; it survives when every test passes. Prints one line
# per mutant and the score; exit status 0 when every mutant is killed, 1 when some survive, 2
# when the list is wrong or the unmutated baseline does not build or pass.
#
#   tests/mutation/run.sh [MUTATIONS_FILE] [NAME_REGEX]
#
# Not run by ctest. The copy (/tmp/dlab-mutation-$USER) and its build are kept between runs, so
# only the first run builds everything; ccache helps when installed.
# DLAB_MUTATION_TIMEOUT: seconds a test run may take before its mutant counts as killed (300).
set -euo pipefail

root=$(git -C "$(dirname "$0")" rev-parse --show-toplevel)
list=${1:-$root/tests/mutation/mutations.txt}
only=${2:-.}
timeout_s=${DLAB_MUTATION_TIMEOUT:-300}
work=/tmp/dlab-mutation-${USER:-$(id -un)}
src=$work/src
build=$work/build
mkdir -p "$src" "$build"
echo "mutation testing in $src"

# The working tree as it is (tracked and untracked, not ignored), so uncommitted work is tested.
# Only files whose content differs are copied (with a fresh time): the rest is not rebuilt.
(cd "$root" && git ls-files -z --cached --others --exclude-standard) |
    while IFS= read -r -d '' f; do
        [[ -f $root/$f ]] || continue
        if ! cmp -s "$root/$f" "$src/$f"; then
            mkdir -p "$(dirname "$src/$f")"
            cp "$root/$f" "$src/$f"
        fi
    done
launcher=()
if command -v ccache >/dev/null; then
    launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
    export CCACHE_BASEDIR=$work CCACHE_NOHASHDIR=1
fi
nice -n 15 cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDLAB_CHECKS=ON \
    "${launcher[@]}" >"$work/configure.log" 2>&1 || {
    echo "configure failed: $work/configure.log"
    exit 2
}

build_tests() { nice -n 15 make -C "$build" -j2 dlab_core_tests >"$work/build.log" 2>&1; }
run_tests() {
    # The subshell's own stderr too: the shell's "Aborted" notice for a failed DLAB_ASSERT.
    (cd "$build/tests" && timeout "$timeout_s" ./dlab_core_tests --gtest_fail_fast \
        --gtest_brief=1 >"$work/test.log" 2>&1) 2>>"$work/test.log"
}

echo "baseline: building and running the unmutated tests"
start=$SECONDS
build_tests || {
    echo "baseline build failed: $work/build.log"
    exit 2
}
run_tests || {
    echo "baseline tests fail: $work/test.log"
    exit 2
}
echo "baseline passes ($((SECONDS - start))s)"

# mutations.txt: NAME <TAB> FILE <TAB> ORIGINAL <TAB> REPLACEMENT; # starts a comment.
# ORIGINAL must occur exactly once in FILE; \n in ORIGINAL or REPLACEMENT stands for a newline.
apply_mutation() {  # file original replacement
    python3 - "$1" "$2" "$3" <<'PY'
import sys
path = sys.argv[1]
original, replacement = (a.replace('\\n', '\n') for a in sys.argv[2:4])
text = open(path).read()
count = text.count(original)
if count != 1:
    sys.exit(f"{path}: the original text occurs {count} times, not once: {original!r}")
open(path, 'w').write(text.replace(original, replacement))
PY
}

killed=0
survived=0
survivors=()
while IFS=$'\t' read -r name file original replacement || [[ -n $name ]]; do
    [[ -z $name || $name == \#* ]] && continue
    [[ $name =~ $only ]] || continue
    cp -p "$src/$file" "$work/original.txt"
    apply_mutation "$src/$file" "$original" "$replacement" || {
        echo "list error: $name"
        exit 2
    }
    start=$SECONDS
    if ! build_tests; then
        verdict="killed (does not compile)"
    elif ! run_tests; then
        why=$(grep -m1 -oE '\[  FAILED  \] [A-Za-z0-9_./]+|\) failed: .*' "$work/test.log" |
            sed 's/^) failed: /DLAB_ASSERT: /' || true)
        verdict="killed (${why:-crash or timeout})"
    else
        verdict="SURVIVED"
    fi
    cp "$work/original.txt" "$src/$file"  # a fresh time: the next build recompiles it
    if [[ $verdict == SURVIVED ]]; then
        survived=$((survived + 1))
        survivors+=("$name")
    else
        killed=$((killed + 1))
    fi
    printf '%-36s %s (%ds)\n' "$name" "$verdict" $((SECONDS - start))
done <"$list"

echo "score: $killed of $((killed + survived)) mutants killed"
((survived == 0)) || {
    echo "survivors: ${survivors[*]}"
    exit 1
}
