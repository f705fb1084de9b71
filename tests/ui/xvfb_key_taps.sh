#!/usr/bin/env bash
# Key taps in a real window: delaunay-lab (the built-in demo, 108 operations) on a virtual X
# server; xdotool sends 40 taps of Right, each press and release back to back, 12 ms apart, as a
# presentation clicker does. Every tap must step once: the app's own state (--test-info) says
# position 40, however many of the taps came between two frames.
#   usage: xvfb_key_taps.sh DELAUNAY_LAB OUT_DIR
set -euo pipefail

if [[ "${1:-}" != --inside ]]; then
    exe=$(realpath "$1") out=$(realpath -m "$2")/xvfb_key_taps
    for tool in xvfb-run xdotool python3; do
        if ! command -v $tool >/dev/null; then
            echo "$tool not installed (apt-get install xvfb xauth xdotool python3): skipped"
            exit 77
        fi
    done
    rm -rf "$out"
    mkdir -p "$out/config/delaunay-lab"
    echo '{"window": {"width": 1280, "height": 720}}' >"$out/config/delaunay-lab/settings.json"
    exec timeout 60 xvfb-run -a -s "-screen 0 1280x720x24" bash "$0" --inside "$exe" "$out"
fi

exe=$2 out=$3 taps=40
cd "$out"
info=$out/info.json
XDG_CONFIG_HOME=$out/config "$exe" --no-autosave --test-info "$info" >app.log 2>&1 &
app=$!
fail() {
    echo "FAIL: $*"
    [[ -f "$info" ]] && { echo "state: "; cat "$info"; }
    cat app.log
    kill $app 2>/dev/null || true
    exit 1
}
for _ in $(seq 100); do
    [[ -f "$info" ]] && break
    sleep 0.1
done
timeout 20 xdotool search --sync --onlyvisible --name "Delaunay Lab" >/dev/null || fail "no window"
xdotool mousemove --sync 300 300  # no window manager: the keyboard goes where the pointer is
sleep 0.5
xdotool key --delay 12 $(for _ in $(seq $taps); do printf "Right "; done)
# Waits (10 s at most) for the position the taps make.
for _ in $(seq 100); do
    grep -q "\"position\": $taps," "$info" 2>/dev/null && break
    sleep 0.1
done
grep -q "\"position\": $taps," "$info" || fail "$taps taps of Right did not make $taps steps"
xdotool key ctrl+q
wait $app || fail "delaunay-lab exited with status $?"
echo "ok: $taps taps, $taps steps"
