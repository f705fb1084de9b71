// Writers: .node/.ele/.neigh round trips (bit-exact coordinates, CCW triangles, neighbours that
// agree with computeOpposites), index bases, Voronoi files, OFF/OBJ counts, SVG element counts and
// no NaN, atomic file output.
#include "core/engine/generators.h"
#include "core/engine/inserter.h"
#include "core/engine/io_read.h"
#include "core/engine/io_write.h"
#include "core/engine/mesh_build.h"
#include "core/engine/voronoi.h"
#include "tests/exact_check.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>

using namespace dlab;

namespace {

Mesh triangulate(const std::vector<Vec2>& pts) {
    Inserter ins(pts, InsertOptions{});
    ins.run();
    return ins.mesh();
}

std::string toString(const std::function<void(std::ostream&)>& write) {
    std::ostringstream os;
    write(os);
    EXPECT_TRUE(os.good());
    return os.str();
}

std::vector<std::vector<std::string>> tokens(const std::string& text) {
    std::vector<std::vector<std::string>> lines;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream ls(line);
        std::vector<std::string> f;
        for (std::string w; ls >> w;) f.push_back(w);
        lines.push_back(f);
    }
    return lines;
}

std::size_t count(const std::string& s, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
    return n;
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

std::int32_t numEdges(const Mesh& m) {
    std::int32_t hull = 0;
    for (std::int32_t o : m.O) hull += o == kNone;
    return (m.numCorners() + hull) / 2;
}

// Points whose text forms are the hard cases for a writer, plus a random cloud to triangulate.
std::vector<Vec2> awkwardPoints() {
    return {{0.1, 0.2},
            {1e-300, -1e-300},
            {-DBL_MAX, DBL_MAX},
            {4.9406564584124654e-324, 2.2250738585072009e-308},  // subnormals
            {DBL_MIN, -DBL_MIN},
            {-0.0, 0.0},
            {1.0 / 3.0, 2.0 / 3.0},
            {123456789.123456789, -9.87654321e-5},
            {0x1.fffffffffffffp-1, 0x1p-1074}};
}

// A fresh directory per process: ctest runs tests in parallel, possibly from several build trees.
std::filesystem::path scratchDir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("dlab_test_io_write_" + name + "_" + std::to_string(std::random_device{}()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

TEST(WriteNode, RoundTripsBitExact) {
    for (const int base : {0, 1}) {
        const std::vector<Vec2> pts = awkwardPoints();
        const std::string text = toString([&](std::ostream& os) { writeNode(os, pts, base); });
        const auto lines = tokens(text);
        ASSERT_EQ(lines.size(), pts.size() + 1);
        EXPECT_EQ(lines[0], (std::vector<std::string>{std::to_string(pts.size()), "2", "0", "0"}));
        EXPECT_EQ(lines[1][0], std::to_string(base));
        EXPECT_EQ(lines[1][1], "0.1");  // the shortest form, not 0.10000000000000001
        const PointSet back = parseNode(text, "written.node");
        EXPECT_EQ(back.indexBase, base);
        ASSERT_EQ(back.points.size(), pts.size());
        for (std::size_t i = 0; i < pts.size(); ++i) {
            EXPECT_TRUE(sameBits(back.points[i].x, pts[i].x))
                << "point " << i << " x " << lines[i + 1][1];
            EXPECT_TRUE(sameBits(back.points[i].y, pts[i].y))
                << "point " << i << " y " << lines[i + 1][2];
        }
    }
    // Random bit patterns of finite doubles, too.
    std::mt19937_64 rng(99);
    std::vector<Vec2> random;
    while (random.size() < 2000) {
        double x, y;
        const std::uint64_t bx = rng(), by = rng();
        std::memcpy(&x, &bx, sizeof x);
        std::memcpy(&y, &by, sizeof y);
        if (std::isfinite(x) && std::isfinite(y)) random.push_back({x, y});
    }
    const PointSet back =
        parseNode(toString([&](std::ostream& os) { writeNode(os, random, 0); }), "random.node");
    ASSERT_EQ(back.points.size(), random.size());
    for (std::size_t i = 0; i < random.size(); ++i) {
        ASSERT_TRUE(sameBits(back.points[i].x, random[i].x) &&
                    sameBits(back.points[i].y, random[i].y))
            << i;
    }
}

TEST(WriteEleNeigh, RoundTripAgreesWithTheMesh) {
    std::vector<Vec2> pts = generatePoints(Generator::Uniform, 500, 3);
    pts.push_back({0.1, 0.3});
    pts.push_back({1e-300, 1e-300});
    pts.push_back(pts[10]);  // a duplicate: stays in G, used by no triangle
    const Mesh m = triangulate(pts);
    ASSERT_GT(m.numTriangles(), 0);
    for (const int base : {0, 1}) {
        SCOPED_TRACE("index base " + std::to_string(base));
        const std::string node = toString([&](std::ostream& os) { writeNode(os, m.G, base); });
        const std::string ele = toString([&](std::ostream& os) { writeEle(os, m, base); });
        const std::string neigh = toString([&](std::ostream& os) { writeNeigh(os, m, base); });

        // Rebuild the mesh from the files alone.
        Mesh r;
        r.G = parseNode(node, "m.node").points;
        ASSERT_EQ(r.G.size(), m.G.size());
        const auto e = tokens(ele);
        ASSERT_EQ(e.size(), static_cast<std::size_t>(m.numTriangles()) + 1);
        EXPECT_EQ(e[0], (std::vector<std::string>{std::to_string(m.numTriangles()), "3", "0"}));
        for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
            const auto& f = e[t + 1];
            ASSERT_EQ(f.size(), 4u);
            EXPECT_EQ(std::stoi(f[0]), t + base);
            for (int i = 0; i < 3; ++i) {
                const int v = std::stoi(f[1 + i]) - base;
                ASSERT_GE(v, 0);
                ASSERT_LT(v, r.numVertices());
                EXPECT_EQ(v, m.V[corner(t, i)]);  // the input ids
                r.V.push_back(v);
            }
            EXPECT_EQ(
                orientGmp(r.point(corner(t, 0)), r.point(corner(t, 1)), r.point(corner(t, 2))), 1)
                << "triangle " << t << " is not counter-clockwise";
        }
        computeOpposites(r);
        EXPECT_EQ(checkDelaunayExact(r), "");

        const auto n = tokens(neigh);
        ASSERT_EQ(n.size(), static_cast<std::size_t>(m.numTriangles()) + 1);
        EXPECT_EQ(n[0], (std::vector<std::string>{std::to_string(m.numTriangles()), "3"}));
        int hull = 0;
        for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
            const auto& f = n[t + 1];
            ASSERT_EQ(f.size(), 4u);
            EXPECT_EQ(std::stoi(f[0]), t + base);
            for (int i = 0; i < 3; ++i) {
                const int nb = std::stoi(f[1 + i]);
                const std::int32_t o = r.O[corner(t, i)];
                if (o == kNone) {
                    EXPECT_EQ(nb, -1);  // -1 whatever the base
                    ++hull;
                } else {
                    EXPECT_EQ(nb, tri(o) + base);
                }
            }
        }
        EXPECT_EQ(hull, numEdges(m) * 2 - m.numCorners());
    }
}

TEST(WriteEleNeigh, EmptyMeshAndBadBase) {
    Mesh empty;
    empty.G = {{0, 0}, {1, 1}};
    EXPECT_EQ(toString([&](std::ostream& os) { writeEle(os, empty, 0); }), "0 3 0\n");
    EXPECT_EQ(toString([&](std::ostream& os) { writeNeigh(os, empty, 1); }), "0 3\n");
    EXPECT_EQ(toString([&](std::ostream& os) { writeNode(os, {}, 0); }), "0 2 0 0\n");
    std::ostringstream os;
    EXPECT_THROW(writeNode(os, empty.G, 2), std::invalid_argument);
    EXPECT_THROW(writeEle(os, empty, -1), std::invalid_argument);
    Mesh noO = triangulate({{0, 0}, {1, 0}, {0, 1}});
    noO.O.clear();
    EXPECT_THROW(writeNeigh(os, noO, 0), std::invalid_argument);
    // A tiny exact example: one triangle, all neighbours -1 in both bases.
    const Mesh one = triangulate({{0, 0}, {1, 0}, {0, 1}});
    ASSERT_EQ(one.numTriangles(), 1);
    EXPECT_EQ(toString([&](std::ostream& s) { writeNeigh(s, one, 1); }), "1 3\n1 -1 -1 -1\n");
    EXPECT_EQ(toString([&](std::ostream& s) { writeNode(s, one.G, 1); }),
              "3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n");
}

TEST(WriteVoronoi, NodeAndEdgeFiles) {
    const Mesh m = triangulate(generatePoints(Generator::Uniform, 200, 5));
    const VoronoiDiagram d = buildVoronoi(m);
    for (const int base : {0, 1}) {
        const auto vn = tokens(toString([&](std::ostream& os) { writeVoronoiNode(os, d, base); }));
        ASSERT_EQ(vn.size(), d.vertices.size() + 1);
        EXPECT_EQ(vn[0],
                  (std::vector<std::string>{std::to_string(d.vertices.size()), "2", "0", "0"}));
        for (std::size_t i = 0; i < d.vertices.size(); ++i) {
            ASSERT_EQ(vn[i + 1].size(), 3u);
            EXPECT_EQ(std::stoll(vn[i + 1][0]), static_cast<long long>(i) + base);
            EXPECT_TRUE(sameBits(std::stod(vn[i + 1][1]), d.vertices[i].x));
            EXPECT_TRUE(sameBits(std::stod(vn[i + 1][2]), d.vertices[i].y));
        }
        const auto ve = tokens(toString([&](std::ostream& os) { writeVoronoiEdge(os, d, base); }));
        ASSERT_EQ(ve.size(), d.edges.size() + 1);
        EXPECT_EQ(ve[0], (std::vector<std::string>{std::to_string(d.edges.size()), "0"}));
        std::size_t rays = 0;
        for (std::size_t i = 0; i < d.edges.size(); ++i) {
            const auto& f = ve[i + 1];
            const VoronoiDiagram::Edge& e = d.edges[i];
            EXPECT_EQ(std::stoll(f[0]), static_cast<long long>(i) + base);
            EXPECT_EQ(std::stoi(f[1]), e.a + base);
            if (e.isRay()) {
                ++rays;
                ASSERT_EQ(f.size(), 5u);
                EXPECT_EQ(f[2], "-1");
                EXPECT_TRUE(sameBits(std::stod(f[3]), e.direction.x));
                EXPECT_TRUE(sameBits(std::stod(f[4]), e.direction.y));
            } else {
                ASSERT_EQ(f.size(), 3u);
                EXPECT_EQ(std::stoi(f[2]), e.b + base);
            }
        }
        EXPECT_GT(rays, 2u);
    }
}

TEST(WriteOffObj, Counts) {
    std::vector<Vec2> pts = generatePoints(Generator::Uniform, 100, 9);
    pts.push_back(pts[0]);  // duplicate: a vertex no face uses
    const Mesh m = triangulate(pts);
    const auto off = tokens(toString([&](std::ostream& os) { writeOff(os, m); }));
    ASSERT_GE(off.size(), 2u);
    EXPECT_EQ(off[0], std::vector<std::string>{"OFF"});
    EXPECT_EQ(off[1], (std::vector<std::string>{std::to_string(m.numVertices()),
                                                std::to_string(m.numTriangles()), "0"}));
    ASSERT_EQ(off.size(), 2u + m.G.size() + m.numTriangles());
    for (std::size_t i = 0; i < m.G.size(); ++i) {
        ASSERT_EQ(off[2 + i].size(), 3u);
        EXPECT_TRUE(sameBits(std::stod(off[2 + i][0]), m.G[i].x));
        EXPECT_EQ(off[2 + i][2], "0");
    }
    for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
        const auto& f = off[2 + m.G.size() + t];
        ASSERT_EQ(f.size(), 4u);
        EXPECT_EQ(f[0], "3");
        for (int i = 0; i < 3; ++i) EXPECT_EQ(std::stoi(f[1 + i]), m.V[corner(t, i)]);
    }

    const std::string obj = toString([&](std::ostream& os) { writeObj(os, m); });
    std::size_t vs = 0, fs = 0;
    for (const auto& f : tokens(obj)) {
        if (f.empty() || f[0] == "#") continue;
        if (f[0] == "v") {
            ASSERT_EQ(f.size(), 4u);
            EXPECT_EQ(f[3], "0");
            ++vs;
        } else if (f[0] == "f") {
            ASSERT_EQ(f.size(), 4u);
            for (int i = 0; i < 3; ++i) {
                const int v = std::stoi(f[1 + i]);
                EXPECT_EQ(v, m.V[corner(static_cast<std::int32_t>(fs), i)] + 1);  // 1-based
                EXPECT_GE(v, 1);
                EXPECT_LE(v, m.numVertices());
            }
            ++fs;
        } else {
            ADD_FAILURE() << "unexpected OBJ line starting with " << f[0];
        }
    }
    EXPECT_EQ(vs, m.G.size());
    EXPECT_EQ(fs, static_cast<std::size_t>(m.numTriangles()));
}

