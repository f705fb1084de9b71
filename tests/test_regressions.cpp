// Inputs that broke other triangulators: a flip cascade far deeper than any fixed stack, endless
// flipping on cocircular points, huge and tiny coordinates, piles of duplicates.
#include "core/engine/generators.h"
#include "core/engine/inserter.h"
#include "core/engine/locator.h"
#include "tests/exact_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace dlab;

namespace {

std::vector<Vec2> regularPolygon(int n, double r, Vec2 c) {
    std::vector<Vec2> pts;
    for (int i = 0; i < n; ++i) {
        const double a = 2 * std::numbers::pi * i / n;
        pts.push_back({c.x + r * std::cos(a), c.y + r * std::sin(a)});
    }
    return pts;
}

std::int32_t degreeOf(const Mesh& m, std::int32_t v) {
    std::int32_t d = 0;
    for (std::int32_t c = 0; c < m.numCorners(); ++c) d += m.V[c] == v;
    return d;
}

}  // namespace

TEST(Regression, CentreOfA2000GonFlipsEveryFanEdgeWithoutOverflowingTheWorkList) {
    // The polygon's vertices are (nearly) cocircular; its centre, inserted last, sees every
    // fan edge flip: a cascade of ~2000 flips from one insertion.
    auto pts = regularPolygon(2000, 500, {800, 800});
    pts.push_back({800, 800});
    for (Boundary b : {Boundary::Exact, Boundary::Super}) {
        SCOPED_TRACE(toString(b));
        InsertOptions opt;
        opt.order = OrderKind::Input;
        opt.boundary = b;
        Inserter ins(pts, opt);
        Journal journal(ins);
        std::int64_t flipsBefore = -1;
        while (journal.forward()) {
            if (ins.currentVertex() == 2000 && flipsBefore < 0) flipsBefore = ins.stats().flips;
        }
        ASSERT_TRUE(ins.done());
        EXPECT_GE(ins.stats().flips - flipsBefore, 1900);  // none dropped, whatever the stack depth
        EXPECT_TRUE(validate(ins.mesh()).empty());
        if (b == Boundary::Exact) {
            EXPECT_EQ(checkDelaunayExact(ins.mesh()), "");
            EXPECT_EQ(degreeOf(ins.mesh(), 2000), 2000);
        }
    }
}

TEST(Regression, ExactlyCocircularPointsNeverFlipForever) {
    // Integer lattice and the 8 lattice points on a circle of radius 5 (3-4-5 triangles): every
    // in-circle test of a cocircular quadruple returns 0, which must not flip.
    std::vector<Vec2> circle;
    for (auto [x, y] : {std::pair{5, 0},
                        {4, 3},
                        {3, 4},
                        {0, 5},
                        {-3, 4},
                        {-4, 3},
                        {-5, 0},
                        {-4, -3},
                        {-3, -4},
                        {0, -5},
                        {3, -4},
                        {4, -3}}) {
        circle.push_back({double(x), double(y)});
    }
    for (const auto& pts : {circle, generatePoints(Generator::Grid, 4096, 1)}) {
        for (OrderKind order : {OrderKind::Input, OrderKind::Random, OrderKind::Brio}) {
            InsertOptions opt;
            opt.order = order;
            Inserter ins(pts, opt);
            ins.run();
            // Terminating is the point; randomized orders also keep the expected O(n) flips
            // (a lattice in row order is a legitimately bad order: O(n sqrt n) flips).
            if (order != OrderKind::Input) {
                EXPECT_LT(ins.stats().flips, 4 * static_cast<std::int64_t>(pts.size()));
            }
            EXPECT_EQ(checkDelaunayExact(ins.mesh()), "");
        }
    }
}

TEST(Regression, HugeAndTinyCoordinatesGiveExactDelaunay) {
    const auto base = generatePoints(Generator::Clusters, 800, 3);
    for (double scale : {1e-300, 1e-200, 1e-20, 1e20, 1e200, 1e300}) {
        SCOPED_TRACE(scale);
        std::vector<Vec2> pts;
        for (Vec2 p : base) pts.push_back({p.x * scale / 1600, p.y * scale / 1600});
        Inserter ins(pts);
        ins.run();
        EXPECT_EQ(checkDelaunayExact(ins.mesh()), "");
    }
    // A tiny cluster far from the origin: relative extent 1e-13.
    std::vector<Vec2> far;
    for (Vec2 p : base) far.push_back({1e9 + p.x * 1e-7, -1e9 + p.y * 1e-7});
    Inserter ins(far);
    ins.run();
    EXPECT_EQ(checkDelaunayExact(ins.mesh()), "");
}

