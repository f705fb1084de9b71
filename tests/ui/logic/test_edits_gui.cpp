// Edits after the run, driven as a user drives them: Delete on a selected corner's vertex, the
// canvas tools' clicks on vertices, each edit's ops stepped with the arrow keys and undone bit for
// bit, the caption reading the op's record, refusals in the message log, and sessions that keep
// the edits.
#include "core/engine/mesh.h"
#include "core/engine/predicates.h"
#include "tests/ui/ui_harness.h"
#include "ui/files/files.h"
#include "ui/files/session.h"
#include "ui/panels/panels.h"
#include "ui/platform/keys.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

using dlab::kNone;
using dlab::test::UiHarness;
namespace key = dlab::ui::key;
namespace ui = dlab::ui;

namespace {

struct Cells {
    std::vector<std::int32_t> V, O;
    bool operator==(const Cells&) const = default;
};
Cells cells(const ui::Engine& e) { return {e.mesh().V, e.mesh().O}; }

void toRunEnd(UiHarness& h) {
    h.press(key::kEnd);
    h.frames(3);
    ASSERT_TRUE(h.state().engine.atEnd());
    ASSERT_FALSE(h.state().run.running);
}

bool logged(const ui::AppState& st, const std::string& words) {
    return std::any_of(st.messages.begin(), st.messages.end(), [&](const ui::Message& m) {
        return m.text.find(words) != std::string::npos;
    });
}

bool usesVertex(const dlab::Mesh& m, std::int32_t v) {
    return std::find(m.V.begin(), m.V.end(), v) != m.V.end();
}

// Where vertex v is on the screen.
void screenOf(UiHarness& h, std::int32_t v, float& x, float& y) {
    const auto q = h.state().view.toScreen(h.state().engine.points()[v]);
    x = static_cast<float>(q.x);
    y = static_cast<float>(q.y);
}

// An interior vertex of the demo's mesh (no ghost triangle at it).
std::int32_t interiorVertex(const ui::Engine& e) {
    const dlab::Mesh& m = e.mesh();
    for (std::int32_t v = 0; v < static_cast<std::int32_t>(e.points().size()); ++v) {
        bool onHull = false, used = false;
        for (std::int32_t c = 0; c < m.numCorners(); ++c) {
            if (m.V[c] != v) continue;
            used = true;
            onHull |= m.O[dlab::next(c)] == kNone || m.O[dlab::prev(c)] == kNone;
        }
        if (used && !onHull) return v;
    }
    return kNone;
}

}  // namespace

TEST(EditsInTheGui, DeleteRemovesTheSelectedVertexStepByStepAndLeftUndoesItBitForBit) {
    UiHarness h;
    auto& e = h.state().engine;
    toRunEnd(h);
    const std::size_t runEnd = e.position();
    const Cells before = cells(e);
    const std::int32_t v = interiorVertex(e);
    ASSERT_NE(v, kNone);
    std::int32_t c = 0;
    while (e.mesh().V[c] != v) ++c;
    h.state().select(c);
    h.press(key::kDelete);
    EXPECT_TRUE(logged(h.state(), "removed vertex " + std::to_string(v))) << v;
    h.state().run.running = false;  // step it by hand
    h.frames(1);
    ASSERT_NE(e.editor(), nullptr);
    const std::size_t total = e.recorded();
    ASSERT_GT(total, runEnd + 1) << "a removal is several ops: ear tests, flips, a merge";
    e.seek(runEnd);
    h.frames(1);
    std::size_t flips = 0;
    while (e.position() < total) {
        h.press(key::kRight);
        ASSERT_TRUE(e.editing());
        const std::string caption = ui::captionText(h.state());
        EXPECT_NE(caption.find("remove vertex " + std::to_string(v)), std::string::npos) << caption;
        const dlab::EditStep s = e.currentEdit();
        ASSERT_NE(s.removal, nullptr);
        if (s.removal->type == dlab::RemoveOpType::Flip) {
            ++flips;
            EXPECT_NE(caption.find("flip "), std::string::npos) << caption;
        }
    }
    EXPECT_GT(flips, 0u);
    EXPECT_FALSE(usesVertex(e.mesh(), v));
    EXPECT_EQ(e.pointStates()[v], ui::Engine::PointState::Removed);
    dlab::ValidateOptions o;
    o.firstVirtual = e.inserter().firstVirtual();
    EXPECT_TRUE(dlab::validate(e.mesh(), o).empty()) << "valid and Delaunay after the removal";
    while (e.position() > runEnd) h.press(key::kLeft);
    EXPECT_FALSE(e.editing());
    EXPECT_EQ(cells(e), before);
    EXPECT_EQ(e.pointStates()[v], ui::Engine::PointState::Inserted);
}

