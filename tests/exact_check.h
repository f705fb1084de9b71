// An independent check of a finished triangulation, in exact rational arithmetic (GMP), sharing
// no code with the library's predicates or validate():
//   - every triangle is counter-clockwise (strictly),
//   - every edge is used once per direction at most, O is consistent with the shared edges,
//   - the boundary is one closed loop that turns left or goes straight at every vertex (a convex
//     hull, collinear hull points included),
//   - Euler: #triangles = 2 * #vertices - #hull vertices - 2 (so the triangles tile the hull
//     without gaps or overlaps, given the above),
//   - every interior edge is locally Delaunay (the opposite vertex is not strictly inside the
//     circumcircle), which for a triangulation of a convex region means globally Delaunay,
//   - optionally, the vertices used are exactly `expectedVertices`.
// Returns "" when all holds, else a description of the first failure.
#pragma once

#include "core/engine/geometry.h"
#include "core/engine/mesh.h"

#include <string>
#include <vector>

std::string checkDelaunayExact(const dlab::Mesh& mesh,
                               const std::vector<std::int32_t>* expectedVertices = nullptr);

// The index of the first occurrence of every distinct point (== on doubles: -0 equals 0, as in
// the inserter): the vertices a finished triangulation must use.
std::vector<std::int32_t> firstOccurrences(const std::vector<dlab::Vec2>& points);

// True when every point of `points` lies on one line (or there are fewer than 3 distinct ones):
// then no triangle exists and an empty mesh is the right answer.
bool allCollinearExact(const std::vector<dlab::Vec2>& points);

// Exact signs in GMP rationals, for tests that compare against the library's predicates.
int orientGmp(dlab::Vec2 a, dlab::Vec2 b, dlab::Vec2 c);
int incircleGmp(dlab::Vec2 a, dlab::Vec2 b, dlab::Vec2 c, dlab::Vec2 d);
