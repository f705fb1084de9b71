// What the screen says agrees with what the engine did: one numbering of operations, stop
// reasons that belong to their position, counters as of the current position, ghost triangles
// named as such, End past the breakpoints, messages for undo and redo, and every key press
// counted even when it is released before the next frame.
#include "core/engine/generators.h"
#include "core/teaching/describe.h"
#include "tests/ui/ui_harness.h"
#include "ui/panels/panels.h"
#include "ui/platform/keys.h"
#include "ui/render/drawn_text.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <algorithm>
#include <string>
#include <vector>

using dlab::OpType;
using dlab::test::UiHarness;
namespace key = dlab::ui::key;

namespace {

// A tap of a presentation clicker under load: the press and the release both reach the window
// between two frames, so no frame sees the key down (io.KeysDown stays false).
void tapBetweenFrames(int k, int times) {
    for (int i = 0; i < times; ++i) dlab::ui::queueKeyPress(k, false, false);
}

bool startsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

// A breakpoint on every flip, then Space at full speed until the run stops.
void runToAFlipBreakpoint(UiHarness& h) {
    auto& st = h.state();
    st.run.breakpoints.push_back({{dlab::BreakKind::Flip, std::nullopt}, true});
    st.run.opsPerSecond = dlab::ui::RunControl::kFullSpeed;
    h.press(key::kSpace);
    for (int i = 0; i < 50 && st.run.running; ++i) h.frames(1);
}

}  // namespace

TEST(Keys, TapsReleasedBeforeTheFrameEachStepOnce) {
    UiHarness h;
    auto& e = h.state().engine;
    ASSERT_EQ(e.position(), 0u);
    tapBetweenFrames(key::kPageDown, 7);
    h.frames(1);
    EXPECT_EQ(e.position(), 7u);
    tapBetweenFrames(key::kLeft, 3);
    h.frames(1);
    EXPECT_EQ(e.position(), 4u);
    h.frames(3);  // nothing left over
    EXPECT_EQ(e.position(), 4u);
}

TEST(Keys, TapsWhileTypingInAFieldAreTypingNotSteps) {
    UiHarness h;
    auto& st = h.state();
    st.expressions.refocusInput = 1;  // a text field has the keyboard this frame
    tapBetweenFrames(key::kRight, 4);
    h.frames(2);
    EXPECT_EQ(st.engine.position(), 0u);
}

TEST(Captions, CaptionBannerTimelineAndStopsShareOneNumbering) {
    UiHarness h;
    auto& st = h.state();
    for (int i = 0; i < 3; ++i) h.press(key::kRight);
    ASSERT_EQ(st.engine.position(), 3u);
    EXPECT_TRUE(startsWith(dlab::ui::captionText(st), "[op 3] ")) << dlab::ui::captionText(st);
    EXPECT_TRUE(startsWith(dlab::ui::timelineText(st.engine), "op 3 of "))
        << dlab::ui::timelineText(st.engine);
    // A breakpoint's stop says the same number in the messages.
    runToAFlipBreakpoint(h);
    ASSERT_FALSE(st.run.running);
    const std::string at = "[op " + std::to_string(st.engine.position()) + "]";
    ASSERT_FALSE(st.messages.empty());
    EXPECT_NE(st.messages.back().text.find("run stopped at " + at), std::string::npos)
        << st.messages.back().text;
    EXPECT_TRUE(startsWith(dlab::ui::captionText(st), at + " Flip: ")) << dlab::ui::captionText(st);
}

TEST(Captions, TheStopReasonGoesWhenThePositionMoves) {
    UiHarness h;
    auto& st = h.state();
    runToAFlipBreakpoint(h);
    ASSERT_NE(st.run.stopReason.find("breakpoint"), std::string::npos);
    h.frames(2);  // staying there keeps it
    EXPECT_FALSE(st.run.stopReason.empty());
    h.press(key::kRight);
    EXPECT_TRUE(st.run.stopReason.empty()) << st.run.stopReason;
    // The end of a run, then a restart of the run at op 0: the old reason does not come back.
    st.run.breakpoints.clear();
    h.press(key::kEnd);
    for (int i = 0; i < 200 && st.run.running; ++i) h.frames(1);
    ASSERT_EQ(st.run.stopReason, "end of the run");
    dlab::InsertOptions o = st.engine.options();
    o.boundary =
        o.boundary == dlab::Boundary::Exact ? dlab::Boundary::Super : dlab::Boundary::Exact;
    ASSERT_TRUE(st.setOptions(o));
    h.frames(1);
    EXPECT_EQ(st.engine.position(), 0u);
    EXPECT_TRUE(st.run.stopReason.empty()) << st.run.stopReason;
}

