// Voronoi diagram: circumcenters checked against exact rational ones (at offsets and extreme
// scales), duality of buildVoronoi with the corner table, cells by swinging, Liang–Barsky clipping.
#include "core/engine/generators.h"
#include "core/engine/inserter.h"
#include "core/engine/io_write.h"
#include "core/engine/mesh_build.h"
#include "core/engine/voronoi.h"

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace dlab;

namespace {

constexpr double kEps = DBL_EPSILON;  // 2^-52

Mesh triangulate(const std::vector<Vec2>& pts) {
    Inserter ins(pts, InsertOptions{});
    ins.run();
    return ins.mesh();
}

// The exact circumcenter of a, b, c, as rationals.
struct ExactCenter {
    mpq_class x, y;
};
ExactCenter exactCircumcenter(Vec2 a, Vec2 b, Vec2 c) {
    const mpq_class ax(a.x), ay(a.y);
    const mpq_class bx = mpq_class(b.x) - ax, by = mpq_class(b.y) - ay;
    const mpq_class cx = mpq_class(c.x) - ax, cy = mpq_class(c.y) - ay;
    const mpq_class d = 2 * (bx * cy - by * cx);
    const mpq_class b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
    return {ax + (cy * b2 - by * c2) / d, ay + (bx * c2 - cx * b2) / d};
}

mpq_class dist2(const mpq_class& x, const mpq_class& y, Vec2 p) {
    const mpq_class dx = x - p.x, dy = y - p.y;
    return dx * dx + dy * dy;
}

// Edges of a triangulation: every corner faces one; interior edges are faced twice.
std::int32_t countEdges(const Mesh& m, std::int32_t* hull = nullptr) {
    std::int32_t h = 0;
    for (std::int32_t o : m.O) h += o == kNone;
    if (hull) *hull = h;
    return (m.numCorners() + h) / 2;
}

std::set<std::int32_t> hullVertices(const Mesh& m) {
    std::set<std::int32_t> s;
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        if (m.O[c] == kNone) {
            s.insert(m.V[next(c)]);
            s.insert(m.V[prev(c)]);
        }
    }
    return s;
}

}  // namespace

TEST(Circumcenter, ExactOnSimpleTriangles) {
    struct Case {
        Vec2 a, b, c, center;
    };
    const Case cases[] = {
        {{0, 0}, {2, 0}, {0, 2}, {1, 1}},
        {{0, 0}, {4, 0}, {0, 2}, {2, 1}},
        {{1, 1}, {3, 1}, {1, 5}, {2, 3}},
        {{-1, 0}, {1, 0}, {0, 1}, {0, 0}},
        {{0, 0}, {1, 0}, {0.5, 0.5}, {0.5, 0}},
        {{1e9, 1e9}, {1e9 + 2, 1e9}, {1e9, 1e9 + 2}, {1e9 + 1, 1e9 + 1}},
        {{0, 0}, {0x1p-1000, 0}, {0, 0x1p-1000}, {0x1p-1001, 0x1p-1001}},
        {{0, 0}, {0x1p1000, 0}, {0, 0x1p1000}, {0x1p999, 0x1p999}},
        // The differences overflow: the halving path.
        {{-1e308, 0}, {1e308, 0}, {0, 1e308}, {0, 0}},
        {{-DBL_MAX, -DBL_MAX}, {DBL_MAX, -DBL_MAX}, {-DBL_MAX, DBL_MAX}, {0, 0}},
        // Subnormal coordinates: scaling up is exact.
        {{0, 0}, {0x1p-1070, 0}, {0, 0x1p-1070}, {0x1p-1071, 0x1p-1071}},
    };
    for (const Case& k : cases) {
        // Every rotation and both orientations give the same exact answer.
        const Vec2 perms[6][3] = {{k.a, k.b, k.c}, {k.b, k.c, k.a}, {k.c, k.a, k.b},
                                  {k.a, k.c, k.b}, {k.c, k.b, k.a}, {k.b, k.a, k.c}};
        for (const auto& p : perms) {
            const Vec2 o = circumcenter(p[0], p[1], p[2]);
            EXPECT_EQ(o.x, k.center.x) << "triangle (" << p[0].x << "," << p[0].y << ") (" << p[1].x
                                       << "," << p[1].y << ") (" << p[2].x << "," << p[2].y << ")";
            EXPECT_EQ(o.y, k.center.y);
        }
    }
}

