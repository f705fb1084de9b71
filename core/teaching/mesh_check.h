// Checking a student's mesh after an insertion, in the words of a plain triangle list: which
// point is missing, which triangle is flat, clockwise, overlapping or missing, and which edge is
// not Delaunay (with the vertex inside the circle and the flip we expected). Every geometric
// decision goes through the exact predicates.
#pragma once

#include "core/engine/geometry.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace dlab {

// A triangle as a vertex triple rotated so that its smallest vertex comes first (orientation
// kept): (5, 2, 9) and (2, 9, 5) are the same triangle, (2, 5, 9) is the other orientation.
using Triple = std::array<std::int32_t, 3>;
Triple canonical(std::int32_t v0, std::int32_t v1, std::int32_t v2);
// "(0, 4, 7)", and a list of at most `most` of them ("none" when empty).
std::string tripleText(const Triple& t);
std::string triplesText(const std::vector<Triple>& ts, std::size_t most = 6);

// Where the vertices are: input points, then the super-triangle's vertices or the ghost vertex.
struct MeshGeometry {
    std::vector<Vec2> points;  // indexed by vertex id; empty when unknown (a .jsonl reference)
    std::int32_t numInput = 0;
    bool ghost = false;  // vertex numInput is the ghost vertex: it has no position
    bool known() const { return !points.empty(); }
    bool isGhost(std::int32_t v) const { return ghost && v == numInput; }
};

// A flip the student made: the edge it removed and the edge it made (vertex pairs).
struct FlipMade {
    std::array<std::int32_t, 2> removed, added;
};

struct MeshVerdict {
    bool ok = true;
    std::string reason;                // one line: "not Delaunay at edge 1–2: ..."
    std::vector<std::string> details;  // more evidence, one line each
};

// A flip that should not have been made: the edge it removed was Delaunay, the point across it
// outside (or on) the circle of the triangle on the other side, decided by the exact in-circle
// test. The point is `newVertex` when the flip made an edge to it. nullopt when the flip was
// right or cannot be judged (a ghost or unknown vertex, a flat triangle before the flip).
std::optional<MeshVerdict> checkFlipMade(const FlipMade& flip, const MeshGeometry& geometry,
                                         std::int32_t newVertex);

// Judges the student's triangles (canonical, sorted) against ours after the same insertion.
// `newVertex` is the point this insertion put in (-1 when none), `flips` the flips the student
// made during it, `wrongFlip` the first of them that checkFlipMade refused (the reason, after
// the vertices are checked, when it came before any other mistake of the insertion). ok only
// when the two meshes are the same.
MeshVerdict checkStudentMesh(const std::vector<Triple>& student, const std::vector<Triple>& ours,
                             const MeshGeometry& geometry, std::int32_t newVertex,
                             const std::vector<FlipMade>& flips,
                             const std::optional<MeshVerdict>& wrongFlip = std::nullopt);

// "1–2": an undirected edge, smaller vertex first.
std::string edgeName(std::int32_t a, std::int32_t b);

}  // namespace dlab
