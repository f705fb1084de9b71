// The two-core batch path (core/engine/halves.h): the halves, joined, are exactly Delaunay (GMP)
// on every distribution and on degenerate sets, with the vertices and duplicates of the
// incremental path; where the triangulation is unique, the same triangles.
#include "core/engine/generators.h"
#include "core/engine/halves.h"
#include "tests/exact_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <string>
#include <vector>

using namespace dlab;

namespace {

std::optional<JoinedTriangulation> joined(std::vector<Vec2> points,
                                          std::size_t smallest = kSmallestSplit) {
    const std::optional<Vec2> split = splitPoint(points, smallest);
    if (!split) return std::nullopt;
    HalfTriangulation left = triangulateHalf(points, *split, true, {});
    HalfTriangulation right = triangulateHalf(points, *split, false, {});
    return joinHalves(points, std::move(left), std::move(right));
}

using Triangle = std::array<std::int32_t, 3>;

// Each triangle as its vertices from the smallest on (orientation kept).
std::set<Triangle> triangles(const Mesh& m) {
    std::set<Triangle> out;
    for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
        Triangle v{m.V[3 * t], m.V[3 * t + 1], m.V[3 * t + 2]};
        std::rotate(v.begin(), std::min_element(v.begin(), v.end()), v.end());
        out.insert(v);
    }
    return out;
}

// Checks the joined result against the incremental one; `unique`: no four cocircular points,
// so the very triangles must agree.
void expectJoinedDelaunay(const std::vector<Vec2>& points, const std::string& name, bool unique,
                          std::size_t smallest = kSmallestSplit) {
    SCOPED_TRACE(name);
    const auto result = joined(points, smallest);
    ASSERT_TRUE(result.has_value()) << "the set did not split or join";
    const std::vector<std::int32_t> vertices = firstOccurrences(points);
    EXPECT_EQ(checkDelaunayExact(result->mesh, &vertices), "");
    Inserter whole(points);
    whole.run();
    EXPECT_EQ(result->mesh.numTriangles(), whole.mesh().numTriangles());
    std::vector<std::int32_t> skipped = whole.skipped();  // in insertion order
    std::sort(skipped.begin(), skipped.end());
    EXPECT_EQ(result->skipped, skipped);
    EXPECT_EQ(result->mesh.G, whole.mesh().G);
    if (unique) {
        EXPECT_EQ(triangles(result->mesh), triangles(whole.mesh()));
    }
}

}  // namespace

TEST(Halves, EveryDistributionJoinsIntoTheDelaunayTriangulation) {
    for (Generator g : allGenerators()) {
        if (g == Generator::AllCollinear) continue;
        const bool unique = g == Generator::Uniform || g == Generator::Gaussian ||
                            g == Generator::Kuzmin || g == Generator::Clusters;
        expectJoinedDelaunay(generatePoints(g, 1 << 14, 5), toString(g), unique);
    }
}

TEST(Halves, LatticesWithTheSeamOnAColumnOfPoints) {
    // Every quadrilateral cocircular, hull sides collinear with the tangents, the median on a
    // column shared by many points.
    for (const int side : {64, 65, 101}) {
        std::vector<Vec2> pts;
        for (int i = 0; i < side; ++i) {
            for (int j = 0; j < side; ++j) pts.push_back({double(i), double(j)});
        }
        expectJoinedDelaunay(pts, "lattice " + std::to_string(side), false);
    }
}

TEST(Halves, CopiesOfTheSplitPointStayTogether) {
    // One point in five is a copy of the centre, one in five a copy of another point: the split
    // point is the centre, and every copy of it goes to the right half.
    std::vector<Vec2> pts = generatePoints(Generator::Uniform, 6000, 3);
    const Vec2 centre{800, 800};  // the middle of the generators' box
    for (int k = 0; k < 4000; ++k) pts.push_back(k % 2 ? centre : pts[k]);
    const std::optional<Vec2> split = splitPoint(pts);
    ASSERT_TRUE(split.has_value());
    EXPECT_EQ(*split, centre);
    const HalfTriangulation left = triangulateHalf(pts, centre, true, {});
    for (const std::int32_t v : left.mesh.V) EXPECT_FALSE(pts[v] == centre) << v;
    for (const std::int32_t v : left.skipped) EXPECT_FALSE(pts[v] == centre) << v;
    expectJoinedDelaunay(pts, "duplicates", true);
}

