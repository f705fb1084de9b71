// dtlab check MESH and dtlab repair MESH -o BASE: the exact check of a foreign triangulation
// (every problem named) and Lawson's flip algorithm on a valid one.
// Exit status: 0 valid Delaunay (check) or repaired (repair), 1 problems, 2 bad input.
#include "app/dtlab_common.h"

#include "core/engine/io_write.h"
#include "core/engine/mesh_diff.h"
#include "core/engine/mesh_read.h"
#include "core/engine/text_util.h"
#include "core/engine/triangulation_check.h"

#include <nlohmann/json.hpp>

#include <fstream>
#include <iostream>
#include <optional>

namespace dlab::cli {

namespace {

struct CheckArgs {
    std::string mesh;
    std::string points;
    bool json = false;
    bool all = false;
    bool diff = false;
};

struct RepairArgs {
    std::string mesh;
    std::string points;
    std::string output;
    std::string trace;
};

ImportedMesh loadMesh(const std::string& path, const std::string& points) {
    try {
        ImportedMesh im = readMeshFile(path, points);
        for (const std::string& w : im.warnings)
            std::cerr << "dtlab: warning: " << escapeControls(w) << "\n";
        return im;
    } catch (const InputError& e) {
        fail(e.what(), 2);
    }
}

CheckReport checkImported(const ImportedMesh& im) {
    CheckOptions o;
    o.hasOpposites = im.hasOpposites;
    o.indexBase = im.indexBase;
    return checkMesh(im.mesh, o);
}

nlohmann::json ids(const std::vector<std::int32_t>& v, int base) {
    nlohmann::json out = nlohmann::json::array();
    for (const std::int32_t x : v) out.push_back(std::int64_t{x} + base);
    return out;
}

nlohmann::json edgeList(const std::vector<MeshEdge>& edges, int base, bool all) {
    nlohmann::json out = nlohmann::json::array();
    for (const MeshEdge& e : edges) {
        if (!all && out.size() == 20) break;
        out.push_back({std::int64_t{e.first} + base, std::int64_t{e.second} + base});
    }
    return out;
}

void printJson(const CheckReport& r, const ImportedMesh& im, bool all, const DelaunayDiff* diff) {
    nlohmann::json j;
    j["summary"] = r.summary();
    j["format"] = im.format;
    j["points"] = r.points;
    j["used_points"] = r.usedPoints;
    j["triangles"] = r.triangles;
    j["valid_triangulation"] = r.isTriangulation();
    j["delaunay"] = r.isDelaunay();
    j["index_base"] = im.indexBase;
    j["overlap_search_cut"] = r.overlapSearchCut;
    nlohmann::json counts = nlohmann::json::object();
    for (const MeshProblem& p : r.problems) counts[toString(p.kind)] = r.count(p.kind);
    j["counts"] = counts;
    nlohmann::json list = nlohmann::json::array();
    for (const MeshProblem& p : r.problems) {
        if (!all && list.size() == 20) break;
        list.push_back({{"kind", toString(p.kind)},
                        {"message", p.message},
                        {"triangles", ids(p.triangles, im.indexBase)},
                        {"vertices", ids(p.vertices, im.indexBase)},
                        {"corners", ids(p.corners, 0)}});
    }
    j["problems"] = list;
    if (diff) {
        j["diff"] = {{"shared_edges", diff->sharedEdges},
                     {"only_in_mesh", diff->onlyGiven.size()},
                     {"only_in_delaunay", diff->onlyDelaunay.size()},
                     {"cocircular", diff->cocircular},
                     {"edges_only_in_mesh", edgeList(diff->onlyGiven, im.indexBase, all)},
                     {"edges_only_in_delaunay", edgeList(diff->onlyDelaunay, im.indexBase, all)}};
    }
    std::cout << j.dump(2) << "\n";
}

void printList(const std::vector<const MeshProblem*>& list, bool all, std::ostream& os) {
    std::size_t shown = 0;
    for (const MeshProblem* p : list) {
        if (!all && shown == 20) {
            os << "  ... " << list.size() - shown << " more (--all lists every one)\n";
            break;
        }
        os << "  " << toString(p->kind) << ": " << escapeControls(p->message) << "\n";
        ++shown;
    }
}

void printEdges(const char* label, const std::vector<MeshEdge>& edges, int base, bool all) {
    std::size_t shown = 0;
    for (const MeshEdge& e : edges) {
        if (!all && shown == 20) {
            std::cout << "  ... " << edges.size() - shown << " more (--all lists every one)\n";
            break;
        }
        std::cout << "  " << label << ": " << e.first + base << "-" << e.second + base << "\n";
        ++shown;
    }
}

void printDiff(const DelaunayDiff& d, const ImportedMesh& im, bool all) {
    if (d.same()) {
        std::cout << "the same edges as the Delaunay triangulation of these points ("
                  << d.sharedEdges << ")\n";
        return;
    }
    auto edges = [](std::size_t k) { return std::to_string(k) + (k == 1 ? " edge" : " edges"); };
    std::cout << "against the Delaunay triangulation of these points: " << edges(d.onlyGiven.size())
              << " only in this mesh, " << d.onlyDelaunay.size()
              << " only in the Delaunay triangulation, " << d.sharedEdges << " shared";
    if (d.cocircular > 0) {
        std::cout << "; " << d.cocircular << " of the Delaunay triangulation's have their four "
                  << "points on one circle, where either diagonal is Delaunay";
    }
    std::cout << "\n";
    printEdges("only in this mesh", d.onlyGiven, im.indexBase, all);
    printEdges("only in the Delaunay triangulation", d.onlyDelaunay, im.indexBase, all);
}

void runCheck(const CheckArgs& args) {
    const ImportedMesh im = loadMesh(args.mesh, args.points);
    const CheckReport r = checkImported(im);
    std::optional<DelaunayDiff> diff;
    if (args.diff && r.isTriangulation()) diff = diffWithDelaunay(im.mesh);
    if (args.json) {
        printJson(r, im, args.all, diff ? &*diff : nullptr);
    } else {
        std::cout << escapeControls(args.mesh) << " (" << im.format << "): " << r.summary() << "\n";
        std::vector<const MeshProblem*> list;
        for (const MeshProblem& p : r.problems) list.push_back(&p);
        printList(list, args.all, std::cout);
        if (r.overlapSearchCut)
            std::cout << "  (the search for overlapping pairs stopped early: the list of "
                         "overlaps may be incomplete)\n";
        if (diff) printDiff(*diff, im, args.all);
        if (args.diff && !diff)
            std::cout << "no comparison with the Delaunay triangulation: this is not a valid "
                         "triangulation of its points\n";
    }
    std::cout.flush();
    if (!r.isDelaunay()) throw Exit{1};
}

void writeTrace(const std::string& path, const RepairResult& r, int base,
                const std::vector<std::string>& inputs) {
    writeTextFiles({{path,
                     [&](std::ostream& os) {
                         std::int64_t i = 0;
                         for (const FlipRecord& f : r.flips) {
                             const nlohmann::json j = {
                                 {"i", i++},
                                 {"op", "Flip"},
                                 {"a", f.corner},
                                 {"b", f.opposite},
                                 {"removed", ids({f.removed[0], f.removed[1]}, base)},
                                 {"added", ids({f.added[0], f.added[1]}, base)}};
                             os << j.dump() << "\n";
                         }
                     }}},
                   inputs);
}

void runRepair(const RepairArgs& args) {
    const ImportedMesh im = loadMesh(args.mesh, args.points);
    const std::vector<OutputFile> probe = {
        {args.output + ".node", {}}, {args.output + ".ele", {}}, {args.output + ".neigh", {}}};
    checkOutputFiles(probe, im.inputs);  // refuse before any work
    const CheckReport r = checkImported(im);
    if (!r.isTriangulation()) {
        std::cerr << "dtlab: error: " << escapeControls(args.mesh)
                  << ": cannot repair by flips: " << r.summary() << "\n";
        std::vector<const MeshProblem*> blocking;
        for (const MeshProblem& p : r.problems)
            if (blocksRepair(p.kind)) blocking.push_back(&p);
        printList(blocking, false, std::cerr);
        throw Exit{1};
    }
    const RepairResult fixed = repairByFlips(im.mesh, r);
    const int base = im.indexBase;
    const Mesh& m = fixed.mesh;
    writeTextFiles({{args.output + ".node", [&](std::ostream& os) { writeNode(os, m.G, base); }},
                    {args.output + ".ele", [&](std::ostream& os) { writeEle(os, m, base); }},
                    {args.output + ".neigh", [&](std::ostream& os) { writeNeigh(os, m, base); }}},
                   im.inputs);
    if (!args.trace.empty()) writeTrace(args.trace, fixed, base, im.inputs);
    CheckOptions o;
    o.indexBase = base;
    const CheckReport after = checkMesh(m, o);
    std::cout << escapeControls(args.mesh) << ": " << fixed.flips.size() << " flips ("
              << fixed.incircleTests << " in-circle tests; at most quadratic in the points); "
              << escapeControls(args.output) << ".node/.ele/.neigh: " << after.summary() << "\n";
    if (!after.isTriangulation() || after.count(MeshProblem::Kind::NotDelaunay) != 0) throw Exit{1};
}

}  // namespace

void addCheck(CLI::App& app) {
    auto args = std::make_shared<CheckArgs>();
    CLI::App* cmd = app.add_subcommand(
        "check",
        "Check a triangulation exactly: every problem named (exit 0 valid Delaunay, 1 problems, 2 "
        "bad input). Reads .ele (+ .node, .neigh beside it), .off, .obj, .corners, .json (corner "
        "table or Delaunator)");
    cmd->add_option("mesh", args->mesh, "The mesh file")->required();
    cmd->add_option("--points", args->points,
                    "The points from this file (an .ele's instead of the .node beside it)");
    cmd->add_flag("--json", args->json, "The report as JSON");
    cmd->add_flag("--all", args->all, "List every problem (the first 20 by default)");
    cmd->add_flag("--diff", args->diff,
                  "Compare the edges with the Delaunay triangulation of the same points");
    cmd->callback([args] { guarded([&] { runCheck(*args); }); });

    auto rep = std::make_shared<RepairArgs>();
    CLI::App* r = app.add_subcommand(
        "repair",
        "Lawson's flip algorithm: a valid triangulation made Delaunay by flips, written as "
        "BASE.node/.ele/.neigh with the input's vertex numbering (exit 1 when the mesh is not a "
        "valid triangulation: the problems that block the repair are listed)");
    r->add_option("mesh", rep->mesh, "The mesh file")->required();
    r->add_option("-o,--output", rep->output, "Base name of the repaired mesh")->required();
    r->add_option("--points", rep->points, "The points from this file");
    r->add_option("--trace", rep->trace, "Write the flips as JSON Lines");
    r->callback([rep] { guarded([&] { runRepair(*rep); }); });
}

}  // namespace dlab::cli
