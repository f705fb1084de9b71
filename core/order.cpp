// Insertion orders. BRIO (Amenta, Choi, Rote): rounds of geometrically growing size drawn at
// random, each round sorted along a Hilbert curve, so that consecutive points are close (short
// walks) while the rounds keep the expected-case guarantees of a random order.
#include "core/order.h"

#include <algorithm>
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
    // Walk the quadrants from the coarsest level down; in each, rotate/reflect the remaining
    // coordinates so that the sub-curve has the standard orientation.
    std::uint32_t d = 0;
    for (std::uint32_t s = 1u << (bits - 1); s > 0; s >>= 1) {
        const std::uint32_t rx = (x & s) ? 1u : 0u;
        const std::uint32_t ry = (y & s) ? 1u : 0u;
        d += s * s * ((3u * rx) ^ ry);
        if (ry == 0) {
            if (rx == 1) {
                x = s - 1 - (x & (s - 1)) + (x & ~(s - 1));
                y = s - 1 - (y & (s - 1)) + (y & ~(s - 1));
            }
            std::swap(x, y);
        }
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
    std::vector<std::int32_t> order(n);
    std::iota(order.begin(), order.end(), 0);
    shuffle(order, rng);
    if (n < 64) return order;

    double minX = points[0].x, maxX = minX, minY = points[0].y, maxY = minY;
    for (const Vec2& p : points) {
        minX = std::min(minX, p.x); maxX = std::max(maxX, p.x);
        minY = std::min(minY, p.y); maxY = std::max(maxY, p.y);
    }
    constexpr int kBits = 16;
    static constexpr double kCells = 65535.0;
    // Scale each axis to [0, 65535]; the span is computed as a difference of halves so that
    // it cannot overflow for coordinates near the largest doubles.
    const double spanX = maxX / 2 - minX / 2, spanY = maxY / 2 - minY / 2;
    const double sx = spanX > 0 ? kCells / 2 / spanX : 0.0;
    const double sy = spanY > 0 ? kCells / 2 / spanY : 0.0;
    auto cell = [](double v) {
        return static_cast<std::uint32_t>(std::clamp(v, 0.0, kCells));
    };

    // Rounds: the last holds about half the points, the one before a quarter, ...; the
    // first round (smallest) is at least 64 points.
    std::vector<std::size_t> bounds{n};
    while (bounds.back() > 128) bounds.push_back(bounds.back() / 2);
    bounds.push_back(0);
    std::reverse(bounds.begin(), bounds.end());

    std::vector<std::uint64_t> rec, tmp;
    for (std::size_t r = 0; r + 1 < bounds.size(); ++r) {
        const std::size_t lo = bounds[r], hi = bounds[r + 1];
        rec.resize(hi - lo);
        for (std::size_t i = lo; i < hi; ++i) {
            const Vec2& p = points[order[i]];
            const std::uint32_t key =
                hilbertIndex(cell((p.x / 2 - minX / 2) * sx), cell((p.y / 2 - minY / 2) * sy), kBits);
            rec[i - lo] = (std::uint64_t{key} << 32) | static_cast<std::uint32_t>(order[i]);
        }
        radixSortByKey(rec, tmp);
        for (std::size_t i = lo; i < hi; ++i) order[i] = static_cast<std::int32_t>(rec[i - lo] & 0xFFFFFFFFu);
    }
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
