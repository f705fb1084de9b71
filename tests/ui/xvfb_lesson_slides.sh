#!/usr/bin/env bash
# The lesson player in a real window: delaunay-lab opens a lesson in presentation mode at
# 1280x720 on a virtual X server; xdotool presses Page Down to the first stop with a question,
# clicks the answer field, types the answer `dtlab lesson show` gives, presses Enter, takes
# screenshots with F12, moves on and back with Page Down / Page Up and quits with Ctrl+Q.
# Checked: the app's own state (--test-info) follows every key, the answer is marked right, the
# question area of the screenshot shows the green feedback only after the answer, and the
# settings written at exit keep the stop and the right answer.
#   usage: xvfb_lesson_slides.sh DELAUNAY_LAB DTLAB LESSON.toml OUT_DIR
set -euo pipefail

if [[ "${1:-}" != --inside ]]; then
    exe=$(realpath "$1") dtlab=$2 lesson=$(realpath "$3") out=$(realpath -m "$4")/xvfb_lesson
    for tool in xvfb-run xdotool python3; do
        if ! command -v $tool >/dev/null; then
            echo "$tool not installed (apt-get install xvfb xauth xdotool python3): skipped"
            exit 77
        fi
    done
    rm -rf "$out"
    mkdir -p "$out/config/delaunay-lab"
    echo '{"presentation": true, "window": {"width": 1280, "height": 720}}' \
        >"$out/config/delaunay-lab/settings.json"
    # The first stop with a question, and its answer as `lesson show` writes it ("A: 3-4   (...)").
    read -r stop answer < <("$dtlab" lesson show "$lesson" | awk '
        /^## stop / { k = $3 }
        /^A: / && k > 1 { sub(/^A: /, ""); sub(/   \(.*$/, ""); print k, $0; exit }')
    [[ -n "$stop" && -n "$answer" ]] || { echo "no question found in $lesson"; exit 1; }
    echo "stop $stop: answering \"$answer\""
    exec timeout 90 xvfb-run -a -s "-screen 0 1280x720x24" \
        bash "$0" --inside "$exe" "$lesson" "$out" "$stop" "$answer"
fi

exe=$2 lesson=$3 out=$4 stop=$5 answer=$6
cd "$out"
info=$out/info.json
XDG_CONFIG_HOME=$out/config "$exe" --no-autosave --test-info "$info" "$lesson" >app.log 2>&1 &
app=$!
fail() {
    echo "FAIL: $*"
    [[ -f "$info" ]] && { echo "state: "; cat "$info"; }
    cat app.log
    kill $app 2>/dev/null || true
    exit 1
}
# Waits (10 s at most) until the app's state matches the pattern.
await() {
    for _ in $(seq 100); do
        grep -q -- "$1" "$info" 2>/dev/null && return 0
        sleep 0.1
    done
    fail "waited for $1"
}
# A key held for a few frames: the GUI reads key states once a frame and would miss a press and
# release that come between two frames.
press() {
    xdotool keydown "$1"
    sleep 0.15
    xdotool keyup "$1"
    sleep 0.05
}
rect() { sed -n "s/.*\"$1\": \[\([^]]*\)\].*/\1/p" "$info" | tr -d ' '; }
# F12: the app saves a screenshot in its folder (delaunay-lab-TIME.png); it becomes $1.
shot() {
    shopt -s nullglob
    local before=(delaunay-lab-*.png) now
    press F12
    for _ in $(seq 100); do
        now=(delaunay-lab-*.png)
        ((${#now[@]} > ${#before[@]})) && break
        sleep 0.1
    done
    ((${#now[@]} > ${#before[@]})) || fail "F12 wrote no screenshot"
    sleep 0.3  # written whole
    mv "$(ls -t delaunay-lab-*.png | head -1)" "$1"
}
# Green feedback pixels ((26, 140, 51) as drawn) inside the rectangle x0,y0,x1,y1 of a PNG.
green_pixels() {
    python3 - "$1" "$2" <<'EOF'
import struct, sys, zlib
data = open(sys.argv[1], "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
pos, idat, w, h, ch = 8, b"", 0, 0, 0
while pos < len(data):
    n, kind = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + n]
    if kind == b"IHDR":
        w, h, depth, colour = struct.unpack(">IIBB", body[:10])
        assert depth == 8 and colour in (2, 6), "8-bit RGB or RGBA only"
        ch = 3 if colour == 2 else 4
    elif kind == b"IDAT":
        idat += body
    pos += 12 + n
raw, stride, rows, prev = zlib.decompress(idat), w * ch, [], bytearray(w * ch)
for y in range(h):
    f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    for i in range(stride):
        a = line[i - ch] if i >= ch else 0
        b, c = prev[i], prev[i - ch] if i >= ch else 0
        if f == 1: line[i] = (line[i] + a) & 255
        elif f == 2: line[i] = (line[i] + b) & 255
        elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
        elif f == 4:
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    rows.append(line)
    prev = line
x0, y0, x1, y1 = (int(float(v)) for v in sys.argv[2].split(","))
def green(p):
    return p[1] > p[0] + 60 and p[1] > p[2] + 40
print(w, h, sum(1 for y in range(max(y0, 0), min(y1, h)) for x in range(max(x0, 0), min(x1, w))
                if green(rows[y][x * ch:x * ch + 3])))
EOF
}

timeout 20 xdotool search --sync --onlyvisible --name "Delaunay Lab" >/dev/null || fail "no window"
await '"slide": true'
await '"stop": 1,'
xdotool mousemove --sync 300 300  # no window manager: the keyboard goes where the pointer is
for ((k = 1; k < stop; ++k)); do
    press Next
    await "\"stop\": $((k + 1)),"
done
await '"lesson-answer"'
shot "$out/before.png"
question=$(rect slide-question)
read -r w h before < <(green_pixels "$out/before.png" "$question")
[[ "$w $h" == "1280 720" ]] || fail "the screenshot is ${w}x$h, not 1280x720"
# The answer field: click it, type, Enter.
IFS=, read -r x0 y0 x1 y1 <<<"$(rect lesson-answer)"
xdotool mousemove --sync $(((${x0%.*} + ${x1%.*}) / 2)) $(((${y0%.*} + ${y1%.*}) / 2)) click 1
sleep 0.3
xdotool type --delay 30 "$answer"
press Return
await '"feedback": "right"'
xdotool mousemove --sync 300 300
shot "$out/answered.png"
read -r _ _ after < <(green_pixels "$out/answered.png" "$(rect slide-question)")
echo "green pixels in the question area ($question): $before before the answer, $after after"
((before == 0)) || fail "green in the question area before any answer"
((after > 100)) || fail "no green feedback in the question area after the right answer"
# On and back with the presentation clicker's keys.
press Next
await "\"stop\": $((stop + 1)),"
shot "$out/next.png"
press Prior
await "\"stop\": $stop,"
press ctrl+q
wait $app || fail "delaunay-lab exited with status $?"
settings=$out/config/delaunay-lab/settings.json
python3 - "$settings" "$lesson" "$stop" <<'EOF' || fail "the settings do not keep the progress"
import json, sys
lessons = json.load(open(sys.argv[1]))["lessons"]
p = lessons[sys.argv[2]]
k = int(sys.argv[3]) - 1
print("progress kept at exit:", p)
assert p["stop"] == k and p["furthest"] == k + 1 and p["answers"][k] == 2
EOF
echo "ok: screenshots in $out"