TEST(WriteSvg, ElementCounts) {
    const Mesh m = triangulate(generatePoints(Generator::Uniform, 150, 4));
    const std::int32_t edges = numEdges(m);
    {
        const std::string svg = toString([&](std::ostream& os) { writeSvg(os, m, SvgOptions{}); });
        EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
        EXPECT_EQ(count(svg, "<svg "), 1u);
        EXPECT_EQ(count(svg, "</svg>"), 1u);
        EXPECT_EQ(count(svg, "<line"), static_cast<std::size_t>(edges));
        EXPECT_EQ(count(svg, "<circle"), m.G.size());
        EXPECT_EQ(count(svg, "<polygon"), 0u);
        EXPECT_EQ(svg.find("nan"), std::string::npos);
        EXPECT_EQ(svg.find("inf"), std::string::npos);
    }
    {
        SvgOptions o;
        o.mesh = false;
        o.points = false;
        o.voronoi = true;
        o.circumcircles = true;
        o.highlight = {0, 5, 7, -1, m.numTriangles()};  // out-of-range ids are ignored
        const std::string svg = toString([&](std::ostream& os) { writeSvg(os, m, o); });
        EXPECT_EQ(count(svg, "<polygon"), 3u);
        EXPECT_EQ(count(svg, "<circle"), static_cast<std::size_t>(m.numTriangles()));
        // Voronoi edges clipped to the picture: most of them show, none twice.
        const std::size_t lines = count(svg, "<line");
        EXPECT_GT(lines, static_cast<std::size_t>(edges) / 2);
        EXPECT_LE(lines, static_cast<std::size_t>(edges));
        EXPECT_EQ(svg.find("nan"), std::string::npos);
    }
}

