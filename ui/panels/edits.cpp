// Edits after the run on the canvas, in the caption and in the toolbar: the constrained edges, the
// op of the edit in progress as its record says (the ear tested and its circle, a flip's new edge,
// the merged triangle; the segment's walk, Sloan's flips and waits, the repair's tests), and the
// canvas tools that make edits (remove the vertex clicked, constrain or free a segment between
// two vertices clicked; Delete removes the selected corner's vertex).
#include "core/engine/editor.h"
#include "core/engine/voronoi.h"
#include "core/teaching/describe_edit.h"
#include "ui/panels/canvas_looks.h"
#include "ui/panels/panels.h"

#include <imgui.h>

#include <cmath>
#include <string>

namespace dlab::ui {

namespace {

bool finiteVertex(const Engine& e, std::int32_t v) {
    return v >= 0 && v < e.mesh().numVertices() && !e.isVirtual(v);
}

ImVec2 screenOf(const AppState& st, std::int32_t v) {
    return toIm(st.view.toScreen(st.engine.mesh().G[v]));
}

void EdgeLine(AppState& st, ImDrawList* dl, std::int32_t a, std::int32_t b, Mark mark, float w) {
    const Engine& e = st.engine;
    if (!finiteVertex(e, a) || !finiteVertex(e, b)) return;
    const ImU32 col = useLook(st, mark);
    const ImVec2 pa = screenOf(st, a), pb = screenOf(st, b);
    if (lookOf(mark).shape != Shape::Dashed) {
        dl->AddLine(pa, pb, col, w);
        return;
    }
    const float dx = pb.x - pa.x, dy = pb.y - pa.y, len = std::hypot(dx, dy);
    const int dashes = std::max(1, static_cast<int>(len / 14));
    for (int k = 0; k < dashes; k += 2) {
        const float t0 = static_cast<float>(k) / dashes, t1 = static_cast<float>(k + 1) / dashes;
        dl->AddLine(ImVec2(pa.x + dx * t0, pa.y + dy * t0), ImVec2(pa.x + dx * t1, pa.y + dy * t1),
                    col, w);
    }
}

// The circle through three finite vertices (none for a ghost triangle: its "circle" is a
// half-plane).
void CircleThrough(AppState& st, ImDrawList* dl, std::int32_t a, std::int32_t b, std::int32_t c,
                   Mark mark) {
    const Engine& e = st.engine;
    if (!finiteVertex(e, a) || !finiteVertex(e, b) || !finiteVertex(e, c)) return;
    const auto& G = e.mesh().G;
    const Vec2 o = circumcenter(G[a], G[b], G[c]);
    const double r = std::hypot(o.x - G[a].x, o.y - G[a].y) * st.view.scale;
    if (!std::isfinite(r) || r > 1e6) return;
    dl->AddCircle(toIm(st.view.toScreen(o)), static_cast<float>(r), useLook(st, mark), 96, 2.0f);
}

void FillTriangle(AppState& st, ImDrawList* dl, std::int32_t a, std::int32_t b, std::int32_t c,
                  Mark mark) {
    const Engine& e = st.engine;
    if (!finiteVertex(e, a) || !finiteVertex(e, b) || !finiteVertex(e, c)) return;
    const ImU32 col = useLook(st, mark);
    dl->AddTriangleFilled(screenOf(st, a), screenOf(st, b), screenOf(st, c),
                          (col & 0x00FFFFFFu) | (170u << 24));
}

void DrawRemovalOp(AppState& st, ImDrawList* dl, const Edit& edit, const RemoveOp& op) {
    const Mesh& m = st.engine.mesh();
    switch (op.type) {
        case RemoveOpType::EarTest: {
            const Ear ear = earOf(m, op);
            if (op.sign > 0) FillTriangle(st, dl, ear.a, ear.b, ear.c, Mark::EarTriangle);
            CircleThrough(st, dl, ear.a, ear.b, ear.c,
                          op.sign > 0 ? Mark::CircleKeep : Mark::CircleFlip);
            EdgeLine(st, dl, op.vertex, ear.b, Mark::TestEdge, 3.0f);
            break;
        }
        case RemoveOpType::Flip: {
            const FlipEdges f = flipEdges(edit.removal.changes, op.firstChange, op.numChanges);
            EdgeLine(st, dl, f.newA, f.newB, Mark::FlippedEdge, 3.5f);
            break;
        }
        case RemoveOpType::Merge:
            if (op.a >= 0 && op.a < m.numTriangles())
                FillTriangle(st, dl, m.V[3 * op.a], m.V[3 * op.a + 1], m.V[3 * op.a + 2],
                             Mark::NewTriangles);
            break;
        case RemoveOpType::Collapse: break;
    }
}

void DrawConstraintOp(AppState& st, ImDrawList* dl, const Edit& edit, const ConstrainOp& op) {
    const Mesh& m = st.engine.mesh();
    const bool corner = op.a >= 0 && op.a < m.numCorners();
    switch (op.type) {
        case ConstrainOpType::Walk: EdgeLine(st, dl, op.a, op.b, Mark::TestEdge, 3.0f); break;
        case ConstrainOpType::SloanFlip:
        case ConstrainOpType::Flip: {
            const FlipEdges f = flipEdges(edit.constraint.changes, op.firstChange, op.numChanges);
            const bool crosses = op.type == ConstrainOpType::SloanFlip && op.sign > 0;
            EdgeLine(st, dl, f.newA, f.newB, crosses ? Mark::CrossingEdge : Mark::FlippedEdge,
                     3.5f);
            break;
        }
        case ConstrainOpType::SloanWait:
            if (corner)
                EdgeLine(st, dl, m.V[next(op.a)], m.V[prev(op.a)], Mark::CrossingEdge, 3.5f);
            break;
        case ConstrainOpType::InCircleTest:
            if (!corner) break;
            EdgeLine(st, dl, m.V[next(op.a)], m.V[prev(op.a)], Mark::TestEdge, 3.0f);
            if (st.engine.isVirtual(m.V[next(op.a)]) || st.engine.isVirtual(m.V[prev(op.a)])) {
                // Between two ghost triangles: the hull edge whose half-plane is the "circle".
                const std::int32_t x =
                    st.engine.isVirtual(m.V[next(op.a)]) ? m.V[prev(op.a)] : m.V[next(op.a)];
                EdgeLine(st, dl, m.V[op.a], x, Mark::TestEdge, 3.0f);
            }
            CircleThrough(st, dl, m.V[op.a], m.V[next(op.a)], m.V[prev(op.a)],
                          op.sign > 0 ? Mark::CircleFlip : Mark::CircleKeep);
            break;
        case ConstrainOpType::MoveVertex: {
            const ImU32 col = useLook(st, Mark::EditSegment);
            const ImVec2 from = toIm(st.view.toScreen(edit.from)), to = screenOf(st, edit.a);
            dl->AddLine(from, to, col, 2.5f);
            dl->AddCircle(from, 7.0f, useLook(st, Mark::RemovedPoint), 0, 2.0f);
            break;
        }
        case ConstrainOpType::Locate:
            if (op.b >= 0 && op.b < m.numTriangles())
                FillTriangle(st, dl, m.V[3 * op.b], m.V[3 * op.b + 1], m.V[3 * op.b + 2],
                             Mark::WalkNow);
            break;
        case ConstrainOpType::Split:
        case ConstrainOpType::SplitEdge:
        case ConstrainOpType::Fan:
            for (std::int32_t c = 0; c < m.numCorners(); ++c) {
                if (m.V[c] == op.a)
                    FillTriangle(st, dl, m.V[3 * tri(c)], m.V[3 * tri(c) + 1], m.V[3 * tri(c) + 2],
                                 Mark::NewTriangles);
            }
            break;
        case ConstrainOpType::Mark:
        case ConstrainOpType::Unmark:
        case ConstrainOpType::Reflag: break;
    }
}

}  // namespace

const char* const kCanvasToolNames[5] = {"add points", "remove vertex", "constrain segment",
                                         "free segment", "move vertex"};

void DrawEditOverlay(AppState& st, ImDrawList* dl) {
    const Engine& e = st.engine;
    const bool picking =
        st.tool == AppState::CanvasTool::Constrain || st.tool == AppState::CanvasTool::Unconstrain;
    if (picking && finiteVertex(e, st.toolFirstVertex)) {  // the segment follows the mouse
        const ImU32 col = useLook(st, Mark::EditSegment);
        dl->AddLine(screenOf(st, st.toolFirstVertex), ImGui::GetIO().MousePos, col, 2.0f);
        dl->AddCircle(screenOf(st, st.toolFirstVertex), 9.0f, col, 0, 2.5f);
    }
    if (!e.editing()) return;
    for (const auto& [a, b] : e.editor()->constrainedEdges())
        EdgeLine(st, dl, a, b, Mark::ConstrainedEdge, st.presentation ? 5.0f : 4.0f);
    const EditStep s = e.currentEdit();
    if (!s.edit) return;
    if (s.edit->kind != EditKind::RemoveVertex) {
        EdgeLine(st, dl, s.edit->a, s.edit->b, Mark::EditSegment, 2.0f);
    } else if (finiteVertex(e, s.edit->a)) {
        dl->AddCircle(screenOf(st, s.edit->a), 11.0f, useLook(st, Mark::RemovedPoint), 0, 3.0f);
    }
    if (s.removal) DrawRemovalOp(st, dl, *s.edit, *s.removal);
    if (s.constraint) DrawConstraintOp(st, dl, *s.edit, *s.constraint);
}

std::string editOpText(const Engine& e) {
    return e.editing() ? describeEditStep(*e.editor()) : std::string();
}

void ApplyEdit(AppState& st, Edit edit) {
    std::string message;
    const std::string what = describe(edit);
    if (!st.engine.edit(std::move(edit), message)) {
        st.log(Message::Level::Warning, what + " refused: " + message);
        return;
    }
    st.select(kNone);  // the corners name other triangles now
    st.log(Message::Level::Info,
           message + "; it plays now (Left steps back through it, Ctrl+Z undoes it)");
    st.run.running = true;
    st.run.toEnd = false;
}

void RemoveSelectedVertex(AppState& st) {
    const Mesh& m = st.engine.mesh();
    const std::int32_t c = st.selection.corner;
    if (c < 0 || c >= m.numCorners()) {
        st.log(Message::Level::Info,
               "Delete removes the vertex of the selected corner: click a corner first");
        return;
    }
    if (st.engine.isVirtual(m.V[c])) {
        st.log(Message::Level::Info, "the ghost vertex is not removed: select a real vertex");
        return;
    }
    ApplyEdit(st, makeEdit(EditKind::RemoveVertex, m.V[c]));
}

std::int32_t pointAt(const AppState& st, ImVec2 mouse, Engine::PointState state, float radius) {
    const auto& states = st.engine.pointStates();
    const auto& pts = st.engine.shownPoints();
    std::int32_t best = kNone;
    float bestD = radius * radius;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        if (states[i] != state) continue;
        const ImVec2 q = toIm(st.view.toScreen(pts[i]));
        const float d = (q.x - mouse.x) * (q.x - mouse.x) + (q.y - mouse.y) * (q.y - mouse.y);
        if (d < bestD) {
            bestD = d;
            best = static_cast<std::int32_t>(i);
        }
    }
    return best;
}

