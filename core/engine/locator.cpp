// Locators: naive (fixed start), walk (last triangle), grid (bucket of recent triangles) and the
// CPU colour-ID buffer (a software rasterizer of triangle ids).
#include "core/engine/locator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace dlab {

const char* toString(LocatorKind kind) { return nameIn(kLocatorNames, kind).data(); }

std::optional<LocatorKind> parseLocatorKind(std::string_view name) {
    return parseIn(kLocatorNames, name);
}

bool needsGl(LocatorKind kind) {
    return kind == LocatorKind::IdBufferGl || kind == LocatorKind::IdBufferGlBatched;
}

Bounds Bounds::of(const std::vector<Vec2>& points) {
    Bounds b{{0, 0}, {0, 0}};
    if (points.empty()) return b;
    b.lo = b.hi = points[0];
    for (const Vec2& p : points) {
        b.lo.x = std::min(b.lo.x, p.x);
        b.lo.y = std::min(b.lo.y, p.y);
        b.hi.x = std::max(b.hi.x, p.x);
        b.hi.y = std::max(b.hi.y, p.y);
    }
    return b;
}

namespace {

// Cells per unit of half-coordinates: the maps take (x/2 - lo/2), at most halfWidth inside the
// box, to [0, cells]; so the scale is cells / halfWidth. (It was cells / (2 * halfWidth), which
// mapped the box onto the lower-left quarter of the cells: the ID buffers used a quarter of
// their pixels and the grid a quarter of its cells.) Kept finite: a subnormal extent (points
// near 1e-310) overflows the quotient to inf, and inf * 0 gives NaN cell coordinates, whose
// conversion to int is undefined (found by fuzz_engine). Capped, offsets within the box
// (<= halfWidth) still map below cells.
double cellScale(double cells, double halfWidth) {
    return halfWidth > 0 ? std::min(cells / halfWidth, std::numeric_limits<double>::max()) : 0.0;
}

}  // namespace

void PixelMap::init(const Bounds& b, double cellsX, double cellsY) {
    lo = b.lo;
    const double wx = b.hi.x / 2 - b.lo.x / 2, wy = b.hi.y / 2 - b.lo.y / 2;
    scale.x = cellScale(cellsX, wx);
    scale.y = cellScale(cellsY, wy);
}

Vec2 PixelMap::centre(int i, int j) const {
    // Inverse of fx = (x/2 - lo/2) * scale, kept in halves like the forward map.
    const double x = scale.x > 0 ? 2.0 * ((i + 0.5) / scale.x + lo.x / 2) : lo.x;
    const double y = scale.y > 0 ? 2.0 * ((j + 0.5) / scale.y + lo.y / 2) : lo.y;
    return {x, y};
}

bool PixelMap::pixel(Vec2 p, int w, int h, int& i, int& j) const {
    const double x = fx(p.x), y = fy(p.y);
    if (!(x >= 0 && y >= 0)) return false;
    i = x < w - 1 ? static_cast<int>(x) : w - 1;  // compared first: no out-of-range conversion
    j = y < h - 1 ? static_cast<int>(y) : h - 1;
    return true;
}

