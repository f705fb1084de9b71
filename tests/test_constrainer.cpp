// Constrained edges: random segments on uniform sets and lattices (segments through vertices,
// collinear runs), each insertion checked: a valid table, the segment's pieces constrained,
// every other edge locally Delaunay in GMP, crossings refused without a change.
#include "core/engine/constrainer.h"
#include "core/engine/generators.h"
#include "core/engine/inserter.h"
#include "core/engine/remover.h"
#include "tests/distinct_points.h"
#include "tests/exact_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <set>
#include <string>

using namespace dlab;
using dlab::testutil::distinct;

namespace {

// The exact Delaunay triangulation of pts in its closed form (ghost triangles around the hull):
// what the Constrainer and the Remover work on.
Mesh closedDelaunay(const std::vector<Vec2>& pts) {
    Inserter ins(pts);
    ins.run();
    Mesh mesh = ins.takeMesh();
    addGhosts(mesh);
    return mesh;
}

// The integer points of a side x side square: collinear runs and cocircular squares everywhere.
std::vector<Vec2> squareLattice(int side) {
    std::vector<Vec2> pts;
    for (int y = 0; y < side; ++y) {
        for (int x = 0; x < side; ++x) pts.push_back({double(x), double(y)});
    }
    return pts;
}

bool flaggedEdge(const Mesh& m, const Constrainer& con, std::int32_t a, std::int32_t b) {
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        const std::int32_t u = m.V[next(c)], w = m.V[prev(c)];
        if (((u == a && w == b) || (u == b && w == a)) && con.isConstrained(c)) return true;
    }
    return false;
}

// The vertices on the closed segment a-b, in order from a.
std::vector<std::int32_t> onSegment(const std::vector<Vec2>& pts, std::int32_t a, std::int32_t b) {
    std::vector<std::int32_t> out;
    const Vec2 pa = pts[a], pb = pts[b];
    for (std::int32_t i = 0; i < static_cast<std::int32_t>(pts.size()); ++i) {
        const Vec2 p = pts[i];
        if (orientGmp(pa, pb, p) != 0) continue;
        const double t = (p.x - pa.x) * (pb.x - pa.x) + (p.y - pa.y) * (pb.y - pa.y);
        const double len = (pb.x - pa.x) * (pb.x - pa.x) + (pb.y - pa.y) * (pb.y - pa.y);
        if (t >= 0 && t <= len) out.push_back(i);
    }
    std::sort(out.begin(), out.end(), [&](std::int32_t i, std::int32_t j) {
        return std::abs(pts[i].x - pa.x) + std::abs(pts[i].y - pa.y) <
               std::abs(pts[j].x - pa.x) + std::abs(pts[j].y - pa.y);
    });
    return out;
}

// Every unconstrained edge between finite triangles is locally Delaunay (exact, GMP).
std::string checkConstrainedDelaunay(const Mesh& m, const Constrainer& con, std::int32_t n) {
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        const std::int32_t o = m.O[c];
        if (o == kNone) return "corner " + std::to_string(c) + " has no opposite (closed mesh)";
        if (con.isConstrained(c) != con.isConstrained(o))
            return "corner " + std::to_string(c) + ": the flag differs across its edge";
        const std::int32_t t = tri(c);
        const std::int32_t a = m.V[3 * t], b = m.V[3 * t + 1], d = m.V[3 * t + 2];
        if (a >= n || b >= n || d >= n || m.V[o] >= n || con.isConstrained(c)) continue;
        if (incircleGmp(m.G[a], m.G[b], m.G[d], m.G[m.V[o]]) > 0)
            return "edge opposite corner " + std::to_string(c) + " is not Delaunay";
    }
    return "";
}

