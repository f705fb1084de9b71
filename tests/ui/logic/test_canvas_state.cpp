// What the canvas shows of the engine's state: the flip queue numbered in stack order on the
// canvas and in the Queue tab, the legend of the marks drawn, the ghost triangle the walk is in,
// and labels that never cover each other (read back from the frame's draw lists).
#include "core/engine/generators.h"
#include "core/teaching/describe.h"
#include "tests/ui/ui_harness.h"
#include "ui/panels/canvas_looks.h"
#include "ui/panels/panels.h"
#include "ui/render/drawn_text.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

using dlab::kNone;
using dlab::test::UiHarness;

namespace {

std::vector<dlab::ui::DrawnText> frameText() { return dlab::ui::drawnText(ImGui::GetDrawData()); }

bool inside(const dlab::ui::DrawnText& t, const std::array<float, 4>& r) {
    return t.x0 >= r[0] && t.x1 <= r[2] && t.y0 >= r[1] && t.y1 <= r[3];
}

bool isNumber(const std::string& s) {
    return !s.empty() &&
           std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// Only the queue's numbers on the canvas: no ids, no legend.
void queueOnly(dlab::ui::AppState& st) {
    st.overlays.vertexIds = st.overlays.cornerIds = st.overlays.triangleIds = false;
    st.overlays.legend = false;
}

// Steps the demo to the first flip after which at least `depth` edges wait (mid-cascade).
bool toCascade(dlab::ui::AppState& st, std::size_t depth) {
    st.engine.toStart();
    while (st.engine.forward()) {
        const dlab::Op* op = st.engine.current();
        if (op && op->type == dlab::OpType::Flip &&
            st.engine.inserter().flipStack().size() >= depth)
            return true;
    }
    return false;
}

// An edge as the captions name it ("4-ghost").
std::string edgeName(const dlab::ui::AppState& st, std::array<std::int32_t, 2> e) {
    const auto& ins = st.engine.inserter();
    return dlab::vertexName(ins, e[0]) + "-" + dlab::vertexName(ins, e[1]);
}

// The edge opposite the corner `fromTop` places below the top of the inserter's flip stack.
std::array<std::int32_t, 2> stackEdge(const dlab::ui::AppState& st, std::size_t fromTop) {
    const auto& stack = st.engine.inserter().flipStack();
    const std::int32_t c = stack[stack.size() - 1 - fromTop];
    const dlab::Mesh& m = st.engine.mesh();
    return {m.V[dlab::next(c)], m.V[dlab::prev(c)]};
}

}  // namespace

TEST(FlipQueue, TheCanvasNumbersTheEdgesInStackOrderTheNextOneFirst) {
    UiHarness h(1280, 720);
    auto& st = h.state();
    queueOnly(st);
    ASSERT_TRUE(toCascade(st, 3));
    h.frames(2);
    st.view.scale *= 0.6;  // the rays to the ghost on the canvas too
    h.frames(2);
    const std::size_t k = st.engine.inserter().flipStack().size();
    const auto canvas = h.rect("canvas");
    std::vector<dlab::ui::DrawnText> numbers;
    for (const auto& t : frameText()) {
        if (isNumber(t.text) && inside(t, canvas)) numbers.push_back(t);
    }
    ASSERT_EQ(numbers.size(), k) << "one number per edge on the flip stack";
    int ghostEdges = 0;
    for (std::size_t i = 0; i < k; ++i) {
        const std::string want = std::to_string(i + 1);
        const auto it = std::find_if(numbers.begin(), numbers.end(),
                                     [&](const auto& t) { return t.text == want; });
        ASSERT_NE(it, numbers.end()) << want;
        // At the middle of the edge i places below the top of the stack; for an edge to the
        // ghost, out from its hull vertex (along the ray the ghost wedges share).
        const auto e = stackEdge(st, i);
        const auto& G = st.engine.mesh().G;
        const auto& ins = st.engine.inserter();
        const float x = (it->x0 + it->x1) / 2, y = (it->y0 + it->y1) / 2;
        if (ins.isVirtual(e[0]) || ins.isVirtual(e[1])) {
            ++ghostEdges;
            const glm::dvec2 u = st.view.toScreen(G[ins.isVirtual(e[0]) ? e[1] : e[0]]);
            const double d = std::hypot(x - u.x, y - u.y), fs = ImGui::GetFontSize();
            EXPECT_GT(d, 1.4 * fs) << "number " << want;
            EXPECT_LT(d, 5.0 * fs) << "number " << want;
            continue;
        }
        const glm::dvec2 a = st.view.toScreen(G[e[0]]), b = st.view.toScreen(G[e[1]]);
        EXPECT_NEAR(x, (a.x + b.x) / 2, 4.0) << "number " << want;
        EXPECT_NEAR(y, (a.y + b.y) / 2, 4.0) << "number " << want;
    }
    EXPECT_GT(ghostEdges, 0) << "the demo's cascade has edges to the ghost: numbered too";
}

TEST(FlipQueue, TheQueueTabListsTheStackTheNextEdgeFirst) {
    UiHarness h(1280, 720);
    auto& st = h.state();
    ASSERT_TRUE(toCascade(st, 3));
    st.pendingTab = "predicates";
    h.frames(3);
    const std::vector<std::string> lines = dlab::ui::drawnLines(frameText());
    const auto& stack = st.engine.inserter().flipStack();
    std::size_t at = 0;
    for (std::size_t i = 0; i < stack.size(); ++i) {
        const auto e = stackEdge(st, i);
        const std::string want =
            std::to_string(i + 1) + ". edge " + edgeName(st, e) + " (triangles ";
        const auto it = std::find_if(lines.begin() + static_cast<std::ptrdiff_t>(at), lines.end(),
                                     [&](const std::string& l) { return l.rfind(want, 0) == 0; });
        ASSERT_NE(it, lines.end()) << "row " << want << " below row " << i;
        at = static_cast<std::size_t>(it - lines.begin()) + 1;
    }
    // A row names the triangles on the edge's two sides.
    const std::int32_t top = stack.back();
    const dlab::Mesh& m = st.engine.mesh();
    const auto name = [&](std::int32_t t) {
        return std::to_string(t) + (st.engine.inserter().isVirtualTriangle(t) ? " ghost" : "");
    };
    const std::string row = "1. edge " + edgeName(st, stackEdge(st, 0)) + " (triangles " +
                            name(dlab::tri(top)) + " | " + name(dlab::tri(m.O[top])) + ")";
    EXPECT_NE(std::find_if(lines.begin(), lines.end(),
                           [&](const std::string& l) { return l.rfind(row, 0) == 0; }),
              lines.end())
        << row;
}

TEST(Legend, ListsTheMarksTheCanvasDrewAndOnlyThose) {
    UiHarness h(1280, 720);
    auto& st = h.state();
    st.overlays.legend = true;
    ASSERT_TRUE(toCascade(st, 2));
    ASSERT_TRUE(st.engine.forward());  // the test of the edge on top
    ASSERT_EQ(st.engine.current()->type, dlab::OpType::InCircleTest);
    const bool flip = st.engine.current()->sign > 0;
    h.frames(2);
    auto lines = dlab::ui::drawnLines(frameText());
    const auto has = [&](dlab::ui::Mark m) {
        const std::string want = dlab::ui::lookOf(m).meaning;
        return std::any_of(lines.begin(), lines.end(),
                           [&](const std::string& l) { return l.find(want) != std::string::npos; });
    };
    ASSERT_TRUE(st.itemRects.count("canvas-legend"));
    EXPECT_TRUE(has(dlab::ui::Mark::TestEdge));
    EXPECT_TRUE(has(dlab::ui::Mark::QueuedEdge));
    EXPECT_TRUE(has(dlab::ui::Mark::QueueOrder));
    EXPECT_TRUE(has(dlab::ui::Mark::FlippedEdge));
    EXPECT_EQ(has(dlab::ui::Mark::CircleFlip), flip);
    EXPECT_EQ(has(dlab::ui::Mark::CircleKeep), !flip);
    EXPECT_TRUE(has(dlab::ui::Mark::NextPoint));
    EXPECT_FALSE(has(dlab::ui::Mark::Voronoi)) << "not drawn, not listed";
    EXPECT_FALSE(has(dlab::ui::Mark::WalkVisited));
    st.overlays.voronoi = true;
    h.frames(2);
    lines = dlab::ui::drawnLines(frameText());
    EXPECT_TRUE(has(dlab::ui::Mark::Voronoi));
    // Toggled off: gone.
    st.overlays.legend = false;
    h.frames(2);
    lines = dlab::ui::drawnLines(frameText());
    EXPECT_FALSE(has(dlab::ui::Mark::TestEdge));
    EXPECT_FALSE(st.itemRects.count("canvas-legend"));
}

TEST(Legend, IsAlwaysOnSlidesAndLeavesTheQuestionClear) {
    UiHarness h(1280, 720);
    auto& st = h.state();
    st.presentation = true;
    st.overlays.legend = false;
    ASSERT_TRUE(dlab::ui::openLesson(st, std::string(DLAB_SOURCE_DIR) + "/lessons/05_flips.toml"));
    dlab::ui::goToStop(st, 0);
    h.frames(3);
    ASSERT_TRUE(dlab::ui::slideMode(st));
    ASSERT_TRUE(st.itemRects.count("canvas-legend"));
    const auto legend = st.itemRects["canvas-legend"];
    const auto canvas = h.rect("canvas");
    EXPECT_TRUE(legend[0] >= canvas[0] && legend[2] <= canvas[2] && legend[1] >= canvas[1] &&
                legend[3] <= canvas[3])
        << "inside the canvas";
    // Compact, on the canvas, not over the slide's text or question.
    EXPECT_LT((legend[2] - legend[0]) * (legend[3] - legend[1]),
              0.25f * (canvas[2] - canvas[0]) * (canvas[3] - canvas[1]));
    if (st.itemRects.count("slide-question")) {
        const auto q = st.itemRects["slide-question"];
        EXPECT_TRUE(legend[2] <= q[0] || q[2] <= legend[0] || legend[3] <= q[1] ||
                    q[3] <= legend[1]);
    }
}

// The disc numbered `n` on the canvas, and its distance in pixels to the edge (a, b) on screen.
float discToEdge(const dlab::ui::AppState& st, const std::array<float, 4>& canvas,
                 const std::string& n, dlab::ui::VertexEdge e) {
    const auto& G = st.engine.mesh().G;
    const auto pa = st.view.toScreen(G[e.a]), pb = st.view.toScreen(G[e.b]);
    float best = 1e9f;
    for (const auto& t : frameText()) {
        if (t.text != n || !inside(t, canvas)) continue;
        const double cx = (t.x0 + t.x1) / 2, cy = (t.y0 + t.y1) / 2;
        const double dx = pb.x - pa.x, dy = pb.y - pa.y, len2 = dx * dx + dy * dy;
        const double u =
            len2 > 0 ? std::clamp(((cx - pa.x) * dx + (cy - pa.y) * dy) / len2, 0.0, 1.0) : 0;
        best =
            std::min(best, static_cast<float>(std::hypot(pa.x + u * dx - cx, pa.y + u * dy - cy)));
    }
    return best;
}

TEST(FlipQueue, ALessonAskingTheNextTestNumbersTheQueueInPushOrder) {
    // Lesson 5 asks which edge is tested first: its stop numbers the queue in push order, so the
    // edge tested next (the top of the stack) carries the highest number, not 1.
    UiHarness h(1280, 720);
    auto& st = h.state();
    st.presentation = true;
    ASSERT_TRUE(dlab::ui::openLesson(st, std::string(DLAB_SOURCE_DIR) + "/lessons/05_flips.toml"));
    dlab::ui::goToStop(st, 1);
    st.overlays.vertexIds = false;
    h.frames(3);
    const auto queue = st.engine.pendingTests();  // queue[0]: the top, tested next
    ASSERT_EQ(queue.size(), 3u);
    const auto canvas = h.rect("canvas");
    const auto lines = dlab::ui::drawnLines(frameText());
    const auto has = [&](dlab::ui::Mark m) {
        return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) {
            return l.find(dlab::ui::lookOf(m).meaning) != std::string::npos;
        });
    };
    EXPECT_TRUE(has(dlab::ui::Mark::QueuedEdge));
    EXPECT_TRUE(has(dlab::ui::Mark::QueuePushed));
    EXPECT_FALSE(has(dlab::ui::Mark::QueueOrder));
    EXPECT_LT(discToEdge(st, canvas, "3", queue[0].edge), 12) << "the last pushed, on the top";
    EXPECT_LT(discToEdge(st, canvas, "1", queue[2].edge), 12) << "the first pushed, at the bottom";
    // In test order the top is 1.
    st.overlays.queueOrder = true;
    h.frames(2);
    EXPECT_LT(discToEdge(st, canvas, "1", queue[0].edge), 12);
    EXPECT_LT(discToEdge(st, canvas, "3", queue[2].edge), 12);
    // Neither: no numbers at all.
    st.overlays.queueOrder = st.overlays.queuePushed = false;
    h.frames(2);
    for (const auto& t : frameText()) EXPECT_FALSE(isNumber(t.text) && inside(t, canvas)) << t.text;
}

