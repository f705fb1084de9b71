#!/usr/bin/env bash
# The code's format, checked: every C++ source as clang-format (Debian's, .clang-format) writes
# it, and no line over 100 columns (clang-format leaves comments alone: ReflowComments is off so
# that ASCII diagrams survive). `make format` applies clang-format; long comments are by hand.
# Usage: .ci/format_check.sh [SOURCE_DIR]
set -euo pipefail
cd "${1:-$(dirname "${BASH_SOURCE[0]}")/..}"

if ! command -v clang-format >/dev/null 2>&1; then
    echo "format: clang-format is not installed (apt-get install clang-format)" >&2
    exit 1
fi
mapfile -t sources < <(git ls-files -co --exclude-standard '*.cpp' '*.h' | grep -v '/corpus/' |
    while read -r f; do [[ -f $f ]] && echo "$f"; done)
status=0
if ! clang-format --dry-run --Werror "${sources[@]}" 2>/tmp/format_check.$$; then
    grep -oE '^[^ :]+:[0-9]+' /tmp/format_check.$$ | sort -t: -k1,1 -k2,2n -u |
        sed 's/^/format: not clang-formatted: /' | head -50
    echo "format: run 'make format' to fix" >&2
    status=1
fi
rm -f /tmp/format_check.$$
# Columns are characters (UTF-8), not bytes: perl is in every Debian (perl-base).
long=$(perl -CSD -ne 'chomp; printf "%s:%d: %d columns\n", $ARGV, $., length if length > 100;
    close ARGV if eof' "${sources[@]}")
if [[ -n $long ]]; then
    echo "$long" | sed 's/^/format: over 100 columns: /' | head -50
    status=1
fi
((status == 0)) && echo "format: ${#sources[@]} files clang-formatted, none over 100 columns"
exit $status
