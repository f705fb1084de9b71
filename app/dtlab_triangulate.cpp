// dtlab triangulate: a point file in, Triangle's .node/.ele/.neigh out (plus optional Voronoi,
// OFF, OBJ and SVG), ids in the input's index base.
#include "app/dtlab_common.h"

#include "core/engine/constrainer.h"
#include "core/engine/io_read.h"
#include "core/engine/io_write.h"
#include "core/engine/mesh.h"
#include "core/engine/predicates.h"
#include "core/engine/remover.h"
#include "core/engine/voronoi.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <optional>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace dlab::cli {

namespace {

struct TriangulateArgs {
    std::string input;
    std::string base;
    std::string voronoiSvg, svg, off, obj, voronoiBase;
    std::string removeFile;  // ids to remove after the insertion
    bool check = false;
    bool quiet = false;
    int threads = 2;
    EngineFlags engine;
};

// The result of either batch path: the inserter, or two halves joined (--threads 2).
struct Triangulated {
    Mesh mesh;
    std::vector<std::int32_t> skipped;
    InsertStats stats;
    int threads = 1;
    std::string oneCoreWhy{};  // with --threads 2, why the one inserter ran
    std::vector<std::pair<std::int32_t, std::int32_t>> constrained{};  // IN.poly: the segments
    std::size_t removed = 0;                                           // --remove: vertices removed
    double removeMs = 0;
};

Triangulated triangulate(const TriangulateArgs& args, std::vector<Vec2> points) {
    std::string why;
    if (args.threads == 2) {
        if (auto joined = triangulateOnTwoCores(points, args.engine.options(), &why))
            return {std::move(joined->mesh), std::move(joined->skipped), joined->stats, 2, {}};
    }
    // GL locators need a context; with --threads 2 the order's sorts use both cores
    const auto made = args.engine.makeInserter(std::move(points), args.threads);
    {
        // On a terminal, a line with the share done and the time left (quiet when piped).
        Progress progress("triangulate", made->numInput());
        made->setProgress(
            [&](std::int32_t taken) { progress.set(taken, std::to_string(taken) + " points"); });
        made->run();
        made->setProgress({});
    }
    Triangulated out{made->takeMesh(), made->skipped(), made->stats(), 1, std::move(why)};
    return out;
}

// The points equal to each other (== on doubles, as the inserter compares): groups of ids,
// increasing, only those with more than one member.
std::vector<std::vector<std::int32_t>> equalGroups(const std::vector<Vec2>& G, std::int32_t n) {
    std::vector<std::int32_t> ids(static_cast<std::size_t>(n));
    for (std::int32_t i = 0; i < n; ++i) ids[i] = i;
    std::sort(ids.begin(), ids.end(), [&](std::int32_t a, std::int32_t b) {
        if (G[a].x != G[b].x) return G[a].x < G[b].x;
        if (G[a].y != G[b].y) return G[a].y < G[b].y;
        return a < b;
    });
    std::vector<std::vector<std::int32_t>> groups;
    for (std::size_t i = 0; i < ids.size();) {
        std::size_t j = i + 1;
        while (j < ids.size() && G[ids[j]] == G[ids[i]]) ++j;
        if (j - i > 1) groups.emplace_back(ids.begin() + i, ids.begin() + j);
        i = j;
    }
    return groups;
}

// Removes `gone` (input ids) from the closed mesh. A vertex with an equal point left is not
// removed but renamed to the lowest id of those left; the skipped list becomes the equal points
// left that are not vertices.
std::size_t removeVertices(Mesh& mesh, std::int32_t n, Boundary boundary,
                           const std::vector<std::int32_t>& gone,
                           std::vector<std::int32_t>& skipped) {
    std::vector<bool> isGone(static_cast<std::size_t>(n), false);
    for (const std::int32_t i : gone) isGone[i] = true;
    std::vector<std::int32_t> renamed(static_cast<std::size_t>(n), kNone);
    skipped.clear();
    for (const auto& group : equalGroups(mesh.G, n)) {
        auto left = std::find_if(group.begin(), group.end(), [&](auto i) { return !isGone[i]; });
        if (left == group.end()) continue;
        if (*left != group[0]) renamed[group[0]] = *left;
        for (auto it = left + 1; it != group.end(); ++it)
            if (!isGone[*it]) skipped.push_back(*it);
    }
    std::sort(skipped.begin(), skipped.end());
    for (std::int32_t& v : mesh.V) {
        if (v < n && renamed[v] != kNone) v = renamed[v];
    }
    Remover remover(mesh, n, boundary);
    std::size_t removed = 0;
    for (const std::int32_t i : gone) {
        if (renamed[i] != kNone) continue;
        const RemoveResult r = remover.remove(i);
        removed += r == RemoveResult::Removed || r == RemoveResult::Collapsed;
    }
    return removed;
}

// --remove: the one inserter to the closed mesh (ghosts or super-triangle), the removals, then
// the virtual triangles dropped. G keeps every input point: ids stay the input's.
Triangulated triangulateThenRemove(const TriangulateArgs& args, std::vector<Vec2> points,
                                   const std::vector<std::int32_t>& gone) {
    const auto n = static_cast<std::int32_t>(points.size());
    const Boundary boundary = args.engine.options().boundary;
    const auto made = args.engine.makeInserter(std::move(points));
    Triangulated out;
    if (boundary == Boundary::Exact) {
        made->run();
        out.mesh = made->takeMesh();
        addGhosts(out.mesh);
    } else {
        while (made->control().phase != Phase::Finalize && !made->done()) made->step();
        out.mesh = made->mesh();
    }
    out.stats = made->stats();
    const auto t0 = std::chrono::steady_clock::now();
    out.removed = removeVertices(out.mesh, n, boundary, gone, out.skipped);
    dropVirtual(out.mesh, n);
    out.removeMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

bool isPoly(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return ext == ".poly";
}

// The constrained edge p-q lies on which of the first `upTo` segments?
std::size_t segmentHolding(const PolyFile& poly, std::size_t upTo, std::int32_t p, std::int32_t q) {
    const auto& G = poly.points.points;
    for (std::size_t k = 0; k < upTo; ++k) {
        const auto [a, b] = poly.segments[k];
        if (orient2d(G[a], G[b], G[p]) == 0 && orient2d(G[a], G[b], G[q]) == 0) return k;
    }
    return upTo;
}

// --remove on a .poly: the listed points removed from the constrained mesh, every constraint
// kept (the rim repaired to constrained Delaunay). A point on a segment is refused, named with it.
void removeKeepingSegments(const TriangulateArgs& args, const PolyFile& poly, Constrainer& con,
                           const std::vector<std::int32_t>& gone, Triangulated& out) {
    const auto n = static_cast<std::int32_t>(poly.points.points.size());
    const int base = poly.points.indexBase;
    const auto t0 = std::chrono::steady_clock::now();
    Remover remover(out.mesh, n, Boundary::Exact);
    for (const std::int32_t i : gone) {
        const VertexRemoval r = con.removeVertex(remover, i, nullptr, nullptr);
        if (r.refused) {
            const auto [p, q] = r.constrained;
            const std::size_t k = std::min(segmentHolding(poly, poly.segments.size(), p, q),
                                           poly.segments.size() - 1);
            fail("--remove " + args.removeFile + ": point " + std::to_string(i + base) +
                     " is on segment " + std::to_string(k + base) + " (" +
                     std::to_string(poly.segments[k].first + base) + "-" +
                     std::to_string(poly.segments[k].second + base) +
                     "): a point of a segment is not removed",
                 2);
        }
        out.removed += r.removed == RemoveResult::Removed || r.removed == RemoveResult::Collapsed;
    }
    out.removeMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// IN.poly: the one inserter, the ghosts back, every segment constrained (Sloan's flips), the
// listed points removed (--remove), the ghosts dropped. Two segments that cross stop with both
// named.
Triangulated triangulatePoly(const TriangulateArgs& args, const PolyFile& poly,
                             const std::vector<std::int32_t>& gone) {
    if (args.engine.options().boundary != Boundary::Exact)
        fail(args.input + ": segments need --boundary exact", 2);
    const auto n = static_cast<std::int32_t>(poly.points.points.size());
    const int base = poly.points.indexBase;
    const auto made = args.engine.makeInserter(poly.points.points);
    made->run();
    Triangulated out{made->takeMesh(), made->skipped(), made->stats(), 1};
    if (out.mesh.numTriangles() == 0) return out;  // collinear: no triangle to constrain
    addGhosts(out.mesh);
    Constrainer con(out.mesh, n);
    for (std::size_t k = 0; k < poly.segments.size(); ++k) {
        const auto [a, b] = poly.segments[k];
        const ConstrainOutcome r = con.insert(a, b);
        if (r.result != ConstrainResult::Crosses) continue;
        const std::size_t other = segmentHolding(poly, k, r.crossed.first, r.crossed.second);
        fail(args.input + ": segment " + std::to_string(k + base) + " (" +
                 std::to_string(a + base) + "-" + std::to_string(b + base) + ") crosses segment " +
                 std::to_string(other + base) + " (" +
                 std::to_string(poly.segments[other].first + base) + "-" +
                 std::to_string(poly.segments[other].second + base) +
                 "); crossing segments are not split",
             2);
    }
    if (!args.removeFile.empty()) removeKeepingSegments(args, poly, con, gone, out);
    const Mesh& m = out.mesh;
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        if (con.isConstrained(c) && c < m.O[c])
            out.constrained.push_back({m.V[next(c)], m.V[prev(c)]});
    }
    dropVirtual(out.mesh, n);
    return out;
}

// BASE.poly: the vertices in BASE.node, the constrained edges (pieces of the input's segments).
void writeSegmentsPoly(std::ostream& os, const Triangulated& t, int base) {
    os << "0 2 0 0\n" << t.constrained.size() << " 0\n";
    for (std::size_t k = 0; k < t.constrained.size(); ++k) {
        os << k + base << " " << t.constrained[k].first + base << " "
           << t.constrained[k].second + base << "\n";
    }
    os << "0\n";
}

PolyFile loadPoly(const std::string& path) {
    try {
        return readPolyFile(path);
    } catch (const InputError& e) {
        fail(e.what(), 2);
    }
}

std::vector<std::int32_t> loadRemoveIds(const std::string& path, int base, std::size_t n) {
    try {
        return parseIdList(readRegularFile(path, kMaxFileBytes), path, base, n);
    } catch (const InputError& e) {
        fail(std::string("--remove ") + e.what(), 2);
    }
}

std::string idList(const std::vector<std::int32_t>& ids, int base, std::size_t most) {
    std::string s;
    for (std::size_t i = 0; i < ids.size() && i < most; ++i)
        s += (i ? ", " : "") + std::to_string(ids[i] + base);
    if (ids.size() > most) s += ", ...";
    return s;
}

std::vector<std::string> inputsOf(const TriangulateArgs& args) {
    std::vector<std::string> in{args.input};
    if (!args.removeFile.empty()) in.push_back(args.removeFile);
    return in;
}

// Refuses, before any work, outputs that would overwrite the input or each other.
void checkOutputs(const TriangulateArgs& args) {
    if (args.base.empty() || std::filesystem::path(args.base).filename().empty())
        fail("-o \"" + args.base + "\": give a base name for the output files, e.g. -o out", 2);
    std::vector<OutputFile> out;
    for (const char* ext : {".node", ".ele", ".neigh"}) out.push_back({args.base + ext, {}});
    for (const std::string* p : {&args.off, &args.obj, &args.svg, &args.voronoiSvg})
        if (!p->empty()) out.push_back({*p, {}});
    if (!args.voronoiBase.empty()) {
        out.push_back({args.voronoiBase + ".v.node", {}});
        out.push_back({args.voronoiBase + ".v.edge", {}});
    }
    if (isPoly(args.input)) out.push_back({args.base + ".poly", {}});
    try {
        checkOutputFiles(out, inputsOf(args));
    } catch (const std::runtime_error& e) {
        fail(e.what(), 2);
    }
}

// One run, then the process ends: every large buffer goes back to the system as soon as it is
// freed. By default glibc raises its mmap threshold after the first large free and serves later
// large buffers from the heap, which keeps what they free: 2^20 lattice points on two threads
// then peak at 135 MiB instead of 92 (measured; no slower in a fresh process).
void returnLargeBuffersWhenFreed() {
#if defined(__GLIBC__)
    mallopt(M_MMAP_THRESHOLD, 1 << 20);
#endif
}

// The one-paragraph report on stdout.
void printSummary(const TriangulateArgs& args, const Triangulated& result, int base, std::size_t n,
                  double ms, std::size_t listed) {
    const Mesh& m = result.mesh;
    const bool exact = args.engine.options().boundary == Boundary::Exact;
    const InsertStats& st = result.stats;
    std::cout << args.input << ": " << n << " points, " << m.numTriangles() << " triangles in "
              << ms << " ms (locate " << args.engine.locate << ", order " << args.engine.order
              << ", boundary " << args.engine.boundary
              << (result.threads == 2 ? ", two halves on two threads, joined" : "") << ")\n";
    if (!result.oneCoreWhy.empty()) std::cout << "  one core: " << result.oneCoreWhy << "\n";
    if (!args.removeFile.empty()) {
        std::cout << "  " << result.removed << " of the " << listed
                  << " listed point(s) removed in " << result.removeMs << " ms";
        if (result.removed < listed)
            std::cout << " (the others: duplicates handing their vertex on, or in no triangle)";
        std::cout << "\n";
    }
    if (!result.skipped.empty()) {
        std::cout << "  " << result.skipped.size()
                  << " duplicate point(s) skipped, the first occurrence kept: "
                  << idList(result.skipped, base, 10) << "\n";
    }
    if (m.numTriangles() == 0 && n > 0)
        std::cout << "  all points" << (listed == 0 ? "" : " left")
                  << " are collinear: no triangle exists\n";
    if (!exact) {
        std::cout << "  boundary=super: triangles near the hull may be missing or non-Delaunay "
                     "(the paper's "
                     "finite super-triangle)\n";
    }
    std::cout << "  " << st.flips << " flips, " << st.inCircleTests << " in-circle tests, "
              << st.walkSteps << " walk steps; wrote " << escapeControls(args.base)
              << ".node/.ele/.neigh\n";
}

void runTriangulate(const TriangulateArgs& args) {
    returnLargeBuffersWhenFreed();
    checkOutputs(args);
    std::optional<PolyFile> poly;
    LoadedPoints loaded;
    if (isPoly(args.input)) {
        poly = loadPoly(args.input);
        loaded = {poly->points.points, poly->points.indexBase};
    } else {
        loaded = loadPoints(args.input);
    }
    const int base = loaded.indexBase;
    const std::size_t n = loaded.points.size();
    std::vector<std::int32_t> gone;
    if (!args.removeFile.empty()) gone = loadRemoveIds(args.removeFile, base, n);
    const auto t0 = std::chrono::steady_clock::now();
    const Triangulated result = poly ? triangulatePoly(args, *poly, gone)
                                : args.removeFile.empty()
                                    ? triangulate(args, std::move(loaded.points))
                                    : triangulateThenRemove(args, std::move(loaded.points), gone);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const Mesh& m = result.mesh;
    const bool exact = args.engine.options().boundary == Boundary::Exact;

    if (args.check) {
        ValidateOptions vo;
        vo.delaunay = exact && !poly;  // super mode does not promise it, nor do constraints
        const auto bad = validate(m, vo);
        if (!bad.empty())
            fail("result failed validation at corner " + std::to_string(bad[0].corner) + ": " +
                 bad[0].message);
    }

    std::vector<OutputFile> out;
    auto add = [&](const std::string& path, std::function<void(std::ostream&)> body) {
        out.push_back({path, std::move(body)});
    };
    add(args.base + ".node", [&](std::ostream& os) { writeNode(os, m.G, base); });
    add(args.base + ".ele", [&](std::ostream& os) { writeEle(os, m, base); });
    add(args.base + ".neigh", [&](std::ostream& os) { writeNeigh(os, m, base); });
    if (poly)
        add(args.base + ".poly", [&](std::ostream& os) { writeSegmentsPoly(os, result, base); });
    if (!args.off.empty()) add(args.off, [&](std::ostream& os) { writeOff(os, m); });
    if (!args.obj.empty()) add(args.obj, [&](std::ostream& os) { writeObj(os, m); });
    SvgOptions meshSvg, voronoiSvg;
    meshSvg.title = args.input;
    voronoiSvg.voronoi = true;
    voronoiSvg.title = args.input + " (Voronoi)";
    if (!args.svg.empty()) add(args.svg, [&](std::ostream& os) { writeSvg(os, m, meshSvg); });
    if (!args.voronoiSvg.empty())
        add(args.voronoiSvg, [&](std::ostream& os) { writeSvg(os, m, voronoiSvg); });
    VoronoiDiagram vd;
    if (!args.voronoiBase.empty()) {
        vd = buildVoronoi(m);
        add(args.voronoiBase + ".v.node",
            [&](std::ostream& os) { writeVoronoiNode(os, vd, base); });
        add(args.voronoiBase + ".v.edge",
            [&](std::ostream& os) { writeVoronoiEdge(os, vd, base); });
    }
    writeTextFiles(out, inputsOf(args));  // all of them or none; never over an input

    if (!args.quiet) printSummary(args, result, base, n, ms, gone.size());
}

}  // namespace

void addTriangulate(CLI::App& app) {
    auto args = std::make_shared<TriangulateArgs>();
    CLI::App* cmd = app.add_subcommand(
        "triangulate", "Delaunay-triangulate a point file; write BASE.node/.ele/.neigh");
    cmd->add_option("input", args->input, "Point file (.node, .csv, .xy, .pts)")->required();
    cmd->add_option("-o,--output", args->base,
                    "Output base name (writes BASE.node, BASE.ele, BASE.neigh)")
        ->required();
    cmd->add_option("--voronoi-svg", args->voronoiSvg,
                    "Also write an SVG of the mesh and its Voronoi diagram");
    cmd->add_option("--svg", args->svg, "Also write an SVG of the mesh");
    cmd->add_option("--voronoi", args->voronoiBase,
                    "Also write Triangle's BASE.v.node / BASE.v.edge");
    cmd->add_option("--off", args->off, "Also write the mesh as OFF");
    cmd->add_option("--obj", args->obj, "Also write the mesh as OBJ");
    cmd->add_option("--remove", args->removeFile,
                    "Remove these points after inserting them all (ids one a line, in the "
                    "input's index base): the result is the Delaunay triangulation of the points "
                    "left, ids unchanged (one thread)");
    cmd->add_flag("--check", args->check,
                  "Validate the result (corner table, orientation, Delaunay) before writing");
    cmd->add_flag("-q,--quiet", args->quiet, "Print nothing on success");
    cmd->add_option("--threads", args->threads,
                    "2: the set split at a sampled median, the halves triangulated at once and "
                    "joined (the same result on any machine; exact boundary, walk, 4096 points "
                    "or more, else one). With cocircular points it may pick another of the "
                    "Delaunay triangulations than 1")
        ->check(CLI::Range(1, 2))
        ->capture_default_str();
    args->engine.add(*cmd);
    cmd->callback([args] { guarded([&] { runTriangulate(*args); }); });
}

}  // namespace dlab::cli