TEST(WriteSvg, YAxisPointsUpAndEverythingFits) {
    const Mesh m = triangulate({{0, 0}, {10, 0}, {0, 10}, {10, 20}});
    SvgOptions o;
    o.width = 400;
    const std::string svg = toString([&](std::ostream& os) { writeSvg(os, m, o); });
    // The point circles come last, in G order.
    std::vector<Vec2> c;
    for (std::size_t p = svg.find("<g class=\"points\"");
         (p = svg.find("<circle cx=\"", p)) != std::string::npos; ++p) {
        const double cx = std::stod(svg.substr(p + 12));
        const double cy = std::stod(svg.substr(svg.find("cy=\"", p) + 4));
        c.push_back({cx, cy});
    }
    ASSERT_EQ(c.size(), 4u);
    const double height = std::stod(svg.substr(svg.find("height=\"") + 8));
    EXPECT_LT(c[2].y, c[0].y);  // (0,10) is drawn above (0,0)
    EXPECT_LT(c[3].y, c[2].y);  // (10,20) above both
    EXPECT_EQ(c[0].y, c[1].y);
    EXPECT_GT(c[1].x, c[0].x);  // x is not mirrored
    EXPECT_EQ(c[0].x, c[2].x);
    // Equal world lengths, equal pixel lengths (no stretching), all inside the picture.
    EXPECT_NEAR(c[1].x - c[0].x, c[0].y - c[2].y, 0.011);
    for (Vec2 q : c) {
        EXPECT_GT(q.x, 0.0);
        EXPECT_LT(q.x, 400.0);
        EXPECT_GT(q.y, 0.0);
        EXPECT_LT(q.y, height);
    }
}

