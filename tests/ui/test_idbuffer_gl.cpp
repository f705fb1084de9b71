// The GL colour-ID buffer (OSMesa, EGL): its pixels against the CPU reference away from edges,
// exact locates from its hints, whole triangulations in every readback mode, undo/redo through
// the Journal, the GL state it must leave alone, the GUI path and `dtlab table1`'s files.
#include "core/engine/generators.h"
#include "core/engine/inserter.h"
#include "core/engine/predicates.h"
#include "tests/ui/ui_harness.h"
#include "ui/gl/gl_api.h"
#include "ui/gl/idbuffer_gl.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace dlab;
using ui::GlReadback;
using ui::IdBufferGl;
using ui::IdBufferGlOptions;

namespace {

class IdBufferGlTest : public ::testing::Test {
protected:
    void SetUp() override {
        std::string error;
        ASSERT_TRUE(m_headless.open(error)) << error;
        m_gl = m_headless.gl;
        glGetIntegerv(GL_SUBPIXEL_BITS, &m_subpixelBits);
    }

    struct Run {
        std::unique_ptr<Inserter> ins;
        IdBufferGl* gl = nullptr;
    };
    Run makeRun(std::vector<Vec2> points, InsertOptions o, IdBufferGlOptions g) {
        auto locator = std::make_unique<IdBufferGl>(m_gl, g);
        Run r;
        r.gl = locator.get();
        r.ins = std::make_unique<Inserter>(std::move(points), o, std::move(locator));
        r.gl->followOrder(*r.ins);
        return r;
    }

    test::HeadlessGl m_headless;
    std::shared_ptr<ui::GlContext> m_gl;
    GLint m_subpixelBits = 4;
};

IdBufferGlOptions glOptions(GlReadback mode, int w = 320, int h = 200, int batch = 64) {
    IdBufferGlOptions g;
    g.width = w;
    g.height = h;
    g.readback = mode;
    g.batch = batch;
    return g;
}

// The pixels of the GL buffer against a freshly painted CPU buffer of the same mesh. A pixel may
// differ only when its centre lies within the rasterizer's error of an edge of the triangle
// either buffer shows there. That error, conservatively: GL snaps each corner to a grid of
// 2^-subpixelBits pixels after a float transform (about 2^-10 pixels, plus 2^-22 of the
// coordinate's size); an endpoint moved by delta moves the line, at the point with parameter s
// along the edge, by at most delta * (|1 - s| + |s|).
struct Comparison {
    std::size_t agree = 0;     // equal and away from every edge of their triangle
    std::size_t nearEdge = 0;  // equal or not, within the error of an edge
    std::size_t mismatches = 0;
    std::string first;
};

// Whether pixel-space point (cx, cy) lies within the rasterizer's error of an edge of triangle t.
bool nearEdgeOf(const Mesh& m, const PixelMap& map, int subpixelBits, std::int32_t t, double cx,
                double cy) {
    if (t < 0 || t >= m.numTriangles()) return false;
    const double snap = std::ldexp(1.0, -subpixelBits) + std::ldexp(1.0, -10);
    double x[3], y[3];
    for (int k = 0; k < 3; ++k) {
        const Vec2 g = m.G[m.V[3 * t + k]];
        x[k] = map.fx(g.x);
        y[k] = map.fy(g.y);
    }
    auto delta = [&](int v) {
        return std::sqrt(2.0) *
               (snap + std::max(std::abs(x[v]), std::abs(y[v])) * std::ldexp(1.0, -22));
    };
    for (int k = 0; k < 3; ++k) {
        const int a = k, b = (k + 1) % 3;
        const double ex = x[b] - x[a], ey = y[b] - y[a];
        const double len2 = ex * ex + ey * ey;
        if (!(len2 > 0)) return true;  // a degenerate edge in pixel space: no claim
        const double s = ((cx - x[a]) * ex + (cy - y[a]) * ey) / len2;
        const double dist = std::abs(ex * (cy - y[a]) - ey * (cx - x[a])) / std::sqrt(len2);
        if (dist <= delta(a) * std::abs(1 - s) + delta(b) * std::abs(s) + 1e-9) return true;
    }
    return false;
}

Comparison compareWithCpu(const std::vector<std::int32_t>& glIds, const Inserter& ins,
                          const IdBufferGl& gl, const Bounds& bounds, int subpixelBits) {
    const Mesh& m = ins.mesh();
    IdBufferCpu cpu(gl.width(), gl.height());
    const LocatorContext ctx{&m, ins.firstVirtual(), ins.options().boundary == Boundary::Exact,
                             static_cast<std::size_t>(ins.numInput())};
    cpu.reset(ctx, bounds);
    auto nearEdge = [&](std::int32_t t, double cx, double cy) {
        return nearEdgeOf(m, gl.map(), subpixelBits, t, cx, cy);
    };
    Comparison c;
    const auto& ref = cpu.pixels();
    for (int j = 0; j < gl.height(); ++j) {
        for (int i = 0; i < gl.width(); ++i) {
            const std::size_t k = static_cast<std::size_t>(j) * gl.width() + i;
            const std::int32_t tg = glIds[k], tc = ref[k];
            const double cx = i + 0.5, cy = j + 0.5;
            const bool near = nearEdge(tc, cx, cy) || nearEdge(tg, cx, cy);
            if (near) {
                ++c.nearEdge;
            } else if (tg == tc) {
                ++c.agree;
            } else {
                if (c.mismatches++ == 0) {
                    c.first = "pixel (" + std::to_string(i) + ", " + std::to_string(j) + "): GL " +
                              std::to_string(tg) + ", CPU " + std::to_string(tc);
                }
            }
        }
    }
    return c;
}

bool contains(const Mesh& m, std::int32_t t, Vec2 q);

void expectMatchesCpu(const std::vector<std::int32_t>& ids, const Inserter& ins,
                      const IdBufferGl& gl, const Bounds& bounds, int subpixelBits,
                      const std::string& what) {
    ASSERT_EQ(ids.size(), static_cast<std::size_t>(gl.width()) * gl.height()) << what;
    const Comparison c = compareWithCpu(ids, ins, gl, bounds, subpixelBits);
    // Independently of the CPU buffer, on a sample of pixels: the pixel's triangle contains the
    // pixel's centre (exact predicates in world coordinates), and a "no triangle" pixel lies in
    // no shown triangle, unless the centre is within the rasterizer's error of an edge.
    const Mesh& m = ins.mesh();
    const bool ghost = ins.options().boundary == Boundary::Exact;
    int emptyChecks = 0, checked = 0, representable = 0;
    for (std::size_t k = 0; k < ids.size(); k += 97) {
        const int i = static_cast<int>(k % gl.width()), j = static_cast<int>(k / gl.width());
        const Vec2 q = gl.pixelCentre(i, j);
        // Near 1e15 (huge-tiny-box) doubles are 0.125 apart, coarser than the pixels: the centre
        // has no world position there, and only the pixel-space comparison above applies.
        if (std::abs(gl.map().fx(q.x) - (i + 0.5)) > 1e-3 ||
            std::abs(gl.map().fy(q.y) - (j + 0.5)) > 1e-3)
            continue;
        ++representable;
        const std::int32_t t = ids[k];
        std::int32_t truth = t;
        if (t >= 0) {
            ASSERT_LT(t, m.numTriangles()) << what;
            if (contains(m, t, q)) {
                ++checked;
                continue;
            }
        } else if (emptyChecks++ < 200) {
            truth = kNone;
            for (std::int32_t u = 0; u < m.numTriangles() && truth == kNone; ++u) {
                if (!(ghost && ins.isVirtualTriangle(u)) && contains(m, u, q)) truth = u;
            }
            if (truth == kNone) {
                ++checked;
                continue;
            }
        } else {
            continue;
        }
        EXPECT_TRUE(nearEdgeOf(m, gl.map(), subpixelBits, truth, i + 0.5, j + 0.5))
            << what << ": pixel (" << i << ", " << j << ") shows " << t
            << " but its centre lies in " << truth;
    }
    EXPECT_GE(checked, representable / 4) << what;
    EXPECT_EQ(c.mismatches, 0u) << what << ": " << c.mismatches
                                << " pixels differ away from edges; first " << c.first;
    // Most pixels are far from any edge: the comparison is not vacuous.
    EXPECT_GT(c.agree, ids.size() * 7 / 10)
        << what << ": only " << c.agree << " of " << ids.size() << " pixels away from edges ("
        << c.nearEdge << " near)";
}

// Each triangle as its vertex triple rotated to start at the smallest id (orientation kept),
// sorted.
std::vector<std::array<std::int32_t, 3>> canonical(const Mesh& m) {
    std::vector<std::array<std::int32_t, 3>> tris;
    for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
        std::array<std::int32_t, 3> v = {m.V[3 * t], m.V[3 * t + 1], m.V[3 * t + 2]};
        std::rotate(v.begin(), std::min_element(v.begin(), v.end()), v.end());
        tris.push_back(v);
    }
    std::sort(tris.begin(), tris.end());
    return tris;
}

