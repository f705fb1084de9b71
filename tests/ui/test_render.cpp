// The one renderer in the running GUI (headless core profile): after stepping, the frame shows the
// engine's mesh and is, pixel for pixel, the frame of a GUI that went there directly; stepping
// back redraws the frame before. Whichever path drew the mesh (our vertex buffer, the dense
// raster), with the GL ID buffer's view on screen.
#include "core/engine/generators.h"
#include "core/engine/mesh.h"
#include "tests/ui/ui_harness.h"
#include "ui/gl/idbuffer_gl.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

using dlab::test::UiHarness;

namespace {

std::vector<std::uint8_t> frame(UiHarness& h) {
    h.frames(2);
    int w = 0, height = 0;
    return h.gui().lastFrame(w, height);
}

std::size_t differingPixels(const std::vector<std::uint8_t>& a,
                            const std::vector<std::uint8_t>& b) {
    if (a.size() != b.size()) return a.size() + b.size();
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.size(); i += 4)
        n += a[i] != b[i] || a[i + 1] != b[i + 1] || a[i + 2] != b[i + 2];
    return n;
}

// Edges of the current mesh on the canvas with no dark pixel around their midpoint: the mesh
// that the renderer shows is not the engine's.
int undrawnEdges(UiHarness& h) {
    const auto& st = h.state();
    const dlab::Mesh& m = st.engine.mesh();
    const auto canvas = h.rect("canvas");
    int missing = 0;
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        const std::int32_t a = m.V[dlab::next(c)], b = m.V[dlab::prev(c)];
        if (st.engine.inserter().isVirtual(a) || st.engine.inserter().isVirtual(b)) continue;
        const auto pa = st.view.toScreen(m.G[a]), pb = st.view.toScreen(m.G[b]);
        const int x = static_cast<int>(std::lround((pa.x + pb.x) / 2)),
                  y = static_cast<int>(std::lround((pa.y + pb.y) / 2));
        if (x < canvas[0] + 2 || y < canvas[1] + 2 || x > canvas[2] - 2 || y > canvas[3] - 2)
            continue;
        bool dark = false;
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                const auto p = h.pixel(x + dx, y + dy);
                dark |= p[0] + p[1] + p[2] < 3 * 200;
            }
        }
        missing += !dark;
    }
    return missing;
}

}  // namespace

// One harness at one step, as a user would open it: the points, the GL locator with its view.
struct Opened {
    explicit Opened(std::size_t points) {
        auto& st = h.state();
        if (points != 12) {
            EXPECT_TRUE(st.loadPoints(dlab::generatePoints(dlab::Generator::Uniform, points, 5),
                                      "uniform"));
        }
        dlab::InsertOptions o = st.engine.options();
        o.locator = dlab::LocatorKind::IdBufferGl;
        o.locatorOptions.idBufferWidth = o.locatorOptions.idBufferHeight = 400;
        EXPECT_TRUE(st.setOptions(o));
        st.pendingTab = "idbuffer";
    }
    UiHarness h;
};

TEST(Render, SteppingForwardAndBackRedrawsTheSamePixelsAsGoingThereDirectly) {
    struct Case {
        std::size_t points;
        bool dense;  // over MeshRenderer::kDenseEdges visible edges: the CPU raster
    };
    for (const Case c : {Case{12, false}, Case{3000, false}, Case{16000, true}}) {
        std::size_t at = 0, ahead = 0;
        std::vector<std::uint8_t> before, stepped, back;
        {
            Opened o(c.points);
            auto& e = o.h.state().engine;
            at = e.recorded() * 2 / 3;
            ahead = std::min(e.recorded(), at + 400);
            e.seek(at);
            before = frame(o.h);
            EXPECT_EQ(o.h.state().frameStats.denseMesh, c.dense) << c.points << " points";
            e.seek(ahead);
            stepped = frame(o.h);
            EXPECT_EQ(undrawnEdges(o.h), 0) << c.points << " points";
            e.seek(at);
            back = frame(o.h);
        }
        Opened direct(c.points);
        direct.h.state().engine.seek(ahead);
        const std::vector<std::uint8_t> there = frame(direct.h);
        EXPECT_GT(differingPixels(before, stepped), 50u) << c.points << " points: nothing moved";
        EXPECT_EQ(differingPixels(stepped, there), 0u) << c.points << " points, forward";
        EXPECT_EQ(differingPixels(before, back), 0u) << c.points << " points, back";
    }
}

// A dense canvas goes to one of two textures in turn (the one the last frame did not show):
// single steps forward and back with one frame each end on the frame of a GUI that went there
// directly.
TEST(Render, DenseCanvasSteppedOneFrameAStepShowsTheMeshOfItsPosition) {
    auto lastFrame = [](UiHarness& h) {
        h.frames(1);
        int w = 0, height = 0;
        return h.gui().lastFrame(w, height);
    };
    std::size_t at = 0;
    std::vector<std::uint8_t> stepped, first;
    {
        Opened o(16000);
        auto& e = o.h.state().engine;
        e.seek(e.recorded() * 2 / 3);
        first = frame(o.h);
        ASSERT_TRUE(o.h.state().frameStats.denseMesh);
        for (const int move : {+1, +1, +1, -1, +1, +1, +40, -1, +1, +1}) {
            e.seek(e.position() + move);
            stepped = lastFrame(o.h);
        }
        at = e.position();
    }
    Opened direct(16000);
    direct.h.state().engine.seek(at);
    const std::vector<std::uint8_t> there = frame(direct.h);  // laid out in its first frames
    EXPECT_GT(differingPixels(first, stepped), 20u) << "nothing moved";
    EXPECT_EQ(differingPixels(stepped, there), 0u);
}
