// dtlab diff-trace REF STUDENT: the first insertion after which a student's mesh differs from
// ours, and why (or, with --by-op, the first operation that differs).
// Exit status: 0 the runs agree, 1 they differ, 2 bad input.
#include "app/dtlab_common.h"

#include "core/engine/io_read.h"
#include "core/teaching/lesson.h"
#include "core/teaching/trace_diff.h"

#include <filesystem>
#include <iostream>

namespace dlab::cli {

namespace {

struct DiffArgs {
    std::string reference;
    std::string student;
    DiffOptions options;
};

// The reference: a trace file, or a lesson / assignment (.toml) whose run is traced here.
TraceFile loadReference(const std::string& path) {
    if (std::filesystem::path(path).extension() == ".toml") {
        try {
            const Lesson lesson = loadLesson(path);
            auto ins = makeInserter(lesson);
            return traceOfRun(*ins, path + " (our run)");
        } catch (const LessonError& e) {
            fail(e.what(), 2);
        }
    }
    return readTraceFile(path);
}

void runDiff(const DiffArgs& args) {
    TraceFile ref, student;
    try {
        ref = loadReference(args.reference);
        student = readTraceFile(args.student);
    } catch (const InputError& e) {
        fail(e.what(), 2);
    }
    TraceDiff diff;
    try {
        diff = diffTraces(ref, student, args.options);
    } catch (const std::bad_alloc&) {
        fail("not enough memory to compare " + escapeControls(args.reference) + " (" +
                 std::to_string(ref.ops.size()) + " operations) with " +
                 escapeControls(args.student) + " (" + std::to_string(student.ops.size()) +
                 " operations)",
             2);
    }
    std::cout << formatDiff(diff, ref, student, args.options);
    std::cout.flush();
    if (!diff.equal) throw Exit{1};
}

}  // namespace

void addDiffTrace(CLI::App& app) {
    auto args = std::make_shared<DiffArgs>();
    CLI::App* cmd =
        app.add_subcommand("diff-trace",
                           "Check a student's trace against ours: the first insertion after which "
                           "the student's triangles are wrong, and why (exit 0 same, 1 differ, 2 "
                           "bad input)");
    cmd->add_option(
           "reference", args->reference,
           "Our trace (.jsonl from dtlab trace), or a lesson/assignment (.toml) to run and trace")
        ->required();
    cmd->add_option("student", args->student, "The student's trace (.jsonl)")->required();
    cmd->add_flag("--by-op", args->options.byOp,
                  "Compare operation by operation (each split and flip, in our order), not only "
                  "the triangles after each insertion");
    cmd->add_flag("--all-ops", args->options.allOps,
                  "Compare every operation one to one, walk steps (LocateStep, Located) and "
                  "in-circle tests too, not only those that change the mesh; implies --by-op. A "
                  "trace written to the assignment has no such lines: it cannot pass");
    cmd->add_flag("--corners", args->options.corners,
                  "The student follows the paper's corner-reuse convention (see the assignment's "
                  "text): compare V (and O) corner by corner; implies --by-op");
    cmd->add_option("--context", args->options.context,
                    "Operations of context shown before the difference")
        ->check(CLI::Range(0, 100))
        ->capture_default_str();
    cmd->callback([args] { guarded([&] { runDiff(*args); }); });
}

}  // namespace dlab::cli
