// Point-set generators: the paper's uniform box and the inputs that broke other triangulators.
#pragma once

#include "core/engine/geometry.h"
#include "core/engine/mesh.h"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace dlab {

enum class Generator : std::uint8_t {
    Uniform,         // uniform in the paper's 1600 x 1600 box
    Clusters,        // Gaussian clusters
    Grid,            // integer lattice: many cocircular quadruples
    RotatedGrid,     // a lattice rotated by an irrational angle (near-degenerate, not exact)
    Ngon,            // regular N-gon: all points cocircular
    Circle,          // random points on a circle (rounded: nearly cocircular)
    Collinear,       // several collinear runs, plus a few points off the lines
    NearDuplicates,  // clusters of points 1-4 ulps apart, and exact duplicates
    HugeTinyBox,     // a 64 x 64 box at coordinates around 1e15 (ulp 0.125: tiny relative extent)
    AllCollinear,    // every point on one line (no triangle exists)
    // Uneven density: what a fixed grid over the bounding box sorts badly.
    Gaussian,        // one normal distribution (sigma 200) around the box's centre
    UnevenClusters,  // clusters whose sizes and spreads differ by orders of magnitude
    Kuzmin,          // Kuzmin's disc (PBBS): mass within r is 1 - 1/sqrt(1 + r^2), heavy-tailed
    LogRadial,       // around the origin, the radius log-uniform over 12 decades (1e-12 ... 1)
    DiscInBox,       // 90 % in a disc of radius 4, 10 % spread over the 1600 x 1600 box
    Curves,          // on a line, a circle and a spiral, bunched towards one end of each
    // Points in convex position and long facing chains: what a split in two and a join attack.
    Parabola,    // y = x^2 for a uniform x: every point on the hull, both halves convex chains
    FacingArcs,  // two circular arcs bulging towards each other across the middle
    Spiral,      // an Archimedean spiral of six turns, evenly spread along its length
    ConvexHull,  // integer x and y = x^2 exactly: every point a hull vertex, no rounding
};

const char* toString(Generator g);
std::optional<Generator> parseGenerator(std::string_view name);
std::string generatorNames();  // "uniform, clusters, ..." for help texts
// Every kind, in the order of generatorNames().
std::vector<Generator> allGenerators();

std::vector<Vec2> generatePoints(Generator kind, std::size_t n, std::uint64_t seed);

// A triangulation of n points that Lawson's flip algorithm needs quadratically many flips to make
// Delaunay (n even, at least 6: n / 2 points on each of two chains). The chains run side by side
// and bow towards each other, so every point of one sees every point of the other and no edge
// joins two points of one chain across the middle. Between the chains the mesh is two fans: the
// upper chain's first point joined to every lower point, the lower chain's last point to every
// upper point; the caps outside the chains are fans too. The Delaunay triangulation joins each
// point to the nearest ones across, and each flip between the chains moves one cell of the
// lattice path such a triangulation is, so on the order of n^2 / 8 flips. Integer coordinates
// (exact), counter-clockwise triangles, O computed.
Mesh flipWorstCase(std::size_t n);

// The built-in demo: 12 points that show a locate walk, splits, flips and a point on an edge.
std::vector<Vec2> demoPoints();

}  // namespace dlab