// An exact visibility walk from `t` to the triangle that contains q (closed); kNone if it runs
// out of the mesh. Written here, sharing nothing with the inserter's walk.
std::int32_t walkTo(const Mesh& m, std::int32_t t, Vec2 q, int& steps) {
    steps = 0;
    for (int guard = 0; guard < 4 * m.numTriangles() + 16; ++guard) {
        bool moved = false;
        for (int k = 0; k < 3 && !moved; ++k) {
            const std::int32_t c = 3 * t + k;
            if (orient2d(m.G[m.V[next(c)]], m.G[m.V[prev(c)]], q) < 0) {
                if (m.O[c] == kNone) return kNone;
                t = tri(m.O[c]);
                ++steps;
                moved = true;
            }
        }
        if (!moved) return t;
    }
    return kNone;
}

bool contains(const Mesh& m, std::int32_t t, Vec2 q) {
    for (int k = 0; k < 3; ++k) {
        const std::int32_t c = 3 * t + k;
        if (orient2d(m.G[m.V[next(c)]], m.G[m.V[prev(c)]], q) < 0) return false;
    }
    return true;
}

}  // namespace

// ============================================================================================
// Encoding
// ============================================================================================

TEST(IdBufferGlEncoding, IsThePapersAndRoundTrips) {
    // r = (i >> 16) & 255, g = (i >> 8) & 255, b = i & 255, alpha the bits beyond 2^24.
    const auto c = ui::encodeTriangleId(0x0A0B0C0D);
    EXPECT_EQ(c[0], 0x0B);
    EXPECT_EQ(c[1], 0x0C);
    EXPECT_EQ(c[2], 0x0D);
    EXPECT_EQ(c[3], 0x0A);
    for (std::int32_t id :
         {0, 1, 255, 256, 65535, 65536, (1 << 24) - 1, 1 << 24, (1 << 24) + 77, (1 << 27) + 5}) {
        const auto e = ui::encodeTriangleId(id);
        EXPECT_EQ(ui::decodeTriangleId(e.data()), id) << id;
    }
    const auto none = ui::encodeTriangleId(kNone);
    EXPECT_EQ(none, (std::array<std::uint8_t, 4>{255, 255, 255, 255}));
    EXPECT_EQ(ui::decodeTriangleId(none.data()), kNone);
}

