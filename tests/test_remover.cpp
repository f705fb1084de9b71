// Vertex removal: every vertex removed in random order, the mesh checked exactly after each one
// against a fresh triangulation of the points left; undo restores V and O bit for bit.
#include "core/engine/generators.h"
#include "core/engine/inserter.h"
#include "core/engine/predicates.h"
#include "core/engine/remover.h"
#include "tests/distinct_points.h"
#include "tests/exact_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <string>
#include <utility>

using namespace dlab;
using dlab::testutil::distinct;

namespace {

using EdgeSet = std::set<std::pair<std::int32_t, std::int32_t>>;

EdgeSet edgesOf(const Mesh& m, const std::vector<std::int32_t>* names = nullptr) {
    EdgeSet out;
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        std::int32_t a = m.V[next(c)], b = m.V[prev(c)];
        if (names) {
            a = (*names)[a];
            b = (*names)[b];
        }
        out.insert({std::min(a, b), std::max(a, b)});
    }
    return out;
}

// The inserter's mesh before Finalize: the ghost triangles or the super-triangle still in.
Mesh closedMesh(const std::vector<Vec2>& pts, Boundary boundary, std::uint64_t seed) {
    InsertOptions opt;
    opt.boundary = boundary;
    opt.seed = seed;
    Inserter ins(pts, opt);
    while (ins.control().phase != Phase::Finalize && !ins.done()) ins.step();
    return ins.mesh();
}

// The exact mode's fresh triangulation of `left` (ids into pts), with the ids of pts.
EdgeSet freshEdges(const std::vector<Vec2>& pts, const std::vector<std::int32_t>& left) {
    std::vector<Vec2> sub;
    for (const std::int32_t i : left) sub.push_back(pts[i]);
    Inserter ins(sub);
    ins.run();
    return edgesOf(ins.mesh(), &left);
}

struct RemovalRun {
    std::vector<Vec2> pts;
    Boundary boundary = Boundary::Exact;
    bool generalPosition = false;  // the Delaunay triangulation is unique: compare edge sets
    bool checkUndo = true;
    std::uint64_t seed = 1;
};

// Removes the vertices in random order down to 3, checking after every removal.
void removeAll(const RemovalRun& run, const std::string& label) {
    SCOPED_TRACE(label);
    const auto& pts = run.pts;
    const std::int32_t n = static_cast<std::int32_t>(pts.size());
    Mesh mesh = closedMesh(pts, run.boundary, run.seed);
    const bool exact = run.boundary == Boundary::Exact;
    Remover remover(mesh, n, run.boundary);
    std::vector<std::int32_t> order(static_cast<std::size_t>(n));
    for (std::int32_t i = 0; i < n; ++i) order[i] = i;
    std::mt19937_64 rng(run.seed * 7919 + 3);
    std::shuffle(order.begin(), order.end(), rng);
    std::vector<bool> gone(static_cast<std::size_t>(n), false);
    for (std::size_t step = 0; step + 3 < order.size(); ++step) {
        const std::int32_t v = order[step];
        const Mesh before = mesh;
        RemovalRecord record;
        const RemoveResult r = remover.remove(v, &record);
        gone[v] = true;
        std::vector<std::int32_t> left;
        std::vector<Vec2> leftPts;
        for (std::int32_t i = 0; i < n; ++i) {
            if (!gone[i]) {
                left.push_back(i);
                leftPts.push_back(pts[i]);
            }
        }
        const std::string at = "removal " + std::to_string(step) + " of vertex " +
                               std::to_string(v) + ": " + toString(r);
        if (mesh.numTriangles() == 0 && before.numTriangles() == 0) {
            ASSERT_EQ(r, RemoveResult::NotInMesh) << at;
            continue;
        }
        ASSERT_TRUE(r == RemoveResult::Removed || r == RemoveResult::Collapsed) << at;
        ValidateOptions vo;
        vo.firstVirtual = exact ? n : -1;  // the super-triangle's vertices are real points
        const auto bad = validate(mesh, vo);
        ASSERT_TRUE(bad.empty()) << at << ": " << bad[0].message;
        if (exact) {
            Mesh finished = mesh;
            dropVirtual(finished, n);
            if (allCollinearExact(leftPts)) {
                ASSERT_EQ(finished.numTriangles(), 0) << at;
                ASSERT_EQ(r, RemoveResult::Collapsed) << at;
            } else {
                ASSERT_EQ(r, RemoveResult::Removed) << at;
                const std::string err = checkDelaunayExact(finished, &left);
                ASSERT_EQ(err, "") << at;
                if (run.generalPosition) {
                    ASSERT_EQ(edgesOf(finished), freshEdges(pts, left)) << at;
                }
            }
        } else {
            ASSERT_EQ(r, RemoveResult::Removed) << at;
            ASSERT_EQ(remover.liveVertices(), static_cast<std::int32_t>(left.size())) << at;
        }
        if (run.checkUndo) {
            const Mesh after = mesh;
            remover.undo(record);
            ASSERT_TRUE(mesh.V == before.V && mesh.O == before.O) << at << ": undo";
            RemovalRecord again;
            ASSERT_EQ(remover.remove(v, &again), r) << at;
            ASSERT_TRUE(mesh.V == after.V && mesh.O == after.O) << at << ": redo differs";
            ASSERT_EQ(again.ops.size(), record.ops.size()) << at;
        }
    }
}

