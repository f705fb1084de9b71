// The lesson player in the GUI: open a lesson, go from stop to stop, answer its questions.
#include "core/teaching/lesson.h"
#include "tests/ui/ui_harness.h"
#include "ui/files/settings.h"
#include "ui/lesson_player.h"
#include "ui/panels/canvas_looks.h"
#include "ui/panels/labels.h"
#include "ui/panels/panels.h"
#include "ui/platform/keys.h"
#include "ui/render/drawn_marks.h"
#include "ui/render/drawn_text.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>
#include <vector>

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

TEST(LessonPlayer, ALessonWithTrianglesPlaysTheFlipAlgorithmAndBringsItBack) {
    UiHarness h;
    auto& st = h.state();
    ASSERT_TRUE(dlab::ui::openLesson(st, lessonPath("11_flip_algorithm.toml")))
        << st.messages.back().text;
    h.frames(2);
    const auto& L = st.lessonPlayer;
    ASSERT_TRUE(L.lesson && L.lesson->start);
    EXPECT_TRUE(st.engine.repairs());
    EXPECT_EQ(st.engine.position(), L.plan.stops[0].position);
    EXPECT_EQ(st.engine.mesh().numTriangles(), 8);  // the fan, as given
    h.clickItem("lesson-next");
    EXPECT_EQ(st.engine.current()->type, dlab::OpType::InCircleTest);
    EXPECT_EQ(dlab::ui::captionText(st), L.plan.stops[1].banner);
    // The same points inserted instead: not the lesson's run; Next brings the flip algorithm back.
    ASSERT_TRUE(st.loadPoints(L.lesson->points, "same points"));
    EXPECT_FALSE(st.engine.repairs());
    EXPECT_TRUE(dlab::ui::lessonStateChanged(st));
    h.frames(2);
    h.clickItem("lesson-next");
    EXPECT_EQ(L.progress.stop, 2u);
    EXPECT_TRUE(st.engine.repairs());
    EXPECT_FALSE(dlab::ui::lessonStateChanged(st));
    EXPECT_EQ(st.engine.position(), L.plan.stops[2].position);
    EXPECT_EQ(st.engine.current()->type, dlab::OpType::Flip);
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

// ---- Slides: presentation mode with a lesson open ----------------------------------------------

namespace {

std::vector<std::string> lessonsWithStops() {
    std::vector<std::string> out;
    for (const auto& e : std::filesystem::directory_iterator(lessonPath(""))) {
        if (e.path().extension() != ".toml" || dlab::isTrackFile(e.path().string())) continue;
        if (!dlab::loadLesson(e.path().string()).stops.empty()) out.push_back(e.path().string());
    }
    std::sort(out.begin(), out.end());
    return out;
}

bool inside(const std::array<float, 4>& r, float w, float h) {
    return r[0] >= 0 && r[1] >= 0 && r[2] <= w && r[3] <= h && r[0] < r[2] && r[1] < r[3];
}

// r inside box, to half a pixel.
bool within(const std::array<float, 4>& r, const std::array<float, 4>& box) {
    return r[0] >= box[0] - 0.5f && r[1] >= box[1] - 0.5f && r[2] <= box[2] + 0.5f &&
           r[3] <= box[3] + 0.5f;
}

std::string text(const std::array<float, 4>& r) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.0f, %.0f)-(%.0f, %.0f)", r[0], r[1], r[2], r[3]);
    return buf;
}

// Nothing on the slide's side column is cut off: the stop's text fits its box (no scrolling,
// no word past the right edge), the statistics are no wider than their panel, and the ID-buffer
// image is whole inside its tab.
void sideColumnFits(dlab::ui::AppState& st, const std::string& where) {
    auto& r = st.itemRects;
    ASSERT_TRUE(r.count("slide-text-content")) << where;
    EXPECT_TRUE(within(r["slide-text-content"], r["slide-text"]))
        << where << ": the text needs " << text(r["slide-text-content"]) << ", its box is "
        << text(r["slide-text"]);
    if (r.count("statistics-content")) {
        // As wide as the panel at most (it may scroll down, never sideways).
        EXPECT_LE(r["statistics-content"][2], r["statistics-panel"][2] + 0.5f)
            << where << ": the statistics need " << text(r["statistics-content"])
            << ", their panel is " << text(r["statistics-panel"]);
    }
    if (r.count("idbuffer-image-whole")) {
        ASSERT_TRUE(r.count("slide-tab")) << where;
        EXPECT_TRUE(within(r["idbuffer-image-whole"], r["slide-tab"]))
            << where << ": the ID-buffer image is " << text(r["idbuffer-image-whole"])
            << ", its tab " << text(r["slide-tab"]);
    }
}

