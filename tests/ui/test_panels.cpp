// The debugging panels driven as a user drives them: an expression typed into the console
// (its value and the path drawn on the canvas), watches that pause a run, the predicate
// inspector's warning on a near-degenerate in-circle test where plain floating point is wrong,
// the ID-buffer view hovered and checked against the core's locator, and the statistics.
#include "core/engine/generators.h"
#include "core/engine/predicates.h"
#include "tests/ui/ui_harness.h"
#include "ui/gl/idbuffer_gl.h"
#include "ui/panels/panels.h"
#include "ui/platform/keys.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <set>

using dlab::kNone;
using dlab::OpType;
using dlab::Vec2;
using dlab::test::UiHarness;
namespace key = dlab::ui::key;

namespace {

constexpr std::array<int, 3> kPathRgb = {214, 0, 120};     // expressions.cpp
constexpr std::array<int, 3> kWarningRgb = {200, 20, 30};  // predicates.cpp
constexpr std::array<int, 3> kViolationRgb = {230, 0, 0};  // statistics.cpp
constexpr std::array<int, 3> kPendingRgb = {245, 110,
                                            150};  // statistics.cpp: expected mid-insertion

void typeText(UiHarness& h, const std::string& text) {
    for (char ch : text) {
        ImGui::GetIO().AddInputCharacter(static_cast<unsigned>(ch));
        h.frames(1);
    }
}

// Opens a side tab by clicking it, as a user does.
void openTab(UiHarness& h, const char* name) {
    h.clickItem(name);
    h.frames(2);
}

bool anchorOf(UiHarness& h, std::int32_t c, float& x, float& y) {
    return dlab::ui::cornerAnchor(h.state(), c, x, y);
}

std::array<float, 4> around(float x, float y, float r) { return {x - r, y - r, x + r, y + r}; }

// Whether the item was drawn in the last frame (itemRects keeps old entries: clear, draw, look).
bool drawnNow(UiHarness& h, const std::string& name) {
    h.state().itemRects.erase(name);
    h.frames(1);
    return h.state().itemRects.count(name) > 0;
}

}  // namespace

// ============================================================================================
// Corner expressions
// ============================================================================================

TEST(Panels, TypedExpressionGivesItsValueAndDrawsItsPath) {
    UiHarness h;
    auto& st = h.state();
    while (!st.engine.toEnd(1 << 20)) {}
    h.frames(2);
    const dlab::Mesh& m = st.engine.mesh();
    // A corner whose c.n.o path is visible all the way: c, n(c) and o(n(c)) labelled on the canvas.
    std::int32_t c = kNone;
    float ax = 0, ay = 0, bx = 0, by = 0, ox = 0, oy = 0;
    for (std::int32_t k = 0; k < m.numCorners() && c == kNone; ++k) {
        const std::int32_t o = m.O[dlab::next(k)];
        if (o != kNone && anchorOf(h, k, ax, ay) && anchorOf(h, dlab::next(k), bx, by) &&
            anchorOf(h, o, ox, oy))
            c = k;
    }
    ASSERT_NE(c, kNone);
    openTab(h, "Expressions");
    EXPECT_EQ(h.countColour(h.rect("canvas"), kPathRgb), 0)
        << "path colour on the canvas before any expression";
    st.select(c);
    h.clickItem("expr-input");
    typeText(h, "c.n.o");
    h.press(key::kEnter);
    h.frames(2);
    const auto& ex = st.expressions;
    ASSERT_FALSE(ex.history.empty());
    const auto& line = ex.history.back();
    EXPECT_EQ(line.text, "c.n.o");
    EXPECT_TRUE(line.ok) << line.answer;
    const std::int32_t expected = m.O[dlab::next(c)];
    EXPECT_EQ(line.answer,
              "= " + std::to_string(expected) + "  (corner, c = " + std::to_string(c) + ")");
    ASSERT_EQ(ex.path.size(), 2u);
    EXPECT_EQ(ex.path[0].op, 'n');
    EXPECT_EQ(ex.path[0].from, c);
    EXPECT_EQ(ex.path[0].to, dlab::next(c));
    EXPECT_EQ(ex.path[1].op, 'o');
    EXPECT_EQ(ex.path[1].to, expected);
    // Each move is drawn: a curve in the path colour with a label box ("1.n", "2.o") on it,
    // between the two corners.
    const float ends[2][4] = {{ax, ay, bx, by}, {bx, by, ox, oy}};
    for (int k = 0; k < 2; ++k) {
        const std::string label = "expr-path-" + std::to_string(k + 1);
        ASSERT_TRUE(st.itemRects.count(label)) << "move " << k + 1 << " not drawn";
        const auto r = h.rect(label);
        EXPECT_GT(h.countColour(r, kPathRgb), 30) << label;
        const float mx = (r[0] + r[2]) / 2, my = (r[1] + r[3]) / 2, (&e)[4] = ends[k];
        const float len = std::hypot(e[2] - e[0], e[3] - e[1]);
        EXPECT_LT(std::hypot(mx - (e[0] + e[2]) / 2, my - (e[1] + e[3]) / 2), 0.2f * len + 4)
            << label << " is not between its corners";
    }
    EXPECT_TRUE(st.expressions.input.empty());  // the console is ready for the next line

    // The call form with a number, and an error with its column.
    h.clickItem("expr-input");
    typeText(h, "r(o(n(" + std::to_string(c) + ")))");
    h.press(key::kEnter);
    const std::int32_t r =
        m.O[dlab::next(c)] == kNone ? kNone : m.O[dlab::prev(m.O[dlab::next(c)])];
    if (r != kNone) {
        EXPECT_EQ(ex.history.back().answer, "= " + std::to_string(r) + "  (corner)");  // no c in it
    }
    h.clickItem("expr-input");
    typeText(h, "c.n.x");
    h.press(key::kEnter);
    EXPECT_FALSE(ex.history.back().ok);
    EXPECT_EQ(ex.history.back().errorColumn, 4u) << ex.history.back().answer;
}