void insertRandomSegments(const std::vector<Vec2>& input, int count, std::uint64_t seed,
                          const std::string& label) {
    SCOPED_TRACE(label);
    const std::vector<Vec2> pts = distinct(input);
    const auto n = static_cast<std::int32_t>(pts.size());
    Mesh mesh = closedDelaunay(pts);
    Constrainer con(mesh, n);
    std::mt19937_64 rng(seed);
    std::vector<std::pair<std::int32_t, std::int32_t>> inserted;
    int accepted = 0, refused = 0;
    for (int k = 0; k < count; ++k) {
        const auto a = static_cast<std::int32_t>(rng() % n),
                   b = static_cast<std::int32_t>(rng() % n);
        if (a == b) continue;
        const Mesh before = mesh;
        const auto flagsBefore = con.flags();
        const ConstrainOutcome out = con.insert(a, b);
        const std::string at = "segment " + std::to_string(a) + "-" + std::to_string(b);
        if (out.result == ConstrainResult::Crosses) {
            ++refused;
            ASSERT_TRUE(mesh.V == before.V && mesh.O == before.O && con.flags() == flagsBefore)
                << at << ": a refusal changed the mesh";
            const auto [p, q] = out.crossed;
            ASSERT_TRUE(flaggedEdge(mesh, con, p, q)) << at;
            ASSERT_LT(orientGmp(pts[a], pts[b], pts[p]) * orientGmp(pts[a], pts[b], pts[q]), 0)
                << at;
            continue;
        }
        ASSERT_EQ(out.result, ConstrainResult::Inserted) << at;
        ++accepted;
        inserted.push_back({a, b});
        ValidateOptions vo;
        vo.firstVirtual = n;
        vo.delaunay = false;
        const auto bad = validate(mesh, vo);
        ASSERT_TRUE(bad.empty()) << at << ": " << bad[0].message;
        ASSERT_EQ(checkConstrainedDelaunay(mesh, con, n), "") << at;
        for (const auto& [s, t] : inserted) {
            const auto chain = onSegment(pts, s, t);
            for (std::size_t i = 0; i + 1 < chain.size(); ++i)
                ASSERT_TRUE(flaggedEdge(mesh, con, chain[i], chain[i + 1]))
                    << at << ": piece " << chain[i] << "-" << chain[i + 1] << " lost";
        }
    }
    EXPECT_GT(accepted, 0);
    ::testing::Test::RecordProperty(label + " refused", refused);
}

}  // namespace

TEST(Constrainer, RandomSegmentsOnUniformSetsGiveTheConstrainedDelaunayTriangulation) {
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        insertRandomSegments(generatePoints(Generator::Uniform, 300, seed), 60, seed,
                             "uniform seed " + std::to_string(seed));
    }
}

TEST(Constrainer, SegmentsThroughLatticeVerticesSplitThere) {
    const std::vector<Vec2> pts = squareLattice(12);
    insertRandomSegments(pts, 80, 7, "lattice 12x12");
    insertRandomSegments(generatePoints(Generator::Collinear, 200, 3), 60, 3, "collinear runs");
}

TEST(Constrainer, CrossingSegmentsAreRefusedNamingTheConstrainedEdge) {
    const std::vector<Vec2> pts = {{0, 0}, {4, 0}, {4, 4}, {0, 4}, {1, 2}, {3, 2}};
    Mesh mesh = closedDelaunay(pts);
    Constrainer con(mesh, 6);
    ASSERT_EQ(con.insert(0, 2).result, ConstrainResult::Inserted);
    const ConstrainOutcome out = con.insert(1, 3);
    ASSERT_EQ(out.result, ConstrainResult::Crosses);
    const std::set<std::int32_t> named = {out.crossed.first, out.crossed.second};
    EXPECT_EQ(named, std::set<std::int32_t>({0, 2}));
    EXPECT_EQ(con.insert(4, 5).result, ConstrainResult::Crosses);  // through (2, 2)
    EXPECT_EQ(con.insert(2, 2).result, ConstrainResult::SameVertex);
    EXPECT_EQ(con.insert(0, 6).result, ConstrainResult::NotInMesh);
    EXPECT_EQ(con.insert(4, 3).result, ConstrainResult::Inserted);
    EXPECT_EQ(checkConstrainedDelaunay(mesh, con, 6), "");
}