std::vector<Vec2> latticeWithHoles(int side) {
    std::vector<Vec2> pts;
    for (int y = 0; y < side; ++y) {
        for (int x = 0; x < side; ++x) pts.push_back({double(x), double(y)});
    }
    return pts;
}

}  // namespace

TEST(Remover, EveryVertexOfUniformSetsInRandomOrderMatchesAFreshTriangulation) {
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
        RemovalRun run;
        run.pts = distinct(generatePoints(Generator::Uniform, 40 + 30 * seed, seed));
        run.generalPosition = true;
        run.seed = seed;
        removeAll(run, "uniform seed " + std::to_string(seed));
    }
}

TEST(Remover, SmallRandomSetsDownToThreePoints) {
    for (std::uint64_t seed = 1; seed <= 12; ++seed) {
        RemovalRun run;
        run.pts = distinct(generatePoints(Generator::Uniform, 4 + seed % 6, seed + 100));
        run.generalPosition = true;
        run.seed = seed;
        removeAll(run, "small seed " + std::to_string(seed));
    }
}

TEST(Remover, LatticesWithCocircularPointsStayDelaunay) {
    for (int side = 2; side <= 9; ++side) {
        RemovalRun run;
        run.pts = latticeWithHoles(side);
        run.seed = static_cast<std::uint64_t>(side);
        removeAll(run, "lattice " + std::to_string(side));
    }
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
        RemovalRun run;
        run.pts = distinct(generatePoints(Generator::Grid, 150, seed));
        run.seed = seed;
        removeAll(run, "grid generator seed " + std::to_string(seed));
    }
}

TEST(Remover, CollinearCocircularAndClusteredSets) {
    const std::pair<Generator, std::size_t> kinds[] = {
        {Generator::Collinear, 120},   {Generator::Ngon, 40},
        {Generator::Clusters, 150},    {Generator::Circle, 60},
        {Generator::AllCollinear, 12}, {Generator::NearDuplicates, 80},
        {Generator::HugeTinyBox, 80},  {Generator::Curves, 100}};
    for (const auto& [kind, count] : kinds) {
        for (std::uint64_t seed = 1; seed <= 2; ++seed) {
            RemovalRun run;
            run.pts = distinct(generatePoints(kind, count, seed));
            run.seed = seed;
            removeAll(run, std::string(toString(kind)) + " seed " + std::to_string(seed));
        }
    }
}

TEST(Remover, SuperTriangleModeKeepsTheClosedMeshDelaunay) {
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        RemovalRun run;
        run.pts =
            distinct(generatePoints(seed % 2 ? Generator::Uniform : Generator::Grid, 80, seed));
        run.boundary = Boundary::Super;
        run.seed = seed;
        removeAll(run, "super seed " + std::to_string(seed));
    }
}

TEST(Remover, SquareCentreOfDegreeFourLeavesTheSquare) {
    // Every ear of the square has the centre on its diagonal: the cut leaves a flat triangle.
    const std::vector<Vec2> pts = {{0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 1}};
    Mesh mesh = closedMesh(pts, Boundary::Exact, 1);
    Remover remover(mesh, 5, Boundary::Exact);
    RemovalRecord record;
    ASSERT_EQ(remover.remove(4, &record), RemoveResult::Removed);
    Mesh finished = mesh;
    dropVirtual(finished, 5);
    const std::vector<std::int32_t> left = {0, 1, 2, 3};
    EXPECT_EQ(checkDelaunayExact(finished, &left), "");
    EXPECT_EQ(finished.numTriangles(), 2);
    int flips = 0, merges = 0;
    for (const RemoveOp& op : record.ops) {
        flips += op.type == RemoveOpType::Flip;
        merges += op.type == RemoveOpType::Merge;
    }
    EXPECT_EQ(flips, 1);
    EXPECT_EQ(merges, 1);
}