TEST(IdBufferGlEncoding, CoreRefusesTheGlKindsWithAReason) {
    for (LocatorKind k : {LocatorKind::IdBufferGl, LocatorKind::IdBufferGlBatched}) {
        EXPECT_TRUE(needsGl(k));
        try {
            makeLocator(k);
            ADD_FAILURE() << "makeLocator built " << toString(k) << " without a GL context";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("needs a GL context"), std::string::npos)
                << e.what();
        }
    }
    EXPECT_EQ(parseLocatorKind("idbuffer-gl"), LocatorKind::IdBufferGl);
    EXPECT_EQ(parseLocatorKind("idbuffer-gl-batched"), LocatorKind::IdBufferGlBatched);
    EXPECT_STREQ(toString(LocatorKind::IdBufferGlBatched), "idbuffer-gl-batched");
}

// ============================================================================================
// Pixels
// ============================================================================================

TEST_F(IdBufferGlTest, PixelsMatchTheCpuBufferAwayFromEdges) {
    struct Case {
        Generator gen;
        std::size_t n;
        Boundary boundary;
        int w, h;
    };
    const Case cases[] = {
        {Generator::Uniform, 60, Boundary::Exact, 320, 200},
        {Generator::Uniform, 3000, Boundary::Exact, 320, 200},
        {Generator::Clusters, 2000, Boundary::Exact, 257, 301},
        {Generator::HugeTinyBox, 500, Boundary::Exact, 320, 200},
        {Generator::Uniform, 400, Boundary::Super, 320, 200},
        {Generator::Grid, 400, Boundary::Exact, 200, 200},
        {Generator::Uniform, 20000, Boundary::Exact, 1600, 1600},
    };
    for (const Case& k : cases) {
        const std::vector<Vec2> points = generatePoints(k.gen, k.n, 7);
        InsertOptions o;
        o.boundary = k.boundary;
        o.order = OrderKind::Random;
        Run r = makeRun(points, o, glOptions(GlReadback::OnePixel, k.w, k.h));
        Journal journal(*r.ins);
        const std::string name =
            std::string(toString(k.gen)) + " n=" + std::to_string(k.n) + " " + toString(k.boundary);
        // Mid-run (ghost triangles and a partial hull), then at the end of the insertions.
        for (const double share : {0.3, 1.0}) {
            const std::size_t target = static_cast<std::size_t>(share * k.n);
            while (r.ins->stats().inserted + r.ins->stats().duplicates <
                       static_cast<std::int64_t>(target) &&
                   !r.ins->done() && r.ins->control().phase != Phase::Finalize) {
                journal.forward();
            }
            expectMatchesCpu(r.gl->readAll(), *r.ins, *r.gl, Bounds::of(points), m_subpixelBits,
                             name + " at " + std::to_string(target));
        }
        // After Finalize (the triangles are renumbered without a report: the buffer notices).
        while (journal.forward()) {}
        expectMatchesCpu(r.gl->readAll(), *r.ins, *r.gl, Bounds::of(points), m_subpixelBits,
                         name + " final");
    }
}

// Regression: the pixel map took the box onto the lower-left quarter of the pixels (both the
// CPU and the GL buffer, which agreed with each other): the painted share of the buffer must be
// the hull's share of the box.
TEST_F(IdBufferGlTest, BuffersCoverTheWholeBoxNotItsLowerLeftQuarter) {
    const std::vector<Vec2> points = generatePoints(Generator::Uniform, 3000, 12);
    Run r = makeRun(points, {}, glOptions(GlReadback::OnePixel, 300, 200));
    r.ins->run();
    const Mesh& m = r.ins->mesh();
    double hull = 0;
    for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
        const Vec2 a = m.G[m.V[3 * t]], b = m.G[m.V[3 * t + 1]], c = m.G[m.V[3 * t + 2]];
        hull += ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)) / 2;
    }
    const Bounds box = Bounds::of(points);
    const double share = hull / ((box.hi.x - box.lo.x) * (box.hi.y - box.lo.y));
    IdBufferCpu cpu(300, 200);
    cpu.reset({&m, r.ins->firstVirtual(), true, points.size()}, box);
    const std::vector<std::int32_t> gl = r.gl->readAll();
    for (const auto* ids : {&cpu.pixels(), &gl}) {
        const double painted = static_cast<double>(
            std::count_if(ids->begin(), ids->end(), [](std::int32_t t) { return t >= 0; }));
        EXPECT_NEAR(painted / ids->size(), share, 0.02);
        // Each quadrant's centre shows a triangle.
        for (const auto& [i, j] :
             {std::pair{75, 50}, std::pair{225, 50}, std::pair{75, 150}, std::pair{225, 150}}) {
            EXPECT_GE((*ids)[static_cast<std::size_t>(j) * 300 + i], 0) << i << "," << j;
        }
    }
}

