// Constrained edges on the exact mode's closed mesh: Sloan's flips of the crossed edges, then
// Lawson's flips back to the constrained Delaunay triangulation.
//
// insert(a, b) walks from a towards b collecting the edges the open segment crosses; a vertex
// exactly on the segment splits it there. Each crossed edge whose quadrilateral is convex is
// flipped; a new edge that still crosses the segment goes back in the queue, one that does not
// is kept for the repair (Sloan 1993: the queue empties). The segment is then an edge, marked
// constrained on both its corners, and every new edge is flipped while it is not locally Delaunay
// and not constrained. Constrained edges are never flipped and the in-circle test ignores them, so
// the result is the constrained Delaunay triangulation. With a record, every walk, flip, mark
// and in-circle test is a recorded operation whose V, O and flag changes undo it bit for bit.
#pragma once

#include "core/engine/inserter.h"
#include "core/engine/mesh.h"
#include "core/engine/remover.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace dlab {

enum class ConstrainResult : std::uint8_t {
    Inserted,        // the segment (or its pieces between the vertices on it) are constrained edges
    SameVertex,      // a == b
    NotInMesh,       // a or b is not a vertex of the mesh (or is the ghost vertex)
    Crosses,         // the segment crosses the constrained edge `crossed` (nothing changed)
    NotConstrained,  // remove: the segment is not a chain of constrained edges (nothing changed)
};

enum class ConstrainOpType : std::uint8_t {
    Walk,          // the piece a-b walked (b: the segment's end or a vertex on it): `count` edges
                   // cross it
    SloanFlip,     // the crossed edge opposite corner a flipped (b: its new edge still crosses)
    SloanWait,     // the crossed edge opposite corner a: its quadrilateral is not convex, later
    Mark,          // the edge a-b (vertices) is now constrained, flagged on both its corners
    Reflag,        // vertex a removed: the constrained flags put back on their edges' corners
    Unmark,        // the edge a-b (vertices) is one constraint less (free once none is left)
    InCircleTest,  // the repair: the edge opposite corner a tested against corner b's vertex
    Flip,          // the repair flipped the edge opposite corner a
    MoveVertex,    // vertex a, taken out, takes its new place (G changes; the editor records it)
    Locate,        // vertex a goes into triangle b (count: the corner facing the edge it is on,
                   // -1 inside)
    Split,         // triangle b split in three around vertex a
    SplitEdge,     // the edge opposite corner b split at vertex a (its constraints kept on both
                   // halves)
    Fan,           // the points left were collinear (no triangle): vertex a, off their line, and
                   // they make count triangles (a fan, with its ghost triangles)
};
const char* toString(ConstrainOpType t);

// A constrained flag of one corner changed.
struct FlagChange {
    std::int32_t corner;
    std::uint8_t before, after;
};

// One recorded operation; its changes are changes[firstChange, +numChanges) and
// flagChanges[firstFlag, +numFlags).
struct ConstrainOp {
    ConstrainOpType type = ConstrainOpType::Walk;
    std::int32_t trianglesBefore = 0, trianglesAfter = 0;  // a split adds triangles
    std::int8_t sign = 0;
    std::int32_t a = kNone, b = kNone;
    std::int32_t segmentA = kNone, segmentB = kNone;  // the segment being inserted
    std::int32_t count = 0;                           // Walk: the edges the piece crosses
    std::uint32_t firstChange = 0, numChanges = 0;
    std::uint32_t firstFlag = 0, numFlags = 0;
};

// The record of one or more constraint insertions, in order.
struct ConstraintRecord {
    std::vector<ConstrainOp> ops;
    std::vector<CellChange> changes;
    std::vector<FlagChange> flagChanges;
};

// What removeVertex did.
struct VertexRemoval {
    RemoveResult removed = RemoveResult::NotInMesh;  // the Remover's answer, when it ran
    bool refused = false;  // a constrained edge ends at the vertex: nothing changed
    std::pair<std::int32_t, std::int32_t> constrained{-1, -1};  // that edge
    std::int32_t droppedConstraints = 0;  // Collapsed: the constrained edges left with no mesh
};

// Where insertVertex put the vertex, or why not.
enum class PlaceResult : std::uint8_t {
    Placed,     // inside a triangle, on an edge, or outside the hull (which grows to take it in)
    OnVertex,   // another vertex is there (nothing changed)
    NoTriangle  // the mesh has no triangle: the points are collinear (nothing changed)
};

struct ConstrainOutcome {
    ConstrainResult result = ConstrainResult::Inserted;
    std::pair<std::int32_t, std::int32_t> crossed{-1, -1};
};

class Constrainer {
public:
    // The mesh: closed. The exact mode's: its ghost vertex at firstVirtual, a ghost triangle at
    // every hull edge. The super-triangle's: the inserter's before Finalize, its three vertices
    // from firstVirtual on real points (in every test, never an end of a segment).
    Constrainer(Mesh& mesh, std::int32_t firstVirtual, Boundary boundary = Boundary::Exact);

