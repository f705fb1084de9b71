// The user's options against the demo's and the lessons': a file opens with the user's own
// options, a closed lesson gives them back; a student's trace in the Open dialog and on points it
// does not belong to; a run whose history would pass the op limit is offered BRIO order or a run
// without a history, and stepping is never switched off without a word.
#include "core/engine/generators.h"
#include "core/engine/mesh.h"
#include "core/teaching/lesson.h"
#include "core/teaching/trace.h"
#include "tests/ui/ui_harness.h"
#include "ui/files/files.h"
#include "ui/panels/panels.h"
#include "ui/platform/keys.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

using dlab::test::TempDir;
using dlab::test::UiHarness;
namespace key = dlab::ui::key;

namespace {

const std::string kAssignment =
    std::string(DLAB_SOURCE_DIR) + "/lessons/10_assignment_insertion.toml";

void writeCsv(const std::string& path, const std::vector<dlab::Vec2>& pts) {
    std::ofstream out(path);
    out.precision(17);
    for (const dlab::Vec2& p : pts) out << p.x << "," << p.y << "\n";
}

// Chooses a value of a toolbar combo ("Order", "random") as a user does: two clicks.
void choose(UiHarness& h, const std::string& combo, const std::string& value) {
    h.clickItem(combo);
    h.frames(1);
    h.clickItem(combo + ":" + value);
    h.frames(1);
}

bool logged(const dlab::ui::AppState& st, const std::string& text) {
    for (const auto& m : st.messages) {
        if (m.text.find(text) != std::string::npos) return true;
    }
    return false;
}

// Every op of a run, counted by recording it whole.
std::size_t recordedOps(const std::vector<dlab::Vec2>& pts, const dlab::InsertOptions& o) {
    dlab::Inserter ins(pts, o);
    dlab::Journal journal(ins);
    while (journal.forward()) {}
    return journal.recorded();
}

// The same count from a batch run's statistics: Start and Finalize; Located, a split and
// Inserted for each point a walk placed (exact mode's Start places three without one); Located
// and SkipDuplicate for each duplicate; every walk step, in-circle test and flip.
std::size_t batchOps(const std::vector<dlab::Vec2>& pts, const dlab::InsertOptions& o) {
    dlab::Inserter ins(pts, o);
    ins.run();
    const dlab::InsertStats& s = ins.stats();
    const std::int64_t placed = s.inserted - (o.boundary == dlab::Boundary::Exact ? 3 : 0);
    return static_cast<std::size_t>(2 + 3 * placed + 2 * s.duplicates + s.walkSteps +
                                    s.inCircleTests + s.boundaryPops + s.flips);
}

}  // namespace

TEST(UserOptions, AFileOpensWithTheUsersOptionsNotTheDemos) {
    TempDir dir("user_options");
    UiHarness h;
    auto& st = h.state();
    ASSERT_EQ(st.engine.options().order, dlab::OrderKind::Input) << "the demo's own order";
    const std::string csv = dir / "points.csv";
    writeCsv(csv, dlab::generatePoints(dlab::Generator::Uniform, 50, 4));
    ASSERT_TRUE(dlab::ui::openFile(st, csv));
    EXPECT_EQ(st.engine.options().order, dlab::OrderKind::Brio) << "BRIO until the user chooses";
    EXPECT_TRUE(logged(st, "order brio"));
    // The user chooses random order in the toolbar: the next file, after the demo, runs in it.
    choose(h, "Order", "random");
    ASSERT_EQ(st.engine.options().order, dlab::OrderKind::Random);
    dlab::ui::loadDemo(st);
    EXPECT_EQ(st.engine.options().order, dlab::OrderKind::Input);
    ASSERT_TRUE(dlab::ui::openFile(st, csv));
    EXPECT_EQ(st.engine.options().order, dlab::OrderKind::Random);
    EXPECT_EQ(st.engine.points().size(), 50u);
}