bool EditClick(AppState& st, ImVec2 mouse, Vec2 world) {
    using Tool = AppState::CanvasTool;
    if (st.tool == Tool::AddPoints) return false;
    if (st.tool == Tool::MoveVertex && st.toolFirstVertex != kNone) {  // where it goes
        ApplyEdit(st, makeMove(st.toolFirstVertex, world));
        st.toolFirstVertex = kNone;
        return true;
    }
    const std::int32_t v = pointAt(st, mouse, Engine::PointState::Inserted, 12.0f);
    if (v == kNone) {
        st.log(Message::Level::Info, std::string(kCanvasToolNames[static_cast<int>(st.tool)]) +
                                         ": click on a vertex of the mesh");
        return true;
    }
    if (st.tool == Tool::RemoveVertex) {
        ApplyEdit(st, makeEdit(EditKind::RemoveVertex, v));
    } else if (st.toolFirstVertex == kNone || st.toolFirstVertex == v) {
        st.toolFirstVertex = v;
        st.log(Message::Level::Info,
               st.tool == Tool::MoveVertex
                   ? "vertex " + std::to_string(v) + ": click where it goes (Esc cancels)"
                   : "segment from " + std::to_string(v) +
                         ": click the vertex at its other end (Esc cancels)");
    } else {
        const EditKind kind =
            st.tool == Tool::Constrain ? EditKind::Constrain : EditKind::Unconstrain;
        ApplyEdit(st, makeEdit(kind, st.toolFirstVertex, v));
        st.toolFirstVertex = kNone;
    }
    return true;
}

}  // namespace dlab::ui
