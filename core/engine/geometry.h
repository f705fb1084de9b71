// Plain 2D point type shared by every layer of the core.
#pragma once

#include <cstddef>

namespace dlab {

// The most points anything takes, readers and engine alike: 2^25 = 33,554,432. The corner
// table indexes corners with int32: about 6n corners for n points, so 2^25 stays 10x below
// INT32_MAX, leaving room for ghost/super vertices and step-by-step journals. It is also a
// memory bound: ~64 bytes per point across G, V and O is about 2 GiB, the most a lab session
// should ask for. Readers refuse larger counts before any allocation, the Inserter on entry.
inline constexpr std::size_t kMaxPoints = std::size_t{1} << 25;

struct Vec2 {
    double x = 0.0;
    double y = 0.0;
    friend bool operator==(const Vec2&, const Vec2&) = default;
};

}  // namespace dlab