TEST(Legend, EveryMarkHasItsOwnLook) {
    const auto looks = dlab::ui::canvasLooks();
    ASSERT_EQ(looks.size(), dlab::ui::kMarkCount);
    for (std::size_t i = 0; i < looks.size(); ++i) {
        EXPECT_EQ(static_cast<std::size_t>(looks[i].mark), i);
        EXPECT_FALSE(std::string(looks[i].meaning).empty());
        for (std::size_t j = 0; j < i; ++j) {
            EXPECT_FALSE(looks[i].colour == looks[j].colour && looks[i].shape == looks[j].shape)
                << looks[i].meaning << " and " << looks[j].meaning << " look the same";
            EXPECT_NE(std::string(looks[i].meaning), looks[j].meaning);
        }
    }
    // The edge under test, the queue, the selection and the next point: four colours.
    const std::array<dlab::ui::Mark, 4> four{dlab::ui::Mark::TestEdge, dlab::ui::Mark::QueuedEdge,
                                             dlab::ui::Mark::SelectedCorner,
                                             dlab::ui::Mark::NextPoint};
    for (std::size_t i = 0; i < four.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            EXPECT_NE(dlab::ui::lookOf(four[i]).colour, dlab::ui::lookOf(four[j]).colour);
}

namespace {

// The canvas' draw-list vertices of exactly this colour.
std::vector<ImVec2> verticesOfColour(ImU32 col) {
    std::vector<ImVec2> out;
    const ImDrawData* data = ImGui::GetDrawData();
    for (int l = 0; data && l < data->CmdListsCount; ++l) {
        for (const ImDrawVert& v : data->CmdLists[l]->VtxBuffer) {
            if (v.col == col) out.push_back(v.pos);
        }
    }
    return out;
}

// Steps to the first locate op whose walk stands in a ghost triangle (exact mode).
std::int32_t toGhostWalk(dlab::ui::AppState& st) {
    st.engine.toStart();
    while (st.engine.forward()) {
        const dlab::Op* op = st.engine.current();
        if (!op || (op->type != dlab::OpType::LocateStep && op->type != dlab::OpType::Located))
            continue;
        const auto path = st.engine.walkPath();
        if (!path.empty() && st.engine.inserter().isVirtualTriangle(path.back()))
            return path.back();
    }
    return kNone;
}

}  // namespace

TEST(IdBufferGrid, ThePixelsOverTheMeshAndThePixelUnderTheNextPointOutlined) {
    // Lesson 8's first stop asks which triangle the pixel under vertex 4 holds: the canvas draws
    // the buffer's pixels (a dot at each centre) and outlines the pixel under vertex 4.
    UiHarness h(1280, 720);
    auto& st = h.state();
    st.presentation = true;
    ASSERT_TRUE(
        dlab::ui::openLesson(st, std::string(DLAB_SOURCE_DIR) + "/lessons/08_idbuffer.toml"));
    dlab::ui::goToStop(st, 0);
    h.frames(3);
    ASSERT_TRUE(st.overlays.idBufferGrid);
    const std::int32_t v = st.engine.currentVertex();
    ASSERT_EQ(v, 4);
    const auto q = st.view.toScreen(st.engine.mesh().G[v]);
    std::vector<ImVec2> outline;  // near vertex 4: not the legend's sample
    for (const ImVec2& p : verticesOfColour(dlab::ui::lookOf(dlab::ui::Mark::IdPixelNow).colour))
        if (std::hypot(p.x - q.x, p.y - q.y) < 150) outline.push_back(p);
    ASSERT_GE(outline.size(), 4u);
    float x0 = 1e9f, y0 = 1e9f, x1 = -1e9f, y1 = -1e9f;
    for (const ImVec2& p : outline) {
        x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x),
        y1 = std::max(y1, p.y);
    }
    EXPECT_TRUE(q.x > x0 && q.x < x1 && q.y > y0 && q.y < y1) << "vertex 4 in its outlined pixel";
    // One pixel of the 8 x 8 buffer: an eighth of the points' box (81 x 79 units) each way.
    EXPECT_NEAR((x1 - x0) / st.view.scale, 81.0 / 8, 1.0);
    // 64 centres, each a dot of the grid's colour.
    const auto dots = verticesOfColour(dlab::ui::lookOf(dlab::ui::Mark::IdPixel).colour);
    EXPECT_GE(dots.size(), 64u * 3);
    const auto lines = dlab::ui::drawnLines(frameText());
    EXPECT_TRUE(std::any_of(lines.begin(), lines.end(), [](const std::string& l) {
        return l.find(dlab::ui::lookOf(dlab::ui::Mark::IdPixel).meaning) != std::string::npos;
    }));
    // Off: nothing of it.
    st.overlays.idBufferGrid = false;
    h.frames(2);
    EXPECT_TRUE(verticesOfColour(dlab::ui::lookOf(dlab::ui::Mark::IdPixelNow).colour).empty());
}

