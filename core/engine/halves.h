// Two triangulations at once, joined: the batch path for two cores.
//
// The points split at their median (x, then y): the left half lies lexicographically below the
// right one, so their convex hulls are disjoint. Each half is triangulated by the incremental
// inserter (the caller runs the two on two threads: nothing here starts one), then the gap
// between the two hulls, from their lower common tangent to their upper one, is zipped with
// triangles, and Lawson's flips repair the seam: an edge whose quadrilateral changed and whose
// in-circle test is positive is flipped (its quadrilateral is convex), until none is left. Only
// the zip's edges and those flips can be non-Delaunay: every other edge keeps the quadrilateral
// it had in its half. Every decision is an exact predicate. The result is the Delaunay
// triangulation of the whole set (with cocircular points, one of them), numbered differently
// from the incremental path's.
#pragma once

#include "core/engine/inserter.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace dlab {

// Input indices of each half; both empty when the set is too small to be worth splitting.
// Equal points are never split apart.
struct Halves {
    std::vector<std::int32_t> left, right;
};
Halves splitAtMedian(const std::vector<Vec2>& points);

// One half, triangulated by the batch inserter; its vertex ids and duplicates are input indices
// (mapped on the half's own thread). The mesh holds no points (G empty).
struct HalfTriangulation {
    Mesh mesh;
    std::vector<std::int32_t> skipped;  // duplicates, input indices
    InsertStats stats;
};
HalfTriangulation triangulateHalf(const std::vector<Vec2>& points,
                                  const std::vector<std::int32_t>& indices,
                                  const InsertOptions& options);

// The whole set's triangulation: vertex ids are input indices, as the incremental path's.
struct JoinedTriangulation {
    Mesh mesh;
    std::vector<std::int32_t> skipped;  // input indices, increasing
    InsertStats stats;
};
// Empty, `points` untouched, when the halves cannot be joined this way (a half without a
// triangle: all its points on a line): triangulate the whole set in one then. Otherwise the
// points move into the result's mesh.
std::optional<JoinedTriangulation> joinHalves(std::vector<Vec2>& points, const Halves& halves,
                                              HalfTriangulation left, HalfTriangulation right);

}  // namespace dlab
