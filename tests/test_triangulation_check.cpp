// Mesh readers and the exact checker: a defect of every kind planted in a Delaunay mesh and
// written in every format is named with its elements; our meshes check as valid Delaunay;
// Lawson's repair ends exactly Delaunay (GMP); dtlab check and repair end to end.
#include "core/engine/generators.h"
#include "core/engine/inserter.h"
#include "core/engine/io_read.h"
#include "core/engine/io_write.h"
#include "core/engine/mesh_diff.h"
#include "core/engine/mesh_read.h"
#include "core/engine/predicates.h"
#include "core/engine/triangulation_check.h"
#include "tests/exact_check.h"
#include "tests/run_dtlab.h"
#include "tests/scrambled_mesh.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

using namespace dlab;
using Kind = MeshProblem::Kind;
namespace fs = std::filesystem;

namespace {

enum class Format { Ele, EleNeigh, Off, Obj, CornerText, CornerJson, Delaunator };
constexpr Format kFormats[] = {Format::Ele,       Format::EleNeigh,   Format::Off,
                               Format::Obj,       Format::CornerText, Format::CornerJson,
                               Format::Delaunator};

const char* formatName(Format f) {
    switch (f) {
        case Format::Ele: return "ele";
        case Format::EleNeigh: return "ele+neigh";
        case Format::Off: return "off";
        case Format::Obj: return "obj";
        case Format::CornerText: return "corners";
        case Format::CornerJson: return "corner-json";
        case Format::Delaunator: return "delaunator";
    }
    return "?";
}

bool holdsOpposites(Format f) {
    return f == Format::EleNeigh || f == Format::CornerText || f == Format::CornerJson ||
           f == Format::Delaunator;
}

// Even integer coordinates, so that midpoints are exact.
Mesh delaunayMesh(std::size_t n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> d(0, 500);
    std::vector<Vec2> pts;
    for (std::size_t i = 0; i < n; ++i) pts.push_back({2.0 * d(rng), 2.0 * d(rng)});
    Inserter ins(pts, InsertOptions{});
    ins.run();
    return ins.mesh();
}

std::string text(const std::function<void(std::ostream&)>& write) {
    std::ostringstream os;
    write(os);
    return os.str();
}

std::string cornerText(const Mesh& m) {
    std::string s = "# a corner table\n";
    for (const Vec2 p : m.G) s += "g " + shortest(p.x) + " " + shortest(p.y) + "\n";
    for (std::int32_t t = 0; t < m.numTriangles(); ++t)
        s += "v " + std::to_string(m.V[3 * t]) + " " + std::to_string(m.V[3 * t + 1]) + " " +
             std::to_string(m.V[3 * t + 2]) + "\n";
    for (std::int32_t t = 0; t < m.numTriangles(); ++t)
        s += "o " + std::to_string(m.O[3 * t]) + " " + std::to_string(m.O[3 * t + 1]) + " " +
             std::to_string(m.O[3 * t + 2]) + "\n";
    return s;
}

std::string jsonInts(const std::vector<std::int32_t>& v) {
    std::string s = "[";
    for (std::size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + std::to_string(v[i]);
    return s + "]";
}

std::string cornerJson(const Mesh& m) {
    std::string s = "{\"G\": [";
    for (std::size_t i = 0; i < m.G.size(); ++i)
        s += (i ? ", [" : "[") + shortest(m.G[i].x) + ", " + shortest(m.G[i].y) + "]";
    return s + "],\n \"V\": " + jsonInts(m.V) + ",\n \"O\": " + jsonInts(m.O) + "}\n";
}

std::int32_t swap12(std::int32_t c) {
    return c < 0 || c % 3 == 0 ? c : (c % 3 == 1 ? c + 1 : c - 1);
}

// Delaunator's arrays: its triangles clockwise with y up (corners 1 and 2 swapped), half-edge e
// from triangles[e] to triangles[next(e)], halfedges[next(c)] = next(O[c]).
std::string delaunatorJson(const Mesh& m) {
    std::vector<std::int32_t> tris(m.V.size()), half(m.V.size());
    for (std::int32_t c = 0; c < m.numCorners(); ++c) tris[swap12(c)] = m.V[c];
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        const std::int32_t o = m.O[c];
        const std::int32_t e = swap12(c);
        half[next(e)] = o < 0 ? o : (o >= m.numCorners() ? o : next(swap12(o)));
    }
    std::string s = "{\"coords\": [";
    for (std::size_t i = 0; i < m.G.size(); ++i)
        s += (i ? "," : "") + shortest(m.G[i].x) + "," + shortest(m.G[i].y);
    return s + "], \"triangles\": " + jsonInts(tris) + ", \"halfedges\": " + jsonInts(half) + "}";
}

// The mesh written in a format and read back.
ImportedMesh roundTrip(const Mesh& m, Format f) {
    switch (f) {
        case Format::Ele:
        case Format::EleNeigh: {
            const PointSet nodes =
                parseNode(text([&](std::ostream& os) { writeNode(os, m.G, 1); }), "m.node");
            const std::string ele = text([&](std::ostream& os) { writeEle(os, m, 1); });
            if (f == Format::Ele) return parseEle(ele, "m.ele", nodes);
            return parseEle(ele, "m.ele", nodes,
                            text([&](std::ostream& os) { writeNeigh(os, m, 1); }), "m.neigh");
        }
        case Format::Off:
            return parseOff(text([&](std::ostream& os) { writeOff(os, m); }), "m.off");
        case Format::Obj:
            return parseObj(text([&](std::ostream& os) { writeObj(os, m); }), "m.obj");
        case Format::CornerText: return parseCornerText(cornerText(m), "m.corners");
        case Format::CornerJson: return parseMeshJson(cornerJson(m), "m.json");
        case Format::Delaunator: return parseMeshJson(delaunatorJson(m), "d.json");
    }
    return {};
}

CheckReport check(const ImportedMesh& im) {
    CheckOptions o;
    o.hasOpposites = im.hasOpposites;
    o.indexBase = im.indexBase;
    return checkMesh(im.mesh, o);
}

bool contains(const std::vector<std::int32_t>& v, std::int32_t x) {
    return std::find(v.begin(), v.end(), x) != v.end();
}

// A defect planted in a copy of a Delaunay mesh, and what the checker must name.
struct Planted {
    Mesh mesh;
    Kind kind;
    std::vector<std::int32_t> triangles, vertices, corners;  // each must be in the problem
    bool needsOpposites = false;
};

std::int32_t interiorCorner(const Mesh& m) {
    for (std::int32_t c = 0; c < m.numCorners(); ++c)
        if (m.O[c] != kNone) return c;
    return kNone;
}

void appendTriangle(Mesh& m, std::int32_t a, std::int32_t b, std::int32_t c) {
    m.V.insert(m.V.end(), {a, b, c});
    m.O.insert(m.O.end(), {kNone, kNone, kNone});
}

void removeTriangle(Mesh& m, std::int32_t t) {  // the last triangle moves to t
    const std::int32_t last = m.numTriangles() - 1;
    for (std::int32_t k = 0; k < 3; ++k)
        if (m.O[3 * t + k] != kNone) m.O[m.O[3 * t + k]] = kNone;
    for (std::int32_t k = 0; k < 3 && t != last; ++k) {
        m.V[3 * t + k] = m.V[3 * last + k];
        m.O[3 * t + k] = m.O[3 * last + k];
        if (m.O[3 * t + k] != kNone) m.O[m.O[3 * t + k]] = 3 * t + k;
    }
    m.V.resize(m.V.size() - 3);
    m.O.resize(m.O.size() - 3);
}

// A triangle with `boundaryEdges` corners on the boundary and a vertex not on the hull.
std::int32_t triangleWithBoundary(const Mesh& m, int boundaryEdges) {
    std::vector<char> onHull(m.G.size(), 0);
    for (std::int32_t c = 0; c < m.numCorners(); ++c)
        if (m.O[c] == kNone) onHull[m.V[next(c)]] = onHull[m.V[prev(c)]] = 1;
    for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
        int b = 0, interior = 0;
        for (std::int32_t k = 0; k < 3; ++k) {
            b += m.O[3 * t + k] == kNone;
            interior += !onHull[m.V[3 * t + k]];
        }
        if (b == boundaryEdges && interior >= (boundaryEdges == 0 ? 3 : 1)) return t;
    }
    return kNone;
}

