// Pixels of the GUI's frames: the table's highlighted cells, the canvas' edges, and every overlay
// within the draw list's budget.
#include "core/engine/generators.h"
#include "core/engine/mesh.h"
#include "tests/ui/ui_harness.h"
#include "ui/panels/panels.h"
#include "ui/platform/keys.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <cmath>

using dlab::kNone;
using dlab::OpType;
using dlab::test::UiHarness;
namespace key = dlab::ui::key;

TEST(Gui, ChangedCellsAreHighlightedWhereTheTableShowsThem) {
    UiHarness h;
    auto& st = h.state();
    constexpr std::array<int, 3> kChanged = {255, 200, 120};
    // Find a Split: the table follows the op and highlights the cells it changed.
    while (st.engine.forward() && st.engine.current()->type != OpType::Split) {}
    ASSERT_EQ(st.engine.current()->type, OpType::Split);
    h.frames(3);
    const auto table = h.rect("corner-table");
    const int highlighted = h.countColour(table, kChanged);
    EXPECT_GT(highlighted, 100) << "no highlighted cell in the corner table";
    // Elsewhere on the screen that colour does not occur.
    EXPECT_EQ(h.countColour(h.rect("canvas"), kChanged), 0);
    // Before anything happened, nothing is highlighted.
    st.engine.toStart();
    h.frames(3);
    EXPECT_EQ(h.countColour(h.rect("corner-table"), kChanged), 0);
}

TEST(Gui, TheCanvasDrawsTheMeshEdges) {
    UiHarness h;
    auto& st = h.state();
    st.engine.seek(60);
    h.frames(3);
    const dlab::Mesh& m = st.engine.mesh();
    int dark = 0, tested = 0;
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        const std::int32_t a = m.V[dlab::next(c)], b = m.V[dlab::prev(c)];
        if (st.engine.inserter().isVirtual(a) || st.engine.inserter().isVirtual(b)) continue;
        const auto pa = st.view.toScreen(m.G[a]), pb = st.view.toScreen(m.G[b]);
        // Sample a point a third along the edge (labels sit near the ends).
        const int x = static_cast<int>(std::lround(pa.x + (pb.x - pa.x) / 3)),
                  y = static_cast<int>(std::lround(pa.y + (pb.y - pa.y) / 3));
        bool found = false;
        for (int dy = -1; dy <= 1 && !found; ++dy) {
            for (int dx = -1; dx <= 1 && !found; ++dx) {
                const auto p = h.pixel(x + dx, y + dy);
                found = p[0] + p[1] + p[2] < 3 * 200;
            }
        }
        dark += found;
        ++tested;
    }
    ASSERT_GT(tested, 10);
    EXPECT_EQ(dark, tested);
}

// ImGui aborts on a draw list over 65536 vertices (16-bit indices): every overlay at
// once over a few thousand points must leave shapes out and say so, not crash; zoomed in,
// everything is drawn again and the notice goes.
TEST(Gui, EveryOverlayOnAThousandsOfPointsStaysWithinTheDrawListAndSaysWhatIsLeftOut) {
    for (const std::size_t n : {450u, 1500u, 4000u}) {
        UiHarness h;
        auto& st = h.state();
        ASSERT_TRUE(
            st.loadPoints(dlab::generatePoints(dlab::Generator::Uniform, n, 11), "uniform"));
        dlab::InsertOptions options = st.engine.options();
        options.order = dlab::OrderKind::Input;  // a long walk from the first triangle
        ASSERT_TRUE(st.setOptions(options));
        auto& o = st.overlays;
        o.fill = o.vertexIds = o.cornerIds = o.triangleIds = o.walk = o.flipQueue = o.flipped =
            o.circumcircles = o.voronoi = o.pendingPoints = o.virtualTriangles = true;
        // Halfway, in the middle of an insertion's flips.
        st.engine.toEnd(SIZE_MAX);
        st.engine.seek(st.engine.position() / 2);
        while (st.engine.current() && st.engine.current()->type != OpType::InCircleTest &&
               st.engine.forward()) {}
        h.frames(2);
        EXPECT_TRUE(st.frameStats.canvasFull) << n << " points";
        const std::array<float, 4> canvas = h.rect("canvas");
        EXPECT_GT(
            h.countColour({canvas[0], canvas[1], canvas[0] + 600, canvas[1] + 40}, {120, 70, 0}),
            20)
            << "no notice on the canvas";
        // Zoomed in on a few triangles, everything fits.
        for (int i = 0; i < 14; ++i)
            h.scroll((canvas[0] + canvas[2]) / 2, (canvas[1] + canvas[3]) / 2, 1);
        h.frames(2);
        EXPECT_FALSE(st.frameStats.canvasFull) << n << " points, zoomed in";
    }
}