TEST_F(IdBufferGlTest, ReadApiAgreesWithItself) {
    const std::vector<Vec2> points = generatePoints(Generator::Uniform, 500, 3);
    Run r = makeRun(points, {}, glOptions(GlReadback::OnePixel, 300, 170));
    r.ins->run();
    const std::vector<std::int32_t> all = r.gl->readAll();
    ASSERT_EQ(all.size(), 300u * 170u);
    for (const auto& [i, j] :
         {std::pair{0, 0}, std::pair{299, 169}, std::pair{150, 85}, std::pair{7, 160}}) {
        EXPECT_EQ(r.gl->idAt(i, j), all[static_cast<std::size_t>(j) * 300 + i]) << i << "," << j;
    }
    EXPECT_EQ(r.gl->idAt(-1, 0), kNone);
    EXPECT_EQ(r.gl->idAt(300, 0), kNone);
    // pixelOf and pixelCentre are inverse on pixel centres.
    int i = 0, j = 0;
    ASSERT_TRUE(r.gl->pixelOf(r.gl->pixelCentre(123, 45), i, j));
    EXPECT_EQ(i, 123);
    EXPECT_EQ(j, 45);
    EXPECT_NE(r.gl->texture(), 0u);
}

TEST_F(IdBufferGlTest, TooLargeABufferIsRefusedInOneLine) {
    GLint maxTexture = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
    try {
        IdBufferGl big(m_gl, glOptions(GlReadback::OnePixel, maxTexture + 1, 16));
        ADD_FAILURE() << "a buffer wider than GL_MAX_TEXTURE_SIZE was accepted";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("does not fit"), std::string::npos) << e.what();
    }
}

// ============================================================================================
// Locating
// ============================================================================================

TEST_F(IdBufferGlTest, HintsPlusTheExactWalkFindTheContainingTriangle) {
    const std::vector<Vec2> points = generatePoints(Generator::Uniform, 4000, 11);
    for (const GlReadback mode : {GlReadback::OnePixel, GlReadback::Batched}) {
        Run r = makeRun(points, {}, glOptions(mode, 400, 400, 128));
        r.ins->run();
        const Mesh& m = r.ins->mesh();
        // Random queries inside the hull (the box minus a margin, checked by brute force).
        SplitMix64 rng(5);
        std::vector<Vec2> queries;
        while (queries.size() < 5000) {
            const Vec2 q{20 + rng.uniform01() * 1560, 20 + rng.uniform01() * 1560};
            bool inside = false;
            for (std::int32_t t = 0; t < m.numTriangles() && !inside; ++t)
                inside = contains(m, t, q);
            if (inside) queries.push_back(q);
        }
        if (mode == GlReadback::Batched)
            r.gl->setInsertionOrder(queries);  // read ahead along the queries
        const auto before = r.gl->stats();
        const auto readsBefore = r.gl->glStats().reads;
        std::size_t hits = 0;
        for (const Vec2& q : queries) {
            const std::int32_t h = r.gl->hint(q, 0);
            ASSERT_GE(h, 0);
            ASSERT_LT(h, m.numTriangles());
            int steps = 0;
            const std::int32_t t = walkTo(m, h, q, steps);
            ASSERT_NE(t, kNone) << "walk from " << h << " left the mesh";
            ASSERT_TRUE(contains(m, t, q));
            r.gl->located(q, t, steps);
            hits += steps == 0;
        }
        // 4000 points in 400 x 400 pixels: about 20 pixels per triangle, most hints are right
        // (a pixel centre and the query in it lie in different triangles in a band along edges).
        EXPECT_GT(hits, queries.size() * 7 / 10) << toString(mode);
        EXPECT_EQ(r.gl->stats().queries - before.queries, queries.size());
        if (mode == GlReadback::Batched) {
            // One read per batch of 128, after the first batches grew 1, 1, 2, 4, ..., 64.
            const std::uint64_t reads = r.gl->glStats().reads - readsBefore;
            EXPECT_GE(reads, (queries.size() + 127) / 128);
            EXPECT_LE(reads, (queries.size() + 127) / 128 + 8);
        }
    }
}

// ============================================================================================
// Whole triangulations
// ============================================================================================

