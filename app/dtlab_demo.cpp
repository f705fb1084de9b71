// dtlab demo: the built-in demo point set, narrated one operation at a time, then stepped all
// the way back to the empty start and checked; writes the result (SVG, Triangle files, trace).
#include "app/dtlab_common.h"

#include "core/engine/generators.h"
#include "core/engine/io_write.h"
#include "core/teaching/describe.h"
#include "core/teaching/trace.h"

#include <filesystem>
#include <iostream>

namespace dlab::cli {

namespace {

struct DemoArgs {
    std::string outDir = "demo-out";
    bool quiet = false;
    EngineFlags engine;
};

void runDemo(const DemoArgs& args) {
    const auto made = args.engine.makeInserter(demoPoints());  // GL locators need a context
    Inserter& ins = *made;
    const Mesh empty = ins.mesh();
    Journal journal(ins);
    std::error_code ec;
    std::filesystem::create_directories(args.outDir, ec);
    if (ec) fail("cannot create directory " + args.outDir + ": " + ec.message());

    const std::string tracePath = args.outDir + "/demo.trace.jsonl";
    std::size_t flips = 0, tests = 0;
    writeTextFile(tracePath, [&](std::ostream& os) {
        while (const Op* op = journal.forward()) {
            const std::size_t i = journal.position() - 1;
            if (!args.quiet)
                std::cout << "[" << i << "] " << toString(op->type) << ": " << describe(*op, ins)
                          << "\n";
            os << toJsonLine(traceRecord(journal, i, ins.mesh())) << '\n';
            flips += op->type == OpType::Flip;
            tests += op->type == OpType::InCircleTest;
        }
    });
    const Mesh result = ins.mesh();
    const auto bad = validate(result);
    if (!bad.empty())
        fail("demo result is invalid at corner " + std::to_string(bad[0].corner) + ": " +
             bad[0].message);

    // Back to the start: every V/O cell must be restored bit for bit, then forward again.
    const std::size_t total = journal.position();
    while (journal.back()) {}
    const Mesh& start = ins.mesh();
    if (start.V != empty.V || start.O != empty.O || start.G.size() != empty.G.size()) {
        fail("stepping back to the start did not restore the initial corner table");
    }
    journal.seek(total);
    if (ins.mesh().V != result.V || ins.mesh().O != result.O)
        fail("replaying the journal gave a different mesh");

    SvgOptions so;
    so.voronoi = true;
    so.circumcircles = false;
    so.title = "Delaunay Lab demo: " + std::to_string(result.numTriangles()) +
               " triangles and their Voronoi diagram";
    writeTextFiles({
        {args.outDir + "/demo.svg", [&](std::ostream& os) { writeSvg(os, result, so); }, {}},
        {args.outDir + "/demo.node", [&](std::ostream& os) { writeNode(os, result.G, 0); }, {}},
        {args.outDir + "/demo.ele", [&](std::ostream& os) { writeEle(os, result, 0); }, {}},
        {args.outDir + "/demo.neigh", [&](std::ostream& os) { writeNeigh(os, result, 0); }, {}},
    });

    std::cout
        << "demo: " << result.numTriangles() << " triangles, " << total << " operations (" << tests
        << " in-circle tests, " << flips << " flips, " << ins.skipped().size()
        << " duplicate skipped); stepped back to the empty start and forward again: identical\n"
        << "wrote " << escapeControls(args.outDir)
        << "/demo.svg, demo.node/.ele/.neigh and demo.trace.jsonl\n";
}

}  // namespace

void addDemo(CLI::App& app) {
    auto args = std::make_shared<DemoArgs>();
    CLI::App* cmd = app.add_subcommand(
        "demo", "Narrate the built-in demo one operation at a time and write its result");
    cmd->add_option("-o,--output", args->outDir, "Output directory")->capture_default_str();
    cmd->add_flag("-q,--quiet", args->quiet, "Do not narrate each operation");
    args->engine.add(*cmd);
    cmd->callback([args] { guarded([&] { runDemo(*args); }); });
}

}  // namespace dlab::cli
