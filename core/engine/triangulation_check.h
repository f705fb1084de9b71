// The exact mesh checker (every problem of a foreign triangulation, named) and Lawson's repair.
//
// checkMesh decides everything with the exact predicates and runs in O(n log n): one sort of
// the points (duplicates, the convex hull), a bucket sort of the edges by their lower vertex.
// Whether the triangles tile the convex hull of their vertices exactly once follows from local
// facts: every triangle counter-clockwise, every edge in at most two triangles that run it in
// opposite directions, the boundary edges forming exactly the hull's edges (collinear hull
// points included) and Euler's count T = 2n - h - 2 (n vertices used, h of them on the hull):
// such a mesh is a disc mapped onto the hull without folds, so it covers it once. When one of
// these fails the checker looks for the overlapping pairs (an exact separating-edge test over
// a bucket grid) and traces the boundary loops (clockwise loops are holes, a counter-clockwise
// loop that turns right is a non-convex outline, a hull edge no triangle has is a gap).
#pragma once

#include "core/engine/mesh.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace dlab {

struct MeshProblem {
    enum class Kind : std::uint8_t {
        VertexRange,            // a triangle names a vertex that does not exist
        RepeatedVertex,         // a triangle repeats a vertex
        FlatTriangle,           // its three vertices are collinear
        ClockwiseTriangle,      // clockwise with y up
        OppositeRange,          // O[c] is not a corner (nor -1)
        OppositeNotInvolution,  // O[O[c]] != c
        OppositeWrongEdge,      // O[c] lies in a triangle that does not share c's edge (or -1 on a
                                // shared edge)
        EdgeInManyTriangles,    // an edge in three or more triangles
        Overlap,                // two triangles whose interiors intersect
        Hole,                   // part of the convex hull no triangle covers
        NonConvexOutline,       // the outline turns right at these vertices
        DuplicatePoint,         // two used vertices at the same place
        UnusedPoint,            // a point no triangle uses (and no used vertex duplicates)
        UnusedDuplicate,        // a note: an unused copy of a used vertex (skipped, as we do)
        NotDelaunay,            // the vertex across an edge lies inside the circle of a triangle
    };
    Kind kind;
    std::vector<std::int32_t> triangles;  // 0-based, the elements it is about
    std::vector<std::int32_t> vertices;
    std::vector<std::int32_t> corners;
    std::string message;  // one line, ids in the file's numbering
};

const char* toString(MeshProblem::Kind kind);  // "clockwise-triangle", "not-delaunay", ...
// True for the problems that make the mesh something else than a triangulation (all but
// unused points, unused duplicates and non-Delaunay edges): a repair cannot start.
bool blocksRepair(MeshProblem::Kind kind);

struct CheckOptions {
    bool hasOpposites = false;  // check the mesh's O against the triangles (else O is ignored)
    int indexBase = 0;          // vertex and triangle ids in messages: 0- or 1-based
    std::size_t maxOverlapTests = std::size_t{1} << 28;  // exact pair tests of the overlap search
};

struct CheckReport {
    std::int32_t points = 0, usedPoints = 0, triangles = 0;
    std::vector<MeshProblem> problems;    // every problem, grouped by kind
    std::vector<std::int32_t> opposites;  // O computed from the triangles (kNone: boundary or
                                          // an edge in no consistent pair)
    bool overlapSearchCut = false;        // the overlap search stopped at maxOverlapTests

    std::size_t count(MeshProblem::Kind kind) const;
    bool isTriangulation() const;  // no problem blocks a repair
    bool isDelaunay() const;       // no problem at all but notes
    // "valid Delaunay triangulation of 1000 points (1990 triangles)", "valid triangulation of
    // 1000 points, 17 edges not Delaunay", "not a triangulation: 2 holes, 1 overlap; ...".
    std::string summary() const;
};

CheckReport checkMesh(const Mesh& mesh, const CheckOptions& options = {});

// One flip of Lawson's algorithm: the edge opposite corner `corner` (shared with `opposite`),
// between triangles tri(corner) and tri(opposite), replaced by the edge between the corners'
// vertices.
struct FlipRecord {
    std::int32_t corner = kNone, opposite = kNone;
    std::int32_t removed[2] = {kNone, kNone};  // the edge's vertices before the flip
    std::int32_t added[2] = {kNone, kNone};    // V[corner], V[opposite]: the new edge
};

struct RepairResult {
    Mesh mesh;                       // Delaunay, the input's vertex numbering kept
    std::vector<FlipRecord> flips;   // in order
    std::int64_t incircleTests = 0;  // edges tested
};

// Lawson's flip algorithm from a triangulation that checkMesh found valid (report.opposites is
// its O): every edge that is not locally Delaunay is queued, flipped, its four neighbours
// queued again, until none is left; exact in-circle tests. Throws std::invalid_argument when
// the report has a problem that blocks a repair (it names them).
RepairResult repairByFlips(const Mesh& mesh, const CheckReport& report);

}  // namespace dlab
