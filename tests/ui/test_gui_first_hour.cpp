// What a newcomer meets in the first hour, driven as they drive it: End and the saved speed,
// typing into text fields, an in-circle test against a ghost triangle, small windows and
// resizes, why stepping is off, the counts of points, and the small things (captions, the corner
// table's cells and tooltips, side tabs, the timeline, F1, F12, the Open dialog, Esc, ghost
// corners, bad files).
#include "core/engine/generators.h"
#include "tests/ui/ui_harness.h"
#include "ui/files/files.h"
#include "ui/files/settings.h"
#include "ui/lesson_player.h"
#include "ui/panels/panels.h"
#include "ui/platform/keys.h"

#include <gtest/gtest.h>
#include <imgui.h>
#include <unistd.h>
#include <glm/geometric.hpp>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

using dlab::kNone;
using dlab::OpType;
using dlab::Vec2;
using dlab::test::UiHarness;
namespace key = dlab::ui::key;
namespace fs = std::filesystem;

namespace {

// A fresh folder under the system's temporary folder, removed with its contents at the end.
struct TempDir {
    fs::path path;
    explicit TempDir(const std::string& name) {
        path = fs::temp_directory_path() /
               (name + "-" + std::to_string(::getpid()) + "-" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(path);
        fs::create_directories(path);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

// Types as a keyboard does in the real window: each key goes down (what the shortcuts see) and
// gives its character (what a text field sees).
void typeKeys(UiHarness& h, const std::string& text) {
    ImGuiIO& io = ImGui::GetIO();
    for (char ch : text) {
        const int k = key::letter(ch);
        io.KeysDown[k] = true;
        dlab::ui::queueKeyPress(k, false, false);
        io.AddInputCharacter(static_cast<unsigned>(ch));
        h.frames(1);
        io.KeysDown[k] = false;
        h.frames(1);
    }
}

// Whether the item was drawn in the last frame (itemRects keeps old entries: clear, draw, look).
bool drawnNow(UiHarness& h, const std::string& name) {
    h.state().itemRects.erase(name);
    h.frames(1);
    return h.state().itemRects.count(name) > 0;
}

void runToEnd(UiHarness& h) {
    for (int i = 0; i < 400 && h.state().run.running; ++i) h.frames(1);
}

void stepTo(UiHarness& h, const std::function<bool(const dlab::Op&)>& wanted) {
    auto& e = h.state().engine;
    while (e.forward()) {
        if (wanted(*e.current())) break;
    }
    h.frames(2);
}

}  // namespace

// ============================================================================================
// End and the user's speed
// ============================================================================================

TEST(GuiRun, EndRunsToTheEndButKeepsTheSavedSpeed) {
    TempDir dir("dlab-speed");
    const std::string settings = (dir.path / "settings.json").string();
    {
        UiHarness h;
        auto& st = h.state();
        st.run.opsPerSecond = 6.0f;
        h.press(key::kEnd);
        runToEnd(h);
        EXPECT_TRUE(st.engine.atEnd());
        EXPECT_EQ(st.run.opsPerSecond, 6.0f) << "End changed the speed slider";
        h.press(key::kHome);
        h.clickItem(">|");
        runToEnd(h);
        EXPECT_TRUE(st.engine.atEnd());
        EXPECT_EQ(st.run.opsPerSecond, 6.0f) << ">| changed the speed slider";
        std::string error;
        dlab::ui::WindowOptions window;
        ASSERT_TRUE(dlab::ui::saveSettings(settings, st, window, error)) << error;
    }
    // A restart with those settings: Space runs at the user's 6 operations a second.
    UiHarness h;
    auto& st = h.state();
    dlab::ui::WindowOptions window;
    std::string warning;
    dlab::ui::loadSettings(settings, st, window, warning);
    EXPECT_TRUE(warning.empty()) << warning;
    EXPECT_EQ(st.run.opsPerSecond, 6.0f);
    h.press(key::kSpace);
    ImGui::GetIO().DeltaTime = 0.1f;
    h.frames(5);
    ImGui::GetIO().DeltaTime = 1.0f / 60.0f;
    EXPECT_LE(st.engine.position(), 6u) << "Space ran at full speed after a restart";
    EXPECT_FALSE(st.engine.atEnd());
}

TEST(GuiRun, PausingARunToTheEndGoesOnAtTheSlidersSpeed) {
    UiHarness h;
    auto& st = h.state();
    st.run.opsPerSecond = 2.0f;
    st.run.runToEnd();
    EXPECT_TRUE(st.run.fullSpeed());
    h.press(key::kSpace);  // pause before it ran
    EXPECT_FALSE(st.run.running);
    h.press(key::kSpace);  // and on again: at 2 operations a second
    EXPECT_FALSE(st.run.fullSpeed());
    const std::size_t at = st.engine.position();
    ImGui::GetIO().DeltaTime = 0.1f;
    h.frames(5);
    ImGui::GetIO().DeltaTime = 1.0f / 60.0f;
    EXPECT_LE(st.engine.position(), at + 2);
    EXPECT_EQ(st.run.opsPerSecond, 2.0f);
}

// ============================================================================================
// Text fields keep the keyboard
// ============================================================================================

TEST(GuiKeyboard, ExpressionFieldKeepsTheKeyboardAfterEnter) {
    UiHarness h;
    auto& st = h.state();
    while (!st.engine.toEnd(1 << 20)) {}
    st.select(4);
    h.clickItem("Expressions");
    h.frames(2);
    h.clickItem("expr-input");
    typeKeys(h, "n(c)");
    h.press(key::kEnter);
    ASSERT_EQ(st.expressions.history.size(), 1u);
    EXPECT_TRUE(st.expressions.history.back().ok) << st.expressions.history.back().answer;
    // The next expression, typed straight away, goes to the field again.
    const bool circles = st.overlays.circumcircles;
    typeKeys(h, "o(c)");
    EXPECT_EQ(st.overlays.circumcircles, circles) << "'c' toggled the circumcircles";
    EXPECT_EQ(st.selection.corner, 4) << "'o' moved the selection";
    EXPECT_EQ(st.expressions.input, "o(c)");
    h.press(key::kEnter);
    ASSERT_EQ(st.expressions.history.size(), 2u);
    EXPECT_EQ(st.expressions.history.back().text, "o(c)");
}

struct TextField {
    const char* name;          // its itemRects name
    void (*open)(UiHarness&);  // brings it on screen
};

void PrintTo(const TextField& field, std::ostream* os) { *os << field.name; }

class GuiTextField : public ::testing::TestWithParam<TextField> {};

// Every text field: while it has the keyboard, letters are typing, never shortcuts.
TEST_P(GuiTextField, NoShortcutFiresWhileItHasTheKeyboard) {
    UiHarness h;
    auto& st = h.state();
    while (!st.engine.toEnd(1 << 20)) {}
    st.select(4);
    h.frames(2);
    // A view of the user's own: F would change it.
    const auto canvas = h.rect("canvas");
    h.scroll((canvas[0] + canvas[2]) / 2, (canvas[1] + canvas[3]) / 2, 2);
    GetParam().open(h);
    h.frames(2);
    ASSERT_TRUE(st.itemRects.count(GetParam().name)) << GetParam().name << " is not on screen";
    // Into the text, near its left end (a number field ends with its - and + buttons).
    const auto field = h.rect(GetParam().name);
    h.click(field[0] + 12, (field[1] + field[3]) / 2);
    ASSERT_TRUE(ImGui::GetIO().WantTextInput) << GetParam().name << " did not take the keyboard";
    const auto overlays = st.overlays;
    const bool snap = st.snapToGrid;
    const auto view = st.view;
    // Every single-letter shortcut: corner operators, fit, Voronoi, circumcircles, grid.
    typeKeys(h, "nplorsufvcg");
    EXPECT_EQ(st.selection.corner, 4);
    EXPECT_EQ(st.overlays.voronoi, overlays.voronoi);
    EXPECT_EQ(st.overlays.circumcircles, overlays.circumcircles);
    EXPECT_EQ(st.snapToGrid, snap);
    EXPECT_EQ(st.view.center, view.center);
    EXPECT_EQ(st.view.scale, view.scale);
}

void openNothing(UiHarness&) {}
void openExpressions(UiHarness& h) { h.clickItem("Expressions"); }
void openPredicates(UiHarness& h) { h.clickItem("Predicates"); }
void openBreakpoints(UiHarness& h) { h.clickItem("breakpoints"); }
void openRandomOrder(UiHarness& h) {
    dlab::InsertOptions o = h.state().engine.options();
    o.order = dlab::OrderKind::Random;
    h.state().setOptions(o);
    while (!h.state().engine.toEnd(1 << 20)) {}
    h.state().select(4);
}
void openDialog(UiHarness& h) { h.press(key::letter('O'), false, /*ctrl=*/true); }

INSTANTIATE_TEST_SUITE_P(EveryField, GuiTextField,
                         ::testing::Values(TextField{"expr-input", openExpressions},
                                           TextField{"watch-input", openExpressions},
                                           TextField{"predicate-point-a", openPredicates},
                                           TextField{"predicate-point-d", openPredicates},
                                           TextField{"go-to-corner", openNothing},
                                           TextField{"seed", openRandomOrder},
                                           TextField{"breakpoint-vertex", openBreakpoints},
                                           TextField{"breakpoint-corner", openBreakpoints},
                                           TextField{"breakpoint-text", openBreakpoints},
                                           TextField{"dialog-path", openDialog}),
                         [](const ::testing::TestParamInfo<TextField>& info) {
                             std::string n = info.param.name;
                             for (char& c : n)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return n;
                         });

// ============================================================================================
// An in-circle test against a ghost triangle
// ============================================================================================

TEST(GuiCanvas, InCircleTestAgainstAGhostTriangleDrawsTheHullEdgeAndItsHalfPlane) {
    UiHarness h(1600, 1000);
    auto& st = h.state();
    st.overlays.cornerIds = false;
    st.overlays.vertexIds = false;
    const dlab::Inserter& ins = st.engine.inserter();
    const dlab::Mesh& m = st.engine.mesh();
    // The first in-circle test whose far triangle is a ghost one.
    stepTo(h, [&](const dlab::Op& op) {
        return op.type == OpType::InCircleTest && op.b != kNone &&
               ins.isVirtualTriangle(dlab::tri(op.b)) && st.engine.flippedEdges().empty();
    });
    const dlab::Op* op = st.engine.current();
    ASSERT_TRUE(op && op->type == OpType::InCircleTest);
    // Its hull edge u -> w: the two real vertices of the ghost triangle, in its order.
    const std::int32_t t = dlab::tri(op->b);
    int k = 0;
    while (!ins.isVirtual(m.V[3 * t + k])) ++k;
    const std::int32_t u = m.V[3 * t + (k + 1) % 3], w = m.V[3 * t + (k + 2) % 3];
    const auto& view = st.view;
    const glm::dvec2 pu = view.toScreen(m.G[u]), pw = view.toScreen(m.G[w]);
    // The hull edge itself, solid: the edge under test's orange when the test is of that edge,
    // else (an edge to the ghost vertex, which has no segment) in the test's colour.
    const bool hullEdgeTested =
        !ins.isVirtual(m.V[dlab::next(op->a)]) && !ins.isVirtual(m.V[dlab::prev(op->a)]);
    const std::array<int, 3> col = hullEdgeTested ? std::array<int, 3>{240, 120, 0}
                                   : op->sign > 0 ? std::array<int, 3>{215, 40, 40}
                                                  : std::array<int, 3>{30, 150, 60};
    int onEdge = 0;
    for (double s = 0.3; s <= 0.71; s += 0.1) {
        const glm::dvec2 p = pu + (pw - pu) * s;
        onEdge +=
            h.pixel(static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y))) == col;
    }
    EXPECT_GE(onEdge, 4) << "the hull edge is not drawn";
    // The half-plane beyond it (the ghost's side: the world's left of u -> w) is shaded, the
    // side of the mesh is not.
    const glm::dvec2 d = glm::normalize(pw - pu), out(d.y, -d.x), mid = (pu + pw) * 0.5;
    auto tinted = [&](glm::dvec2 p) {
        const auto px = h.pixel(static_cast<int>(p.x), static_cast<int>(p.y));
        return std::abs(px[0] - px[1]) > 8 || std::abs(px[1] - px[2]) > 8;
    };
    int shaded = 0;
    for (int i = 0; i < 9; ++i) shaded += tinted(mid + out * (70.0 + 5 * i) + d * ((i - 4) * 6.0));
    EXPECT_GE(shaded, 7) << "the half-plane beyond the hull edge is not shaded";
    // The old drawing: a line from the hull vertex to the ghost's placeholder coordinates.
    const std::int32_t ghost = m.V[3 * t + k];
    const std::int32_t hullVertex =
        ins.isVirtual(m.V[dlab::next(op->a)]) ? m.V[dlab::prev(op->a)] : m.V[dlab::next(op->a)];
    const glm::dvec2 pg = view.toScreen(m.G[ghost]), ph = view.toScreen(m.G[hullVertex]);
    int onOldLine = 0;
    for (double s = 0.25; s <= 0.75; s += 0.01) {
        const glm::dvec2 p = ph + (pg - ph) * s;
        onOldLine +=
            h.pixel(static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y))) == col;
    }
    EXPECT_EQ(onOldLine, 0) << "a line still runs towards the ghost's placeholder";
}

