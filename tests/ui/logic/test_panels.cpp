// The debugging panels' logic: the path an expression draws follows every step, and watches
// pause a run where they break (their pixels: test_panels.cpp).
#include "core/engine/generators.h"
#include "tests/ui/ui_harness.h"
#include "ui/panels/panels.h"
#include "ui/platform/keys.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <algorithm>
#include <string>

using dlab::kNone;
using dlab::test::UiHarness;
namespace key = dlab::ui::key;

TEST(Panels, TheDrawnPathFollowsEveryStep) {
    UiHarness h;
    auto& st = h.state();
    st.engine.seek(40);
    h.frames(2);
    float x = 0, y = 0;
    std::int32_t c = kNone;
    for (std::int32_t k = 0; k < st.engine.mesh().numCorners() && c == kNone; ++k) {
        if (dlab::ui::cornerAnchor(h.state(), k, x, y)) c = k;
    }
    ASSERT_NE(c, kNone);
    st.select(c);
    ASSERT_TRUE(dlab::ui::evaluateExpression(st, "c.n"));
    h.frames(1);
    const auto before = st.expressions.path;
    h.press(key::kRight);
    h.frames(1);
    // Re-evaluated at the new step (same text, same c): the path is the mesh's, now.
    ASSERT_EQ(st.expressions.liveVersion, st.engine.version());
    ASSERT_EQ(st.expressions.path.size(), 1u);
    EXPECT_EQ(st.expressions.path[0].to, dlab::next(c));
}

TEST(Panels, TheOperatorArrowIsDroppedOnceAnOperationChangesTheMesh) {
    UiHarness h;
    auto& st = h.state();
    st.engine.seek(40);
    h.frames(2);
    std::int32_t c = kNone;
    for (std::int32_t k = 0; k < st.engine.mesh().numCorners() && c == kNone; ++k) {
        if (st.engine.mesh().O[k] != kNone) c = k;
    }
    ASSERT_NE(c, kNone);
    st.select(c);
    ASSERT_TRUE(st.moveSelection('o'));
    h.frames(1);
    ASSERT_NE(st.currentMove(), nullptr);
    EXPECT_EQ(st.currentMove()->from, c);
    EXPECT_EQ(st.currentMove()->to, st.engine.mesh().O[c]);
    const std::uint64_t version = st.engine.version();
    for (int i = 0; i < 20 && st.engine.version() == version; ++i) {
        h.press(key::kRight);
        h.frames(1);
    }
    ASSERT_NE(st.engine.version(), version) << "twenty steps left the mesh as it was";
    EXPECT_EQ(st.currentMove(), nullptr);
    ASSERT_TRUE(st.moveSelection('n'));  // a new move on the new mesh is drawn again
    EXPECT_NE(st.currentMove(), nullptr);
}

TEST(Panels, AWatchPausesTheRunAtTheFirstOperationThatBreaksIt) {
    UiHarness h;
    auto& st = h.state();
    // "No corner's vertex is 7" breaks exactly when vertex 7 enters the mesh.
    ASSERT_TRUE(dlab::ui::addWatch(st, "V[c] != 7"));
    ASSERT_FALSE(dlab::ui::addWatch(st, "c.n.o"));  // not a comparison: refused, logged
    h.press(key::kEnd);                             // full speed: many operations per frame
    for (int i = 0; i < 200 && st.run.running; ++i) h.frames(1);
    ASSERT_FALSE(st.run.running);
    ASSERT_FALSE(st.engine.atEnd()) << "the run went to the end: the watch did not stop it";
    // The first position where some corner has vertex 7, found independently.
    dlab::ui::Engine probe;
    std::string error;
    ASSERT_TRUE(probe.reset(st.engine.points(), st.engine.options(), error));
    std::size_t first = 0;
    for (;;) {
        const auto& V = probe.mesh().V;
        if (std::find(V.begin(), V.end(), 7) != V.end()) break;
        ASSERT_TRUE(probe.forward());
        first = probe.position();
    }
    EXPECT_EQ(st.engine.position(), first);
    EXPECT_NE(st.run.stopReason.find("V[c] != 7"), std::string::npos) << st.run.stopReason;
    ASSERT_NE(st.selection.corner, kNone);
    EXPECT_EQ(st.engine.mesh().V[st.selection.corner], 7);
    // The log names the operation and the corner.
    bool named = false;
    for (const auto& msg : st.messages) {
        named |= msg.level == dlab::ui::Message::Level::Error &&
                 msg.text.find("[op " + std::to_string(first) + "] (") != std::string::npos &&
                 msg.text.find("c = " + std::to_string(st.selection.corner)) != std::string::npos;
    }
    EXPECT_TRUE(named);
    // Running on: the watch stays broken and does not stop the run again.
    h.press(key::kEnd);
    for (int i = 0; i < 300 && st.run.running; ++i) h.frames(1);
    EXPECT_TRUE(st.engine.atEnd());
}

TEST(Panels, OnALargeMeshAWatchChecksTheChangedCornersAndStillStopsAtTheRightOperation) {
    UiHarness h;
    auto& st = h.state();
    // 1500 points in input order: about 9000 corners, beyond where every corner is checked.
    ASSERT_TRUE(
        st.loadPoints(dlab::generatePoints(dlab::Generator::Uniform, 1500, 4), "uniform 1500"));
    ASSERT_TRUE(dlab::ui::addWatch(st, "V[c] != 1400"));
    ASSERT_TRUE(dlab::ui::addWatch(st, "o(o(c)) == c"));
    h.press(key::kEnd);
    for (int i = 0; i < 2000 && st.run.running; ++i) h.frames(1);
    ASSERT_FALSE(st.run.running);
    ASSERT_GT(st.engine.mesh().numCorners(), 6000);
    ASSERT_FALSE(st.engine.atEnd()) << st.run.stopReason;
    const auto& V = st.engine.mesh().V;
    EXPECT_NE(std::find(V.begin(), V.end(), 1400), V.end());
    st.engine.back();  // one op earlier, vertex 1400 was in no corner
    const auto& before = st.engine.mesh().V;
    EXPECT_EQ(std::find(before.begin(), before.end(), 1400), before.end());
    EXPECT_FALSE(st.expressions.watches[1].failing) << st.expressions.watches[1].status;
}

TEST(Panels, TheStandardWatchesHoldThroughAWholeRun) {
    UiHarness h;
    auto& st = h.state();
    ASSERT_TRUE(st.loadPoints(dlab::generatePoints(dlab::Generator::Grid, 64, 3),
                              "grid"));  // cocircular quadruples
    h.clickItem("Expressions");          // the tab, as a user opens it
    h.frames(2);
    for (const char* w : dlab::standardWatches()) ASSERT_TRUE(dlab::ui::addWatch(st, w));
    h.press(key::kEnd);
    for (int i = 0; i < 500 && st.run.running; ++i) h.frames(1);
    EXPECT_TRUE(st.engine.atEnd()) << st.run.stopReason;
    for (const auto& w : st.expressions.watches) {
        EXPECT_FALSE(w.failing) << w.text << ": " << w.status;
        EXPECT_NE(w.status.find("holds"), std::string::npos) << w.text << ": " << w.status;
    }
}
