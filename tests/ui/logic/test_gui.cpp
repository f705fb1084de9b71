// The GUI driven as a user drives it: clicks on the step buttons, keys, clicks on the canvas,
// the corner table's scrolling (its pixels: test_gui_pixels.cpp).
#include "core/engine/generators.h"
#include "core/engine/mesh.h"
#include "tests/ui/ui_harness.h"
#include "ui/panels/panels.h"
#include "ui/platform/keys.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

using dlab::kNone;
using dlab::OpType;
using dlab::test::UiHarness;
namespace key = dlab::ui::key;

namespace {

// A corner of the current mesh whose label is on the canvas.
std::int32_t visibleCorner(UiHarness& h, float& x, float& y, std::int32_t from = 0) {
    for (std::int32_t c = from; c < h.state().engine.mesh().numCorners(); ++c) {
        if (dlab::ui::cornerAnchor(h.state(), c, x, y)) return c;
    }
    return kNone;
}

}  // namespace

TEST(Gui, StepButtonsDriveTheJournal) {
    UiHarness h;
    auto& e = h.state().engine;
    ASSERT_EQ(e.position(), 0u);
    h.clickItem(">");
    EXPECT_EQ(e.position(), 1u);
    EXPECT_EQ(e.current()->type, OpType::Start);
    h.clickItem(">");
    h.clickItem(">");
    EXPECT_EQ(e.position(), 3u);
    h.clickItem("<");
    EXPECT_EQ(e.position(), 2u);
    h.clickItem(">>");  // to the end of the first insertion
    ASSERT_NE(e.current(), nullptr);
    EXPECT_TRUE(e.current()->type == OpType::Inserted ||
                e.current()->type == OpType::SkipDuplicate);
    const std::size_t afterOne = e.position();
    h.clickItem(">>");
    EXPECT_GT(e.position(), afterOne);
    EXPECT_EQ(e.current()->type == OpType::Inserted || e.current()->type == OpType::SkipDuplicate,
              true);
    h.clickItem("<<");
    EXPECT_EQ(e.position(), afterOne);
    h.clickItem("|<");
    EXPECT_EQ(e.position(), 0u);
    EXPECT_EQ(e.mesh().numTriangles(), 0);
}

TEST(Gui, KeysStepRunAndRewind) {
    UiHarness h;
    auto& e = h.state().engine;
    h.press(key::kRight);
    EXPECT_EQ(e.position(), 1u);
    h.press(key::kPageDown);  // a presentation clicker
    EXPECT_EQ(e.position(), 2u);
    h.press(key::kRight, /*shift=*/true);
    EXPECT_TRUE(dlab::endsInsertion(e.current()->type));
    h.press(key::kLeft);
    EXPECT_FALSE(dlab::endsInsertion(e.current()->type));
    h.press(key::kHome);
    EXPECT_EQ(e.position(), 0u);
    h.press(key::kEnd);  // run to the end at full speed, a frame budget at a time
    for (int i = 0; i < 200 && !e.atEnd(); ++i) h.frames(1);
    EXPECT_TRUE(e.atEnd());
    EXPECT_FALSE(h.state().run.running);
    EXPECT_TRUE(dlab::validate(e.mesh()).empty());
    // 11 distinct points (point 11 repeats point 4), 6 of them on the hull (point 2 lies on
    // the hull edge 0-1): 2 * 11 - 6 - 2 triangles.
    EXPECT_EQ(e.mesh().numTriangles(), 14);
    h.press(key::kSpace);  // at the end, run does nothing
    EXPECT_FALSE(h.state().run.running);
}

TEST(Gui, RunAnimatesAtTheChosenSpeed) {
    UiHarness h;
    auto& st = h.state();
    st.run.opsPerSecond = 30.0f;
    h.press(key::kSpace);
    EXPECT_TRUE(st.run.running);
    ImGui::GetIO().DeltaTime = 0.1f;  // each frame: 0.1 s, so 3 operations
    h.frames(4);
    ImGui::GetIO().DeltaTime = 1.0f / 60.0f;
    EXPECT_GE(st.engine.position(), 9u);
    EXPECT_LE(st.engine.position(), 18u);
    h.press(key::kSpace);
    const std::size_t paused = st.engine.position();
    h.frames(5);
    EXPECT_EQ(st.engine.position(), paused);
}