TEST(UserOptions, ClosingALessonBringsBackTheUsersOptions) {
    UiHarness h;
    auto& st = h.state();
    choose(h, "Order", "random");
    const dlab::InsertOptions mine = st.engine.options();
    ASSERT_EQ(mine.order, dlab::OrderKind::Random);
    ASSERT_TRUE(dlab::ui::openLesson(st, kAssignment));
    h.frames(2);
    EXPECT_EQ(st.engine.options().boundary, dlab::Boundary::Super);
    EXPECT_EQ(st.engine.options().order, dlab::OrderKind::Input);
    // A change made while the lesson is open is the lesson run's, not the user's own.
    choose(h, "Locate", "grid");
    ASSERT_EQ(st.engine.options().locator, dlab::LocatorKind::Grid);
    h.clickItem("lesson-close");
    ASSERT_FALSE(st.lessonPlayer.lesson);
    EXPECT_TRUE(dlab::sameRun(st.engine.options(), mine))
        << dlab::ui::optionsText(st.engine.options());
    EXPECT_TRUE(logged(st, "lesson closed: your options are back"));
    // And a file opened now runs with them too.
    TempDir dir("user_options_lesson");
    writeCsv(dir / "p.csv", dlab::generatePoints(dlab::Generator::Uniform, 30, 2));
    ASSERT_TRUE(dlab::ui::openFile(st, dir / "p.csv"));
    EXPECT_TRUE(dlab::sameRun(st.engine.options(), mine));
}

TEST(StudentTraceInTheGui, TheOpenDialogListsTraceAndLessonFiles) {
    TempDir dir("open_dialog");
    for (const char* name : {"points.csv", "student.jsonl", "lesson.toml", "picture.png"})
        std::ofstream(dir / name) << "\n";
    UiHarness h;
    auto& st = h.state();
    h.press(key::letter('O'), false, /*ctrl=*/true);
    st.files.dialogPath = dir / "x";
    st.itemRects.clear();
    h.frames(2);
    EXPECT_TRUE(st.itemRects.count("dialog-file:student.jsonl"));
    EXPECT_TRUE(st.itemRects.count("dialog-file:lesson.toml"));
    EXPECT_TRUE(st.itemRects.count("dialog-file:points.csv"));
    EXPECT_FALSE(st.itemRects.count("dialog-file:picture.png"));
}

TEST(StudentTraceInTheGui, ATraceOfOtherPointsSaysWhatToLoadFirst) {
    TempDir dir("trace_points");
    const dlab::Lesson lesson = dlab::loadLesson(kAssignment);
    const std::string trace = dir / "student.jsonl";
    {
        auto ins = dlab::makeInserter(lesson);
        dlab::Journal journal(*ins);
        std::ofstream out(trace);
        while (journal.forward())
            out << dlab::toJsonLine(dlab::traceRecord(journal, journal.position() - 1, ins->mesh()))
                << "\n";
    }
    UiHarness h;  // the demo: 12 points
    auto& st = h.state();
    const auto demo = st.engine.points();
    EXPECT_FALSE(dlab::ui::openFile(st, trace));
    EXPECT_FALSE(st.traceCompare.student);
    EXPECT_EQ(st.engine.points(), demo);
    const std::string said = st.messages.back().text;
    EXPECT_EQ(st.messages.back().level, dlab::ui::Message::Level::Error);
    EXPECT_EQ(said,
              trace +
                  " uses vertices up to 40, but the points loaded here (built-in demo) are 12: "
                  "open the points or the assignment (.toml) the trace belongs to first, then "
                  "the trace (nothing was changed)");
    EXPECT_EQ(st.files.notice, said) << "over the canvas too";
    // The assignment's points without its options: the super-triangle is named.
    const std::string csv = dir / "assignment.csv";
    writeCsv(csv, lesson.points);
    ASSERT_TRUE(dlab::ui::openFile(st, csv));
    EXPECT_FALSE(dlab::ui::openFile(st, trace));
    EXPECT_NE(st.messages.back().text.find("choose boundary \"super\""), std::string::npos)
        << st.messages.back().text;
    // Its options but BRIO order (the user's): the trace opens, and the order is named.
    dlab::InsertOptions brio;
    brio.boundary = dlab::Boundary::Super;
    ASSERT_TRUE(st.setUserOptions(brio));
    ASSERT_TRUE(dlab::ui::openFile(st, trace));
    EXPECT_FALSE(st.traceCompare.diff.equal);
    EXPECT_NE(st.messages.back().text.find("; the trace inserts point 0 first, this run point "),
              std::string::npos)
        << st.messages.back().text;
    EXPECT_NE(st.messages.back().text.find("(order brio): choose the order the trace was made in"),
              std::string::npos)
        << st.messages.back().text;
    // The assignment itself: the trace opens and is ours.
    ASSERT_TRUE(dlab::ui::openFile(st, kAssignment));
    ASSERT_TRUE(dlab::ui::openFile(st, trace)) << st.messages.back().text;
    EXPECT_TRUE(st.traceCompare.diff.equal) << st.traceCompare.diff.what;
}