    // Constrains the segment a-b; with a record, every operation is appended to it.
    ConstrainOutcome insert(std::int32_t a, std::int32_t b, ConstraintRecord* record = nullptr);
    // Takes the constraint a-b away: each of its pieces (the edges between the vertices on it)
    // counts one constraint less; those left with none are free, and Lawson's flips make the mesh
    // around them constrained Delaunay again. NotConstrained when a-b was not inserted.
    ConstrainOutcome remove(std::int32_t a, std::int32_t b, ConstraintRecord* record = nullptr);
    // Removes vertex v with `remover` (its ear flips and merge recorded in `removal`) and keeps
    // every constraint: refused when a constrained edge ends at v (take the constraint away
    // first); else the flags go back on their edges (a Reflag op) and Lawson's flips make the
    // edges around the hole constrained Delaunay (recorded in `record`). To undo: this record's
    // ops, then the removal's, then refresh().
    VertexRemoval removeVertex(Remover& remover, std::int32_t v, RemovalRecord* removal,
                               ConstraintRecord* record);
    // Puts vertex v (no triangle uses it; its point is G[v]) into the mesh: the triangle that
    // holds it split in three, or the edge it lies on in four (a constrained edge's halves keep
    // its constraints), then Lawson's flips that skip constrained edges; recorded (Locate,
    // Split or SplitEdge, the tests and flips). Outside the hull, the ghost triangle of a hull
    // edge that sees it is split, and the flips take in the hull vertices it makes reflex. On
    // another vertex nothing changes.
    PlaceResult insertVertex(std::int32_t v, ConstraintRecord* record = nullptr);
    // The mesh has no triangle and `left` are the vertices left, collinear (a removal
    // collapsed): vertex v (its point G[v]) off their line makes the fan of triangles with them,
    // and its ghost triangles, recorded as one Fan op. On their line or on one of them, nothing
    // changes (NoTriangle, OnVertex).
    PlaceResult fanOut(std::int32_t v, const std::vector<std::int32_t>& left,
                       ConstraintRecord* record = nullptr);
    // Would vertex v at `to` keep every triangle of its star counter-clockwise (strictly)? False
    // for a hull vertex (its star is open to the outside) and for a vertex in no triangle.
    bool inKernel(std::int32_t v, Vec2 to);
    // Vertex v was moved (G[v] changed by the caller) inside its star's kernel: the triangles are
    // all still valid, and Lawson's flips from every edge of its star (the spokes and the link)
    // make the mesh constrained Delaunay again; recorded (the tests and flips).
    void follow(std::int32_t v, ConstraintRecord* record = nullptr);
    // The mesh was changed by another editor (the Remover's undo): the index is rebuilt.
    void refresh() { rebuildIndex(); }
    // Reverts the record's ops from the last back to op `from` (V, O and the flags exactly as
    // before them).
    void undo(const ConstraintRecord& record, std::size_t from = 0);
    // Redoes (forward) or undoes recorded op i alone: V, O and the flags exactly as after /
    // before it.
    void replay(const ConstraintRecord& record, std::size_t i, bool forward);
    // Is the edge opposite corner c constrained? (flags()[c]: by how many inserted segments)
    bool isConstrained(std::int32_t c) const { return m_flag[c] != 0; }
    const std::vector<std::uint8_t>& flags() const { return m_flag; }

private:
    using Edge = std::pair<std::int32_t, std::int32_t>;
    bool isVirtual(std::int32_t v) const { return v >= m_firstVirtual; }  // not the input's
    bool isGhost(std::int32_t v) const { return v >= m_ghost; }     // the exact mode's ghost vertex
    std::int32_t edgeCorner(std::int32_t u, std::int32_t w) const;  // corner facing u-w
    bool crossedEdges(std::int32_t a, std::int32_t b, std::vector<Edge>& crossed,
                      std::int32_t& stop, ConstrainOutcome& out) const;
    bool firstCrossing(std::int32_t a, std::int32_t b, std::int32_t& corner,
                       std::int32_t& stop) const;
    void flipOut(std::int32_t a, std::int32_t b, std::vector<Edge> queue, std::vector<Edge>& fresh);
    void restore(std::vector<Edge> stack);
    void flip(std::int32_t c);
    bool locate(Vec2 p, std::int32_t& tri, std::int32_t& edge, PlaceResult& refused) const;
    void splitTriangle(std::int32_t t, std::int32_t v);
    void splitEdge(std::int32_t c, std::int32_t v);
    std::int32_t appendTriangles(int count);
    void mark(std::int32_t a, std::int32_t b);
    void setV(std::int32_t c, std::int32_t v);
    void setO(std::int32_t c, std::int32_t o);
    void setFlag(std::int32_t c, std::uint8_t f);
    ConstrainOp* beginOp(ConstrainOpType type, std::int32_t a, std::int32_t b, int sign = 0);
    void endOp();
    void rebuildIndex();

    bool pieces(std::int32_t a, std::int32_t b, std::vector<Edge>& out) const;
    void beginRecording(ConstraintRecord* record, std::int32_t a, std::int32_t b);

    Mesh& m_mesh;
    std::int32_t m_firstVirtual;
    std::int32_t m_ghost;  // the ghost vertex (exact), past every vertex (super)
    std::vector<std::int32_t> m_cornerOf;
    std::vector<std::uint8_t> m_flag;  // per corner: how many constraints hold the edge opposite
    bool m_stale = false;              // m_cornerOf must be rebuilt (after replay)
    ConstraintRecord* m_record = nullptr;  // where the current call records, if anywhere
    std::int32_t m_segA = kNone, m_segB = kNone;
};

}  // namespace dlab
