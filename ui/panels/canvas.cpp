// The canvas: the mesh, the current operation highlighted (walk path and line L, the new
// triangles of a split, the edge under test with its circle, flips, the queue of edges still to
// test), labels of vertices, corners and triangles, Voronoi and circumcircles; pan, zoom, fit,
// click to add a point, right-click to remove a queued one, drag queued points, pick corners.
//
// Index
//   [SECTION] Colours and small drawing helpers
//   [SECTION] Corner anchors (where a corner's label sits inside its triangle)
//   [SECTION] Highlights of the current operation
//   [SECTION] Labels, points, selection
//   [SECTION] Input
//   [SECTION] ShowCanvas
#include "core/engine/voronoi.h"
#include "ui/gui.h"
#include "ui/panels/canvas_looks.h"
#include "ui/panels/labels.h"
#include "ui/panels/panels.h"
#include "ui/render/drawn_marks.h"
#include "ui/render/renderer.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace dlab::ui {

// Up to this many points, points are drawn as ImDrawList circles with ids; above, by GL.
// Up to this many points are drawn as ImGui circles (with ids when asked); beyond, our GL renderer
// draws them: each circle costs ~50 of a draw list's 65536 vertices (canvasHasRoom).
constexpr std::size_t kFewPoints = 600;
constexpr unsigned kVerticesPerPoint = 64;
constexpr int kSkippedDrawn = 300;  // crosses for skipped duplicates when there are many points

struct CanvasCache {
    // The mesh as the renderer draws it (GL, or counted by the null renderer), made by it.
    std::unique_ptr<CanvasMesh> renderer;
    Renderer* madeBy = nullptr;
    bool rebuiltLastFrame = false;
    View builtView;  // the view of the last rebuild
    // The view the last fit made: while center and scale are still these, the user has not
    // moved it, and a resize fits again.
    bool fitted = false;
    glm::dvec2 fitCenter{0, 0};
    double fitScale = 0;
    // Interaction in progress (press on the canvas until release).
    enum class Drag : std::uint8_t { None, Pan, Point, Pending, Vertex } drag = Drag::None;
    std::int32_t dragPoint = kNone;
    bool dragMoved = false;  // Drag::Vertex: the drag's move edit is made (the last edit)
    Vec2 dragTo{0, 0};       // where it last went
    ImVec2 pressPos{0, 0};
    bool moved = false;
    bool pressedOnCorner = false;
    // What this frame drew (the legend's entries; the layers over the canvas add theirs) and
    // what the legend should not cover.
    MarksDrawn drawn;
    std::vector<BusyPoint> busy;
    IdBufferCopy idCopy;  // a GL ID buffer read back for the pixel grid
};

namespace {

// ============================================================================================
// [SECTION] Colours and small drawing helpers
// ============================================================================================

// The mesh's own colours; what stands for something of the run takes its look from the marks'
// table (canvas_looks.h), which the legend lists.
struct Palette {
    ImU32 background, grid, fill, edge, virtualEdge, vertex, vertexId;
    ImU32 split[3], cornerId, triangleId, ghostId;
};

Palette palette(bool presentation) {
    Palette p{};
    p.background = IM_COL32(255, 255, 255, 255);
    p.grid = IM_COL32(232, 236, 242, 255);
    p.fill = IM_COL32(236, 242, 252, 255);
    p.edge = presentation ? IM_COL32(20, 20, 30, 255) : IM_COL32(70, 78, 96, 255);
    p.virtualEdge = IM_COL32(175, 180, 190, 255);
    p.vertex = IM_COL32(20, 20, 30, 255);
    p.vertexId = IM_COL32(25, 60, 160, 255);
    // The new triangles of a split (Mark::NewTriangles), told apart by their fills.
    p.split[0] = IM_COL32(214, 234, 200, 255);
    p.split[1] = lookOf(Mark::NewTriangles).colour;
    p.split[2] = IM_COL32(240, 214, 236, 255);
    p.cornerId = IM_COL32(110, 110, 120, 255);
    p.triangleId = IM_COL32(90, 120, 90, 255);
    p.ghostId = IM_COL32(150, 130, 190, 255);
    return p;
}

// Clips segment ab to the rectangle [lo, hi] (Liang-Barsky); false when nothing is left.
bool clipSegment(ImVec2& a, ImVec2& b, ImVec2 lo, ImVec2 hi) {
    const double dx = static_cast<double>(b.x) - a.x, dy = static_cast<double>(b.y) - a.y;
    double t0 = 0, t1 = 1;
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {static_cast<double>(a.x) - lo.x, static_cast<double>(hi.x) - a.x,
                         static_cast<double>(a.y) - lo.y, static_cast<double>(hi.y) - a.y};
    for (int i = 0; i < 4; ++i) {
        if (!std::isfinite(p[i]) || !std::isfinite(q[i])) return false;
        if (p[i] == 0) {
            if (q[i] < 0) return false;
            continue;
        }
        const double r = q[i] / p[i];
        if (p[i] < 0)
            t0 = std::max(t0, r);
        else
            t1 = std::min(t1, r);
        if (t0 > t1) return false;
    }
    const ImVec2 a0 = a;
    a = ImVec2(static_cast<float>(a0.x + t0 * dx), static_cast<float>(a0.y + t0 * dy));
    b = ImVec2(static_cast<float>(a0.x + t1 * dx), static_cast<float>(a0.y + t1 * dy));
    return true;
}

// Dashes only the visible part: an edge to a super-triangle vertex of a huge box can be
// millions of pixels long on screen (a dash each would exhaust memory).
void DashedLine(ImDrawList* dl, ImVec2 a, ImVec2 b, ImU32 col, float thickness, float dash = 7,
                float gap = 5) {
    if (!clipSegment(a, b, dl->GetClipRectMin(), dl->GetClipRectMax())) return;
    const float dx = b.x - a.x, dy = b.y - a.y, len = std::sqrt(dx * dx + dy * dy);
    if (len < 1e-3f) return;
    const float ux = dx / len, uy = dy / len;
    for (float t = 0; t < len; t += dash + gap) {
        const float e = std::min(len, t + dash);
        dl->AddLine(ImVec2(a.x + ux * t, a.y + uy * t), ImVec2(a.x + ux * e, a.y + uy * e), col,
                    thickness);
    }
}

void Arrow(ImDrawList* dl, ImVec2 a, ImVec2 b, ImU32 col, float thickness) {
    dl->AddLine(a, b, col, thickness);
    const float dx = b.x - a.x, dy = b.y - a.y, len = std::sqrt(dx * dx + dy * dy);
    if (len < 1) return;
    const float ux = dx / len, uy = dy / len, s = 9 + thickness * 2;
    dl->AddTriangleFilled(b, ImVec2(b.x - ux * s - uy * s * 0.5f, b.y - uy * s + ux * s * 0.5f),
                          ImVec2(b.x - ux * s + uy * s * 0.5f, b.y - uy * s - ux * s * 0.5f), col);
}

// The point being inserted: a diamond, white-edged (no other mark is one).
void DrawNextPoint(ImDrawList* dl, ImVec2 q, float r, ImU32 col) {
    const float d = r + 5;
    dl->AddQuadFilled(ImVec2(q.x, q.y - d - 2), ImVec2(q.x + d + 2, q.y), ImVec2(q.x, q.y + d + 2),
                      ImVec2(q.x - d - 2, q.y), IM_COL32(255, 255, 255, 255));
    dl->AddQuadFilled(ImVec2(q.x, q.y - d), ImVec2(q.x + d, q.y), ImVec2(q.x, q.y + d),
                      ImVec2(q.x - d, q.y), col);
}

// A label centred at `centre`; with an id, recorded as a mark in `role` (lesson check).
void LabelBox(ImDrawList* dl, ImFont* font, float size, ImVec2 centre, ImU32 text, ImU32 box,
              const char* s, SlideMarkRole role = SlideMarkRole::Canvas, std::int32_t id = -1) {
    const ImVec2 ts = font->CalcTextSizeA(size, 1e9f, 0, s);
    const ImVec2 a(centre.x - ts.x / 2 - 2, centre.y - ts.y / 2),
        b(centre.x + ts.x / 2 + 2, centre.y + ts.y / 2);
    if (box) dl->AddRectFilled(a, b, box, 3);
    dl->AddText(font, size, ImVec2(a.x + 2, a.y), text, s);
    if (id >= 0) recordMark(role, id, -1, a.x + 2, a.y, b.x - 2, b.y);
}

// ============================================================================================
// [SECTION] Corner anchors
// ============================================================================================

// Everything the overlays need to place things on the screen.
struct Scene {
    AppState& st;  // non-const only for frameStats.canvasFull (room())
    const Engine& e;
    const Mesh& m;
    const Inserter& ins;
    const View& view;
    ImDrawList* dl;
    Palette pal;
    bool running;  // virtual vertices still present
    bool ghostMode;
    // Labels placed so far this frame (x0, y0, x1, y1), and where each vertex label goes (its
    // top-left; NaN: none): later labels avoid earlier ones (labels.cpp).
    mutable LabelBoxes labels{};
    mutable std::vector<ImVec2> vertexLabelAt{};
    mutable std::size_t vertexLabelsFrom = 0, vertexLabelsTo = 0;  // their boxes in `labels`
    mutable std::optional<ImVec2> selectedLabelAt{};  // where the selected corner's label went
    mutable MarksDrawn drawn{};                       // the marks drawn so far (the legend's)