// ============================================================================================
// Small screens and resizes
// ============================================================================================

TEST(GuiWindow, SavedWindowLargerThanTheScreenIsFittedIntoItsWorkArea) {
    TempDir dir("dlab-window");
    const std::string path = (dir.path / "settings.json").string();
    std::ofstream(path) << R"({"window": {"x": 900, "y": 700, "width": 2560, "height": 1440}})";
    dlab::ui::AppState st;
    dlab::ui::WindowOptions window;
    std::string warning;
    dlab::ui::loadSettings(path, st, window, warning);
    ASSERT_EQ(window.width, 2560);
    // A 1280 x 720 screen whose panel takes 32 pixels at the top.
    dlab::ui::clampWindowToWorkArea(window, 0, 32, 1280, 688);
    EXPECT_EQ(window.width, 1280);
    EXPECT_EQ(window.height, 688);
    EXPECT_EQ(window.x, 0);
    EXPECT_EQ(window.y, 32);
    // A window that fits stays as it was.
    dlab::ui::WindowOptions small;
    small.width = 800;
    small.height = 600;
    small.x = 100;
    small.y = 80;
    dlab::ui::clampWindowToWorkArea(small, 0, 32, 1280, 688);
    EXPECT_EQ(small.width, 800);
    EXPECT_EQ(small.height, 600);
    EXPECT_EQ(small.x, 100);
    EXPECT_EQ(small.y, 80);
}

