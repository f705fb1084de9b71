// The corner table (Rossignac): geometry G, corner->vertex V, corner->opposite corner O.
//
// Triangle t owns corners 3t, 3t+1, 3t+2, listed counter-clockwise in world coordinates
// (y up; the paper's "clockwise on screen"). O[c] is the corner facing c across the edge
// opposite c, in the neighbouring triangle; kNone on the boundary.
//
//          V[p(c)]
//            |  `.
//   l(c) --> |    `.   <-- o(c): across the edge opposite c
//            |  t   `.
//          V[c] ------ V[n(c)]
//                 ^ r(c): across the edge V[c]-V[n(c)]
//
// Looking from V[c] into its triangle, n(c) is on the right and p(c) on the left; the left
// neighbour lies across the edge V[c]-V[p(c)], the one opposite n(c).
// Our convention (stated in the UI too): l(c) = o(n(c)), r(c) = o(p(c)).
// Swing s(c) = n(l(c)) turns counter-clockwise around V[c]; unswing u(c) = p(r(c)) turns
// clockwise. Both return kNone when they would cross the boundary.
#pragma once

#include "core/engine/geometry.h"

#include <cstdint>
#include <string>
#include <vector>

namespace dlab {

inline constexpr std::int32_t kNone = -1;

inline constexpr std::int32_t tri(std::int32_t c) { return c / 3; }
inline constexpr std::int32_t next(std::int32_t c) { return c % 3 == 2 ? c - 2 : c + 1; }
inline constexpr std::int32_t prev(std::int32_t c) { return c % 3 == 0 ? c + 2 : c - 1; }
inline constexpr std::int32_t corner(std::int32_t t, std::int32_t i) { return 3 * t + i; }

struct Mesh {
    std::vector<Vec2> G;          // vertex coordinates
    std::vector<std::int32_t> V;  // vertex of each corner
    std::vector<std::int32_t> O;  // opposite corner of each corner, kNone on the boundary

    std::int32_t numVertices() const { return static_cast<std::int32_t>(G.size()); }
    std::int32_t numCorners() const { return static_cast<std::int32_t>(V.size()); }
    std::int32_t numTriangles() const { return numCorners() / 3; }

    // Rossignac's operators, named as in the paper.
    static std::int32_t t(std::int32_t c) { return tri(c); }
    static std::int32_t n(std::int32_t c) { return next(c); }
    static std::int32_t p(std::int32_t c) { return prev(c); }
    std::int32_t v(std::int32_t c) const { return V[c]; }
    std::int32_t o(std::int32_t c) const { return O[c]; }
    std::int32_t l(std::int32_t c) const { return O[next(c)]; }
    std::int32_t r(std::int32_t c) const { return O[prev(c)]; }
    std::int32_t s(std::int32_t c) const {
        const std::int32_t x = l(c);
        return x == kNone ? kNone : next(x);
    }
    std::int32_t u(std::int32_t c) const {
        const std::int32_t x = r(c);
        return x == kNone ? kNone : prev(x);
    }
    Vec2 point(std::int32_t c) const { return G[V[c]]; }
};

// One broken invariant, named by the corner where it was found.
struct Violation {
    enum class Kind : std::uint8_t {
        BadSize,              // V/O sizes differ or are not a multiple of 3
        VertexRange,          // V[c] outside [0, |G|)
        OppositeRange,        // O[c] outside [-1, |V|)
        OppositeSelf,         // O[c] lies in c's own triangle
        OppositeSymmetry,     // O[O[c]] != c
        EdgeMismatch,         // the edge opposite c is not the reversed edge opposite O[c]
        DegenerateTri,        // a triangle repeats a vertex
        NotCounterClockwise,  // orient2d of a triangle is <= 0
        NotDelaunay,          // the vertex O[c] lies strictly inside the circumcircle of t(c)
    };
    Kind kind;
    std::int32_t corner;
    std::string message;
};

const char* toString(Violation::Kind kind);

struct ValidateOptions {
    bool geometry = true;  // check counter-clockwise orientation (exact)
    bool delaunay = true;  // check the local Delaunay property on every interior edge (exact)
    std::int32_t firstVirtual = -1;  // vertices >= this are ghost/super vertices: skip geometry
    std::size_t maxViolations = 1;   // stop after this many (1: report the first broken invariant)
};

std::vector<Violation> validate(const Mesh& mesh, const ValidateOptions& options = {});

}  // namespace dlab
