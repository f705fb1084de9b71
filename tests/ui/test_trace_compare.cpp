// A student's trace in the GUI: opened like any file, it is compared with our run on
// the same points and options; the view goes to the first difference, and both runs step side by
// side from there. The Open dialog, the notice for a trace of other points and the history offer
// at 1280x720 and 1600x1000.
#include "core/engine/generators.h"
#include "core/engine/inserter.h"
#include "core/teaching/trace.h"
#include "tests/ui/ui_harness.h"
#include "ui/files/files.h"
#include "ui/panels/panels.h"
#include "ui/platform/keys.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
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

// What a user sees at the two common window sizes: the Open dialog listing a student's trace,
// the one-line notice when the trace belongs to other points, and the history offer for 30,000
// points in input order: each on the screen whole (inside the window) and drawn in its colours.
// DLAB_UI_SHOTS=FOLDER keeps the screenshots there.
TEST(TraceCompare, TheDialogTheNoticeAndTheHistoryOfferAtTwoWindowSizes) {
    const fs::path dir =
        fs::temp_directory_path() / ("dlab_trace_shots_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const char* keep = std::getenv("DLAB_UI_SHOTS");
    for (const auto& [w, hgt] : {std::pair{1280, 720}, std::pair{1600, 1000}}) {
        UiHarness h(w, hgt);
        auto& st = h.state();
        const std::string size = std::to_string(w) + "x" + std::to_string(hgt);
        // A trace of 41 vertices (the assignment's), opened on the demo's 12 points.
        std::vector<std::string> lines{
            "{\"op\":\"Start\",\"triangles\":[[0,38,39,40]]}",
            "{\"op\":\"Split\",\"triangles\":[[0,0,38,39],[1,0,39,40],[2,0,40,38]]}"};
        const std::string trace = writeLines("dlab_shot_student.jsonl", lines);
        fs::copy_file(trace, dir / "student.jsonl", fs::copy_options::overwrite_existing);
        std::ofstream(dir / "points.csv") << "0,0\n1,0\n0,1\n";
        h.press(dlab::ui::key::letter('O'), false, /*ctrl=*/true);
        st.files.dialogPath = (dir / "x").string();
        h.frames(3);
        const auto row = h.rect("dialog-file:student.jsonl");
        EXPECT_TRUE(row[0] >= 0 && row[2] <= w && row[1] >= 0 && row[3] <= hgt) << size;
        const std::string dialogShot = (dir / ("open_dialog_" + size + ".png")).string();
        ASSERT_TRUE(dlab::ui::saveScreenshotFile(h.gui(), dialogShot));
        // Opened from the dialog: the notice says what to load; the dialog stays for another.
        h.clickItem("dialog-file:student.jsonl");
        h.clickItem("dialog-ok");
        h.frames(3);
        EXPECT_FALSE(st.traceCompare.student);
        EXPECT_NE(st.files.notice.find("student.jsonl uses vertices up to 40, but the points "
                                       "loaded here (built-in demo) are 12"),
                  std::string::npos)
            << st.files.notice;
        const auto notice = h.rect("file-notice");
        EXPECT_TRUE(notice[0] >= 0 && notice[2] <= w && notice[3] <= hgt) << size;
        EXPECT_GT(h.countColour(notice, {191, 20, 26}), 1000) << "the notice's red, " << size;
        const std::string noticeShot = (dir / ("trace_notice_" + size + ".png")).string();
        ASSERT_TRUE(dlab::ui::saveScreenshotFile(h.gui(), noticeShot));
        h.clickItem("dialog-cancel");
        h.clickItem("notice-dismiss");
        EXPECT_TRUE(st.files.notice.empty());
        dlab::InsertOptions input;
        input.order = dlab::OrderKind::Input;
        ASSERT_TRUE(st.setUserOptions(input));
        ASSERT_TRUE(st.loadUserPoints(dlab::generatePoints(dlab::Generator::Uniform, 30000, 2),
                                      "uniform 30000"));
        h.frames(3);
        ASSERT_TRUE(st.historyOffer.open) << size;
        const auto offer = h.rect("history-offer"), canvas = h.rect("canvas");
        EXPECT_TRUE(offer[0] >= canvas[0] && offer[2] <= canvas[2] && offer[1] >= canvas[1] &&
                    offer[3] <= canvas[3])
            << size;
        for (const char* b : {"history-brio", "history-batch", "history-keep"}) {
            const auto r = h.rect(b);
            EXPECT_TRUE(r[0] >= offer[0] && r[2] <= offer[2] && r[3] <= offer[3]) << b << size;
        }
        const std::string offerShot = (dir / ("history_offer_" + size + ".png")).string();
        ASSERT_TRUE(dlab::ui::saveScreenshotFile(h.gui(), offerShot));
        if (keep) {
            for (const std::string& s : {dialogShot, noticeShot, offerShot})
                fs::copy_file(s, fs::path(keep) / fs::path(s).filename(),
                              fs::copy_options::overwrite_existing);
        }
    }
    fs::remove_all(dir);
}