TEST_F(IdBufferGlTest, TriangulationsEqualTheWalkLocatorsInEveryReadbackMode) {
    struct Case {
        Generator gen;
        std::size_t n;
        bool unique;  // no four cocircular points: the Delaunay triangulation is unique
    };
    const Case cases[] = {
        {Generator::Uniform, 5000, true},         {Generator::Clusters, 3000, true},
        {Generator::NearDuplicates, 1500, false}, {Generator::Grid, 900, false},
        {Generator::Collinear, 800, false},       {Generator::HugeTinyBox, 1000, false}};
    for (const Case& k : cases) {
        const std::vector<Vec2> points = generatePoints(k.gen, k.n, 21);
        for (const Boundary boundary : {Boundary::Exact, Boundary::Super}) {
            InsertOptions o;
            o.boundary = boundary;
            o.order = OrderKind::Input;
            Inserter reference(points, o);
            reference.run();
            const auto want = canonical(reference.mesh());
            for (const GlReadback mode :
                 {GlReadback::OnePixel, GlReadback::Batched, GlReadback::Pipelined}) {
                const std::string name =
                    std::string(toString(k.gen)) + " " + toString(boundary) + " " + toString(mode);
                Run r = makeRun(points, o, glOptions(mode, 320, 240, 37));
                r.ins->run();
                const Mesh& m = r.ins->mesh();
                ValidateOptions vo;
                vo.delaunay =
                    boundary == Boundary::Exact;  // super mode does not promise it near the hull
                const auto bad = validate(m, vo);
                EXPECT_TRUE(bad.empty()) << name << ": " << (bad.empty() ? "" : bad[0].message);
                EXPECT_EQ(r.ins->skipped(), reference.skipped()) << name;
                if (k.unique) {
                    EXPECT_EQ(canonical(m), want) << name;  // the Delaunay triangulation is unique
                }
                EXPECT_EQ(m.numTriangles(), reference.mesh().numTriangles()) << name;
                EXPECT_EQ(
                    r.gl->stats().queries,
                    static_cast<std::uint64_t>(r.ins->stats().inserted + r.ins->stats().duplicates -
                                               (boundary == Boundary::Exact ? 3 : 0)))
                    << name << ": one hint per located point";
                if (mode != GlReadback::OnePixel) {
                    // (Not on a grid in input order: row by row, every point lies outside the hull
                    // that the read-ahead pixels show, so it has no id to use.)
                    if (k.unique) {
                        EXPECT_GT(r.gl->glStats().staleQueries, 0u)
                            << name << ": later points use read-ahead ids";
                    }
                    EXPECT_LT(r.gl->glStats().reads, r.gl->stats().queries / 10) << name;
                }
            }
        }
    }
}

TEST_F(IdBufferGlTest, StaleIdsStillLandNearTheirPoint) {
    const std::vector<Vec2> points = generatePoints(Generator::Uniform, 20000, 4);
    InsertOptions o;
    o.order = OrderKind::Input;
    Run one = makeRun(points, o, glOptions(GlReadback::OnePixel, 800, 800));
    one.ins->run();
    Run batched = makeRun(points, o, glOptions(GlReadback::Batched, 800, 800, 512));
    batched.ins->run();
    const auto& s = batched.gl->glStats();
    ASSERT_GT(s.staleQueries, 10000u);
    const double staleSteps = static_cast<double>(s.staleSteps) / s.staleQueries;
    const double staleHits = static_cast<double>(s.staleHits) / s.staleQueries;
    // A walk from an arbitrary triangle of a 40000-triangle mesh takes about a hundred steps;
    // from a stale id, a step or less on average, and the id is mostly still right.
    EXPECT_LT(staleSteps, 2.0);
    EXPECT_GT(staleHits, 0.5);
    EXPECT_GT(s.staleAgeSum / s.staleQueries, 100u) << "ids were read hundreds of insertions ahead";
    // The fresh one-pixel hints are right more often than the stale ones.
    const auto& f = one.gl->glStats();
    EXPECT_GT(static_cast<double>(f.freshHits) / f.freshQueries, staleHits);
    EXPECT_EQ(canonical(one.ins->mesh()), canonical(batched.ins->mesh()));
}

// ============================================================================================
// Undo / redo
// ============================================================================================

TEST_F(IdBufferGlTest, UndoAndRedoKeepTheBufferInSync) {
    // Input order: early points often lie outside the hull, so undoing them shrinks the hull.
    const std::vector<Vec2> points = generatePoints(Generator::Uniform, 300, 9);
    InsertOptions o;
    o.order = OrderKind::Input;
    for (const GlReadback mode : {GlReadback::OnePixel, GlReadback::Batched}) {
        Run r = makeRun(points, o, glOptions(mode, 240, 180, 16));
        Journal journal(*r.ins);
        SplitMix64 rng(17);
        int checks = 0;
        for (int round = 0; round < 40; ++round) {
            const int forward = 1 + static_cast<int>(rng.below(120));
            const int back = static_cast<int>(rng.below(100));
            for (int i = 0; i < forward && journal.forward(); ++i) {}
            for (int i = 0; i < back && journal.back(); ++i) {}
            if (round % 7 == 3)
                journal.seek(
                    rng.below(static_cast<std::uint32_t>(journal.recorded() + 1)));  // bulk: resync
            expectMatchesCpu(r.gl->readAll(), *r.ins, *r.gl, Bounds::of(points), m_subpixelBits,
                             std::string(toString(mode)) + " round " + std::to_string(round) +
                                 " at op " + std::to_string(journal.position()));
            ++checks;
        }
        EXPECT_GT(checks, 20);
        // Some undo shrank the hull: one pixel per insertion clears the old footprints; the
        // batched modes (their pixels painted at different times) repaint everything then.
        if (mode == GlReadback::OnePixel) {
            EXPECT_GT(r.gl->glStats().trianglesCleared, 0u);
        }
        while (journal.forward()) {}
        EXPECT_TRUE(validate(r.ins->mesh()).empty());
        expectMatchesCpu(r.gl->readAll(), *r.ins, *r.gl, Bounds::of(points), m_subpixelBits,
                         "at the end");
    }
}

// ============================================================================================
// GL state: in the GUI the locator runs mid-frame and must leave everything as it found it
// ============================================================================================