// Every stop of every lesson on a slide of this size: the text and the whole question (answer
// field, Check) are on the slide, and the message log is not.
void everyStopFits(int width, int height) {
    UiHarness h(width, height);
    auto& st = h.state();
    st.presentation = true;
    const std::vector<std::string> lessons = lessonsWithStops();
    ASSERT_GE(lessons.size(), 9u);
    for (const std::string& path : lessons) {
        ASSERT_TRUE(dlab::ui::openLesson(st, path)) << st.messages.back().text;
        const auto& stops = st.lessonPlayer.lesson->stops;
        for (std::size_t k = 0; k < stops.size(); ++k) {
            const std::string where = path + " stop " + std::to_string(k + 1);
            dlab::ui::goToStop(st, k);
            st.itemRects.clear();
            h.frames(3);
            ASSERT_TRUE(dlab::ui::slideMode(st)) << where;
            EXPECT_TRUE(st.itemRects.count("slide-text")) << where;
            EXPECT_FALSE(st.itemRects.count("messages")) << where;
            EXPECT_TRUE(st.itemRects.count("lesson-next")) << where;
            sideColumnFits(st, where);
            if (stops[k].question.empty()) continue;
            ASSERT_TRUE(st.itemRects.count("slide-question")) << where;
            EXPECT_TRUE(inside(st.itemRects["slide-question"], width, height))
                << where << ": the question ends at y = " << st.itemRects["slide-question"][3];
            // The field and the button are whole (RecordItem clips what is cut off).
            for (const char* item : {"lesson-answer", "lesson-check"}) {
                ASSERT_TRUE(st.itemRects.count(item)) << where << " " << item;
                const auto r = st.itemRects[item];
                EXPECT_GT(r[3] - r[1], ImGui::GetFontSize()) << where << " " << item;
            }
        }
        dlab::ui::closeLesson(st);
    }
}

// The vertices' points and labels a legend box [x0, x1] x [y0, y1] would cover.
std::vector<std::string> coveredBy(const dlab::SlideBox& box,
                                   const std::vector<dlab::SlideMark>& marks) {
    std::vector<std::string> out;
    for (const dlab::SlideMark& m : marks) {
        const bool point = m.role == dlab::SlideMarkRole::Vertex;
        if ((point || m.role == dlab::SlideMarkRole::VertexLabel) && box.meets(m.box, 0))
            out.push_back((point ? "vertex " : "the label of vertex ") + std::to_string(m.a));
    }
    return out;
}

}  // namespace

// Where one corner of the canvas has room for the legend clear of every vertex and its label,
// the legend covers none, on every stop of every lesson (it may go elsewhere than that corner).
TEST(LessonSlides, TheLegendCoversNoVertexWhereACornerOfTheCanvasIsFree) {
    UiHarness h(1280, 720);
    auto& st = h.state();
    st.presentation = true;
    int legends = 0;
    for (const std::string& path : lessonsWithStops()) {
        ASSERT_TRUE(dlab::ui::openLesson(st, path)) << st.messages.back().text;
        for (std::size_t k = 0; k < st.lessonPlayer.lesson->stops.size(); ++k) {
            dlab::ui::goToStop(st, k);
            h.frames(2);
            std::vector<dlab::SlideMark> marks;
            {
                const dlab::ui::MarkRecording recording(marks);
                h.frames(1);
            }
            const auto role = [&](dlab::SlideMarkRole r) {
                return std::find_if(marks.begin(), marks.end(),
                                    [&](const dlab::SlideMark& m) { return m.role == r; });
            };
            const auto legend = role(dlab::SlideMarkRole::Legend);
            const auto canvas = role(dlab::SlideMarkRole::Canvas);
            if (legend == marks.end() || canvas == marks.end()) continue;
            ++legends;
            const std::vector<std::string> covered = coveredBy(legend->box, marks);
            if (covered.empty()) continue;
            const dlab::SlideBox c = canvas->box, l = legend->box;
            const float w = l.x1 - l.x0, ht = l.y1 - l.y0;
            for (const float x : {c.x0 + 6, c.x1 - w - 6}) {
                for (const float y : {c.y0 + 6, c.y1 - ht - 6}) {
                    EXPECT_FALSE(coveredBy({x, y, x + w, y + ht}, marks).empty())
                        << path << " stop " << k + 1 << ": the legend covers " << covered[0]
                        << " while the corner at (" << x << ", " << y << ") is free";
                }
            }
        }
        dlab::ui::closeLesson(st);
    }
    EXPECT_GT(legends, 50);
}

