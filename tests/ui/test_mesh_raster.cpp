// The dense canvas raster, patched as the run moves along its journal, equals a raster drawn
// whole at the same position, pixel for pixel (no GL needed: the raster is CPU memory).
#include "core/engine/generators.h"
#include "ui/engine.h"
#include "ui/gl/mesh_renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace {

using dlab::ui::Engine;
using dlab::ui::MeshRenderer;
using dlab::ui::MeshStyle;
using dlab::ui::View;

MeshStyle denseStyle() {
    MeshStyle s;
    s.fill = 0x11223344u;
    s.edge = 0xff000000u;
    s.virtualEdge = 0xff0000ffu;
    s.point = 0xff00ff00u;
    s.pending = 0xffff0000u;
    return s;
}

View canvasView(const Engine& e, double zoom) {
    View v;
    v.origin = {20, 30};
    v.size = {700, 500};
    dlab::Vec2 lo = e.points()[0], hi = lo;
    for (const dlab::Vec2& p : e.points()) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    v.fit(lo, hi);
    v.scale *= zoom;
    return v;
}

std::size_t differingPixels(const std::vector<std::uint32_t>& a,
                            const std::vector<std::uint32_t>& b) {
    if (a.size() != b.size()) return std::max(a.size(), b.size());
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.size(); ++i) n += a[i] != b[i];
    return n;
}

// Random steps forward and back (single ops, whole insertions, jumps), each checked against a
// renderer that draws the same position from scratch.
void checkPatchedRaster(dlab::Boundary boundary, double zoom, std::uint32_t seed, int minPatches) {
    Engine e;
    dlab::InsertOptions o;
    o.boundary = boundary;
    std::string error;
    ASSERT_TRUE(e.reset(dlab::generatePoints(dlab::Generator::Uniform, 45000, seed), o, error))
        << error;
    const View view = canvasView(e, zoom);
    const MeshStyle style = denseStyle();
    MeshRenderer patched;
    std::mt19937 rng(seed);
    int patches = 0;
    e.seek(300000);
    for (int i = 0; i < 60; ++i) {
        const std::size_t pos = e.position();
        switch (rng() % 6) {
            case 0: e.seek(pos + 1 + rng() % 3); break;
            case 1: e.seek(pos - std::min<std::size_t>(pos, 1 + rng() % 3)); break;
            case 2: e.forwardInsertion(); break;
            case 3: e.backInsertion(); break;
            case 4: e.seek(pos + rng() % 3000); break;
            default: e.seek(pos - std::min<std::size_t>(pos, rng() % 3000)); break;
        }
        if (i == 45) e.toEnd(100000000);  // the end: virtual triangles go
        if (i == 50) e.seek(e.recorded() / 2);
        patched.update(e, view, style);
        ASSERT_TRUE(patched.dense());
        patches += patched.lastPatched();
        MeshRenderer whole;
        whole.update(e, view, style);
        ASSERT_FALSE(whole.lastPatched());
        ASSERT_EQ(patched.visibleEdges(), whole.visibleEdges()) << "step " << i;
        ASSERT_EQ(differingPixels(patched.raster(), whole.raster()), 0u)
            << "step " << i << ", position " << e.position() << " of " << e.recorded();
    }
    EXPECT_GE(patches, minPatches);
}

}  // namespace

TEST(MeshRaster, PatchedAfterRandomStepsEqualsARasterDrawnWhole) {
    checkPatchedRaster(dlab::Boundary::Exact, 1.0, 3, 30);  // most updates patch
}

TEST(MeshRaster, PatchedEqualsWholeWhenZoomedInAndWithASuperTriangle) {
    checkPatchedRaster(dlab::Boundary::Super, 3.0, 4, 1);
}

TEST(MeshRaster, AStepPatchesAFewTilesOnly) {
    Engine e;
    std::string error;
    ASSERT_TRUE(e.reset(dlab::generatePoints(dlab::Generator::Uniform, 45000, 5), {}, error));
    const View view = canvasView(e, 1.0);
    MeshRenderer r;
    e.seek(400000);
    r.update(e, view, denseStyle());
    std::vector<std::uint32_t> before = r.raster();
    e.forwardInsertion();
    r.update(e, view, denseStyle());
    ASSERT_TRUE(r.lastPatched());
    const std::size_t changed = differingPixels(before, r.raster());
    EXPECT_GT(changed, 0u);  // the new vertex and its edges
    EXPECT_LT(changed, 2000u);
}
