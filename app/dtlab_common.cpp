// dtlab shared pieces: engine flags, loading with clear errors, exit-status handling.
#include "app/dtlab_common.h"

#include "core/engine/io_read.h"
#include "ui/platform/platform.h"

#include <iostream>

namespace dlab::cli {

namespace {
int g_exitCode = 0;
}

void EngineFlags::add(CLI::App& cmd) {
    cmd.add_option(
           "--locate", locate,
           "Point location: naive | walk | grid | idbuffer-cpu | idbuffer-gl | idbuffer-gl-batched "
           "(the GL ones on a headless OSMesa context)")
        ->check(CLI::IsMember(
            {"naive", "walk", "grid", "idbuffer-cpu", "idbuffer-gl", "idbuffer-gl-batched"}))
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

ui::IdBufferGlOptions EngineFlags::glOptions() const {
    const InsertOptions o = options();
    ui::IdBufferGlOptions g = ui::IdBufferGlOptions::from(o.locator, o.locatorOptions);
    if (readback == "pipelined") g.readback = ui::GlReadback::Pipelined;
    return g;
}

std::unique_ptr<Inserter> EngineFlags::makeInserter(std::vector<Vec2> points) const {
    const InsertOptions o = options();
    if (!needsGl(o.locator)) return std::make_unique<Inserter>(std::move(points), o);
    auto locator = std::make_unique<ui::IdBufferGl>(headlessGl(), glOptions());
    ui::IdBufferGl* gl = locator.get();
    auto ins = std::make_unique<Inserter>(std::move(points), o, std::move(locator));
    gl->followOrder(*ins);  // the batched readback reads ahead along the insertion order
    return ins;
}

namespace {

// One OSMesa context for the whole process. The buffer it renders into is tiny: the GL
// locators draw into their own framebuffer objects.
struct HeadlessContext {
    std::unique_ptr<ui::Platform> platform;
    std::shared_ptr<ui::GlContext> gl;
    ~HeadlessContext() {
        if (gl) gl->lose();
    }
};

}  // namespace

std::shared_ptr<ui::GlContext> headlessGl() {
    static HeadlessContext context;
    if (!context.gl) {
        std::string error;
        context.platform = ui::makeOsmesaPlatform(16, 16, error);
        if (context.platform) context.gl = ui::GlContext::fromCurrent(error);
        if (!context.gl) fail("--locate idbuffer-gl: " + error);
    }
    return context.gl;
}

void fail(const std::string& message, int code) {
    std::cerr << "dtlab: error: " << message << "\n";
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
    } catch (const std::exception& e) {
        std::cerr << "dtlab: error: " << e.what() << "\n";
        g_exitCode = 1;
    }
}

int exitCode() { return g_exitCode; }

}  // namespace dlab::cli
