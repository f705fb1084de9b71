// cgal_baseline: times CGAL's Delaunay_triangulation_2 (Epick, range insert) on a point file.
//
//   cgal_baseline FILE [--repeat R] [--json] [--ele BASE]
//
// The reference that `make bench` compares dtlab against. The file is read with dtlab's own reader
// (so both tools see the same points) and converted to CGAL points once; then one warm-up run and
// R timed runs (default 5). Only `dt.insert(first, last)` is timed: CGAL's range insert sorts the
// points spatially (Hilbert order) before inserting, so this is CGAL at its best, not a naive
// incremental loop. Destroying the triangulation happens after the clock stops. --ele writes
// CGAL's triangulation (untimed) as Triangle's BASE.node and BASE.ele, for `dtlab check`.
#include "core/engine/io_read.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangulation = CGAL::Delaunay_triangulation_2<Kernel>;
using Point = Kernel::Point_2;

constexpr const char* kUsage =
    "usage: cgal_baseline FILE [--repeat R] [--json]\n"
    "  Times CGAL::Delaunay_triangulation_2<Epick> range insertion of the points in FILE\n"
    "  (any format dtlab reads): 1 warm-up run, then R timed runs (default 5).\n"
    "  --repeat R  number of timed runs (R >= 1)\n"
    "  --json      print one JSON object instead of text\n"
    "  --ele BASE  also write the triangulation to BASE.node and BASE.ele (Triangle's format,\n"
    "              the input's point numbering, from 0)\n";

struct Options {
    std::string path;
    int repeat = 5;
    bool json = false;
    std::string ele;  // --ele BASE
};

[[noreturn]] void usageError(const std::string& message) {
    std::fprintf(stderr, "cgal_baseline: %s\n%s", message.c_str(), kUsage);
    std::exit(2);
}

Options parseArgs(int argc, char** argv) {
    Options options;
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        if (arg == "-h" || arg == "--help") {
            std::fputs(kUsage, stdout);
            std::exit(0);
        } else if (arg == "--json") {
            options.json = true;
        } else if (arg == "--repeat" || arg.starts_with("--repeat=")) {
            std::string value;
            if (arg == "--repeat") {
                if (i + 1 >= argc) usageError("--repeat needs a value");
                value = argv[++i];
            } else {
                value = std::string(arg.substr(std::string_view("--repeat=").size()));
            }
            char* end = nullptr;
            const long r = std::strtol(value.c_str(), &end, 10);
            if (value.empty() || *end != '\0' || r < 1 || r > 1000000) {
                usageError("--repeat wants a whole number >= 1, not '" + value + "'");
            }
            options.repeat = static_cast<int>(r);
        } else if (arg == "--ele") {
            if (i + 1 >= argc) usageError("--ele needs a base name");
            options.ele = argv[++i];
        } else if (arg.starts_with("-") && arg != "-") {
            usageError("unknown option '" + std::string(arg) + "'");
        } else if (options.path.empty()) {
            options.path = arg;
        } else {
            usageError("one input file only ('" + options.path + "', then '" + std::string(arg) +
                       "')");
        }
    }
    if (options.path.empty()) usageError("no input file");
    return options;
}

struct Run {
    double ms = 0.0;
    std::size_t vertices = 0;
    std::size_t faces = 0;
};

Run triangulateOnce(const std::vector<Point>& points) {
    Run run;
    Triangulation dt;
    const auto start = std::chrono::steady_clock::now();
    dt.insert(points.begin(), points.end());
    const auto stop = std::chrono::steady_clock::now();
    run.ms = std::chrono::duration<double, std::milli>(stop - start).count();
    run.vertices = dt.number_of_vertices();
    run.faces = dt.number_of_faces();  // finite faces only
    return run;
}

// Finite faces with each vertex's input index; of equal points CGAL keeps one, as dtlab does.
using IndexedVertex = CGAL::Triangulation_vertex_base_with_info_2<std::size_t, Kernel>;
using IndexedTriangulation =
    CGAL::Delaunay_triangulation_2<Kernel, CGAL::Triangulation_data_structure_2<IndexedVertex>>;

