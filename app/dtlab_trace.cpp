// dtlab trace: one JSON object per operation (JSON Lines), as documented in core/teaching/trace.h.
#include "app/dtlab_common.h"

#include "core/engine/io_write.h"
#include "core/teaching/trace.h"
#include "core/teaching/trace_diff.h"

#include <iostream>

namespace dlab::cli {

namespace {

// What shortens a run's history: the brio order walks far less, unless it is the order already.
std::string shorterRun(const Inserter& ins) {
    return ins.options().order == OrderKind::Brio ? "use --limit or fewer points"
                                                  : "use --limit, fewer points, or the brio order "
                                                    "(it walks far less)";
}

struct TraceArgs {
    std::string input;
    std::string output;
    long long limit = -1;
    EngineFlags engine;
};

void runTrace(const TraceArgs& args) {
    try {
        checkOutputFiles({{args.output, {}}}, {args.input});
    } catch (const std::runtime_error& e) {
        fail(e.what(), 2);
    }
    LoadedPoints loaded = loadPoints(args.input);
    const auto made =
        args.engine.makeInserter(std::move(loaded.points));  // GL locators need a context
    Inserter& ins = *made;
    Journal journal(ins);
    long long count = 0;
    std::size_t bytes = 0;
    writeTextFile(args.output, [&](std::ostream& out) {
        while ((args.limit < 0 || count < args.limit) && journal.forward()) {
            const std::string line =
                toJsonLine(traceRecord(journal, journal.position() - 1, ins.mesh())) + '\n';
            bytes += line.size();
            ++count;
            // A trace that diff-trace would refuse is not written either.
            if (bytes > kMaxTraceFileBytes || static_cast<std::size_t>(count) > kMaxTraceOps) {
                fail("the trace passes what diff-trace reads (" +
                     std::to_string(kMaxTraceFileBytes >> 20) + " MiB, " +
                     std::to_string(kMaxTraceOps) + " operations) at operation " +
                     std::to_string(count) + ": nothing written; " + shorterRun(ins));
            }
            out << line;
        }
        if (journal.budgetReached()) {  // no file rather than a trace cut short silently
            fail("the run passes the history's memory budget (" +
                 std::to_string(journal.budget() >> 20) + " MiB) after " + std::to_string(count) +
                 " operations: nothing written; " + shorterRun(ins));
        }
    });
    std::cout << "wrote " << count << " operations to " << escapeControls(args.output)
              << (ins.done() ? "" : " (stopped at --limit before the end)") << "\n";
}

}  // namespace

void addTrace(CLI::App& app) {
    auto args = std::make_shared<TraceArgs>();
    CLI::App* cmd = app.add_subcommand("trace", "Write every operation of a run as JSON Lines");
    cmd->add_option("input", args->input, "Point file (.node, .csv, .xy, .pts)")->required();
    cmd->add_option("-o,--output", args->output, "Trace file (.jsonl)")->required();
    cmd->add_option("--limit", args->limit, "Stop after this many operations (default: none)")
        ->check(CLI::Validator(
            [](std::string& v) {
                return !v.empty() && v[0] == '-' ? "--limit must be 0 or more, not " + v
                                                 : std::string();
            },
            "N >= 0"));
    args->engine.add(*cmd);
    cmd->callback([args] { guarded([&] { runTrace(*args); }); });
}

}  // namespace dlab::cli
