// Edits after the run on the canvas, in the caption and in the toolbar: the constrained edges, the
// op of the edit in progress as its record says (the ear tested and its circle, a flip's new edge,
// the merged triangle; the segment's walk, Sloan's flips and waits, the repair's tests), and the
// canvas tools that make edits (remove the vertex clicked, constrain or free a segment between
// two vertices clicked; Delete removes the selected corner's vertex).
#include "core/engine/editor.h"
#include "core/engine/numbers.h"
#include "core/engine/voronoi.h"
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

// A flip writes two V cells: the new edge's ends after it, the old edge's before it.
struct FlipEdges {
    std::int32_t oldA = kNone, oldB = kNone, newA = kNone, newB = kNone;
};
FlipEdges flipEdges(const std::vector<CellChange>& changes, std::uint32_t first, std::uint32_t n) {
    FlipEdges f;
    int k = 0;
    for (std::uint32_t i = 0; i < n && k < 2; ++i) {
        const CellChange& ch = changes[first + i];
        if (ch.isO()) continue;
        (k == 0 ? f.oldA : f.oldB) = ch.before;
        (k == 0 ? f.newB : f.newA) = ch.after;
        ++k;
    }
    return f;
}

// The ear of an ear test: its tip b, and the neighbours a and c of v on either side of it.
struct Ear {
    std::int32_t a = kNone, b = kNone, c = kNone;
};
Ear earOf(const Mesh& m, const RemoveOp& op) {
    Ear ear;
    if (op.a < 0 || op.a >= m.numCorners()) return ear;
    ear.a = m.V[next(op.a)];
    ear.b = op.b;
    const std::int32_t o = m.O[next(op.a)];
    ear.c = o == kNone ? kNone : m.V[o];
    return ear;
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

namespace {

// The ghost triangle t's hull edge, the mesh on its left, or false for a finite triangle.
bool hullEdgeOf(const Engine& e, std::int32_t t, std::int32_t& x, std::int32_t& y) {
    const Mesh& m = e.mesh();
    if (t < 0 || t >= m.numTriangles()) return false;
    for (std::int32_t g = 3 * t; g < 3 * t + 3; ++g) {
        if (!e.isVirtual(m.V[g])) continue;
        x = m.V[prev(g)];
        y = m.V[next(g)];
        return true;
    }
    return false;
}

// The ops that put a moved vertex in at its new place, in words.
std::string placeText(const Engine& e, const Edit& edit, const ConstrainOp& op) {
    const std::string v = std::to_string(op.a);
    switch (op.type) {
        case ConstrainOpType::MoveVertex: {
            std::string at = "(";
            appendShortest(at, edit.to.x);
            at += ", ";
            appendShortest(at, edit.to.y);
            at += ")";
            if (op.sign > 0)
                return v + " moves to " + at +
                       ", inside its star's kernel: every triangle at it still turns "
                       "counter-clockwise, so flips alone follow; its star's edges wait for their "
                       "in-circle tests";
            return v + " is out of the mesh (its new place is beyond its star's kernel): it "
                       "takes its new place " + at;
        }
        case ConstrainOpType::Locate: {
            std::int32_t x = kNone, y = kNone;
            if (hullEdgeOf(e, op.b, x, y))
                return v + " lies beyond the hull edge " + std::to_string(x) + "-" +
                       std::to_string(y) + " (ghost triangle " + std::to_string(op.b) +
                       "): the hull grows to take it in";
            return v +
                   (op.count == kNone ? " lies inside triangle "
                                      : " lies on an edge of triangle ") +
                   std::to_string(op.b);
        }
        case ConstrainOpType::Split:
            return "triangle " + std::to_string(op.b) + " split in three around " + v +
                   "; its edges wait for their in-circle tests";
        case ConstrainOpType::SplitEdge:
            return "the edge " + v + " lies on split in two (a constraint on it holds both halves)";
        default: return toString(op.type);
    }
}

}  // namespace

std::string editOpText(const Engine& e) {
    const EditStep s = e.currentEdit();
    if (!s.edit) return "";
    const Mesh& m = e.mesh();
    // The ghost vertex reads "g", as the canvas labels it.
    const auto id = [&](std::int32_t v) { return e.isVirtual(v) ? "g" : std::to_string(v); };
    const auto edge = [&](std::int32_t a, std::int32_t b) { return id(a) + "-" + id(b); };
    std::string out = describe(*s.edit) + ", ";
    if (s.removal) {
        const RemoveOp& op = *s.removal;
        const std::string v = std::to_string(op.vertex);
        switch (op.type) {
            case RemoveOpType::EarTest: {
                const Ear ear = earOf(m, op);
                out += "ear test at " + id(ear.b) + ": triangle " + edge(ear.a, ear.b) + "-" +
                       id(ear.c) +
                       (op.sign > 0 ? " has no other neighbour of " + v +
                                          " inside its circle: an ear, cut it next"
                        : op.sign == 0 ? " is flat: cut only when no other ear is left"
                                       : " is no ear: a neighbour of " + v +
                                             " is inside its circle, or it turns the wrong way");
                break;
            }
            case RemoveOpType::Flip: {
                const FlipEdges f =
                    flipEdges(s.edit->removal.changes, op.firstChange, op.numChanges);
                out += "flip " + edge(f.oldA, f.oldB) + " to " + edge(f.newA, f.newB) +
                       ": the ear is a triangle of the result, " + v + " has one neighbour less";
                break;
            }
            case RemoveOpType::Merge:
                out += v + " has three neighbours left: its triangles merge into triangle " +
                       std::to_string(op.a);
                break;
            case RemoveOpType::Collapse: out += "the points left make no triangle"; break;
        }
        return out;
    }
    const ConstrainOp& op = *s.constraint;
    switch (op.type) {
        case ConstrainOpType::Walk:
            out += "walk from " + std::to_string(op.a) + " to " + std::to_string(op.b) + ": " +
                   std::to_string(op.count) + (op.count == 1 ? " edge crosses" : " edges cross") +
                   " the segment" + (op.b != op.segmentB ? " (a vertex lies on it)" : "");
            break;
        case ConstrainOpType::SloanFlip: {
            const FlipEdges f =
                flipEdges(s.edit->constraint.changes, op.firstChange, op.numChanges);
            out +=
                "flip the crossing edge " + edge(f.oldA, f.oldB) + " to " + edge(f.newA, f.newB) +
                (op.sign > 0 ? ": it still crosses, back in the queue" : ": it no longer crosses");
            break;
        }
        case ConstrainOpType::SloanWait:
            out += "the crossing edge " + edge(m.V[next(op.a)], m.V[prev(op.a)]) +
                   " has a quadrilateral that is not convex: it waits";
            break;
        case ConstrainOpType::Mark: out += edge(op.a, op.b) + " is now a constrained edge"; break;
        case ConstrainOpType::Unmark:
            out += edge(op.a, op.b) + " is held by one constraint less";
            break;
        case ConstrainOpType::Reflag:
            out += "the constrained edges are flagged again on their corners";
            break;
        case ConstrainOpType::InCircleTest: {
            const std::int32_t A = m.V[next(op.a)], B = m.V[prev(op.a)];
            if (e.isVirtual(A) || e.isVirtual(B)) {  // between two ghost triangles
                const std::int32_t x = e.isVirtual(A) ? B : A;  // on the hull, or leaving it
                out += "is " + id(m.V[op.b]) + " beyond the hull edge " + edge(m.V[op.a], x) +
                       "? " +
                       (op.sign > 0 ? "yes: flip, " + id(x) + " leaves the hull"
                                    : "no: keep, " + id(x) + " stays on the hull");
                break;
            }
            out += "is " + id(m.V[op.b]) + " inside the circle across " + edge(A, B) + "? " +
                   (op.sign > 0 ? "yes: flip" : "no: keep");
            break;
        }
        case ConstrainOpType::Flip: {
            const FlipEdges f =
                flipEdges(s.edit->constraint.changes, op.firstChange, op.numChanges);
            out += "flip " + edge(f.oldA, f.oldB) + " to " + edge(f.newA, f.newB);
            break;
        }
        default: out += placeText(e, *s.edit, op); break;
    }
    return out;
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
