# Delaunay Lab — the single entry point. `make run` and `make test` are all a user needs; both
# install missing Debian 12 packages first (as root), then configure, build and run with CMake.
#
#   make run     deps, configure build/ (RelWithDebInfo), build, run the main job
#   make test    deps, configure, build everything, ctest (non-zero exit when a test fails),
#                then a short fuzz run of every fuzz target (TEST_FUZZ_SECONDS each; skipped with
#                a message when clang/libFuzzer is missing and cannot be installed)
#   make build   deps, configure, build
#   make deps    install missing Debian packages (root), or print the apt-get command and fail
#   make asan    deps, configure build-asan/ (Debug, ASan + UBSan), build, ctest
#   make fuzz    deps, build the libFuzzer targets (clang, build-fuzz/), fuzz each FUZZ_SECONDS
#   make bench   build, then dtlab vs CGAL on 2^20 points of each distribution and larger uniform
#                sets, with peak memory (.ci/bench_compare.sh; BENCH_* variables; ~20 min)
#   make format  clang-format every C++ source (make test checks the format: Style.Format)
#   make web     the browser build: build-web/ (index.html, .js, .wasm, .data with the lessons,
#                their point sets and the fonts), with Debian's emscripten and the sources of
#                Debian's imgui and giflib (.ci/debian_source.sh); serve the folder over HTTP
#   make serve-web   build-web/ on http://127.0.0.1:$(WEB_PORT)/ (python3's http.server)
#   make clean   remove build/, build-asan/, build-release/, build-fuzz/, build-web/
#
# Variables: JOBS (build parallelism, default nproc), WEB_PORT (default 8000), WEB_TEST=0 (make test
# neither installs nor runs the browser test), CTEST_JOBS (default 2), DLAB_SKIP_DEPS=1
# (skip the Debian package check), CMAKE_ARGS (extra arguments for the configure step),
# FUZZ_SECONDS (per target for `make fuzz`, default 120), TEST_FUZZ_SECONDS (per target in
# `make test`, default 20; 0 skips fuzzing), FUZZ_JOBS (targets fuzzed at once, default nproc).

SHELL := /bin/bash
MAKEFLAGS += --no-print-directory
.SHELLFLAGS := -euo pipefail -c
.DEFAULT_GOAL := build

JOBS ?= $(shell nproc 2>/dev/null || echo 2)
CTEST_JOBS ?= 2
CMAKE_ARGS ?=

BUILD_DIR := build
ASAN_DIR := build-asan
FUZZ_DIR := build-fuzz
FUZZ_SECONDS ?= 120
TEST_FUZZ_SECONDS ?= 20

# Debian 12 (bookworm) package names. libcgal-dev only serves the benchmark baseline; time and jq
# serve `make bench`; xvfb and xauth (xvfb-run needs it) serve the real-window tests, xdotool
# (keys and clicks) and python3 (reads the screenshots) the lesson-slides one;
# fonts-dejavu-core gives the GUI a readable font (it falls back to ImGui's own without it).
# Headless GL: libegl-dev and libopengl-dev (glvnd) with libegl-mesa0 (Mesa's EGL: llvmpipe, and
# the GPUs Mesa drives) for dtlab-gl; libosmesa6-dev for dtlab-gl-osmesa (optional in CMake).
DEB_PACKAGES := \
	build-essential cmake pkg-config \
	libimgui-dev libglfw3-dev libgl-dev libglm-dev libosmesa6-dev libstb-dev libgif-dev \
	libegl-dev libopengl-dev libegl-mesa0 \
	libcli11-dev libtomlplusplus-dev nlohmann-json3-dev libgmp-dev libfast-float-dev libfmt-dev \
	libgtest-dev libbenchmark-dev clang-format \
	xvfb xauth xdotool python3 fonts-dejavu-core \
	libcgal-dev time jq

# Fuzzing (libFuzzer needs clang; its runtime is in libclang-rt-14-dev, which clang-14 only
# recommends). Installed by `make deps` as root like the rest; elsewhere they are optional:
# without them `make test` says that fuzzing was skipped and why, and passes.
FUZZ_DEB_PACKAGES := clang-14 libclang-rt-14-dev

# The browser build (make web) and its test in Chromium (Web.Browser, in make test): emscripten,
# dpkg-dev (dpkg-source unpacks Debian's imgui and giflib sources), chromium, npm (puppeteer-core
# goes into $(BUILD_DIR)/web-test, never the system). Installed by `make deps` as root; elsewhere
# optional: without them the browser test is not registered and make test says so.
WEB_DEB_PACKAGES := emscripten dpkg-dev python3
# npm is needed as a command: a Node.js from elsewhere (NodeSource's nodejs, which conflicts with
# Debian's npm package) brings its own, and then Debian's npm is neither needed nor installable.
WEB_TEST_DEB_PACKAGES := chromium $(if $(shell command -v npm 2>/dev/null),,npm)
WEB_DIR := build-web
WEB_PORT ?= 8000
WEB_TEST ?= 1
# Debian's emscripten needs Debian's node modules (acorn) on Node's path.
WEB_ENV := NODE_PATH=/usr/share/nodejs

.PHONY: all run test build configure deps asan fuzz bench format clean help web serve-web web-deps \
	web-test-deps

all: build

help:
	@sed -n '1,/^$$/p' $(firstword $(MAKEFILE_LIST))

deps:
	@bash .ci/deps.sh $(DEB_PACKAGES)
	@if [[ $$(id -u) -eq 0 ]]; then \
		bash .ci/deps.sh $(FUZZ_DEB_PACKAGES); \
	elif ! bash .ci/deps.sh $(FUZZ_DEB_PACKAGES) >/dev/null 2>&1; then \
		echo "deps: optional fuzzing packages missing ($(FUZZ_DEB_PACKAGES)): fuzzing will be skipped"; \
	fi