TEST(Remover, RefusesVirtualAndAbsentVertices) {
    const std::vector<Vec2> pts = {{0, 0}, {4, 0}, {0, 4}, {1, 1}};
    Mesh mesh = closedMesh(pts, Boundary::Exact, 1);
    Remover remover(mesh, 4, Boundary::Exact);
    const Mesh before = mesh;
    EXPECT_EQ(remover.remove(4), RemoveResult::Virtual);
    EXPECT_EQ(remover.remove(-1), RemoveResult::NotInMesh);
    EXPECT_EQ(remover.remove(99), RemoveResult::NotInMesh);
    EXPECT_TRUE(mesh.V == before.V && mesh.O == before.O);
    EXPECT_EQ(remover.remove(3), RemoveResult::Removed);
    EXPECT_EQ(remover.remove(3), RemoveResult::NotInMesh);
    // Down to two points: nothing is left to triangulate, and removing goes on cleanly.
    EXPECT_EQ(remover.remove(0), RemoveResult::Collapsed);
    EXPECT_EQ(mesh.numTriangles(), 0);
    EXPECT_EQ(remover.remove(1), RemoveResult::NotInMesh);
}

TEST(Remover, GhostsAddedToAFinishedMeshEqualTheInsertersClosedMesh) {
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        const auto pts = distinct(generatePoints(Generator::Collinear, 90, seed));
        const std::int32_t n = static_cast<std::int32_t>(pts.size());
        Inserter ins(pts);
        ins.run();
        Mesh closed = ins.mesh();
        addGhosts(closed);
        ValidateOptions vo;
        vo.firstVirtual = n;
        const auto bad = validate(closed, vo);
        ASSERT_TRUE(bad.empty()) << bad[0].message;
        EXPECT_EQ(edgesOf(closed), edgesOf(closedMesh(pts, Boundary::Exact, 1)));
        Remover remover(closed, n, Boundary::Exact);
        for (std::int32_t v = 0; v < n; v += 3) ASSERT_NE(remover.remove(v), RemoveResult::Virtual);
        dropVirtual(closed, n);
        std::vector<std::int32_t> left;
        std::vector<Vec2> leftPts;
        for (std::int32_t v = 0; v < n; ++v) {
            if (v % 3 != 0) {
                left.push_back(v);
                leftPts.push_back(pts[v]);
            }
        }
        if (allCollinearExact(leftPts)) continue;
        EXPECT_EQ(checkDelaunayExact(closed, &left), "");
    }
}

TEST(Remover, CentreOfExactlyCocircularPointsAndThenTheCircleItself) {
    // The 36 lattice points of x^2 + y^2 = 65^2 and their centre: the centre has degree 36 and
    // every ear of its hole is cocircular with all the others.
    std::vector<Vec2> pts = {{0, 0}};
    for (int x = -65; x <= 65; ++x) {
        for (int y = -65; y <= 65; ++y) {
            if (x * x + y * y == 65 * 65) pts.push_back({double(x), double(y)});
        }
    }
    ASSERT_EQ(pts.size(), 37u);
    for (const Boundary boundary : {Boundary::Exact, Boundary::Super}) {
        Mesh mesh = closedMesh(pts, boundary, 1);
        const std::int32_t n = static_cast<std::int32_t>(pts.size());
        Remover remover(mesh, n, boundary);
        ASSERT_EQ(remover.remove(0), RemoveResult::Removed);
        ValidateOptions vo;
        vo.firstVirtual = boundary == Boundary::Exact ? n : -1;
        const auto bad = validate(mesh, vo);
        ASSERT_TRUE(bad.empty()) << bad[0].message;
        if (boundary == Boundary::Exact) {
            Mesh finished = mesh;
            dropVirtual(finished, n);
            std::vector<std::int32_t> left;
            for (std::int32_t i = 1; i < n; ++i) left.push_back(i);
            EXPECT_EQ(checkDelaunayExact(finished, &left), "");
            EXPECT_EQ(finished.numTriangles(), n - 3);  // 36 hull points: 34 triangles
        }
    }
    RemovalRun run;
    run.pts = pts;
    removeAll(run, "circle of 36 lattice points and its centre");
}
