// dtlab gen: writes one of the built-in point sets (uniform, clusters, grid, ...) to a file.
#include "app/dtlab_common.h"

#include "core/engine/generators.h"
#include "core/engine/io_read.h"
#include "core/engine/io_write.h"

#include <charconv>
#include <filesystem>
#include <iostream>

namespace dlab::cli {

namespace {

struct GenArgs {
    std::string kind;
    long long n = 0;
    std::uint64_t seed = 1;
    std::string output;
};

constexpr const char* kFlipWorstCase = "flip-worst-case";

// BASE.node and BASE.ele (BASE: the output less a .node or .ele ending), as one set.
void writeFlipWorstCase(const GenArgs& args) {
    std::string base = args.output;
    for (const char* ext : {".ele", ".node"})
        if (base.size() > std::string(ext).size() && base.ends_with(ext))
            base.resize(base.size() - std::string(ext).size());
    const auto n = static_cast<std::size_t>(args.n);
    if (n < 6 || n % 2 != 0 || n > 65536)
        fail(std::string(kFlipWorstCase) + " " + std::to_string(args.n) +
                 ": give an even number of points from 6 to 65536 (two chains of n/2)",
             2);
    const Mesh mesh = flipWorstCase(n);
    writeTextFiles({{base + ".node", [&](std::ostream& os) { writeNode(os, mesh.G, 0); }},
                    {base + ".ele", [&](std::ostream& os) { writeEle(os, mesh, 0); }}},
                   {});
    std::cout << "wrote " << mesh.numVertices() << " points and " << mesh.numTriangles()
              << " triangles (" << kFlipWorstCase
              << ": Lawson's flips need on the order of n^2/8) to " << escapeControls(base)
              << ".node/.ele\n";
}

void runGen(const GenArgs& args) {
    if (args.kind == kFlipWorstCase) return writeFlipWorstCase(args);
    const auto kind = parseGenerator(args.kind);
    if (!kind) fail("unknown point set '" + args.kind + "' (one of: " + generatorNames() + ")", 2);
    const std::vector<Vec2> pts =
        generatePoints(*kind, static_cast<std::size_t>(args.n), args.seed);
    std::string ext = std::filesystem::path(args.output).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (args.output.empty() || std::filesystem::path(args.output).filename().empty())
        fail("-o \"" + args.output + "\": give a file name for the points, e.g. -o points.node", 2);
    writeTextFile(args.output, [&](std::ostream& os) {
        if (ext == ".csv" || ext == ".xy" || ext == ".txt" || ext == ".pts") {
            std::string s;
            if (ext == ".pts") s = std::to_string(pts.size()) + "\n";
            if (ext == ".csv") s = "x,y\n";
            for (const Vec2& p : pts) {
                appendShortest(s, p.x);
                s += ext == ".xy" || ext == ".txt" ? ' ' : ',';
                appendShortest(s, p.y);
                s += '\n';
            }
            os << s;
        } else {
            writeNode(os, pts, 0);
        }
    });
    std::cout << "wrote " << pts.size() << " points (" << toString(*kind) << ", seed " << args.seed
              << ") to " << escapeControls(args.output) << "\n";
}

}  // namespace

void addGen(CLI::App& app) {
    auto args = std::make_shared<GenArgs>();
    CLI::App* cmd =
        app.add_subcommand("gen",
                           "Write a built-in point set (.node; .csv/.xy/.pts by extension), or "
                           "flip-worst-case: a mesh (BASE.node/.ele) that Lawson's flips need "
                           "quadratically many flips to repair");
    cmd->add_option("kind", args->kind,
                    "Point set: " + generatorNames() + "; or the mesh " + kFlipWorstCase)
        ->required();
    cmd->add_option("n", args->n, "Number of points (1 to 2^25)")
        ->required()
        ->check(CLI::Range(1LL, static_cast<long long>(kMaxPoints)));
    cmd->add_option("--seed", args->seed, "Random seed")->capture_default_str();
    cmd->add_option("-o,--output", args->output, "Output file")->required();
    cmd->callback([args] { guarded([&] { runGen(*args); }); });
}

}  // namespace dlab::cli