    // A mark's colour, recorded as drawn.
    ImU32 use(Mark mark) const {
        drawn.set(static_cast<std::size_t>(mark));
        return lookOf(mark).colour;
    }

    ImVec2 screen(std::int32_t v) const { return toIm(view.toScreen(m.G[v])); }
    bool virtualTri(std::int32_t t) const { return running && e.isVirtualTriangle(t); }
    bool room(unsigned vertices) const { return canvasHasRoom(st, dl, vertices); }
    // Labels leave this much room for the points, drawn after them (on top).
    unsigned pointReserve() const {
        return kVerticesPerPoint *
               static_cast<unsigned>(std::min<std::size_t>(e.points().size(), kFewPoints));
    }
    bool drawable(std::int32_t t) const {
        return t >= 0 && t < m.numTriangles() && !(ghostMode && virtualTri(t));
    }
    // Exact mode while the run is in progress: a ghost triangle (u, w, ghost) stands for the
    // half-plane beyond the hull edge u -> w (on its left). Its corners are drawn just outside
    // that edge.
    bool ghostTri(std::int32_t t) const {
        return ghostMode && t >= 0 && t < m.numTriangles() && virtualTri(t);
    }
    // The hull edge u -> w of ghost triangle t and the index (0..2) of its ghost corner.
    bool hullEdge(std::int32_t t, std::int32_t& u, std::int32_t& w, int& k) const {
        if (!ghostTri(t)) return false;
        for (k = 0; k < 3 && !ins.isVirtual(m.V[3 * t + k]); ++k) {}
        if (k == 3) return false;
        u = m.V[3 * t + (k + 1) % 3];
        w = m.V[3 * t + (k + 2) % 3];
        return !ins.isVirtual(u) && !ins.isVirtual(w);
    }
    // The screen direction along u -> w (unit), its length, and the unit normal towards the
    // ghost's side (the world's left of u -> w is the screen's right: y is flipped).
    static void edgeFrame(ImVec2 pu, ImVec2 pw, ImVec2& dir, float& len, ImVec2& out) {
        const float dx = pw.x - pu.x, dy = pw.y - pu.y;
        len = std::sqrt(dx * dx + dy * dy);
        dir = len > 0 ? ImVec2(dx / len, dy / len) : ImVec2(1, 0);
        out = ImVec2(dir.y, -dir.x);
    }
    // A ghost triangle's corner label: the ghost corner beyond the middle of the hull edge, the
    // two others beside their hull vertices, all on the ghost's side.
    bool ghostAnchor(std::int32_t c, ImVec2& out) const {
        std::int32_t u, w;
        int k;
        if (!hullEdge(tri(c), u, w, k)) return false;
        const ImVec2 pu = screen(u), pw = screen(w);
        ImVec2 dir, n;
        float len;
        edgeFrame(pu, pw, dir, len, n);
        if (!(len > 60) || !std::isfinite(len)) return false;
        if (c == 3 * tri(c) + k) {
            out = ImVec2((pu.x + pw.x) / 2 + n.x * 26, (pu.y + pw.y) / 2 + n.y * 26);
        } else if (m.V[c] == u) {
            out = ImVec2(pu.x + dir.x * 20 + n.x * 13, pu.y + dir.y * 20 + n.y * 13);
        } else {
            out = ImVec2(pw.x - dir.x * 20 + n.x * 13, pw.y - dir.y * 20 + n.y * 13);
        }
        return true;
    }
    // The three screen corners of a drawable triangle.
    void corners(std::int32_t t, ImVec2 out[3]) const {
        for (int k = 0; k < 3; ++k) out[k] = screen(m.V[3 * t + k]);
    }
    // Where corner c's label sits: on the angle bisector at c, a little inside the triangle.
    // False when the triangle is too small on screen for a label.
    bool anchor(std::int32_t c, ImVec2& out) const {
        if (c < 0 || c >= m.numCorners()) return false;
        if (ghostTri(tri(c))) return ghostAnchor(c, out);
        if (!drawable(tri(c))) return false;
        const ImVec2 a = screen(m.V[c]), b = screen(m.V[next(c)]), d = screen(m.V[prev(c)]);
        const float e1x = b.x - a.x, e1y = b.y - a.y, e2x = d.x - a.x, e2y = d.y - a.y;
        const float l1 = std::sqrt(e1x * e1x + e1y * e1y), l2 = std::sqrt(e2x * e2x + e2y * e2y);
        if (!(l1 > 24 && l2 > 24) || !std::isfinite(l1 + l2)) return false;
        float bx = e1x / l1 + e2x / l2, by = e1y / l1 + e2y / l2;
        const float bl = std::sqrt(bx * bx + by * by);
        if (bl < 1e-4f) return false;
        bx /= bl;
        by /= bl;
        const float dist = std::clamp(0.3f * std::min(l1, l2), 10.0f, 26.0f);
        out = ImVec2(a.x + bx * dist, a.y + by * dist);
        return true;
    }
    // Whether a screen box [x0, x1] x [y0, y1] (plus a margin) meets the canvas: shapes off it
    // are not sent to the draw list at all (it holds at most 65536 vertices).
    bool onCanvas(float x0, float y0, float x1, float y1, float margin = 4) const {
        return x1 >= view.origin.x - margin && x0 <= view.origin.x + view.size.x + margin &&
               y1 >= view.origin.y - margin && y0 <= view.origin.y + view.size.y + margin;
    }
    bool onCanvas(const ImVec2 (&p)[3]) const {
        return onCanvas(std::min({p[0].x, p[1].x, p[2].x}), std::min({p[0].y, p[1].y, p[2].y}),
                        std::max({p[0].x, p[1].x, p[2].x}), std::max({p[0].y, p[1].y, p[2].y}));
    }
    void fillTriangle(std::int32_t t, ImU32 col) const {
        if (!drawable(t)) return;
        ImVec2 p[3];
        corners(t, p);
        if (onCanvas(p)) dl->AddTriangleFilled(p[0], p[1], p[2], col);
    }
    void outlineTriangle(std::int32_t t, ImU32 col, float w) const {
        if (!drawable(t)) return;
        ImVec2 p[3];
        corners(t, p);
        dl->AddTriangle(p[0], p[1], p[2], col, w);
    }
    // Edge a-b; with a role other than Canvas, recorded as a mark in it (lesson check).
    bool edge(std::int32_t a, std::int32_t b, ImU32 col, float w, bool dashed = false,
              SlideMarkRole role = SlideMarkRole::Canvas) const {
        if (a < 0 || b < 0 || a >= m.numVertices() || b >= m.numVertices()) return false;
        if (ghostMode && running && (ins.isVirtual(a) || ins.isVirtual(b))) return false;
        const ImVec2 pa = screen(a), pb = screen(b);
        if (!onCanvas(std::min(pa.x, pb.x), std::min(pa.y, pb.y), std::max(pa.x, pb.x),
                      std::max(pa.y, pb.y), w))
            return false;
        dashed ? DashedLine(dl, pa, pb, col, w) : dl->AddLine(pa, pb, col, w);
        if (role != SlideMarkRole::Canvas) recordMark(role, a, b, pa.x, pa.y, pb.x, pb.y);
        return true;
    }
    // A circle given in world coordinates (centre, radius), clipped by the canvas.
    bool circle(Vec2 c, double r, ImU32 col, float w) const {
        const glm::dvec2 s = view.toScreen(c);
        const double rs = r * view.scale;
        if (!std::isfinite(rs) || rs > 1e6) return false;
        const float x = static_cast<float>(s.x), y = static_cast<float>(s.y),
                    rf = static_cast<float>(rs);
        if (!onCanvas(x - rf, y - rf, x + rf, y + rf, w)) return false;
        // Wholly around the canvas: nothing of it shows.
        const double dx =
            std::max(std::abs(s.x - view.origin.x), std::abs(s.x - view.origin.x - view.size.x));
        const double dy =
            std::max(std::abs(s.y - view.origin.y), std::abs(s.y - view.origin.y - view.size.y));
        if (dx * dx + dy * dy < (rs - w) * (rs - w)) return false;
        dl->AddCircle(toIm(s), static_cast<float>(rs), col,
                      std::clamp(static_cast<int>(rs / 3), 24, 256), w);
        return true;
    }
};

bool circumcircle(const Mesh& m, std::int32_t t, Vec2& centre, double& radius) {
    const Vec2 a = m.G[m.V[3 * t]], b = m.G[m.V[3 * t + 1]], c = m.G[m.V[3 * t + 2]];
    centre = circumcenter(a, b, c);
    radius = std::hypot(centre.x - a.x, centre.y - a.y);
    return std::isfinite(centre.x) && std::isfinite(centre.y) && std::isfinite(radius);
}

// ============================================================================================
// [SECTION] Highlights of the current operation
// ============================================================================================

// The walk is in ghost triangle t (exact mode: the point lies beyond that hull edge): its wedge
// outside the hull in the colour of the walk's current triangle, deep enough to hold the point.
void DrawGhostTarget(const Scene& s, std::int32_t t, std::int32_t point) {
    ImVec2 a, b, da, db;
    if (!ghostWedge(s.st, t, a, b, da, db)) return;
    ImVec2 dir, n;
    float len;
    Scene::edgeFrame(a, b, dir, len, n);
    float depth = std::max(ImGui::GetFontSize() * 5.0f,
                           0.15f * static_cast<float>(std::min(s.view.size.x, s.view.size.y)));
    if (point >= 0 && point < s.m.numVertices()) {
        const ImVec2 q = s.screen(point);
        depth = std::max(depth, (q.x - a.x) * n.x + (q.y - a.y) * n.y + 30.0f);
    }
    depth = std::min(depth, 4.0f * static_cast<float>(s.view.size.x + s.view.size.y));
    const ImVec2 p[4] = {a, b, ImVec2(b.x + db.x * depth, b.y + db.y * depth),
                         ImVec2(a.x + da.x * depth, a.y + da.y * depth)};
    const ImU32 col = s.use(Mark::WalkNow);
    s.dl->AddConvexPolyFilled(p, 4, (col & 0x00FFFFFFu) | (190u << 24));
    s.dl->AddPolyline(p, 4, col, ImDrawFlags_Closed, 2.0f);
}

void DrawOpUnderlay(const Scene& s) {
    const Op* op = s.e.current();
    if (!op || !s.st.overlays.walk) return;
    const Mesh& m = s.m;
    switch (op->type) {
        case OpType::LocateStep:
        case OpType::Located: {
            const std::vector<std::int32_t> path = s.e.walkPath();
            for (std::int32_t t : path) {
                if (!s.room(16)) break;
                s.fillTriangle(t, s.use(Mark::WalkVisited));
            }
            if (!path.empty() && s.ghostTri(path.back()))
                DrawGhostTarget(s, path.back(), op->vertex);
            else if (!path.empty())
                s.fillTriangle(path.back(), s.use(Mark::WalkNow));
            break;
        }
        case OpType::Split:
            s.use(Mark::NewTriangles);
            s.fillTriangle(op->a, s.pal.split[0]);
            s.fillTriangle(op->trianglesBefore, s.pal.split[1]);
            s.fillTriangle(op->trianglesBefore + 1, s.pal.split[2]);
            break;
        case OpType::SplitEdge:
            s.use(Mark::NewTriangles);
            s.fillTriangle(tri(op->a), s.pal.split[0]);
            s.fillTriangle(op->trianglesBefore, s.pal.split[1]);
            if (op->b != kNone) {
                s.fillTriangle(tri(op->b), s.pal.split[2]);
                s.fillTriangle(op->trianglesBefore + 1, s.pal.split[0]);
            }
            break;
        case OpType::Flip:
            s.use(Mark::NewTriangles);
            if (op->a >= 0 && op->a < m.numCorners()) s.fillTriangle(tri(op->a), s.pal.split[1]);
            if (op->b >= 0 && op->b < m.numCorners()) s.fillTriangle(tri(op->b), s.pal.split[2]);
            break;
        default: break;
    }
}

// Clips a convex polygon to the rectangle [lo, hi] (Sutherland-Hodgman, one side at a time).
std::vector<ImVec2> clipPolygon(std::vector<ImVec2> poly, ImVec2 lo, ImVec2 hi) {
    auto side = [&](int axis, float bound, bool keepBelow) {
        std::vector<ImVec2> out;
        auto inside = [&](ImVec2 p) {
            const float v = axis == 0 ? p.x : p.y;
            return keepBelow ? v <= bound : v >= bound;
        };
        for (std::size_t i = 0; i < poly.size(); ++i) {
            const ImVec2 a = poly[i], b = poly[(i + 1) % poly.size()];
            const bool ia = inside(a), ib = inside(b);
            if (ia) out.push_back(a);
            if (ia != ib) {
                const float va = axis == 0 ? a.x : a.y, vb = axis == 0 ? b.x : b.y;
                const float t = (bound - va) / (vb - va);
                out.emplace_back(a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t);
            }
        }
        poly = std::move(out);
    };
    side(0, lo.x, false);
    side(0, hi.x, true);
    side(1, lo.y, false);
    side(1, hi.y, true);
    return poly;
}

// An in-circle test against ghost triangle t: its "circle" is the open half-plane beyond the
// hull edge u -> w (plus the open edge itself). Drawn as that: the half-plane lightly shaded and
// the line through the edge dashed beyond it, clipped to the canvas; the hull edge keeps the
// colour of the edge under test when it is that edge, else it takes the half-plane's.
void DrawHalfPlane(const Scene& s, std::int32_t t, ImU32 col, float w, bool edgeUnderTest) {
    std::int32_t u, v;
    int k;
    if (!s.hullEdge(t, u, v, k)) return;
    const ImVec2 pu = s.screen(u), pv = s.screen(v);
    ImVec2 dir, n;
    float len;
    Scene::edgeFrame(pu, pv, dir, len, n);
    if (!(len > 0) || !std::isfinite(len)) return;
    // Far enough to leave the canvas in every direction.
    const float far = 4.0f * static_cast<float>(s.view.size.x + s.view.size.y) + len;
    const ImVec2 a(pu.x - dir.x * far, pu.y - dir.y * far),
        b(pv.x + dir.x * far, pv.y + dir.y * far);
    const ImVec2 lo = toIm(s.view.origin), hi = toIm(s.view.origin + s.view.size);
    const std::vector<ImVec2> shade = clipPolygon(
        {a, b, ImVec2(b.x + n.x * far, b.y + n.y * far), ImVec2(a.x + n.x * far, a.y + n.y * far)},
        lo, hi);
    if (shade.size() >= 3 && s.room(static_cast<unsigned>(shade.size()) * 2 + 8))
        s.dl->AddConvexPolyFilled(shade.data(), static_cast<int>(shade.size()), col);
    // The half-plane's border: the hull edge's line beyond the edge under test (left as it is).
    const ImU32 line = col | 0xFF000000u;
    if (s.room(400)) {
        DashedLine(s.dl, a, pu, line, w * 0.6f);
        DashedLine(s.dl, pv, b, line, w * 0.6f);
    }
    if (!edgeUnderTest) s.edge(u, v, line, w * 1.6f);  // the tested edge is a ghost one
}

// Where queued edge q is drawn on the screen: from pa to pb. An edge to the ghost vertex (exact
// mode) stands for the ray from its hull vertex that two ghost wedges share: drawn that far.
bool queuedEdgeOnScreen(const Scene& s, const Engine::QueuedTest& q, ImVec2& pa, ImVec2& pb) {
    const VertexEdge e = q.edge;
    if (e.a < 0 || e.b < 0 || e.a >= s.m.numVertices() || e.b >= s.m.numVertices()) return false;
    const bool va = s.ins.isVirtual(e.a), vb = s.ins.isVirtual(e.b);
    if (!s.ghostMode || !s.running || (!va && !vb)) {
        pa = s.screen(e.a);
        pb = s.screen(e.b);
        return true;
    }
    if (va && vb) return false;
    const std::int32_t u = va ? e.b : e.a;
    ImVec2 a, b, da, db;
    if (!ghostWedge(s.st, q.near, a, b, da, db)) return false;
    pa = s.screen(u);
    const ImVec2 side = (pa.x == a.x && pa.y == a.y) ? da : db;
    const float len = ImGui::GetFontSize() * 3.2f;
    pb = ImVec2(pa.x + side.x * len, pa.y + side.y * len);
    return true;
}

// The point at `t` along a -> b, or (when that is within `clear` pixels of `point`) the nearest
// of a few others along the edge that is not.
ImVec2 clearOfPoint(ImVec2 a, ImVec2 b, float t, float clear, std::optional<ImVec2> point) {
    const auto at = [&](float u) { return ImVec2(a.x + (b.x - a.x) * u, a.y + (b.y - a.y) * u); };
    if (!point) return at(t);
    for (const float d : {0.0f, -0.15f, 0.15f, -0.25f, 0.25f}) {
        const ImVec2 p = at(t + d);
        if (std::hypot(p.x - point->x, p.y - point->y) >= clear) return p;
    }
    return at(t);
}

// The edges on the flip stack, dashed (grey where an entry now names a hull edge: it comes off
// with nothing to test), each edge once however often it is on the stack, and each entry's place
// in the stack in a disc on its edge: 1 is the top, the edge the engine tests next (the Flip
// queue section lists them alike), or in push order 1 is the bottom, the entry pushed first; a
// second entry of one edge sits beside the first's disc.
void DrawFlipQueue(const Scene& s, float w) {
    const std::vector<Engine::QueuedTest> queue = s.e.pendingTests();
    if (queue.empty()) return;
    std::vector<ImVec2> ends(2 * queue.size());
    std::vector<bool> shown(queue.size());
    std::vector<int> repeat(queue.size(), 0);  // earlier entries (nearer the top) of the same edge
    std::map<std::pair<std::int32_t, std::int32_t>, int> seen;
    for (std::size_t i = 0; i < queue.size(); ++i) {
        const VertexEdge e = queue[i].edge;
        repeat[i] = seen[{std::min(e.a, e.b), std::max(e.a, e.b)}]++;
        shown[i] = queuedEdgeOnScreen(s, queue[i], ends[2 * i], ends[2 * i + 1]);
        const ImVec2 pa = ends[2 * i], pb = ends[2 * i + 1];
        if (!shown[i] || !s.room(200)) continue;  // dashes: at most ~2 screen diagonals of them
        const ImU32 col = s.use(queue[i].far == kNone ? Mark::QueuedOnHull : Mark::QueuedEdge);
        if (s.onCanvas(std::min(pa.x, pb.x), std::min(pa.y, pb.y), std::max(pa.x, pb.x),
                       std::max(pa.y, pb.y), w)) {
            if (repeat[i] == 0) DashedLine(s.dl, pa, pb, col, w);  // an edge's dashes once
            recordMark(SlideMarkRole::QueuedEdge, queue[i].edge.a, queue[i].edge.b, pa.x, pa.y,
                       pb.x, pb.y);  // every entry: the queue's count as drawn
        }
    }
    // Numbered in test order (1 = the top), or else in push order (1 = the bottom, pushed first).
    const bool testOrder = s.st.overlays.queueOrder;
    if (!testOrder && !s.st.overlays.queuePushed) return;
    const ImU32 badge = s.use(testOrder ? Mark::QueueOrder : Mark::QueuePushed);
    ImFont* font = fonts().ui;
    const float fs = ImGui::GetFontSize() * 0.8f, r = fs * 0.72f;
    char buf[24];
    const std::int32_t v = s.e.currentVertex();  // its point is drawn over the discs
    const std::optional<ImVec2> now =
        v >= 0 && v < s.m.numVertices() ? std::optional<ImVec2>(s.screen(v)) : std::nullopt;
    // The last first, so that the next edge's disc is on top where discs meet.
    for (std::size_t i = queue.size(); i-- > 0;) {
        if (!shown[i]) continue;
        const ImVec2 pa = ends[2 * i], pb = ends[2 * i + 1];
        std::snprintf(buf, sizeof buf, "%zu", testOrder ? i + 1 : queue.size() - i);
        const ImVec2 ts = font->CalcTextSizeA(fs, 1e9f, 0, buf);
        const float rr = std::max(r, ts.x / 2 + 3);
        const float dx = pb.x - pa.x, dy = pb.y - pa.y, len = std::hypot(dx, dy);
        const float shift = len > 0 ? repeat[i] * (2 * rr + 3) / len : 0;  // along the edge
        const ImVec2 mid = clearOfPoint(pa, pb, 0.5f + shift, rr + 12, now);
        if (!s.onCanvas(mid.x - r, mid.y - r, mid.x + r, mid.y + r) || !s.room(80)) continue;
        s.dl->AddCircleFilled(mid, rr + 1.5f, IM_COL32(255, 255, 255, 255));
        s.dl->AddCircleFilled(mid, rr, queue[i].far == kNone ? s.use(Mark::QueuedOnHull) : badge);
        s.dl->AddText(font, fs, ImVec2(mid.x - ts.x / 2, mid.y - ts.y / 2),
                      IM_COL32(255, 255, 255, 255), buf);
        s.labels.add(mid, ImVec2(2 * rr - 4, 2 * rr));  // corner labels keep clear of it
    }
}

// The edges a split (or an edge split) made at the new vertex, when the current op is one.
void DrawSplitEdges(const Scene& s, float w) {
    const Op* op = s.e.current();
    const Mesh& m = s.m;
    if (!op || (op->type != OpType::Split && op->type != OpType::SplitEdge)) return;
    if (op->vertex < 0 || op->vertex >= m.numVertices()) return;
    for (std::int32_t t : {tri(op->a), op->trianglesBefore, op->trianglesBefore + 1}) {
        if (t < 0 || t >= m.numTriangles()) continue;
        for (int k = 0; k < 3; ++k) {
            if (m.V[3 * t + k] == op->vertex)
                s.edge(op->vertex, m.V[3 * t + (k + 1) % 3], s.use(Mark::NewEdge), w);
        }
    }
}

void DrawOpOverlay(const Scene& s) {
    const Op* op = s.e.current();
    const Mesh& m = s.m;
    const Overlays& ov = s.st.overlays;
    const float w = s.st.presentation ? 4.0f : 2.5f;
    // Through the whole insertion: edges flipped so far and edges still to test.
    if (ov.flipped) {
        for (const VertexEdge& fe : s.e.flippedEdges()) {
            if (!s.room(8)) break;
            s.edge(fe.a, fe.b, s.use(Mark::FlippedEdge), w, false, SlideMarkRole::FlippedEdge);
        }
    }
    if (ov.flipQueue) DrawFlipQueue(s, w);
    if (!op) return;
    switch (op->type) {
        case OpType::LocateStep:
        case OpType::Located: {
            if (!ov.walk) break;
            const Control& ctl = s.ins.control();
            const std::int32_t v = op->vertex;
            if (v >= 0 && v < m.numVertices() && ctl.walk.straight && ctl.walk.steps > 0) {
                // The paper's line L from q (inside the start triangle) to the new point.
                Arrow(s.dl, toIm(s.view.toScreen(ctl.walk.origin)), s.screen(v), s.use(Mark::LineL),
                      w * 0.7f);
            }
            break;
        }
        case OpType::InCircleTest: {
            const std::int32_t a = op->a, b = op->b;
            if (a < 0 || a >= m.numCorners()) break;
            // An edge to the ghost vertex has no segment to draw: no legend entry for it then.
            const std::int32_t ea = m.V[next(a)], eb = m.V[prev(a)];
            const bool realEdge =
                !(s.ghostMode && s.running && (s.ins.isVirtual(ea) || s.ins.isVirtual(eb)));
            if (realEdge)
                s.edge(ea, eb, s.use(Mark::TestEdge), w * 1.6f, false, SlideMarkRole::TestEdge);
            if (b == kNone || b >= m.numCorners()) break;
            const bool flip = op->sign > 0;
            const std::int32_t t = tri(b);
            if (s.ghostTri(t)) {
                DrawHalfPlane(s, t, s.use(flip ? Mark::HalfPlaneFlip : Mark::HalfPlaneKeep), w,
                              realEdge);
            } else {
                const ImU32 col = s.use(flip ? Mark::CircleFlip : Mark::CircleKeep);
                Vec2 c;
                double r;
                if (circumcircle(m, t, c, r) && s.circle(c, r, col, w)) {
                    const glm::dvec2 q = s.view.toScreen(c);
                    const double rs = r * s.view.scale;
                    recordMark(SlideMarkRole::TestCircle, t, -1, static_cast<float>(q.x - rs),
                               static_cast<float>(q.y - rs), static_cast<float>(q.x + rs),
                               static_cast<float>(q.y + rs));
                }
                s.dl->AddCircleFilled(s.screen(m.V[b]), 6, col);
            }
            break;
        }
        case OpType::Flip:
            if (op->a >= 0 && op->b >= 0 && op->a < m.numCorners() && op->b < m.numCorners()) {
                s.edge(m.V[op->a], m.V[op->b], s.use(Mark::FlippedEdge), w * 1.6f, false,
                       SlideMarkRole::FlippedEdge);
            }
            break;
        case OpType::Split:
        case OpType::SplitEdge: DrawSplitEdges(s, w); break;
        default: break;
    }
}

// ============================================================================================
// [SECTION] Labels, points, selection
// ============================================================================================

void DrawVoronoi(const Scene& s) {
    const Mesh& m = s.m;
    if (m.numTriangles() == 0) return;
    const Vec2 lo = s.view.toWorld({s.view.origin.x, s.view.origin.y + s.view.size.y});
    const Vec2 hi = s.view.toWorld({s.view.origin.x + s.view.size.x, s.view.origin.y});
    std::vector<Vec2> cc(static_cast<std::size_t>(m.numTriangles()));
    for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
        if (s.virtualTri(t)) continue;
        double r;
        circumcircle(m, t, cc[t], r);
    }
    const float w = s.st.presentation ? 2.5f : 1.5f;
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        const std::int32_t t = tri(c);
        if (s.virtualTri(t)) continue;
        const std::int32_t o = m.O[c];
        const bool ray = o == kNone || s.virtualTri(tri(o));
        if (!ray && o < c) continue;
        std::optional<std::pair<Vec2, Vec2>> seg;
        if (ray) {
            seg = clipToBox(cc[t], edgeNormal(m, c), HUGE_VAL, lo, hi);
        } else {
            const Vec2 d{cc[tri(o)].x - cc[t].x, cc[tri(o)].y - cc[t].y};
            seg = clipToBox(cc[t], d, 1.0, lo, hi);
        }
        if (!seg) continue;
        if (!s.room(8)) return;
        s.dl->AddLine(toIm(s.view.toScreen(seg->first)), toIm(s.view.toScreen(seg->second)),
                      s.use(Mark::Voronoi), w);
    }
    for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
        if (s.virtualTri(t)) continue;
        const ImVec2 q = toIm(s.view.toScreen(cc[t]));
        if (q.x < s.view.origin.x || q.y < s.view.origin.y ||
            q.x > s.view.origin.x + s.view.size.x || q.y > s.view.origin.y + s.view.size.y)
            continue;
        if (!s.room(32)) return;
        s.dl->AddCircleFilled(q, 2.5f, s.use(Mark::Voronoi));
    }
}

