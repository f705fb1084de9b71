// dtlab shared pieces: engine flags, loading with clear errors, exit-status handling.
#include "app/dtlab_common.h"

#include "core/engine/io_read.h"
#include "core/engine/predicates.h"
#include "core/engine/text_util.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iostream>
#include <new>
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
    cmd.add_option("--locate", locate,
                   "Point location: " + joinedNames(kLocatorNames) +
                       " (the GL ones on a headless GL context: --gl)")
        ->check(CLI::IsMember(namesIn(kLocatorNames)))
        ->each([](const std::string& value) {
            if (needsGl(*parseLocatorKind(value))) needGl();
        })
        ->capture_default_str();
    cmd.add_option("--order", order, "Insertion order: " + joinedNames(kOrderNames))
        ->check(CLI::IsMember(namesIn(kOrderNames)))
        ->capture_default_str();
    cmd.add_option("--boundary", boundary,
                   "exact: true Delaunay with convex hull (ghost vertex); super: the paper's "
                   "finite super-triangle")
        ->check(CLI::IsMember(namesIn(kBoundaryNames)))
        ->capture_default_str();
    cmd.add_option("--seed", seed, "Seed of the random and brio orders (0 to 2^64-1)")
        ->check(CLI::Validator(
            [](std::string& v) {
                std::uint64_t x = 0;
                const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), x);
                return !v.empty() && ec == std::errc() && end == v.data() + v.size()
                           ? std::string()
                           : "--seed must be a whole number from 0 to 18446744073709551615 "
                             "(2^64-1), not " +
                                 escapeControls(v);
            },
            "0..2^64-1"))
        ->capture_default_str();
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

std::unique_ptr<Inserter> EngineFlags::makeInserter(std::vector<Vec2> points, int threads) const {
    InsertOptions o = options();
    o.threads = threads;
    noteSlowChoices(o, points);
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

Progress::Progress(std::string what, double total)
    : m_what(std::move(what)),
      m_total(total),
      m_tty(::isatty(STDERR_FILENO) == 1),
      m_start(std::chrono::steady_clock::now()),
      m_drawn(m_start) {}

Progress::~Progress() { clear(); }

void Progress::clear() {
    if (m_tty && m_shown) std::fprintf(stderr, "\r\033[K");
    m_shown = false;
}

std::string Progress::line(const std::string& what, double done, double total, double elapsedS,
                           const std::string& detail) {
    const double share = total > 0 ? std::clamp(done / total, 0.0, 1.0) : 0.0;
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s: %.0f%%", what.c_str(), 100 * share);
    std::string s = buf;
    if (!detail.empty()) s += " (" + detail + ")";
    if (share > 0 && share < 1) {
        const double left = elapsedS * (1 - share) / share;
        std::snprintf(
            buf, sizeof buf, ", about %s left",
            left < 90 ? (std::to_string(static_cast<int>(std::ceil(left))) + " s").c_str()
                      : (std::to_string(static_cast<int>(std::ceil(left / 60))) + " min").c_str());
        s += buf;
    }
    return s;
}

void Progress::advance(double work, const std::string& detail) {
    m_done += work;
    if (!m_tty) return;
    const auto now = std::chrono::steady_clock::now();
    if (m_shown && now - m_drawn < std::chrono::milliseconds(250)) return;
    m_drawn = now;
    m_shown = true;
    const double elapsed = std::chrono::duration<double>(now - m_start).count();
    std::fprintf(stderr, "\r\033[K%s",
                 escapeControls(line(m_what, m_done, m_total, elapsed, detail)).c_str());
    std::fflush(stderr);
}

void noteSlowChoices(const InsertOptions& o, const std::vector<Vec2>& points) {
    const std::size_t n = points.size();
    const auto pixels = static_cast<double>(o.locatorOptions.idBufferWidth) *
                        static_cast<double>(o.locatorOptions.idBufferHeight);
    if (o.locator == LocatorKind::IdBufferCpu && pixels > 4096.0 * 4096.0 && n > 10000) {
        std::fprintf(stderr,
                     "dtlab: note: an ID buffer of %d x %d pixels on the CPU (%.0f MiB) repaints "
                     "large areas for every point: %zu points may take minutes; the default "
                     "--idbuffer-size 1600 is much faster\n",
                     o.locatorOptions.idBufferWidth, o.locatorOptions.idBufferHeight,
                     pixels * 4 / (1 << 20), n);
    }
    if (!needsGl(o.locator) || n < 1000) return;
    double lo = 0, hi = 0;
    for (const Vec2& p : points) {
        for (const double c : {std::fabs(p.x), std::fabs(p.y)}) {
            if (c == 0) continue;
            lo = lo == 0 ? c : std::min(lo, c);
            hi = std::max(hi, c);
        }
    }
    if (lo > 0 && hi / lo > 1e30) {  // float32 pixels hold about 7 digits
        std::fprintf(stderr,
                     "dtlab: note: coordinates from %.0e to %.0e are beyond what the GL ID "
                     "buffer's float pixels tell apart: most points fall back to a long walk, and "
                     "%zu points may take minutes; --locate walk is much faster\n",
                     lo, hi, n);
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
    } catch (const std::bad_alloc&) {  // a reader or the engine says which limit where it can
        std::cerr << "dtlab: error: out of memory (the input is too large for the memory this "
                     "process may use)\n";
        g_exitCode = 1;
    } catch (const std::exception& e) {
        std::cerr << "dtlab: error: " << escapeControls(e.what()) << "\n";
        g_exitCode = 1;
    }
}

int exitCode() { return g_exitCode; }

}  // namespace dlab::cli
