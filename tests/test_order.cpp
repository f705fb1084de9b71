// Insertion orders: permutations, the same order for the same seed, the Hilbert tables against
// the textbook conversion, and BRIO's walks staying short whatever the density of the points.
#include "core/engine/generators.h"
#include "core/engine/inserter.h"
#include "core/engine/order.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <utility>

using namespace dlab;

namespace {

// The textbook conversion from cell to position on the curve (rotate the quadrant at every
// level), written from the curve's definition: it shares nothing with the library's tables.
std::uint64_t referenceHilbert(std::uint32_t x, std::uint32_t y, int bits) {
    const std::uint32_t n = 1u << bits;
    std::uint64_t d = 0;
    for (std::uint32_t s = n / 2; s > 0; s /= 2) {
        const std::uint32_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
        d += std::uint64_t{s} * s * ((3 * rx) ^ ry);
        if (ry == 0) {
            if (rx == 1) {
                x = n - 1 - x;
                y = n - 1 - y;
            }
            std::swap(x, y);
        }
    }
    return d;
}

// The curve entered in `state` is the state-0 curve of the cell mirrored through the centre
// (bit 1) and then across the diagonal (bit 0).
std::uint64_t referenceHilbert16(std::uint32_t x, std::uint32_t y, std::uint32_t state) {
    if (state & 2u) {
        x ^= 0xFFFFu;
        y ^= 0xFFFFu;
    }
    if (state & 1u) std::swap(x, y);
    return referenceHilbert(x, y, 16);
}

}  // namespace

TEST(Order, EveryKindIsAPermutation) {
    for (Generator g : allGenerators()) {
        const auto pts = generatePoints(g, 5000, 1);
        for (OrderKind k : {OrderKind::Input, OrderKind::Random, OrderKind::Brio}) {
            SCOPED_TRACE(std::string(toString(g)) + "/" + toString(k));
            auto order = insertionOrder(pts, k, 3);
            std::sort(order.begin(), order.end());
            for (std::int32_t i = 0; i < 5000; ++i) ASSERT_EQ(order[i], i);
        }
    }
}

TEST(Order, TheSameSeedGivesTheSameOrder) {
    for (Generator g : {Generator::Uniform, Generator::LogRadial, Generator::NearDuplicates}) {
        const auto pts = generatePoints(g, 20000, 2);
        for (OrderKind k : {OrderKind::Random, OrderKind::Brio}) {
            SCOPED_TRACE(std::string(toString(g)) + "/" + toString(k));
            const auto a = insertionOrder(pts, k, 7);
            EXPECT_EQ(a, insertionOrder(pts, k, 7));
            EXPECT_NE(a, insertionOrder(pts, k, 8));
        }
    }
}

TEST(Order, TwoThreadsSortToTheOneThreadOrder) {
    // Large enough for the second thread; every generator, so that crowded cells (lattices,
    // near-duplicates, clusters) and cells cut near the middle of the records are met.
    for (Generator g : allGenerators()) {
        for (std::size_t n : {std::size_t{1} << 16, std::size_t{200003}}) {
            SCOPED_TRACE(std::string(toString(g)) + " " + std::to_string(n));
            const auto pts = generatePoints(g, n, 4);
            EXPECT_EQ(insertionOrder(pts, OrderKind::Brio, 9, 2),
                      insertionOrder(pts, OrderKind::Brio, 9, 1));
        }
    }
    // All points equal: one cell holds them all and the middle cannot fall inside it.
    const std::vector<Vec2> same(100000, Vec2{0.5, -3});
    EXPECT_EQ(insertionOrder(same, OrderKind::Brio, 1, 2),
              insertionOrder(same, OrderKind::Brio, 1));
}

TEST(Order, SplitMixSkipsAsManyNumbersAsItIsAskedTo) {
    SplitMix64 a(42), b(42);
    for (int i = 0; i < 1000; ++i) a.next();
    b.discard(1000);
    EXPECT_EQ(a.next(), b.next());
}

TEST(Order, HilbertIndexFollowsTheCurveOneLevelAtATime) {
    EXPECT_EQ(hilbertIndex(0, 0, 1), 0u);
    EXPECT_EQ(hilbertIndex(0, 1, 1), 1u);
    EXPECT_EQ(hilbertIndex(1, 1, 1), 2u);
    EXPECT_EQ(hilbertIndex(1, 0, 1), 3u);
    for (std::uint32_t x = 0; x < 64; ++x) {
        for (std::uint32_t y = 0; y < 64; ++y)
            ASSERT_EQ(hilbertIndex(x, y, 6), referenceHilbert(x, y, 6));
    }
}

TEST(Order, HilbertTableMatchesTheTextbookCurveInEveryState) {
    SplitMix64 rng(11);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> cells = {
        {0, 0}, {0xFFFF, 0xFFFF}, {0, 0xFFFF}, {0xFFFF, 0}, {0x8000, 0x7FFF}, {0x7FFF, 0x8000}};
    for (int i = 0; i < 200000; ++i) {
        const std::uint64_t r = rng.next();
        cells.emplace_back(static_cast<std::uint32_t>(r & 0xFFFF),
                           static_cast<std::uint32_t>((r >> 16) & 0xFFFF));
    }
    for (const auto& [x, y] : cells) {
        for (std::uint32_t state = 0; state < 4; ++state) {
            ASSERT_EQ(hilbertIndex16(x, y, state), referenceHilbert16(x, y, state))
                << "cell (" << x << ", " << y << "), state " << state;
        }
        ASSERT_EQ(hilbertIndex16(x, y), hilbertIndex(x, y, 16));
    }
}

TEST(Order, HilbertStateAfterContinuesTheCurveInsideASubSquare) {
    // Split 16 levels into 8 + 8: the index of the coarse sub-square, then the index inside it
    // on the curve entered in the state hilbertStateAfter gives, make the full index.
    SplitMix64 rng(12);
    for (int i = 0; i < 100000; ++i) {
        const std::uint64_t r = rng.next();
        const std::uint32_t x = r & 0xFFFF, y = (r >> 16) & 0xFFFF,
                            state = static_cast<std::uint32_t>(r >> 32) & 3u;
        const std::uint32_t coarse = hilbertIndex16(x & 0xFF00, y & 0xFF00, state) >> 16;
        const std::uint32_t inner = hilbertStateAfter(state, coarse, 8);
        const std::uint32_t fine = hilbertIndex16((x & 0xFF) << 8, (y & 0xFF) << 8, inner) >> 16;
        ASSERT_EQ(hilbertIndex16(x, y, state), (coarse << 16) | fine)
            << "cell (" << x << ", " << y << "), state " << state;
    }
}

TEST(Order, BrioWalksAreShortWhateverTheDensity) {
    // Points that crowd into a few cells of a grid over the bounding box (a heavy tail, radii
    // over 12 decades, a dense disc in a sparse box) must still be sorted along the curve, or
    // each walk crosses the whole crowd. Points on curves are left out: there every walk
    // crosses fans of thin triangles, ~5 steps on a line of evenly spaced points in any order.
    for (Generator g : {Generator::Uniform, Generator::Gaussian, Generator::Clusters,
                        Generator::UnevenClusters, Generator::Kuzmin, Generator::LogRadial,
                        Generator::DiscInBox, Generator::Grid, Generator::RotatedGrid}) {
        SCOPED_TRACE(toString(g));
        Inserter ins(generatePoints(g, 1 << 14, 3));
        ins.run();
        EXPECT_LT(static_cast<double>(ins.stats().walkSteps) / (1 << 14), 4.0);
    }
}