// Where corner c's label goes, from its anchor `a` in triangle p (a ghost's: its hull edge and
// the edge's midpoint), clear of the labels placed before it; registered.
ImVec2 placeCornerLabel(const Scene& s, std::int32_t c, bool ghost, ImVec2 a, const ImVec2 (&p)[3],
                        ImVec2 size) {
    if (c == s.st.selection.corner)  // room for the selection's disc (DrawSelection)
        size = ImVec2(std::max(size.x, 24.0f), std::max(size.y, 22.0f));
    if (!ghost) return placeAlong(s.labels, s.screen(s.m.V[c]), a, p, size);
    // Beside the hull edge: further along it while another label is there.
    const ImVec2 d((p[1].x - p[0].x) * 0.15f, (p[1].y - p[0].y) * 0.15f);
    const ImVec2 in((p[2].x - a.x) * 0.35f, (p[2].y - a.y) * 0.35f);
    return placeFirstFree(
        s.labels,
        {a, ImVec2(a.x + in.x, a.y + in.y), ImVec2(a.x + 2 * in.x, a.y + 2 * in.y),
         ImVec2(a.x + d.x, a.y + d.y), ImVec2(a.x - d.x, a.y - d.y)},
        size);
}

// The radius of the circle inscribed in a screen triangle (twice its area over its perimeter).
float inradius(const ImVec2 (&p)[3]) {
    const float area2 =
        std::abs((p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[1].y - p[0].y) * (p[2].x - p[0].x));
    float perimeter = 0;
    for (int k = 0; k < 3; ++k)
        perimeter += std::hypot(p[(k + 1) % 3].x - p[k].x, p[(k + 1) % 3].y - p[k].y);
    return perimeter > 0 ? area2 / perimeter : 0.0f;
}