using dlab::test::flipEdge;

// A flippable edge (the quadrilateral strictly convex) that is not cocircular.
std::int32_t convexEdge(const Mesh& m, std::int32_t from = 0) {
    for (std::int32_t c = from; c < m.numCorners(); ++c) {
        const std::int32_t d = m.O[c];
        if (d == kNone || d < c) continue;
        const Vec2 P = m.point(c), A = m.point(next(c)), B = m.point(prev(c)), D = m.point(d);
        if (orient2d(P, A, D) > 0 && orient2d(D, B, P) > 0 && incircle(P, A, B, D) < 0) return c;
    }
    return kNone;
}

std::vector<Planted> plantDefects(const Mesh& base) {
    std::vector<Planted> out;
    const auto plant = [&](Kind kind) -> Planted& {
        out.push_back({base, kind, {}, {}, {}, false});
        return out.back();
    };
    const std::int32_t nv = base.numVertices(), nt = base.numTriangles();
    {
        Planted& p = plant(Kind::VertexRange);
        p.mesh.V[4] = nv + 5;
        p.triangles = {1};
    }
    {
        Planted& p = plant(Kind::RepeatedVertex);
        p.mesh.V[7] = p.mesh.V[6];
        p.triangles = {2};
    }
    {
        Planted& p = plant(Kind::FlatTriangle);
        const Vec2 a = base.G[base.V[0]], b = base.G[base.V[1]];
        p.mesh.G.push_back({(a.x + b.x) / 2, (a.y + b.y) / 2});
        appendTriangle(p.mesh, base.V[0], base.V[1], nv);
        p.triangles = {nt};
    }
    {
        Planted& p = plant(Kind::ClockwiseTriangle);
        std::swap(p.mesh.V[10], p.mesh.V[11]);
        p.triangles = {3};
    }
    {
        Planted& p = plant(Kind::EdgeInManyTriangles);
        const std::int32_t c = interiorCorner(base);
        appendTriangle(p.mesh, base.V[next(c)], base.V[prev(c)], base.V[c]);
        p.triangles = {tri(c), tri(base.O[c]), nt};
    }
    {
        Planted& p = plant(Kind::Overlap);
        const Vec2 a = base.point(0), b = base.point(1), c = base.point(2);
        const auto mix = [](Vec2 x, Vec2 y, Vec2 z) {
            return Vec2{(2 * x.x + y.x + z.x) / 4, (2 * x.y + y.y + z.y) / 4};
        };
        p.mesh.G.insert(p.mesh.G.end(), {mix(a, b, c), mix(b, c, a), mix(c, a, b)});
        appendTriangle(p.mesh, nv, nv + 1, nv + 2);
        p.triangles = {0, nt};
    }
    {
        Planted& p = plant(Kind::Hole);
        const std::int32_t t = triangleWithBoundary(base, 0);
        p.vertices = {base.V[3 * t], base.V[3 * t + 1], base.V[3 * t + 2]};
        removeTriangle(p.mesh, t);
    }
    {
        Planted& p = plant(Kind::NonConvexOutline);
        const std::int32_t t = triangleWithBoundary(base, 1);
        for (std::int32_t k = 0; k < 3; ++k)
            if (base.O[3 * t + k] == kNone) p.vertices = {base.V[3 * t + k]};
        removeTriangle(p.mesh, t);
    }
    {
        Planted& p = plant(Kind::DuplicatePoint);
        p.mesh.G.push_back(base.G[base.V[0]]);
        p.mesh.V[0] = nv;
        p.vertices = {base.V[0], nv};
    }
    {
        Planted& p = plant(Kind::UnusedPoint);
        p.mesh.G.push_back({-7, -9});
        p.vertices = {nv};
    }
    {
        Planted& p = plant(Kind::UnusedDuplicate);
        p.mesh.G.push_back(base.G[base.V[5]]);
        p.vertices = {nv, base.V[5]};
    }
    {
        Planted& p = plant(Kind::NotDelaunay);
        const std::int32_t c = convexEdge(base);
        const std::int32_t d = base.O[c];
        flipEdge(p.mesh, c);
        p.vertices = {base.V[c], base.V[d]};
    }
    const std::int32_t c = interiorCorner(base), d = base.O[c];
    {
        Planted& p = plant(Kind::OppositeRange);
        p.mesh.O[c] = base.numCorners() + 7;
        p.corners = {c};
        p.needsOpposites = true;
    }
    {
        Planted& p = plant(Kind::OppositeNotInvolution);
        std::int32_t far = 0;  // a corner of a third triangle
        while (tri(far) == tri(c) || tri(far) == tri(d)) far += 3;
        p.mesh.O[d] = far;  // O[c] = d still, but O[d] no longer c
        p.corners = {c};
        p.needsOpposites = true;
    }
    {
        Planted& p = plant(Kind::OppositeWrongEdge);
        p.mesh.O[c] = kNone;  // -1 on a shared edge (O[d] still says c)
        p.corners = {c};
        p.needsOpposites = true;
    }
    return out;
}