TEST(WriteSvg, DegenerateInputsGiveValidPictures) {
    // lines: at least minLines (the mesh edges), at most maxLines (plus every Voronoi edge).
    auto check = [](const Mesh& m, const SvgOptions& o, std::size_t circles, std::size_t minLines,
                    std::size_t maxLines) {
        const std::string svg = toString([&](std::ostream& os) { writeSvg(os, m, o); });
        EXPECT_EQ(count(svg, "<circle"), circles);
        EXPECT_GE(count(svg, "<line"), minLines);
        EXPECT_LE(count(svg, "<line"), maxLines);
        EXPECT_EQ(svg.find("nan"), std::string::npos) << svg;
        EXPECT_EQ(svg.find("inf"), std::string::npos) << svg;
        EXPECT_EQ(count(svg, "</svg>"), 1u);
    };
    SvgOptions all;
    all.voronoi = true;
    all.circumcircles = true;
    check(Mesh{}, all, 0, 0, 0);  // nothing at all
    Mesh one;
    one.G = {{3, 4}};
    check(one, all, 1, 0, 0);
    Mesh same;
    same.G = {{1e300, -1e300}, {1e300, -1e300}};
    check(same, all, 2, 0, 0);
    // Collinear points: no triangle, only points.
    const Mesh line = triangulate({{0, 0}, {1, 1}, {2, 2}, {3, 3}});
    ASSERT_EQ(line.numTriangles(), 0);
    check(line, all, 4, 0, 0);
    // A vertical column of points: zero width.
    Mesh column;
    column.G = {{5, 0}, {5, 1}, {5, 2}};
    check(column, all, 3, 0, 0);
    // Odd widths fall back to something drawable.
    SvgOptions odd;
    odd.width = std::numeric_limits<double>::quiet_NaN();
    check(column, odd, 3, 0, 0);
    odd.width = -5;
    check(column, odd, 3, 0, 0);
    // Tiny, huge and subnormal extents.
    for (const double s : {1e-300, 1e300, 0x1p-1070}) {
        const Mesh m = triangulate({{0, 0}, {s, 0}, {0, s}, {s, s * 0.5}});
        ASSERT_GT(m.numTriangles(), 0);
        const auto e = static_cast<std::size_t>(numEdges(m));
        check(m, all, 4 + m.numTriangles(), e, 2 * e);
    }
}