TEST(Regression, APileOfDuplicatesKeepsTheFirstOccurrence) {
    std::vector<Vec2> pts(500, Vec2{1, 1});
    pts.insert(pts.begin() + 100, Vec2{0, 0});
    pts.push_back({2, 0});
    pts.push_back({1, 1});
    for (OrderKind order : {OrderKind::Input, OrderKind::Random, OrderKind::Brio}) {
        InsertOptions opt;
        opt.order = order;
        Inserter ins(pts, opt);
        ins.run();
        ASSERT_EQ(ins.mesh().numTriangles(), 1);
        EXPECT_EQ(ins.skipped().size(), pts.size() - 3);
        for (std::int32_t v : ins.mesh().V) EXPECT_TRUE(v == 0 || v == 100 || v == 501) << v;
    }
}

TEST(Regression, CollinearRunThenOneOffPointMakesAFan) {
    std::vector<Vec2> pts;
    for (int i = 0; i < 50; ++i) pts.push_back({double(i), 2.0 * i});
    Inserter line(pts);
    line.run();
    EXPECT_EQ(line.mesh().numTriangles(), 0);
    pts.push_back({30, -5});
    Inserter fan(pts);
    fan.run();
    EXPECT_EQ(fan.mesh().numTriangles(), 49);
    EXPECT_EQ(checkDelaunayExact(fan.mesh()), "");
}

// Found by fuzz_engine: points a few subnormals apart made the ID buffer's and the grid's scale
// (cells / extent) overflow to inf; 0 * inf gave NaN pixel coordinates and inf ones became
// INT_MIN when converted to int (undefined behaviour): a pixel read far out of bounds.
TEST(Regression, IdBufferScaleStaysFiniteForASubnormalExtent) {
    std::vector<Vec2> pts;
    for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) pts.push_back({std::ldexp(i, -1074), std::ldexp(j, -1074)});
    }
    for (LocatorKind locator : {LocatorKind::IdBufferCpu, LocatorKind::Grid}) {
        SCOPED_TRACE(toString(locator));
        InsertOptions opt;
        opt.locator = locator;
        opt.locatorOptions.idBufferWidth = opt.locatorOptions.idBufferHeight = 16;
        Inserter ins(pts, opt);
        ins.run();
        EXPECT_EQ(checkDelaunayExact(ins.mesh()), "");
        if (auto* ids = dynamic_cast<IdBufferCpu*>(ins.locator())) {
            for (const Vec2& p : pts) {
                const std::int32_t t = ids->pixelAt(p);
                EXPECT_TRUE(t == kNone || (t >= 0 && t < ins.mesh().numTriangles())) << t;
            }
        }
    }
}

// Found by fuzz_engine: in super mode the super-triangle's nearly flat edges put the row span's
// end at -3e12 pixels; converting that to int was undefined (on x86 INT_MIN: a loop over
// billions of pixels, writing outside the row wherever the huge triangle covers them).
TEST(Regression, IdBufferSpanOfANearlyFlatEdgeIsClampedBeforeConversion) {
    const std::vector<Vec2> pts{{-0x1p+1, -0x1.0000000002p+40},
                                {-0x1p+1, -0x1p+40},
                                {-0x1p+1, -0x1.fffffffffcp+39},
                                {-0x1p+0, -0x1.0000000002p+40},
                                {-0x1p+0, -0x1p+40},
                                {-0x1p+0, -0x1.fffffffffcp+39},
                                {0x0p+0, -0x1.0000000002p+40},
                                {0x0p+0, -0x1p+40},
                                {0x0p+0, -0x1.fffffffffcp+39},
                                {0x1p+0, -0x1.0000000002p+40},
                                {0x1p+0, -0x1.fffffffffcp+39},
                                {-0x1.8p+0, -0x1.0000000001p+40},
                                {-0x1p+0, -0x1.0000000001p+40},
                                {0x0p+0, -0x1.0000000008p+40},
                                {0x1p+1, -0x1.0000000008p+40},
                                {0x1p+1, -0x1.0000000008p+40},
                                {0x0.0000000080ap-1022, 0x0.00a0a000fp-1022}};
    for (Boundary boundary : {Boundary::Super, Boundary::Exact}) {
        SCOPED_TRACE(toString(boundary));
        InsertOptions opt;
        opt.boundary = boundary;
        opt.locator = LocatorKind::IdBufferCpu;
        opt.locatorOptions.idBufferWidth = opt.locatorOptions.idBufferHeight = 16;
        Inserter ins(pts, opt);
        Journal journal(ins);
        while (journal.forward()) {}
        const auto v = validate(ins.mesh());
        EXPECT_TRUE(v.empty()) << v[0].message;
        if (boundary == Boundary::Exact) {
            EXPECT_EQ(checkDelaunayExact(ins.mesh()), "");
        }
    }
}