// ============================================================================================
// Predicate inspector
// ============================================================================================

namespace {

// Four points where the run's in-circle test of d against triangle abc is one that plain
// floating point gets wrong: d is rounded from a point on the circle through a, b, c.
struct NearDegenerate {
    std::vector<Vec2> points;
    std::size_t position = 0;  // the in-circle test's position
};

NearDegenerate findNearDegenerate() {
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int attempt = 0; attempt < 5000; ++attempt) {
        const Vec2 a{u(rng) * 100, u(rng) * 100}, b{u(rng) * 100, u(rng) * 100},
            c{u(rng) * 100, u(rng) * 100};
        const double d2 = 2 * (a.x * (b.y - c.y) + b.x * (c.y - a.y) + c.x * (a.y - b.y));
        if (std::fabs(d2) < 100) continue;
        const double ux =
            ((a.x * a.x + a.y * a.y) * (b.y - c.y) + (b.x * b.x + b.y * b.y) * (c.y - a.y) +
             (c.x * c.x + c.y * c.y) * (a.y - b.y)) /
            d2;
        const double uy =
            ((a.x * a.x + a.y * a.y) * (c.x - b.x) + (b.x * b.x + b.y * b.y) * (a.x - c.x) +
             (c.x * c.x + c.y * c.y) * (b.x - a.x)) /
            d2;
        const double r = std::hypot(a.x - ux, a.y - uy), t = u(rng) * 6.283185307179586;
        const Vec2 d{ux + r * std::cos(t), uy + r * std::sin(t)};
        dlab::ui::Engine e;
        std::string error;
        if (!e.reset({a, b, c, d}, dlab::ui::demoOptions(), error)) continue;
        while (e.forward()) {
            if (e.current()->type != OpType::InCircleTest) continue;
            for (const auto& call : dlab::ui::currentPredicateCalls(e)) {
                if (call.inCircle && call.report.naiveSign != call.report.exactSign)
                    return {{a, b, c, d}, e.position()};
            }
        }
    }
    return {};
}

}  // namespace