bool names(const MeshProblem& p, const Planted& want) {
    for (const std::int32_t t : want.triangles)
        if (!contains(p.triangles, t)) return false;
    for (const std::int32_t v : want.vertices)
        if (!contains(p.vertices, v)) return false;
    for (const std::int32_t c : want.corners)
        if (!contains(p.corners, c)) return false;
    return true;
}

std::string listed(const CheckReport& r) {
    std::string s = r.summary();
    for (const MeshProblem& p : r.problems)
        s += std::string("\n  ") + toString(p.kind) + ": " + p.message;
    return s;
}

}  // namespace

TEST(TriangulationCheck, OurMeshesInEveryFormatAreValidDelaunay) {
    for (const unsigned seed : {1u, 2u, 3u}) {
        const Mesh m = delaunayMesh(60, seed);
        ASSERT_EQ(checkDelaunayExact(m), "");
        for (const Format f : kFormats) {
            const ImportedMesh im = roundTrip(m, f);
            EXPECT_EQ(im.hasOpposites, holdsOpposites(f)) << formatName(f);
            const CheckReport r = check(im);
            EXPECT_TRUE(r.isDelaunay()) << formatName(f) << ": " << listed(r);
            EXPECT_EQ(r.triangles, m.numTriangles());
            if (f != Format::Delaunator) {
                EXPECT_EQ(im.mesh.V, m.V) << formatName(f);
            }
            if (holdsOpposites(f)) {
                EXPECT_EQ(r.opposites, im.mesh.O) << formatName(f);
            }
        }
    }
}

