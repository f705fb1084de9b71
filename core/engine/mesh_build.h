// Building a corner table from triangles alone: O from V, and one starting corner per vertex.
#pragma once

#include "core/engine/mesh.h"

#include <cstdint>
#include <vector>

namespace dlab {

// Fills m.O from m.V: the corner opposite edge a->b in one triangle faces the corner opposite
// edge b->a in the other (counter-clockwise triangles traverse a shared edge in opposite
// directions). Unmatched edges get kNone (the boundary). Linear time (a counting sort of the
// edges by their smaller vertex, then a tiny sort per vertex).
//
// Throws std::invalid_argument, naming the triangles and vertices involved, when
//   - |V| is not a multiple of 3, or a vertex id lies outside [0, |G|),
//   - a triangle repeats a vertex,
//   - two triangles traverse the same directed edge (inconsistent orientation),
//   - an edge is shared by more than two triangles (not a manifold).
// m.O is left untouched when it throws.
void computeOpposites(Mesh& m);

// One corner per vertex (index = vertex id), kNone for vertices no triangle uses.
// For a vertex on the boundary the corner returned is the most clockwise one around it
// (u(c) == kNone), so swinging with s() from it visits every incident corner; for an interior
// vertex any corner does. Assumes a valid O (each vertex's triangles form one fan).
std::vector<std::int32_t> vertexCorners(const Mesh& m);

}  // namespace dlab