TEST(Halves, SmallSetsOfEveryShapeSplitAnywhere) {
    // Hundreds of seams: small sets split however small, the seam crossing cocircular lattices,
    // circles (every point on the hull), clusters and collinear runs.
    const Generator shapes[] = {Generator::Uniform,   Generator::Grid,   Generator::RotatedGrid,
                                Generator::Ngon,      Generator::Circle, Generator::Clusters,
                                Generator::Collinear, Generator::Curves, Generator::NearDuplicates};
    int joins = 0;
    for (const Generator g : shapes) {
        for (std::uint64_t seed = 1; seed <= 40; ++seed) {
            const auto n = static_cast<std::size_t>(12 + (seed * 37) % 300);
            const std::vector<Vec2> pts = generatePoints(g, n, seed);
            const std::string name = std::string(toString(g)) + " seed " + std::to_string(seed);
            const std::optional<Vec2> split = splitPoint(pts, 2);
            ASSERT_TRUE(split.has_value()) << name;
            const bool bothHaveTriangles =
                triangulateHalf(pts, *split, true, {}).mesh.numTriangles() > 0 &&
                triangulateHalf(pts, *split, false, {}).mesh.numTriangles() > 0;
            if (!bothHaveTriangles) {  // a half on one line: the caller runs one inserter
                EXPECT_FALSE(joined(pts, 2).has_value()) << name;
                continue;
            }
            expectJoinedDelaunay(pts, name, false, 2);
            ++joins;
        }
    }
    EXPECT_GT(joins, 300);
}

TEST(Halves, AHalfOnOneLineDoesNotJoin) {
    // The left half on the x axis (no triangle of its own), the right half in a box.
    std::vector<Vec2> pts;
    for (int i = 0; i < 5000; ++i) pts.push_back({-1.0 - i, 0.0});
    const auto box = generatePoints(Generator::Uniform, 5001, 2);
    pts.insert(pts.end(), box.begin(), box.end());
    EXPECT_FALSE(joined(pts).has_value());
}

TEST(Halves, SmallSetsAreNotSplit) {
    EXPECT_FALSE(splitPoint(generatePoints(Generator::Uniform, 1000, 1)).has_value());
    EXPECT_TRUE(splitPoint(generatePoints(Generator::Uniform, 5000, 1)).has_value());
}

TEST(Halves, TheSplitHalvesEveryDistributionWithinOnePerCent) {
    // The two threads wait for the larger half: the sampled median must be close to the true
    // one, on sets larger than the sample (the median of a sample) and smaller (exact).
    for (const int n : {1 << 20, 20000}) {
        for (Generator g : allGenerators()) {
            if (g == Generator::NearDuplicates) continue;  // copies of a point stay together
            const std::vector<Vec2> pts = generatePoints(g, n, 7);
            const std::optional<Vec2> split = splitPoint(pts);
            ASSERT_TRUE(split.has_value());
            const auto below = std::count_if(pts.begin(), pts.end(), [&](Vec2 p) {
                return p.x < split->x || (p.x == split->x && p.y < split->y);
            });
            EXPECT_NEAR(static_cast<double>(below) / n, 0.5, 0.01)
                << toString(g) << ", " << n << " points";
        }
    }
}

TEST(Halves, APilotDeclinesTheSplitWhereTheSeamGrowsWithTheSet) {
    // On a parabola the vertex next to the split is the apex of a fan over its whole half, and
    // the join erases almost every edge; between two facing arcs every point has a seam
    // triangle. There the join is a fifth of the whole run's work at any size (and slower per
    // call than the inserter); elsewhere the seam is a thin line and the span about half.
    for (Generator g : allGenerators()) {
        if (g == Generator::AllCollinear) continue;
        for (const std::uint64_t seed : {1, 3}) {
            const std::vector<Vec2> pts = generatePoints(g, 1 << 16, seed);
            const SplitPilot pilot = pilotSplit(pts, *splitPoint(pts), {});
            SCOPED_TRACE(std::string(toString(g)) + " seed " + std::to_string(seed));
            EXPECT_EQ(pilot.sample, kPilotSample);
            EXPECT_TRUE(pilot.joined);
            const bool seamGrows = g == Generator::Parabola || g == Generator::ConvexHull ||
                                   g == Generator::FacingArcs;
            EXPECT_EQ(pilot.pays(), !seamGrows)
                << "span " << pilot.ratio() << ", join " << pilot.seamShare();
            if (seamGrows) {
                EXPECT_GT(pilot.seamShare(), 0.15);
            } else {
                EXPECT_LT(pilot.ratio(), 0.8);
                EXPECT_LT(pilot.seamShare(), 0.06);
            }
        }
    }
}

TEST(Halves, APilotOfAHalfOnOneLineDoesNotPay) {
    std::vector<Vec2> pts;
    for (int i = 0; i < 5000; ++i) pts.push_back({-1.0 - i, 0.0});
    const auto box = generatePoints(Generator::Uniform, 5001, 2);
    pts.insert(pts.end(), box.begin(), box.end());
    const SplitPilot pilot = pilotSplit(pts, *splitPoint(pts), {});
    EXPECT_FALSE(pilot.joined);
    EXPECT_FALSE(pilot.pays());
}

TEST(Halves, TwoNeedlesJoinWithMoreSeamTrianglesThanCorners) {
    // Each half is one needle triangle, their tops 1e-274 apart: the seam zigzags through six
    // triangles, more than the halves have corners.
    const std::vector<Vec2> pts = {{1.3939306136085695e-308, 5.7879437653027852e-275},
                                   {3, -4398046511112},
                                   {-1.90625, -4398046511106},
                                   {-1.875, -4398046511106},
                                   {7.415058735927868e-305, 1.1179707971429261e-308},
                                   {2, -4398046511112}};
    expectJoinedDelaunay(pts, "two needles", false, 2);
}