TEST(Circumcenter, DegenerateGivesNonFinite) {
    auto nonFinite = [](Vec2 p) { return !std::isfinite(p.x) || !std::isfinite(p.y); };
    EXPECT_TRUE(nonFinite(circumcenter({0, 0}, {1, 1}, {2, 2})));
    EXPECT_TRUE(nonFinite(circumcenter({0, 0}, {1, 1}, {1, 1})));
    EXPECT_TRUE(nonFinite(circumcenter({3, 4}, {3, 4}, {3, 4})));
    EXPECT_TRUE(nonFinite(circumcenter({0, 0}, {1, 0}, {std::nan(""), 1})));
    EXPECT_TRUE(nonFinite(circumcenter({0, 0}, {1, 0}, {INFINITY, 1})));
}

// Random well-shaped triangles at every scale and at a far offset: the computed center is the
// exact one up to a few 1e-15 of the circumradius (plus the final rounding of a + offset), and the
// three distances from it agree to the same relative accuracy.
TEST(Circumcenter, AccurateOnRandomTrianglesAtAnyScaleAndOffset) {
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const double scales[] = {1.0, 1e-200, 1e200, 1e-300, 1e298};
    const double offsets[] = {0.0, 1e9};
    int checked = 0;
    for (const double scale : scales) {
        for (const double offset : offsets) {
            for (int trial = 0; trial < 300; ++trial) {
                const Vec2 ua{u(rng), u(rng)}, ub{u(rng), u(rng)}, uc{u(rng), u(rng)};
                // Keep reasonably shaped triangles: twice the area against the longest side
                // squared.
                const double area2 =
                    std::fabs((ub.x - ua.x) * (uc.y - ua.y) - (ub.y - ua.y) * (uc.x - ua.x));
                const double l2 = std::max({std::hypot(ub.x - ua.x, ub.y - ua.y),
                                            std::hypot(uc.x - ua.x, uc.y - ua.y),
                                            std::hypot(uc.x - ub.x, uc.y - ub.y)});
                if (area2 < 0.1 * l2 * l2) continue;
                auto place = [&](Vec2 p) {
                    return Vec2{(offset + p.x) * scale, (offset + p.y) * scale};
                };
                const Vec2 a = place(ua), b = place(ub), c = place(uc);
                const Vec2 o = circumcenter(a, b, c);
                ASSERT_TRUE(std::isfinite(o.x) && std::isfinite(o.y));
                const ExactCenter e = exactCircumcenter(a, b, c);
                const double rx = mpq_class(e.x - a.x).get_d(), ry = mpq_class(e.y - a.y).get_d();
                const double r = std::hypot(rx, ry);
                const double ex = mpq_class(o.x - e.x).get_d(), ey = mpq_class(o.y - e.y).get_d();
                const double err = std::hypot(ex, ey);
                // The relative part, plus half an ulp per coordinate for adding a (and for a
                // subnormal result, the subnormal spacing).
                const double ulps = kEps * std::max(std::fabs(o.x), std::fabs(o.y)) +
                                    2 * std::numeric_limits<double>::denorm_min();
                EXPECT_LE(err, 4e-15 * r + ulps)
                    << "scale " << scale << " offset " << offset << " trial " << trial;
                // Equidistance, exactly evaluated.
                const mpq_class da = dist2(o.x, o.y, a), db = dist2(o.x, o.y, b),
                                dc = dist2(o.x, o.y, c);
                const mpq_class r2 = mpq_class(rx) * rx + mpq_class(ry) * ry;
                const double spread = mpq_class((abs(da - db) + abs(da - dc)) / r2).get_d();
                EXPECT_LE(spread, 8e-15 + 4 * ulps / r)
                    << "scale " << scale << " offset " << offset;
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 2000);
}

// |computed - exact| in units of the spacing of doubles at the exact value (the subnormal
// spacing near zero); infinity when the computed value is not finite.
static double ulpsOff(double computed, const mpq_class& exact) {
    if (!std::isfinite(computed)) return INFINITY;
    const double e = std::fabs(exact.get_d());
    const double spacing = std::isfinite(e) ? std::nextafter(e, INFINITY) - e : 0x1p971;
    return mpq_class(abs(mpq_class(computed) - exact) / mpq_class(spacing)).get_d();
}

static bool exactFits(const mpq_class& v) { return abs(v) <= mpq_class(DBL_MAX); }

// Triangles mixing 1e-300 and 1e300, DBL_MAX and subnormals: whenever the exact center is a
// finite double, the computed one is finite and within a few ulps of it, coordinate by
// coordinate (checked against exact rationals).
TEST(Circumcenter, WithinAFewUlpsForMixedMagnitudes) {
    struct Tri {
        Vec2 a, b, c;
    };
    std::vector<Tri> tris = {
        {{0, 0}, {1e-300, 0}, {0, 1e300}},
        {{0, 0}, {1e-160, 0}, {0, 1e160}},
        {{0, 0}, {DBL_MAX, 0}, {0, 1e-300}},
        {{1e-300, 1e-300}, {-DBL_MAX / 2, 0}, {0, DBL_MAX / 2}},
        {{1e300, 1}, {1e300, -1}, {1e300 - 1e285, 0}},
        {{0x1p-1074, 0}, {0, 0x1p-1074}, {1e10, 1e10}},
        {{1e10, 1e10}, {1e10 + 1e-5, 1e10}, {1e10, 1e10 + 3e-5}},
    };
    std::mt19937_64 rng(77);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::uniform_int_distribution<int> exponent(-1000, 1000);
    auto coordinate = [&] { return std::ldexp(unit(rng), exponent(rng)); };
    for (int k = 0; k < 3000; ++k)
        tris.push_back({{coordinate(), coordinate()},
                        {coordinate(), coordinate()},
                        {coordinate(), coordinate()}});
    int checked = 0;
    for (const Tri& t : tris) {
        const mpq_class bx = mpq_class(t.b.x) - t.a.x, by = mpq_class(t.b.y) - t.a.y;
        const mpq_class cx = mpq_class(t.c.x) - t.a.x, cy = mpq_class(t.c.y) - t.a.y;
        if (bx * cy == by * cx) continue;  // collinear: no center
        const ExactCenter e = exactCircumcenter(t.a, t.b, t.c);
        const Vec2 o = circumcenter(t.a, t.b, t.c);
        const std::string where = "(" + std::to_string(t.a.x) + "," + std::to_string(t.a.y) +
                                  ") (" + std::to_string(t.b.x) + "," + std::to_string(t.b.y) +
                                  ") (" + std::to_string(t.c.x) + "," + std::to_string(t.c.y) + ")";
        if (exactFits(e.x)) {
            EXPECT_LE(ulpsOff(o.x, e.x), 5.0) << where;
        }
        if (exactFits(e.y)) {
            EXPECT_LE(ulpsOff(o.y, e.y), 5.0) << where;
        }
        ++checked;
    }
    EXPECT_GT(checked, 2900);
    // The first case of all: the exact center is (5e-301, 5e299).
    const Vec2 o = circumcenter({0, 0}, {1e-300, 0}, {0, 1e300});
    EXPECT_LE(ulpsOff(o.x, mpq_class(1e-300) / 2), 1.0);
    EXPECT_LE(ulpsOff(o.y, mpq_class(1e300) / 2), 1.0);
}

TEST(Voronoi, EdgeNormalPointsOutOfItsTriangle) {
    Mesh m;
    m.G = {{0, 0}, {4, 0}, {0, 3}};
    m.V = {0, 1, 2};
    computeOpposites(m);
    // Corner 0 faces edge 1 -> 2: (4,0) -> (0,3), d = (-4, 3), normal (3, 4).
    EXPECT_EQ(edgeNormal(m, 0), (Vec2{3, 4}));
    EXPECT_EQ(edgeNormal(m, 1), (Vec2{-3, 0}));  // edge 2 -> 0: d = (0, -3)
    EXPECT_EQ(edgeNormal(m, 2), (Vec2{0, -4}));  // edge 0 -> 1: d = (4, 0)
}

TEST(Voronoi, ARayOfAHullEdgeLongerThanDblMaxHasAFiniteDirection) {
    // The edge (-1.5e308, 0) -> (1.5e308, 0) is 3e308 long: past DBL_MAX. Its ray points straight
    // down, written with finite numbers (a ray's direction has no length).
    Mesh m;
    m.G = {{-1.5e308, 0}, {1.5e308, 0}, {0, 1e308}};
    m.V = {0, 1, 2};
    computeOpposites(m);
    const Vec2 d = edgeNormal(m, 2);
    EXPECT_EQ(d, (Vec2{0, -0.75e308}));
    EXPECT_FALSE(std::signbit(d.x));
    const VoronoiDiagram diagram = buildVoronoi(m);
    std::ostringstream out;
    writeVoronoiEdge(out, diagram);
    EXPECT_EQ(out.str().find("inf"), std::string::npos) << out.str();
    EXPECT_EQ(out.str().find("nan"), std::string::npos) << out.str();
    EXPECT_EQ(out.str().find("-0 "), std::string::npos) << out.str();
    for (const VoronoiDiagram::Edge& e : diagram.edges) {
        if (!e.isRay()) continue;
        EXPECT_TRUE(std::isfinite(e.direction.x) && std::isfinite(e.direction.y));
        EXPECT_TRUE(e.direction.x != 0 || e.direction.y != 0);
    }
}

TEST(Voronoi, BuildIsTheDualOfTheMesh) {
    for (const std::uint64_t seed : {1u, 2u, 3u}) {
        const Mesh m = triangulate(generatePoints(Generator::Uniform, 600, seed));
        ASSERT_GT(m.numTriangles(), 0);
        const VoronoiDiagram d = buildVoronoi(m);
        ASSERT_EQ(d.vertices.size(), static_cast<std::size_t>(m.numTriangles()));
        std::int32_t hull = 0;
        ASSERT_EQ(d.edges.size(), static_cast<std::size_t>(countEdges(m, &hull)));
        for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
            const Vec2 o =
                circumcenter(m.point(corner(t, 0)), m.point(corner(t, 1)), m.point(corner(t, 2)));
            ASSERT_EQ(d.vertices[t], o);
        }
        std::int32_t rays = 0;
        std::size_t k = 0;
        forEachEdge(m, [&](std::int32_t c) {
            ASSERT_LT(k, d.edges.size());
            const VoronoiDiagram::Edge& e = d.edges[k++];
            EXPECT_EQ(e.corner, c);  // the order of forEachEdge
            EXPECT_EQ(e.a, tri(c));
            EXPECT_EQ(e.direction, edgeNormal(m, c));
            if (m.O[c] == kNone) {
                ++rays;
                EXPECT_TRUE(e.isRay());
                // Outward: away from the vertex at c, across the hull edge.
                const Vec2 p = m.point(c), q = m.point(next(c));
                EXPECT_GT(e.direction.x * (q.x - p.x) + e.direction.y * (q.y - p.y), 0.0);
                return;
            }
            EXPECT_EQ(e.b, tri(m.O[c]));
            ASSERT_FALSE(e.isRay());
            // The endpoints are the circumcenters of the two triangles sharing the edge, and
            // b - a runs along the normal (up to rounding when the two centers nearly coincide).
            const Vec2 va = d.vertices[e.a], vb = d.vertices[e.b];
            const double dot = (vb.x - va.x) * e.direction.x + (vb.y - va.y) * e.direction.y;
            const double scale =
                std::hypot(e.direction.x, e.direction.y) * (1.0 + std::hypot(va.x, va.y));
            EXPECT_GE(dot, -1e-12 * scale) << "edge of corner " << c;
        });
        EXPECT_EQ(rays, hull);
    }
}

TEST(Voronoi, CellsAreClosedInsideAndOpenOnTheHull) {
    const Mesh m = triangulate(generatePoints(Generator::Uniform, 400, 7));
    const std::set<std::int32_t> hull = hullVertices(m);
    std::vector<std::int32_t> valence(static_cast<std::size_t>(m.numVertices()), 0);
    for (std::int32_t v : m.V) ++valence[v];
    std::int32_t cells = 0;
    forEachVoronoiCell(m, [&](std::int32_t v, const VoronoiCell& cell) {
        ++cells;
        EXPECT_EQ(cell.closed, hull.count(v) == 0) << "vertex " << v;
        ASSERT_EQ(cell.triangles.size(), cell.corners.size());
        ASSERT_EQ(cell.corners.size(), static_cast<std::size_t>(valence[v]));
        for (std::size_t i = 0; i < cell.corners.size(); ++i) {
            EXPECT_EQ(m.V[cell.corners[i]], v);
            EXPECT_EQ(tri(cell.corners[i]), cell.triangles[i]);
            // Counter-clockwise: each entry is the swing of the one before.
            if (i + 1 < cell.corners.size()) {
                EXPECT_EQ(m.s(cell.corners[i]), cell.corners[i + 1]);
            }
        }
        if (cell.closed) {
            EXPECT_EQ(m.s(cell.corners.back()), cell.corners.front());
            // Starting anywhere gives the same cycle, rotated.
            const VoronoiCell again = voronoiCell(m, cell.corners[cell.corners.size() / 2]);
            EXPECT_TRUE(again.closed);
            EXPECT_TRUE(std::is_permutation(again.corners.begin(), again.corners.end(),
                                            cell.corners.begin()));
        } else {
            EXPECT_EQ(m.u(cell.corners.front()), kNone);
            EXPECT_EQ(m.s(cell.corners.back()), kNone);
            // The rays the header promises are the hull edges at v.
            EXPECT_EQ(m.O[prev(cell.corners.front())], kNone);
            EXPECT_EQ(m.O[next(cell.corners.back())], kNone);
            // Any corner of the fan finds the same cell.
            const VoronoiCell again = voronoiCell(m, cell.corners.back());
            EXPECT_FALSE(again.closed);
            EXPECT_EQ(again.corners, cell.corners);
        }
    });
    EXPECT_EQ(cells, m.numVertices());
}

TEST(Voronoi, InteriorCellOfASquareGridIsASquare) {
    std::vector<Vec2> pts;
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 5; ++x) pts.push_back({double(x), double(y)});
    const Mesh m = triangulate(pts);
    ASSERT_EQ(m.numTriangles(), 32);
    const VoronoiDiagram d = buildVoronoi(m);
    const std::vector<std::int32_t> start = vertexCorners(m);
    for (const auto& [gx, gy] : {std::pair{2, 2}, std::pair{1, 1}, std::pair{3, 2}}) {
        const std::int32_t v = gy * 5 + gx;
        ASSERT_NE(start[v], kNone);
        const VoronoiCell cell = voronoiCell(m, start[v]);
        ASSERT_TRUE(cell.closed);
        // Both triangles of a split square share its center: drop the repeats.
        std::vector<Vec2> ring;
        for (std::int32_t t : cell.triangles) {
            const Vec2 p = d.vertices[t];
            if (ring.empty() || !(ring.back() == p)) ring.push_back(p);
        }
        if (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
        ASSERT_EQ(ring.size(), 4u) << "vertex " << v;
        std::set<std::pair<double, double>> got, want;
        for (Vec2 p : ring) got.insert({p.x, p.y});
        for (double dx : {-0.5, 0.5})
            for (double dy : {-0.5, 0.5}) want.insert({gx + dx, gy + dy});
        EXPECT_EQ(got, want);
        // Counter-clockwise.
        double area2 = 0;
        for (std::size_t i = 0; i < ring.size(); ++i) {
            const Vec2 p = ring[i], q = ring[(i + 1) % ring.size()];
            area2 += p.x * q.y - q.x * p.y;
        }
        EXPECT_EQ(area2, 2.0);
    }
    // A corner vertex of the grid: an open cell.
    const VoronoiCell cornerCell = voronoiCell(m, start[0]);
    EXPECT_FALSE(cornerCell.closed);
}

TEST(Voronoi, CellRejectsBadInput) {
    const Mesh good = triangulate({{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.4}});
    EXPECT_THROW(voronoiCell(good, -1), std::invalid_argument);
    EXPECT_THROW(voronoiCell(good, good.numCorners()), std::invalid_argument);
    // Point an opposite at a corner of another vertex: the swing must stop with an exception.
    Mesh bad = good;
    const std::int32_t c = 0;
    const std::int32_t o = bad.O[next(c)] != kNone ? next(c) : prev(c);
    ASSERT_NE(bad.O[o], kNone);
    bad.O[o] = bad.O[o] % 3 == 0 ? bad.O[o] + 1 : bad.O[o] - 1;  // same triangle, wrong corner
    bool threw = false;
    for (std::int32_t k = 0; k < bad.numCorners(); ++k) {
        try {
            voronoiCell(bad, k);
        } catch (const std::invalid_argument&) {
            threw = true;
        }
    }
    EXPECT_TRUE(threw);
}

TEST(ClipToBox, Cases) {
    const Vec2 lo{0, 0}, hi{10, 10};
    const double inf = std::numeric_limits<double>::infinity();
    using Seg = std::pair<Vec2, Vec2>;
    auto clip = [&](Vec2 p, Vec2 d, double t) { return clipToBox(p, d, t, lo, hi); };

    // Inside: unchanged.
    EXPECT_EQ(clip({1, 1}, {2, 3}, 1.0), (Seg{{1, 1}, {3, 4}}));
    // Crossing the whole box.
    EXPECT_EQ(clip({-5, 5}, {20, 0}, 1.0), (Seg{{0, 5}, {10, 5}}));
    EXPECT_EQ(clip({-1, -1}, {12, 12}, 1.0), (Seg{{0, 0}, {10, 10}}));
    // Entering only: the far end is kept.
    EXPECT_EQ(clip({-2, 4}, {4, 2}, 1.0), (Seg{{0, 5}, {2, 6}}));
    // Touching a corner only: a single point (the box is closed).
    EXPECT_EQ(clip({-1, 9}, {2, 2}, 1.0), (Seg{{0, 10}, {0, 10}}));
    // Ending exactly on the boundary.
    EXPECT_EQ(clip({-4, 5}, {4, 0}, 1.0), (Seg{{0, 5}, {0, 5}}));
    // Parallel to an axis, outside: nothing; on the boundary: the boundary part.
    EXPECT_FALSE(clip({-1, -5}, {0, 20}, 1.0));
    EXPECT_FALSE(clip({-5, 11}, {20, 0}, 1.0));
    EXPECT_EQ(clip({0, -5}, {0, 20}, 1.0), (Seg{{0, 0}, {0, 10}}));
    // Outside, missing the box, or stopping short of it.
    EXPECT_FALSE(clip({11, 11}, {5, 1}, 1.0));
    EXPECT_FALSE(clip({-10, 5}, {5, 0}, 1.0));
    EXPECT_FALSE(clip({-3, 12}, {15, -1}, 1.0));
    // Rays.
    EXPECT_EQ(clip({5, 5}, {1, 0}, inf), (Seg{{5, 5}, {10, 5}}));
    EXPECT_EQ(clip({-10, 5}, {1, 0}, inf), (Seg{{0, 5}, {10, 5}}));
    EXPECT_EQ(clip({5, 5}, {-1, -1}, inf), (Seg{{5, 5}, {0, 0}}));
    EXPECT_FALSE(clip({-10, 5}, {-1, 0}, inf));
    EXPECT_FALSE(clip({-10, 5}, {1, 1}, inf));  // passes above the box
    // A zero direction is the point p.
    EXPECT_EQ(clip({3, 4}, {0, 0}, inf), (Seg{{3, 4}, {3, 4}}));
    EXPECT_FALSE(clip({30, 4}, {0, 0}, 1.0));
    // Non-finite input, an empty box.
    EXPECT_FALSE(clip({NAN, 1}, {1, 0}, 1.0));
    EXPECT_FALSE(clip({1, 1}, {INFINITY, 0}, 1.0));
    EXPECT_FALSE(clipToBox({1, 1}, {1, 0}, 1.0, {5, 5}, {4, 6}));
    // Results never leave the box, however the rounding falls.
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-20.0, 30.0);
    for (int i = 0; i < 2000; ++i) {
        const Vec2 p{u(rng), u(rng)}, d{u(rng) * 0.37, u(rng) * 0.29};
        for (double t : {1.0, inf}) {
            if (auto s = clip(p, d, t)) {
                for (Vec2 q : {s->first, s->second}) {
                    EXPECT_TRUE(q.x >= 0 && q.x <= 10 && q.y >= 0 && q.y <= 10);
                }
            }
        }
    }
}