TEST(EditsInTheGui, TheConstrainToolTakesTheTwoVerticesClickedAndRefusesACrossing) {
    UiHarness h;
    auto& st = h.state();
    auto& e = st.engine;
    toRunEnd(h);
    st.tool = ui::AppState::CanvasTool::Constrain;
    h.frames(1);
    // The two hull vertices farthest apart: their segment crosses the mesh.
    const auto& pts = e.points();
    std::int32_t a = 0, b = 1;
    double far = -1;
    for (std::int32_t i = 0; i < static_cast<std::int32_t>(pts.size()); ++i) {
        for (std::int32_t j = i + 1; j < static_cast<std::int32_t>(pts.size()); ++j) {
            if (!usesVertex(e.mesh(), i) || !usesVertex(e.mesh(), j)) continue;
            const double d = std::hypot(pts[i].x - pts[j].x, pts[i].y - pts[j].y);
            if (d > far) {
                far = d;
                a = i;
                b = j;
            }
        }
    }
    float x, y;
    screenOf(h, a, x, y);
    h.click(x, y);
    EXPECT_EQ(st.toolFirstVertex, a);
    screenOf(h, b, x, y);
    h.click(x, y);
    EXPECT_EQ(st.toolFirstVertex, kNone);
    ASSERT_NE(e.editor(), nullptr);
    ASSERT_EQ(e.editor()->edits().size(), 1u);
    EXPECT_EQ(e.editor()->edits()[0].kind, dlab::EditKind::Constrain);
    h.press(key::kEnd);
    h.frames(3);
    const auto edges = e.editor()->constrainedEdges();
    ASSERT_FALSE(edges.empty());
    const bool endsAtA = std::any_of(edges.begin(), edges.end(), [&](const auto& ed) {
        return ed.first == a || ed.second == a;
    });
    EXPECT_TRUE(endsAtA);
    // A segment across it is refused, named, and changes nothing.
    const Cells constrained = cells(e);
    std::int32_t p = kNone, q = kNone;
    for (std::int32_t i = 0; i < static_cast<std::int32_t>(pts.size()) && q == kNone; ++i) {
        for (std::int32_t j = 0; j < static_cast<std::int32_t>(pts.size()); ++j) {
            if (i == a || i == b || j == a || j == b || !usesVertex(e.mesh(), i) ||
                !usesVertex(e.mesh(), j))
                continue;
            const dlab::Vec2 A = pts[a], B = pts[b], P = pts[i], Q = pts[j];
            if (dlab::orient2d(A, B, P) * dlab::orient2d(A, B, Q) < 0 &&
                dlab::orient2d(P, Q, A) * dlab::orient2d(P, Q, B) < 0) {
                p = i;
                q = j;
                break;
            }
        }
    }
    ASSERT_NE(q, kNone) << "the demo has a segment across " << a << "-" << b;
    screenOf(h, p, x, y);
    h.click(x, y);
    screenOf(h, q, x, y);
    h.click(x, y);
    EXPECT_TRUE(logged(st, "crosses the constrained edge")) << p << "-" << q;
    EXPECT_EQ(cells(e), constrained);
    EXPECT_EQ(e.editor()->edits().size(), 1u);
}

