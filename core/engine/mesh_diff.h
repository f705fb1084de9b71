// A triangulation's edges against the Delaunay triangulation of its own points: the edges only
// in one of them, each decided by vertex position (of equal points the first copy stands for all).
#pragma once

#include "core/engine/mesh.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace dlab {

using MeshEdge = std::pair<std::int32_t, std::int32_t>;  // vertex ids, first < second

struct DelaunayDiff {
    std::vector<MeshEdge> onlyGiven;     // in the given mesh, not in the Delaunay triangulation
    std::vector<MeshEdge> onlyDelaunay;  // in the Delaunay triangulation, not in the given mesh
    // Edges of onlyDelaunay whose two triangles' four points lie on one circle (exactly): there
    // either diagonal is Delaunay, so a difference there is a choice, not an error.
    std::int64_t cocircular = 0;
    std::int64_t sharedEdges = 0;
    bool same() const { return onlyGiven.empty() && onlyDelaunay.empty(); }
};

// `given`: a valid triangulation (V names points of given.G; O unused). The Delaunay
// triangulation is made by the inserter with its default options.
DelaunayDiff diffWithDelaunay(const Mesh& given);

}  // namespace dlab