// Triangle t's id inside it (screen corners p), unless it would cover another label.
void DrawTriangleId(const Scene& s, std::int32_t t, const ImVec2 (&p)[3], float fs) {
    if (!s.room(48 + s.pointReserve())) return;
    ImFont* mono = fonts().mono;
    char buf[32];
    std::snprintf(buf, sizeof buf, "t%d", t);
    const ImVec2 centre((p[0].x + p[1].x + p[2].x) / 3, (p[0].y + p[1].y + p[2].y) / 3);
    const ImVec2 at = placeInside(s.labels, p, centre, mono->CalcTextSizeA(fs, 1e9f, 0, buf));
    if (!s.labels.lastFree) {
        s.labels.dropLast();
        return;
    }
    LabelBox(s.dl, mono, fs, at, s.pal.triangleId, IM_COL32(255, 255, 255, 200), buf,
             SlideMarkRole::TriangleLabel, t);
}

void DrawLabels(const Scene& s, std::int32_t& hoveredCorner, ImVec2 mouse, bool mouseInCanvas) {
    const Mesh& m = s.m;
    const Overlays& ov = s.st.overlays;
    ImFont* mono = fonts().mono;
    const float fs = ImGui::GetFontSize() * (s.st.presentation ? 0.8f : 0.85f);
    // Cells the current op changed: their corners' labels are drawn in the highlight colour. An
    // op that fills the whole table (the flip algorithm's Start, Finalize) marks none: every
    // label would be a badge.
    std::vector<std::int32_t> changed;
    constexpr std::uint32_t kBadgesAtMost = 64;
    if (const Op* op = s.e.current(); op && s.e.journal() && op->numChanges <= 2 * kBadgesAtMost) {
        for (std::uint32_t i = 0; i < op->numChanges; ++i)
            changed.push_back(s.e.journal()->changes()[op->firstChange + i].corner());
    }
    const bool fewTriangles = m.numTriangles() <= 20000;
    float best = 14.0f * 14.0f;
    hoveredCorner = kNone;
    char buf[32];
    for (std::int32_t t = 0; fewTriangles && t < m.numTriangles(); ++t) {
        const bool ghost = s.ghostTri(t);
        if (!s.drawable(t) && !ghost) continue;
        ImVec2 p[3];
        if (ghost) {
            // Its corners' labels sit just outside the hull edge (Scene::ghostAnchor).
            std::int32_t u, w;
            int k;
            if (!s.hullEdge(t, u, w, k)) continue;
            p[0] = s.screen(u);
            p[1] = s.screen(w);
            p[2] = ImVec2((p[0].x + p[1].x) / 2, (p[0].y + p[1].y) / 2);
        } else {
            s.corners(t, p);
        }
        // Cull triangles off the canvas.
        const float minX = std::min({p[0].x, p[1].x, p[2].x}),
                    maxX = std::max({p[0].x, p[1].x, p[2].x});
        const float minY = std::min({p[0].y, p[1].y, p[2].y}),
                    maxY = std::max({p[0].y, p[1].y, p[2].y});
        if (maxX < s.view.origin.x || minX > s.view.origin.x + s.view.size.x ||
            maxY < s.view.origin.y || minY > s.view.origin.y + s.view.size.y) {
            continue;
        }
        if (ov.triangleIds && !ghost && maxX - minX > 40 && maxY - minY > 30)
            DrawTriangleId(s, t, p, fs);
        // A sliver (a long hull triangle at a far zoom) has no room for its corners' labels:
        // they would sit on its edges, over the neighbours' (legible only when zoomed in).
        const bool roomy = ghost || inradius(p) >= 0.5f * fs;
        for (int k = 0; k < 3; ++k) {
            const std::int32_t c = 3 * t + k;
            ImVec2 a;
            if (!s.anchor(c, a)) continue;
            if (mouseInCanvas) {
                const float dx = a.x - mouse.x, dy = a.y - mouse.y;
                if (dx * dx + dy * dy < best) {
                    best = dx * dx + dy * dy;
                    hoveredCorner = c;
                }
            }
            if (!ov.cornerIds || !roomy || !s.room(48 + s.pointReserve())) continue;
            const bool isChanged = std::find(changed.begin(), changed.end(), c) != changed.end();
            // A ghost triangle's corners in the ghost colour, beside its hull edge; the ghost
            // corner itself says so.
            const bool ghostCorner = ghost && s.ins.isVirtual(m.V[c]);
            std::snprintf(buf, sizeof buf, ghostCorner ? "%d g" : "%d", c);
            a = placeCornerLabel(s, c, ghost, a, p, mono->CalcTextSizeA(fs, 1e9f, 0, buf));
            // One that would cover another is left out; the selected corner's, never.
            if (!s.labels.lastFree && c != s.st.selection.corner) {
                s.labels.dropLast();
                continue;
            }
            const ImU32 text = isChanged ? IM_COL32(255, 255, 255, 255)
                               : ghost   ? s.pal.ghostId
                                         : s.pal.cornerId;
            LabelBox(s.dl, mono, fs, a, text, isChanged ? s.use(Mark::ChangedCorner) : 0, buf,
                     SlideMarkRole::CornerLabel, c);
            if (c == s.st.selection.corner) s.selectedLabelAt = a;
        }
    }
}