namespace {

struct Snapshot {
    std::vector<std::int32_t> V, O;
    std::vector<std::uint8_t> flags;
    bool operator==(const Snapshot&) const = default;
};

Snapshot snapshot(const Mesh& m, const Constrainer& con) { return {m.V, m.O, con.flags()}; }

// Replays ops [from, end) of the record forwards from their `before` state: what a journal's redo
// does with the cell and flag changes alone.
void replay(Mesh& m, std::vector<std::uint8_t>& flags, const ConstraintRecord& r,
            std::size_t from) {
    for (std::size_t i = from; i < r.ops.size(); ++i) {
        const ConstrainOp& op = r.ops[i];
        for (std::uint32_t k = 0; k < op.numChanges; ++k) {
            const CellChange& ch = r.changes[op.firstChange + k];
            (ch.isO() ? m.O : m.V)[ch.corner()] = ch.after;
        }
        for (std::uint32_t k = 0; k < op.numFlags; ++k) {
            const FlagChange& f = r.flagChanges[op.firstFlag + k];
            flags[f.corner] = f.after;
        }
    }
}

void recordAndUndo(const std::vector<Vec2>& input, int count, std::uint64_t seed) {
    const std::vector<Vec2> pts = distinct(input);
    const auto n = static_cast<std::int32_t>(pts.size());
    Mesh mesh = closedDelaunay(pts);
    Constrainer con(mesh, n);
    const Snapshot start = snapshot(mesh, con);
    ConstraintRecord record;
    std::mt19937_64 rng(seed);
    int inserted = 0;
    for (int k = 0; k < count; ++k) {
        const auto a = static_cast<std::int32_t>(rng() % n),
                   b = static_cast<std::int32_t>(rng() % n);
        const Snapshot before = snapshot(mesh, con);
        const std::size_t from = record.ops.size();
        const ConstrainOutcome out = con.insert(a, b, &record);
        const std::string at = "segment " + std::to_string(a) + "-" + std::to_string(b);
        if (out.result != ConstrainResult::Inserted) {
            ASSERT_EQ(record.ops.size(), from) << at << ": a refusal recorded operations";
            continue;
        }
        ++inserted;
        const Snapshot after = snapshot(mesh, con);
        std::int32_t crossed = 0, sloanFlips = 0, marks = 0;
        for (std::size_t i = from; i < record.ops.size(); ++i) {
            const ConstrainOp& op = record.ops[i];
            EXPECT_EQ(op.segmentA, a) << at;
            EXPECT_EQ(op.segmentB, b) << at;
            if (op.type == ConstrainOpType::Walk) crossed += op.count;
            if (op.type == ConstrainOpType::SloanFlip) ++sloanFlips;
            if (op.type == ConstrainOpType::Mark) ++marks;
        }
        EXPECT_GE(sloanFlips, crossed) << at;  // every crossed edge is flipped out at least once
        EXPECT_GE(marks, 1) << at;
        con.undo(record, from);
        ASSERT_TRUE(snapshot(mesh, con) == before) << at << ": undo is not bit for bit";
        Mesh redone = mesh;
        std::vector<std::uint8_t> flags = before.flags;
        replay(redone, flags, record, from);
        ASSERT_TRUE((Snapshot{redone.V, redone.O, flags}) == after) << at << ": replay differs";
        // Insert again, recorded anew: the same mesh.
        record.changes.resize(record.ops[from].firstChange);
        record.flagChanges.resize(record.ops[from].firstFlag);
        record.ops.resize(from);
        ASSERT_EQ(con.insert(a, b, &record).result, ConstrainResult::Inserted) << at;
        ASSERT_TRUE(snapshot(mesh, con) == after) << at << ": not the same mesh again";
    }
    EXPECT_GT(inserted, 0);
    con.undo(record);
    EXPECT_TRUE(snapshot(mesh, con) == start) << "undoing every insertion";
}

}  // namespace

// Every walk, Sloan flip, mark, in-circle test and repair flip is recorded with its V, O and
// flag changes: undoing an insertion restores the mesh and the flags bit for bit, replaying the
// changes gives the constrained mesh again, and undoing the whole record gives the start.
TEST(Constrainer, EveryInsertionIsRecordedAndUndoneBitForBit) {
    recordAndUndo(generatePoints(Generator::Uniform, 300, 5), 60, 5);
    const std::vector<Vec2> lattice = squareLattice(10);
    recordAndUndo(lattice, 60, 6);
    recordAndUndo(generatePoints(Generator::Collinear, 200, 4), 40, 4);
}