namespace {

struct GlSnapshot {
    std::vector<GLint> ints;
    std::vector<GLfloat> floats;
    std::vector<GLboolean> enables;
    bool operator==(const GlSnapshot&) const = default;
};

GlSnapshot snapshot() {
    GlSnapshot s;
    auto ints = [&](GLenum e, int count) {
        GLint v[4] = {0, 0, 0, 0};
        glGetIntegerv(e, v);
        s.ints.insert(s.ints.end(), v, v + count);
    };
    for (GLenum e : {GL_DRAW_FRAMEBUFFER_BINDING,
                     GL_READ_FRAMEBUFFER_BINDING,
                     GL_ARRAY_BUFFER_BINDING,
                     GL_PIXEL_PACK_BUFFER_BINDING,
                     GL_PIXEL_UNPACK_BUFFER_BINDING,
                     GL_CURRENT_PROGRAM,
                     GL_VERTEX_ARRAY_BINDING,
                     GL_ELEMENT_ARRAY_BUFFER_BINDING,
                     GL_ACTIVE_TEXTURE,
                     GL_TEXTURE_BINDING_2D,
                     GL_BLEND_SRC_RGB,
                     GL_BLEND_DST_RGB,
                     GL_BLEND_SRC_ALPHA,
                     GL_BLEND_DST_ALPHA,
                     GL_BLEND_EQUATION_RGB,
                     GL_BLEND_EQUATION_ALPHA,
                     GL_PACK_ALIGNMENT,
                     GL_PACK_ROW_LENGTH,
                     GL_PACK_SKIP_ROWS,
                     GL_UNPACK_ALIGNMENT,
                     GL_UNPACK_ROW_LENGTH,
                     GL_UNPACK_SKIP_PIXELS}) {
        ints(e, 1);
    }
    ints(GL_POLYGON_MODE, 2);
    ints(GL_VIEWPORT, 4);
    ints(GL_SCISSOR_BOX, 4);
    // The caller's vertex array: what its attributes point at.
    for (GLuint a : {0u, 1u}) {
        for (GLenum e : {GL_VERTEX_ATTRIB_ARRAY_ENABLED, GL_VERTEX_ATTRIB_ARRAY_SIZE,
                         GL_VERTEX_ATTRIB_ARRAY_STRIDE, GL_VERTEX_ATTRIB_ARRAY_BUFFER_BINDING,
                         GL_VERTEX_ATTRIB_ARRAY_DIVISOR}) {
            GLint v = 0;
            glGetVertexAttribiv(a, e, &v);
            s.ints.push_back(v);
        }
    }
    // Texture unit 0 (ours), whichever unit is active: its texture and sampler.
    GLint active = GL_TEXTURE0, unit0[2] = {0, 0};
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    glActiveTexture(GL_TEXTURE0);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &unit0[0]);
    glGetIntegerv(GL_SAMPLER_BINDING, &unit0[1]);
    glActiveTexture(static_cast<GLenum>(active));
    s.ints.insert(s.ints.end(), unit0, unit0 + 2);
    for (GLenum e : {GL_COLOR_CLEAR_VALUE, GL_POINT_SIZE, GL_LINE_WIDTH}) {
        GLfloat v[4] = {};
        glGetFloatv(e, v);
        s.floats.insert(s.floats.end(), v, v + 4);
    }
    for (GLenum e : {GL_BLEND, GL_SCISSOR_TEST, GL_DITHER, GL_CULL_FACE, GL_DEPTH_TEST,
                     GL_STENCIL_TEST, GL_MULTISAMPLE, GL_COLOR_LOGIC_OP, GL_FRAMEBUFFER_SRGB,
                     GL_PROGRAM_POINT_SIZE, GL_RASTERIZER_DISCARD, GL_SAMPLE_ALPHA_TO_COVERAGE}) {
        s.enables.push_back(glIsEnabled(e));
    }
    GLboolean mask[4];
    glGetBooleanv(GL_COLOR_WRITEMASK, mask);
    s.enables.insert(s.enables.end(), mask, mask + 4);
    return s;
}

// A caller's program: anything that is not ours.
GLuint callerProgram() {
    std::string error;
    const GLuint p = ui::buildProgram(
        "layout(location = 0) in vec2 aPos;\nvoid main() { gl_Position = vec4(aPos, 0.0, 1.0); }\n",
        "out vec4 c;\nvoid main() { c = vec4(1.0); }\n", error);
    EXPECT_NE(p, 0u) << error;
    return p;
}

}  // namespace