bool writeEle(const std::vector<Point>& points, const std::string& input, const std::string& base) {
    const std::string nodePath = base + ".node", elePath = base + ".ele";
    std::error_code ec;
    for (const std::string& out : {nodePath, elePath}) {
        if (std::filesystem::equivalent(out, input, ec)) {
            std::fprintf(stderr, "cgal_baseline: %s is the input: not overwritten\n", out.c_str());
            return false;
        }
    }
    std::vector<std::pair<Point, std::size_t>> indexed;
    indexed.reserve(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) indexed.emplace_back(points[i], i);
    IndexedTriangulation dt(indexed.begin(), indexed.end());
    std::FILE* node = std::fopen(nodePath.c_str(), "w");
    std::FILE* ele = node ? std::fopen(elePath.c_str(), "w") : nullptr;
    bool ok = node && ele;
    if (ok) {
        std::fprintf(node, "%zu 2 0 0\n", points.size());
        for (std::size_t i = 0; i < points.size(); ++i)
            std::fprintf(node, "%zu %.17g %.17g\n", i, points[i].x(), points[i].y());
        std::fprintf(ele, "%zu 3 0\n", dt.number_of_faces());
        std::size_t t = 0;
        for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
            std::fprintf(ele, "%zu %zu %zu %zu\n", t++, f->vertex(0)->info(), f->vertex(1)->info(),
                         f->vertex(2)->info());
        }
    }
    if (node && (std::ferror(node) || std::fclose(node) != 0)) ok = false;
    if (ele && (std::ferror(ele) || std::fclose(ele) != 0)) ok = false;
    if (!ok)
        std::fprintf(stderr, "cgal_baseline: cannot write %s or %s\n", nodePath.c_str(),
                     elePath.c_str());
    return ok;
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t m = values.size() / 2;
    return values.size() % 2 == 1 ? values[m] : 0.5 * (values[m - 1] + values[m]);
}

}  // namespace

int main(int argc, char** argv) {
    const Options options = parseArgs(argc, argv);

    std::vector<Point> points;
    try {
        const auto input = dlab::readPointsFile(options.path);
        points.reserve(input.points.size());
        for (const dlab::Vec2& p : input.points) points.emplace_back(p.x, p.y);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "cgal_baseline: %s\n", e.what());
        return 1;
    }
    if (points.empty()) {
        std::fprintf(stderr, "cgal_baseline: %s holds no points\n", options.path.c_str());
        return 1;
    }

    const Run warmUp = triangulateOnce(points);
    std::vector<double> times;
    times.reserve(static_cast<std::size_t>(options.repeat));
    Run last = warmUp;
    for (int i = 0; i < options.repeat; ++i) {
        last = triangulateOnce(points);
        times.push_back(last.ms);
    }

    if (!options.ele.empty() && !writeEle(points, options.path, options.ele)) return 1;
    const std::size_t n = points.size();
    const double medianMs = median(times);
    const double minMs = *std::min_element(times.begin(), times.end());
    const double nsPerPoint = medianMs * 1e6 / static_cast<double>(n);

    if (options.json) {
        std::printf(
            "{\"tool\":\"cgal\",\"cgal_version\":\"%s\",\"n\":%zu,\"repeat\":%d,"
            "\"median_ms\":%.3f,\"min_ms\":%.3f,\"ns_per_point\":%.2f,"
            "\"warmup_ms\":%.3f,\"vertices\":%zu,\"faces\":%zu}\n",
            CGAL_VERSION_STR, n, options.repeat, medianMs, minMs, nsPerPoint, warmUp.ms,
            last.vertices, last.faces);
    } else {
        std::printf("cgal_baseline (CGAL %s, Delaunay_triangulation_2<Epick>, range insert)\n",
                    CGAL_VERSION_STR);
        std::printf("  input      %s: %zu points\n", options.path.c_str(), n);
        std::printf("  result     %zu vertices, %zu finite faces\n", last.vertices, last.faces);
        std::printf("  warm-up    %.3f ms\n", warmUp.ms);
        std::printf("  %d runs    median %.3f ms, min %.3f ms, %.2f ns/point\n", options.repeat,
                    medianMs, minMs, nsPerPoint);
    }
    return 0;
}