TEST(TriangulationCheck, DelaunatorHalfEdgesAreTwinsAndMapToOurOpposites) {
    const Mesh m = delaunayMesh(40, 7);
    const std::string json = delaunatorJson(m);
    // The written arrays follow Delaunator's definition: half-edge e runs from triangles[e] to
    // triangles[next(e)], and its twin runs the other way.
    const ImportedMesh raw = parseMeshJson(json, "d.json");
    ASSERT_FALSE(raw.warnings.empty());
    EXPECT_NE(raw.warnings[0].find("clockwise with y up"), std::string::npos) << raw.warnings[0];
    EXPECT_EQ(raw.mesh.V, m.V);  // corners 1 and 2 swapped back
    EXPECT_EQ(raw.mesh.O, m.O);
    // Counter-clockwise arrays (no swap) read as they are.
    std::vector<std::int32_t> half(m.V.size());
    for (std::int32_t c = 0; c < m.numCorners(); ++c)
        half[next(c)] = m.O[c] < 0 ? -1 : next(m.O[c]);
    std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> from;
    for (std::int32_t e = 0; e < m.numCorners(); ++e) from[{m.V[e], m.V[next(e)]}] = e;
    for (std::int32_t e = 0; e < m.numCorners(); ++e) {
        const auto twin = from.find({m.V[next(e)], m.V[e]});
        EXPECT_EQ(half[e], twin == from.end() ? -1 : twin->second);
    }
    std::string ccw = "{\"coords\": [";
    for (std::size_t i = 0; i < m.G.size(); ++i)
        ccw += (i ? "," : "") + shortest(m.G[i].x) + "," + shortest(m.G[i].y);
    ccw += "], \"triangles\": " + jsonInts(m.V) + ", \"halfedges\": " + jsonInts(half) + "}";
    const ImportedMesh kept = parseMeshJson(ccw, "ccw.json");
    EXPECT_EQ(kept.mesh.V, m.V);
    EXPECT_EQ(kept.mesh.O, m.O);
    EXPECT_TRUE(check(kept).isDelaunay());
}

TEST(TriangulationCheck, EveryPlantedDefectIsNamedInEveryFormat) {
    const Mesh base = delaunayMesh(60, 11);
    for (const Planted& p : plantDefects(base)) {
        for (const Format f : kFormats) {
            if (p.needsOpposites && !holdsOpposites(f)) continue;
            if (p.kind == Kind::OppositeRange && f == Format::EleNeigh) continue;  // a read error
            SCOPED_TRACE(std::string(toString(p.kind)) + " in " + formatName(f));
            ImportedMesh im;
            ASSERT_NO_THROW(im = roundTrip(p.mesh, f));
            const CheckReport r = check(im);
            const Planted& want = p;  // Delaunator's corners come back in our numbering
            const bool found = std::any_of(
                r.problems.begin(), r.problems.end(),
                [&](const MeshProblem& q) { return q.kind == p.kind && names(q, want); });
            EXPECT_TRUE(found) << listed(r);
            EXPECT_EQ(r.isDelaunay(), p.kind == Kind::UnusedDuplicate) << listed(r);
        }
    }
}

TEST(TriangulationCheck, ANeighbourOutOfRangeIsABadLine) {
    const Mesh m = delaunayMesh(20, 3);
    const PointSet nodes =
        parseNode(text([&](std::ostream& os) { writeNode(os, m.G, 0); }), "m.node");
    const std::string ele = text([&](std::ostream& os) { writeEle(os, m, 0); });
    std::string neigh = text([&](std::ostream& os) { writeNeigh(os, m, 0); });
    const std::size_t line2 = neigh.find('\n') + 1;
    neigh.replace(line2, neigh.find('\n', line2) - line2, "0 999 -1 -1");
    try {
        parseEle(ele, "m.ele", nodes, neigh, "m.neigh");
        FAIL() << "read";
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), "m.neigh");
        EXPECT_EQ(e.line(), 2);
        EXPECT_NE(e.message().find("999"), std::string::npos) << e.what();
    }
}

