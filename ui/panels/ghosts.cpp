// Virtual triangles on the canvas ("virtual-triangles" overlay). Exact mode: each ghost triangle
// stands for the open half-plane beyond one hull edge, drawn as a grey band along that edge on
// the outside, so that lessons can show what "the walk ends in a ghost triangle" means. Super
// mode: the super-triangle's vertices are labelled.
#include "ui/panels/panels.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace dlab::ui {

namespace {

// Super mode: the super-triangle's vertices are named like the tables name them ("4 (s0)").
void LabelSuperVertices(AppState& st, ImDrawList* dl) {
    const Engine& e = st.engine;
    const Inserter& ins = e.inserter();
    const Mesh& m = e.mesh();
    for (std::int32_t v = ins.firstVirtual(); v < m.numVertices(); ++v) {
        const glm::dvec2 q = st.view.toScreen(m.G[v]);
        const std::string label =
            std::to_string(v) + " (s" + std::to_string(v - ins.firstVirtual()) + ")";
        const ImVec2 size = ImGui::CalcTextSize(label.c_str());
        // Inside the canvas, beside the vertex.
        const float x =
            std::clamp(static_cast<float>(q.x) + 6, static_cast<float>(st.view.origin.x),
                       static_cast<float>(st.view.origin.x + st.view.size.x) - size.x);
        const float y =
            std::clamp(static_cast<float>(q.y) - size.y - 4, static_cast<float>(st.view.origin.y),
                       static_cast<float>(st.view.origin.y + st.view.size.y) - size.y);
        dl->AddText(ImVec2(x, y), IM_COL32(110, 115, 130, 255), label.c_str());
    }
}

}  // namespace

void DrawGhostTriangles(AppState& st, ImDrawList* dl) {
    const Engine& e = st.engine;
    if (e.batch() || !st.overlays.virtualTriangles) return;
    const Inserter& ins = e.inserter();
    if (ins.done()) return;
    if (e.options().boundary == Boundary::Super) {
        if (st.overlays.vertexIds) LabelSuperVertices(st, dl);
        return;
    }
    const Mesh& m = e.mesh();
    constexpr std::int32_t kMostBands = 2000;
    const float band = ImGui::GetFontSize() * 2.2f;
    int drawn = 0;
    for (std::int32_t t = 0; t < m.numTriangles() && drawn < kMostBands; ++t) {
        if (!ins.isVirtualTriangle(t)) continue;
        // (x, y, g) with g the ghost: the half-plane left of x -> y (y up), outside the hull.
        int k = 0;
        while (k < 3 && !ins.isVirtual(m.V[3 * t + k])) ++k;
        if (k == 3) continue;
        const Vec2 x = m.G[m.V[3 * t + (k + 1) % 3]], y = m.G[m.V[3 * t + (k + 2) % 3]];
        const glm::dvec2 a = st.view.toScreen(x), b = st.view.toScreen(y);
        // On the screen y points down: the world's left of x -> y is the screen's right of a -> b.
        glm::dvec2 n{-(b.y - a.y), b.x - a.x};
        const double len = std::hypot(n.x, n.y);
        if (!(len > 0)) continue;
        n *= -band / len;
        const ImVec2 p[4] = {ImVec2(float(a.x), float(a.y)), ImVec2(float(b.x), float(b.y)),
                             ImVec2(float(b.x + n.x), float(b.y + n.y)),
                             ImVec2(float(a.x + n.x), float(a.y + n.y))};
        dl->AddConvexPolyFilled(p, 4, IM_COL32(150, 155, 170, 45));
        dl->AddLine(p[2], p[3], IM_COL32(150, 155, 170, 160), 1.0f);
        if (st.overlays.triangleIds) {
            const std::string label = "ghost t" + std::to_string(t);
            const ImVec2 size = ImGui::CalcTextSize(label.c_str());
            // A third of the way along the band: its middle is the ghost corner's label's.
            const ImVec2 c(p[0].x + (p[1].x - p[0].x) * 0.3f + float(n.x) / 2 - size.x / 2,
                           p[0].y + (p[1].y - p[0].y) * 0.3f + float(n.y) / 2 - size.y / 2);
            dl->AddText(c, IM_COL32(90, 95, 110, 255), label.c_str());
        }
        ++drawn;
    }
}

}  // namespace dlab::ui