TEST(EditsInTheGui, ASessionKeepsTheEditsAndTheStepInsideThem) {
    std::string text;
    Cells mid;
    std::size_t runEnd = 0;
    std::int32_t v = kNone;
    {  // one GUI at a time (ImGui's context is global)
        UiHarness h;
        auto& e = h.state().engine;
        toRunEnd(h);
        runEnd = e.position();
        std::string message;
        v = interiorVertex(e);
        ASSERT_TRUE(e.edit(dlab::makeEdit(dlab::EditKind::RemoveVertex, v), message)) << message;
        e.seek(runEnd + 2);
        text = ui::sessionText(h.state());
        mid = cells(e);
    }
    EXPECT_NE(text.find("\"remove vertex " + std::to_string(v) + "\""), std::string::npos);
    {
        UiHarness other;
        std::string error;
        ASSERT_TRUE(ui::loadSessionText(other.state(), text, "edits.json", error)) << error;
        const auto& f = other.state().engine;
        EXPECT_EQ(f.position(), runEnd + 2);
        EXPECT_TRUE(f.editing());
        EXPECT_EQ(cells(f), mid);
    }
    // A session naming an edit it cannot read is refused with the place of the error.
    std::string bad = text;
    bad.replace(bad.find("remove vertex"), 13, "erase vertex");
    UiHarness third;
    std::string error;
    EXPECT_FALSE(ui::loadSessionText(third.state(), bad, "bad.json", error));
    EXPECT_NE(error.find("edits"), std::string::npos) << error;
}

// The paper's super-triangle: the edits work on the mesh before Finalize dropped it, its three
// vertices real points; stepping back to the run's end shows the finished mesh again.
TEST(EditsInTheGui, TheSuperTriangleRunIsEditedWithTheSuperTriangleIn) {
    UiHarness h;
    auto& st = h.state();
    auto& e = st.engine;
    dlab::InsertOptions o = e.options();
    o.boundary = dlab::Boundary::Super;
    ASSERT_TRUE(st.setOptions(o));
    toRunEnd(h);
    const std::size_t runEnd = e.position();
    const Cells finished = cells(e);
    const std::int32_t v = interiorVertex(e);
    ASSERT_NE(v, kNone);
    std::string message;
    ASSERT_TRUE(e.edit(dlab::makeEdit(dlab::EditKind::RemoveVertex, v), message)) << message;
    ASSERT_NE(e.editor(), nullptr);
    EXPECT_EQ(e.editor()->boundary(), dlab::Boundary::Super);
    e.seek(e.recorded());
    EXPECT_FALSE(usesVertex(e.mesh(), v));
    const auto n = static_cast<std::int32_t>(e.points().size());
    for (std::int32_t s = n; s < n + 3; ++s)
        EXPECT_TRUE(usesVertex(e.mesh(), s)) << "the super-triangle's vertex " << s;
    EXPECT_TRUE(e.showsVirtual()) << "its triangles are drawn as during the run";
    dlab::ValidateOptions vo;
    vo.firstVirtual = -1;  // the super-triangle's vertices are real points
    vo.delaunay = true;
    EXPECT_TRUE(dlab::validate(e.mesh(), vo).empty());
    e.seek(runEnd);
    EXPECT_EQ(cells(e), finished) << "back at the run's end, the finished mesh";
}

TEST(EditsInTheGui, CtrlZTakesTheLastEditOutAndCtrlYMakesItAgain) {
    UiHarness h;
    auto& e = h.state().engine;
    toRunEnd(h);
    const Cells before = cells(e);
    const std::int32_t v = interiorVertex(e);
    std::string message;
    ASSERT_TRUE(e.edit(dlab::makeEdit(dlab::EditKind::RemoveVertex, v), message)) << message;
    e.seek(e.recorded());
    const Cells removed = cells(e);
    h.press(key::letter('Z'), false, true);
    EXPECT_TRUE(logged(h.state(), "undone: remove vertex " + std::to_string(v)));
    EXPECT_TRUE(e.editor()->edits().empty());
    EXPECT_EQ(cells(e), before);
    EXPECT_TRUE(e.atEnd());
    h.press(key::letter('Y'), false, true);
    EXPECT_TRUE(logged(h.state(), "redone: remove vertex " + std::to_string(v)));
    ASSERT_EQ(e.editor()->edits().size(), 1u);
    e.seek(e.recorded());
    EXPECT_EQ(cells(e), removed);
}