TEST(Panels, PredicateInspectorWarnsWhereFloatingPointIsWrong) {
    const NearDegenerate nd = findNearDegenerate();
    ASSERT_FALSE(nd.points.empty()) << "no near-degenerate configuration found";
    UiHarness h;
    auto& st = h.state();
    openTab(h, "Predicates");
    // An ordinary in-circle test of the demo first: no warning.
    while (st.engine.forward() && st.engine.current()->type != OpType::InCircleTest) {}
    const auto calls = dlab::ui::currentPredicateCalls(st.engine);
    ASSERT_FALSE(calls.empty());
    if (calls[0].report.naiveSign == calls[0].report.exactSign) {
        EXPECT_FALSE(drawnNow(h, "predicate-warning"));
        EXPECT_EQ(h.countColour(h.rect("Predicates"), kWarningRgb), 0);
    }

    ASSERT_TRUE(st.loadPoints(nd.points, "near-degenerate"));
    // Step there with the panel's own button: "Next in-circle test" until the position.
    for (int i = 0; i < 20 && st.engine.position() < nd.position; ++i)
        h.clickItem("predicate-next");
    ASSERT_EQ(st.engine.position(), nd.position);
    const auto now = dlab::ui::currentPredicateCalls(st.engine);
    ASSERT_EQ(now.size(), 1u);
    ASSERT_TRUE(now[0].inCircle);
    EXPECT_NE(now[0].report.naiveSign, now[0].report.exactSign);
    EXPECT_NE(now[0].report.tier, dlab::PredicateTier::Filter);
    // The exact sign is the one the inserter used.
    EXPECT_EQ(now[0].report.exactSign, st.engine.current()->sign);
    ASSERT_TRUE(drawnNow(h, "predicate-warning"));
    const auto box = h.rect("predicate-warning");
    EXPECT_GT(h.countColour(box, kWarningRgb), 1000) << "the warning box is not red";

    // The same four points typed in by hand give the same verdict.
    st.engine.toStart();
    auto& typed = st.predicates.points;
    const auto& p = now[0].p;
    char buf[128];
    for (int k = 0; k < 4; ++k) {
        std::snprintf(buf, sizeof buf, "%.17g, %.17g", p[k].x, p[k].y);
        typed[k] = buf;
    }
    Vec2 q;
    ASSERT_TRUE(dlab::ui::parsePointText(typed[3], q));
    EXPECT_EQ(q, p[3]);  // 17 digits read back exactly
    EXPECT_FALSE(dlab::ui::parsePointText("1, nan", q));
    EXPECT_FALSE(dlab::ui::parsePointText("1, 2, 3", q));
    ASSERT_TRUE(drawnNow(h, "predicate-warning"));
}

// ============================================================================================
// ID buffer
// ============================================================================================

TEST(Panels, HoveredIdBufferPixelIsTheLocatorsAndIsCheckedExactly) {
    UiHarness h;
    auto& st = h.state();
    openTab(h, "ID buffer");
    // With the walk locator there is no buffer; the panel offers to switch.
    ASSERT_TRUE(drawnNow(h, "idbuffer-use"));
    h.clickItem("idbuffer-use");
    ASSERT_EQ(st.engine.options().locator, dlab::LocatorKind::IdBufferCpu);
    ASSERT_TRUE(st.loadPoints(dlab::generatePoints(dlab::Generator::Uniform, 60, 5), "uniform 60"));
    st.engine.seek(250);
    h.frames(3);
    ASSERT_TRUE(drawnNow(h, "idbuffer-image"));
    const auto img = h.rect("idbuffer-image");
    auto* cpu = dynamic_cast<const dlab::IdBufferCpu*>(
        const_cast<dlab::Inserter&>(st.engine.inserter()).locator());
    ASSERT_NE(cpu, nullptr);
    const dlab::Mesh& m = st.engine.mesh();
    const auto& ins = st.engine.inserter();
    // Where a world point shows in the image (pixel centres span [0.5, W - 0.5] pixel widths).
    const Vec2 lo = cpu->pixelCentre(0, 0),
               hi = cpu->pixelCentre(cpu->width() - 1, cpu->height() - 1);
    auto screenOf = [&](Vec2 q) {
        const double fx = ((q.x - lo.x) / (hi.x - lo.x) * (cpu->width() - 1) + 0.5) / cpu->width();
        const double fy =
            ((q.y - lo.y) / (hi.y - lo.y) * (cpu->height() - 1) + 0.5) / cpu->height();
        return std::array<float, 2>{img[0] + static_cast<float>(fx) * (img[2] - img[0]),
                                    img[3] - static_cast<float>(fy) * (img[3] - img[1])};
    };
    // Probes: the centroids of some real triangles, and a few points of a grid.
    std::vector<std::array<float, 2>> probes;
    for (std::int32_t t = 0; t < m.numTriangles() && probes.size() < 12; t += 2) {
        if (ins.isVirtualTriangle(t)) continue;
        const Vec2 a = m.G[m.V[3 * t]], b = m.G[m.V[3 * t + 1]], c = m.G[m.V[3 * t + 2]];
        probes.push_back(screenOf({(a.x + b.x + c.x) / 3, (a.y + b.y + c.y) / 3}));
    }
    for (int k = 1; k <= 4; ++k)
        probes.push_back(
            {img[0] + (img[2] - img[0]) * k / 5.0f, img[1] + (img[3] - img[1]) * (5 - k) / 5.0f});
    int agree = 0, inside = 0;
    for (const auto& [x, y] : probes) {
        h.moveTo(x, y);
        const auto& hv = st.idBuffer.hover;
        ASSERT_TRUE(hv.valid);
        // The decoded id is the core locator's pixel there.
        EXPECT_EQ(hv.id, cpu->pixelAt(hv.centre));
        EXPECT_EQ(hv.centre, cpu->pixelCentre(hv.i, hv.j));
        // The exact containment, computed here independently.
        std::set<std::int32_t> containing;
        for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
            if (!ins.done() && ins.isVirtualTriangle(t)) continue;
            const Vec2 a = m.G[m.V[3 * t]], b = m.G[m.V[3 * t + 1]], c = m.G[m.V[3 * t + 2]];
            if (dlab::orient2d(a, b, hv.centre) >= 0 && dlab::orient2d(b, c, hv.centre) >= 0 &&
                dlab::orient2d(c, a, hv.centre) >= 0) {
                containing.insert(t);
            }
        }
        const bool truth = hv.id == kNone ? containing.empty() : containing.count(hv.id) > 0;
        EXPECT_EQ(hv.agrees, truth) << "pixel " << hv.i << "," << hv.j;
        agree += truth;
        inside += hv.id != kNone;
        // What the image shows under the mouse is that id's false colour.
        const auto px = h.pixel(static_cast<int>(x), static_cast<int>(y));
        const std::uint32_t col = dlab::ui::IdFalseColour(hv.id);
        EXPECT_EQ(
            px, (std::array<int, 3>{static_cast<int>(col & 255), static_cast<int>((col >> 8) & 255),
                                    static_cast<int>((col >> 16) & 255)}));
    }
    const int probesN = static_cast<int>(probes.size());
    EXPECT_GE(inside, 10) << "the probes missed the mesh";
    EXPECT_GE(agree, probesN - 1);
}