TEST(GuiWindow, CanvasRefitsAfterAResizeUnlessTheUserMovedTheView) {
    UiHarness h(1600, 1000);
    auto& st = h.state();
    h.frames(2);
    auto allPointsOnCanvas = [&] {
        const auto r = h.rect("canvas");
        for (const Vec2& p : st.engine.points()) {
            const glm::dvec2 s = st.view.toScreen(p);
            if (s.x < r[0] || s.x > r[2] || s.y < r[1] || s.y > r[3]) return false;
        }
        return true;
    };
    ASSERT_TRUE(allPointsOnCanvas());
    ASSERT_TRUE(h.gui().platform().resize(1280, 720));
    h.frames(3);
    EXPECT_TRUE(allPointsOnCanvas()) << "the view was not fitted to the smaller canvas";
    // The user zooms in: a resize keeps their view.
    const auto c = h.rect("canvas");
    h.scroll((c[0] + c[2]) / 2, (c[1] + c[3]) / 2, 3);
    const auto centre = st.view.center;
    const double scale = st.view.scale;
    ASSERT_TRUE(h.gui().platform().resize(1600, 1000));
    h.frames(3);
    EXPECT_EQ(st.view.scale, scale);
    EXPECT_EQ(st.view.center, centre);
}

class GuiSmallScreen : public ::testing::TestWithParam<bool> {};

