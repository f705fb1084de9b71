// Meshes far from Delaunay for the tests of the checker, the repair and the Check tab: random
// legal flips (of edges whose quadrilateral is strictly convex) of a valid triangulation keep it
// valid and make it non-Delaunay.
#pragma once

#include "core/engine/mesh.h"
#include "core/engine/predicates.h"

#include <cstdint>
#include <random>

namespace dlab::test {

// Flips the edge opposite corner c in place (the inserter's flip: V[p(c)] = V[O[c]] and
// V[p(O[c])] = V[c]).
inline void flipEdge(Mesh& m, std::int32_t c) {
    const std::int32_t d = m.O[c], cn = next(c), cp = prev(c), dn = next(d), dp = prev(d);
    const std::int32_t ocn = m.O[cn], odn = m.O[dn];
    m.V[cp] = m.V[d];
    m.V[dp] = m.V[c];
    const auto link = [&](std::int32_t a, std::int32_t b) {
        m.O[a] = b;
        if (b != kNone) m.O[b] = a;
    };
    link(c, odn);
    link(d, ocn);
    link(cn, dn);
}

// `tries` random corners; each whose edge can be flipped legally is. Returns the flips made.
inline int scrambleByLegalFlips(Mesh& m, unsigned seed, int tries) {
    std::mt19937 rng(seed);
    int flipped = 0;
    for (int i = 0; i < tries; ++i) {
        const std::int32_t c = static_cast<std::int32_t>(rng() % m.V.size());
        const std::int32_t d = m.O[c];
        if (d == kNone) continue;
        const Vec2 P = m.point(c), A = m.point(next(c)), B = m.point(prev(c)), D = m.point(d);
        if (orient2d(P, A, D) <= 0 || orient2d(D, B, P) <= 0) continue;
        flipEdge(m, c);
        ++flipped;
    }
    return flipped;
}

}  // namespace dlab::test