TEST(WriteSvg, ExtremeCoordinatesNoNaN) {
    for (const auto& pts :
         {std::vector<Vec2>{{-DBL_MAX, -DBL_MAX}, {DBL_MAX, -DBL_MAX}, {0, DBL_MAX}},
          std::vector<Vec2>{{0, 0}, {1e-300, 0}, {0, 1e-300}, {1e-300, 1e-300}},
          std::vector<Vec2>{{1e15, 1e15}, {1e15 + 1, 1e15}, {1e15, 1e15 + 1}}}) {
        const Mesh m = triangulate(pts);
        ASSERT_GT(m.numTriangles(), 0);
        SvgOptions o;
        o.voronoi = true;
        o.circumcircles = true;
        o.highlight = {0};
        const std::string svg = toString([&](std::ostream& os) { writeSvg(os, m, o); });
        EXPECT_EQ(svg.find("nan"), std::string::npos) << svg;
        EXPECT_EQ(svg.find("inf"), std::string::npos) << svg;
        EXPECT_EQ(count(svg, "<polygon"), 1u);
        EXPECT_EQ(count(svg, "<circle"), m.G.size() + m.numTriangles());
        EXPECT_GE(count(svg, "<line"), static_cast<std::size_t>(numEdges(m)));
    }
}

TEST(WriteSvg, TitleIsEscaped) {
    Mesh one;
    one.G = {{0, 0}};
    SvgOptions o;
    o.title = "a<b & \"c\" 'd' <line> \x01 \xff ok \xc3\xa9";
    const std::string svg = toString([&](std::ostream& os) { writeSvg(os, one, o); });
    EXPECT_NE(
        svg.find(
            "<title>a&lt;b &amp; &quot;c&quot; &apos;d&apos; &lt;line&gt; ? ? ok \xc3\xa9</title>"),
        std::string::npos)
        << svg;
    EXPECT_EQ(count(svg, "<line"), 0u);
    EXPECT_EQ(svg.find('\x01'), std::string::npos);
    EXPECT_EQ(svg.find('\xff'), std::string::npos);
}

