// Vertex removal from a Delaunay triangulation on the corner table, by recorded flips and a merge.
//
// The mesh is "closed": every vertex's star is a ring. That is the inserter's mesh before
// Finalize in both boundary modes (the exact mode's ghost triangles, the super-triangle), or a
// finished exact-mode mesh after addGhosts(). Removing v cuts ears off its link: an ear is three
// consecutive link vertices a, b, c whose triangle is one of the result (no other link vertex
// strictly inside its circle; with the ghost vertex g, a ghost triangle's "circle" is the open
// half-plane beyond its hull edge plus the open edge). Flipping the edge v-b turns the ear into
// that triangle and leaves v of degree one less; at degree 3 the three triangles around v merge
// into one. Each ear test, flip and merge is a recorded operation whose V/O cell changes undo it
// bit for bit. The result is the Delaunay triangulation of the points left (one of them, where
// cocircular points allow several), with its convex hull in the exact mode.
#pragma once

#include "core/engine/inserter.h"
#include "core/engine/mesh.h"

#include <cstdint>
#include <vector>

namespace dlab {

enum class RemoveOpType : std::uint8_t {
    EarTest,   // the ear with tip `b` (link vertex) tested: sign +1 cut next is possible, 0 only
               // with a flat triangle left at v, -1 not an ear; a = the corner at v before it
    Flip,      // the edge v-b flipped (a = the corner facing it, b = the tip): the ear is cut
    Merge,     // degree 3: the three triangles around v merged into triangle a
    Collapse,  // exact boundary: the points left are collinear or fewer than 3: no triangle
};
const char* toString(RemoveOpType t);

// One recorded operation of a removal; its cell changes are changes[firstChange, +numChanges).
struct RemoveOp {
    RemoveOpType type = RemoveOpType::EarTest;
    std::int8_t sign = 0;
    std::int32_t vertex = kNone;  // the vertex being removed
    std::int32_t a = kNone;
    std::int32_t b = kNone;
    std::int32_t trianglesBefore = 0;
    std::int32_t trianglesAfter = 0;
    std::uint32_t firstChange = 0;
    std::uint32_t numChanges = 0;
};

// The record of one or more removals, in order.
struct RemovalRecord {
    std::vector<RemoveOp> ops;
    std::vector<CellChange> changes;
};

enum class RemoveResult : std::uint8_t {
    Removed,    // the vertex is gone, the rest is Delaunay
    Collapsed,  // exact boundary: the vertex is gone and the points left make no triangle
    NotInMesh,  // no triangle uses this vertex (out of range, removed, duplicate, collinear set)
    Virtual,    // the ghost vertex or a super-triangle vertex: never removed
};
const char* toString(RemoveResult r);

class Remover {
public:
    // `firstVirtual`: vertices at or past it are the ghost vertex (exact) or the super-triangle's.
    // The mesh must stay alive and be changed only through this remover (or undo()) meanwhile.
    Remover(Mesh& mesh, std::int32_t firstVirtual, Boundary boundary);

    // Removes vertex v; with a record, every ear test, flip and merge is appended to it.
    // Throws std::logic_error when v's star is open (the mesh is not closed).
    RemoveResult remove(std::int32_t v, RemovalRecord* record = nullptr);
    // Reverts the record's ops from the last back to op `from` (V and O exactly as before them).
    void undo(const RemovalRecord& record, std::size_t from = 0);
    // Redoes (forward) or undoes recorded op i alone: V and O exactly as after / before it.
    void replay(const RemovalRecord& record, std::size_t i, bool forward);

    // Another editor of the same mesh (the Constrainer) changed it: the index is rebuilt.
    void meshChanged() { m_stale = true; }
    // A corner at vertex v, kNone when no triangle uses it.
    std::int32_t cornerAt(std::int32_t v);
    // Finite vertices some triangle uses.
    std::int32_t liveVertices();

private:
    bool isVirtual(std::int32_t v) const { return v >= m_firstVirtual; }
    bool isGhost(std::int32_t v) const { return m_boundary == Boundary::Exact && isVirtual(v); }
    void rebuildIndex();
    void gatherStar(std::int32_t v, std::int32_t start);
    bool leavesNoTriangle(std::int32_t v) const;
    int inCircleOf(std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t w) const;
    int earSign(std::int32_t v, std::size_t i) const;
    int testEar(std::int32_t v, std::size_t i);
    std::size_t chooseEar(std::int32_t v);
    void cutEar(std::int32_t v, std::size_t i);
    void merge(std::int32_t v);
    void collapse(std::int32_t v);
    void freeTriangle(std::int32_t t);

    void setV(std::int32_t c, std::int32_t v);
    void setO(std::int32_t c, std::int32_t o);
    void link(std::int32_t c, std::int32_t d);
    RemoveOp beginOp(RemoveOpType type, std::int32_t v) const;
    void endOp(RemoveOp op);

    Mesh& m_mesh;
    std::int32_t m_firstVirtual;
    Boundary m_boundary;
    std::vector<std::int32_t> m_cornerOf;  // a corner at each vertex, kNone when none
    std::int32_t m_live = 0;               // finite vertices in the mesh
    bool m_stale = true;                   // m_cornerOf must be rebuilt (after undo)
    RemovalRecord* m_record = nullptr;     // where the current removal records, if anywhere
    std::vector<std::int32_t> m_link;      // the link of v, counter-clockwise
    std::vector<std::int32_t> m_corners;   // corner at v of triangle (v, link[i], link[i+1])
    static constexpr std::int8_t kUntested = 2;
    std::vector<std::int8_t> m_ear;  // earSign of the ear with tip link[i], or kUntested
};

// Is w inside the circle of the counter-clockwise triangle (a, b, c) on the exact mode's closed
// mesh, where vertices at or past `ghost` are the ghost vertex: +1 inside, 0 on it, -1 outside.
// A ghost triangle's "circle" is the open half-plane beyond its hull edge plus the open edge;
// the ghost vertex is inside no circle.
int ghostInCircle(const std::vector<Vec2>& G, std::int32_t ghost, std::int32_t a, std::int32_t b,
                  std::int32_t c, std::int32_t w);

// The exact mode's closed form of a finished mesh: the ghost vertex (index |G|, placed at the
// first vertex) and one ghost triangle (y, x, g) beside every boundary edge x->y, linked around g.
void addGhosts(Mesh& mesh);
// Drops every triangle with a vertex at or past firstVirtual (the boundary edges get kNone),
// keeps the others in order, and G's first firstVirtual points.
void dropVirtual(Mesh& mesh, std::int32_t firstVirtual);

}  // namespace dlab