// The estimate counts every op of a run (Start to Finalize) exactly when the pilot is the whole
// run, in every order and boundary mode.
TEST(HistoryEstimate, CountsASmallRunExactly) {
    auto pts = dlab::generatePoints(dlab::Generator::Uniform, 700, 3);
    const auto grid = dlab::generatePoints(dlab::Generator::Grid, 100, 3);  // on edges, cocircular
    pts.insert(pts.end(), grid.begin(), grid.end());
    pts.push_back(pts[5]);  // a duplicate
    for (auto order : {dlab::OrderKind::Input, dlab::OrderKind::Random, dlab::OrderKind::Brio}) {
        for (auto boundary : {dlab::Boundary::Exact, dlab::Boundary::Super}) {
            dlab::InsertOptions o;
            o.order = order;
            o.boundary = boundary;
            const std::size_t real = recordedOps(pts, o);
            EXPECT_EQ(dlab::ui::estimateRunOps(pts, o), real) << dlab::ui::optionsText(o);
            EXPECT_EQ(batchOps(pts, o), real) << dlab::ui::optionsText(o);
        }
    }
}

// Beyond the pilot the walk is extrapolated: within a third of the real count (batchOps, checked
// against a recording above) for uniform points in input, random and BRIO order (input order
// walks ~sqrt(n) a point, BRIO a few), and for a grid in input order (row by row: short walks).
TEST(HistoryEstimate, FollowsTheRunBeyondThePilot) {
    const auto uniform = dlab::generatePoints(dlab::Generator::Uniform, 60000, 8);
    struct Case {
        dlab::Generator kind;
        dlab::OrderKind order;
    };
    for (const Case c : {Case{dlab::Generator::Uniform, dlab::OrderKind::Input},
                         Case{dlab::Generator::Uniform, dlab::OrderKind::Random},
                         Case{dlab::Generator::Uniform, dlab::OrderKind::Brio},
                         Case{dlab::Generator::Grid, dlab::OrderKind::Input}}) {
        const auto pts = c.kind == dlab::Generator::Uniform
                             ? uniform
                             : dlab::generatePoints(dlab::Generator::Grid, 60000, 8);
        dlab::InsertOptions o;
        o.order = c.order;
        const double real = static_cast<double>(batchOps(pts, o));
        const auto t0 = std::chrono::steady_clock::now();
        const double guess = static_cast<double>(dlab::ui::estimateRunOps(pts, o));
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count();
        EXPECT_LT(std::abs(guess - real), real / 3)
            << dlab::ui::optionsText(o) << ": " << guess << " estimated, " << real << " counted";
        std::printf("%s, %s: %.0f ops estimated (in %.0f ms), %.0f counted\n", toString(c.kind),
                    dlab::ui::optionsText(o).c_str(), guess, ms, real);
    }
}