// At 1280 x 720, normal and presentation mode: every control of the toolbar whole and on screen,
// none over another, and the canvas, the timeline, the side tabs and the messages still there.
TEST_P(GuiSmallScreen, EveryControlIsWholeAndOnScreen) {
    UiHarness h(1280, 720);
    auto& st = h.state();
    st.presentation = GetParam();
    dlab::InsertOptions o = st.engine.options();
    o.order = dlab::OrderKind::Brio;  // the seed field shows too
    st.setOptions(o);
    h.frames(4);
    const char* const toolbar[] = {
        "|<",       ">|",           "run",    "speed",       "breakpoints", "Boundary label",
        "Boundary", "Locate label", "Locate", "Order label", "Order",       "seed"};
    std::vector<std::array<float, 4>> seen;
    for (const char* name : toolbar) {
        ASSERT_TRUE(drawnNow(h, name)) << name << " is not on screen";
        const auto r = h.rect(name);
        EXPECT_GE(r[0], 0) << name;
        EXPECT_LT(r[2], 1280 - 4) << name << " runs into the window's edge";
        for (const auto& q : seen) {
            const bool overlap =
                r[0] < q[2] - 1 && q[0] < r[2] - 1 && r[1] < q[3] - 1 && q[1] < r[3] - 1;
            EXPECT_FALSE(overlap) << name << " overlaps another control";
        }
        seen.push_back(r);
    }
    const auto canvas = h.rect("canvas");
    EXPECT_GT(canvas[3] - canvas[1], 250) << "the canvas is squeezed";
    EXPECT_GT(canvas[2] - canvas[0], 500);
    ASSERT_TRUE(drawnNow(h, "timeline"));
    EXPECT_LE(h.rect("timeline")[2], 1280);
    EXPECT_LE(h.rect("timeline")[3], 720);
    EXPECT_TRUE(drawnNow(h, "Corner table"));
}