// The legend's place: a free corner when one is free, the place covering the least otherwise.
TEST(LessonSlides, TheLegendGoesWhereItCoversTheLeast) {
    using dlab::ui::BusyPoint;
    const ImVec2 lo(0, 0), hi(600, 400), size(200, 100);
    const auto point = [](float x, float y) {
        return BusyPoint{ImVec2(x - 5, y - 5), dlab::ui::kBusyVertex, ImVec2(x + 5, y + 5)};
    };
    // Vertices near the top-right, bottom-right and top-left corners: bottom left is free.
    std::vector<BusyPoint> busy = {point(590, 10), point(590, 390), point(10, 10)};
    ImVec2 at = dlab::ui::placeLegend(lo, hi, size, busy, true);
    EXPECT_EQ(at.x, 6);
    EXPECT_EQ(at.y, 400 - 100 - 6);
    // Every corner taken: a free place elsewhere, with only an edge across it, if nothing freer.
    busy.push_back(point(10, 390));
    at = dlab::ui::placeLegend(lo, hi, size, busy, true);
    EXPECT_EQ(dlab::ui::coveredWeight(at, ImVec2(at.x + size.x, at.y + size.y), busy, 4), 0);
    busy.push_back({ImVec2(0, 200), dlab::ui::kBusyEdge, ImVec2(600, 200), true});
    busy.push_back({ImVec2(300, 0), dlab::ui::kBusyEdge, ImVec2(300, 400), true});
    at = dlab::ui::placeLegend(lo, hi, size, busy, true);
    const float least = dlab::ui::coveredWeight(at, ImVec2(at.x + size.x, at.y + size.y), busy, 4);
    EXPECT_EQ(least, 0) << "a quarter of the canvas between the edges is free";
    // Only the corners with `anywhere` off (many points): the least covered of them.
    const std::vector<BusyPoint> three = {point(590, 10), point(10, 10), point(12, 390)};
    at = dlab::ui::placeLegend(lo, hi, size, three, false);
    EXPECT_EQ(at.x, 600 - 200 - 6);
    EXPECT_EQ(at.y, 400 - 100 - 6);
}

TEST(LessonSlides, EveryStopShowsItsWholeQuestionAt1280x720) { everyStopFits(1280, 720); }

TEST(LessonSlides, EveryStopShowsItsWholeQuestionAt1920x1080) { everyStopFits(1920, 1080); }

TEST(LessonSlides, FontsGrowWithTheWindowHeight) {
    float small = 0, large = 0;
    for (auto [w, h, out] : {std::tuple{1280, 720, &small}, std::tuple{1920, 1080, &large}}) {
        UiHarness harness(w, h);
        harness.state().presentation = true;
        harness.frames(2);
        *out = ImGui::GetFontSize();
    }
    EXPECT_GE(small, 20.0f);
    EXPECT_GT(large, small * 1.4f);
}

TEST(LessonSlides, PageDownAndPageUpMoveBetweenStops) {
    UiHarness h(1280, 720);
    auto& st = h.state();
    st.presentation = true;
    ASSERT_TRUE(dlab::ui::openLesson(st, lessonPath("05_flips.toml")));
    h.frames(2);
    const auto& L = st.lessonPlayer;
    h.press(dlab::ui::key::kPageDown);
    EXPECT_EQ(L.progress.stop, 1u);
    EXPECT_EQ(st.engine.position(), L.plan.stops[1].position);
    h.press(dlab::ui::key::kPageDown);
    h.press(dlab::ui::key::kPageUp);
    EXPECT_EQ(L.progress.stop, 1u);
    EXPECT_EQ(st.engine.position(), L.plan.stops[1].position);
    // Out of presentation mode, Page Down steps one operation as before.
    st.presentation = false;
    h.frames(2);
    h.press(dlab::ui::key::kPageDown);
    EXPECT_EQ(L.progress.stop, 1u);
    EXPECT_EQ(st.engine.position(), L.plan.stops[1].position + 1);
}

