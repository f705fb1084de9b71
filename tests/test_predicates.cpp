// orient2d and incircle against GMP rationals: random, near-degenerate (ulp perturbations of
// collinear and cocircular points), large offsets, and coordinates whose products under- or
// overflow double.
#include "core/engine/predicates.h"
#include "tests/exact_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

using dlab::incircle;
using dlab::incircleReport;
using dlab::orient2d;
using dlab::orient2dReport;
using dlab::PredicateTier;
using dlab::Vec2;

namespace {

// Walks x by k ulps (k may be negative).
double ulps(double x, int k) {
    const double dir =
        k < 0 ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
    for (int i = 0; i < std::abs(k); ++i) x = std::nextafter(x, dir);
    return x;
}

// Checks both predicates on every permutation that should keep or flip the sign.
void expectOrient(Vec2 a, Vec2 b, Vec2 c) {
    const int expected = orientGmp(a, b, c);
    ASSERT_EQ(orient2d(a, b, c), expected)
        << a.x << "," << a.y << " " << b.x << "," << b.y << " " << c.x << "," << c.y;
    ASSERT_EQ(orient2d(b, c, a), expected);
    ASSERT_EQ(orient2d(b, a, c), -expected);
    const auto r = orient2dReport(a, b, c);
    ASSERT_EQ(r.exactSign, expected);
}

void expectIncircle(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
    const int expected = incircleGmp(a, b, c, d);
    ASSERT_EQ(incircle(a, b, c, d), expected)
        << a.x << "," << a.y << " " << b.x << "," << b.y << " " << c.x << "," << c.y << " " << d.x
        << "," << d.y;
    ASSERT_EQ(incircle(b, c, a, d), expected);
    ASSERT_EQ(incircle(b, a, c, d), -expected);
    const auto r = incircleReport(a, b, c, d);
    ASSERT_EQ(r.exactSign, expected);
}

}  // namespace

TEST(Predicates, SignConventions) {
    const Vec2 o{0, 0}, x{1, 0}, y{0, 1};
    EXPECT_EQ(orient2d(o, x, y), 1);   // counter-clockwise
    EXPECT_EQ(orient2d(o, y, x), -1);  // clockwise
    EXPECT_EQ(orient2d(o, x, Vec2{2, 0}), 0);
    EXPECT_EQ(orient2d(o, o, x), 0);
    EXPECT_EQ(incircle(o, x, y, Vec2{0.4, 0.4}), 1);   // inside
    EXPECT_EQ(incircle(o, x, y, Vec2{2, 2}), -1);      // outside
    EXPECT_EQ(incircle(o, x, y, Vec2{1, 1}), 0);       // on the circle
    EXPECT_EQ(incircle(o, y, x, Vec2{0.4, 0.4}), -1);  // clockwise triangle flips the sign
}

TEST(Predicates, RandomPointsMatchGmp) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 20000; ++i) {
        const Vec2 a{u(rng), u(rng)}, b{u(rng), u(rng)}, c{u(rng), u(rng)}, d{u(rng), u(rng)};
        expectOrient(a, b, c);
        expectIncircle(a, b, c, d);
    }
}

// Kettner et al.'s classic failure of the naive predicate: a 256x256 grid of ulp steps near a
// point of the line y = x. The plain floating-point determinant gets many of these wrong.
TEST(Predicates, UlpGridNearALineMatchesGmp) {
    const Vec2 q{12, 12}, r{24, 24};
    int naiveWrong = 0, decidedExactly = 0;
    for (int i = 0; i < 256; ++i) {
        for (int j = 0; j < 256; ++j) {
            const Vec2 p{ulps(0.5, i), ulps(0.5, j)};
            expectOrient(p, q, r);
            const auto rep = orient2dReport(p, q, r);
            naiveWrong += rep.naiveSign != rep.exactSign;
            decidedExactly += rep.tier != PredicateTier::Filter;
        }
    }
    EXPECT_GT(naiveWrong, 100) << "the test should include cases where plain doubles fail";
    EXPECT_GT(decidedExactly, naiveWrong);
}

// Four exactly cocircular points (an integer circle of radius 5 and 25), each coordinate moved by
// -2..2 ulps: inside, outside and on the circle all occur and must all be exact.
TEST(Predicates, UlpPerturbedCocircularPointsMatchGmp) {
    const std::vector<Vec2> circle5 = {{5, 0}, {3, 4}, {0, 5}, {-4, 3}, {-3, -4}, {4, -3}};
    int signs[3] = {0, 0, 0};
    for (double scale : {1.0, 5.0, 1e-3, 1e7}) {
        for (int k = -2; k <= 2; ++k) {
            for (int m = -2; m <= 2; ++m) {
                const Vec2 a{circle5[0].x * scale, circle5[0].y * scale};
                const Vec2 b{circle5[1].x * scale, circle5[1].y * scale};
                const Vec2 c{circle5[2].x * scale, circle5[2].y * scale};
                for (std::size_t i = 3; i < circle5.size(); ++i) {
                    const Vec2 d{ulps(circle5[i].x * scale, k), ulps(circle5[i].y * scale, m)};
                    expectIncircle(a, b, c, d);
                    ++signs[incircle(a, b, c, d) + 1];
                }
            }
        }
    }
    EXPECT_GT(signs[0], 0);
    EXPECT_GT(signs[1], 0);
    EXPECT_GT(signs[2], 0);
}