INSTANTIATE_TEST_SUITE_P(BothModes, GuiSmallScreen, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& info) {
                             return info.param ? "Presentation" : "Normal";
                         });

// ============================================================================================
// Why stepping is off; counts
// ============================================================================================

TEST(GuiCaption, BannerGivesTheRealReasonSteppingIsOff) {
    UiHarness h;
    auto& st = h.state();
    st.engine.setOpLimit(40);  // a history limit the demo reaches
    st.setOptions(dlab::ui::demoOptions());
    st.loadPoints(dlab::demoPoints(), "built-in demo");
    h.press(key::kEnd);
    runToEnd(h);
    ASSERT_TRUE(st.engine.batch());
    const std::string banner = dlab::ui::captionText(st);
    EXPECT_EQ(banner.find("no stepping above"), std::string::npos) << banner;
    EXPECT_NE(banner.find("the history reached 40 operations"), std::string::npos) << banner;
    // The same words as the message log.
    bool logged = false;
    for (const auto& msg : st.messages)
        logged |= banner.find(msg.text) != std::string::npos && !msg.text.empty() &&
                  msg.text.find("history") != std::string::npos;
    EXPECT_TRUE(logged) << banner;
}

TEST(GuiCounts, TimelineStatisticsAndLessonCountThePointsTheSameWay) {
    UiHarness h;
    auto& st = h.state();
    ASSERT_TRUE(
        dlab::ui::openLesson(st, std::string(DLAB_SOURCE_DIR) + "/lessons/03_locating.toml"));
    h.frames(3);
    const dlab::Mesh& m = st.engine.mesh();
    const dlab::Inserter& ins = st.engine.inserter();
    // Vertices in the mesh, counted from its triangles.
    std::vector<bool> used(st.engine.points().size(), false);
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        if (!ins.isVirtual(m.V[c])) used[static_cast<std::size_t>(m.V[c])] = true;
    }
    const auto in = std::count(used.begin(), used.end(), true);
    const std::string counts = dlab::ui::pointCountsText(st.engine);
    EXPECT_EQ(counts, std::to_string(in) + " of " + std::to_string(st.engine.points().size()) +
                          " points inserted");
    EXPECT_NE(dlab::ui::timelineText(st.engine).find(counts), std::string::npos);
    // The statistics panel's own counts agree: its insertions after the first triangle, plus
    // the first triangle's three.
    const auto& c = dlab::ui::UpdateRunCounts(st);
    EXPECT_EQ(c.inserted + 3, in);
    // At the end of the demo: the duplicate is counted as skipped, the others as inserted.
    dlab::ui::closeLesson(st);
    st.setOptions(dlab::ui::demoOptions());
    st.loadPoints(dlab::demoPoints(), "built-in demo");
    while (!st.engine.toEnd(1 << 20)) {}
    h.frames(2);
    EXPECT_EQ(dlab::ui::pointCountsText(st.engine),
              "11 of 12 points inserted, 1 duplicate skipped");
}