TEST(Captions, EndRunsToTheEndPastBreakpointsAndRunStopsAtThem) {
    UiHarness h;
    auto& st = h.state();
    st.run.breakpoints.push_back({{dlab::BreakKind::Flip, std::nullopt}, true});
    h.press(key::kEnd);
    for (int i = 0; i < 200 && st.run.running; ++i) h.frames(1);
    EXPECT_TRUE(st.engine.atEnd());
    EXPECT_EQ(st.run.stopReason, "end of the run");
    h.press(key::kHome);
    st.run.opsPerSecond = dlab::ui::RunControl::kFullSpeed;
    h.press(key::kSpace);
    for (int i = 0; i < 200 && st.run.running; ++i) h.frames(1);
    EXPECT_FALSE(st.engine.atEnd());
    ASSERT_NE(st.engine.current(), nullptr);
    EXPECT_EQ(st.engine.current()->type, OpType::Flip);
}

TEST(Captions, ExactFallbacksAreThoseOfTheOpsDoneSoFar) {
    UiHarness h;
    auto& st = h.state();
    // A lattice: many cocircular quadruples, which the floating-point filter cannot decide.
    ASSERT_TRUE(st.loadPoints(dlab::generatePoints(dlab::Generator::Grid, 64, 3), "grid"));
    auto& e = st.engine;
    ASSERT_GT(e.recorded(), 0u);  // the whole run is recorded already
    EXPECT_EQ(e.exactFallbacks()[0] + e.exactFallbacks()[1], 0u);  // no triangle yet
    e.seek(e.recorded());
    const auto atEnd = e.exactFallbacks();
    EXPECT_GT(atEnd[0] + atEnd[1], 0u);
    // Halfway: between none and all, and the same however the position was reached.
    const std::size_t half = e.recorded() / 2;
    e.seek(half);
    const auto backward = e.exactFallbacks();
    e.toStart();
    e.seek(half);
    EXPECT_EQ(e.exactFallbacks(), backward);
    EXPECT_LE(backward[0], atEnd[0]);
    EXPECT_LE(backward[1], atEnd[1]);
    EXPECT_LT(backward[0] + backward[1], atEnd[0] + atEnd[1]);
}

TEST(Captions, AnInCircleTestAgainstAGhostTriangleNamesItsHullEdge) {
    UiHarness h;
    auto& st = h.state();
    dlab::InsertOptions o = st.engine.options();
    o.boundary = dlab::Boundary::Exact;
    ASSERT_TRUE(st.setOptions(o));
    auto& e = st.engine;
    int ghostTests = 0;
    while (e.forward()) {
        const dlab::Op* op = e.current();
        if (op->type != OpType::InCircleTest || op->b == dlab::kNone) continue;
        const std::string text = dlab::describe(*op, e.inserter());
        const std::int32_t t = dlab::tri(op->b);
        if (e.inserter().isVirtualTriangle(t)) {
            ++ghostTests;
            EXPECT_NE(text.find("beyond hull edge "), std::string::npos) << text;
            EXPECT_NE(text.find("(ghost triangle " + std::to_string(t) + ")"), std::string::npos)
                << text;
            EXPECT_EQ(text.find("circle of triangle"), std::string::npos) << text;
        } else {
            EXPECT_NE(text.find("inside the circle of triangle " + std::to_string(t)),
                      std::string::npos)
                << text;
        }
        EXPECT_EQ(text.find("ghost-"), std::string::npos) << text;
        EXPECT_EQ(text.find("-ghost"), std::string::npos) << text;
    }
    EXPECT_GT(ghostTests, 0);
}