TEST(TriangulationCheck, ReadersRefuseMalformedInputWithTheLine) {
    const PointSet nodes = parseNode("3 2\n0 0 0\n1 1 0\n2 0 1\n", "p.node");
    const struct {
        std::function<ImportedMesh()> read;
        int line;
        const char* words;
    } cases[] = {
        {[&] { return parseEle("2 3 0\n0 0 1 2\n", "m.ele", nodes); }, 2, "expected 2"},
        {[&] { return parseEle("1 3 0\n0 0 1\n", "m.ele", nodes); }, 2, "fields"},
        {[&] { return parseEle("1 6 0\n0 0 1 2 3 4 5\n", "m.ele", nodes); }, 1, "must be 3"},
        {[&] { return parseEle("1 3\n5 0 1 2\n", "m.ele", nodes); }, 2, "0 or 1"},
        {[&] { return parseOff("OFF\n3 1 0\n0 0 0\n1 0 1\n0 1 0\n3 0 1 2\n", "m.off"); }, 4, "3D"},
        {[&] { return parseOff("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2 0\n", "m.off"); }, 6,
         "only triangles"},
        {[&] { return parseOff("OF\n", "m.off"); }, 1, "OFF"},
        {[&] { return parseObj("v 0 0 0\nv 1 0 0\nv 0 1 2\n", "m.obj"); }, 3, "3D"},
        {[&] { return parseObj("v 0 0\nv 1 0\nv 0 1\nf 1 2 3 1\n", "m.obj"); }, 4,
         "only triangles"},
        {[&] { return parseObj("v 0 0\nf 1 x 3\n", "m.obj"); }, 2, "integer"},
        {[&] { return parseCornerText("g 0 0\nv 0 0\n", "m.corners"); }, 2, "fields"},
        {[&] {
             return parseCornerText("g 0 0\ng 1 0\ng 0 1\nv 0 1 2\nv 0 1 2\no -1 -1 -1\n",
                                    "m.corners");
         },
         6, "every triangle"},
        {[&] { return parseCornerText("g 0 nan\n", "m.corners"); }, 1, "non-finite"},
        {[&] { return parseMeshJson("{\"G\": [[0,0],[1,0],[0,1]],\n\"V\": [0,1]}", "m.json"); }, 2,
         "multiple of 3"},
        {[&] { return parseMeshJson("{\"G\": [[0,0]], \"V\": [0,0,0], \"O\": [-1]}", "m.json"); },
         1, "\"O\" holds 1"},
        {[&] {
             return parseMeshJson("{\"coords\": [0,0,1],\n\"triangles\": [], \"halfedges\": []}",
                                  "d.json");
         },
         1, "x, y pairs"},
        {[&] {
             return parseMeshJson(
                 "{\"coords\": [0,0,1,0,0,1], \"triangles\": [0,1,2],\n\"halfedges\": [-1]}",
                 "d.json");
         },
         2, "\"halfedges\" holds 1"},
        {[&] {
             return parseMeshJson("{\"coords\": [0,0,1,0,0,1],\n \"triangles\": [0,1,2.5]",
                                  "d.json");
         },
         2, "integer"},
        {[&] { return parseMeshJson("{\"x\": 1}", "d.json"); }, 0, "neither"},
        {[&] { return parseMeshJson("[1,2]", "d.json"); }, 1, "expected '{'"},
    };
    for (const auto& c : cases) {
        try {
            c.read();
            ADD_FAILURE() << "read: " << c.words;
        } catch (const InputError& e) {
            EXPECT_EQ(e.line(), c.line) << e.what();
            EXPECT_NE(e.message().find(c.words), std::string::npos) << e.what();
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
        }
    }
}

TEST(TriangulationCheck, FlatMeshesWithAConstantZAreReadWithAWarning) {
    const ImportedMesh off = parseOff("OFF\n3 1 0\n0 0 5\n1 0 5\n0 1 5\n3 0 1 2\n", "m.off");
    ASSERT_EQ(off.warnings.size(), 1u);
    EXPECT_NE(off.warnings[0].find("every z is 5"), std::string::npos);
    const ImportedMesh obj =
        parseObj("v 0 0\nv 1 0\nv 0 1\nvn 0 0 1\nf 1//1 2//1 -1//1\n", "m.obj");
    EXPECT_EQ(obj.mesh.V, (std::vector<std::int32_t>{0, 1, 2}));
    EXPECT_TRUE(check(obj).isDelaunay());
}

TEST(TriangulationCheck, RepairByFlipsEndsExactlyDelaunayWithTheNumberingKept) {
    for (const unsigned seed : {4u, 5u, 6u}) {
        const Mesh base = delaunayMesh(200, seed);
        Mesh m = base;
        const int flipped = dlab::test::scrambleByLegalFlips(m, seed, 400);
        ASSERT_GT(flipped, 100);
        const CheckReport before = checkMesh(m);
        ASSERT_TRUE(before.isTriangulation()) << listed(before);
        ASSERT_GT(before.count(Kind::NotDelaunay), 0u);
        EXPECT_NE(checkDelaunayExact(m), "");
        const RepairResult r = repairByFlips(m, before);
        EXPECT_EQ(checkDelaunayExact(r.mesh), "");
        EXPECT_TRUE(checkMesh(r.mesh).isDelaunay());
        EXPECT_EQ(r.mesh.G, base.G);
        EXPECT_EQ(r.mesh.numTriangles(), base.numTriangles());
        EXPECT_GE(r.flips.size(), before.count(Kind::NotDelaunay));
        EXPECT_GE(r.incircleTests, static_cast<std::int64_t>(r.flips.size()));
    }
}

