// Insertion orders. BRIO (Amenta, Choi, Rote): rounds of geometrically growing size drawn at
// random, each round sorted along a Hilbert curve, so that consecutive points are close (short
// walks) while the rounds keep the expected-case guarantees of a random order.
#include "core/order.h"

#include <algorithm>
#include <bit>
#include <cmath>
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

std::uint32_t hilbertIndex(std::uint32_t x, std::uint32_t y, int bits) {
    // From the coarsest level down: the sub-square's digit depends on the bits seen through
    // the rotation/reflection accumulated so far (2 bits of state: swap, reflect). Written
    // without branches: the branchy version mispredicts on almost every level.
    std::uint32_t swap = 0, reflect = 0, d = 0;
    for (int i = bits - 1; i >= 0; --i) {
        const std::uint32_t bx = ((x >> i) & 1u) ^ reflect, by = ((y >> i) & 1u) ^ reflect;
        const std::uint32_t rx = swap ? by : bx, ry = swap ? bx : by;
        d = (d << 2) | ((3u * rx) ^ ry);
        const std::uint32_t turn = ry ^ 1u;  // lower-left or lower-right quadrant
        swap ^= turn;
        reflect ^= turn & rx;
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

// Stable LSD radix sort of (key << 32 | index) records by their upper 32 bits.
void radixSortByKey(std::vector<std::uint64_t>& rec, std::vector<std::uint64_t>& tmp) {
    tmp.resize(rec.size());
    for (int pass = 0; pass < 2; ++pass) {
        const int shift = 32 + 16 * pass;
        std::vector<std::uint32_t> count(65537, 0);
        for (std::uint64_t r : rec) ++count[((r >> shift) & 0xFFFF) + 1];
        for (std::size_t i = 1; i < count.size(); ++i) count[i] += count[i - 1];
        for (std::uint64_t r : rec) tmp[count[(r >> shift) & 0xFFFF]++] = r;
        rec.swap(tmp);
    }
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
        minX = std::min(minX, p.x); maxX = std::max(maxX, p.x);
        minY = std::min(minY, p.y); maxY = std::max(maxY, p.y);
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
    const double sx = spanX > 0 ? kCells / 2 / spanX : 0.0;
    const double sy = spanY > 0 ? kCells / 2 / spanY : 0.0;
    auto cell = [](double v) { return static_cast<std::uint32_t>(std::clamp(v, 0.0, kCells)); };

    std::vector<std::uint64_t> rec(n), tmp;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2& p = points[i];
        const std::uint64_t r = rng.next();
        const int zeros = r == 0 ? 64 : std::countr_zero(r);
        const std::uint32_t round = 15u - static_cast<std::uint32_t>(std::min(zeros, 15));
        const std::uint32_t key =
            (round << 28) | hilbertIndex(cell((p.x / 2 - minX / 2) * sx), cell((p.y / 2 - minY / 2) * sy), kBits);
        rec[i] = (std::uint64_t{key} << 32) | static_cast<std::uint32_t>(i);
    }
    radixSortByKey(rec, tmp);
    std::vector<std::int32_t> order(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::int32_t>(rec[i] & 0xFFFFFFFFu);
    return order;
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