TEST(Captions, UndoAndRedoSayWhatTheyDid) {
    UiHarness h;
    auto& st = h.state();
    std::vector<dlab::Vec2> pts = st.engine.points();
    const std::size_t n = pts.size();
    pts.push_back({123.5, 456.25});
    ASSERT_TRUE(st.editPoints(pts));
    h.press(key::letter('Z'), false, /*ctrl=*/true);
    ASSERT_EQ(st.engine.points().size(), n);
    ASSERT_FALSE(st.messages.empty());
    EXPECT_EQ(st.messages.back().text, "undone: point " + std::to_string(n) + " added (" +
                                           std::to_string(n) + " -> " + std::to_string(n + 1) +
                                           " points)");
    h.press(key::letter('Y'), false, /*ctrl=*/true);
    ASSERT_EQ(st.engine.points().size(), n + 1);
    EXPECT_EQ(st.messages.back().text, "redone: point " + std::to_string(n) + " added (" +
                                           std::to_string(n) + " -> " + std::to_string(n + 1) +
                                           " points)");
    h.press(key::letter('Y'), false, /*ctrl=*/true);
    EXPECT_EQ(st.messages.back().text, "nothing to redo: no edit of the points");
}

TEST(Layout, EverySideTabShowsItsWholeLabelAt1280x720) {
    UiHarness h(1280, 720);
    h.frames(2);
    const std::pair<const char*, const char*> tabs[] = {
        {"Corner table", "Corners"}, {"G (vertices)", "G"}, {"Expressions", "Expr"},
        {"Predicates", "Pred"},      {"ID buffer", "IDs"},  {"Statistics", "Stats"},
        {"Student trace", "Trace"}};
    const float pad = ImGui::GetStyle().FramePadding.x;
    for (const auto& [title, label] : tabs) {
        h.state().itemRects.erase(title);
        h.frames(1);
        ASSERT_TRUE(h.state().itemRects.count(title)) << title << " is not on screen";
        const auto r = h.rect(title);
        EXPECT_GE(r[2] - r[0] + 0.5f, ImGui::CalcTextSize(label).x + 2 * pad)
            << "the tab " << label << " is cut";
    }
}

// The watches sit right under the answer and the log of earlier answers below them: Eval after
// Eval, the watches in sight stay in sight.
TEST(Layout, EvalsDoNotPushTheWatchesAwayAt1280x720) {
    UiHarness h(1280, 720);
    auto& st = h.state();
    for (const char* w : dlab::standardWatches()) ASSERT_TRUE(dlab::ui::addWatch(st, w));
    for (int i = 0; i < 30; ++i) st.engine.forward();
    st.pendingTab = "expressions";
    h.frames(2);
    auto watchesInSight = [&] {
        std::string all;
        for (const std::string& l : dlab::ui::drawnLines(dlab::ui::drawnText(ImGui::GetDrawData())))
            all += l + "\n";
        std::vector<std::string> seen;
        for (const char* w : dlab::standardWatches())
            if (all.find(w) != std::string::npos) seen.push_back(w);
        return seen;
    };
    st.expressions.input = "n(7)";
    h.clickItem("expr-eval");  // as typed; the field keeps the keyboard after it
    h.frames(2);
    const std::vector<std::string> first = watchesInSight();
    EXPECT_GE(first.size(), 3u);
    for (const char* e : {"o(n(7))", "V[p(7)]", "r(o(7))", "n(n(7))", "o(7)", "p(p(7))"}) {
        ASSERT_TRUE(dlab::ui::evaluateExpression(st, e));
        h.frames(2);
        EXPECT_EQ(watchesInSight(), first) << "after " << e;
    }
    ASSERT_EQ(st.expressions.history.size(), 7u);
}

TEST(Layout, TheInspectorShowsSwingAndUnswingWithoutScrollingAt1280x720) {
    UiHarness h(1280, 720);
    auto& st = h.state();
    for (int i = 0; i < 30; ++i) st.engine.forward();
    st.select(4);
    h.frames(3);
    const std::vector<std::string> lines =
        dlab::ui::drawnLines(dlab::ui::drawnText(ImGui::GetDrawData()));
    std::string all;
    for (const std::string& l : lines) all += l + "\n";
    for (const char* row : {"c.s", "c.u"}) {
        EXPECT_TRUE(std::any_of(lines.begin(), lines.end(),
                                [&](const std::string& l) { return l.rfind(row, 0) == 0; }))
            << row << " is not on screen:\n"
            << all;
    }
}