TEST(EditsInTheGui, AddingAPointKeepsTheEditsAfterTheRun) {
    UiHarness h;
    auto& st = h.state();
    auto& e = st.engine;
    toRunEnd(h);
    const std::int32_t v = interiorVertex(e);
    std::string message;
    ASSERT_TRUE(e.edit(dlab::makeEdit(dlab::EditKind::RemoveVertex, v), message)) << message;
    e.seek(e.recorded());
    std::vector<dlab::Vec2> pts = e.points();
    dlab::Vec2 lo = pts[0], hi = pts[0];
    for (const auto& p : pts) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    pts.push_back({lo.x + 0.37 * (hi.x - lo.x), lo.y + 0.61 * (hi.y - lo.y)});
    ASSERT_TRUE(st.editPoints(pts));
    ASSERT_NE(e.editor(), nullptr);
    ASSERT_EQ(e.editor()->edits().size(), 1u);
    EXPECT_EQ(e.editor()->edits()[0].a, v);
    e.seek(e.recorded());
    EXPECT_FALSE(usesVertex(e.mesh(), v));
    EXPECT_TRUE(usesVertex(e.mesh(), static_cast<std::int32_t>(pts.size()) - 1));
}

TEST(EditsInTheGui, APolyFileOpensItsPointsThenConstrainsItsSegments) {
    dlab::test::TempDir dir("poly_gui");
    const std::string path = dir / "square.poly";
    {
        std::ofstream f(path);
        f << "5 2 0 0\n1 0 0\n2 10 0\n3 10 10\n4 0 10\n5 3 6\n"
          << "3 0\n1 1 3\n2 4 5\n3 2 5\n0\n";
    }
    UiHarness h;
    auto& st = h.state();
    ASSERT_TRUE(ui::openFile(st, path)) << st.files.notice;
    auto& e = st.engine;
    EXPECT_EQ(e.position(), 0u) << "it starts from the first insertion";
    ASSERT_NE(e.editor(), nullptr);
    ASSERT_EQ(e.editor()->edits().size(), 2u);
    e.seek(e.recorded());
    const auto edges = e.editor()->constrainedEdges();
    auto has = [&](std::int32_t a, std::int32_t b) {
        return std::any_of(edges.begin(), edges.end(), [&](const auto& ed) {
            return (ed.first == a && ed.second == b) || (ed.first == b && ed.second == a);
        });
    };
    EXPECT_TRUE(has(0, 2)) << "segment 1-3 of the file, 1-based";
    EXPECT_TRUE(has(3, 4));
    EXPECT_TRUE(logged(st, "segment 1-4 refused")) << "2-5 of the file crosses 1-3";
}

// The README's two pictures of edits mid-way, as the engine makes them on the demo.
TEST(EditsInTheGui, TheReadmePicturesOfEditsShowWhatTheEngineDid) {
    UiHarness h;
    auto& e = h.state().engine;
    dlab::InsertOptions o = e.options();  // dtlab render's: BRIO order, seed 1
    o.order = dlab::OrderKind::Brio;
    o.seed = 1;
    ASSERT_TRUE(h.state().setOptions(o));
    toRunEnd(h);
    const std::size_t runEnd = e.position();
    std::string message;
    ASSERT_TRUE(e.edit(dlab::makeEdit(dlab::EditKind::RemoveVertex, 8), message)) << message;
    e.seek(runEnd + 2);
    const std::string removal = ui::captionText(h.state());
    EXPECT_NE(removal.find("remove vertex 8, ear test at 5: triangle 10-5-3 is no ear"),
              std::string::npos)
        << removal;
    const auto& G = e.mesh().G;
    for (std::int32_t inside : {2, 4, 9})
        EXPECT_GT(dlab::incircle(G[10], G[5], G[3], G[inside]), 0) << inside;
    ASSERT_TRUE(h.state().undoEdit());
    ASSERT_TRUE(e.edit(dlab::makeEdit(dlab::EditKind::Constrain, 0, 6), message)) << message;
    e.seek(runEnd + 4);
    const std::string constraint = ui::captionText(h.state());
    EXPECT_NE(constraint.find("constrain 0-6, the crossing edge 8-3 has a quadrilateral that is "
                              "not convex: it waits"),
              std::string::npos)
        << constraint;
    bool made03 = false, made08 = false;
    const dlab::Mesh& m = e.mesh();
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        const std::int32_t u = m.V[dlab::next(c)], w = m.V[dlab::prev(c)];
        made03 |= (u == 0 && w == 3) || (u == 3 && w == 0);
        made08 |= (u == 0 && w == 8) || (u == 8 && w == 0);
    }
    EXPECT_TRUE(made03 && made08) << "Sloan's flips made 0-3 and 0-8";
    ASSERT_TRUE(h.state().undoEdit());
    ASSERT_TRUE(e.edit(dlab::makeMove(5, {760, 560}), message)) << message;
    e.seek(runEnd + 13);
    const std::string move = ui::captionText(h.state());
    EXPECT_NE(move.find("move vertex 5 to 760, 560, is 3 beyond the hull edge 5-6? yes: flip, 6 "
                        "leaves the hull"),
              std::string::npos)
        << move;
    EXPECT_GT(dlab::orient2d(e.mesh().G[5], e.mesh().G[3], e.mesh().G[6]), 0)
        << "6 is inside the hull 5-3";
    e.seek(e.recorded());
    const auto onHull = [&](std::int32_t v) {
        const dlab::Mesh& mm = e.mesh();
        for (std::int32_t c = 0; c < mm.numCorners(); ++c)
            if (mm.V[c] == v && e.isVirtual(mm.V[dlab::next(c)])) return true;
        return false;
    };
    EXPECT_FALSE(onHull(6));
    EXPECT_TRUE(onHull(5) && onHull(3));
}