namespace {

void insertThenRemove(const std::vector<Vec2>& input, int count, std::uint64_t seed) {
    const std::vector<Vec2> pts = distinct(input);
    const auto n = static_cast<std::int32_t>(pts.size());
    Mesh mesh = closedDelaunay(pts);
    Constrainer con(mesh, n);
    std::mt19937_64 rng(seed);
    std::vector<std::pair<std::int32_t, std::int32_t>> inserted;
    for (int k = 0; k < count; ++k) {
        const auto a = static_cast<std::int32_t>(rng() % n),
                   b = static_cast<std::int32_t>(rng() % n);
        if (a != b && con.insert(a, b).result == ConstrainResult::Inserted)
            inserted.push_back({a, b});
    }
    ASSERT_FALSE(inserted.empty());
    std::shuffle(inserted.begin(), inserted.end(), rng);
    ConstraintRecord record;
    while (!inserted.empty()) {
        const auto [a, b] = inserted.back();
        inserted.pop_back();
        const std::string at = "removing " + std::to_string(a) + "-" + std::to_string(b);
        const Snapshot before = snapshot(mesh, con);
        const std::size_t from = record.ops.size();
        ASSERT_EQ(con.remove(a, b, &record).result, ConstrainResult::Inserted) << at;
        ASSERT_EQ(checkConstrainedDelaunay(mesh, con, n), "") << at;
        for (const auto& [s, t] : inserted) {  // the others keep every piece
            const auto chain = onSegment(pts, s, t);
            for (std::size_t i = 0; i + 1 < chain.size(); ++i)
                ASSERT_TRUE(flaggedEdge(mesh, con, chain[i], chain[i + 1])) << at;
        }
        const Snapshot after = snapshot(mesh, con);
        con.undo(record, from);
        ASSERT_TRUE(snapshot(mesh, con) == before) << at << ": undo is not bit for bit";
        record.changes.resize(record.ops[from].firstChange);
        record.flagChanges.resize(record.ops[from].firstFlag);
        record.ops.resize(from);
        ASSERT_EQ(con.remove(a, b, &record).result, ConstrainResult::Inserted) << at;
        ASSERT_TRUE(snapshot(mesh, con) == after) << at;
    }
    for (const std::uint8_t f : con.flags()) ASSERT_EQ(f, 0);
    Mesh finished = mesh;
    dropVirtual(finished, n);
    EXPECT_EQ(checkDelaunayExact(finished), "") << "every constraint removed: Delaunay again";
}

}  // namespace

// Constraints taken away in random order: the others keep every piece, the mesh is constrained
// Delaunay after each removal (undone and redone bit for bit), and Delaunay once none is left.
TEST(Constrainer, RemovedConstraintsLeaveTheConstrainedDelaunayTriangulationOfTheOthers) {
    insertThenRemove(generatePoints(Generator::Uniform, 300, 8), 40, 8);
    const std::vector<Vec2> lattice = squareLattice(10);
    insertThenRemove(lattice, 40, 9);
    insertThenRemove(generatePoints(Generator::Collinear, 200, 5), 30, 5);
}

TEST(Constrainer, RemovingASegmentThatIsNoConstraintChangesNothing) {
    const std::vector<Vec2> pts = {{0, 0}, {4, 0}, {4, 4}, {0, 4}, {1, 2}, {3, 2}, {2, 2}};
    Mesh mesh = closedDelaunay(pts);
    Constrainer con(mesh, 7);
    ASSERT_EQ(con.insert(4, 5).result, ConstrainResult::Inserted);  // pieces 4-6 and 6-5
    const Snapshot before = snapshot(mesh, con);
    ConstraintRecord record;
    EXPECT_EQ(con.remove(0, 2, &record).result, ConstrainResult::NotConstrained);
    EXPECT_EQ(con.remove(4, 4, &record).result, ConstrainResult::SameVertex);
    EXPECT_EQ(con.remove(4, 9, &record).result, ConstrainResult::NotInMesh);
    EXPECT_TRUE(record.ops.empty());
    EXPECT_TRUE(snapshot(mesh, con) == before);
    // Inserted twice, removed once: still constrained.
    ASSERT_EQ(con.insert(4, 6).result, ConstrainResult::Inserted);
    ASSERT_EQ(con.remove(4, 5, &record).result, ConstrainResult::Inserted);
    EXPECT_TRUE(flaggedEdge(mesh, con, 4, 6));
    EXPECT_FALSE(flaggedEdge(mesh, con, 6, 5));
}