TEST(WriteTextFile, AtomicWriteAndErrors) {
    const auto dir = scratchDir("atomic");
    const std::string path = (dir / "out.txt").string();
    writeTextFile(path, [](std::ostream& os) { os << "first\n"; });
    EXPECT_EQ(slurp(path), "first\n");
    writeTextFile(path, [](std::ostream& os) { os << "second\n"; });  // replaces
    EXPECT_EQ(slurp(path), "second\n");
    EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));

    // The body throws: the old file stays, no temporary is left behind.
    EXPECT_THROW(writeTextFile(path,
                               [](std::ostream& os) {
                                   os << "partial";
                                   throw std::logic_error("stop");
                               }),
                 std::logic_error);
    EXPECT_EQ(slurp(path), "second\n");
    EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));

    // A missing directory: "cannot write PATH: <strerror>".
    const std::string missing = (dir / "no" / "such" / "dir.txt").string();
    try {
        writeTextFile(missing, [](std::ostream& os) { os << "x"; });
        ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()), "cannot write " + missing + ": " + std::strerror(ENOENT));
    }
    // The target is a directory: the rename fails, the temporary is removed.
    const std::string asDir = (dir / "adir").string();
    std::filesystem::create_directories(asDir + "/inner");
    try {
        writeTextFile(asDir, [](std::ostream& os) { os << "x"; });
        ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()).rfind("cannot write " + asDir + ": ", 0), 0u) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(asDir + ".tmp"));

    // Every writer through a real file, and the node file reads back.
    const Mesh m = triangulate(generatePoints(Generator::Uniform, 50, 1));
    const std::string node = (dir / "m.node").string();
    writeTextFile(node, [&](std::ostream& os) { writeNode(os, m.G, 1); });
    const PointSet back = readPointsFile(node);
    EXPECT_EQ(back.indexBase, 1);
    EXPECT_EQ(back.points, m.G);
    std::filesystem::remove_all(dir);
}

namespace {

std::string whatOf(const std::function<void()>& write) {
    try {
        write();
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "no exception";
}

}  // namespace

TEST(WriteTextFile, ADeviceThatTakesNothingGivesTheSystemsReason) {
    const std::string expect = std::string("cannot write /dev/full: ") + std::strerror(ENOSPC);
    // A body smaller than the stream's buffer (the error shows at the flush) and one larger.
    for (const std::size_t bytes : {std::size_t{10}, std::size_t{1} << 20}) {
        EXPECT_EQ(whatOf([&] {
                      writeTextFile("/dev/full",
                                    [&](std::ostream& os) { os << std::string(bytes, 'x'); });
                  }),
                  expect)
            << bytes;
    }
}

TEST(WriteTextFiles, AFolderOutputReplacesTheOldFolderWholeOrNotAtAll) {
    const auto dir = scratchDir("folder");
    const std::string folder = (dir / "pictures").string(), page = (dir / "page.html").string();
    std::filesystem::create_directories(folder);
    std::ofstream(folder + "/01.png") << "old 1";
    std::ofstream(folder + "/02.png") << "old 2";
    std::ofstream(page) << "old page";
    auto fill = [](int n, bool fail) {
        return [n, fail](const std::string& d) {
            for (int k = 1; k <= n; ++k)
                std::ofstream(d + "/0" + std::to_string(k) + ".png") << "new " << k;
            if (fail) throw std::runtime_error("cannot write 03.png: the picture failed");
        };
    };
    auto set = [&](bool fail) {
        writeTextFiles({{page, [](std::ostream& os) { os << "new page"; }},
                        {folder, {}, fill(fail ? 2 : 1, fail)}});
    };
    // A fill that fails: the old page and the old folder, nothing else.
    EXPECT_EQ(whatOf([&] { set(true); }), "cannot write 03.png: the picture failed");
    EXPECT_EQ(slurp(page), "old page");
    EXPECT_EQ(slurp(folder + "/01.png"), "old 1");
    EXPECT_EQ(slurp(folder + "/02.png"), "old 2");
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++entries;
    EXPECT_EQ(entries, 2u);  // no temporary left
    // Success: the folder is the new one (its old 02.png gone with it).
    set(false);
    EXPECT_EQ(slurp(page), "new page");
    EXPECT_EQ(slurp(folder + "/01.png"), "new 1");
    EXPECT_FALSE(std::filesystem::exists(folder + "/02.png"));
    entries = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++entries;
    EXPECT_EQ(entries, 2u);
    // A file where the folder goes is refused before anything is written.
    std::filesystem::remove_all(folder);
    std::ofstream(folder) << "a file";
    EXPECT_EQ(whatOf([&] { set(false); }), "cannot write " + folder + ": it is not a folder");
    EXPECT_EQ(slurp(page), "new page");
    std::filesystem::remove_all(dir);
}