TEST_F(IdBufferGlTest, LeavesTheCallersGlStateAsItFoundIt) {
    // A caller's state in the middle of drawing: an unusual one on purpose.
    GLuint tex[2] = {0, 0}, buffers[2] = {0, 0}, vao = 0, sampler = 0, readFbo = 0;
    glGenTextures(2, tex);
    glGenBuffers(2, buffers);
    glGenVertexArrays(1, &vao);
    glGenSamplers(1, &sampler);
    glGenFramebuffers(1, &readFbo);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, readFbo);
    glBindTexture(GL_TEXTURE_2D, tex[0]);  // unit 0
    glBindSampler(0, sampler);
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_2D, tex[1]);
    const GLuint program = callerProgram();
    glUseProgram(program);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, buffers[0]);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 12, nullptr);
    glVertexAttribDivisor(0, 2);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, buffers[1]);  // a read would land in it
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, buffers[1]);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ZERO);
    glBlendEquation(GL_FUNC_REVERSE_SUBTRACT);
    glEnable(GL_SCISSOR_TEST);
    glScissor(1, 2, 3, 4);
    glViewport(3, 4, 5, 6);
    glClearColor(0.1f, 0.2f, 0.3f, 0.4f);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glPixelStorei(GL_PACK_ROW_LENGTH, 7);
    glPixelStorei(GL_PACK_SKIP_ROWS, 2);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 9);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 1);
    glPointSize(3);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
    glDisable(GL_DITHER);
    glEnable(GL_CULL_FACE);
    glEnable(GL_COLOR_LOGIC_OP);
    glLogicOp(GL_XOR);
    while (glGetError() != GL_NO_ERROR) {}
    const GlSnapshot before = snapshot();

    const std::vector<Vec2> points = generatePoints(Generator::Uniform, 3000, 8);
    for (const GlReadback mode :
         {GlReadback::OnePixel, GlReadback::Batched, GlReadback::Pipelined}) {
        InsertOptions o;
        o.order = OrderKind::Input;
        Run r = makeRun(points, o, glOptions(mode, 200, 200, 50));
        Journal journal(*r.ins);
        for (int i = 0; i < 4000 && journal.forward(); ++i) {}
        for (int i = 0; i < 500 && journal.back(); ++i) {}
        r.gl->idAt(10, 10);
        r.gl->readAll();
        EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR)) << toString(mode);
        EXPECT_TRUE(snapshot() == before) << toString(mode) << ": the GL state changed";
        // And the buffer is still right, whatever the caller's state was.
        expectMatchesCpu(r.gl->readAll(), *r.ins, *r.gl, Bounds::of(points), m_subpixelBits,
                         toString(mode));
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &readFbo);
    glBindVertexArray(0);
    glDeleteVertexArrays(1, &vao);
    glUseProgram(0);
    glDeleteProgram(program);
    glDeleteSamplers(1, &sampler);
    glDeleteBuffers(2, buffers);
    glDeleteTextures(2, tex);
}

// ============================================================================================
// The GUI: the same locator on the window's context
// ============================================================================================

TEST(IdBufferGlGui, TheGuiRunsTheGlLocatorOnItsContext) {
    test::UiHarness h;
    auto& st = h.state();
    ASSERT_TRUE(st.engine.hasGl());
    ASSERT_EQ(st.engine.idBufferGl(), nullptr);
    // (400 points: with 2000 the canvas' ImGui draw list overflows, whatever the locator.)
    const std::vector<Vec2> points = generatePoints(Generator::Uniform, 400, 2);
    st.loadPoints(points, "uniform");
    for (const LocatorKind kind : {LocatorKind::IdBufferGl, LocatorKind::IdBufferGlBatched}) {
        InsertOptions o = st.engine.options();
        o.locator = kind;
        o.locatorOptions.idBufferWidth = 400;
        o.locatorOptions.idBufferHeight = 300;
        o.locatorOptions.idBufferBatch = 32;
        ASSERT_TRUE(st.setOptions(o)) << st.messages.back().text;
        auto* gl = static_cast<IdBufferGl*>(st.engine.idBufferGl());
        ASSERT_NE(gl, nullptr);
        EXPECT_EQ(gl->name(),
                  kind == LocatorKind::IdBufferGl ? "idbuffer-gl" : "idbuffer-gl-batched");
        // The run was recorded (400 points: the whole history), so the locator worked already;
        // step back and forth through the frames as a user would.
        h.frames(2);
        st.engine.seek(st.engine.recorded() / 2);
        h.frames(2);
        EXPECT_EQ(gl->width(), 400);
        const std::vector<std::int32_t> ids = gl->readAll();
        std::int32_t shown = 0;
        for (std::int32_t id : ids) shown += id >= 0;
        EXPECT_GT(shown, 400 * 300 / 2) << "the buffer shows the mesh";
        // The same pixels as the CPU reference: the GUI's GL state did not get in the way.
        GLint subpixelBits = 4;
        glGetIntegerv(GL_SUBPIXEL_BITS, &subpixelBits);
        expectMatchesCpu(ids, st.engine.inserter(), *gl, Bounds::of(points), subpixelBits,
                         toString(kind));
        st.engine.seek(st.engine.recorded());
        h.frames(2);
        EXPECT_TRUE(st.engine.atEnd());
        EXPECT_TRUE(validate(st.engine.mesh()).empty());
        // Most hints right (batched: ids up to 31 insertions old, on a mesh of a few hundred).
        EXPECT_GT(gl->stats().hits,
                  gl->stats().queries * (kind == LocatorKind::IdBufferGl ? 7 : 5) / 10);
    }
    // Without a context, the engine refuses the GL kinds with a reason.
    ui::Engine bare;
    std::string error;
    InsertOptions o;
    o.locator = LocatorKind::IdBufferGl;
    EXPECT_FALSE(bare.reset(points, o, error));
    EXPECT_NE(error.find("needs a GL context"), std::string::npos) << error;
}

// ============================================================================================
// dtlab table1: the files it writes
// ============================================================================================

