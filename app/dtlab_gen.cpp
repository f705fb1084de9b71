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

void runGen(const GenArgs& args) {
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
        app.add_subcommand("gen", "Write a built-in point set (.node; .csv/.xy/.pts by extension)");
    cmd->add_option("kind", args->kind, "Point set: " + generatorNames())->required();
    cmd->add_option("n", args->n, "Number of points (1 to 2^25)")
        ->required()
        ->check(CLI::Range(1LL, static_cast<long long>(kMaxPoints)));
    cmd->add_option("--seed", args->seed, "Random seed")->capture_default_str();
    cmd->add_option("-o,--output", args->output, "Output file")->required();
    cmd->callback([args] { guarded([&] { runGen(*args); }); });
}

}  // namespace dlab::cli