TEST(LessonSlides, AStopsViewFitsItsVerticesAndItsTabIsShown) {
    UiHarness h(1280, 720);
    auto& st = h.state();
    st.presentation = true;
    // Lesson 5 zooms on the cascade (vertices 2 to 11), away from vertices 0 and 1 high above.
    ASSERT_TRUE(dlab::ui::openLesson(st, lessonPath("05_flips.toml")));
    dlab::ui::goToStop(st, 1);
    h.frames(3);
    const auto canvas = h.rect("canvas");
    const auto& G = st.engine.mesh().G;
    const auto left = st.view.toScreen(G[2]), right = st.view.toScreen(G[10]);
    EXPECT_GE(left.x, canvas[0]);
    EXPECT_LE(right.x, canvas[2]);
    EXPECT_GT(right.x - left.x, 0.7 * (canvas[2] - canvas[0]));
    EXPECT_LT(st.view.toScreen(G[1]).y, canvas[1]) << "vertex 1 is off the slide";
    EXPECT_FALSE(st.itemRects.count("slide-tab"));
    // Its stop at the end of the run shows the whole run, with the statistics in front.
    const auto& stops = st.lessonPlayer.lesson->stops;
    std::size_t end = stops.size() - 1;
    while (end > 0 && stops[end].tab != "statistics") --end;
    dlab::ui::goToStop(st, end);
    st.itemRects.clear();
    h.frames(3);
    EXPECT_GE(st.view.toScreen(G[0]).y, canvas[1]);
    EXPECT_TRUE(st.itemRects.count("slide-tab"));
    // Lesson 8 shows its ID buffer beside the canvas.
    ASSERT_TRUE(dlab::ui::openLesson(st, lessonPath("08_idbuffer.toml")));
    st.itemRects.clear();
    h.frames(3);
    EXPECT_TRUE(st.itemRects.count("slide-tab"));
}

TEST(LessonPlayer, ClosingALessonBringsBackTheUsersOverlays) {
    UiHarness h;
    auto& st = h.state();
    st.overlays.cornerIds = true;
    st.overlays.walk = true;
    st.overlays.circumcircles = false;
    h.frames(2);
    ASSERT_TRUE(dlab::ui::openLesson(st, lessonPath("05_flips.toml")));
    h.frames(2);
    // The lesson's overlays: no corner ids, no walk, circumcircles.
    EXPECT_FALSE(st.overlays.cornerIds);
    EXPECT_FALSE(st.overlays.walk);
    EXPECT_TRUE(st.overlays.circumcircles);
    // Settings saved while the lesson is open keep the user's overlays.
    const auto settings = std::filesystem::temp_directory_path() / "dlab_lesson_settings.json";
    std::string error;
    ASSERT_TRUE(dlab::ui::saveSettings(settings.string(), st, {}, error)) << error;
    {
        dlab::ui::AppState fresh;
        dlab::ui::WindowOptions window;
        fresh.overlays.cornerIds = false;
        fresh.overlays.circumcircles = true;
        dlab::ui::loadSettings(settings.string(), fresh, window, error);
        EXPECT_TRUE(fresh.overlays.cornerIds);
        EXPECT_TRUE(fresh.overlays.walk);
        EXPECT_FALSE(fresh.overlays.circumcircles);
    }
    h.clickItem("lesson-close");
    EXPECT_FALSE(st.lessonPlayer.lesson);
    EXPECT_TRUE(st.overlays.cornerIds);
    EXPECT_TRUE(st.overlays.walk);
    EXPECT_FALSE(st.overlays.circumcircles);
    // A stop's zoom is not left behind: the canvas shows every point again.
    const auto canvas = h.rect("canvas");
    for (const dlab::Vec2& p : st.engine.points()) {
        const auto q = st.view.toScreen(p);
        EXPECT_TRUE(q.x >= canvas[0] && q.x <= canvas[2] && q.y >= canvas[1] && q.y <= canvas[3]);
    }
}