TEST(GhostTarget, TheWedgeTheWalkEntersIsHighlightedOutsideTheHull) {
    UiHarness h(1280, 720);
    auto& st = h.state();
    ASSERT_EQ(st.engine.options().boundary, dlab::Boundary::Exact);
    st.overlays.legend = true;
    const std::int32_t t = toGhostWalk(st);
    ASSERT_NE(t, kNone) << "the demo's walk enters a ghost triangle";
    h.frames(2);
    const ImU32 now = dlab::ui::lookOf(dlab::ui::Mark::WalkNow).colour;
    const std::vector<ImVec2> wedge = verticesOfColour((now & 0x00FFFFFFu) | (190u << 24));
    ASSERT_GE(wedge.size(), 4u) << "the ghost triangle's wedge is filled";
    // All of it on the outside of its hull edge u -> w (the world's left of it).
    ImVec2 a, b, da, db;
    ASSERT_TRUE(dlab::ui::ghostWedge(st, t, a, b, da, db));
    const float nx = b.y - a.y, ny = -(b.x - a.x);
    for (const ImVec2& p : wedge)
        EXPECT_GE((p.x - a.x) * nx + (p.y - a.y) * ny, -1e-2f * (nx * nx + ny * ny));
    // The legend says what it is.
    const auto lines = dlab::ui::drawnLines(frameText());
    EXPECT_NE(std::find_if(lines.begin(), lines.end(),
                           [&](const std::string& l) {
                               return l.find(dlab::ui::lookOf(dlab::ui::Mark::WalkNow).meaning) !=
                                      std::string::npos;
                           }),
              lines.end());
    // Walking inside the hull: no wedge.
    st.engine.toStart();
    while (st.engine.forward()) {
        const dlab::Op* op = st.engine.current();
        const auto path = st.engine.walkPath();
        if (op && op->type == dlab::OpType::LocateStep && !path.empty() &&
            !st.engine.inserter().isVirtualTriangle(path.back()))
            break;
    }
    h.frames(2);
    EXPECT_TRUE(verticesOfColour((now & 0x00FFFFFFu) | (190u << 24)).empty());
}

