// Point location strategies. A locator only proposes a start triangle (a hint); the inserter
// walks from it with exact predicates, so a wrong or stale hint costs steps, never correctness.
#pragma once

#include "core/engine/enum_names.h"
#include "core/engine/geometry.h"
#include "core/engine/mesh.h"

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace dlab {

// IdBufferGl / IdBufferGlBatched live in ui/ (ui/gl/idbuffer_gl.h): they need a GL context, so
// makeLocator() refuses them and the caller (GUI, dtlab) builds them on its context.
enum class LocatorKind : std::uint8_t {
    Naive,
    Walk,
    Grid,
    IdBufferCpu,
    IdBufferGl,
    IdBufferGlBatched
};

// In the order menus and help list them. toString reads this table.
inline constexpr std::array<EnumName<LocatorKind>, 6> kLocatorNames{{
    {LocatorKind::Walk, "walk"},
    {LocatorKind::Naive, "naive"},
    {LocatorKind::Grid, "grid"},
    {LocatorKind::IdBufferCpu, "idbuffer-cpu"},
    {LocatorKind::IdBufferGl, "idbuffer-gl"},
    {LocatorKind::IdBufferGlBatched, "idbuffer-gl-batched"},
}};
const char* toString(LocatorKind kind);
std::optional<LocatorKind> parseLocatorKind(std::string_view name);

struct Bounds {
    Vec2 lo, hi;
    static Bounds of(const std::vector<Vec2>& points);
};

// What the locators can see of the inserter's mesh: triangles touching a vertex >= firstVirtual
// are ghost (exact mode) or super (paper mode) triangles.
struct LocatorContext {
    const Mesh* mesh = nullptr;
    std::int32_t firstVirtual = 0;
    bool ghost = true;               // exact mode: the virtual vertex has no coordinates
    std::size_t expectedPoints = 0;  // points the run will insert (to size spatial indexes)
    bool isVirtual(std::int32_t v) const { return v >= firstVirtual; }
    bool isVirtualTriangle(std::int32_t t) const {
        const auto& V = mesh->V;
        return isVirtual(V[3 * t]) || isVirtual(V[3 * t + 1]) || isVirtual(V[3 * t + 2]);
    }
};

struct LocatorStats {
    std::uint64_t queries = 0;
    std::uint64_t hits = 0;       // the hinted triangle contained the point (walk of length 0)
    std::uint64_t missSteps = 0;  // walk steps summed over the misses
    LocatorStats& operator+=(const LocatorStats& o) {
        queries += o.queries;
        hits += o.hits;
        missSteps += o.missSteps;
        return *this;
    }
};

class Locator {
public:
    virtual ~Locator() = default;
    virtual std::string name() const = 0;
    // Start of a run (the first triangle(s) exist); bounds cover every input point.
    virtual void reset(const LocatorContext& ctx, const Bounds& bounds) = 0;
    // Where to start walking towards p. lastTriangle is the triangle of the last insertion.
    virtual std::int32_t hint(Vec2 p, std::int32_t lastTriangle) = 0;
    // Whether trianglesChanged() must be called (spatial indexes that paint triangles).
    virtual bool wantsChanges() const { return false; }
    // These triangles' corners changed (a split, a flip, an undo): repaint them.
    virtual void trianglesChanged(const std::int32_t* /*tris*/, int /*count*/) {}
    // Rebuild the whole index from the current mesh (after a bulk seek that skipped
    // trianglesChanged calls). Only called after reset().
    virtual void resync() {}
    // A locate ended in triangle `found` after `steps` walk steps from the hint.
    virtual void located(Vec2 /*p*/, std::int32_t /*found*/, std::int32_t steps) {
        ++m_stats.queries;
        if (steps == 0)
            ++m_stats.hits;
        else
            m_stats.missSteps += steps;
    }
    const LocatorStats& stats() const { return m_stats; }

protected:
    LocatorStats m_stats;
};

struct LocatorOptions {
    int idBufferWidth = 1600;  // the paper's box
    int idBufferHeight = 1600;
    int idBufferBatch = 256;  // idbuffer-gl-batched: points whose pixels one readback fetches
};

bool needsGl(LocatorKind kind);

// Throws std::invalid_argument for the GL kinds (core has no GL context to draw on).
std::unique_ptr<Locator> makeLocator(LocatorKind kind, const LocatorOptions& options = {});

// World -> pixel coordinates of an ID buffer of cells.x by cells.y pixels over a box: pixel
// (i, j) covers [i, i+1) x [j, j+1) in pixel coordinates, row 0 at the lowest y. Half-differences
// keep the map finite for boxes near the double range; shared by the CPU and GL ID buffers so
// that both paint the same picture.
struct PixelMap {
    Vec2 lo{}, scale{0, 0};
    void init(const Bounds& bounds, double cellsX, double cellsY);
    double fx(double x) const { return (x / 2 - lo.x / 2) * scale.x; }
    double fy(double y) const { return (y / 2 - lo.y / 2) * scale.y; }
    // World position of the centre of pixel (i, j).
    Vec2 centre(int i, int j) const;
    // The pixel of p, clamped to [0, w) x [0, h); false when p lies left of or below the box.
    bool pixel(Vec2 p, int w, int h, int& i, int& j) const;
};

// The CPU colour-ID buffer: the paper's idea without GL, and the reference the GL version is
// tested against. Pixel (i, j) covers world [lo + i*dx, lo + (i+1)*dx) x [...]; a pixel holds
// the id of the triangle containing its centre, or kNone.
class IdBufferCpu final : public Locator {
public:
    IdBufferCpu(int width, int height);
    std::string name() const override { return "idbuffer-cpu"; }
    void reset(const LocatorContext& ctx, const Bounds& bounds) override;
    std::int32_t hint(Vec2 p, std::int32_t lastTriangle) override;
    bool wantsChanges() const override { return true; }
    void trianglesChanged(const std::int32_t* tris, int count) override;
    void resync() override;

    int width() const { return m_width; }
    int height() const { return m_height; }
    const std::vector<std::int32_t>& pixels() const { return m_pixels; }  // row 0 = lowest y
    std::int32_t pixelAt(Vec2 p) const;
    // World position of the centre of pixel (i, j).
    Vec2 pixelCentre(int i, int j) const;
    void paintTriangle(std::int32_t t);
    std::uint64_t pixelsPainted() const { return m_painted; }

private:
    int m_width, m_height;
    LocatorContext m_ctx;
    PixelMap m_map;
    std::vector<std::int32_t> m_pixels;
    std::uint64_t m_painted = 0;
    // The pixel rectangle each triangle was last painted in (empty when it holds none): a
    // triangle that changes shape, or turns into a ghost (an undo of a point outside the hull),
    // first takes its id off the pixels it no longer covers.
    struct PixelRect {
        int i0 = 0, i1 = -1, j0 = 0, j1 = -1;
    };
    std::vector<PixelRect> m_rects;
    void unpaintTriangle(std::int32_t t);
};

}  // namespace dlab