TEST(LessonPlayer, AnAssignmentShowsItsText) {
    UiHarness h;
    auto& st = h.state();
    ASSERT_TRUE(dlab::ui::openLesson(st, lessonPath("10_assignment_insertion.toml")));
    st.itemRects.clear();
    h.frames(3);
    ASSERT_TRUE(st.itemRects.count("assignment-text"));
    const auto r = st.itemRects["assignment-text"];
    EXPECT_GT(r[3] - r[1], 5 * ImGui::GetFontSize()) << "several lines of the text are on show";
    h.clickItem("lesson-close");
    EXPECT_FALSE(st.lessonPlayer.lesson);
}

TEST(CanvasLabels, ATriangleLabelMovesOffALabelAtItsCentroidAndStaysInside) {
    dlab::ui::LabelBoxes labels;
    const ImVec2 tri[3] = {{0, 0}, {300, 0}, {0, 240}};
    const ImVec2 centre(100, 80), size(30, 14);
    labels.add(centre, ImVec2(40, 20));  // a vertex label already sits on the centroid
    const ImVec2 at = dlab::ui::placeInside(labels, tri, centre, size);
    EXPECT_FALSE(at.x == centre.x && at.y == centre.y);
    // Inside the triangle (x, y >= 0, below the hypotenuse) and clear of the first label.
    EXPECT_GE(at.x - size.x / 2, 0.0f);
    EXPECT_GE(at.y - size.y / 2, 0.0f);
    EXPECT_LE((at.x + size.x / 2) / 300 + (at.y + size.y / 2) / 240, 1.0f);
    EXPECT_FALSE(at.x - size.x / 2 < 120 && 80 < at.x + size.x / 2 && at.y - size.y / 2 < 90 &&
                 70 < at.y + size.y / 2);
    // A free centroid stays where it is.
    dlab::ui::LabelBoxes empty;
    const ImVec2 free = dlab::ui::placeInside(empty, tri, centre, size);
    EXPECT_EQ(free.x, centre.x);
    EXPECT_EQ(free.y, centre.y);
}

TEST(CanvasLabels, AGhostCornerLabelTakesTheFirstFreeSpot) {
    dlab::ui::LabelBoxes labels;
    labels.add(ImVec2(50, 50), ImVec2(20, 14));
    const ImVec2 at =
        dlab::ui::placeFirstFree(labels, {ImVec2(52, 50), ImVec2(52, 90)}, ImVec2(20, 14));
    EXPECT_EQ(at.y, 90.0f);
    EXPECT_FALSE(labels.isFree(42, 83, 62, 97)) << "the label is registered";
}

TEST(LessonSlides, TheTextOfAFrameIsReadBackFromItsDrawLists) {
    UiHarness h(1280, 720);
    auto& st = h.state();
    st.presentation = true;
    ASSERT_TRUE(dlab::ui::openLesson(st, lessonPath("01_corner_table.toml")));
    const auto& stops = st.lessonPlayer.lesson->stops;
    const auto last = stops.size() - 2;  // the corner table, corner 2 selected (then a summary)
    ASSERT_EQ(stops[last].tab, "corner-table");
    dlab::ui::goToStop(st, last);
    h.frames(3);
    const std::vector<std::string> lines =
        dlab::ui::drawnLines(dlab::ui::drawnText(ImGui::GetDrawData()));
    const auto has = [&](const std::string& want) {
        return std::any_of(lines.begin(), lines.end(),
                           [&](const std::string& l) { return l.find(want) != std::string::npos; });
    };
    std::string all;
    for (const std::string& l : lines) all += l + "\n";
    // Table cells, one row per line; its header; the banner; canvas labels; the question.
    const dlab::Mesh& m = st.engine.mesh();
    const std::string row2 = "2 | 0 | " + std::to_string(m.V[2]) + " | " + std::to_string(m.O[2]);
    EXPECT_TRUE(has(row2)) << row2 << "\n" << all;
    EXPECT_TRUE(has(std::to_string(m.numCorners()) + " corners")) << all;
    EXPECT_TRUE(has("Finalize: 4 ghost triangles removed")) << all;
    EXPECT_TRUE(std::count(lines.begin(), lines.end(), std::string("t1")) == 1) << all;
    EXPECT_TRUE(has("which")) << all;
    // What the check makes of them: the count of corners is on this slide, and not on one whose
    // side tab is the vertex table.
    dlab::Answer corners;
    corners.kind = dlab::Answer::Kind::Integer;
    corners.a = m.numCorners();
    corners.units = {"corners", "corner"};
    EXPECT_TRUE(dlab::answerOnSlide(corners, lines, ""));
    dlab::ui::goToStop(st, last - 1);
    h.frames(3);
    EXPECT_FALSE(dlab::answerOnSlide(
        corners, dlab::ui::drawnLines(dlab::ui::drawnText(ImGui::GetDrawData())), ""));
}