namespace {

// At the run's end with the move tool: an interior vertex and where it is on the screen.
std::int32_t withTheMoveTool(UiHarness& h, float& x, float& y) {
    toRunEnd(h);
    const std::int32_t v = interiorVertex(h.state().engine);
    h.state().tool = ui::AppState::CanvasTool::MoveVertex;
    h.frames(1);
    if (v != kNone) screenOf(h, v, x, y);
    return v;
}

}  // namespace

TEST(EditsInTheGui, TheMoveToolTakesAVertexThenItsNewPlaceAndTheCanvasDrawsItThere) {
    UiHarness h;
    auto& st = h.state();
    auto& e = st.engine;
    float x = 0, y = 0;
    const std::int32_t v = withTheMoveTool(h, x, y);
    ASSERT_NE(v, kNone);
    h.click(x, y);
    EXPECT_EQ(st.toolFirstVertex, v);
    // Halfway to another interior-ish point: the centroid of the points.
    dlab::Vec2 c{0, 0};
    for (const auto& p : e.points()) c = {c.x + p.x, c.y + p.y};
    c = {c.x / e.points().size(), c.y / e.points().size()};
    const auto q = st.view.toScreen(c);
    h.click(static_cast<float>(q.x) + 7, static_cast<float>(q.y) - 5);
    ASSERT_NE(e.editor(), nullptr);
    ASSERT_EQ(e.editor()->edits().size(), 1u) << st.messages.back().text;
    EXPECT_EQ(e.editor()->edits()[0].kind, dlab::EditKind::MoveVertex);
    h.press(key::kEnd);
    h.frames(3);
    const dlab::Vec2 to = e.editor()->edits()[0].to;
    EXPECT_EQ(e.mesh().G[v].x, to.x);
    EXPECT_EQ(e.shownPoints()[v].x, to.x) << "the point is drawn at its new place";
    EXPECT_EQ(e.points()[v].x, e.editor()->edits()[0].from.x) << "the input is not changed";
    EXPECT_TRUE(usesVertex(e.mesh(), v));
    dlab::ValidateOptions o;
    o.firstVirtual = e.inserter().firstVirtual();
    EXPECT_TRUE(dlab::validate(e.mesh(), o).empty());
    const std::string text = ui::sessionText(st);
    EXPECT_NE(text.find("\"move vertex " + std::to_string(v) + " to "), std::string::npos);
}