namespace {

void removeVerticesKeepingConstraints(const std::vector<Vec2>& input, int segments,
                                      std::uint64_t seed) {
    const std::vector<Vec2> pts = distinct(input);
    const auto n = static_cast<std::int32_t>(pts.size());
    Mesh mesh = closedDelaunay(pts);
    Constrainer con(mesh, n);
    Remover remover(mesh, n, Boundary::Exact);
    std::mt19937_64 rng(seed);
    std::vector<std::pair<std::int32_t, std::int32_t>> inserted;
    for (int k = 0; k < segments; ++k) {
        const auto a = static_cast<std::int32_t>(rng() % n),
                   b = static_cast<std::int32_t>(rng() % n);
        if (a != b && con.insert(a, b).result == ConstrainResult::Inserted)
            inserted.push_back({a, b});
    }
    std::set<std::int32_t> held;  // vertices on a constraint
    for (const auto& [a, b] : inserted)
        for (const std::int32_t v : onSegment(pts, a, b)) held.insert(v);
    std::vector<std::int32_t> order(static_cast<std::size_t>(n));
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), rng);
    order.resize(order.size() / 2);
    RemovalRecord removal;
    ConstraintRecord record;
    int removed = 0, refused = 0;
    for (const std::int32_t v : order) {
        const std::string at = "vertex " + std::to_string(v);
        const Snapshot before = snapshot(mesh, con);
        const std::size_t fromR = removal.ops.size(), fromC = record.ops.size();
        const VertexRemoval out = con.removeVertex(remover, v, &removal, &record);
        if (held.count(v)) {
            ASSERT_TRUE(out.refused) << at << " is on a constraint";
            ASSERT_TRUE(snapshot(mesh, con) == before) << at;
            ++refused;
            continue;
        }
        ASSERT_FALSE(out.refused) << at;
        ASSERT_EQ(out.removed, RemoveResult::Removed) << at;
        ++removed;
        ValidateOptions vo;
        vo.firstVirtual = n;
        vo.delaunay = false;
        const auto bad = validate(mesh, vo);
        ASSERT_TRUE(bad.empty()) << at << ": " << bad[0].message;
        ASSERT_EQ(checkConstrainedDelaunay(mesh, con, n), "") << at;
        for (const auto& [s, t] : inserted) {
            const auto chain = onSegment(pts, s, t);
            for (std::size_t i = 0; i + 1 < chain.size(); ++i)
                ASSERT_TRUE(flaggedEdge(mesh, con, chain[i], chain[i + 1])) << at;
        }
        const Snapshot after = snapshot(mesh, con);
        con.undo(record, fromC);  // the flags and flips first, then the removal itself
        remover.undo(removal, fromR);
        con.refresh();
        ASSERT_TRUE(snapshot(mesh, con) == before) << at << ": undo is not bit for bit";
        removal.changes.resize(removal.ops[fromR].firstChange);
        removal.ops.resize(fromR);
        record.changes.resize(record.ops[fromC].firstChange);
        record.flagChanges.resize(record.ops[fromC].firstFlag);
        record.ops.resize(fromC);
        ASSERT_FALSE(con.removeVertex(remover, v, &removal, &record).refused) << at;
        ASSERT_TRUE(snapshot(mesh, con) == after) << at;
    }
    EXPECT_GT(removed, 0);
    EXPECT_GT(refused, 0);
}

}  // namespace

// Vertices removed from a constrained triangulation: refused on a constraint (nothing changed);
// elsewhere the mesh stays valid and constrained Delaunay with every constraint's pieces, and
// each removal is undone (flags, flips, then the removal) bit for bit and done again alike.
TEST(Constrainer, VertexRemovalKeepsEveryConstraint) {
    removeVerticesKeepingConstraints(generatePoints(Generator::Uniform, 200, 11), 25, 11);
    removeVerticesKeepingConstraints(squareLattice(9), 12, 12);
}