// ============================================================================================
// The small things
// ============================================================================================

TEST(GuiSmall, FirstCaptionSaysStartOnce) {
    UiHarness h;
    h.press(key::kRight);
    const std::string caption = dlab::ui::captionText(h.state());
    EXPECT_EQ(caption.find("Start: start"), std::string::npos) << caption;
    EXPECT_EQ(caption.find("triangle triangle"), std::string::npos) << caption;
    EXPECT_EQ(caption.rfind("[op 1] Start: triangle 0 (", 0), 0u) << caption;
}

TEST(GuiSmall, GhostVertexCellShowsWholeAndItsTooltipCoversTheCell) {
    UiHarness h(1600, 1000);
    auto& st = h.state();
    h.press(key::kRight);  // Start: three ghost triangles
    h.frames(2);
    ASSERT_TRUE(st.itemRects.count("ghost-v-cell"));
    const auto cell = h.rect("ghost-v-cell");
    EXPECT_LE(cell[0], cell[1]) << "\"(ghost)\" is cut: text " << cell[0] << " px in a " << cell[1]
                                << " px cell";
    // The old-value tooltip: hovering the right end of a highlighted cell, far from its digits.
    constexpr std::array<int, 3> kChanged = {255, 200, 120};
    const auto table = h.rect("corner-table");
    int y = -1, xRight = -1;
    for (int yy = static_cast<int>(table[1]); yy < table[3] && y < 0; ++yy) {
        for (int xx = static_cast<int>(table[2]) - 1; xx > table[0]; --xx) {
            if (h.pixel(xx, yy) == kChanged) {
                y = yy + 3;
                xRight = xx - 2;
                break;
            }
        }
    }
    ASSERT_GE(y, 0) << "no highlighted cell";
    st.itemRects.erase("cell-tooltip");
    h.moveTo(static_cast<float>(xRight), static_cast<float>(y));
    EXPECT_TRUE(st.itemRects.count("cell-tooltip")) << "no tooltip at the cell's right end";
}

