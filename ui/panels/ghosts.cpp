// Virtual triangles on the canvas ("virtual-triangles" overlay). Exact mode: each ghost triangle
// stands for the open half-plane beyond one hull edge, drawn as a grey band along that edge on
// the outside, so that lessons can show what "the walk ends in a ghost triangle" means; the bands
// meet along the bisectors at the hull vertices (no gaps, no overlaps). Super mode: the
// super-triangle's vertices are labelled.
#include "ui/panels/canvas_looks.h"
#include "ui/panels/labels.h"
#include "ui/panels/panels.h"
#include "ui/render/drawn_marks.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace dlab::ui {

namespace {

// The hull edge u -> w of ghost triangle t (the world's left of it is outside) and the corners
// of t at u and at w; false when t is no ghost triangle.
bool ghostHullEdge(const Engine& ins, std::int32_t t, std::int32_t& cu, std::int32_t& cw) {
    const Mesh& m = ins.mesh();
    if (t < 0 || t >= m.numTriangles()) return false;
    int k = 0;
    while (k < 3 && !ins.isVirtual(m.V[3 * t + k])) ++k;
    if (k == 3) return false;
    cu = 3 * t + (k + 1) % 3;
    cw = 3 * t + (k + 2) % 3;
    return !ins.isVirtual(m.V[cu]) && !ins.isVirtual(m.V[cw]);
}

// The unit screen normal of ghost triangle t's hull edge, towards the outside; false when none.
bool outwardNormal(const AppState& st, std::int32_t t, glm::dvec2& n) {
    const Engine& ins = st.engine;
    std::int32_t cu, cw;
    if (!ghostHullEdge(ins, t, cu, cw)) return false;
    const Mesh& m = ins.mesh();
    const glm::dvec2 a = st.view.toScreen(m.G[m.V[cu]]), b = st.view.toScreen(m.G[m.V[cw]]);
    // On the screen y points down: the world's left of u -> w is the screen's right of a -> b.
    n = {b.y - a.y, -(b.x - a.x)};
    const double len = std::hypot(n.x, n.y);
    if (!(len > 0) || !std::isfinite(len)) return false;
    n /= len;
    return true;
}

// The side of a wedge at a hull vertex: along the bisector of the outward normals of its two
// hull edges (n, and that of the ghost triangle across corner c), scaled so that a band of
// depth 1 keeps depth 1 along its hull edge (at most 3, at a sharp hull vertex).
glm::dvec2 wedgeSide(const AppState& st, glm::dvec2 n, std::int32_t c) {
    const Mesh& m = st.engine.mesh();
    glm::dvec2 other;
    const std::int32_t o = m.O[c];
    if (o == kNone || !outwardNormal(st, tri(o), other)) return n;
    glm::dvec2 bis = n + other;
    const double len = std::hypot(bis.x, bis.y);
    if (!(len > 1e-9)) return n;
    bis /= len;
    const double cosine = bis.x * n.x + bis.y * n.y;
    return bis * std::min(3.0, 1.0 / std::max(cosine, 1e-3));
}

}  // namespace

bool ghostWedge(const AppState& st, std::int32_t t, ImVec2& a, ImVec2& b, ImVec2& da, ImVec2& db) {
    const Engine& e = st.engine;
    if (e.batch() || !e.showsVirtual() || e.options().boundary != Boundary::Exact) return false;
    std::int32_t cu, cw;
    glm::dvec2 n;
    if (!ghostHullEdge(e, t, cu, cw) || !outwardNormal(st, t, n)) return false;
    const Mesh& m = e.mesh();
    // The ghost triangle across the edge (w, ghost) is opposite u's corner, and conversely.
    const glm::dvec2 su = wedgeSide(st, n, cw), sw = wedgeSide(st, n, cu);
    a = toIm(st.view.toScreen(m.G[m.V[cu]]));
    b = toIm(st.view.toScreen(m.G[m.V[cw]]));
    da = toIm(su);
    db = toIm(sw);
    return true;
}