namespace {

using test::dtlabGlFlag;

// A folder of its own for each test executable (OSMesa, EGL): ctest may run them side by side.
std::filesystem::path table1Dir() {
    const std::string gl = dtlabGlFlag();
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                      ("dlab_table1_test_" + gl.substr(gl.rfind(' ') + 1));
    std::filesystem::create_directories(dir);
    return dir;
}

// The whole of a text file.
std::string slurp(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

}  // namespace

TEST(IdBufferGlTable1, WritesTheCsvAndThePlotAndSaysWhereItRan) {
    test::HeadlessGl context;  // this executable's GL, as dtlab's --gl gets it
    std::string error;
    ASSERT_TRUE(context.open(error)) << error;
    const std::string renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const std::filesystem::path dir = table1Dir();
    const std::string csv = (dir / "t1.csv").string(), png = (dir / "t1.png").string();
    std::filesystem::remove(csv);
    std::filesystem::remove(png);
    const std::string cmd =
        std::string(DLAB_DTLAB_PATH) + " table1 --sizes 200,400,800 --repeat 1 --batch 32 --csv " +
        csv + " --png " + png + " " + dtlabGlFlag() + " > " + (dir / "out.txt").string() + " 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    // The header and the CSV's comment name the renderer and the API; the read's cost.
    const std::string out = slurp(dir / "out.txt");
    EXPECT_NE(out.find("here: " + renderer + ", OpenGL "), std::string::npos) << out;
    const std::string api = std::string(dtlabGlFlag()) == "--gl egl" ? " (EGL, " : " (OSMesa)";
    EXPECT_NE(out.find(api), std::string::npos) << out;
    EXPECT_EQ(out.find("dtlab: GL: "), std::string::npos) << "piped, stderr stays quiet: " << out;
    EXPECT_NE(out.find("One pixel read costs "), std::string::npos) << out;
    EXPECT_NE(out.find("A read costs "), std::string::npos) << out;
    std::ifstream in(csv);
    std::string comment, header;
    std::getline(in, comment);
    EXPECT_EQ(comment.rfind("# dtlab table1, median ms; " + renderer + ", OpenGL ", 0), 0u)
        << comment;
    std::getline(in, header);
    EXPECT_EQ(header, "n,naive,idbuffer-gl,idbuffer-gl-batched,idbuffer-cpu,walk,best");
    std::vector<std::size_t> ns;
    for (std::string line; std::getline(in, line);) {
        std::stringstream ss(line);
        std::string cell;
        std::getline(ss, cell, ',');
        ns.push_back(std::stoul(cell));
        int values = 0;
        while (std::getline(ss, cell, ',')) {
            EXPECT_GT(std::stod(cell), 0.0) << line;
            ++values;
        }
        EXPECT_EQ(values, 6) << line;
    }
    EXPECT_EQ(ns, (std::vector<std::size_t>{200, 400, 800}));
    // A PNG of the plot's size.
    std::ifstream p(png, std::ios::binary);
    unsigned char head[24] = {};
    p.read(reinterpret_cast<char*>(head), 24);
    ASSERT_TRUE(p) << "no " << png;
    EXPECT_EQ(head[1], 'P');
    EXPECT_EQ(head[2], 'N');
    const unsigned w = (head[16] << 24) | (head[17] << 16) | (head[18] << 8) | head[19];
    const unsigned hgt = (head[20] << 24) | (head[21] << 16) | (head[22] << 8) | head[23];
    EXPECT_EQ(w, 1400u);
    EXPECT_EQ(hgt, 900u);
    // Bad sizes: one line, a non-zero status.
    const std::string bad = std::string(DLAB_DTLAB_PATH) + " table1 --sizes 100,x " +
                            dtlabGlFlag() + " > " + (dir / "bad.txt").string() + " 2>&1";
    EXPECT_NE(std::system(bad.c_str()), 0);
    std::ifstream b(dir / "bad.txt");
    std::string line;
    std::getline(b, line);
    EXPECT_NE(line.find("--sizes"), std::string::npos) << line;
}

TEST(IdBufferGlTable1, DtlabTriangulatesWithTheGlLocatorInEveryReadbackMode) {
    const std::filesystem::path dir = table1Dir();
    const std::string dtlab = DLAB_DTLAB_PATH, pts = (dir / "u.node").string(),
                      log = (dir / "tri.txt").string();
    ASSERT_EQ(std::system((dtlab + " gen uniform 3000 -o " + pts + " > " + log).c_str()), 0);
    // "FILE: 3000 points, T triangles in ..." must say the same T as the walk locator's run.
    auto triangles = [&](const char* flags) {
        const std::string cmd = dtlab + " triangulate " + pts + " -o " + (dir / "out").string() +
                                " --check " + dtlabGlFlag() + " " + flags + " > " + log + " 2>&1";
        EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
        std::ifstream in(log);
        std::string first;  // the summary (the GL locators' runs say on a line before which GL)
        while (std::getline(in, first) && first.find(" points, ") == std::string::npos) {}
        const std::size_t at = first.find(" points, ");
        return at == std::string::npos ? std::string("?")
                                       : first.substr(at, first.find(" triangles") - at);
    };
    const std::string want = triangles("--locate walk");
    ASSERT_NE(want, "?");
    for (const char* flags : {"--locate idbuffer-gl", "--locate idbuffer-gl-batched --batch 100",
                              "--locate idbuffer-gl --readback pipelined --batch 64"}) {
        EXPECT_EQ(triangles(flags), want) << flags;
    }
}