TEST(GuiSmall, SideTabLabelsShowWholeAt1600Pixels) {
    UiHarness h(1600, 1000);
    h.frames(2);
    const std::pair<const char*, const char*> tabs[] = {
        {"Corner table", "Corners"},  {"G (vertices)", "G"},      {"Expressions", "Expressions"},
        {"Predicates", "Predicates"}, {"ID buffer", "ID buffer"}, {"Statistics", "Statistics"},
        {"Student trace", "Trace"}};
    const float pad = ImGui::GetStyle().FramePadding.x;
    for (const auto& [title, label] : tabs) {
        ASSERT_TRUE(drawnNow(h, title)) << title << " is not on screen";
        const auto r = h.rect(title);
        EXPECT_GE(r[2] - r[0] + 0.5f, ImGui::CalcTextSize(label).x + 2 * pad)
            << "the tab " << label << " is cut";
    }
}

TEST(GuiSmall, TimelineTextIsBesideItsHandleAndNeverSaysOpZeroOfZero) {
    UiHarness h;
    auto& st = h.state();
    h.press(key::kRight);
    h.press(key::kRight);
    ASSERT_TRUE(drawnNow(h, "timeline-text"));
    const auto text = h.rect("timeline-text"), slider = h.rect("timeline");
    EXPECT_LE(text[2], slider[0]) << "the slider covers its text";
    EXPECT_EQ(dlab::ui::timelineText(st.engine).rfind("op 2 of ", 0), 0u);
    // Too many points to record at once: the run is recorded as it goes.
    st.loadPoints(dlab::generatePoints(dlab::Generator::Uniform, 30000, 1), "uniform");
    h.frames(2);
    ASSERT_EQ(st.engine.recorded(), 0u);
    const std::string t = dlab::ui::timelineText(st.engine);
    EXPECT_EQ(t.find("of 0"), std::string::npos) << t;
    EXPECT_EQ(t.rfind("op 0 (recorded as you step)", 0), 0u) << t;
}

TEST(GuiSmall, HelpListsEveryFileShortcut) {
    UiHarness h;
    h.press(key::kF1);
    EXPECT_TRUE(h.state().showHelp);
    EXPECT_TRUE(drawnNow(h, "help"));
    for (const char* k : {"F12", "Ctrl + O", "Ctrl + S", "F1", "Ctrl + Q", "Esc"}) {
        bool listed = false;
        for (const auto& row : dlab::ui::helpRows()) listed |= std::string(row[0]) == k;
        EXPECT_TRUE(listed) << k << " is not in the help";
    }
    h.press(key::kEscape);
    EXPECT_FALSE(h.state().showHelp);
}

TEST(GuiSmall, ScreenshotMessageGivesTheAbsolutePath) {
    TempDir dir("dlab-shot");
    const fs::path before = fs::current_path();
    fs::current_path(dir.path);
    {
        UiHarness h;
        h.press(key::kF12);
        dlab::ui::serviceCaptures(h.gui());
        const std::string msg = h.state().messages.back().text;
        ASSERT_EQ(msg.rfind("screenshot: ", 0), 0u) << msg;
        const std::string path = msg.substr(12);
        EXPECT_TRUE(fs::path(path).is_absolute()) << path;
        EXPECT_TRUE(fs::exists(path)) << path;
    }
    fs::current_path(before);
}

TEST(GuiSmall, DoubleClickInTheOpenDialogOpensTheFile) {
    TempDir dir("dlab-open");
    const fs::path file = dir.path / "square.csv";
    std::ofstream(file) << "0,0\n10,0\n10,10\n0,10\n5,5\n";
    UiHarness h;
    auto& st = h.state();
    h.press(key::letter('O'), false, /*ctrl=*/true);
    st.files.dialogPath = (dir.path / "x").string();
    h.frames(2);
    const auto r = h.rect("dialog-file:square.csv");
    const float x = (r[0] + r[2]) / 2, y = (r[1] + r[3]) / 2;
    ImGui::GetIO().DeltaTime = 1.0f / 60.0f;
    h.click(x, y);
    h.click(x, y);
    EXPECT_EQ(st.engine.points().size(), 5u) << "the double-clicked file was not opened";
    EXPECT_EQ(st.source, file.string());
    EXPECT_FALSE(drawnNow(h, "dialog-ok")) << "the dialog stayed open";
}

