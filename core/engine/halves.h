// Two triangulations at once, joined: the batch path for two cores.
//
// The points split at a sampled median (x, then y): the left half lies lexicographically below
// the right one, so their convex hulls are disjoint. Each half is triangulated by the incremental
// inserter (the caller runs the two on two threads: nothing here starts one), then Guibas and
// Stolfi's merge joins them. It climbs from the lower common tangent to the upper one, one seam
// triangle a step: the apex is a neighbour of the base's left end or of its right end in its own
// half, and a neighbour's edge is erased when the next neighbour lies inside the circle through
// the base and it. The erased edges' triangles go and the seam's take their slots. Every decision
// is an exact predicate, and the work is linear in the seam and
// the edges it crosses. The result is the Delaunay triangulation of the whole set (with
// cocircular points, one of them), numbered differently from the incremental path's.
#pragma once

#include "core/engine/inserter.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace dlab {

// Where the set splits in two: the left half is every point lexicographically below the split
// point, the right half the rest, so the halves' convex hulls are disjoint and copies of a point
// stay together. Empty below `smallest` points, where a split costs more than it saves (tests
// split smaller sets).
inline constexpr std::size_t kSmallestSplit = 4096;
std::optional<Vec2> splitPoint(const std::vector<Vec2>& points,
                               std::size_t smallest = kSmallestSplit);

// Whether two halves split at `split` and joined cost less than the whole set in one, judged by a
// pilot run on a sample (fixed seed: the same answer on every machine). It exists for the sets
// whose seam is not a thin line across the set: points in convex position (a half's fan around
// the vertex next to the split re-forms every time a point lands beyond it, and the join erases
// nearly every edge of both halves) and long chains that face each other across the split (the
// seam holds a triangle for every point of both). The join reaches its points by input index,
// a cache miss each at a million points, so a seam of a fixed share of the set costs more than
// the one inserter's whole run.
struct SplitPilot {
    std::size_t sample = 0;  // points in the pilot's sample
    // Work in predicate calls (in-circle tests, walk steps, and two per insertion): the whole
    // sample in one, each half, and the join.
    std::int64_t whole = 0, left = 0, right = 0, join = 0;
    bool joined = false;  // the sample's halves could be joined
    // The two-core path's span (the larger half, then the join) over the one inserter's work.
    double ratio() const;
    // The join's work over the one inserter's. A seam across the set grows as the square root of
    // its size: about 0.01 to 0.04 of the work at the pilot's size, less on the whole set. A
    // seam that grows with the set stays near 0.2 at any size.
    double seamShare() const;
    bool pays() const;
};
inline constexpr std::size_t kPilotSample = 4095;
SplitPilot pilotSplit(const std::vector<Vec2>& points, Vec2 split, const InsertOptions& options,
                      std::size_t sample = kPilotSample);

// One half, triangulated by the batch inserter on the caller's thread; its vertex ids and
// duplicates are input indices. The mesh holds no points (G empty). The left half's corner table
// has room for the whole result, which joinHalves() builds in it.
struct HalfTriangulation {
    Mesh mesh;
    std::vector<std::int32_t> hull;     // boundary corners, counter-clockwise
    std::vector<std::int32_t> skipped;  // duplicates, input indices
    InsertStats stats;
    LocatorStats locatorStats;
};
HalfTriangulation triangulateHalf(const std::vector<Vec2>& points, Vec2 split, bool left,
                                  const InsertOptions& options);

// The whole set's triangulation: vertex ids are input indices, as the incremental path's.
struct JoinedTriangulation {
    Mesh mesh;
    std::vector<std::int32_t> skipped;  // input indices, increasing
    InsertStats stats;
    LocatorStats locatorStats;
};
// Empty, `points` untouched, when the halves cannot be joined this way (a half without a
// triangle: all its points on a line): triangulate the whole set in one then. Otherwise the
// points move into the result's mesh.
std::optional<JoinedTriangulation> joinHalves(std::vector<Vec2>& points, HalfTriangulation left,
                                              HalfTriangulation right);

}  // namespace dlab