TEST(HistoryOffer, APastTheLimitRunOffersBrioOrNoHistory) {
    UiHarness h;
    auto& st = h.state();
    const auto pts = dlab::generatePoints(dlab::Generator::Uniform, 3000, 6);
    dlab::InsertOptions input;
    input.order = dlab::OrderKind::Input;
    dlab::InsertOptions brio = input;
    brio.order = dlab::OrderKind::Brio;
    const std::size_t inputOps = recordedOps(pts, input), brioOps = recordedOps(pts, brio);
    ASSERT_LT(brioOps * 2, inputOps);
    const std::size_t limit = (brioOps + inputOps) / 2;
    st.engine.setOpLimit(limit);
    ASSERT_TRUE(st.setUserOptions(input));
    ASSERT_TRUE(st.loadUserPoints(pts, "uniform 3000"));
    h.frames(2);
    ASSERT_TRUE(st.historyOffer.open);
    ASSERT_TRUE(st.itemRects.count("history-offer"));
    EXPECT_EQ(st.messages.back().level, dlab::ui::Message::Level::Warning);
    EXPECT_NE(st.messages.back().text.find("3,000 points in input order make about"),
              std::string::npos)
        << st.messages.back().text;
    EXPECT_NE(st.messages.back().text.find("more than the history holds (" +
                                           dlab::ui::approximateCount(limit) + ")"),
              std::string::npos)
        << st.messages.back().text;
    // BRIO order: the offer goes, and the whole run steps.
    h.clickItem("history-brio");
    EXPECT_EQ(st.engine.options().order, dlab::OrderKind::Brio);
    EXPECT_EQ(st.userOptions.order, dlab::OrderKind::Brio);
    h.frames(1);
    EXPECT_FALSE(st.historyOffer.open);
    EXPECT_FALSE(st.itemRects.count("history-offer"));
    while (!st.engine.toEnd(1 << 20)) {}
    EXPECT_FALSE(st.engine.batch());
    EXPECT_EQ(st.engine.recorded(), brioOps);
}

TEST(HistoryOffer, NoHistoryOrSteppingAnywayAreChoicesAndStoppingIsSaid) {
    UiHarness h;
    auto& st = h.state();
    const auto pts = dlab::generatePoints(dlab::Generator::Uniform, 3000, 6);
    dlab::InsertOptions input;
    input.order = dlab::OrderKind::Input;
    st.engine.setOpLimit(recordedOps(pts, input) / 2);
    ASSERT_TRUE(st.setUserOptions(input));
    ASSERT_TRUE(st.loadUserPoints(pts, "uniform 3000"));
    h.frames(2);
    ASSERT_TRUE(st.historyOffer.open);
    h.clickItem("history-batch");
    EXPECT_TRUE(st.engine.batch());
    EXPECT_TRUE(st.engine.inserter().done());
    EXPECT_TRUE(dlab::validate(st.engine.mesh()).empty());
    EXPECT_NE(dlab::ui::captionText(st).find("without a history, as asked"), std::string::npos)
        << dlab::ui::captionText(st);
    h.frames(1);
    EXPECT_FALSE(st.historyOffer.open);
    // Again, and step anyway: the history stops at the limit and says so over the canvas.
    ASSERT_TRUE(st.loadUserPoints(pts, "uniform 3000 again"));
    h.frames(1);
    ASSERT_TRUE(st.historyOffer.open);
    h.clickItem("history-keep");
    EXPECT_FALSE(st.historyOffer.open);
    st.run.frameBudgetMs = st.run.targetFrameMs = 1e9;
    h.press(key::kEnd);
    for (int i = 0; i < 200 && st.run.running; ++i) h.frames(1);
    h.frames(1);
    ASSERT_TRUE(st.engine.batch());
    EXPECT_NE(st.files.notice.find("the history reached"), std::string::npos) << st.files.notice;
    EXPECT_TRUE(st.itemRects.count("file-notice"));
}