// ============================================================================================
// Statistics
// ============================================================================================

TEST(Panels, StatisticsCountTheRunAndViolationsShowOnTheCanvas) {
    UiHarness h;
    auto& st = h.state();
    openTab(h, "Statistics");
    // Right after a split, before its flips: edges not yet Delaunay are expected and drawn.
    bool found = false;
    while (st.engine.forward()) {
        if (st.engine.current()->type != OpType::Split) continue;
        h.frames(2);
        if (!st.statistics.violations.empty()) {
            found = true;
            break;
        }
    }
    ASSERT_TRUE(found) << "no split left a non-Delaunay edge in the demo";
    for (const auto& v : st.statistics.violations)
        EXPECT_EQ(v.kind, dlab::Violation::Kind::NotDelaunay);
    h.frames(1);
    // Expected mid-insertion: drawn in the calmer colour, not as errors.
    EXPECT_GT(h.countColour(h.rect("canvas"), kPendingRgb), 40) << "violations not drawn";
    EXPECT_EQ(h.countColour(h.rect("canvas"), kViolationRgb), 0);
    // To the end: every check passes, nothing red, and the counts are the inserter's.
    while (!st.engine.toEnd(1 << 20)) {}
    h.frames(3);
    EXPECT_TRUE(st.statistics.violations.empty());
    EXPECT_TRUE(st.statistics.hullDents.empty());
    EXPECT_NE(st.statistics.hullReport.find("Euler holds"), std::string::npos)
        << st.statistics.hullReport;
    EXPECT_EQ(h.countColour(h.rect("canvas"), kViolationRgb), 0);
    ASSERT_TRUE(drawnNow(h, "flips-plot"));
    constexpr std::array<int, 3> kHistogramRgb = {230, 179,
                                                  0};  // ImGui's light style PlotHistogram
    EXPECT_GT(h.countColour(h.rect("flips-plot"), kHistogramRgb), 100)
        << "the flips plot is not drawn";
    const auto& ins = st.engine.inserter().stats();
    const auto& c = st.statistics.counts;
    EXPECT_EQ(c.flips, ins.flips);
    EXPECT_EQ(c.walkSteps, ins.walkSteps);
    EXPECT_EQ(c.inCircleTests, ins.inCircleTests);
    EXPECT_EQ(c.duplicates, ins.duplicates);
    double sum = 0;
    for (float f : c.flipsPerInsertion) sum += f;
    EXPECT_EQ(static_cast<std::int64_t>(sum), ins.flips);
    // Back to the start recounts.
    h.press(key::kHome);
    h.frames(1);
    EXPECT_EQ(c.flips, 0);
    EXPECT_FALSE(st.statistics.frameMs.empty());
}