void LabelSuperVertices(AppState& st, ImDrawList* dl, LabelBoxes& labels) {
    const Engine& e = st.engine;
    const Inserter& ins = e.inserter();
    if (e.batch() || !st.overlays.virtualTriangles || !st.overlays.vertexIds || ins.done() ||
        e.options().boundary != Boundary::Super)
        return;
    const Mesh& m = e.mesh();
    const float left = static_cast<float>(st.view.origin.x),
                top = static_cast<float>(st.view.origin.y);
    const float right = left + static_cast<float>(st.view.size.x),
                bottom = top + static_cast<float>(st.view.size.y);
    for (std::int32_t v = ins.firstVirtual(); v < m.numVertices(); ++v) {
        const glm::dvec2 q = st.view.toScreen(m.G[v]);
        const std::string label =
            std::to_string(v) + " (s" + std::to_string(v - ins.firstVirtual()) + ")";
        const ImVec2 size = ImGui::CalcTextSize(label.c_str());
        // Beside the vertex, inside the canvas; else further along the canvas's edge, then below.
        const float x0 = static_cast<float>(q.x) + 6, y0 = static_cast<float>(q.y) - size.y - 4;
        ImVec2 at(std::clamp(x0, left, right - size.x), std::clamp(y0, top, bottom - size.y));
        for (int k = 0; k < 9; ++k) {
            const float dx = (k + 1) / 2 * (size.x + 10) * (k % 2 ? 1.0f : -1.0f);
            const float dy = k >= 7 ? (k == 7 ? 1.0f : -1.0f) * (size.y + 6) : 0.0f;
            const ImVec2 c(std::clamp(x0 + (k ? dx : 0), left, right - size.x),
                           std::clamp(y0 + dy, top, bottom - size.y));
            if (labels.isFree(c.x, c.y, c.x + size.x, c.y + size.y)) {
                at = c;
                break;
            }
        }
        labels.addBox(at.x, at.y, at.x + size.x, at.y + size.y);
        dl->AddText(at, IM_COL32(110, 115, 130, 255), label.c_str());
        recordMark(SlideMarkRole::VertexLabel, v, -1, at.x, at.y, at.x + size.x, at.y + size.y);
    }
}

bool DrawGhostTriangles(AppState& st, ImDrawList* dl) {
    const Engine& e = st.engine;
    if (e.batch() || !st.overlays.virtualTriangles) return false;
    if (!e.showsVirtual()) return false;
    if (e.options().boundary == Boundary::Super) {
        return false;
    }
    const Mesh& m = e.mesh();
    constexpr std::int32_t kMostBands = 2000;
    const float band = ImGui::GetFontSize() * 2.2f;
    const ImU32 fill = lookOf(Mark::GhostBand).colour;
    const ImU32 rim = (fill & 0x00FFFFFFu) | (160u << 24);
    // The ghost triangle the walk is in has its wedge in the walk's colour (canvas.cpp): no band
    // over it.
    std::int32_t target = kNone;
    if (const Op* op = e.current();
        st.overlays.walk && op && (op->type == OpType::LocateStep || op->type == OpType::Located)) {
        const std::vector<std::int32_t> path = e.walkPath();
        if (!path.empty()) target = path.back();
    }
    int drawn = 0;
    for (std::int32_t t = 0; t < m.numTriangles() && drawn < kMostBands; ++t) {
        ImVec2 a, b, da, db;
        if (t == target || !e.isVirtualTriangle(t) || !ghostWedge(st, t, a, b, da, db)) continue;
        const ImVec2 p[4] = {a, b, ImVec2(b.x + db.x * band, b.y + db.y * band),
                             ImVec2(a.x + da.x * band, a.y + da.y * band)};
        dl->AddConvexPolyFilled(p, 4, fill);
        dl->AddLine(p[2], p[3], rim, 1.0f);
        if (st.overlays.triangleIds) {
            const std::string label = "ghost t" + std::to_string(t);
            const ImVec2 size = ImGui::CalcTextSize(label.c_str());
            // A third of the way along the band: its middle is the ghost corner's label's.
            const ImVec2 q(a.x + (b.x - a.x) * 0.3f, a.y + (b.y - a.y) * 0.3f);
            const ImVec2 c(q.x + (da.x + db.x) * band / 4 - size.x / 2,
                           q.y + (da.y + db.y) * band / 4 - size.y / 2);
            dl->AddText(c, IM_COL32(90, 95, 110, 255), label.c_str());
        }
        ++drawn;
    }
    return drawn > 0;
}

}  // namespace dlab::ui