TEST(GhostTarget, NeighbouringGhostWedgesShareTheirSidesAtHullVertices) {
    UiHarness h(1280, 720);
    auto& st = h.state();
    st.loadPoints(dlab::generatePoints(dlab::Generator::Uniform, 3000, 7), "uniform");
    st.engine.seek(st.engine.recorded() / 2);
    h.frames(2);
    const dlab::Mesh& m = st.engine.mesh();
    struct Wedge {
        ImVec2 a, b, da, db;
    };
    std::vector<Wedge> wedges;
    for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
        Wedge w;
        if (dlab::ui::ghostWedge(st, t, w.a, w.b, w.da, w.db)) wedges.push_back(w);
    }
    ASSERT_GE(wedges.size(), 10u);
    std::size_t shared = 0;
    for (const Wedge& w : wedges) {
        for (const Wedge& v : wedges) {
            if (w.b.x != v.a.x || w.b.y != v.a.y) continue;
            ++shared;  // w ends where v starts: one side, no notch and no overlap
            EXPECT_NEAR(w.db.x, v.da.x, 1e-4);
            EXPECT_NEAR(w.db.y, v.da.y, 1e-4);
        }
    }
    EXPECT_EQ(shared, wedges.size()) << "every hull vertex joins two wedges";
}

namespace {

// The canvas' label runs that overlap another (pairs).
std::size_t overlaps(const std::vector<dlab::ui::DrawnText>& runs) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < runs.size(); ++i) {
        for (std::size_t j = 0; j < i; ++j) {
            const auto &a = runs[i], &b = runs[j];
            if (a.x0 < b.x1 - 1 && b.x0 < a.x1 - 1 && a.y0 < b.y1 - 1 && b.y0 < a.y1 - 1) ++n;
        }
    }
    return n;
}