# The browser test's tools, before the configure step (which registers Web.Browser when they are
# there): as root they are installed; otherwise the test is not registered when they are absent.
web-test-deps:
	@if [[ "$(WEB_TEST)" == 0 ]]; then echo "deps: WEB_TEST=0: the browser test is off"; exit 0; fi; \
	if [[ $$(id -u) -eq 0 ]]; then \
		bash .ci/deps.sh $(WEB_DEB_PACKAGES) $(WEB_TEST_DEB_PACKAGES) || \
		echo "deps: apt-get could not install the browser-test packages ($(WEB_DEB_PACKAGES) $(WEB_TEST_DEB_PACKAGES)); the test runs only if emcmake, chromium and node are found"; \
	elif ! bash .ci/deps.sh $(WEB_DEB_PACKAGES) $(WEB_TEST_DEB_PACKAGES) >/dev/null 2>&1; then \
		echo "deps: optional browser-test packages missing ($(WEB_DEB_PACKAGES) $(WEB_TEST_DEB_PACKAGES)): Web.Browser will not run"; \
	fi
	@if [[ "$(WEB_TEST)" != 0 ]] && command -v npm >/dev/null 2>&1 && [[ ! -f $(BUILD_DIR)/web-test/node_modules/puppeteer-core/package.json ]]; then \
		mkdir -p $(BUILD_DIR)/web-test && \
		npm install --prefix $(BUILD_DIR)/web-test --no-audit --no-fund --silent puppeteer-core@24 || \
		echo "deps: npm could not install puppeteer-core: Web.Browser will fail"; \
	fi

web-deps:
	@bash .ci/deps.sh $(DEB_PACKAGES) $(WEB_DEB_PACKAGES)

# The browser build. Release (-O3), no tests; ccache when installed. em++ runs nice'd.
web: web-deps
	$(WEB_ENV) emcmake cmake -S . -B $(WEB_DIR) -DCMAKE_BUILD_TYPE=Release \
		$$(command -v ccache >/dev/null && echo -DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
	$(WEB_ENV) nice -n 10 cmake --build $(WEB_DIR) -j $(JOBS)
	@echo "web: open $(WEB_DIR)/index.html through a web server, e.g. make serve-web"

serve-web: web
	@echo "serve-web: http://127.0.0.1:$(WEB_PORT)/ (Ctrl+C stops)"
	python3 -m http.server $(WEB_PORT) --bind 127.0.0.1 --directory $(WEB_DIR)

# Configure every time: cheap once the cache exists, and it never builds from a stale or
# half-written configuration.
configure: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=RelWithDebInfo $(CMAKE_ARGS)

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

# The main job: the GUI on the built-in demo. With no display, delaunay-lab says so and
# renders the demo headlessly (dtlab render) to $(BUILD_DIR)/demo.png instead.
run: build
	$(BUILD_DIR)/app/delaunay-lab --headless-png $(BUILD_DIR)/demo.png

test: web-test-deps build
	ctest --test-dir $(BUILD_DIR) --output-on-failure --no-tests=error -j $(CTEST_JOBS) \
		$(if $(filter 0,$(WEB_TEST)),-E '^Web\.Browser$$')
	@if [[ "$(TEST_FUZZ_SECONDS)" == 0 ]]; then echo "fuzz: SKIPPED: TEST_FUZZ_SECONDS=0"; \
	else FUZZ_SECONDS=$(TEST_FUZZ_SECONDS) bash tests/fuzz/run_fuzz.sh; fi

asan: deps
	cmake -S . -B $(ASAN_DIR) -DCMAKE_BUILD_TYPE=Debug -DDLAB_SANITIZE=ON \
		-DDLAB_BUILD_CGAL_BASELINE=OFF $(CMAKE_ARGS)
	cmake --build $(ASAN_DIR) -j $(JOBS)
	UBSAN_OPTIONS=print_stacktrace=1 \
		LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp:print_suppressions=0 \
		ctest --test-dir $(ASAN_DIR) --output-on-failure --no-tests=error -j $(CTEST_JOBS) \
		-LE '^realwindow$$' -E '^Web\.Browser$$'
	@# Web.Browser tests the WebAssembly build, which sanitizers do not change: make test runs it.
	@# The real-window tests (label realwindow) with ASan and UBSan but no leak check:
	@# glfwTerminate unloads Mesa's DRI driver (swrast_dri.so), and the caches its globals
	@# pointed to then look leaked from an <unknown module>; a minimal GLFW program under Xvfb
	@# shows the same 128 bytes.
	ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1 \
		ctest --test-dir $(ASAN_DIR) --output-on-failure --no-tests=ignore -L '^realwindow$$'

# Longer fuzzing: `make fuzz FUZZ_SECONDS=600` (per target). New inputs go to
# build-fuzz/fuzz-corpus/, crashes to build-fuzz/fuzz-artifacts/ (see tests/fuzz/run_fuzz.sh).
fuzz: deps
	FUZZ_SECONDS=$(FUZZ_SECONDS) FUZZ_REQUIRED=$${FUZZ_REQUIRED:-1} bash tests/fuzz/run_fuzz.sh

bench: build
	bash .ci/bench_compare.sh $(BUILD_DIR)

format:
	git ls-files -co --exclude-standard '*.cpp' '*.h' | grep -v '/corpus/' | xargs clang-format -i

clean:
	rm -rf $(BUILD_DIR) $(ASAN_DIR) build-release $(FUZZ_DIR) $(WEB_DIR)