// A glyph whose ink reaches left of its pen position (a "T" opening a paragraph at the edge of
// the text's clip rectangle) is read: the check of the slide sees the whole word.
TEST(LessonSlides, ALineOpeningWithAnOverhangingLetterIsReadWhole) {
    UiHarness h(1280, 720);
    auto& st = h.state();
    st.presentation = true;
    ASSERT_TRUE(dlab::ui::openLesson(st, lessonPath("11_flip_algorithm.toml")));
    dlab::ui::goToStop(st, 0);
    h.frames(3);
    std::string all;
    for (const std::string& l : dlab::ui::drawnLines(dlab::ui::drawnText(ImGui::GetDrawData())))
        all += l + "\n";
    EXPECT_NE(all.find("\nThis time"), std::string::npos) << all;
    EXPECT_EQ(all.find("\nhis time"), std::string::npos) << all;
}

// A stop looks the same whether the slides were paged to it or the lesson was reopened at it
// (the progress kept in the settings): the same overlays, and the same text drawn.
TEST(LessonSlides, AResumedStopShowsWhatPagingToItShows) {
    const std::string path = lessonPath("05_flips.toml");
    const std::size_t stop = 3;  // after stop 1, the only one naming its overlays
    auto everyOverlayOn = [](dlab::ui::Overlays& o) {
        for (bool* b :
             {&o.fill, &o.vertexIds, &o.cornerIds, &o.triangleIds, &o.walk, &o.flipQueue,
              &o.flipped, &o.circumcircles, &o.voronoi, &o.pendingPoints, &o.virtualTriangles})
            *b = true;
    };
    // One GUI at a time (one ImGui context): each gives its overlays and the text it drew.
    // `resumeAt`: reopen the lesson where the settings say the student was; else page to it.
    struct Seen {
        dlab::ui::Overlays overlays;
        std::vector<std::string> lines;
        std::size_t stop = 0;
    };
    auto show = [&](bool resume) {
        UiHarness h(1280, 720);
        auto& st = h.state();
        st.presentation = true;
        everyOverlayOn(st.overlays);  // the user's own: ids and ghost labels everywhere
        if (resume) {
            dlab::LessonProgress kept;
            kept.lesson = path;
            kept.title = dlab::loadLesson(path).title;
            kept.stop = kept.furthest = stop;
            st.lessonPlayer.saved[path] = kept;
        }
        EXPECT_TRUE(dlab::ui::openLesson(st, path));
        for (std::size_t k = 1; !resume && k <= stop; ++k) h.press(dlab::ui::key::kPageDown);
        h.frames(3);
        return Seen{st.overlays, dlab::ui::drawnLines(dlab::ui::drawnText(ImGui::GetDrawData())),
                    st.lessonPlayer.progress.stop};
    };
    const Seen paged = show(false), resumed = show(true);
    ASSERT_EQ(paged.stop, stop);
    ASSERT_EQ(resumed.stop, stop);
    const auto& a = paged.overlays;
    const auto& b = resumed.overlays;
    EXPECT_EQ(b.vertexIds, a.vertexIds);
    EXPECT_EQ(b.cornerIds, a.cornerIds);
    EXPECT_EQ(b.triangleIds, a.triangleIds);
    EXPECT_EQ(b.virtualTriangles, a.virtualTriangles);
    EXPECT_EQ(b.circumcircles, a.circumcircles);
    EXPECT_FALSE(b.cornerIds);  // stop 1 names its overlays: no corner ids among them
    std::string pa, pb;
    for (const std::string& l : paged.lines) pa += l + "\n";
    for (const std::string& l : resumed.lines) pb += l + "\n";
    EXPECT_EQ(paged.lines, resumed.lines) << "paged:\n" << pa << "\nresumed:\n" << pb;
}

// ---- Tracks: one lecture made of stops of several lessons ---------------------------------------

