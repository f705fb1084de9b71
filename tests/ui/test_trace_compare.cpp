// A student's trace in the GUI: opened like any file, it is compared with our run on
// the same points and options; the view goes to the first difference, and both runs step side by
// side from there.
#include "core/engine/inserter.h"
#include "core/teaching/trace.h"
#include "tests/ui/ui_harness.h"
#include "ui/files/files.h"
#include "ui/panels/panels.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using dlab::test::UiHarness;
namespace fs = std::filesystem;

namespace {

// Our run on the GUI's current points and options, as dtlab trace writes it: one line per op.
std::vector<std::string> traceLines(const dlab::ui::AppState& st) {
    dlab::Inserter ins(st.engine.points(), st.engine.options());
    dlab::Journal journal(ins);
    std::vector<std::string> lines;
    while (journal.forward()) {
        lines.push_back(
            dlab::toJsonLine(dlab::traceRecord(journal, journal.position() - 1, ins.mesh())));
    }
    return lines;
}

std::string writeLines(const std::string& name, const std::vector<std::string>& lines) {
    const fs::path p = fs::temp_directory_path() / name;
    std::ofstream out(p);
    for (const std::string& l : lines) out << l << "\n";
    return p.string();
}

}  // namespace

TEST(TraceCompare, AStudentWhoMissedAFlipIsShownAtThatInsertionAndBothRunsStepTogether) {
    UiHarness h;
    auto& st = h.state();
    std::vector<std::string> lines = traceLines(st);
    // The student skipped the first flip of the run.
    std::size_t flip = 0;
    while (flip < lines.size() && lines[flip].find("\"op\":\"Flip\"") == std::string::npos) ++flip;
    ASSERT_LT(flip, lines.size());
    std::vector<std::string> student = lines;
    student.erase(student.begin() + static_cast<std::ptrdiff_t>(flip));
    const std::string path = writeLines("dlab_student_missed_flip.jsonl", student);
    const std::vector<dlab::Vec2> points = st.engine.points();

    ASSERT_TRUE(dlab::ui::openFile(st, path)) << st.messages.back().text;
    h.frames(3);
    const auto& tc = st.traceCompare;
    ASSERT_TRUE(tc.student);
    EXPECT_FALSE(tc.diff.equal);
    // Named at the insertion that flip belongs to: the canvas shows our mesh after it.
    std::size_t stepEnd = flip + 1;
    while (stepEnd < lines.size() && lines[stepEnd].find("\"op\":\"Split") == std::string::npos &&
           lines[stepEnd].find("\"op\":\"SkipDuplicate") == std::string::npos &&
           lines[stepEnd].find("\"op\":\"Finalize") == std::string::npos)
        ++stepEnd;
    EXPECT_GT(tc.diff.insertion, 0) << tc.diff.what;
    EXPECT_GE(tc.diff.refOp, flip) << tc.diff.what;
    EXPECT_LT(tc.diff.refOp, stepEnd) << tc.diff.what;
    EXPECT_TRUE(st.engine.current()->type == dlab::OpType::Flip ||
                st.engine.current()->type == dlab::OpType::Split ||
                st.engine.current()->type == dlab::OpType::SplitEdge)
        << "the canvas shows our mesh as that insertion left it";
    EXPECT_EQ(st.engine.position(), tc.diff.refOp + 1);
    EXPECT_EQ(st.engine.points(), points);  // nothing else changed
    EXPECT_EQ(st.messages.back().level, dlab::ui::Message::Level::Warning);
    EXPECT_NE(st.messages.back().text.find("dlab_student_missed_flip.jsonl"), std::string::npos);
    // The tab is on show, and the student's triangles that are not ours are drawn in magenta.
    ASSERT_TRUE(st.itemRects.count("trace-forward"));
    EXPECT_GT(h.countColour(h.rect("canvas"), {200, 0, 160}), 50);

    // Both forward: each run advances to its next mesh change.
    const std::size_t ours = st.engine.position(), theirs = tc.studentPos;
    h.clickItem("trace-forward");
    EXPECT_GT(st.engine.position(), ours);
    EXPECT_GT(tc.studentPos, theirs);
    EXPECT_TRUE(st.engine.current()->type == dlab::OpType::Flip ||
                st.engine.current()->type == dlab::OpType::Split ||
                st.engine.current()->type == dlab::OpType::SplitEdge ||
                st.engine.current()->type == dlab::OpType::Finalize);
    h.clickItem("trace-back");
    EXPECT_EQ(st.engine.position(), ours);
    EXPECT_EQ(tc.studentPos, theirs);
    h.clickItem("trace-forward");
    h.clickItem("trace-difference");
    EXPECT_EQ(st.engine.position(), tc.diff.refOp + 1);
}

TEST(TraceCompare, TheSameRunIsSaidToBeTheSame) {
    UiHarness h;
    auto& st = h.state();
    const std::string path = writeLines("dlab_student_same.jsonl", traceLines(st));
    ASSERT_TRUE(dlab::ui::openFile(st, path));
    EXPECT_TRUE(st.traceCompare.diff.equal) << st.traceCompare.diff.what;
    EXPECT_TRUE(st.engine.atEnd());
    EXPECT_NE(st.messages.back().text.find("the same run"), std::string::npos)
        << st.messages.back().text;
    h.frames(2);
    EXPECT_EQ(h.countColour(h.rect("canvas"), {200, 0, 160}), 0);
}

TEST(TraceCompare, ABadTraceChangesNothingAndNamesTheFileAndLine) {
    UiHarness h;
    auto& st = h.state();
    st.engine.seek(10);
    const std::string path = writeLines(
        "dlab_student_bad.jsonl", {"{\"op\":\"Split\",\"triangles\":[[0,0,1,2]]}", "{\"op\": 17}"});
    EXPECT_FALSE(dlab::ui::openFile(st, path));
    EXPECT_FALSE(st.traceCompare.student);
    EXPECT_EQ(st.engine.position(), 10u);
    EXPECT_NE(st.messages.back().text.find("dlab_student_bad.jsonl:2"), std::string::npos)
        << st.messages.back().text;
    EXPECT_EQ(st.messages.back().level, dlab::ui::Message::Level::Error);
}