TEST(Gui, ClickingACornerSelectsItAndOperatorKeysMoveIt) {
    UiHarness h;
    auto& st = h.state();
    st.engine.seek(40);
    h.frames(2);
    float x = 0, y = 0;
    const std::int32_t c = visibleCorner(h, x, y);
    ASSERT_NE(c, kNone) << "no corner label on the canvas";
    h.moveTo(x, y);
    EXPECT_EQ(st.selection.hoveredCorner, c);  // hovering the canvas lights the table row
    h.click(x, y);
    ASSERT_EQ(st.selection.corner, c);
    const dlab::Mesh& m = st.engine.mesh();
    h.press(key::letter('N'));
    EXPECT_EQ(st.selection.corner, dlab::next(c));
    EXPECT_EQ(st.selection.lastMove.op, 'n');
    h.press(key::letter('P'));
    EXPECT_EQ(st.selection.corner, c);
    // o, then o again comes back (where there is a neighbour).
    std::int32_t d = c;
    while (m.O[d] == kNone) d = dlab::next(d);
    st.select(d);
    h.press(key::letter('O'));
    EXPECT_EQ(st.selection.corner, m.O[d]);
    h.press(key::letter('O'));
    EXPECT_EQ(st.selection.corner, d);
    // Swing goes around V[d] and keeps the vertex, or stays put at the boundary.
    h.press(key::letter('S'));
    EXPECT_EQ(m.V[st.selection.corner], m.V[d]);
    h.press(key::kEscape);
    EXPECT_EQ(st.selection.corner, kNone);
}

TEST(Gui, ClickQueuesAPointAndRightClickRemovesIt) {
    UiHarness h;
    auto& st = h.state();
    const std::size_t n = st.engine.points().size();
    const auto canvas = h.rect("canvas");
    // An empty spot: the lower-left corner area of the canvas, away from every point.
    const float x = canvas[0] + 30, y = canvas[3] - 30;
    h.click(x, y);
    ASSERT_EQ(st.engine.points().size(), n + 1);
    EXPECT_EQ(st.engine.pointStates().back(), dlab::ui::Engine::PointState::Pending);
    // The new point sits where the click was (rounded to a readable precision).
    const auto s = st.view.toScreen(st.engine.points().back());
    EXPECT_NEAR(s.x, x, 3.0);
    EXPECT_NEAR(s.y, y, 3.0);
    h.click(x, y, /*button=*/1);
    EXPECT_EQ(st.engine.points().size(), n);
    // Ctrl+Z brings it back, Ctrl+Y removes it again.
    h.press(key::letter('Z'), false, true);
    EXPECT_EQ(st.engine.points().size(), n + 1);
    h.press(key::letter('Y'), false, true);
    EXPECT_EQ(st.engine.points().size(), n);
}

TEST(Gui, DraggingAQueuedPointMovesIt) {
    UiHarness h;
    auto& st = h.state();
    const auto before = st.engine.points();
    const std::size_t i = 10;  // queued at op 0, and no other point near it
    const auto p = st.view.toScreen(before[i]);
    h.drag(static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.x) + 60,
           static_cast<float>(p.y) + 40);
    const auto after = st.engine.points();
    ASSERT_EQ(after.size(), before.size());
    EXPECT_GT(after[i].x, before[i].x);
    EXPECT_LT(after[i].y, before[i].y);  // screen down is world down
    for (std::size_t k = 0; k < after.size(); ++k) {
        if (k != i) {
            EXPECT_EQ(after[k], before[k]);
        }
    }
}