// The flip worst case: a valid triangulation whose repair by Lawson's flips takes at least
// n^2 / 8 flips (quadratic: doubling n at least triples them), ending exactly Delaunay with the
// points as generated.
TEST(TriangulationCheck, TheFlipWorstCaseNeedsQuadraticallyManyFlips) {
    std::size_t previous = 0;
    for (const std::size_t n : {20u, 40u, 80u, 160u}) {
        SCOPED_TRACE(n);
        const Mesh m = flipWorstCase(n);
        ASSERT_EQ(m.numVertices(), static_cast<std::int32_t>(n));
        const CheckReport report = checkMesh(m);
        ASSERT_TRUE(report.isTriangulation()) << listed(report);
        ASSERT_EQ(report.opposites, m.O);
        const RepairResult r = repairByFlips(m, report);
        EXPECT_GE(r.flips.size(), n * n / 8);
        if (previous != 0) {
            EXPECT_GE(r.flips.size(), 3 * previous);
        }
        previous = r.flips.size();
        EXPECT_EQ(checkDelaunayExact(r.mesh), "");
        EXPECT_EQ(r.mesh.G, m.G);
    }
    EXPECT_THROW(flipWorstCase(7), std::invalid_argument);
    EXPECT_THROW(flipWorstCase(4), std::invalid_argument);
}

// The flip algorithm stepped like insertion: the inserter's repair run makes the flips that
// repairByFlips makes, in the same order; its end is exactly Delaunay; stepping back restores
// the imported mesh after Start bit for bit and the empty table at 0.
TEST(TriangulationCheck, TheSteppedRepairFlipsAsTheBatchRepairAndStepsBack) {
    for (const unsigned seed : {7u, 8u}) {
        Mesh m = delaunayMesh(150, seed);
        dlab::test::scrambleByLegalFlips(m, seed, 300);
        const CheckReport report = checkMesh(m);
        ASSERT_TRUE(report.isTriangulation()) << listed(report);
        ASSERT_GT(report.count(Kind::NotDelaunay), 0u);
        const RepairResult batch = repairByFlips(m, report);

        Inserter ins(m.G, Inserter::StartMesh{m.V, report.opposites});
        ASSERT_TRUE(ins.repairs());
        Journal journal(ins);
        ASSERT_NE(journal.forward(), nullptr);  // Start
        ASSERT_EQ(ins.mesh().V, m.V);
        ASSERT_EQ(ins.mesh().O, report.opposites);
        std::vector<std::int32_t> flips;
        std::size_t tests = 0;
        while (const Op* op = journal.forward()) {
            if (op->type == OpType::Flip) flips.push_back(op->a);
            if (op->type == OpType::InCircleTest) ++tests;
            EXPECT_EQ(op->vertex, kNone);
        }
        ASSERT_TRUE(ins.done());
        std::vector<std::int32_t> batchFlips;
        for (const FlipRecord& f : batch.flips) batchFlips.push_back(f.corner);
        EXPECT_EQ(flips, batchFlips);
        EXPECT_GE(tests, flips.size());
        EXPECT_EQ(ins.stats().flips, static_cast<std::int64_t>(flips.size()));
        EXPECT_EQ(ins.mesh().V, batch.mesh.V);
        EXPECT_EQ(ins.mesh().O, batch.mesh.O);
        EXPECT_EQ(ins.mesh().G, m.G);
        EXPECT_EQ(checkDelaunayExact(ins.mesh()), "");
        EXPECT_TRUE(ins.flipStack().empty());

        journal.seek(1);  // just after Start: the imported mesh again
        EXPECT_EQ(ins.mesh().V, m.V);
        EXPECT_EQ(ins.mesh().O, report.opposites);
        journal.seek(0);
        EXPECT_EQ(ins.mesh().numTriangles(), 0);
        EXPECT_TRUE(ins.flipStack().empty());
        journal.seek(journal.recorded());
        EXPECT_EQ(ins.mesh().V, batch.mesh.V);

        // The batch path of the same run ends in the same mesh.
        Inserter once(m.G, Inserter::StartMesh{m.V, report.opposites});
        once.run();
        EXPECT_EQ(once.mesh().V, batch.mesh.V);
        EXPECT_EQ(once.stats().flips, static_cast<std::int64_t>(flips.size()));
    }
}

