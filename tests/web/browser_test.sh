#!/usr/bin/env bash
# Web.Browser: builds the browser build (as make web: SRC/build-web, incremental), writes the
# native build's trace of the demo, and runs browser_test.mjs in headless Chromium.
#   usage: browser_test.sh SRC WEB_DIR OUT_DIR DTLAB MODULES_DIR
set -euo pipefail
src=$1 web=$2 out=$3 dtlab=$4 modules=$5
export NODE_PATH=/usr/share/nodejs  # Debian's emscripten needs Debian's acorn
mkdir -p "$out"
launcher=()
if command -v ccache >/dev/null; then
    launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
start=$(date +%s)
emcmake cmake -S "$src" -B "$web" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" >"$out/configure.log" 2>&1 ||
    { cat "$out/configure.log"; exit 1; }
nice -n 10 cmake --build "$web" -j 2 >"$out/build.log" 2>&1 || { tail -n 40 "$out/build.log"; exit 1; }
echo "web build up to date in $(($(date +%s) - start)) s"
gz=$(cat "$web/index.html" "$web/platform_web.js" "$web/delaunay-lab.js" "$web/delaunay-lab.wasm" \
    "$web/delaunay-lab.data" | gzip -9 | wc -c)
echo "download: $((gz / 1024)) KiB gzipped (index.html, platform_web.js, delaunay-lab.js/.wasm/.data)"

if [[ ! -f $modules/node_modules/puppeteer-core/package.json ]]; then
    echo "puppeteer-core is not in $modules: installing it (npm; make test does this too)"
    mkdir -p "$modules"
    npm install --prefix "$modules" --no-audit --no-fund --silent puppeteer-core@24 || {
        echo "Web.Browser: cannot install puppeteer-core with npm (offline?)" >&2
        exit 1
    }
fi
"$dtlab" demo --order input --quiet -o "$out/native-demo" >/dev/null
node "$src/tests/web/browser_test.mjs" "$web" "$out" "$out/native-demo/demo.trace.jsonl" \
    "$modules/node_modules"