void DrawPoints(const Scene& s, std::int32_t draggedPoint, Vec2 dragTo) {
    const auto& states = s.e.pointStates();
    const auto& pts = s.e.shownPoints();
    // Many points: the GL renderer draws the inserted and queued ones; here only the point in
    // progress and (at most 2000) skipped duplicates, so the draw list stays small.
    const bool few = pts.size() <= kFewPoints;
    const bool ids = s.st.overlays.vertexIds && few;
    int skippedDrawn = 0;
    ImFont* mono = fonts().mono;
    const float fs = ImGui::GetFontSize() * 0.9f;
    const float r = s.st.presentation ? 5.5f : 4.0f;
    char buf[32];
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const Engine::PointState st = states[i];
        const Vec2 p = static_cast<std::int32_t>(i) == draggedPoint ? dragTo : pts[i];
        const ImVec2 q = toIm(s.view.toScreen(p));
        if (q.x < s.view.origin.x - 20 || q.x > s.view.origin.x + s.view.size.x + 20 ||
            q.y < s.view.origin.y - 20 || q.y > s.view.origin.y + s.view.size.y + 20) {
            continue;
        }
        if (!few && (st == Engine::PointState::Inserted || st == Engine::PointState::Pending))
            continue;
        if (!few && st == Engine::PointState::Skipped && ++skippedDrawn > kSkippedDrawn) continue;
        // The point in progress always; the others while the draw list has room.
        if (st != Engine::PointState::Current && !s.room(kVerticesPerPoint)) continue;
        ImU32 idCol = s.pal.vertexId;
        recordMark(SlideMarkRole::Vertex, static_cast<std::int32_t>(i), -1, q.x - r, q.y - r,
                   q.x + r, q.y + r);
        switch (st) {
            case Engine::PointState::Inserted: s.dl->AddCircleFilled(q, r, s.pal.vertex); break;
            case Engine::PointState::Pending:
                if (!s.st.overlays.pendingPoints) continue;
                idCol = s.use(Mark::QueuedPoint);
                s.dl->AddCircle(q, r + 1, idCol, 0, 1.5f);
                break;
            case Engine::PointState::Current:
                idCol = s.use(Mark::NextPoint);
                DrawNextPoint(s.dl, q, r, idCol);
                break;
            case Engine::PointState::Removed:
                idCol = s.use(Mark::RemovedPoint);
                s.dl->AddCircle(q, r + 1, idCol, 0, 1.5f);
                break;
            case Engine::PointState::Skipped:
                idCol = s.use(Mark::SkippedPoint);
                s.dl->AddLine(ImVec2(q.x - r, q.y - r), ImVec2(q.x + r, q.y + r), idCol, 2);
                s.dl->AddLine(ImVec2(q.x - r, q.y + r), ImVec2(q.x + r, q.y - r), idCol, 2);
                break;
        }
        if (ids) {
            std::snprintf(buf, sizeof buf, "%zu", i);
            const bool placed = i < s.vertexLabelAt.size() &&
                                static_cast<std::int32_t>(i) != draggedPoint &&
                                !std::isnan(s.vertexLabelAt[i].x);
            // A dragged point's label follows it; another is hidden where it would cover one.
            if (placed || static_cast<std::int32_t>(i) == draggedPoint) {
                const ImVec2 at = placed ? s.vertexLabelAt[i] : ImVec2(q.x + r + 2, q.y - r - fs);
                s.dl->AddText(mono, fs, at, idCol, buf);
                if (recordingMarks()) {
                    const ImVec2 ts = mono->CalcTextSizeA(fs, 1e9f, 0, buf);
                    recordMark(SlideMarkRole::VertexLabel, static_cast<std::int32_t>(i), -1, at.x,
                               at.y, at.x + ts.x, at.y + ts.y);
                }
            }
        }
    }
}

