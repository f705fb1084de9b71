// dtlab shared pieces: engine flags, loading with clear errors, exit-status handling.
#include "app/dtlab_common.h"

#include "core/io_read.h"

#include <iostream>

namespace dlab::cli {

namespace {
int g_exitCode = 0;
}

void EngineFlags::add(CLI::App& cmd) {
    cmd.add_option("--locate", locate, "Point location: naive | walk | grid | idbuffer-cpu")
        ->check(CLI::IsMember({"naive", "walk", "grid", "idbuffer-cpu"}))
        ->capture_default_str();
    cmd.add_option("--order", order, "Insertion order: input | random | brio")
        ->check(CLI::IsMember({"input", "random", "brio"}))
        ->capture_default_str();
    cmd.add_option("--boundary", boundary,
                   "exact: true Delaunay with convex hull (ghost vertex); super: the paper's finite super-triangle")
        ->check(CLI::IsMember({"exact", "super"}))
        ->capture_default_str();
    cmd.add_option("--seed", seed, "Seed of the random and brio orders")->capture_default_str();
    cmd.add_option("--idbuffer-size", idBufferSize, "Width and height of the ID buffer in pixels")
        ->check(CLI::Range(1, 16384))
        ->capture_default_str();
}

InsertOptions EngineFlags::options() const {
    InsertOptions o;
    o.locator = *parseLocatorKind(locate);
    o.order = *parseOrderKind(order);
    o.boundary = *parseBoundary(boundary);
    o.seed = seed;
    o.locatorOptions.idBufferWidth = o.locatorOptions.idBufferHeight = idBufferSize;
    return o;
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
