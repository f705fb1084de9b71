// Insertion orders. BRIO (Amenta, Choi, Rote): rounds of geometrically growing size drawn at
// random, each round sorted along a Hilbert curve, so that consecutive points are close (short
// walks) while the rounds keep the expected-case guarantees of a random order.
#include "core/engine/order.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>

namespace dlab {

const char* toString(OrderKind kind) {
    switch (kind) {
        case OrderKind::Input: return "input";
        case OrderKind::Random: return "random";
        case OrderKind::Brio: return "brio";
    }
    return "?";
}

std::optional<OrderKind> parseOrderKind(std::string_view name) {
    if (name == "input") return OrderKind::Input;
    if (name == "random") return OrderKind::Random;
    if (name == "brio") return OrderKind::Brio;
    return std::nullopt;
}

namespace {

// One level of the curve, from the coarsest down. The sub-square's digit depends on the bits
// seen through the rotation/reflection accumulated so far: 2 bits of state (bit 0 swap, bit 1
// reflect). Written without branches: a branchy version mispredicts on almost every level.
struct HilbertLevel {
    std::uint32_t digit;
    std::uint32_t state;
};

constexpr HilbertLevel hilbertLevel(std::uint32_t state, std::uint32_t xBit, std::uint32_t yBit) {
    const std::uint32_t swap = state & 1u, reflect = state >> 1;
    const std::uint32_t bx = xBit ^ reflect, by = yBit ^ reflect;
    const std::uint32_t rx = swap ? by : bx, ry = swap ? bx : by;
    const std::uint32_t turn = ry ^ 1u;  // lower-left or lower-right quadrant
    return {(3u * rx) ^ ry, (swap ^ turn) | ((reflect ^ (turn & rx)) << 1)};
}

// Four levels at once: entry [state][x nibble][y nibble] = 8 digit bits | next state << 8.
// The level loop is one long chain of dependent bit operations (it was most of the BRIO
// order's time at a million points); four table lookups give the same digits.
constexpr std::array<std::uint16_t, 4 * 256> kHilbertNibbles = [] {
    std::array<std::uint16_t, 4 * 256> table{};
    for (std::uint32_t state = 0; state < 4; ++state) {
        for (std::uint32_t x = 0; x < 16; ++x) {
            for (std::uint32_t y = 0; y < 16; ++y) {
                std::uint32_t s = state, d = 0;
                for (int i = 3; i >= 0; --i) {
                    const HilbertLevel level = hilbertLevel(s, (x >> i) & 1u, (y >> i) & 1u);
                    d = (d << 2) | level.digit;
                    s = level.state;
                }
                table[(state << 8) | (x << 4) | y] = static_cast<std::uint16_t>(d | (s << 8));
            }
        }
    }
    return table;
}();

// hilbertIndex(x, y, 16) by table.
std::uint32_t hilbertIndex16(std::uint32_t x, std::uint32_t y) {
    std::uint32_t state = 0, d = 0;
    for (int i = 12; i >= 0; i -= 4) {
        const std::uint32_t e =
            kHilbertNibbles[(state << 8) | (((x >> i) & 15u) << 4) | ((y >> i) & 15u)];
        d = (d << 8) | (e & 0xFFu);
        state = e >> 8;
    }
    return d;
}

}  // namespace

std::uint32_t hilbertIndex(std::uint32_t x, std::uint32_t y, int bits) {
    std::uint32_t state = 0, d = 0;
    for (int i = bits - 1; i >= 0; --i) {
        const HilbertLevel level = hilbertLevel(state, (x >> i) & 1u, (y >> i) & 1u);
        d = (d << 2) | level.digit;
        state = level.state;
    }
    return d;
}

namespace {

void shuffle(std::vector<std::int32_t>& v, SplitMix64& rng) {
    for (std::size_t i = v.size(); i > 1; --i) {
        const std::size_t j = rng.below(static_cast<std::uint32_t>(i));
        std::swap(v[i - 1], v[j]);
    }
}

// Stable LSD radix sort of (key << 32 | index) records by their upper 32 bits, in three
// passes of 11, 11 and 10 bits; returns the indices. Three passes over 2048 buckets beat two
// over 65536: those scatter into more open cache lines than the L2 holds. count[pass] must hold
// the digit histograms of rec (the caller fills them while it makes the keys).
constexpr int kRadixBits = 11;
constexpr std::uint32_t kRadixMask = (1u << kRadixBits) - 1;
using RadixCounts = std::array<std::array<std::uint32_t, 1u << kRadixBits>, 3>;

std::uint32_t radixDigit(std::uint64_t r, int pass) {
    return static_cast<std::uint32_t>(r >> (32 + kRadixBits * pass)) & kRadixMask;
}

std::vector<std::int32_t> radixSortByKey(std::vector<std::uint64_t>& rec, RadixCounts& count) {
    for (auto& c : count) {  // exclusive prefix sums: each bucket's first slot
        std::uint32_t sum = 0;
        for (std::uint32_t& x : c) {
            const std::uint32_t k = x;
            x = sum;
            sum += k;
        }
    }
    std::vector<std::uint64_t> tmp(rec.size());
    for (std::uint64_t r : rec) tmp[count[0][radixDigit(r, 0)]++] = r;
    for (std::uint64_t r : tmp) rec[count[1][radixDigit(r, 1)]++] = r;
    tmp = {};
    std::vector<std::int32_t> order(rec.size());
    for (std::uint64_t r : rec)
        order[count[2][radixDigit(r, 2)]++] = static_cast<std::int32_t>(r & 0xFFFFFFFFu);
    return order;
}

std::vector<std::int32_t> brio(const std::vector<Vec2>& points, SplitMix64& rng) {
    const std::size_t n = points.size();
    if (n < 64) {
        std::vector<std::int32_t> order(n);
        std::iota(order.begin(), order.end(), 0);
        shuffle(order, rng);
        return order;
    }
    double minX = points[0].x, maxX = minX, minY = points[0].y, maxY = minY;
    for (const Vec2& p : points) {
        minX = std::min(minX, p.x);
        maxX = std::max(maxX, p.x);
        minY = std::min(minY, p.y);
        maxY = std::max(maxY, p.y);
    }
    // Each point draws its round: the last round (15) with probability 1/2, the one before
    // with 1/4, ..., round 0 takes the rest. The sort key is (round, Hilbert index on a
    // 2^14 x 2^14 grid), so one radix sort over the points in input order (no random
    // gathers, which cost more than everything else at a million points) gives the order.
    constexpr int kBits = 14;
    static constexpr double kCells = (1 << kBits) - 1;
    // Scale each axis to [0, 2^14 - 1]; the span is computed as a difference of halves so
    // that it cannot overflow for coordinates near the largest doubles.
    const double spanX = maxX / 2 - minX / 2, spanY = maxY / 2 - minY / 2;
    // Capped: a subnormal span (points near 1e-310) would make the scale inf, and 0 * inf a NaN
    // cell whose conversion to an integer is undefined.
    constexpr double kMaxScale = std::numeric_limits<double>::max();
    const double sx = spanX > 0 ? std::min(kCells / 2 / spanX, kMaxScale) : 0.0;
    const double sy = spanY > 0 ? std::min(kCells / 2 / spanY, kMaxScale) : 0.0;
    auto cell = [](double v) { return static_cast<std::uint32_t>(std::clamp(v, 0.0, kCells)); };

    // hilbertIndex(x, y, 14) is hilbertIndex16(4x, 4y) without its last two levels.
    std::vector<std::uint64_t> rec(n);
    RadixCounts count{};
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2& p = points[i];
        const std::uint64_t r = rng.next();
        const int zeros = r == 0 ? 64 : std::countr_zero(r);
        const std::uint32_t round = 15u - static_cast<std::uint32_t>(std::min(zeros, 15));
        const std::uint32_t cx = cell((p.x / 2 - minX / 2) * sx),
                            cy = cell((p.y / 2 - minY / 2) * sy);
        const std::uint32_t key = (round << 28) | (hilbertIndex16(cx << 2, cy << 2) >> 4);
        rec[i] = (std::uint64_t{key} << 32) | static_cast<std::uint32_t>(i);
        for (int pass = 0; pass < 3; ++pass) ++count[pass][radixDigit(rec[i], pass)];
    }
    return radixSortByKey(rec, count);
}

}  // namespace

std::vector<std::int32_t> insertionOrder(const std::vector<Vec2>& points, OrderKind kind,
                                         std::uint64_t seed) {
    SplitMix64 rng(seed);
    switch (kind) {
        case OrderKind::Input: {
            std::vector<std::int32_t> order(points.size());
            std::iota(order.begin(), order.end(), 0);
            return order;
        }
        case OrderKind::Random: {
            std::vector<std::int32_t> order(points.size());
            std::iota(order.begin(), order.end(), 0);
            shuffle(order, rng);
            return order;
        }
        case OrderKind::Brio: return brio(points, rng);
    }
    return {};
}

}  // namespace dlab
