// dtlab triangulate --remove: the Delaunay triangulation of the points left, with the input's
// ids, checked exactly; bad id lists refused with one line naming the file and the line.
#include "core/engine/generators.h"
#include "core/engine/io_read.h"
#include "core/engine/io_write.h"
#include "core/engine/mesh.h"
#include "core/engine/mesh_build.h"
#include "tests/exact_check.h"
#include "tests/run_dtlab.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

fs::path removeTempDir() {
    const fs::path dir =
        fs::temp_directory_path() / ("dlab_cli_remove_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir;
}

std::string write(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
}

// BASE.node and BASE.ele back as a corner table, ids shifted by the base.
dlab::Mesh readBack(const std::string& base, int indexBase) {
    dlab::Mesh m;
    m.G = dlab::readPointsFile(base + ".node").points;
    std::ifstream ele(base + ".ele");
    int nt = 0, three = 0, attrs = 0;
    ele >> nt >> three >> attrs;
    for (int t = 0; t < nt; ++t) {
        int id = 0, a = 0, b = 0, c = 0;
        ele >> id >> a >> b >> c;
        m.V.insert(m.V.end(), {a - indexBase, b - indexBase, c - indexBase});
    }
    dlab::computeOpposites(m);
    return m;
}

dlab::testutil::DtlabResult run(const std::string& args) { return dlab::testutil::runDtlab(args); }

}  // namespace

TEST(CliRemove, PointsLeftAreTriangulatedWithTheInputsIds) {
    const fs::path dir = removeTempDir();
    const auto pts = dlab::generatePoints(dlab::Generator::Grid, 400, 3);
    std::ostringstream node;
    dlab::writeNode(node, pts, 1);
    const std::string in = write(dir / "grid.node", node.str());
    std::string ids;
    std::vector<std::int32_t> left;
    for (std::int32_t i = 0; i < static_cast<std::int32_t>(pts.size()); ++i) {
        if (i % 3 == 1) {
            ids += std::to_string(i + 1) + (i % 2 ? "  # a comment\n" : "\n");
        } else {
            left.push_back(i);
        }
    }
    const std::string list = write(dir / "gone.txt", "\n" + ids);
    for (const char* boundary : {"exact", "super"}) {
        const std::string base = (dir / (std::string("out_") + boundary)).string();
        const auto r = run("triangulate " + in + " -o " + base + " --remove " + list +
                           " --check --boundary " + boundary);
        ASSERT_EQ(r.status, 0) << r.out;
        EXPECT_NE(r.out.find("removed"), std::string::npos) << r.out;
        const dlab::Mesh m = readBack(base, 1);
        ASSERT_EQ(m.numVertices(), static_cast<std::int32_t>(pts.size()));
        if (std::string(boundary) == "exact") {
            std::vector<std::int32_t> distinct;
            for (const std::int32_t i : firstOccurrences(pts)) {
                if (i % 3 != 1) distinct.push_back(i);
            }
            EXPECT_EQ(checkDelaunayExact(m, &distinct), "");
        } else {
            dlab::ValidateOptions vo;
            vo.delaunay = false;  // the super-triangle's flaw near the hull stays
            const auto bad = dlab::validate(m, vo);
            EXPECT_TRUE(bad.empty()) << bad[0].message;
        }
    }
}

TEST(CliRemove, RemovingAllButACollinearSetLeavesNoTriangle) {
    const fs::path dir = removeTempDir();
    const std::string in = write(dir / "tri.csv", "0,0\n1,0\n2,0\n1,5\n");
    const std::string list = write(dir / "top.txt", "3\n");
    const std::string base = (dir / "flat").string();
    const auto r = run("triangulate " + in + " -o " + base + " --remove " + list);
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("collinear"), std::string::npos) << r.out;
    std::ifstream ele(base + ".ele");
    int nt = -1;
    ele >> nt;
    EXPECT_EQ(nt, 0);
}

TEST(CliRemove, AFirstOccurrenceRemovedHandsItsPlaceToTheNextEqualPoint) {
    const fs::path dir = removeTempDir();
    const std::string in = write(dir / "dup.csv", "0,0\n4,0\n0,4\n4,0\n4,4\n");
    const std::string list = write(dir / "first.txt", "1\n");
    const std::string base = (dir / "dup").string();
    const auto r = run("triangulate " + in + " -o " + base + " --remove " + list + " --check");
    ASSERT_EQ(r.status, 0) << r.out;
    const dlab::Mesh m = readBack(base, 0);
    const std::vector<std::int32_t> used = {0, 2, 3, 4};
    EXPECT_EQ(checkDelaunayExact(m, &used), "");
}

TEST(CliRemove, BadIdListsAreRefusedNamingTheLine) {
    const fs::path dir = removeTempDir();
    const std::string in = write(dir / "four.node", "4 2 0 0\n1 0 0\n2 1 0\n3 0 1\n4 1 1\n");
    const std::string base = (dir / "never").string();
    const std::pair<std::string, std::string> cases[] = {
        {"0\n", "bad.txt:1: point id 0 is not in the input (ids run 1 to 4)"},
        {"2\nx7\n", "bad.txt:2: \"x7\" is not a point id"},
        {"2\n3\n2\n", "bad.txt:3: point id 2 is listed twice (line 1 too)"},
        {"1.5\n", "bad.txt:1: \"1.5\" is not a point id"},
    };
    for (const auto& [text, message] : cases) {
        const std::string list = write(dir / "bad.txt", text);
        const auto r = run("triangulate " + in + " -o " + base + " --remove " + list);
        EXPECT_EQ(r.status, 2) << r.out;
        EXPECT_NE(r.out.find(message), std::string::npos) << r.out;
        EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
        EXPECT_FALSE(fs::exists(base + ".ele"));
    }
    const auto missing =
        run("triangulate " + in + " -o " + base + " --remove " + (dir / "nope.txt").string());
    EXPECT_EQ(missing.status, 2) << missing.out;
    EXPECT_NE(missing.out.find("nope.txt"), std::string::npos) << missing.out;
    const auto over = run("triangulate " + in + " -o " + (dir / "bad").string() + " --remove " +
                          (dir / "bad.txt").string() + " --off " + (dir / "bad.txt").string());
    EXPECT_NE(over.status, 0) << over.out;
}
