// Shared check of the mesh-reader fuzz targets: any bytes either read, or fail with one
// InputError line naming the input and a line of it; a mesh read is checked (it must not crash,
// and what it reports must hold together), and one the checker calls a triangulation is
// repaired by flips into an exact Delaunay triangulation (GMP).
#pragma once

#include "core/engine/mesh_read.h"
#include "core/engine/triangulation_check.h"
#include "tests/exact_check.h"
#include "tests/fuzz/fuzz_common.h"

#include <cmath>
#include <functional>
#include <string>

namespace dlab::fuzz {

inline void checkImportedMesh(const ImportedMesh& im) {
    const Mesh& m = im.mesh;
    require(m.V.size() % 3 == 0 && m.O.size() == m.V.size(), "|V| = |O|, a multiple of 3");
    require(m.G.size() <= kMaxPoints && m.V.size() <= 3 * kMaxTriangles, "within the limits");
    for (const Vec2 p : m.G) require(std::isfinite(p.x) && std::isfinite(p.y), "finite points");
    CheckOptions o;
    o.hasOpposites = im.hasOpposites;
    o.indexBase = im.indexBase;
    const CheckReport r = checkMesh(m, o);
    require(r.summary().find('\n') == std::string::npos, "the summary is one line");
    require(!r.isDelaunay() || r.isTriangulation(), "Delaunay implies a triangulation");
    for (const MeshProblem& p : r.problems) {
        require(!p.message.empty() && p.message.find('\n') == std::string::npos,
                "a problem is one line", p.message);
        for (const std::int32_t t : p.triangles)
            require(t >= 0 && t < m.numTriangles(), "a problem names triangles that exist");
    }
    if (!r.isTriangulation() || m.numTriangles() > 400) return;
    if (r.isDelaunay()) {
        Mesh copy = m;
        copy.O = r.opposites;
        require(checkDelaunayExact(copy).empty(), "a mesh checked valid Delaunay is (GMP)",
                checkDelaunayExact(copy));
    }
    const RepairResult fixed = repairByFlips(m, r);
    const std::string exact = checkDelaunayExact(fixed.mesh);
    require(exact.empty(), "the repair ends exactly Delaunay (GMP)", exact);
}

inline void checkMeshReader(std::string_view text, const std::string& name,
                            const std::function<ImportedMesh()>& read) {
    ImportedMesh im;
    try {
        im = read();
    } catch (const InputError& e) {
        checkInputError(e, text, name);
        return;
    }
    checkImportedMesh(im);
}

}  // namespace dlab::fuzz