void DrawSelection(const Scene& s) {
    const Selection& sel = s.st.selection;
    const float w = s.st.presentation ? 3.5f : 2.5f;
    ImVec2 a;
    if (sel.corner != kNone && sel.corner < s.m.numCorners()) {
        const ImU32 selected = s.use(Mark::SelectedCorner);
        s.outlineTriangle(tri(sel.corner), selected, w);
        // The split's new edges stay visible on the outline: green inside the selection's colour.
        DrawSplitEdges(s, w * 0.45f);
        std::int32_t u, v;
        int k;
        if (s.hullEdge(tri(sel.corner), u, v, k)) s.edge(u, v, selected, w, true);
        if (s.anchor(sel.corner, a)) {
            if (s.selectedLabelAt) a = *s.selectedLabelAt;  // on its label, wherever that went
            s.dl->AddCircleFilled(a, 11, selected);
            char buf[16];
            std::snprintf(buf, sizeof buf, "%d", sel.corner);
            LabelBox(s.dl, fonts().mono, ImGui::GetFontSize() * 0.85f, a,
                     IM_COL32(255, 255, 255, 255), 0, buf, SlideMarkRole::CornerLabel, sel.corner);
        }
    }
    for (std::int32_t c : {sel.hoveredRow, sel.hoveredCorner}) {
        if (c != kNone && s.anchor(c, a))
            s.dl->AddCircle(a, 13, s.use(Mark::HoveredCorner), 0, 2.5f);
    }
    const CornerMove* mv = s.st.currentMove();
    ImVec2 from, to;
    if (mv && s.anchor(mv->from, from) && s.anchor(mv->to, to)) {
        Arrow(s.dl, from, to, s.use(Mark::CornerMove), w);
        char buf[8];
        std::snprintf(buf, sizeof buf, "%c", mv->op);
        LabelBox(s.dl, fonts().ui, ImGui::GetFontSize(),
                 ImVec2((from.x + to.x) / 2, (from.y + to.y) / 2 - 12),
                 IM_COL32(255, 255, 255, 255), lookOf(Mark::CornerMove).colour, buf);
    }
}

void DrawGrid(const Scene& s, double step) {
    const double px = step * s.view.scale;
    if (!(px >= 6)) return;
    const Vec2 lo = s.view.toWorld({s.view.origin.x, s.view.origin.y + s.view.size.y});
    const Vec2 hi = s.view.toWorld({s.view.origin.x + s.view.size.x, s.view.origin.y});
    // Lines counted, not stepped: far from the origin x + step can round back to x.
    const double x0 = std::floor(lo.x / step) * step, y0 = std::floor(lo.y / step) * step;
    const int nx = static_cast<int>(std::min(4096.0, (hi.x - x0) / step)),
              ny = static_cast<int>(std::min(4096.0, (hi.y - y0) / step));
    for (int i = 0; i <= nx; ++i) {
        const float sx = static_cast<float>(s.view.toScreen({x0 + i * step, 0}).x);
        s.dl->AddLine(ImVec2(sx, s.view.origin.y), ImVec2(sx, s.view.origin.y + s.view.size.y),
                      s.pal.grid);
    }
    for (int i = 0; i <= ny; ++i) {
        const float sy = static_cast<float>(s.view.toScreen({0, y0 + i * step}).y);
        s.dl->AddLine(ImVec2(s.view.origin.x, sy), ImVec2(s.view.origin.x + s.view.size.x, sy),
                      s.pal.grid);
    }
}

// The scene of the engine's current mesh in the app's view, drawn into dl.
Scene makeScene(AppState& st, ImDrawList* dl) {
    const Engine& e = st.engine;
    return Scene{st,
                 e,
                 e.mesh(),
                 e.inserter(),
                 st.view,
                 dl,
                 palette(st.presentation),
                 e.showsVirtual(),
                 e.options().boundary == Boundary::Exact};
}

// ============================================================================================
// [SECTION] Input
// ============================================================================================

// A clicked world position, rounded to the grid (snap) or to a precision that reads well at
// this zoom (integers at the default zoom of the paper's box).
Vec2 roundedClick(const AppState& st, Vec2 p) {
    double step =
        st.snapToGrid ? st.gridStep : std::pow(10.0, std::floor(std::log10(2.0 / st.view.scale)));
    if (!(step > 0) || !std::isfinite(step)) return p;
    return {std::round(p.x / step) * step, std::round(p.y / step) * step};
}

// The move tool's drag: the vertex follows the mouse (one move edit, remade while it goes on).
void dragVertex(AppState& st, CanvasCache& cache, ImVec2 mouse) {
    const Vec2 to = roundedClick(st, st.view.toWorld({mouse.x, mouse.y}));
    if (cache.dragMoved && to == cache.dragTo) return;
    std::string message;
    if (st.engine.dragVertex(cache.dragPoint, to, cache.dragMoved, message)) {
        cache.dragMoved = true;
        cache.dragTo = to;
    } else {
        std::string line =
            "move vertex " + std::to_string(cache.dragPoint) + " refused: " + message;
        if (st.messages.empty() || st.messages.back().text != line)  // once while it stays so
            st.log(Message::Level::Warning, std::move(line));
    }
}

std::int32_t pendingPointAt(const AppState& st, ImVec2 mouse) {
    return pointAt(st, mouse, Engine::PointState::Pending, 10.0f);
}

// A left press on the canvas: what a drag from it will do (move a queued point, drag a vertex
// with the move tool, pan), or a corner selected.
void pressOnCanvas(AppState& st, CanvasCache& cache, ImVec2 mouse) {
    cache.pressPos = mouse;
    cache.moved = false;
    cache.pressedOnCorner = st.selection.hoveredCorner != kNone;
    cache.dragPoint = pendingPointAt(st, mouse);
    cache.drag = cache.dragPoint != kNone ? CanvasCache::Drag::Pending : CanvasCache::Drag::Pan;
    if (st.tool == AppState::CanvasTool::MoveVertex && cache.dragPoint == kNone) {
        // The move tool drags the vertex pressed on (a click without a drag picks it instead).
        const std::int32_t v = pointAt(st, mouse, Engine::PointState::Inserted, 12.0f);
        if (v != kNone) {
            cache.drag = CanvasCache::Drag::Vertex;
            cache.dragPoint = v;
            cache.dragMoved = false;
        }
    }
    // An edit tool takes the click for a vertex, not the corner beside it.
    if (cache.pressedOnCorner && cache.dragPoint == kNone &&
        st.tool == AppState::CanvasTool::AddPoints) {
        st.select(st.selection.hoveredCorner);
        st.selection.jumpToCorner = st.selection.corner;
        cache.drag = CanvasCache::Drag::None;
    }
}