TEST(GuiSmall, ToolbarLabelsComeBeforeTheirCombos) {
    UiHarness h;
    for (const char* name : {"Boundary", "Locate", "Order"}) {
        const auto label = h.rect(std::string(name) + " label"), combo = h.rect(name);
        EXPECT_LE(label[2], combo[0]) << name;
        EXPECT_LT(std::abs((label[1] + label[3]) - (combo[1] + combo[3])) / 2, 4.0f) << name;
    }
}

TEST(GuiSmall, EscClosesTheBreakpointsPopupAndKeepsTheSelection) {
    UiHarness h;
    auto& st = h.state();
    while (!st.engine.toEnd(1 << 20)) {}
    st.select(4);
    h.clickItem("breakpoints");
    ASSERT_TRUE(drawnNow(h, "breakpoints-popup"));
    h.press(key::kEscape);
    EXPECT_FALSE(drawnNow(h, "breakpoints-popup"));
    EXPECT_EQ(st.selection.corner, 4) << "Esc closed the popup and cleared the selection";
}

TEST(GuiSmall, GhostCornersAreLabelledOnTheCanvasAndCanBeClicked) {
    UiHarness h(1600, 1000);
    auto& st = h.state();
    h.press(key::kRight);  // Start: one real triangle, three ghost ones
    h.frames(2);
    const dlab::Inserter& ins = st.engine.inserter();
    const dlab::Mesh& m = st.engine.mesh();
    int ghostCorners = 0;
    std::int32_t clickable = kNone;
    float cx = 0, cy = 0;
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        if (!ins.isVirtualTriangle(dlab::tri(c))) continue;
        float x = 0, y = 0;
        if (!dlab::ui::cornerAnchor(st, c, x, y)) continue;
        ++ghostCorners;
        if (ins.isVirtual(m.V[c]) && clickable == kNone) {
            clickable = c;
            cx = x;
            cy = y;
        }
    }
    EXPECT_EQ(ghostCorners, 9) << "the ghost triangles' corners have no place on the canvas";
    ASSERT_NE(clickable, kNone);
    h.click(cx, cy);
    EXPECT_EQ(st.selection.corner, clickable);
}

TEST(GuiSmall, ShortNodeFileIsExplainedInAUsersWords) {
    TempDir dir("dlab-node");
    const fs::path file = dir.path / "short.node";
    std::ofstream(file) << "5 2 0 0\n0 0 0\n1 1 0\n";
    UiHarness h;
    EXPECT_FALSE(dlab::ui::loadPointFile(h.state(), file.string()));
    const std::string msg = h.state().messages.back().text;
    EXPECT_NE(msg.find("5 vertices but only 2 lines follow"), std::string::npos) << msg;
    EXPECT_EQ(msg.find("bytes"), std::string::npos) << msg;
}

TEST(GuiSmall, FallbackDemoAfterABadFileRunsInTheDemosOrder) {
    UiHarness h;
    auto& st = h.state();
    dlab::InsertOptions o = st.engine.options();
    o.order = dlab::OrderKind::Brio;
    st.setOptions(o);
    EXPECT_FALSE(dlab::ui::openStartupInput(st, "/no/such/folder/points.node"));
    EXPECT_FALSE(st.files.notice.empty());
    EXPECT_EQ(st.source, "built-in demo");
    EXPECT_EQ(st.engine.options().order, dlab::OrderKind::Input);
    // The vertices go in as in the demo started without a file.
    dlab::ui::Engine demo;
    std::string error;
    ASSERT_TRUE(demo.reset(dlab::demoPoints(), dlab::ui::demoOptions(), error)) << error;
    for (int k = 0; k < 5; ++k) {
        h.press(key::kRight, /*shift=*/true);
        demo.forwardInsertion();
        ASSERT_NE(st.engine.current(), nullptr);
        EXPECT_EQ(st.engine.current()->vertex, demo.current()->vertex) << "insertion " << k;
    }
}
