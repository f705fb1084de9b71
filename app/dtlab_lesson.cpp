// dtlab lesson check | show: runs lessons headlessly (every stop reached, every answer computed)
// and prints a lesson's answer key.
#include "app/dtlab_common.h"

#include "core/engine/text_util.h"
#include "core/teaching/lesson.h"

#include <iostream>

namespace dlab::cli {

namespace {

struct LessonArgs {
    std::vector<std::string> files;
    std::string file;
    bool tables = false;
};

// The corner table at a stop, one triangle per line: "t 3: V 4 2 5 | O 7 -1 12".
void printTables(const Inserter& ins) {
    const Mesh& m = ins.mesh();
    for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
        std::cout << "  t " << t << " (corners " << 3 * t << ".." << 3 * t + 2 << "): V";
        for (int k = 0; k < 3; ++k) {
            const std::int32_t v = m.V[3 * t + k];
            std::cout << ' '
                      << (ins.isVirtual(v) && !ins.done()
                              ? (ins.options().boundary == Boundary::Exact
                                     ? "g"
                                     : "s" + std::to_string(v - ins.numInput()))
                              : std::to_string(v));
        }
        std::cout << " | O";
        for (int k = 0; k < 3; ++k) std::cout << ' ' << m.O[3 * t + k];
        std::cout << "\n";
    }
}

std::size_t questions(const Lesson& lesson) {
    std::size_t n = 0;
    for (const LessonStop& s : lesson.stops) n += !s.question.empty();
    return n;
}

void runCheck(const LessonArgs& args) {
    int failed = 0;
    for (const std::string& path : args.files) {
        try {
            const Lesson lesson = loadLesson(path);
            const LessonPlan plan = planLesson(lesson);
            std::cout << escapeControls(path) << ": ok: \"" << escapeControls(lesson.title)
                      << "\" (" << (lesson.assignment ? "assignment, " : "") << lesson.points.size()
                      << " points, " << lesson.stops.size() << " stops, " << questions(lesson)
                      << " questions, " << plan.totalOps << " operations)\n";
        } catch (const LessonError& e) {
            std::cerr << "dtlab: error: " << escapeControls(e.what()) << "\n";
            ++failed;
        }
    }
    std::cout.flush();
    if (failed)
        fail(std::to_string(failed) + " of " + std::to_string(args.files.size()) +
             " lessons failed");
}

void runShow(const LessonArgs& args) {
    try {
        const Lesson lesson = loadLesson(args.file);
        const LessonPlan plan = planLesson(lesson);
        auto ins = makeInserter(lesson);
        Journal journal(*ins);
        // Lesson files are untrusted: no control character reaches the terminal.
        const auto text = [](std::string_view s) { return escapeControlsKeepLines(s); };
        std::cout << "# " << escapeControls(lesson.title) << "\n"
                  << text(lesson.summary) << "\n"
                  << "options: boundary " << toString(lesson.options.boundary) << ", locator "
                  << toString(lesson.options.locator) << ", order "
                  << toString(lesson.options.order) << ", seed " << lesson.options.seed << "; "
                  << lesson.points.size() << " points"
                  << (lesson.pointsFile.empty() ? "" : " from " + escapeControls(lesson.pointsFile))
                  << "; " << plan.totalOps << " operations\n";
        if (!lesson.text.empty())
            std::cout << "\n"
                      << escapeControlsKeepLines(lesson.text)
                      << (lesson.text.back() == '\n' ? "" : "\n");
        for (std::size_t k = 0; k < lesson.stops.size(); ++k) {
            const LessonStop& s = lesson.stops[k];
            const StopState& st = plan.stops[k];
            std::cout << "\n## stop " << k + 1 << " (line " << s.line << "): "
                      << (s.runTo ? "run_to " + toString(*s.runTo) +
                                        (s.count > 1 ? " x" + std::to_string(s.count) : "")
                                  : std::string("stay"))
                      << " -> op " << st.position << "\n";
            if (!st.caption.empty()) std::cout << "caption: " << text(st.caption) << "\n";
            if (args.tables) {
                journal.seek(st.position);
                printTables(*ins);
            }
            if (st.selected != kNone) std::cout << "selected corner: " << st.selected << "\n";
            if (!s.text.empty()) std::cout << text(s.text) << (s.text.back() == '\n' ? "" : "\n");
            if (!s.question.empty()) {
                std::cout << "Q: " << text(s.question) << "\nA: " << text(st.answer->display())
                          << "   (" << text(s.answer) << ")\n";
            }
        }
    } catch (const LessonError& e) {
        fail(e.what(), 2);  // bad input
    }
}

}  // namespace

void addLesson(CLI::App& app) {
    auto args = std::make_shared<LessonArgs>();
    CLI::App* cmd = app.add_subcommand("lesson", "Check lessons, or print a lesson's answer key");
    cmd->require_subcommand(1);
    CLI::App* check = cmd->add_subcommand("check",
                                          "Run every lesson to its end headlessly: each stop "
                                          "reached in order, each answer computable");
    check->add_option("lessons", args->files, "Lesson files (.toml)")->required();
    check->callback([args] { guarded([&] { runCheck(*args); }); });
    CLI::App* show =
        cmd->add_subcommand("show", "Print a lesson stop by stop with the engine's answers");
    show->add_option("lesson", args->file, "Lesson file (.toml)")->required();
    show->add_flag("--tables", args->tables,
                   "Also print the corner table (V and O per triangle) at each stop");
    show->callback([args] { guarded([&] { runShow(*args); }); });
}

}  // namespace dlab::cli