// The move tool drags a vertex: one move edit, remade while the mouse moves, so the mesh follows
// the vertex; a second drag is a second edit, and Ctrl+Z undoes a whole drag.
TEST(EditsInTheGui, DraggingAVertexMakesOneMoveThatTheMeshFollowsWhileTheMouseMoves) {
    UiHarness h;
    auto& st = h.state();
    auto& e = st.engine;
    float x = 0, y = 0;
    const std::int32_t v = withTheMoveTool(h, x, y);
    ASSERT_NE(v, kNone);
    ImGuiIO& io = ImGui::GetIO();
    io.MousePos = ImVec2(x, y);
    h.frames(1);
    io.MouseDown[0] = true;
    h.frames(1);
    dlab::Vec2 last = e.mesh().G[v];
    for (int i = 1; i <= 6; ++i) {  // a few pixels at a time: the mesh follows each one
        io.MousePos = ImVec2(x + 2.0f * i, y + 1.0f * i);
        h.frames(1);
        if (i < 3) continue;  // within the click's slop
        ASSERT_NE(e.editor(), nullptr) << st.messages.back().text;
        ASSERT_EQ(e.editor()->edits().size(), 1u) << "one edit, remade as the drag goes on";
        EXPECT_EQ(e.editor()->position(), e.editor()->total()) << "its ops are done";
        EXPECT_NE(e.mesh().G[v], last) << "the vertex follows the mouse";
        last = e.mesh().G[v];
    }
    io.MouseDown[0] = false;
    h.frames(2);
    ASSERT_EQ(e.editor()->edits().size(), 1u);
    const dlab::Edit& first = e.editor()->edits()[0];
    EXPECT_EQ(first.a, v);
    EXPECT_EQ(first.from, e.points()[v]) << "from where the drag started";
    EXPECT_EQ(first.to, e.mesh().G[v]);
    EXPECT_TRUE(logged(st, "move vertex " + std::to_string(v)));
    dlab::ValidateOptions o;
    o.firstVirtual = e.inserter().firstVirtual();
    EXPECT_TRUE(dlab::validate(e.mesh(), o).empty());
    // Far out to the left of every point: beyond the hull, which grows to take it in.
    double left = e.points()[0].x;
    for (const auto& p : e.points()) left = std::min(left, p.x);
    const auto far = st.view.toScreen({left, e.mesh().G[v].y});
    const auto at = st.view.toScreen(e.mesh().G[v]);
    h.drag(static_cast<float>(at.x), static_cast<float>(at.y), static_cast<float>(far.x) - 60,
           static_cast<float>(far.y));
    ASSERT_EQ(e.editor()->edits().size(), 2u) << st.messages.back().text;
    EXPECT_LT(e.mesh().G[v].x, left) << "outside the hull of the others";
    EXPECT_TRUE(dlab::validate(e.mesh(), o).empty());
    bool onHull = false;  // a ghost triangle at v
    const dlab::Mesh& m = e.mesh();
    for (std::int32_t c = 0; c < m.numCorners(); ++c)
        onHull |=
            m.V[c] == v && (e.isVirtual(m.V[dlab::next(c)]) || e.isVirtual(m.V[dlab::prev(c)]));
    EXPECT_TRUE(onHull);
    h.press(key::letter('Z'), false, true);
    EXPECT_EQ(e.editor()->edits().size(), 1u) << "Ctrl+Z undoes the whole second drag";
}

// A breakpoint on an edit's op stops the run there, as the run's breakpoints do.
TEST(EditsInTheGui, ABreakpointOnAnEarFlipStopsARemovalThere) {
    UiHarness h;
    auto& st = h.state();
    auto& e = st.engine;
    toRunEnd(h);
    const auto bp = dlab::parseBreakpoint("ear-flip");
    ASSERT_TRUE(bp);
    st.run.breakpoints.push_back({*bp, true});
    const std::int32_t v = interiorVertex(e);
    ui::ApplyEdit(st, dlab::makeEdit(dlab::EditKind::RemoveVertex, v));
    st.run.opsPerSecond = ui::RunControl::kFullSpeed - 1;  // fast, but not End: breakpoints hold
    for (int i = 0; i < 200 && st.run.running; ++i) h.frames(1);
    EXPECT_FALSE(st.run.running);
    ASSERT_TRUE(e.editing());
    const dlab::EditStep s = e.currentEdit();
    ASSERT_NE(s.removal, nullptr) << st.run.stopReason;
    EXPECT_EQ(s.removal->type, dlab::RemoveOpType::Flip);
    EXPECT_NE(st.run.stopReason.find("breakpoint"), std::string::npos) << st.run.stopReason;
    EXPECT_LT(e.position(), e.recorded()) << "stopped inside the removal";
}
