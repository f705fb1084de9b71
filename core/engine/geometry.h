// Plain 2D point type shared by every layer of the core.
#pragma once

namespace dlab {

struct Vec2 {
    double x = 0.0;
    double y = 0.0;
    friend bool operator==(const Vec2&, const Vec2&) = default;
};

}  // namespace dlab