namespace {

// The paper's naive walk: always start from the same triangle.
class NaiveLocator final : public Locator {
public:
    std::string name() const override { return "naive"; }
    void reset(const LocatorContext&, const Bounds&) override {}
    std::int32_t hint(Vec2, std::int32_t) override { return 0; }
};

// Walk from the triangle of the previous insertion: short walks when consecutive points are
// close (BRIO/Hilbert order).
class WalkLocator final : public Locator {
public:
    std::string name() const override { return "walk"; }
    void reset(const LocatorContext&, const Bounds&) override {}
    std::int32_t hint(Vec2, std::int32_t last) override { return last < 0 ? 0 : last; }
};

// A uniform grid over the input's bounding box; each cell remembers the triangle where the
// last point in that cell was found. Empty cells fall back to the last triangle.
class GridLocator final : public Locator {
public:
    std::string name() const override { return "grid"; }
    void reset(const LocatorContext& ctx, const Bounds& bounds) override {
        m_bounds = bounds;
        sizeFor(ctx.expectedPoints);
    }
    void sizeFor(std::size_t points) {
        m_side =
            std::clamp(static_cast<int>(std::sqrt(static_cast<double>(points) / 2.0)), 1, 2048);
        m_cells.assign(static_cast<std::size_t>(m_side) * m_side, kNone);
        m_map.init(m_bounds, m_side, m_side);
    }
    std::int32_t hint(Vec2 p, std::int32_t last) override {
        const std::int32_t t = m_cells[index(p)];
        return t != kNone ? t : (last < 0 ? 0 : last);
    }
    void located(Vec2 p, std::int32_t found, std::int32_t steps) override {
        Locator::located(p, found, steps);
        m_cells[index(p)] = found;
    }

private:
    std::size_t index(Vec2 p) const {
        const int i = std::clamp(static_cast<int>(m_map.fx(p.x)), 0, m_side - 1);
        const int j = std::clamp(static_cast<int>(m_map.fy(p.y)), 0, m_side - 1);
        return static_cast<std::size_t>(j) * m_side + i;
    }
    Bounds m_bounds{};
    PixelMap m_map;
    int m_side = 0;
    std::vector<std::int32_t> m_cells;
};

}  // namespace

IdBufferCpu::IdBufferCpu(int width, int height)
    : m_width(std::max(1, width)), m_height(std::max(1, height)) {}

void IdBufferCpu::reset(const LocatorContext& ctx, const Bounds& bounds) {
    m_ctx = ctx;
    // One pixel column per 1/width of the box; half-differences avoid overflow at 1e308.
    m_map.init(bounds, m_width, m_height);
    m_pixels.assign(static_cast<std::size_t>(m_width) * m_height, kNone);
    m_rects.clear();
    m_painted = 0;
    for (std::int32_t t = 0; t < ctx.mesh->numTriangles(); ++t) paintTriangle(t);
}

Vec2 IdBufferCpu::pixelCentre(int i, int j) const { return m_map.centre(i, j); }

std::int32_t IdBufferCpu::pixelAt(Vec2 p) const {
    int i = 0, j = 0;
    if (!m_map.pixel(p, m_width, m_height, i, j)) return kNone;
    return m_pixels[static_cast<std::size_t>(j) * m_width + i];
}

std::int32_t IdBufferCpu::hint(Vec2 p, std::int32_t last) {
    const std::int32_t t = pixelAt(p);
    return t != kNone && t < m_ctx.mesh->numTriangles() ? t : (last < 0 ? 0 : last);
}

void IdBufferCpu::resync() {
    std::fill(m_pixels.begin(), m_pixels.end(), kNone);
    m_rects.clear();
    for (std::int32_t t = 0; t < m_ctx.mesh->numTriangles(); ++t) paintTriangle(t);
}

void IdBufferCpu::trianglesChanged(const std::int32_t* tris, int count) {
    for (int k = 0; k < count; ++k) paintTriangle(tris[k]);
}

void IdBufferCpu::unpaintTriangle(std::int32_t t) {
    if (static_cast<std::size_t>(t) >= m_rects.size()) return;
    PixelRect& r = m_rects[t];
    for (int j = r.j0; j <= r.j1; ++j) {
        std::int32_t* row = &m_pixels[static_cast<std::size_t>(j) * m_width];
        for (int i = r.i0; i <= r.i1; ++i) {
            if (row[i] == t) row[i] = kNone;
        }
    }
    r = {};
}

