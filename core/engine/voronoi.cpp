// The Voronoi diagram as the dual of the triangulation: circumcenters, dual edges and rays,
// cells by swinging around a vertex, and Liang–Barsky clipping for drawing.
#include "core/engine/voronoi.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace dlab {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// a*b - c*d with one rounding error at most a few ulps (Kahan's algorithm with an explicit fma;
// -ffp-contract=off keeps the compiler from fusing anything else).
double diffOfProducts(double a, double b, double c, double d) {
    const double w = c * d;
    const double e = std::fma(-c, d, w);  // exact: w - c*d
    const double f = std::fma(a, b, -w);  // a*b - w, rounded once
    return f + e;
}

bool finite(Vec2 p) { return std::isfinite(p.x) && std::isfinite(p.y); }

}  // namespace

Vec2 circumcenter(Vec2 a, Vec2 b, Vec2 c) {
    if (!finite(a) || !finite(b) || !finite(c)) return {kNaN, kNaN};
    double bx = b.x - a.x, by = b.y - a.y, cx = c.x - a.x, cy = c.y - a.y;
    // The differences overflow only for coordinates near ±DBL_MAX; halving first is exact there
    // (only subnormal bits, far below the rounding of the result, can be lost) and the result
    // is doubled back at the end, by the same exact power-of-two scaling as below.
    int extra = 0;
    if (!std::isfinite(bx) || !std::isfinite(by) || !std::isfinite(cx) || !std::isfinite(cy)) {
        bx = b.x * 0.5 - a.x * 0.5;
        by = b.y * 0.5 - a.y * 0.5;
        cx = c.x * 0.5 - a.x * 0.5;
        cy = c.y * 0.5 - a.y * 0.5;
        extra = 1;
    }
    const double big =
        std::max(std::max(std::fabs(bx), std::fabs(by)), std::max(std::fabs(cx), std::fabs(cy)));
    if (big == 0.0) return {kNaN, kNaN};  // three coincident points
    // Scale so the largest difference lies in [1, 2): the squares below neither overflow nor
    // underflow, whatever the triangle's size. Powers of two scale exactly (up, always; down,
    // up to subnormal bits of components 2^-1000 times smaller than the largest one).
    const int e = std::ilogb(big);
    bx = std::ldexp(bx, -e);
    by = std::ldexp(by, -e);
    cx = std::ldexp(cx, -e);
    cy = std::ldexp(cy, -e);

    const double det = 2.0 * diffOfProducts(bx, cy, by, cx);
    const double b2 = bx * bx + by * by;
    const double c2 = cx * cx + cy * cy;
    const double ux = diffOfProducts(cy, b2, by, c2) / det;
    const double uy = diffOfProducts(bx, c2, cx, b2) / det;
    // det == 0 (collinear) gives ±inf or NaN, as documented.
    return {a.x + std::ldexp(ux, e + extra), a.y + std::ldexp(uy, e + extra)};
}

Vec2 edgeNormal(const Mesh& m, std::int32_t c) {
    const Vec2 p = m.G[m.V[next(c)]];
    const Vec2 q = m.G[m.V[prev(c)]];
    const double dx = q.x - p.x, dy = q.y - p.y;
    return {dy, -dx};
}

VoronoiDiagram buildVoronoi(const Mesh& m) {
    VoronoiDiagram d;
    const std::int32_t nt = m.numTriangles();
    d.vertices.resize(static_cast<std::size_t>(nt));
    for (std::int32_t t = 0; t < nt; ++t) {
        d.vertices[t] =
            circumcenter(m.point(corner(t, 0)), m.point(corner(t, 1)), m.point(corner(t, 2)));
    }
    // A triangulation has |corners|/2 edges plus half the hull edges: reserve the upper bound.
    d.edges.reserve(static_cast<std::size_t>(m.numCorners()));
    forEachEdge(m, [&](std::int32_t c) {
        VoronoiDiagram::Edge e;
        e.a = tri(c);
        e.b = m.O[c] == kNone ? kNone : tri(m.O[c]);
        e.direction = edgeNormal(m, c);
        e.corner = c;
        d.edges.push_back(e);
    });
    return d;
}