void handleInput(AppState& st, CanvasCache& cache, bool hovered) {
    ImGuiIO& io = ImGui::GetIO();
    View& view = st.view;
    const ImVec2 mouse = io.MousePos;
    if (hovered && io.MouseWheel != 0.0f)
        view.zoomAt({mouse.x, mouse.y}, std::pow(1.2, io.MouseWheel));
    // Middle drag pans from anywhere on the canvas.
    if (hovered && ImGui::IsMouseDragging(ImGuiMouseButton_Middle, 0.0f)) {
        view.center.x -= io.MouseDelta.x / view.scale;
        view.center.y += io.MouseDelta.y / view.scale;
    }
    if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) pressOnCanvas(st, cache, mouse);
    if (cache.drag != CanvasCache::Drag::None && ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
        const float dx = mouse.x - cache.pressPos.x, dy = mouse.y - cache.pressPos.y;
        if (dx * dx + dy * dy > 16) cache.moved = true;
        if (cache.moved && cache.drag == CanvasCache::Drag::Pan) {
            view.center.x -= io.MouseDelta.x / view.scale;
            view.center.y += io.MouseDelta.y / view.scale;
        }
        if (cache.moved && cache.drag == CanvasCache::Drag::Vertex) dragVertex(st, cache, mouse);
    }
    if (cache.drag != CanvasCache::Drag::None && ImGui::IsMouseReleased(ImGuiMouseButton_Left)) {
        const Vec2 world = roundedClick(st, view.toWorld({mouse.x, mouse.y}));
        std::vector<Vec2> pts = st.engine.points();
        if (cache.drag == CanvasCache::Drag::Vertex && cache.moved) {
            dragVertex(st, cache, mouse);
            if (cache.dragMoved) {
                st.select(kNone);  // the corners name other triangles now
                st.toolFirstVertex = kNone;
                st.log(Message::Level::Info,
                       describe(st.engine.editor()->edits().back()) +
                           ": Left steps back through its operations, Ctrl+Z undoes it");
            }
        } else if (cache.drag == CanvasCache::Drag::Pending && cache.moved) {
            pts[cache.dragPoint] = world;  // a queued point moved
            st.editPoints(std::move(pts));
        } else if (!cache.moved) {
            if (cache.drag == CanvasCache::Drag::Pending) {
                st.log(Message::Level::Info,
                       "point " + std::to_string(cache.dragPoint) +
                           " is queued: drag it to move it, right-click to remove it");
            } else if (EditClick(st, mouse, world)) {
                // an edit tool's click: a vertex removed or a segment's end picked
            } else if (!st.engine.batch()) {
                pts.push_back(world);  // a click on empty canvas queues a new point
                if (st.editPoints(std::move(pts))) {
                    char buf[96];
                    std::snprintf(buf, sizeof buf, "added point %zu at (%g, %g)",
                                  st.engine.points().size() - 1, world.x, world.y);
                    st.log(Message::Level::Info, buf);
                }
            }
        }
        cache.drag = CanvasCache::Drag::None;
        cache.dragPoint = kNone;
    }
    if (hovered && ImGui::IsMouseReleased(ImGuiMouseButton_Right)) {
        const std::int32_t i = pendingPointAt(st, mouse);
        if (i != kNone) {
            std::vector<Vec2> pts = st.engine.points();
            pts.erase(pts.begin() + i);
            if (st.editPoints(std::move(pts)))
                st.log(Message::Level::Info, "removed queued point " + std::to_string(i));
        }
    }
}

}  // namespace

bool canvasHasRoom(AppState& st, const ImDrawList* dl, unsigned vertices) {
    // Room is kept for the notice, the timeline below the canvas and the selection on top.
    constexpr unsigned kBudget = 56000;
    if (dl->_VtxCurrentIdx + vertices <= kBudget) return true;
    st.frameStats.canvasFull = true;
    return false;
}

ImU32 useLook(AppState& st, Mark mark) {
    if (st.canvas) st.canvas->drawn.set(static_cast<std::size_t>(mark));
    return lookOf(mark).colour;
}

void ShowCanvasLegend(AppState& st) {
    if (!st.canvas || !(st.overlays.legend || slideMode(st))) {
        st.itemRects.erase("canvas-legend");
        return;
    }
    const ImVec2 p0 = toIm(st.view.origin), p1 = toIm(st.view.origin + st.view.size);
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->PushClipRect(p0, p1, true);
    const ImVec4 box = DrawCanvasLegend(dl, p0, p1, st.canvas->drawn,
                                        ImGui::GetFontSize() * (slideMode(st) ? 0.8f : 0.9f),
                                        st.canvas->busy, st.engine.points().size() <= kFewPoints);
    dl->PopClipRect();
    if (box.z > box.x) {
        st.itemRects["canvas-legend"] = {box.x, box.y, box.z, box.w};
        recordMark(SlideMarkRole::Legend, -1, -1, box.x, box.y, box.z, box.w);
    } else
        st.itemRects.erase("canvas-legend");
}

void ShowCanvasNotice(AppState& st) {
    if (!st.frameStats.canvasFull) return;
    const char* text =
        "Too many shapes to draw at this zoom: some labels, circles or points are left out. Zoom "
        "in.";
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 p(static_cast<float>(st.view.origin.x) + 8,
                   static_cast<float>(st.view.origin.y) + 8);
    const ImVec2 ts = ImGui::CalcTextSize(text);
    dl->AddRectFilled(ImVec2(p.x - 4, p.y - 2), ImVec2(p.x + ts.x + 4, p.y + ts.y + 2),
                      IM_COL32(255, 244, 214, 235), 3);
    dl->AddText(p, IM_COL32(120, 70, 0, 255), text);
}

bool cornerAnchor(const AppState& st, std::int32_t c, float& x, float& y) {
    // A read-only scene (no draw list: room() is never asked).
    const Scene scene = makeScene(const_cast<AppState&>(st), nullptr);
    ImVec2 a;
    if (!scene.anchor(c, a)) return false;
    x = a.x;
    y = a.y;
    return true;
}

// ============================================================================================
// [SECTION] ShowCanvas
// ============================================================================================

