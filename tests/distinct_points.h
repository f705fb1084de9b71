// The tests' point sets without repeats: each point once, first copies first, in input order
// (then every id is a vertex, and a removed vertex leaves no equal point behind).
#pragma once

#include "core/engine/geometry.h"

#include <set>
#include <utility>
#include <vector>

namespace dlab::testutil {

inline std::vector<Vec2> distinct(const std::vector<Vec2>& pts) {
    std::vector<Vec2> out;
    std::set<std::pair<double, double>> seen;
    for (const Vec2 p : pts) {
        if (seen.insert({p.x, p.y}).second) out.push_back(p);
    }
    return out;
}

}  // namespace dlab::testutil