VoronoiCell voronoiCell(const Mesh& m, std::int32_t cornerAtVertex) {
    const std::int32_t nc = m.numCorners();
    if (m.O.size() != m.V.size()) {
        throw std::invalid_argument("voronoiCell: |O| = " + std::to_string(m.O.size()) +
                                    " differs from |V| = " + std::to_string(m.V.size()));
    }
    if (cornerAtVertex < 0 || cornerAtVertex >= nc) {
        throw std::invalid_argument("voronoiCell: corner " + std::to_string(cornerAtVertex) +
                                    " outside [0, " + std::to_string(nc) + ")");
    }
    const std::int32_t v = m.V[cornerAtVertex];
    // One step of a swing, checked: a corrupt O must end in an exception, never out of bounds.
    auto checked = [&](std::int32_t c, std::int32_t from) {
        if (c == kNone) return c;
        if (c < 0 || c >= nc || m.V[c] != v) {
            throw std::invalid_argument("voronoiCell: swinging around vertex " + std::to_string(v) +
                                        " from corner " + std::to_string(from) +
                                        " reached corner " + std::to_string(c) +
                                        ", not a corner of that vertex (inconsistent O)");
        }
        return c;
    };
    auto tooLong = [&] {
        throw std::invalid_argument("voronoiCell: the swing around vertex " + std::to_string(v) +
                                    " from corner " + std::to_string(cornerAtVertex) +
                                    " does not close within " + std::to_string(nc) +
                                    " steps (inconsistent O)");
    };

    VoronoiCell cell;
    // Unswing (clockwise) to the hull, or all the way around back to the start.
    std::int32_t first = cornerAtVertex;
    bool closed = false;
    for (std::int32_t steps = 0;; ++steps) {
        if (steps > nc) tooLong();
        const std::int32_t u =
            checked(m.O[prev(first)] == kNone ? kNone : prev(m.O[prev(first)]), first);
        if (u == kNone) break;
        if (u == cornerAtVertex) {
            closed = true;
            first = cornerAtVertex;
            break;
        }
        first = u;
    }
    // Swing (counter-clockwise) from there, collecting the fan.
    std::int32_t c = first;
    for (std::int32_t steps = 0;; ++steps) {
        if (steps > nc) tooLong();
        cell.corners.push_back(c);
        cell.triangles.push_back(tri(c));
        const std::int32_t s = checked(m.O[next(c)] == kNone ? kNone : next(m.O[next(c)]), c);
        if (s == kNone) {
            if (closed) tooLong();  // went around one way but not the other: O is not symmetric
            break;
        }
        if (s == first) {
            if (!closed) tooLong();
            break;
        }
        c = s;
    }
    cell.closed = closed;
    return cell;
}

std::optional<std::pair<Vec2, Vec2>> clipToBox(Vec2 p, Vec2 d, double tMax, Vec2 lo, Vec2 hi) {
    if (!finite(p) || !finite(d) || std::isnan(tMax) || tMax < 0.0 || !finite(lo) || !finite(hi))
        return std::nullopt;
    if (!(lo.x <= hi.x && lo.y <= hi.y)) return std::nullopt;
    double t0 = 0.0, t1 = tMax;
    // One slab per axis: p + t*d stays within [l, h] along that axis.
    auto slab = [&](double pc, double dc, double l, double h) {
        if (dc == 0.0) return l <= pc && pc <= h;
        double ta = (l - pc) / dc, tb = (h - pc) / dc;
        if (dc < 0.0) std::swap(ta, tb);
        // ta/tb may be ±inf after an overflow; the comparisons below still order them right.
        if (ta > t0) t0 = ta;
        if (tb < t1) t1 = tb;
        return t0 <= t1;
    };
    if (!slab(p.x, d.x, lo.x, hi.x) || !slab(p.y, d.y, lo.y, hi.y)) return std::nullopt;
    auto at = [&](double t) {
        // Components along which the line does not move stay exactly where they are (no 0 * inf).
        Vec2 q{d.x == 0.0 ? p.x : p.x + t * d.x, d.y == 0.0 ? p.y : p.y + t * d.y};
        if (t == 0.0) q = p;
        // Rounding may put a computed end a hair outside the closed box: clamp it back.
        q.x = std::clamp(q.x, lo.x, hi.x);
        q.y = std::clamp(q.y, lo.y, hi.y);
        return q;
    };
    if (d.x == 0.0 && d.y == 0.0) return std::make_pair(p, p);  // a point (t1 may be infinite)
    const Vec2 a = at(t0), b = at(t1);
    if (!finite(a) || !finite(b)) return std::nullopt;
    return std::make_pair(a, b);
}

std::vector<std::pair<Vec2, Vec2>> clippedSegments(const VoronoiDiagram& diagram, Vec2 lo,
                                                   Vec2 hi) {
    std::vector<std::pair<Vec2, Vec2>> out;
    const auto nv = static_cast<std::int64_t>(diagram.vertices.size());
    auto inside = [&](Vec2 q) { return lo.x <= q.x && q.x <= hi.x && lo.y <= q.y && q.y <= hi.y; };
    for (const VoronoiDiagram::Edge& e : diagram.edges) {
        if (e.a < 0 || e.a >= nv || (!e.isRay() && e.b >= nv)) continue;
        const Vec2 p = diagram.vertices[e.a];
        if (!finite(p)) continue;
        if (e.isRay()) {
            if (!finite(e.direction) || (e.direction.x == 0.0 && e.direction.y == 0.0)) continue;
            if (auto s =
                    clipToBox(p, e.direction, std::numeric_limits<double>::infinity(), lo, hi)) {
                if (inside(p)) s->first = p;
                out.push_back(*s);
            }
            continue;
        }
        const Vec2 q = diagram.vertices[e.b];
        if (!finite(q)) continue;
        const Vec2 d{q.x - p.x, q.y - p.y};
        if (!finite(d)) continue;
        if (auto s = clipToBox(p, d, 1.0, lo, hi)) {
            // Ends inside the box are kept exactly (p + 1*d need not round back to q).
            if (inside(p)) s->first = p;
            if (inside(q)) s->second = q;
            out.push_back(*s);
        }
    }
    return out;
}

}  // namespace dlab