std::vector<dlab::ui::DrawnText> canvasRuns(UiHarness& h) {
    const auto canvas = h.rect("canvas");
    std::vector<dlab::ui::DrawnText> runs;
    for (const auto& t : frameText()) {
        if (inside(t, canvas)) runs.push_back(t);
    }
    return runs;
}

}  // namespace

TEST(CanvasLabels, NoLabelCoversAnotherAtTwoThousandPointsAtFinalize) {
    UiHarness h(1280, 720);
    auto& st = h.state();
    st.overlays.legend = false;
    st.overlays.triangleIds = true;
    st.loadPoints(dlab::generatePoints(dlab::Generator::Uniform, 2000, 3), "uniform");
    while (!st.engine.toEnd(1 << 20)) {}
    while (st.engine.current() && st.engine.current()->type != dlab::OpType::Finalize)
        st.engine.back();
    ASSERT_NE(st.engine.current(), nullptr);
    h.frames(2);
    const auto runs = canvasRuns(h);
    EXPECT_EQ(overlaps(runs), 0u);
    // The slivers along the hull have no room for their corners' ids: a few labels, not
    // hundreds.
    EXPECT_LT(runs.size(), 40u);
    // Zoomed in, the labels come back, still apart.
    st.view.scale *= 8;
    h.frames(2);
    const auto zoomed = canvasRuns(h);
    EXPECT_GT(zoomed.size(), 20u);
    EXPECT_EQ(overlaps(zoomed), 0u);
}