TEST(Panels, SuperTriangleHullDentIsShown) {
    UiHarness h;
    auto& st = h.state();
    // The paper's finite super-triangle loses the sliver (0,0)-(500,1)-(1000,0): the circle
    // through them is huge and holds a super vertex. The exact hull check finds the dent at
    // vertex 3; in exact mode there is none.
    dlab::InsertOptions o = dlab::ui::demoOptions();
    o.boundary = dlab::Boundary::Super;
    ASSERT_TRUE(st.setOptions(o));
    ASSERT_TRUE(
        st.loadPoints({{0, 0}, {1000, 0}, {500, 500}, {500, 1}, {250, 200}, {700, 150}}, "sliver"));
    while (!st.engine.toEnd(1 << 20)) {}
    h.frames(2);
    ASSERT_EQ(st.statistics.hullDents, std::vector<std::int32_t>{3}) << st.statistics.hullReport;
    EXPECT_NE(st.statistics.hullReport.find("NOT convex"), std::string::npos);
    // Marked: the hull edge that closes it, dashed red, passes just above vertex 3.
    const auto p = st.view.toScreen(st.engine.mesh().G[3]);
    EXPECT_GT(
        h.countColour(around(static_cast<float>(p.x), static_cast<float>(p.y), 40), kViolationRgb),
        20)
        << "the dent is not marked";
    o.boundary = dlab::Boundary::Exact;
    ASSERT_TRUE(st.setOptions(o));
    while (!st.engine.toEnd(1 << 20)) {}
    h.frames(2);
    EXPECT_TRUE(st.statistics.hullDents.empty()) << st.statistics.hullReport;
}

TEST(Panels, TheGlIdBufferShowsInTheSameViewAndAgreesWithItsOwnReadback) {
    UiHarness h;
    auto& st = h.state();
    if (!st.engine.hasGl()) GTEST_SKIP() << "no GL context with framebuffer objects here";
    openTab(h, "ID buffer");
    ASSERT_TRUE(drawnNow(h, "idbuffer-use-gl"));
    h.clickItem("idbuffer-use-gl");
    ASSERT_EQ(st.engine.options().locator, dlab::LocatorKind::IdBufferGl);
    ASSERT_TRUE(st.loadPoints(dlab::generatePoints(dlab::Generator::Uniform, 40, 9), "uniform 40"));
    while (!st.engine.toEnd(1 << 20)) {}
    h.frames(3);
    ASSERT_TRUE(drawnNow(h, "idbuffer-image"));
    auto* gl = static_cast<dlab::ui::IdBufferGl*>(st.engine.idBufferGl());
    ASSERT_NE(gl, nullptr);
    const auto img = h.rect("idbuffer-image");
    const dlab::Mesh& m = st.engine.mesh();
    int inside = 0;
    for (int k = 1; k <= 7; ++k) {
        h.moveTo(img[0] + (img[2] - img[0]) * k / 8.0f,
                 img[1] + (img[3] - img[1]) * ((k * 3) % 8 + 0.5f) / 8.0f);
        const auto& hv = st.idBuffer.hover;
        ASSERT_TRUE(hv.valid);
        EXPECT_EQ(hv.id, gl->idAt(hv.i, hv.j));  // the view decodes what GL holds there
        EXPECT_EQ(hv.centre, gl->pixelCentre(hv.i, hv.j));
        if (hv.id == kNone) continue;
        ++inside;
        const Vec2 a = m.G[m.V[3 * hv.id]], b = m.G[m.V[3 * hv.id + 1]],
                   c = m.G[m.V[3 * hv.id + 2]];
        const bool contains = dlab::orient2d(a, b, hv.centre) >= 0 &&
                              dlab::orient2d(b, c, hv.centre) >= 0 &&
                              dlab::orient2d(c, a, hv.centre) >= 0;
        EXPECT_EQ(hv.agrees, contains);
    }
    EXPECT_GE(inside, 3);
}