TEST(Gui, WheelZoomsAtTheCursorAndDragPans) {
    UiHarness h;
    auto& st = h.state();
    const auto canvas = h.rect("canvas");
    const float cx = canvas[0] + 200, cy = canvas[1] + 150;
    const dlab::Vec2 under = st.view.toWorld({cx, cy});
    const double scale = st.view.scale;
    h.scroll(cx, cy, 2.0f);
    EXPECT_GT(st.view.scale, scale * 1.3);
    const dlab::Vec2 still = st.view.toWorld({cx, cy});
    EXPECT_NEAR(still.x, under.x, 1e-6 * std::abs(under.x) + 1e-9);
    EXPECT_NEAR(still.y, under.y, 1e-6 * std::abs(under.y) + 1e-9);
    const auto centre = st.view.center;
    h.drag(cx, cy, cx + 100, cy, /*button=*/2);  // middle drag
    EXPECT_LT(st.view.center.x, centre.x);
    h.press(key::letter('F'));  // fit
    h.frames(1);
    EXPECT_NEAR(st.view.scale, scale, scale * 1e-9);
}

// Random order walks far (~170 ops a point at 40000 points): the history stops at the op limit,
// the run finishes in one batch with a warning, and the mesh is complete and valid.
TEST(Gui, AHistoryPastTheOpLimitFinishesInOneBatchAndSaysSo) {
    UiHarness h(1100, 720);
    auto& st = h.state();
    dlab::InsertOptions options;
    options.order = dlab::OrderKind::Random;
    ASSERT_TRUE(st.setOptions(options));
    const std::size_t n = 40000;
    ASSERT_TRUE(st.loadPoints(dlab::generatePoints(dlab::Generator::Uniform, n, 5), "uniform 40k"));
    ASSERT_FALSE(st.engine.batch());
    EXPECT_LE(st.engine.recorded(), dlab::ui::Engine::kPrerecordOps);
    const std::size_t messages = st.messages.size();
    // A run that goes as far as it can in one frame, whatever the machine's speed (ASan builds
    // step ~20 times slower).
    st.run.frameBudgetMs = st.run.targetFrameMs = 1e9;
    h.press(key::kEnd);
    for (int i = 0; i < 200 && st.run.running; ++i) h.frames(1);
    h.frames(1);
    ASSERT_TRUE(st.engine.batch());
    EXPECT_TRUE(st.engine.inserter().done());
    EXPECT_EQ(st.engine.mesh().numVertices(), static_cast<std::int32_t>(n));
    EXPECT_TRUE(dlab::validate(st.engine.mesh()).empty());
    ASSERT_GT(st.messages.size(), messages);
    EXPECT_NE(st.messages.back().text.find("one batch"), std::string::npos)
        << st.messages.back().text;
    EXPECT_EQ(st.messages.back().level, dlab::ui::Message::Level::Warning);
}

TEST(Gui, TheCornerTableScrollsAMillionCorners) {
    UiHarness h(1400, 900);
    auto& st = h.state();
    // More points than the history limit: one batch, the final mesh at once (BRIO order: the
    // demo's input order would make every walk long).
    ASSERT_TRUE(st.setOptions(dlab::InsertOptions{}));
    ASSERT_TRUE(
        st.loadPoints(dlab::generatePoints(dlab::Generator::Uniform, 340000, 3), "uniform 340k"));
    ASSERT_TRUE(st.engine.batch());
    ASSERT_GE(st.engine.mesh().numCorners(), 1000000);
    h.frames(3);
    const auto table = h.rect("corner-table");
    const float before = h.rect("corner-table-scroll")[0];
    h.scroll((table[0] + table[2]) / 2, (table[1] + table[3]) / 2, -10.0f);
    const float after = h.rect("corner-table-scroll")[0];
    EXPECT_GT(after, before);
    // Jump to the last corner: the table scrolls near its end.
    const std::int32_t last = st.engine.mesh().numCorners() - 1;
    st.select(last);
    st.selection.jumpToCorner = last;
    h.frames(2);
    const auto scroll = h.rect("corner-table-scroll");
    EXPECT_GT(scroll[0], 0.95f * scroll[1]);
    // Frames stay interactive with a million rows (reported, not asserted: see the README).
    const auto t0 = std::chrono::steady_clock::now();
    h.scroll((table[0] + table[2]) / 2, (table[1] + table[3]) / 2, 5.0f);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() /
        4;
    std::printf("[ info ] %d corners: %.1f ms per frame while scrolling\n",
                st.engine.mesh().numCorners(), ms);
}

