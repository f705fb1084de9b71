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
    // A cocircular call on an integer grid cannot be decided by the filter; its differences are
    // exact, so the zero-tail stage decides it without expansions.
    const auto r = incircleReport({0, 0}, {2, 0}, {2, 2}, {0, 2});
    EXPECT_EQ(r.exactSign, 0);
    EXPECT_EQ(r.tier, PredicateTier::ZeroTail);
    EXPECT_GE(r.errorBound, std::fabs(r.approx));
    const auto c0 = counters.incircleExact;
    const auto z0 = counters.incircleByTier[static_cast<int>(PredicateTier::ZeroTail)];
    incircle({0, 0}, {2, 0}, {2, 2}, {0, 2});
    EXPECT_EQ(counters.incircleExact, c0 + 1);
    EXPECT_EQ(counters.incircleByTier[static_cast<int>(PredicateTier::ZeroTail)], z0 + 1);
}

namespace {

// Inputs that reach every stage: random (filter), lattice degeneracies (zero tail), ulp-nudged
// near-degeneracies off the lattice (stage B or expansions), exact degeneracies whose
// differences round (expansions) and exponent spans of hundreds of binades (big integers).
struct StageTally {
    int orient[dlab::kNumPredicateTiers] = {};
    int incircle[dlab::kNumPredicateTiers] = {};
};

void tallyOrient(StageTally& t, Vec2 a, Vec2 b, Vec2 c) {
    const auto r = orient2dReport(a, b, c);
    ASSERT_EQ(r.exactSign, orientGmp(a, b, c)) << dlab::toString(r.tier);
    ASSERT_EQ(orient2d(a, b, c), r.exactSign);
    ++t.orient[static_cast<int>(r.tier)];
}

void tallyIncircle(StageTally& t, Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
    const auto r = incircleReport(a, b, c, d);
    ASSERT_EQ(r.exactSign, incircleGmp(a, b, c, d)) << dlab::toString(r.tier);
    ASSERT_EQ(incircle(a, b, c, d), r.exactSign);
    ++t.incircle[static_cast<int>(r.tier)];
}

}  // namespace

TEST(Predicates, EveryStageDecidesSomeCallsAndAgreesWithGmp) {
    StageTally t;
    std::mt19937_64 rng(21);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::uniform_int_distribution<int> lattice(-6, 6), k(-3, 3);
    for (int i = 0; i < 4000; ++i) {
        const Vec2 a{u(rng), u(rng)}, b{u(rng), u(rng)}, c{u(rng), u(rng)}, d{u(rng), u(rng)};
        tallyOrient(t, a, b, c);
        tallyIncircle(t, a, b, c, d);
        // Lattice points: collinear triples and cocircular quadruples occur often.
        auto g = [&] { return Vec2{double(lattice(rng)), double(lattice(rng))}; };
        const Vec2 e = g(), f = g();
        tallyOrient(t, e, f, Vec2{2 * f.x - e.x, 2 * f.y - e.y});
        tallyIncircle(t, e, Vec2{f.x, e.y}, f, Vec2{e.x, f.y});
        // Stretched to about 18 bits: exact differences, too long for incircle in plain doubles.
        const double v = 16385;
        tallyOrient(t, {e.x * v, e.y}, {f.x * v, f.y}, {(2 * f.x - e.x) * v, 2 * f.y - e.y});
        tallyIncircle(t, {e.x * v, e.y * 3}, {f.x * v, e.y * 3}, {f.x * v, f.y * 3},
                      {e.x * v, f.y * 3});
        // The same on a lattice of wide span (2^40 steps): exact differences too long for the
        // plain double evaluation, so the zero-tail stage uses expansions.
        const double w = 0x1p40 + 1;
        tallyOrient(t, {e.x * w, e.y}, {f.x * w, f.y}, {(2 * f.x - e.x) * w, 2 * f.y - e.y});
        tallyIncircle(t, {e.x * w, e.y}, {f.x * w, e.y}, {f.x * w, f.y}, {e.x * w, f.y});
        // A rectangle at an offset whose differences round: exactly cocircular, and the
        // rounded differences still form a rectangle, so only the full expansion can say 0.
        const double x0 = u(rng), y0 = u(rng), x1 = x0 + 1 + u(rng), y1 = y0 + 3 + u(rng);
        tallyIncircle(t, {x0, y0}, {x1, y0}, {x1, y1}, {x0, y1});
        tallyOrient(t, {x0, x0}, {x1, x1}, {y1, y1});
        // Near-degenerate off the lattice: a line and a circle, nudged by ulps.
        const double s = u(rng) * 4;
        tallyOrient(t, a, b,
                    {ulps(a.x + s * (b.x - a.x), k(rng)), ulps(a.y + s * (b.y - a.y), k(rng))});
        Vec2 p[4];
        for (Vec2& q : p) {
            const double th = u(rng) * 3.14159;
            q = {ulps(x0 + 0.5 * std::cos(th), 1 + i % 8), y0 + 0.5 * std::sin(th)};
        }
        tallyIncircle(t, p[0], p[1], p[2], p[3]);
    }
    tallyOrient(t, {1e-300, 0}, {1e300, 1e-300}, {-1e300, -1e-300});
    tallyIncircle(t, {1e200, 0}, {0, 1e200}, {1e200, 1e200}, {5e-324, 5e-324});
    for (int tier = 0; tier < dlab::kNumPredicateTiers; ++tier) {
        const char* name = dlab::toString(static_cast<PredicateTier>(tier));
        EXPECT_GT(t.orient[tier], 0) << "orient2d never decided by " << name;
        EXPECT_GT(t.incircle[tier], 0) << "incircle never decided by " << name;
    }
}

