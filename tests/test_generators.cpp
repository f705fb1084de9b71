// Point-set generators: every kind by name, the same points for the same seed, and the shapes
// the uneven-density kinds promise (a heavy tail, twelve decades of radii, a dense disc).
#include "core/engine/generators.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace dlab;

namespace {

std::vector<double> sortedRadii(const std::vector<Vec2>& pts, Vec2 centre) {
    std::vector<double> r;
    for (const Vec2& p : pts) r.push_back(std::hypot(p.x - centre.x, p.y - centre.y));
    std::sort(r.begin(), r.end());
    return r;
}

}  // namespace

TEST(Generators, EveryKindIsNamedAndRepeatsForTheSameSeed) {
    const std::vector<Generator> all = allGenerators();
    EXPECT_EQ(all.size(), 20u);
    for (Generator g : all) {
        SCOPED_TRACE(toString(g));
        EXPECT_EQ(parseGenerator(toString(g)), g);
        EXPECT_NE(generatorNames().find(toString(g)), std::string::npos);
        const auto a = generatePoints(g, 3000, 4), b = generatePoints(g, 3000, 4);
        ASSERT_EQ(a.size(), 3000u);
        EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec2)), 0);
        for (const Vec2& p : a) ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y));
    }
    EXPECT_FALSE(parseGenerator("kuzmin2"));
}

TEST(Generators, KuzminHasItsMedianRadiusAndAHeavyTail) {
    // Mass within r is 1 - 1/sqrt(1 + r^2): the median radius is sqrt(3), and P(r > R) ~ 1/R,
    // so among 2^14 points some lie thousands of units out.
    const auto r = sortedRadii(generatePoints(Generator::Kuzmin, 1 << 14, 1), {0, 0});
    EXPECT_NEAR(r[r.size() / 2], std::sqrt(3.0), 0.1);
    EXPECT_GT(r.back(), 1000.0);
}

TEST(Generators, LogRadialSpansTwelveDecadesEvenly) {
    const auto r = sortedRadii(generatePoints(Generator::LogRadial, 1 << 14, 1), {0, 0});
    EXPECT_LT(r.front(), 1e-11);
    EXPECT_GT(r.back(), 0.1);
    EXPECT_LE(r.back(), 1.0);
    // A twelfth of the points per decade: the median is near 1e-6.
    EXPECT_GT(r[r.size() / 2], 1e-7);
    EXPECT_LT(r[r.size() / 2], 1e-5);
}

TEST(Generators, DiscInBoxPutsNineTenthsInTheDisc) {
    const auto r = sortedRadii(generatePoints(Generator::DiscInBox, 10000, 1), {800, 800});
    const auto inDisc = std::upper_bound(r.begin(), r.end(), 4.0) - r.begin();
    EXPECT_NEAR(static_cast<double>(inDisc) / 10000, 0.9, 0.02);
    EXPECT_GT(r.back(), 400.0);
}

TEST(Generators, UnevenClustersDifferInSizeAndSpread) {
    // Half the points in one cluster, a quarter in the next, ..., spreads from 0.001 to 100: the
    // nearest-neighbour distances span decades (uniform, Gaussian and equal clusters: a ratio
    // of 4 to 9 between the 90th and the 10th percentile).
    const auto pts = generatePoints(Generator::UnevenClusters, 4096, 2);
    std::vector<double> nearest;
    for (std::size_t i = 0; i < pts.size(); i += 16) {
        double best = INFINITY;
        for (std::size_t j = 0; j < pts.size(); ++j) {
            if (j != i) best = std::min(best, std::hypot(pts[i].x - pts[j].x, pts[i].y - pts[j].y));
        }
        nearest.push_back(best);
    }
    std::sort(nearest.begin(), nearest.end());
    EXPECT_GT(nearest[nearest.size() * 9 / 10] / nearest[nearest.size() / 10], 30.0);
}
