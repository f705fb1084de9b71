#!/usr/bin/env bash
# Real-window smoke test: delaunay-lab opens a GLFW window on a virtual X server, draws a few
# frames of the demo, saves a screenshot of itself and quits; the PNG must be a real picture.
set -euo pipefail
exe=$1
out=$2/xvfb_smoke.png
if ! command -v xvfb-run >/dev/null; then
    echo "xvfb-run not installed (apt-get install xvfb xauth): skipped"
    exit 77
fi
rm -f "$out"
xvfb-run -a -s "-screen 0 1600x1000x24" "$exe" --no-settings --frames 8 --screenshot "$out"
test -s "$out" || { echo "no screenshot written"; exit 1; }
# A PNG signature and a size worth a drawn window (a blank PNG of this size is a few KB).
head -c 8 "$out" | od -An -tx1 | grep -q "89 50 4e 47 0d 0a 1a 0a" || { echo "not a PNG"; exit 1; }
size=$(stat -c %s "$out")
echo "screenshot $out: $size bytes"
test "$size" -gt 40000 || { echo "screenshot too small to hold the UI"; exit 1; }