TEST(Predicates, StageCountersSeeEachStage) {
    auto& counters = dlab::predicateCounters();
    // The one stage whose counter a call moved (-1: none, -2: several).
    auto stageOf = [&](auto call) {
        const auto before = counters;
        call();
        int moved = -1;
        for (int i = 0; i < dlab::kNumPredicateTiers; ++i) {
            const auto d = counters.orientByTier[i] - before.orientByTier[i] +
                           counters.incircleByTier[i] - before.incircleByTier[i];
            if (d != 0) moved = moved == -1 && d == 1 ? i : -2;
        }
        const auto past = counters.orientExact - before.orientExact + counters.incircleExact -
                          before.incircleExact;
        EXPECT_EQ(past, moved >= 0 ? 1u : 0u);
        return moved;
    };
    constexpr int kFilter = -1, kZeroTail = static_cast<int>(PredicateTier::ZeroTail),
                  kStageB = static_cast<int>(PredicateTier::StageB),
                  kExpansion = static_cast<int>(PredicateTier::Expansion),
                  kBig = static_cast<int>(PredicateTier::BigInteger);
    // The filter's hot path counts nothing.
    EXPECT_EQ(stageOf([] { orient2d({0, 0}, {1, 0}, {0, 1}); }), kFilter);
    // Zero tail: lattice degeneracies.
    EXPECT_EQ(stageOf([] { orient2d({0, 0}, {1, 1}, {3, 3}); }), kZeroTail);
    EXPECT_EQ(stageOf([] { incircle({0, 0}, {4, 0}, {4, 2}, {0, 2}); }), kZeroTail);
    // Expansions: exactly degenerate, with differences that round.
    EXPECT_EQ(stageOf([] { orient2d({0.1, 0.1}, {1.3, 1.3}, {7.7, 7.7}); }), kExpansion);
    EXPECT_EQ(stageOf([] {
                  incircle({0.1, 0.3}, {1.7, 0.3}, {1.7, 3.9}, {0.1, 3.9});
              }),
              kExpansion);
    // Big integers.
    EXPECT_EQ(stageOf([] { orient2d({1e-300, 0}, {1e300, 1e-300}, {-1e300, -1e-300}); }), kBig);
    EXPECT_EQ(stageOf([] {
                  incircle({1e200, 0}, {0, 1e200}, {1e200, 1e200}, {5e-324, 5e-324});
              }),
              kBig);
    // Stage B: a few ulps off a line or a circle, off the lattice: beyond the filter's reach but
    // not the exact determinant of the rounded differences'. The counter agrees with the report.
    int orientB = 0, incircleB = 0;
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 1; i < 400; ++i) {
        const Vec2 a{ulps(0.5, i), ulps(0.5, 3 * i + 1)}, q{12, 12}, r{24, 24};
        const int o = stageOf([&] { orient2d(a, q, r); });
        if (o >= 0) {
            EXPECT_EQ(o, static_cast<int>(orient2dReport(a, q, r).tier));
        }
        orientB += o == kStageB;
        Vec2 p[4];  // on a circle, nudged
        for (Vec2& v : p) {
            const double th = u(rng) * 3.14159;
            v = {ulps(0.3 + 0.5 * std::cos(th), 1 + i % 4), 0.2 + 0.5 * std::sin(th)};
        }
        const int c = stageOf([&] { incircle(p[0], p[1], p[2], p[3]); });
        if (c >= 0) {
            EXPECT_EQ(c, static_cast<int>(incircleReport(p[0], p[1], p[2], p[3]).tier));
        }
        incircleB += c == kStageB;
    }
    EXPECT_GT(orientB, 0);
    EXPECT_GT(incircleB, 0);
}
