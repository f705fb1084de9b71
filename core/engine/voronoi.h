// The Voronoi diagram as the dual of the triangulation, read off the corner table.
//
// Duality, one element at a time:
//   triangle t            <-> Voronoi vertex t, the circumcenter of t
//   interior edge (c, o)  <-> finite Voronoi edge joining the circumcenters of t(c) and t(o(c))
//   hull edge (o(c) = -1) <-> Voronoi ray from the circumcenter of t(c), along the outward
//                             normal of the hull edge
//   vertex v              <-> Voronoi cell of v: the circumcenters of the triangles around v,
//                             counter-clockwise; unbounded (two rays) when v is on the hull
//
// Corner c names the edge opposite it, V[n(c)] -> V[p(c)], as everywhere in the corner table:
//
//          V[p(c)]
//            |  `.
//            |    `.      the edge opposite c; its outward normal points
//            |  t   `.    away from t(c), toward t(o(c)) or out of the hull
//          V[c] ------ V[n(c)]
#pragma once

#include "core/engine/geometry.h"
#include "core/engine/mesh.h"
#include "core/engine/mesh_build.h"

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace dlab {

struct VoronoiDiagram {
    // vertices[t] = circumcenter of triangle t.
    std::vector<Vec2> vertices;

    struct Edge {
        std::int32_t a = kNone;  // Voronoi vertex (= triangle t(corner))
        std::int32_t b = kNone;  // the other Voronoi vertex (= t(o(corner))), kNone for a ray
        // The normal of the dual mesh edge V[n(c)] -> V[p(c)] turned to the right,
        // (dy, -dx): it points from a's side of the mesh edge to b's side (outward for a ray).
        // Not normalized, so it is exact up to the rounding of dx and dy (an edge longer than
        // DBL_MAX gives it at a quarter of its length: finite). For a ray it is the
        // ray's direction; for a finite edge of a Delaunay mesh vertices[b] - vertices[a] is a
        // non-negative multiple of it.
        Vec2 direction;
        std::int32_t corner = kNone;  // the mesh corner whose opposite edge this edge is dual to
        bool isRay() const { return b == kNone; }
    };
    // One per mesh edge, in the order forEachEdge visits them.
    std::vector<Edge> edges;
};

// Circumcenter of a, b, c, within a few ulps of the exact one whenever that is a finite double,
// for any finite inputs (1e-300 and 1e300 in one triangle, ±DBL_MAX, subnormals). The double
// formula (relative to a, after an exact power-of-two scaling) is used where its error bound
// proves that; elsewhere the exact rational value is computed with integers and rounded once.
// Collinear points give non-finite coordinates, as does a center beyond ±DBL_MAX.
Vec2 circumcenter(Vec2 a, Vec2 b, Vec2 c);

// Outward normal (dy, -dx) of the edge opposite corner c, V[n(c)] -> V[p(c)]: the right-hand
// side of that directed edge, away from t(c). Exact up to the rounding of dx and dy.
Vec2 edgeNormal(const Mesh& m, std::int32_t c);

// Calls f(c) once per mesh edge, with c the edge's lower-numbered corner (c < o(c)) or its
// only corner on the hull (o(c) == kNone).
template <class F>
void forEachEdge(const Mesh& m, F&& f) {
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        if (m.O[c] == kNone || c < m.O[c]) f(c);
    }
}

VoronoiDiagram buildVoronoi(const Mesh& m);

// The Voronoi cell of V[cornerAtVertex]: the triangles around that vertex in counter-clockwise
// order (their circumcenters are the cell's vertices), found by swinging with u() then s().
// closed == false for a hull vertex: the cell is unbounded, a ray along
// edgeNormal(m, prev(corners.front())) precedes the first entry and a ray along
// edgeNormal(m, next(corners.back())) follows the last one.
struct VoronoiCell {
    std::vector<std::int32_t> triangles;
    bool closed = false;
    std::vector<std::int32_t> corners;  // corners[i]: the corner of triangles[i] at the vertex
};

// Throws std::invalid_argument if the swing does not come back to its start within
// |V| steps (an inconsistent O; a valid mesh never does this).
VoronoiCell voronoiCell(const Mesh& m, std::int32_t cornerAtVertex);

// Calls f(v, cell) for every vertex used by a triangle, in vertex order.
template <class F>
void forEachVoronoiCell(const Mesh& m, F&& f) {
    const std::vector<std::int32_t> start = vertexCorners(m);
    for (std::int32_t v = 0; v < static_cast<std::int32_t>(start.size()); ++v) {
        if (start[v] != kNone) f(v, voronoiCell(m, start[v]));
    }
}

// Liang–Barsky: the part of p + t*d, t in [0, tMax] (tMax may be +infinity: a ray), inside the
// box [lo, hi]; nullopt if none. The box is closed: a segment touching it yields a point.
std::optional<std::pair<Vec2, Vec2>> clipToBox(Vec2 p, Vec2 d, double tMax, Vec2 lo, Vec2 hi);

// Every edge of the diagram clipped to the box [lo, hi] (segments to their visible part, rays
// to where they leave the box); edges with no part inside, or with a non-finite end, are
// dropped.
std::vector<std::pair<Vec2, Vec2>> clippedSegments(const VoronoiDiagram& diagram, Vec2 lo, Vec2 hi);

}  // namespace dlab
