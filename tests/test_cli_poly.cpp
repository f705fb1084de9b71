// Triangle's .poly: the reader's refusals, and dtlab triangulate IN.poly: the segments are edges
// of the result and come back in BASE.poly; crossing segments are refused with both named.
#include "core/engine/io_read.h"
#include "core/engine/mesh.h"
#include "core/engine/mesh_build.h"
#include "tests/exact_check.h"
#include "tests/run_dtlab.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

fs::path polyTempDir() {
    const fs::path dir =
        fs::temp_directory_path() / ("dlab_cli_poly_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir;
}

std::string put(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
}

std::set<std::pair<int, int>> eleEdges(const std::string& path) {
    std::ifstream ele(path);
    int nt = 0, three = 0, attrs = 0;
    ele >> nt >> three >> attrs;
    std::set<std::pair<int, int>> out;
    for (int t = 0; t < nt; ++t) {
        int id = 0, v[3];
        ele >> id >> v[0] >> v[1] >> v[2];
        for (int k = 0; k < 3; ++k)
            out.insert({std::min(v[k], v[(k + 1) % 3]), std::max(v[k], v[(k + 1) % 3])});
    }
    return out;
}

}  // namespace

TEST(Poly, ReaderRefusesWhatItCannotTakeNamingTheLine) {
    const auto ok =
        dlab::parsePoly("4 2 0 0\n1 0 0\n2 2 0\n3 2 2\n4 0 2\n1 0\n1 1 3\n0\n", "a.poly");
    EXPECT_EQ(ok.points.points.size(), 4u);
    EXPECT_EQ(ok.points.indexBase, 1);
    ASSERT_EQ(ok.segments.size(), 1u);
    EXPECT_EQ(ok.segments[0], std::make_pair(0, 2));
    const std::pair<std::string, std::string> bad[] = {
        {"0 2 0 0\n1 0\n1 1 2\n", "a.poly:1: vertices in a separate .node file"},
        {"3 2 0 0\n0 0 0\n1 1 0\n2 0 1\n", "a.poly: no segment section"},
        {"3 2 0 0\n0 0 0\n1 1 0\n2 0 1\n1 0\n0 0 3\n",
         "a.poly:6: segment vertex 3 is not a vertex"},
        {"3 2 0 0\n0 0 0\n1 1 0\n2 0 1\n2 0\n0 0 1\n",
         "a.poly:6: end of file: expected 2 segments"},
        {"3 2 0 0\n0 0 0\n1 1 0\n2 0 1\n1 0\n0 0 1\n1\n0 0.5 0.5\n",
         "a.poly:7: holes are not supported"},
    };
    for (const auto& [text, message] : bad) {
        try {
            dlab::parsePoly(text, "a.poly");
            ADD_FAILURE() << "accepted: " << text;
        } catch (const dlab::InputError& e) {
            EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
        }
    }
}

TEST(Poly, TriangulateGivesTheSegmentsAsEdgesAndWritesThemBack) {
    const fs::path dir = polyTempDir();
    // A square with a point near each side's middle, inside: the diagonal 0-2 is not Delaunay
    // here, and the segment 4-6 runs through the vertex 8 in the middle (split there).
    const std::string in = put(dir / "sq.poly",
                               "9 2 0 0\n0 0 0\n1 10 0\n2 10 10\n3 0 10\n4 1 5\n5 5 1\n"
                               "6 9 5\n7 5 9\n8 5 5\n2 0\n0 0 2\n1 4 6\n0\n");
    const std::string base = (dir / "sq_out").string();
    const auto r = dlab::testutil::runDtlab("triangulate " + in + " -o " + base + " --check");
    ASSERT_EQ(r.status, 0) << r.out;
    const auto edges = eleEdges(base + ".ele");
    EXPECT_TRUE(edges.count({0, 8}) && edges.count({2, 8}));  // 0-2 through 8 (5, 5)
    EXPECT_TRUE(edges.count({4, 8}) && edges.count({6, 8}));
    std::ifstream poly(base + ".poly");
    int nv = -1, dim = 0, a = 0, m = 0, ns = 0, sm = 0;
    poly >> nv >> dim >> a >> m >> ns >> sm;
    EXPECT_EQ(nv, 0);
    EXPECT_EQ(ns, 4);  // two segments, each in two pieces at vertex 8
}

TEST(Poly, CrossingSegmentsAreRefusedWithBothNamed) {
    const fs::path dir = polyTempDir();
    const std::string in =
        put(dir / "x.poly", "4 2 0 0\n1 0 0\n2 4 0\n3 4 4\n4 0 4\n2 0\n1 1 3\n2 2 4\n");
    const auto r = dlab::testutil::runDtlab("triangulate " + in + " -o " + (dir / "xo").string());
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_NE(r.out.find("segment 2 (2-4) crosses segment 1 (1-3)"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(dir / "xo.ele"));
}

TEST(Poly, RemovedPointsLeaveEverySegmentAndAPointOnOneIsRefused) {
    const fs::path dir = polyTempDir();
    // The square with the segment 0-2 through the middle point 8; 5 and 7 sit near two sides.
    const std::string in = put(dir / "rm.poly",
                               "9 2 0 0\n0 0 0\n1 10 0\n2 10 10\n3 0 10\n4 1 5\n5 5 1\n"
                               "6 9 5\n7 5 9\n8 5 5\n1 0\n0 0 2\n0\n");
    const std::string ids = put(dir / "rm.txt", "5\n7\n4\n");
    const std::string base = (dir / "rm_out").string();
    const auto r =
        dlab::testutil::runDtlab("triangulate " + in + " -o " + base + " --remove " + ids);
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("3 of the 3 listed point(s) removed"), std::string::npos) << r.out;
    const auto edges = eleEdges(base + ".ele");
    EXPECT_TRUE(edges.count({0, 8}) && edges.count({2, 8}));  // the segment's two pieces
    for (const int gone : {4, 5, 7})
        for (const auto& [a, b] : edges) EXPECT_TRUE(a != gone && b != gone) << gone;
    std::ifstream ele(base + ".ele");
    int triangles = 0;
    ele >> triangles;
    EXPECT_EQ(triangles, 6);  // 0, 1, 2, 3 on the hull, 6 and 8 inside: 2 * 6 - 4 - 2

    const std::string onSegment = put(dir / "on.txt", "8\n");
    const auto refused = dlab::testutil::runDtlab("triangulate " + in + " -o " +
                                                  (dir / "no").string() + " --remove " + onSegment);
    EXPECT_EQ(refused.status, 2) << refused.out;
    EXPECT_NE(refused.out.find("point 8 is on segment 0 (0-2)"), std::string::npos) << refused.out;
    EXPECT_FALSE(fs::exists(dir / "no.ele"));
}
