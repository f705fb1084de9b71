// Ghost triangles on the canvas (exact mode, "virtual-triangles" overlay): each stands for the
// open half-plane beyond one hull edge, drawn as a grey band along that edge on the outside, so
// that lessons can show what "the walk ends in a ghost triangle" means.
#include "ui/panels/panels.h"

#include <imgui.h>

#include <cmath>
#include <string>

namespace dlab::ui {

void DrawGhostTriangles(AppState& st, ImDrawList* dl) {
    const Engine& e = st.engine;
    if (e.batch() || !st.overlays.virtualTriangles || e.options().boundary != Boundary::Exact)
        return;
    const Inserter& ins = e.inserter();
    if (ins.done()) return;
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
            const ImVec2 c((p[0].x + p[1].x + p[2].x + p[3].x) / 4 - size.x / 2,
                           (p[0].y + p[1].y + p[2].y + p[3].y) / 4 - size.y / 2);
            dl->AddText(c, IM_COL32(90, 95, 110, 255), label.c_str());
        }
        ++drawn;
    }
}

}  // namespace dlab::ui