TEST(Predicates, NearlyCollinearAndCocircularRandomMatchGmp) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0), angle(0.0, 6.283185307179586);
    std::uniform_int_distribution<int> k(-3, 3);
    for (int i = 0; i < 5000; ++i) {
        // Points on a line through a and b, rounded to doubles, then nudged by a few ulps.
        const Vec2 a{u(rng), u(rng)}, b{u(rng), u(rng)};
        const double t = u(rng) * 4;
        const Vec2 c{ulps(a.x + t * (b.x - a.x), k(rng)), ulps(a.y + t * (b.y - a.y), k(rng))};
        expectOrient(a, b, c);
        // Points on a circle, rounded to doubles, then nudged.
        const double cx = u(rng), cy = u(rng), rad = 0.5 + u(rng) * 0.25;
        Vec2 p[4];
        for (Vec2& q : p) {
            const double th = angle(rng);
            q = {ulps(cx + rad * std::cos(th), k(rng)), ulps(cy + rad * std::sin(th), k(rng))};
        }
        expectIncircle(p[0], p[1], p[2], p[3]);
    }
}

TEST(Predicates, LargeOffsetsMatchGmp) {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> tiny(-1.0, 1.0);
    for (double offset : {1e9, -1e9, 1e15, 3e17}) {
        for (int i = 0; i < 3000; ++i) {
            auto pt = [&] {
                return Vec2{offset + tiny(rng) * std::fabs(offset) * 1e-12, offset + tiny(rng)};
            };
            const Vec2 a = pt(), b = pt(), c = pt(), d = pt();
            expectOrient(a, b, c);
            expectIncircle(a, b, c, d);
        }
        // Exactly collinear on a large offset: a grid of spacing 1 at 1e9 + i.
        const Vec2 a{offset, offset}, b{offset + 1024, offset + 1024},
            c{offset + 4096, offset + 4096};
        expectOrient(a, b, c);
    }
}

TEST(Predicates, HugeAndTinyMagnitudesNeverGiveAWrongSign) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::uniform_int_distribution<int> k(-2, 2);
    const double mags[] = {1e-300, 1e-200, 1e-160, 1e-100, 1.0,    1e100,
                           1e160,  1e200,  1e300,  5e-324, 1.7e308};
    for (double m : mags) {
        for (int i = 0; i < 500; ++i) {
            auto pt = [&] { return Vec2{u(rng) * m, u(rng) * m}; };
            const Vec2 a = pt(), b = pt(), c = pt(), d = pt();
            expectOrient(a, b, c);
            expectIncircle(a, b, c, d);
            // Degenerate at this scale: the cocircular 3-4-5 circle, nudged.
            const double s = m / 8;  // (5s)^2 stays finite for every m here
            const Vec2 e{5 * s, 0}, f{3 * s, 4 * s}, g{0, 5 * s};
            const Vec2 h{ulps(-4 * s, k(rng)), ulps(3 * s, k(rng))};
            expectIncircle(e, f, g, h);
        }
    }
    // Mixed magnitudes in one call: expansions cannot hold these, big integers must.
    for (int i = 0; i < 500; ++i) {
        const double s = mags[i % 11], t = mags[(i * 7 + 3) % 11];
        const Vec2 a{u(rng) * s, u(rng) * t}, b{u(rng) * t, u(rng) * s}, c{u(rng) * s, u(rng) * s},
            d{u(rng) * t, u(rng) * t};
        expectOrient(a, b, c);
        expectIncircle(a, b, c, d);
    }
}

TEST(Predicates, ExtremeExponentSpansUseBigIntegers) {
    // 1e-300 next to 1e300: exact, and decided by the big-integer tier.
    const Vec2 a{1e-300, 0}, b{1e300, 1e-300}, c{-1e300, -1e-300};
    expectOrient(a, b, c);
    EXPECT_EQ(orient2dReport(a, b, c).tier, PredicateTier::BigInteger);
    // Exactly collinear through the origin at wildly different scales.
    const Vec2 o{0, 0}, p{1e-300, 2e-300}, q{1e300, 2e300};
    EXPECT_EQ(orient2d(o, p, q), orientGmp(o, p, q));
    // A circle through the origin with a point 1e-310 away from it, subnormal.
    const Vec2 w{1e200, 0}, x{0, 1e200}, y{1e200, 1e200}, z{5e-324, 5e-324};
    expectIncircle(w, x, y, z);
    EXPECT_EQ(incircleReport(w, x, y, z).tier, PredicateTier::BigInteger);
    EXPECT_EQ(incircle(w, y, x, z),
              1);  // counter-clockwise; (tiny, tiny) is just inside the circle through 0
}

TEST(Predicates, FilterDecidesOrdinaryCallsAndCountsTheRest) {
    auto& counters = dlab::predicateCounters();
    const auto before = counters;
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(0.0, 1600.0);
    for (int i = 0; i < 1000; ++i) {
        const Vec2 a{u(rng), u(rng)}, b{u(rng), u(rng)}, c{u(rng), u(rng)}, d{u(rng), u(rng)};
        orient2d(a, b, c);
        incircle(a, b, c, d);
        EXPECT_EQ(orient2dReport(a, b, c).tier, PredicateTier::Filter);
    }
    EXPECT_LE(counters.orientExact - before.orientExact, 5u);
    // A cocircular call on an integer grid cannot be decided by the filter.
    const auto r = incircleReport({0, 0}, {2, 0}, {2, 2}, {0, 2});
    EXPECT_EQ(r.exactSign, 0);
    EXPECT_EQ(r.tier, PredicateTier::Expansion);
    EXPECT_GE(r.errorBound, std::fabs(r.approx));
    const auto c0 = counters.incircleExact;
    incircle({0, 0}, {2, 0}, {2, 2}, {0, 2});
    EXPECT_EQ(counters.incircleExact, c0 + 1);
}