TEST(ClipToBox, ClippedSegmentsOfADiagram) {
    const Mesh m = triangulate(generatePoints(Generator::Uniform, 300, 11));
    const VoronoiDiagram d = buildVoronoi(m);
    // A box holding every Voronoi vertex: finite edges come back exactly, rays reach the border.
    Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
    for (Vec2 p : d.vertices) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    lo = {lo.x - 1, lo.y - 1};
    hi = {hi.x + 1, hi.y + 1};
    const auto all = clippedSegments(d, lo, hi);
    ASSERT_EQ(all.size(), d.edges.size());
    for (std::size_t i = 0; i < all.size(); ++i) {
        const VoronoiDiagram::Edge& e = d.edges[i];
        EXPECT_EQ(all[i].first, d.vertices[e.a]);
        if (!e.isRay()) {
            EXPECT_EQ(all[i].second, d.vertices[e.b]);
        } else {
            const Vec2 q = all[i].second;
            EXPECT_TRUE(q.x == lo.x || q.x == hi.x || q.y == lo.y || q.y == hi.y);
        }
    }
    // A small box: fewer segments, all inside.
    const Vec2 slo{400, 400}, shi{900, 800};
    const auto some = clippedSegments(d, slo, shi);
    EXPECT_GT(some.size(), 0u);
    EXPECT_LT(some.size(), d.edges.size());
    for (const auto& [a, b] : some) {
        for (Vec2 q : {a, b})
            EXPECT_TRUE(q.x >= slo.x && q.x <= shi.x && q.y >= slo.y && q.y <= shi.y);
    }
    // Non-finite vertices are dropped, not drawn.
    VoronoiDiagram broken = d;
    broken.vertices[0] = {NAN, 0};
    std::size_t touching0 = 0;
    for (const auto& e : d.edges) touching0 += e.a == 0 || e.b == 0;
    EXPECT_EQ(clippedSegments(broken, lo, hi).size(), d.edges.size() - touching0);
}