TEST(LessonTrack, PageDownPlaysTheLectureAcrossLessons) {
    UiHarness h;
    auto& st = h.state();
    const std::string path = lessonPath("lecture.toml");
    const dlab::Track track = dlab::loadTrack(path);
    ASSERT_TRUE(dlab::ui::openLesson(st, path));
    st.presentation = true;
    h.frames(2);
    ASSERT_TRUE(st.lessonPlayer.track);
    EXPECT_EQ(dlab::ui::slideCount(st), track.slides());
    // The track's objectives on its first slide, not the first lesson's.
    const std::string& first = st.lessonPlayer.plan.stops[track.items[0].stops[0]].text;
    EXPECT_EQ(first.rfind(dlab::objectivesText(track.objectives), 0), 0u) << first;
    std::size_t k = 0;
    for (const auto& [item, stop] : dlab::trackSlides(track)) {
        SCOPED_TRACE("slide " + std::to_string(k + 1));
        EXPECT_EQ(dlab::ui::slideIndex(st), k);
        // The item's lesson is the one open, at the item's stop, its run at that stop.
        EXPECT_EQ(st.lessonPlayer.progress.lesson, track.items[item].lesson);
        EXPECT_EQ(st.lessonPlayer.progress.stop, stop);
        EXPECT_EQ(st.engine.position(), st.lessonPlayer.plan.stops[stop].position);
        h.press(dlab::ui::key::kPageDown);
        ++k;
    }
    EXPECT_EQ(dlab::ui::slideIndex(st), track.slides() - 1) << "Page Down stops at the end";
    // Page Up goes back across the boundary into the previous item's lesson.
    const auto slides = dlab::trackSlides(track);
    std::size_t boundary = 1;
    while (slides[boundary].first == slides[boundary - 1].first) ++boundary;
    dlab::ui::goToSlide(st, boundary);
    h.press(dlab::ui::key::kPageUp);
    EXPECT_EQ(dlab::ui::slideIndex(st), boundary - 1);
    EXPECT_EQ(st.lessonPlayer.progress.lesson, track.items[slides[boundary - 1].first].lesson);
    EXPECT_EQ(st.lessonPlayer.progress.stop, slides[boundary - 1].second);
    // Opening a lesson by itself leaves the track.
    ASSERT_TRUE(dlab::ui::openLesson(st, lessonPath("01_corner_table.toml")));
    EXPECT_FALSE(st.lessonPlayer.track);
    dlab::ui::closeLesson(st);
}

TEST(LessonSlides, AHandoutsPictureShowsTheCanvasAndTheTextOnly) {
    UiHarness h(1280, 720);
    auto& st = h.state();
    st.presentation = true;
    ASSERT_TRUE(dlab::ui::openLesson(st, lessonPath("05_flips.toml")));
    // A stop with a question and a side tab (the statistics, which count its answer).
    std::size_t k = 0;
    const auto& stops = st.lessonPlayer.lesson->stops;
    while (k < stops.size() && (stops[k].question.empty() || stops[k].tab.empty())) ++k;
    if (k == stops.size()) k = 5;  // the flips question: its tab comes from an earlier stop
    const auto drawn = [&] {
        dlab::ui::goToStop(st, k);
        st.itemRects.clear();  // what the frames below record, not what earlier ones did
        h.frames(3);
        std::string all;
        for (const std::string& line :
             dlab::ui::drawnLines(dlab::ui::drawnText(ImGui::GetDrawData())))
            all += line + "\n";
        return all;
    };
    const std::string slide = drawn();
    EXPECT_NE(slide.find("Lessons"), std::string::npos) << "the menus, on a slide";
    EXPECT_TRUE(st.itemRects.count("lesson-answer")) << slide;
    st.handoutSlides = true;
    const std::string picture = drawn();
    for (const char* gone : {"Lessons", "Generate", "Check", "Hint", "Close"})
        EXPECT_EQ(picture.find(gone), std::string::npos) << gone << " in\n" << picture;
    EXPECT_FALSE(st.itemRects.count("lesson-answer"));
    EXPECT_FALSE(st.itemRects.count("slide-tab"));
    EXPECT_FALSE(st.itemRects.count("lesson-next"));
    // The stop's own words are there.
    EXPECT_NE(picture.find(st.lessonPlayer.lesson->title), std::string::npos) << picture;
    st.handoutSlides = false;
    dlab::ui::closeLesson(st);
}