TEST(CanvasLabels, ASparseMeshKeepsEveryVertexLabel) {
    UiHarness h(1280, 720);
    auto& st = h.state();
    st.overlays.legend = false;
    st.overlays.cornerIds = false;  // numbers that are vertex ids only
    while (!st.engine.toEnd(1 << 20)) {}
    h.frames(2);
    const auto runs = canvasRuns(h);
    for (std::size_t v = 0; v < st.engine.points().size(); ++v) {
        const std::string id = std::to_string(v);
        // Two labels side by side read as one run ("11 4": a duplicate on its vertex).
        EXPECT_TRUE(std::any_of(runs.begin(), runs.end(),
                                [&](const auto& r) {
                                    return (" " + r.text + " ").find(" " + id + " ") !=
                                           std::string::npos;
                                }))
            << "vertex " << v;
    }
    EXPECT_EQ(overlaps(runs), 0u);
}

TEST(CanvasLabels, FollowThePresentationFontSize) {
    const auto labelHeight = [](bool presentation) {
        UiHarness h(1280, 720);
        auto& st = h.state();
        st.presentation = presentation;
        st.overlays.legend = false;
        while (!st.engine.toEnd(1 << 20)) {}
        h.frames(3);
        std::vector<float> heights;
        for (const auto& t : canvasRuns(h)) {
            if (isNumber(t.text)) heights.push_back(t.y1 - t.y0);
        }
        if (heights.empty()) return 0.0f;
        std::sort(heights.begin(), heights.end());
        return heights[heights.size() / 2];
    };
    const float normal = labelHeight(false), large = labelHeight(true);
    ASSERT_GT(normal, 0.0f);
    EXPECT_GT(large, 1.15f * normal)
        << normal << " px in the normal mode, " << large << " px in presentation mode";
}
