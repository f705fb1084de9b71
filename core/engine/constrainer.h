// Constrained edges on the exact mode's closed mesh: Sloan's flips of the crossed edges, then
// Lawson's flips back to the constrained Delaunay triangulation.
//
// insert(a, b) walks from a towards b collecting the edges the open segment crosses; a vertex
// exactly on the segment splits it there. Each crossed edge whose quadrilateral is convex is
// flipped; a new edge that still crosses the segment goes back in the queue, one that does not
// is kept for the repair (Sloan 1993: the queue empties). The segment is then an edge, marked
// constrained on both its corners, and every new edge is flipped while it is not locally Delaunay
// and not constrained. Constrained edges are never flipped and the in-circle test ignores them, so
// the result is the constrained Delaunay triangulation. Not yet recorded operations: the flips
// here are plain cell writes.
#pragma once

#include "core/engine/mesh.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace dlab {

enum class ConstrainResult : std::uint8_t {
    Inserted,    // the segment (or its pieces between the vertices on it) are constrained edges
    SameVertex,  // a == b
    NotInMesh,   // a or b is not a vertex of the mesh (or is the ghost vertex)
    Crosses,     // the segment crosses the constrained edge `crossed` (nothing changed)
};

struct ConstrainOutcome {
    ConstrainResult result = ConstrainResult::Inserted;
    std::pair<std::int32_t, std::int32_t> crossed{-1, -1};
};

class Constrainer {
public:
    // The mesh: the exact mode's closed form (ghost vertex and those past it at firstVirtual).
    Constrainer(Mesh& mesh, std::int32_t firstVirtual);

    ConstrainOutcome insert(std::int32_t a, std::int32_t b);
    // Is the edge opposite corner c constrained?
    bool isConstrained(std::int32_t c) const { return m_flag[c] != 0; }
    const std::vector<std::uint8_t>& flags() const { return m_flag; }

private:
    using Edge = std::pair<std::int32_t, std::int32_t>;
    bool isVirtual(std::int32_t v) const { return v >= m_firstVirtual; }
    std::int32_t edgeCorner(std::int32_t u, std::int32_t w) const;  // corner facing u-w
    bool crossedEdges(std::int32_t a, std::int32_t b, std::vector<Edge>& crossed,
                      std::int32_t& stop, ConstrainOutcome& out) const;
    bool firstCrossing(std::int32_t a, std::int32_t b, std::int32_t& corner,
                       std::int32_t& stop) const;
    void flipOut(std::int32_t a, std::int32_t b, std::vector<Edge> queue, std::vector<Edge>& fresh);
    void restore(std::vector<Edge> stack);
    void flip(std::int32_t c);
    void mark(std::int32_t a, std::int32_t b);

    Mesh& m_mesh;
    std::int32_t m_firstVirtual;
    std::vector<std::int32_t> m_cornerOf;
    std::vector<std::uint8_t> m_flag;  // per corner: the edge opposite it is constrained
};

}  // namespace dlab
