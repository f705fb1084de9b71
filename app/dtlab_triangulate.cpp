// dtlab triangulate: a point file in, Triangle's .node/.ele/.neigh out (plus optional Voronoi,
// OFF, OBJ and SVG), ids in the input's index base.
#include "app/dtlab_common.h"

#include "core/engine/io_write.h"
#include "core/engine/mesh.h"
#include "core/engine/voronoi.h"

#include <chrono>
#include <filesystem>
#include <iostream>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace dlab::cli {

namespace {

struct TriangulateArgs {
    std::string input;
    std::string base;
    std::string voronoiSvg, svg, off, obj, voronoiBase;
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
};

Triangulated triangulate(const TriangulateArgs& args, std::vector<Vec2> points) {
    if (args.threads == 2) {
        if (auto joined = triangulateOnTwoCores(points, args.engine.options()))
            return {std::move(joined->mesh), std::move(joined->skipped), joined->stats, 2};
    }
    const auto made = args.engine.makeInserter(std::move(points));  // GL locators need a context
    made->run();
    Triangulated out{made->takeMesh(), made->skipped(), made->stats(), 1};
    return out;
}

std::string idList(const std::vector<std::int32_t>& ids, int base, std::size_t most) {
    std::string s;
    for (std::size_t i = 0; i < ids.size() && i < most; ++i)
        s += (i ? ", " : "") + std::to_string(ids[i] + base);
    if (ids.size() > most) s += ", ...";
    return s;
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
    try {
        checkOutputFiles(out, {args.input});
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

void runTriangulate(const TriangulateArgs& args) {
    returnLargeBuffersWhenFreed();
    checkOutputs(args);
    LoadedPoints loaded = loadPoints(args.input);
    const int base = loaded.indexBase;
    const std::size_t n = loaded.points.size();
    const auto t0 = std::chrono::steady_clock::now();
    const Triangulated result = triangulate(args, std::move(loaded.points));
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const Mesh& m = result.mesh;
    const bool exact = args.engine.options().boundary == Boundary::Exact;

    if (args.check) {
        ValidateOptions vo;
        vo.delaunay = exact;  // super mode does not promise it
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
    writeTextFiles(out, {args.input});  // all of them or none; never over the input

    if (args.quiet) return;
    const InsertStats& st = result.stats;
    std::cout << args.input << ": " << n << " points, " << m.numTriangles() << " triangles in "
              << ms << " ms (locate " << args.engine.locate << ", order " << args.engine.order
              << ", boundary " << args.engine.boundary
              << (result.threads == 2 ? ", two halves on two threads, joined" : "") << ")\n";
    if (!result.skipped.empty()) {
        std::cout << "  " << result.skipped.size()
                  << " duplicate point(s) skipped, the first occurrence kept: "
                  << idList(result.skipped, base, 10) << "\n";
    }
    if (m.numTriangles() == 0 && n > 0)
        std::cout << "  all points are collinear: no triangle exists\n";
    if (!exact) {
        std::cout << "  boundary=super: triangles near the hull may be missing or non-Delaunay "
                     "(the paper's "
                     "finite super-triangle)\n";
    }
    std::cout << "  " << st.flips << " flips, " << st.inCircleTests << " in-circle tests, "
              << st.walkSteps << " walk steps; wrote " << escapeControls(args.base)
              << ".node/.ele/.neigh\n";
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
