// Writers for a finished mesh: Triangle's .node/.ele/.neigh and .v.node/.v.edge, OFF, OBJ, SVG.
//
// Every writer takes a std::ostream& and writes text only; failures show in the stream's state
// (writeTextFile, in output_files.h, checks it). Coordinates are written in the shortest form
// that reads back to the same double (appendShortest), so a .node written here and read by
// parseNode is bit-exact,
// subnormals and ±DBL_MAX included. Ids are in indexBase (0 or 1; anything else throws
// std::invalid_argument); "no neighbour" / "ray" is -1 whatever the base, as in Triangle.
#pragma once

#include "core/engine/geometry.h"
#include "core/engine/mesh.h"
#include "core/engine/numbers.h"       // appendShortest
#include "core/engine/output_files.h"  // writeTextFile(s): every writer here goes through them
#include "core/engine/voronoi.h"

#include <cstdint>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

namespace dlab {

// Triangle .node: "N 2 0 0", then "i x y" per point.
void writeNode(std::ostream& os, const std::vector<Vec2>& points, int indexBase = 0);
// Triangle .ele: "T 3 0", then "t v0 v1 v2" (counter-clockwise, as in the corner table).
void writeEle(std::ostream& os, const Mesh& mesh, int indexBase = 0);
// Triangle .neigh: "T 3", then "t n0 n1 n2", n_i the triangle across the edge opposite corner i,
// -1 on the hull.
void writeNeigh(std::ostream& os, const Mesh& mesh, int indexBase = 0);
// Triangle .v.node: "T 2 0 0", then "t cx cy" (the circumcenter of triangle t).
void writeVoronoiNode(std::ostream& os, const VoronoiDiagram& diagram, int indexBase = 0);
// Triangle .v.edge: "E 0", then "e a b" for a finite edge, "e a -1 dx dy" for a ray.
void writeVoronoiEdge(std::ostream& os, const VoronoiDiagram& diagram, int indexBase = 0);

// OFF: "OFF", "nv nt 0", "x y 0" per vertex (all of G, duplicates included), "3 a b c" per
// triangle.
void writeOff(std::ostream& os, const Mesh& mesh);
// Wavefront OBJ: "v x y 0" per vertex, "f a b c" per triangle (1-based).
void writeObj(std::ostream& os, const Mesh& mesh);

struct SvgOptions {
    bool mesh = true;                     // mesh edges, one <line> each
    bool points = true;                   // every point of G, one <circle> each
    bool voronoi = false;                 // Voronoi edges clipped to the drawing, one <line> each
    bool circumcircles = false;           // one <circle> per triangle
    double width = 800;                   // pixels; the height follows the points' aspect ratio
    std::vector<std::int32_t> highlight;  // triangles to fill, one <polygon> each
    std::string title;                    // shown as <title> and as a caption (escaped)
};

// XML text and attribute content, the one escaping of every SVG writer: markup characters
// escaped; what XML 1.0 forbids (control characters other than tab and newlines, malformed
// UTF-8) replaced by '?', so any title gives a well-formed document.
std::string xmlEscape(std::string_view s);

// A standalone SVG, y axis up, the points' bounding box fitted with a margin. Coordinates are
// mapped to pixels here (exact power-of-two prescaling, so 1e-300 and 1e300 wide inputs work), so
// stroke widths are plain pixels. Empty and one-point meshes give a valid picture, never NaN.
void writeSvg(std::ostream& os, const Mesh& mesh, const SvgOptions& options = {});

}  // namespace dlab