TEST(TriangulationCheck, AStartMeshWithAWrongOppositeIsRefused) {
    const std::vector<Vec2> pts{{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    EXPECT_THROW(Inserter(pts, Inserter::StartMesh{{0, 1, 2}, {1, kNone, kNone}}),
                 std::invalid_argument);
    EXPECT_THROW(Inserter(pts, Inserter::StartMesh{{0, 1, 7}, {kNone, kNone, kNone}}),
                 std::invalid_argument);
    EXPECT_NO_THROW(Inserter(pts, Inserter::StartMesh{{0, 1, 2}, {kNone, kNone, kNone}}));
}

TEST(TriangulationCheck, TheDiffWithDelaunayNamesTheEdgesThatDiffer) {
    const Mesh base = delaunayMesh(200, 7);
    const DelaunayDiff same = diffWithDelaunay(base);
    EXPECT_EQ(same.onlyGiven.size(), 0u);
    EXPECT_EQ(same.onlyDelaunay.size(), same.onlyGiven.size());
    EXPECT_GT(same.sharedEdges, 500);
    // One edge flipped where the four points are not cocircular: exactly that pair differs.
    Mesh m = base;
    std::int32_t flipped = kNone;
    for (std::int32_t c = 0; c < static_cast<std::int32_t>(m.V.size()) && flipped == kNone; ++c) {
        const std::int32_t d = m.O[c];
        if (d == kNone) continue;
        const Vec2 P = m.point(c), A = m.point(next(c)), B = m.point(prev(c)), D = m.point(d);
        if (orient2d(P, A, D) > 0 && orient2d(D, B, P) > 0 && incircle(P, A, B, D) != 0)
            flipped = c;
    }
    ASSERT_NE(flipped, kNone);
    const MeshEdge before = std::minmax(m.V[next(flipped)], m.V[prev(flipped)]);
    const MeshEdge after = std::minmax(m.V[flipped], m.V[m.O[flipped]]);
    flipEdge(m, flipped);
    const DelaunayDiff d = diffWithDelaunay(m);
    ASSERT_EQ(d.onlyGiven.size(), 1u);
    ASSERT_EQ(d.onlyDelaunay.size(), 1u);
    EXPECT_EQ(d.onlyGiven[0], after);
    EXPECT_EQ(d.onlyDelaunay[0], before);
    EXPECT_EQ(d.cocircular, 0);
    EXPECT_EQ(d.sharedEdges, same.sharedEdges - 1);
}

TEST(TriangulationCheck, TheDiffTellsCocircularChoicesAndDuplicatesApart) {
    // A square: either diagonal is Delaunay. Ours takes one; the other differs, cocircular.
    Mesh sq;
    sq.G = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    std::size_t differing = 0;
    for (const auto& diagonal : {std::array{0, 1, 2, 0, 2, 3}, std::array{0, 1, 3, 1, 2, 3}}) {
        sq.V.assign(diagonal.begin(), diagonal.end());
        const DelaunayDiff d = diffWithDelaunay(sq);
        EXPECT_EQ(d.onlyGiven.size(), d.onlyDelaunay.size());
        EXPECT_EQ(d.cocircular, static_cast<std::int64_t>(d.onlyDelaunay.size()));
        differing += d.onlyDelaunay.size();
    }
    EXPECT_EQ(differing, 1u);
    // A mesh that uses the second copy of a point: the same triangulation.
    Mesh dup;
    dup.G = {{0, 0}, {4, 0}, {0, 3}, {0, 0}};
    dup.V = {3, 1, 2};
    const DelaunayDiff d = diffWithDelaunay(dup);
    EXPECT_TRUE(d.same());
    EXPECT_EQ(d.sharedEdges, 3);
}

TEST(TriangulationCheck, RepairRefusesAnInvalidMeshNamingWhy) {
    Mesh m = delaunayMesh(30, 9);
    std::swap(m.V[0], m.V[1]);
    const CheckReport r = checkMesh(m);
    EXPECT_FALSE(r.isTriangulation());
    try {
        repairByFlips(m, r);
        FAIL() << "repaired";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("clockwise"), std::string::npos) << e.what();
    }
}

TEST(TriangulationCheck, DtlabCheckAndRepairEndToEnd) {
    const fs::path dir =
        fs::temp_directory_path() / ("dlab_tricheck_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string pts = (dir / "p.xy").string();
    {
        std::ofstream out(pts);
        std::mt19937 rng(3);
        for (int i = 0; i < 300; ++i) out << rng() % 1000 << " " << rng() % 1000 << "\n";
    }
    const std::string base = (dir / "t").string();
    ASSERT_EQ(
        testutil::runDtlab("triangulate " + pts + " -o " + base + " --off " + base + ".off").status,
        0);
    auto ok = testutil::runDtlab("check " + base + ".ele");
    EXPECT_EQ(ok.status, 0) << ok.out;
    EXPECT_NE(ok.out.find("valid Delaunay triangulation of 300 points"), std::string::npos)
        << ok.out;
    EXPECT_EQ(testutil::runDtlab("check " + base + ".off").status, 0);
    // A flipped edge: the check names it, the repair flips it back.
    ImportedMesh im = readMeshFile(base + ".ele");
    CheckReport r = check(im);
    Mesh m = im.mesh;
    m.O = r.opposites;
    flipEdge(m, convexEdge(m));
    const std::string bad = (dir / "bad").string();
    writeTextFiles({{bad + ".node", [&](std::ostream& os) { writeNode(os, m.G, 0); }},
                    {bad + ".ele", [&](std::ostream& os) { writeEle(os, m, 0); }}});
    auto nd = testutil::runDtlab("check " + bad + ".ele --json");
    EXPECT_EQ(nd.status, 1) << nd.out;
    EXPECT_NE(nd.out.find("\"not-delaunay\": "), std::string::npos) << nd.out;
    auto diff = testutil::runDtlab("check " + bad + ".ele --diff");
    EXPECT_EQ(diff.status, 1) << diff.out;
    EXPECT_NE(diff.out.find("1 edge only in this mesh, 1 only in the Delaunay triangulation"),
              std::string::npos)
        << diff.out;
    EXPECT_EQ(testutil::runDtlab("check " + base + ".ele --diff").status, 0);
    const std::string trace = (dir / "flips.jsonl").string();
    auto rep = testutil::runDtlab("repair " + bad + ".ele -o " + (dir / "fixed").string() +
                                  " --trace " + trace);
    EXPECT_EQ(rep.status, 0) << rep.out;
    std::ifstream traceIn(trace);
    std::size_t flipLines = 0;
    for (std::string line; std::getline(traceIn, line); ++flipLines) {
        EXPECT_NE(line.find("\"op\":\"Flip\""), std::string::npos) << line;
    }
    EXPECT_GE(flipLines, 1u);
    EXPECT_NE(rep.out.find(": " + std::to_string(flipLines) + " flips ("), std::string::npos)
        << rep.out;
    {  // the vertex numbering kept: the same .node, byte for byte
        std::ifstream a(bad + ".node"), b((dir / "fixed.node").string());
        std::stringstream sa, sb;
        sa << a.rdbuf();
        sb << b.rdbuf();
        EXPECT_EQ(sa.str(), sb.str());
    }
    EXPECT_NE(rep.out.find(" flips ("), std::string::npos) << rep.out;
    EXPECT_NE(rep.out.find("valid Delaunay triangulation"), std::string::npos) << rep.out;
    EXPECT_EQ(testutil::runDtlab("check " + (dir / "fixed.ele").string()).status, 0);
    // Invalid: a clockwise triangle blocks the repair; bad input exits 2.
    std::swap(m.V[0], m.V[1]);
    writeTextFiles({{bad + ".ele", [&](std::ostream& os) { writeEle(os, m, 0); }}});
    auto blocked = testutil::runDtlab("repair " + bad + ".ele -o " + (dir / "no").string());
    EXPECT_EQ(blocked.status, 1) << blocked.out;
    EXPECT_NE(blocked.out.find("clockwise-triangle"), std::string::npos) << blocked.out;
    EXPECT_FALSE(fs::exists(dir / "no.ele"));
    std::ofstream(dir / "junk.off") << "OFF\n1 1\n";
    auto junk = testutil::runDtlab("check " + (dir / "junk.off").string());
    EXPECT_EQ(junk.status, 2) << junk.out;
    fs::remove_all(dir);
}

TEST(TriangulationCheck, DtlabGenWritesTheFlipWorstCaseThatRepairMakesDelaunay) {
    const fs::path dir =
        fs::temp_directory_path() / ("dlab_flipworst_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string base = (dir / "w").string();
    auto gen = testutil::runDtlab("gen flip-worst-case 80 -o " + base + ".ele");
    ASSERT_EQ(gen.status, 0) << gen.out;
    EXPECT_NE(gen.out.find("80 points and"), std::string::npos) << gen.out;
    auto chk = testutil::runDtlab("check " + base + ".ele");
    EXPECT_EQ(chk.status, 1) << chk.out;  // valid, not Delaunay
    EXPECT_NE(chk.out.find("valid triangulation of 80 points"), std::string::npos) << chk.out;
    auto rep = testutil::runDtlab("repair " + base + ".ele -o " + (dir / "fixed").string());
    EXPECT_EQ(rep.status, 0) << rep.out;
    const std::size_t at = rep.out.find(" flips (");
    ASSERT_NE(at, std::string::npos) << rep.out;
    const std::size_t from = rep.out.rfind(' ', at - 1) + 1;
    EXPECT_GE(std::stoul(rep.out.substr(from, at - from)), 80u * 80u / 8u) << rep.out;
    EXPECT_EQ(testutil::runDtlab("check " + (dir / "fixed.ele").string()).status, 0);
    auto odd = testutil::runDtlab("gen flip-worst-case 81 -o " + (dir / "odd").string());
    EXPECT_EQ(odd.status, 2) << odd.out;
    EXPECT_NE(odd.out.find("even number"), std::string::npos) << odd.out;
    EXPECT_FALSE(fs::exists(dir / "odd.ele"));
    fs::remove_all(dir);
}