namespace {

// The canvas takes the space above the timeline; a new size refits a view the user had not
// moved, and a pending fit (new points, F, a lesson stop's box) is made here.
void PlaceView(AppState& st, CanvasCache& cache, ImVec2 p0, ImVec2 size) {
    View& view = st.view;
    const bool resized = view.size.x != size.x || view.size.y != size.y;
    view.origin = {p0.x, p0.y};
    view.size = {size.x, size.y};
    // A new canvas size (the window or a splitter) refits a view the user had not moved.
    if (resized && cache.fitted && view.center == cache.fitCenter && view.scale == cache.fitScale)
        st.fitPending = true;
    if (st.fitPending) {
        const Bounds b = Bounds::of(st.engine.points());
        if (st.engine.points().empty())
            view.fit({0, 0}, {1600, 1600});
        else
            view.fit(b.lo, b.hi);
        st.fitPending = false;
        cache.fitted = true;
        cache.fitCenter = view.center;
        cache.fitScale = view.scale;
    }
    if (auto& box = st.lessonPlayer.pendingView) {  // a lesson stop's view
        view.fit({(*box)[0], (*box)[1]}, {(*box)[2], (*box)[3]});
        box.reset();
    }
}

MeshStyle canvasMeshStyle(const AppState& st, const Palette& pal) {
    MeshStyle ms;
    ms.fill = st.overlays.fill ? pal.fill : 0;
    ms.drawFill = st.overlays.fill;
    ms.edge = pal.edge;
    ms.virtualEdge = pal.virtualEdge;
    ms.point = pal.vertex;
    ms.pending = lookOf(Mark::QueuedPoint).colour;
    ms.background = pal.background;
    ms.edgeWidth = st.presentation ? 2.0f : 1.0f;
    ms.pointSize = st.engine.points().size() <= 5000 ? 4.0f : 2.0f;
    ms.drawPoints = st.engine.points().size() > kFewPoints;
    ms.drawVirtual = st.overlays.virtualTriangles;
    return ms;
}

// The renderer's mesh, brought up to date. At full speed on a mesh whose rebuild is costly, the
// mesh is rebuilt every other frame (it shows one frame late): the frame stays interactive on
// software GL. A moved view always rebuilds.
CanvasMesh& updateCanvasMesh(AppState& st, CanvasCache& cache, const MeshStyle& ms) {
    const View& view = st.view;
    const bool sameView =
        view.center == cache.builtView.center && view.scale == cache.builtView.scale &&
        view.origin == cache.builtView.origin && view.size == cache.builtView.size;
    if (!cache.renderer || cache.madeBy != st.renderer) {
        cache.renderer =
            st.renderer ? st.renderer->makeCanvasMesh() : makeNullRenderer()->makeCanvasMesh();
        cache.madeBy = st.renderer;
    }
    CanvasMesh& mesh = *cache.renderer;
    const bool defer = st.run.running && st.run.fullSpeed() && cache.rebuiltLastFrame && sameView &&
                       mesh.lastBuildMs() > 5.0;
    const bool rebuilt = !defer && mesh.update(st.engine, view, ms);
    cache.rebuiltLastFrame = rebuilt;
    if (rebuilt) cache.builtView = view;
    st.frameStats.meshBuildMs = rebuilt ? mesh.lastBuildMs() : 0.0;
    st.frameStats.visibleEdges = mesh.visibleEdges();
    st.frameStats.denseMesh = mesh.dense();
    return mesh;
}

// The ID buffer's pixels on the canvas (the idbuffer-grid overlay): each pixel's border and its
// centre, the point whose triangle the pixel holds, and the pixel under the point being inserted
// outlined. The ids stay in the ID-buffer panel: which triangle holds a centre is for the reader.
void DrawIdBufferGrid(const Scene& s, IdBufferCopy& copy) {
    IdBufferFrame f;
    if (!readIdBuffer(s.e, f, copy) || f.width < 2 || f.height < 2) return;
    const Vec2 c0 = f.centre(0, 0), c1 = f.centre(1, 1);
    const double dx = c1.x - c0.x, dy = c1.y - c0.y;
    // Only while a pixel is large enough on screen to tell its centre from its border.
    if (!(dx > 0) || !(dy > 0) || std::min(dx, dy) * s.view.scale < 12) return;
    if (!s.room(static_cast<unsigned>(4 * (f.width + f.height + 2) + 40 * f.width * f.height)))
        return;
    const double x0 = c0.x - dx / 2, y0 = c0.y - dy / 2;
    const auto at = [&](double x, double y) { return toIm(s.view.toScreen(Vec2{x, y})); };
    const ImU32 col = s.use(Mark::IdPixel);
    const ImU32 faint = (col & 0x00FFFFFFu) | (150u << 24);
    for (int i = 0; i <= f.width; ++i)
        s.dl->AddLine(at(x0 + i * dx, y0), at(x0 + i * dx, y0 + f.height * dy), faint, 1.5f);
    for (int j = 0; j <= f.height; ++j)
        s.dl->AddLine(at(x0, y0 + j * dy), at(x0 + f.width * dx, y0 + j * dy), faint, 1.5f);
    const float r = s.st.presentation ? 4.0f : 3.0f;
    for (int j = 0; j < f.height; ++j)
        for (int i = 0; i < f.width; ++i)
            s.dl->AddCircleFilled(toIm(s.view.toScreen(f.centre(i, j))), r, col);
    const std::int32_t v = s.e.currentVertex();
    if (v < 0 || v >= s.m.numVertices()) return;
    const Vec2 q = s.m.G[v];
    const long i = std::lround((q.x - c0.x) / dx), j = std::lround((q.y - c0.y) / dy);
    if (i < 0 || j < 0 || i >= f.width || j >= f.height) return;
    const ImVec2 a = at(x0 + i * dx, y0 + (j + 1) * dy), b = at(x0 + (i + 1) * dx, y0 + j * dy);
    s.dl->AddRect(a, b, s.use(Mark::IdPixelNow), 0, 0, s.st.presentation ? 4.0f : 3.0f);
}

void DrawCircumcircles(const Scene& scene) {
    for (std::int32_t t = 0; t < scene.m.numTriangles(); ++t) {
        Vec2 c;
        double r;
        if (scene.virtualTri(t) || !circumcircle(scene.m, t, c, r)) continue;
        if (!scene.room(800)) break;
        scene.circle(c, r, scene.use(Mark::Circumcircle), 1.0f);
    }
}

// The mesh: our renderer (any size), with ImDrawList layers between and on top: the background,
// the grid, the fill, the current op's fills, the edges and points, then circles, Voronoi, ghosts
// and the op's lines. A dense mesh is one opaque image with the background in it: the grid and
// the op's fills go over it.
void DrawMeshLayers(AppState& st, CanvasCache& cache, const Scene& scene, ImVec2 p0, ImVec2 p1) {
    const MeshStyle ms = canvasMeshStyle(st, scene.pal);
    CanvasMesh& mesh = updateCanvasMesh(st, cache, ms);
    if (mesh.dense()) {
        mesh.enqueue(scene.dl, CanvasMesh::Pass::Lines, p0.x, p0.y, p1.x, p1.y);
        if (st.snapToGrid) DrawGrid(scene, st.gridStep);
        DrawOpUnderlay(scene);
    } else {
        scene.dl->AddRectFilled(p0, p1, scene.pal.background);
        if (st.snapToGrid) DrawGrid(scene, st.gridStep);
        if (ms.drawFill) mesh.enqueue(scene.dl, CanvasMesh::Pass::Fill, p0.x, p0.y, p1.x, p1.y);
        DrawOpUnderlay(scene);
        mesh.enqueue(scene.dl, CanvasMesh::Pass::Lines, p0.x, p0.y, p1.x, p1.y);
    }
    if (st.overlays.circumcircles) DrawCircumcircles(scene);
    if (st.overlays.voronoi) DrawVoronoi(scene);
    if (st.overlays.idBufferGrid) DrawIdBufferGrid(scene, cache.idCopy);
    if (DrawGhostTriangles(st, scene.dl)) scene.use(Mark::GhostBand);
    DrawCheckOverlay(st, scene.dl);
    DrawEditOverlay(st, scene.dl);
    DrawOpOverlay(scene);
}

// What the legend should not cover: the points on the canvas (the one being inserted most of
// all) and the vertex labels, then the other labels and, with few points, the mesh's edges.
std::vector<BusyPoint> busy(const Scene& s) {
    std::vector<BusyPoint> out;
    const auto& pts = s.e.shownPoints();
    const std::size_t step = std::max<std::size_t>(1, pts.size() / 20000);
    const float r = s.st.presentation ? 5.5f : 4.0f;
    for (std::size_t i = 0; i < pts.size(); i += step) {
        const ImVec2 q = toIm(s.view.toScreen(pts[i]));
        if (s.onCanvas(q.x, q.y, q.x, q.y, 0))
            out.push_back({ImVec2(q.x - r, q.y - r), kBusyVertex, ImVec2(q.x + r, q.y + r)});
    }
    for (std::size_t k = 0; k < s.labels.boxes.size(); ++k) {
        const auto& b = s.labels.boxes[k];
        const bool vertex = k >= s.vertexLabelsFrom && k < s.vertexLabelsTo;
        out.push_back({ImVec2(b[0], b[1]), vertex ? kBusyVertex : kBusyLabel, ImVec2(b[2], b[3])});
    }
    if (const std::int32_t v = s.e.currentVertex();
        v >= 0 && v < static_cast<std::int32_t>(pts.size()))
        out.push_back({toIm(s.view.toScreen(pts[v])), 10 * kBusyVertex});
    const auto opEdge = [&](std::int32_t a, std::int32_t b) {
        if (a >= 0 && b >= 0 && a < s.m.numVertices() && b < s.m.numVertices() &&
            !s.ins.isVirtual(a) && !s.ins.isVirtual(b))
            out.push_back({s.screen(a), kBusyOpEdge, s.screen(b), true});
    };
    if (const Op* op = s.e.current();
        op && op->type == OpType::InCircleTest && op->a >= 0 && op->a < s.m.numCorners())
        opEdge(s.m.V[next(op->a)], s.m.V[prev(op->a)]);
    for (const Engine::QueuedTest& q : s.e.pendingTests()) opEdge(q.edge.a, q.edge.b);
    if (pts.size() > kFewPoints) return out;
    for (std::int32_t c = 0; c < s.m.numCorners(); ++c) {
        const std::int32_t t = c / 3, o = s.m.O[c];
        if (!s.drawable(t) || s.virtualTri(t)) continue;
        const std::int32_t a = s.m.V[next(c)], b = s.m.V[prev(c)];
        if (o >= 0 && s.drawable(o / 3) && !s.virtualTri(o / 3) && a > b) continue;  // once
        out.push_back({s.screen(a), kBusyEdge, s.screen(b), true});
    }
    return out;
}

// Labels, points (a dragged queued point where the mouse is) and the selection; returns the
// corner under the mouse.
std::int32_t DrawLabelsAndPoints(AppState& st, const CanvasCache& cache, Scene& scene,
                                 bool hovered) {
    const Engine& e = st.engine;
    std::int32_t hoveredCorner = kNone;
    scene.vertexLabelsFrom = scene.labels.boxes.size();
    if (st.overlays.vertexIds && e.points().size() <= kFewPoints)
        scene.vertexLabelAt =
            placeVertexLabels(scene.labels, st.view, e.shownPoints(), fonts().mono,
                              ImGui::GetFontSize() * 0.9f, st.presentation ? 5.5f : 4.0f);
    scene.vertexLabelsTo = scene.labels.boxes.size();
    LabelSuperVertices(st, scene.dl, scene.labels);
    DrawLabels(scene, hoveredCorner, ImGui::GetIO().MousePos, hovered);
    st.selection.hoveredCorner = hoveredCorner;
    const Vec2 dragTo =
        roundedClick(st, st.view.toWorld({ImGui::GetIO().MousePos.x, ImGui::GetIO().MousePos.y}));
    DrawPoints(scene,
               cache.drag == CanvasCache::Drag::Pending && cache.moved ? cache.dragPoint : kNone,
               dragTo);
    DrawSelection(scene);
    return hoveredCorner;
}

}  // namespace

void ShowCanvas(AppState& st) {
    if (!st.canvas) st.canvas = std::make_shared<CanvasCache>();
    CanvasCache& cache = *st.canvas;
    const float timelineH = ImGui::GetFrameHeightWithSpacing();
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    ImVec2 size = ImGui::GetContentRegionAvail();
    size.y = std::max(50.0f, size.y - timelineH);
    size.x = std::max(50.0f, size.x);
    PlaceView(st, cache, p0, size);
    ImGui::InvisibleButton("##canvas", size,
                           ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight |
                               ImGuiButtonFlags_MouseButtonMiddle);
    const bool hovered = ImGui::IsItemHovered();
    RecordItem(st, "canvas");
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 p1(p0.x + size.x, p0.y + size.y);
    dl->PushClipRect(p0, p1, true);
    recordMark(SlideMarkRole::Canvas, -1, -1, p0.x, p0.y, p1.x, p1.y);

    st.frameStats.canvasFull = false;
    Scene scene = makeScene(st, dl);
    cache.drawn.reset();  // this frame's marks: the scene's, and those drawn through useLook
    DrawMeshLayers(st, cache, scene, p0, p1);
    const std::int32_t hoveredCorner = DrawLabelsAndPoints(st, cache, scene, hovered);
    cache.drawn |= scene.drawn;
    cache.busy = busy(scene);
    dl->PopClipRect();
    handleInput(st, cache, hovered);
    if (hovered && hoveredCorner != kNone && cache.drag == CanvasCache::Drag::None) {
        ImGui::SetTooltip("corner %d (click to select)", hoveredCorner);
    }
}

}  // namespace dlab::ui
