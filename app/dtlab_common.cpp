// dtlab shared pieces: engine flags, loading with clear errors, exit-status handling.
#include "app/dtlab_common.h"

#include "core/engine/io_read.h"
#include "core/engine/predicates.h"
#include "core/engine/text_util.h"

#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iostream>
#include <stdexcept>
#include <thread>

namespace dlab::cli {

namespace {
int g_exitCode = 0;
std::vector<char*> g_commandLine;
}  // namespace

void rememberCommandLine(int argc, char** argv) { g_commandLine.assign(argv, argv + argc); }

const std::vector<char*>& commandLine() { return g_commandLine; }

void execBeside(const char* name, const std::string& why) {
    std::error_code ec;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
    const std::string path = ((ec ? std::filesystem::path(".") : self.parent_path()) / name);
    std::vector<char*> argv = commandLine();  // argv[0] as typed: help texts say "dtlab"
    argv.push_back(nullptr);
    std::cout.flush();
    execv(path.c_str(), argv.data());
    std::cerr << "dtlab: error: " << why << ", which runs in " << path
              << ", and that cannot be started: " << std::strerror(errno) << "\n";
    std::exit(1);
}

namespace {
std::string g_gl = "auto";
}  // namespace

void addGlFlag(CLI::App& cmd) {
    cmd.add_option("--gl", g_gl,
                   "Headless OpenGL: egl (a GPU, else Mesa's llvmpipe) | osmesa | auto (EGL on a "
                   "GPU if there is one, else OSMesa, else EGL on llvmpipe)")
        ->check(CLI::IsMember({"egl", "osmesa", "auto"}))
        ->capture_default_str();
}

const std::string& glFlag() { return g_gl; }

void EngineFlags::add(CLI::App& cmd) {
    cmd.add_option(
           "--locate", locate,
           "Point location: naive | walk | grid | idbuffer-cpu | idbuffer-gl | idbuffer-gl-batched "
           "(the GL ones on a headless GL context: --gl)")
        ->check(CLI::IsMember(
            {"naive", "walk", "grid", "idbuffer-cpu", "idbuffer-gl", "idbuffer-gl-batched"}))
        ->each([](const std::string& value) {
            if (needsGl(*parseLocatorKind(value))) needGl();
        })
        ->capture_default_str();
    cmd.add_option("--order", order, "Insertion order: input | random | brio")
        ->check(CLI::IsMember({"input", "random", "brio"}))
        ->capture_default_str();
    cmd.add_option("--boundary", boundary,
                   "exact: true Delaunay with convex hull (ghost vertex); super: the paper's "
                   "finite super-triangle")
        ->check(CLI::IsMember({"exact", "super"}))
        ->capture_default_str();
    cmd.add_option("--seed", seed, "Seed of the random and brio orders")->capture_default_str();
    cmd.add_option("--idbuffer-size", idBufferSize, "Width and height of the ID buffer in pixels")
        ->check(CLI::Range(1, 16384))
        ->capture_default_str();
    cmd.add_option("--readback", readback,
                   "GL ID buffer readback: one (a pixel per insertion, the paper) | batched (the "
                   "pixels of the "
                   "next --batch points in one read) | pipelined (batched, read one batch ahead)")
        ->check(CLI::IsMember({"one", "batched", "pipelined"}));
    cmd.add_option("--batch", batch, "GL ID buffer, batched readback: points per read")
        ->check(CLI::Range(1, ui::IdBufferGlOptions::kMaxBatch))
        ->capture_default_str();
    addGlFlag(cmd);
}

InsertOptions EngineFlags::options() const {
    InsertOptions o;
    o.locator = *parseLocatorKind(locate);
    o.order = *parseOrderKind(order);
    o.boundary = *parseBoundary(boundary);
    o.seed = seed;
    o.locatorOptions.idBufferWidth = o.locatorOptions.idBufferHeight = idBufferSize;
    o.locatorOptions.idBufferBatch = batch;
    if (needsGl(o.locator) && !readback.empty()) {
        o.locator = readback == "one" ? LocatorKind::IdBufferGl : LocatorKind::IdBufferGlBatched;
    }
    return o;
}

std::optional<JoinedTriangulation> triangulateOnTwoCores(std::vector<Vec2>& points,
                                                         const InsertOptions& options,
                                                         std::string* declined) {
    auto decline = [&](const std::string& why) {
        if (declined) *declined = why;
        return std::nullopt;
    };
    if (options.boundary != Boundary::Exact || options.locator != LocatorKind::Walk)
        return decline("the two-core path takes the exact boundary and the walk only");
    const std::optional<Vec2> split = splitPoint(points);
    if (!split) return decline("too few points to split");
    // The pilot's predicate calls are timed with the run but not counted as the triangulation's.
    const PredicateCounters before = predicateCounters();
    const SplitPilot pilot = pilotSplit(points, *split, options);
    predicateCounters() = before;
    if (!pilot.pays()) {
        char why[160];
        std::snprintf(why, sizeof why,
                      "a pilot on %zu sampled points: two halves and their join would cost %.2f "
                      "of one run's work, the join alone %.2f",
                      pilot.sample, pilot.ratio(), pilot.seamShare());
        return decline(pilot.joined ? why : "a half of a sample has no triangle");
    }
    // Both halves run on threads of their own, the caller's waits. On the caller's thread, in a
    // process that had triangulated before (dtlab bench's timed runs), a half's steps that fill
    // new buffers (picking its points, the BRIO sort, the copy in insertion order) took up to
    // twice as long as on the other thread, and the whole half 10% longer.
    struct Half {
        HalfTriangulation result;
        PredicateCounters counts;  // the thread's (they start at zero)
    };
    std::array<Half, 2> halves;
    auto run = [&](Half& half, bool left) {
        half.result = triangulateHalf(points, *split, left, options);
        half.counts = predicateCounters();
    };
    std::thread leftThread(run, std::ref(halves[0]), true);
    std::thread rightThread(run, std::ref(halves[1]), false);
    leftThread.join();
    rightThread.join();
    for (const Half& half : halves) predicateCounters() += half.counts;
    auto joined = joinHalves(points, std::move(halves[0].result), std::move(halves[1].result));
    if (!joined) return decline("a half has no triangle");
    return joined;
}

std::unique_ptr<Inserter> EngineFlags::makeInserter(std::vector<Vec2> points) const {
    const InsertOptions o = options();
    if (!needsGl(o.locator)) return std::make_unique<Inserter>(std::move(points), o);
    return makeGlInserter(std::move(points));
}

void fail(const std::string& message, int code) {
    std::cerr << "dtlab: error: " << escapeControls(message) << "\n";  // one line, always
    throw Exit{code};
}

LoadedPoints loadPoints(const std::string& path) {
    try {
        PointSet set = readPointsFile(path);
        for (const std::string& w : set.warnings) std::cerr << "dtlab: warning: " << w << "\n";
        return {std::move(set.points), set.indexBase};
    } catch (const InputError& e) {
        fail(e.what(), 2);
    }
}

void guarded(const std::function<void()>& body) {
    try {
        body();
    } catch (const Exit& e) {
        g_exitCode = e.code;
    } catch (const std::invalid_argument& e) {  // the engine refused the input (too many
        std::cerr << "dtlab: error: " << e.what() << "\n";  // points, no super-triangle)
        g_exitCode = 2;
    } catch (const std::domain_error& e) {
        std::cerr << "dtlab: error: " << e.what() << "\n";
        g_exitCode = 2;
    } catch (const std::exception& e) {
        std::cerr << "dtlab: error: " << escapeControls(e.what()) << "\n";
        g_exitCode = 1;
    }
}

int exitCode() { return g_exitCode; }

}  // namespace dlab::cli
