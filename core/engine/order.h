// Insertion orders: input, seeded random, and BRIO (biased randomized insertion order) with a
// Hilbert sort inside each round that refines the grid wherever points crowd.
#pragma once

#include "core/engine/enum_names.h"
#include "core/engine/geometry.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace dlab {

enum class OrderKind : std::uint8_t { Input, Random, Brio };

inline constexpr std::array<EnumName<OrderKind>, 3> kOrderNames{
    {{OrderKind::Input, "input"}, {OrderKind::Random, "random"}, {OrderKind::Brio, "brio"}}};
const char* toString(OrderKind kind);
std::optional<OrderKind> parseOrderKind(std::string_view name);

// A permutation of [0, points.size()). Deterministic for a given seed on every platform
// (our own generator and shuffle: std::shuffle's result is implementation-defined). BRIO's
// sorts may use two threads (`threads` > 1, large sets): the order is the same.
std::vector<std::int32_t> insertionOrder(const std::vector<Vec2>& points, OrderKind kind,
                                         std::uint64_t seed, int threads = 1);

// Position of (x, y) along a Hilbert curve filling a 2^bits x 2^bits grid (bits <= 16), one
// level at a time.
std::uint32_t hilbertIndex(std::uint32_t x, std::uint32_t y, int bits);
// The same for bits = 16, four levels a table lookup; `state` (0..3) is the orientation the
// curve enters the grid in (0: from the lower left, leaving at the lower right), so that a cell's
// points can be sorted along the piece of the curve that passes through it.
std::uint32_t hilbertIndex16(std::uint32_t x, std::uint32_t y, std::uint32_t state = 0);
// The state the curve, entered in `state`, has inside the sub-square at `index` of a
// 2^levels x 2^levels grid: hilbertIndex16 of a point in that sub-square continues with it.
std::uint32_t hilbertStateAfter(std::uint32_t state, std::uint32_t index, int levels);

// SplitMix64: a tiny, well-mixed, portable generator for seeds and shuffles.
class SplitMix64 {
public:
    explicit SplitMix64(std::uint64_t seed) : m_state(seed) {}
    std::uint64_t next() {
        std::uint64_t z = (m_state += kGamma);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    // Uniform in [0, bound) without modulo bias worth noticing for bound < 2^32.
    std::uint32_t below(std::uint32_t bound) {
        return static_cast<std::uint32_t>(((next() >> 32) * bound) >> 32);
    }
    double uniform01() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    // Skips the next k numbers (the state only counts).
    void discard(std::uint64_t k) { m_state += k * kGamma; }

private:
    static constexpr std::uint64_t kGamma = 0x9E3779B97F4A7C15ull;
    std::uint64_t m_state;
};

}  // namespace dlab