void IdBufferCpu::paintTriangle(std::int32_t t) {
    // Pixels of t's old shape that its new one leaves go to the triangles that changed with it
    // (they repaint too), or to the outside when the hull shrank: clear them first.
    unpaintTriangle(t);
    if (t >= m_ctx.mesh->numTriangles() || (m_ctx.ghost && m_ctx.isVirtualTriangle(t))) {
        return;  // ghost triangles (exact mode) stand for the outside of the hull: not painted
    }
    const Mesh& m = *m_ctx.mesh;
    // Triangle in pixel space (pixel (i, j) has its centre at (i + 0.5, j + 0.5)).
    double px[3], py[3];
    for (int k = 0; k < 3; ++k) {
        const Vec2 g = m.G[m.V[3 * t + k]];
        px[k] = m_map.fx(g.x);
        py[k] = m_map.fy(g.y);
    }
    const double minx = std::min({px[0], px[1], px[2]}), maxx = std::max({px[0], px[1], px[2]});
    const double miny = std::min({py[0], py[1], py[2]}), maxy = std::max({py[0], py[1], py[2]});
    const int i0 = std::max(0, static_cast<int>(std::ceil(std::max(minx - 0.5, -1.0))));
    const int i1 = std::min(m_width - 1, static_cast<int>(std::floor(std::min(maxx - 0.5, 1e9))));
    const int j0 = std::max(0, static_cast<int>(std::ceil(std::max(miny - 0.5, -1.0))));
    const int j1 = std::min(m_height - 1, static_cast<int>(std::floor(std::min(maxy - 0.5, 1e9))));
    if (i0 > i1 || j0 > j1) return;
    if (static_cast<std::size_t>(t) >= m_rects.size()) m_rects.resize(t + std::size_t{1});
    m_rects[t] = {i0, i1, j0, j1};
    // Edge functions, positive inside a counter-clockwise triangle; a pixel centre on an edge
    // goes to whichever triangle paints last (the walk fixes any such pick).
    // Each row only scans the span where all three edge functions can be non-negative (solved
    // per edge, widened by a pixel against rounding); the exact per-pixel test decides inside it.
    for (int j = j0; j <= j1; ++j) {
        const double y = j + 0.5;
        std::int32_t* row = &m_pixels[static_cast<std::size_t>(j) * m_width];
        double lo = i0, hi = i1;
        for (int k = 0; k < 3; ++k) {
            const int a = k, b = (k + 1) % 3;
            // e(x) = (px[b]-px[a])(y-py[a]) - (py[b]-py[a])(x-px[a]) = A x + B
            const double A = -(py[b] - py[a]);
            const double B = (px[b] - px[a]) * (y - py[a]) + (py[b] - py[a]) * px[a];
            if (A > 0)
                lo = std::max(lo, std::floor(-B / A - 0.5) - 1);
            else if (A < 0)
                hi = std::min(hi, std::ceil(-B / A - 0.5) + 1);
        }
        // A nearly flat edge puts its root far outside the box (or at +-inf): clamp before the
        // conversion to int, which is undefined out of range (found by fuzz_engine).
        const int ia = lo > i0 ? static_cast<int>(std::min(lo, i1 + 1.0)) : i0;
        const int ib = hi < i1 ? static_cast<int>(std::max(hi, i0 - 1.0)) : i1;
        for (int i = ia; i <= ib; ++i) {
            const double x = i + 0.5;
            bool inside = true;
            for (int k = 0; k < 3 && inside; ++k) {
                const int a = k, b = (k + 1) % 3;
                inside = (px[b] - px[a]) * (y - py[a]) - (py[b] - py[a]) * (x - px[a]) >= 0;
            }
            if (inside) {
                row[i] = t;
                ++m_painted;
            }
        }
    }
}

std::unique_ptr<Locator> makeLocator(LocatorKind kind, const LocatorOptions& options) {
    switch (kind) {
        case LocatorKind::Naive: return std::make_unique<NaiveLocator>();
        case LocatorKind::Walk: return std::make_unique<WalkLocator>();
        case LocatorKind::Grid: return std::make_unique<GridLocator>();
        case LocatorKind::IdBufferCpu:
            return std::make_unique<IdBufferCpu>(options.idBufferWidth, options.idBufferHeight);
        case LocatorKind::IdBufferGl:
        case LocatorKind::IdBufferGlBatched:
            throw std::invalid_argument(
                std::string("locator ") + toString(kind) +
                " needs a GL context: build it with ui/gl/idbuffer_gl.h on one "
                "(dtlab and the GUI do; core alone cannot)");
    }
    return nullptr;
}

}  // namespace dlab
