// Mesh readers: Triangle .node/.ele/.neigh, OFF, OBJ, a corner-table dump and Delaunator's arrays.
//
// The same rules as the point readers (io_read.h): any bytes either give an ImportedMesh or throw
// InputError ("FILE:LINE: what"), never anything else; nothing is changed on disk; counts are
// refused before anything is allocated (at most kMaxPoints vertices and kMaxTriangles
// triangles). A reader checks the file's form only (fields, numbers, counts, array lengths):
// what the triangles say (an index out of range, a clockwise triangle, an O that points at the
// wrong corner) is kept as written for the checker (mesh_check.h) to name.
//
// Formats:
//   .ele   Triangle: "<#triangles> <3> [<#attributes>]", then "t a b c [attributes]"; triangle
//          ids consecutive from 0 or 1, vertex ids in the .node's base. The .node beside it
//          (same base name) holds the points; a .neigh beside it ("t n0 n1 n2", n_i the triangle
//          across the edge opposite corner i, -1 on the hull) is read too and gives O.
//   .off   "OFF", "nv nf [ne]", nv lines "x y z", nf lines "3 a b c" (0-based).
//   .obj   "v x y [z [w]]" and "f a b c" (1-based, negative = relative; "a/t/n" accepted);
//          other statements (vt, vn, g, o, s, usemtl, mtllib, l) are ignored.
//          OFF and OBJ are 2D when z is 0 or one constant (a warning for a nonzero constant);
//          a z that varies is refused, on the first line where it differs.
//   .corners  A corner table as text, one record a line: "g x y" per vertex (ids 0, 1, ... in
//          order), "v a b c" per triangle (the V of its corners 3t, 3t+1, 3t+2), and optionally
//          "o a b c" per triangle (the O of its corners, -1 on the boundary: all triangles or
//          none). Records of one kind may come in any order relative to the others.
//   .json  Either a corner table {"G": [[x,y],...], "V": [...], "O": [...]} (O optional) or
//          Delaunator's output {"coords": [x0,y0,x1,...], "triangles": [...], "halfedges":
//          [...]} (what JSON.stringify gives after Array.from of each). Other keys are ignored.
//          Delaunator's half-edge e runs from triangles[e] to triangles[next(e)]; our corner c
//          faces the edge V[n(c)] -> V[p(c)], which is half-edge n(c): O[c] =
//          prev(halfedges[next(c)]). When most triangles are clockwise with y up (Delaunator's
//          counter-clockwise on a y-down screen), corners 1 and 2 of every triangle are swapped
//          (O follows them) and a warning says so.
#pragma once

#include "core/engine/io_read.h"
#include "core/engine/mesh.h"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace dlab {

// Twice the point limit: a triangulation of n points has fewer than 2n triangles, and 3 *
// kMaxTriangles corners stay far below INT32_MAX.
inline constexpr std::size_t kMaxTriangles = 2 * kMaxPoints;

struct ImportedMesh {
    Mesh mesh;                          // V 0-based as written (may be out of range), O as given
    bool hasOpposites = false;          // O came from the input (.neigh, a corner table's O,
                                        // Delaunator's halfedges); else O is all kNone
    int indexBase = 0;                  // the ids the file uses for vertices (and triangles)
    std::string format;                 // "Triangle .ele", "OFF", "corner table (JSON)", ...
    std::vector<std::string> inputs;    // every file read
    std::vector<std::string> warnings;  // non-fatal remarks (a constant z, swapped orientation)
};

// Reads a mesh by its extension: .ele (with its .node and .neigh), .off, .obj, .corners, .json.
// Throws InputError for anything else, naming the formats it reads.
ImportedMesh readMeshFile(const std::string& path);
// The same, with the points taken from another file (any point format of io_read.h) for an
// .ele; for the other formats the file's own points are replaced by those (same count needed).
ImportedMesh readMeshFile(const std::string& path, const std::string& pointsPath);
// True when readMeshFile takes this path's extension.
bool isMeshPath(const std::string& path);

// Parsers over in-memory text; `name` names the text in messages.
// An .ele against given points (indexBase from the .node); `neigh` may be empty (none).
ImportedMesh parseEle(std::string_view ele, const std::string& eleName, const PointSet& nodes,
                      std::string_view neigh = {}, const std::string& neighName = {});
// A .neigh for a mesh read from an .ele: gives its O (hasOpposites), or throws.
void parseNeigh(std::string_view neigh, const std::string& neighName, ImportedMesh& im);
ImportedMesh parseOff(std::string_view text, const std::string& name);
ImportedMesh parseObj(std::string_view text, const std::string& name);
ImportedMesh parseCornerText(std::string_view text, const std::string& name);
// A corner table or Delaunator's output, told apart by their keys.
ImportedMesh parseMeshJson(std::string_view text, const std::string& name);

}  // namespace dlab