TEST(Gui, ChangingTheBoundaryModeRestartsWithTheSamePoints) {
    UiHarness h;
    auto& st = h.state();
    st.engine.seek(50);
    const auto points = st.engine.points();
    dlab::InsertOptions o = st.engine.options();
    o.boundary = dlab::Boundary::Super;
    ASSERT_TRUE(st.setOptions(o));
    EXPECT_EQ(st.engine.position(), 0u);
    EXPECT_EQ(st.engine.points(), points);
    EXPECT_EQ(st.engine.options().boundary, dlab::Boundary::Super);
    h.press(key::kRight);
    EXPECT_EQ(st.engine.mesh().numTriangles(), 1);  // the super-triangle
}

TEST(Gui, ABadFileShowsAnErrorAndChangesNothing) {
    UiHarness h;
    auto& st = h.state();
    st.engine.seek(20);
    const auto points = st.engine.points();
    const std::filesystem::path bad = std::filesystem::temp_directory_path() / "dlab_gui_bad.csv";
    std::ofstream(bad) << "1,2\n3,nan\n";
    EXPECT_FALSE(dlab::ui::loadPointFile(st, bad.string()));
    EXPECT_EQ(st.engine.points(), points);
    EXPECT_EQ(st.engine.position(), 20u);
    ASSERT_FALSE(st.messages.empty());
    EXPECT_EQ(st.messages.back().level, dlab::ui::Message::Level::Error);
    EXPECT_NE(st.messages.back().text.find("dlab_gui_bad.csv:2"), std::string::npos)
        << st.messages.back().text;
    h.frames(2);  // and the UI keeps drawing
}

TEST(Gui, HelpOverlayAndPresentationMode) {
    UiHarness h;
    auto& st = h.state();
    h.press(key::kF1);
    EXPECT_TRUE(st.showHelp);
    h.press(key::kEscape);
    EXPECT_FALSE(st.showHelp);
    const float normal = ImGui::GetFontSize();
    st.presentation = true;
    h.frames(2);
    EXPECT_GT(ImGui::GetFontSize(), normal * 1.4f);
}

TEST(Gui, RunStopsAtBreakpoints) {
    UiHarness h;
    auto& st = h.state();
    st.run.breakpoints.push_back({{dlab::BreakKind::Flip, std::nullopt}, true});
    st.run.opsPerSecond = dlab::ui::RunControl::kFullSpeed;
    h.press(key::kSpace);
    for (int i = 0; i < 50 && st.run.running; ++i) h.frames(1);
    ASSERT_FALSE(st.run.running);
    ASSERT_NE(st.engine.current(), nullptr);
    EXPECT_EQ(st.engine.current()->type, OpType::Flip);
    EXPECT_NE(st.run.stopReason.find("breakpoint"), std::string::npos) << st.run.stopReason;
    // Disabled, the flip breakpoint no longer stops; vertex 9 about to be inserted does.
    st.run.breakpoints[0].enabled = false;
    st.run.breakpoints.push_back({{dlab::BreakKind::Insert, 9}, true});
    h.press(key::kSpace);
    for (int i = 0; i < 50 && st.run.running; ++i) h.frames(1);
    ASSERT_FALSE(st.run.running);
    EXPECT_EQ(st.engine.current()->type, OpType::Inserted);
    EXPECT_EQ(st.engine.inserter().currentVertex(), 9);
    // The popup opens from the toolbar.
    h.clickItem("breakpoints");
    EXPECT_TRUE(ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId | ImGuiPopupFlags_AnyPopupLevel));
}
