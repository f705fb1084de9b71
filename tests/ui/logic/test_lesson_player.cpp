// The lesson player in the GUI: open a lesson, go from stop to stop, answer its questions.
#include "core/teaching/lesson.h"
#include "tests/ui/ui_harness.h"
#include "ui/lesson_player.h"
#include "ui/panels/panels.h"
#include "ui/platform/keys.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <filesystem>
#include <fstream>

using dlab::test::UiHarness;

namespace {

std::string lessonPath(const char* name) {
    return std::string(DLAB_SOURCE_DIR) + "/lessons/" + name;
}

// Types text into the focused-by-click answer field, then clicks Check.
void typeAnswer(UiHarness& h, const std::string& text) {
    h.clickItem("lesson-answer");
    ImGuiIO& io = ImGui::GetIO();
    for (char c : text) io.AddInputCharacter(static_cast<unsigned>(c));
    h.frames(2);
    h.clickItem("lesson-check");
}

}  // namespace

TEST(LessonPlayer, StopsSeekTheRunAndSelectTheirCorner) {
    UiHarness h;
    auto& st = h.state();
    ASSERT_TRUE(dlab::ui::openLesson(st, lessonPath("05_flips.toml"))) << st.messages.back().text;
    h.frames(2);
    const auto& L = st.lessonPlayer;
    ASSERT_TRUE(L.lesson);
    EXPECT_EQ(L.progress.stop, 0u);
    EXPECT_EQ(st.engine.position(), L.plan.stops[0].position);
    // Next goes to stop 2, at its planned position; Previous comes back.
    h.clickItem("lesson-next");
    EXPECT_EQ(L.progress.stop, 1u);
    EXPECT_EQ(st.engine.position(), L.plan.stops[1].position);
    EXPECT_EQ(st.engine.current()->type, dlab::OpType::Split);
    h.clickItem("lesson-previous");
    EXPECT_EQ(L.progress.stop, 0u);
    EXPECT_EQ(st.engine.position(), L.plan.stops[0].position);
    // Every stop's selection is applied.
    for (std::size_t k = 0; k < L.plan.stops.size(); ++k) {
        dlab::ui::goToStop(st, k);
        EXPECT_EQ(st.selection.corner, L.plan.stops[k].selected) << "stop " << k + 1;
        EXPECT_EQ(st.engine.position(), L.plan.stops[k].position) << "stop " << k + 1;
    }
}

TEST(LessonPlayer, AfterTheUserChangesThePointsNextBringsTheLessonBackAndCtrlZTheirs) {
    UiHarness h;
    auto& st = h.state();
    ASSERT_TRUE(dlab::ui::openLesson(st, lessonPath("05_flips.toml")));
    h.frames(2);
    const auto& L = st.lessonPlayer;
    const std::vector<dlab::Vec2> mine = {{0, 0}, {4, 0}, {0, 3}, {5, 5}};
    ASSERT_TRUE(st.loadPoints(mine, "mine"));
    dlab::InsertOptions other = st.engine.options();
    other.order = dlab::OrderKind::Input;
    other.boundary = dlab::Boundary::Super;
    ASSERT_TRUE(st.setOptions(other));
    h.frames(2);
    EXPECT_TRUE(dlab::ui::lessonStateChanged(st));
    ASSERT_TRUE(st.itemRects.count("lesson-next"));
    h.clickItem("lesson-next");
    EXPECT_EQ(L.progress.stop, 1u);
    EXPECT_FALSE(dlab::ui::lessonStateChanged(st));
    EXPECT_EQ(st.engine.points(), L.lesson->points);
    EXPECT_EQ(st.engine.options().boundary, L.lesson->options.boundary);
    EXPECT_EQ(st.engine.position(), L.plan.stops[1].position);
    EXPECT_EQ(st.engine.current()->type, dlab::OpType::Split);
    // The user's points are one undo away.
    h.press(dlab::ui::key::letter('Z'), false, true);
    EXPECT_EQ(st.engine.points(), mine);
}

TEST(LessonPlayer, AnswersAreCheckedAgainstTheEngine) {
    UiHarness h;
    auto& st = h.state();
    ASSERT_TRUE(dlab::ui::openLesson(st, lessonPath("05_flips.toml")));
    auto& L = st.lessonPlayer;
    dlab::ui::goToStop(st, 1);  // "Which edge will be tested first?"
    h.frames(2);
    ASSERT_TRUE(L.plan.stops[1].answer);
    const dlab::Answer& edge = *L.plan.stops[1].answer;
    ASSERT_EQ(edge.kind, dlab::Answer::Kind::Edge);
    // The edge on top of the flip stack, the first one the in-circle tests take.
    const std::int32_t top = st.engine.inserter().flipStack().back();
    const auto& V = st.engine.mesh().V;
    EXPECT_EQ(std::min(V[dlab::next(top)], V[dlab::prev(top)]), edge.a);
    EXPECT_EQ(std::max(V[dlab::next(top)], V[dlab::prev(top)]), edge.b);
    typeAnswer(h, "99");
    EXPECT_EQ(L.feedback, dlab::ui::LessonState::Feedback::Wrong);
    EXPECT_EQ(L.progress.answers[1], 1);
    L.typed.clear();
    typeAnswer(h, "edge " + std::to_string(edge.b) + "-" + std::to_string(edge.a));
    EXPECT_EQ(L.feedback, dlab::ui::LessonState::Feedback::Right);
    EXPECT_EQ(L.progress.answers[1], 2);
}

TEST(LessonPlayer, AStopShowsOnlyThePanelsItNames) {
    UiHarness h;
    auto& st = h.state();
    ASSERT_TRUE(dlab::ui::openLesson(st, lessonPath("05_flips.toml")));
    h.frames(2);
    // Stop 1 names canvas and statistics: the corner table's tab is not there, Statistics is.
    const auto& panels = st.lessonPlayer.lesson->stops[0].panels;
    ASSERT_FALSE(panels.empty());
    st.itemRects.clear();
    h.frames(2);
    EXPECT_EQ(st.itemRects.count("Corner table"), 0u);
    EXPECT_EQ(st.itemRects.count("Statistics"), 1u);
    EXPECT_FALSE(dlab::ui::lessonWantsPanel(st, "inspector"));
    dlab::ui::closeLesson(st);
    st.itemRects.clear();
    h.frames(2);
    EXPECT_EQ(st.itemRects.count("Corner table"), 1u);
}

TEST(LessonPlayer, ABrokenLessonChangesNothing) {
    UiHarness h;
    auto& st = h.state();
    const auto points = st.engine.points();
    const auto bad = std::filesystem::temp_directory_path() / "dlab_broken_lesson.toml";
    std::ofstream(bad)
        << "title = \"x\"\npoints = [[0, 0], [1, 0], [0, 1]]\n[[stop]]\nrun_to = \"flop\"\n";
    EXPECT_FALSE(dlab::ui::openLesson(st, bad.string()));
    EXPECT_FALSE(st.lessonPlayer.lesson);
    EXPECT_EQ(st.engine.points(), points);
    ASSERT_FALSE(st.messages.empty());
    EXPECT_NE(st.messages.back().text.find("dlab_broken_lesson.toml:4"), std::string::npos)
        << st.messages.back().text;
}
