// Edits of a finished triangulation: removals and constraints recorded as ops, stepped forwards
// and backwards bit for bit, checked constrained Delaunay in GMP after each, refusals that change
// nothing, and a new edit in the middle of the history dropping the ones after it.
#include "core/engine/editor.h"
#include "core/engine/inserter.h"
#include "core/teaching/describe_edit.h"
#include "tests/exact_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>

using namespace dlab;

namespace {

Mesh finishedDelaunay(const std::vector<Vec2>& pts) {
    Inserter ins(pts);
    ins.run();
    return ins.takeMesh();
}

// The points (x, y) for x and y from 0 to n - 1, row by row.
std::vector<Vec2> lattice(int n) {
    std::vector<Vec2> pts;
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) pts.push_back({double(x), double(y)});
    }
    return pts;
}

std::vector<Vec2> randomPoints(int n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> d(0, 60);  // small integers: cocircular and collinear runs
    std::vector<Vec2> pts;
    for (int i = 0; i < n; ++i) pts.push_back({double(d(rng)), double(d(rng))});
    return pts;
}

// The ghost triangles' hull edges x->y (the mesh on their left) make one convex polygon: at each
// hull vertex the hull turns left or goes straight on, never back.
std::string checkHullConvex(const Editor& ed) {
    const Mesh& m = ed.mesh();
    const std::int32_t n = ed.firstVirtual();
    std::vector<std::int32_t> after(m.G.size(), -1);  // the hull vertex after each one
    std::int32_t first = -1, edges = 0;
    for (std::int32_t g = 0; g < m.numCorners(); ++g) {
        if (m.V[g] < n) continue;
        const std::int32_t x = m.V[prev(g)], y = m.V[next(g)];
        if (after[x] != -1) return "vertex " + std::to_string(x) + " starts two hull edges";
        after[x] = y;
        first = x;
        ++edges;
    }
    std::int32_t x = first;
    for (std::int32_t k = 0; k < edges; ++k) {
        const std::int32_t y = after[x], z = after[y];
        if (y < 0 || z < 0) return "the hull is not one closed polygon";
        const Vec2 a = m.G[x], b = m.G[y], c = m.G[z];
        const int turn = orientGmp(a, b, c);
        const double ahead = (b.x - a.x) * (c.x - b.x) + (b.y - a.y) * (c.y - b.y);
        if (turn < 0 || (turn == 0 && ahead <= 0))
            return "the hull is not convex at vertex " + std::to_string(y);
        x = y;
    }
    return x == first ? "" : "the hull's edges make more than one polygon";
}

// The closed mesh is valid (O its own inverse, edges matched) and every unconstrained edge
// between finite triangles is locally Delaunay (GMP).
std::string checkEdited(const Editor& ed) {
    const Mesh& m = ed.mesh();
    const std::int32_t n = ed.firstVirtual();
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        const std::int32_t o = m.O[c];
        if (o < 0 || o >= m.numCorners() || m.O[o] != c)
            return "corner " + std::to_string(c) + ": O is not its own inverse";
        if (m.V[next(c)] != m.V[prev(o)] || m.V[prev(c)] != m.V[next(o)])
            return "corner " + std::to_string(c) + ": its edge is not its opposite's";
        if (ed.isConstrained(c) != ed.isConstrained(o))
            return "corner " + std::to_string(c) + ": the flag differs across its edge";
        const std::int32_t t = tri(c);
        const std::int32_t a = m.V[3 * t], b = m.V[3 * t + 1], d = m.V[3 * t + 2];
        if (a >= n || b >= n || d >= n) continue;
        if (orientGmp(m.G[a], m.G[b], m.G[d]) <= 0)
            return "triangle " + std::to_string(t) + " is not counter-clockwise";
        if (m.V[o] >= n || ed.isConstrained(c)) continue;
        if (incircleGmp(m.G[a], m.G[b], m.G[d], m.G[m.V[o]]) > 0)
            return "edge opposite corner " + std::to_string(c) + " is not Delaunay";
    }
    return checkHullConvex(ed);
}

struct Snapshot {
    std::vector<std::int32_t> V, O;
    std::vector<std::pair<std::int32_t, std::int32_t>> constrained;
    bool operator==(const Snapshot&) const = default;
};

Snapshot snap(const Editor& ed) { return {ed.mesh().V, ed.mesh().O, ed.constrainedEdges()}; }

}  // namespace

TEST(Editor, EveryEditStepsForwardsAndBackBitForBitAndStaysConstrainedDelaunay) {
    for (unsigned seed = 1; seed <= 6; ++seed) {
        const std::vector<Vec2> pts = randomPoints(120, seed);
        Editor ed(finishedDelaunay(pts));
        std::vector<Snapshot> atEnd{snap(ed)};  // after 0, 1, 2... edits
        std::mt19937 rng(seed * 7919);
        std::uniform_int_distribution<std::int32_t> vertex(0, 119);
        int kept = 0;
        for (int k = 0; k < 40; ++k) {
            Edit edit;
            const int kind = k % 3;
            edit.kind = kind == 0 ? EditKind::RemoveVertex : EditKind::Constrain;
            edit.a = vertex(rng);
            edit.b = vertex(rng);
            if (kind == 2 && !ed.constrainedEdges().empty()) {
                edit.kind = EditKind::Unconstrain;
                const auto& cs = ed.edits();
                for (auto it = cs.rbegin(); it != cs.rend(); ++it) {
                    if (it->kind != EditKind::Constrain) continue;
                    edit.a = it->a;
                    edit.b = it->b;
                    break;
                }
            }
            const Snapshot before = snap(ed);
            std::string message;
            const bool ok = ed.add(edit, message);
            ASSERT_FALSE(message.empty());
            ASSERT_EQ(snap(ed), before) << "seed " << seed << ", " << describe(edit) << ": "
                                        << message << " (the mesh must be back at its start)";
            if (!ok) {
                EXPECT_EQ(ed.position(), ed.total());
                continue;
            }
            ++kept;
            ASSERT_EQ(ed.edits().size(), static_cast<std::size_t>(kept));
            ASSERT_EQ(ed.position(), ed.editStart(ed.edits().size() - 1));
            while (ed.forward()) {
                ASSERT_NE(ed.current().edit, nullptr);
            }
            ASSERT_EQ(checkEdited(ed), "") << "seed " << seed << " after " << describe(edit);
            atEnd.push_back(snap(ed));
        }
        EXPECT_GT(kept, 10) << "seed " << seed;
        // Back to the start op by op, then to the end of every edit: bit for bit.
        for (std::size_t e = atEnd.size() - 1; e-- > 0;) {
            while (ed.position() > ed.editStart(e)) ASSERT_TRUE(ed.back());
            ASSERT_EQ(snap(ed), atEnd[e]) << "seed " << seed << ", back before edit " << e;
        }
        EXPECT_FALSE(ed.back());
        for (std::size_t e = 0; e + 1 < atEnd.size(); ++e) {
            ed.seek(ed.editEnd(e));
            ASSERT_EQ(snap(ed), atEnd[e + 1]) << "seed " << seed << ", after edit " << e;
        }
    }
}

TEST(Editor, RemovingDownToTwoPointsLeavesNoTriangleAndStepsBack) {
    const std::vector<Vec2> pts{{0, 0}, {4, 0}, {4, 4}, {0, 4}, {2, 2}, {1, 3}};
    Editor ed(finishedDelaunay(pts));
    const Snapshot start = snap(ed);
    std::string message;
    for (std::int32_t v : {4, 0, 5, 2}) {
        ASSERT_TRUE(ed.add(makeEdit(EditKind::RemoveVertex, v), message)) << message;
        ed.seek(ed.total());
        EXPECT_EQ(checkEdited(ed), "") << "after removing " << v;
    }
    EXPECT_EQ(ed.mesh().numTriangles(), 0) << "two points make no triangle";
    EXPECT_NE(message.find("no triangle"), std::string::npos) << message;
    ed.seek(0);
    EXPECT_EQ(snap(ed), start);
}

TEST(Editor, RefusedEditsChangeNothingAndSayWhy) {
    // A 3x3 lattice: the segments 1-3 and 0-4 cross at (0.5, 0.5).
    Editor ed(finishedDelaunay(lattice(3)));
    std::string message;
    ASSERT_TRUE(ed.add(makeEdit(EditKind::Constrain, 1, 3), message)) << message;
    ed.seek(ed.total());
    const Snapshot constrained = snap(ed);
    ASSERT_EQ(constrained.constrained.size(), 1u);
    const std::size_t ops = ed.total();

    EXPECT_FALSE(ed.add(makeEdit(EditKind::Constrain, 0, 4), message));
    EXPECT_NE(message.find("crosses the constrained edge"), std::string::npos) << message;
    EXPECT_FALSE(ed.add(makeEdit(EditKind::RemoveVertex, 1), message));
    EXPECT_NE(message.find("take that constraint away first"), std::string::npos) << message;
    EXPECT_FALSE(ed.add(makeEdit(EditKind::RemoveVertex, 9), message));
    EXPECT_NE(message.find("no such vertex"), std::string::npos) << message;
    EXPECT_FALSE(ed.add(makeEdit(EditKind::Unconstrain, 0, 8), message));
    EXPECT_NE(message.find("is not a constraint"), std::string::npos) << message;
    EXPECT_FALSE(ed.add(makeEdit(EditKind::Constrain, 2, 2), message));
    EXPECT_EQ(snap(ed), constrained);
    EXPECT_EQ(ed.total(), ops);

    // Taken away, the constraint no longer blocks the removal of 1.
    ASSERT_TRUE(ed.add(makeEdit(EditKind::Unconstrain, 1, 3), message)) << message;
    ASSERT_TRUE(ed.add(makeEdit(EditKind::RemoveVertex, 1), message)) << message;
    ed.seek(ed.total());
    EXPECT_TRUE(ed.constrainedEdges().empty());
    EXPECT_EQ(checkEdited(ed), "");
    EXPECT_FALSE(ed.add(makeEdit(EditKind::RemoveVertex, 1), message));
    EXPECT_NE(message.find("not in the mesh"), std::string::npos) << message;
}

TEST(Editor, ANewEditGoesAfterEveryEditAndTakeLastUndoesOnlyTheLast) {
    const std::vector<Vec2> pts = randomPoints(60, 3);
    Editor ed(finishedDelaunay(pts));
    std::string message;
    std::vector<std::int32_t> removed;
    std::vector<Snapshot> after;  // after 1, 2, 3 removals
    for (std::int32_t v = 0; removed.size() < 3 && v < 60; ++v) {
        if (ed.add(makeEdit(EditKind::RemoveVertex, v), message)) {
            removed.push_back(v);
            ed.seek(ed.total());
            after.push_back(snap(ed));
        }
    }
    ASSERT_EQ(ed.edits().size(), 3u);
    // Stepping back anywhere drops nothing: a new edit finishes them all and goes after them.
    ed.seek(ed.editStart(1) + 1);
    ASSERT_TRUE(ed.add(makeEdit(EditKind::RemoveVertex, 59), message)) << message;
    ASSERT_EQ(ed.edits().size(), 4u);
    EXPECT_EQ(ed.edits()[3].a, 59);
    EXPECT_EQ(ed.position(), ed.editStart(3));
    EXPECT_EQ(snap(ed), after[2]) << "the mesh after the three removals, before the fourth";
    EXPECT_EQ(ed.editsDone(), 3u);
    // Added and not yet stepped, an edit is kept by the next one, which finishes it first.
    ASSERT_TRUE(ed.add(makeEdit(EditKind::RemoveVertex, 58), message)) << message;
    ASSERT_EQ(ed.edits().size(), 5u);
    EXPECT_EQ(ed.editsDone(), 4u);
    // takeLast undoes the last edit only, from anywhere, and gives it back as asked.
    ed.seek(ed.total());
    const auto last = ed.takeLast();
    ASSERT_TRUE(last);
    EXPECT_EQ(last->a, 58);
    EXPECT_TRUE(last->removal.ops.empty());
    EXPECT_EQ(ed.edits().size(), 4u);
    EXPECT_EQ(ed.position(), ed.total());
    ed.seek(1);
    ASSERT_TRUE(ed.takeLast());
    EXPECT_EQ(ed.position(), 1u) << "before the edit taken out: the position stays";
    ed.seek(ed.total());
    EXPECT_EQ(snap(ed), after[2]);
    EXPECT_EQ(checkEdited(ed), "");
}

TEST(Editor, EditsReadBackAsTheyAreWritten) {
    for (const char* text : {"remove vertex 5", "constrain 2-7", "unconstrain 12-3"}) {
        const auto e = parseEdit(text);
        ASSERT_TRUE(e) << text;
        EXPECT_EQ(describe(*e), text);
    }
    const auto loose = parseEdit("  Remove 5 ");
    ASSERT_TRUE(loose);
    EXPECT_EQ(loose->kind, EditKind::RemoveVertex);
    EXPECT_EQ(loose->a, 5);
    const auto spaced = parseEdit("constrain 2 - 7");
    ASSERT_TRUE(spaced);
    EXPECT_EQ(spaced->b, 7);
    for (const char* bad : {"", "remove", "remove -1", "remove x", "constrain 2", "constrain 2-",
                            "flip 2-7", "remove 5 6"}) {
        EXPECT_FALSE(parseEdit(bad)) << bad;
    }
}

// Edits made after stepping anywhere and after taking edits out give the mesh that the same
// edits give made one after another on a fresh editor.
TEST(Editor, EditsAfterSteppingAndTakingOutMatchAFreshEditor) {
    for (unsigned seed = 1; seed <= 4; ++seed) {
        const std::vector<Vec2> pts = randomPoints(80, seed + 100);
        const Mesh finished = finishedDelaunay(pts);
        Editor ed(finished);
        std::mt19937 rng(seed);
        std::uniform_int_distribution<std::int32_t> vertex(0, 79);
        for (int k = 0; k < 60; ++k) {
            ed.seek(std::uniform_int_distribution<std::size_t>(0, ed.total())(rng));
            if (rng() % 4 == 0) ed.takeLast();
            const EditKind kind = rng() % 2 ? EditKind::RemoveVertex : EditKind::Constrain;
            std::string message;
            ed.add(makeEdit(kind, vertex(rng), vertex(rng)), message);
            ed.seek(ed.total());
            ASSERT_EQ(checkEdited(ed), "") << "seed " << seed << ", step " << k;
            Editor fresh(finished);
            for (const Edit& e : ed.edits()) {
                ASSERT_TRUE(fresh.add(makeEdit(e.kind, e.a, e.b), message)) << message;
                fresh.seek(fresh.total());
            }
            ASSERT_EQ(snap(fresh), snap(ed)) << "seed " << seed << ", step " << k;
        }
    }
}

// A removal taken out puts its vertex back: a segment from it is then constrained as on a mesh
// that never lost it.
TEST(Editor, AVertexWhoseRemovalWasTakenOutTakesASegment) {
    const std::vector<Vec2> pts = randomPoints(50, 7);
    const Mesh finished = finishedDelaunay(pts);
    std::string message;
    for (std::int32_t v = 0; v < 50; ++v) {
        Editor ed(finished);
        if (!ed.add(makeEdit(EditKind::RemoveVertex, v), message)) continue;
        ed.seek(ed.total());
        ASSERT_TRUE(ed.takeLast());
        const std::int32_t w = (v + 25) % 50;
        Editor fresh(finished);
        const bool want = fresh.add(makeEdit(EditKind::Constrain, v, w), message);
        ASSERT_EQ(ed.add(makeEdit(EditKind::Constrain, v, w), message), want)
            << v << ": " << message;
        ed.seek(ed.total());
        fresh.seek(fresh.total());
        ASSERT_EQ(snap(ed), snap(fresh)) << "segment " << v << "-" << w;
        ASSERT_EQ(checkEdited(ed), "");
    }
}

namespace {

bool usesVertex(const Mesh& m, std::int32_t v) {
    return std::find(m.V.begin(), m.V.end(), v) != m.V.end();
}

}  // namespace

// Moves anywhere: inside the hull, beyond it (the hull grows and takes in the vertices it makes
// reflex), and back inside (a hull vertex moved in leaves the hull).
TEST(Editor, AMovedVertexGoesAnywhereAndTheMeshStaysDelaunayWithAConvexHull) {
    int moved = 0, outside = 0, inKernel = 0;
    for (unsigned seed = 1; seed <= 5; ++seed) {
        const std::vector<Vec2> pts = randomPoints(70, seed + 200);
        Editor ed(finishedDelaunay(pts));
        const Mesh start = ed.mesh();
        std::mt19937 rng(seed);
        std::uniform_int_distribution<int> coord(-15, 75);
        for (int k = 0; k < 25; ++k) {
            const std::int32_t v = static_cast<std::int32_t>(rng() % 70);
            const Vec2 to{coord(rng) + 0.5 * (rng() % 2), double(coord(rng))};
            const Mesh before = ed.mesh();
            std::string message;
            if (!ed.add(makeMove(v, to), message)) {
                EXPECT_EQ(ed.mesh().G, before.G) << message;
                EXPECT_EQ(ed.mesh().V, before.V) << message;
                EXPECT_TRUE(message.find("onto another vertex") != std::string::npos ||
                            message.find("already there") != std::string::npos ||
                            message.find("not in the mesh") != std::string::npos)
                    << message;
                continue;
            }
            ++moved;
            outside += to.x < 0 || to.x > 60 || to.y < 0 || to.y > 60;
            inKernel += ed.edits().back().removal.ops.empty();
            ed.seek(ed.total());
            const Mesh& m = ed.mesh();
            ASSERT_EQ(checkEdited(ed), "") << "seed " << seed << ": " << message;
            EXPECT_EQ(m.G[v].x, to.x);
            EXPECT_EQ(m.G[v].y, to.y);
            EXPECT_TRUE(usesVertex(m, v));
            for (std::int32_t u = 0; u < 70; ++u)
                EXPECT_EQ(usesVertex(m, u), usesVertex(before, u)) << "vertex " << u;
        }
        ed.seek(0);
        EXPECT_EQ(ed.mesh().G, start.G);
        EXPECT_EQ(ed.mesh().V, start.V);
        EXPECT_EQ(ed.mesh().O, start.O);
    }
    EXPECT_GT(moved, 100);
    EXPECT_GT(outside, 20) << "moves beyond the hull";
}

// A small move keeps every triangle at the vertex counter-clockwise: no removal, the vertex takes
// its new place and flips follow; a move beyond the kernel takes it out and puts it in again.
TEST(Editor, AMoveInsideTheStarsKernelIsFollowedByFlipsAndStepsBackBitForBit) {
    int flips = 0, kernelMoves = 0, removals = 0;
    for (unsigned seed = 1; seed <= 5; ++seed) {
        std::mt19937 rng(seed + 40);
        std::uniform_real_distribution<double> u(0, 100);
        std::vector<Vec2> pts;
        for (int i = 0; i < 200; ++i) pts.push_back({u(rng), u(rng)});
        Editor ed(finishedDelaunay(pts));
        std::normal_distribution<double> step(0, 1.5);
        std::vector<Snapshot> after{snap(ed)};
        std::vector<std::vector<Vec2>> places{ed.mesh().G};
        for (int k = 0; k < 60; ++k) {
            const std::int32_t v = static_cast<std::int32_t>(rng() % 200);
            const Vec2 to{ed.mesh().G[v].x + step(rng), ed.mesh().G[v].y + step(rng)};
            std::string message;
            ASSERT_TRUE(ed.add(makeMove(v, to), message)) << message;
            const Edit& e = ed.edits().back();
            if (e.removal.ops.empty()) {
                ++kernelMoves;
                EXPECT_EQ(e.constraint.ops.front().type, ConstrainOpType::MoveVertex);
                EXPECT_EQ(e.constraint.ops.front().sign, 1);
                EXPECT_NE(message.find("kernel"), std::string::npos) << message;
                for (const ConstrainOp& op : e.constraint.ops)
                    flips += op.type == ConstrainOpType::Flip;
            } else {
                ++removals;
                EXPECT_NE(message.find("taken out"), std::string::npos) << message;
            }
            ed.seek(ed.total());
            ASSERT_EQ(checkEdited(ed), "") << "seed " << seed << ": " << message;
            after.push_back(snap(ed));
            places.push_back(ed.mesh().G);
        }
        for (std::size_t k = after.size() - 1; k-- > 0;) {  // back edit by edit, bit for bit
            ed.seek(ed.editStart(k));
            ASSERT_EQ(snap(ed), after[k]) << "seed " << seed << ", before edit " << k;
            ASSERT_EQ(ed.mesh().G, places[k]);
        }
    }
    EXPECT_GT(kernelMoves, 150);
    EXPECT_GT(flips, 20) << "small moves still change the triangulation";
    EXPECT_GT(removals, 0) << "some steps leave the kernel";
}

// The paper's super-triangle: edits on the mesh before Finalize, the super-triangle's vertices
// real points in every test; removals, constraints and moves mixed, each checked valid and
// constrained Delaunay (GMP, the super-triangle's vertices included), then stepped back.
TEST(Editor, InTheSuperTrianglesModeEditsKeepTheClosedMeshConstrainedDelaunay) {
    int made = 0;
    for (unsigned seed = 1; seed <= 4; ++seed) {
        InsertOptions o;
        o.boundary = Boundary::Super;
        const std::vector<Vec2> pts = randomPoints(80, seed + 90);
        Inserter ins(pts, o);
        Journal journal(ins);
        while (journal.forward()) {}
        std::unique_ptr<Editor> ed = editorAtRunEnd(journal, ins);
        ASSERT_TRUE(ins.done());
        ASSERT_EQ(ed->boundary(), Boundary::Super);
        const Snapshot start = snap(*ed);
        const std::vector<Vec2> startG = ed->mesh().G;
        std::mt19937 rng(seed);
        for (int k = 0; k < 30; ++k) {
            const auto a = static_cast<std::int32_t>(rng() % 80),
                       b = static_cast<std::int32_t>(rng() % 80);
            Edit edit = makeEdit(k % 3 == 0 ? EditKind::Constrain : EditKind::RemoveVertex, a, b);
            if (k % 3 == 2) edit = makeMove(a, {double(rng() % 70) - 5, double(rng() % 70) - 5});
            std::string message;
            if (!ed->add(edit, message)) continue;
            ++made;
            ed->seek(ed->total());
            const Mesh& m = ed->mesh();
            for (std::int32_t c = 0; c < m.numCorners(); ++c) {
                const std::int32_t oc = m.O[c];
                const std::int32_t t = tri(c);
                ASSERT_GT(orientGmp(m.G[m.V[3 * t]], m.G[m.V[3 * t + 1]], m.G[m.V[3 * t + 2]]), 0)
                    << describe(edit);
                if (oc == kNone) {
                    ASSERT_TRUE(m.V[next(c)] >= 80 && m.V[prev(c)] >= 80)
                        << "only the super-triangle's sides are open";
                    continue;
                }
                ASSERT_EQ(m.O[oc], c);
                if (ed->isConstrained(c)) continue;
                ASSERT_LE(
                    incircleGmp(m.G[m.V[c]], m.G[m.V[next(c)]], m.G[m.V[prev(c)]], m.G[m.V[oc]]), 0)
                    << "seed " << seed << " after " << describe(edit);
            }
        }
        ed->seek(0);
        EXPECT_EQ(snap(*ed), start);
        EXPECT_EQ(ed->mesh().G, startG);
    }
    EXPECT_GT(made, 60);
}

// A hull vertex moved out along the hull edge's line, onto a hull edge, and far out.
TEST(Editor, MovesOntoAndBeyondTheHullKeepItConvex) {
    Editor ed(finishedDelaunay(lattice(5)));
    std::string message;
    for (const auto& [v, to] : std::vector<std::pair<std::int32_t, Vec2>>{
             {12, {2, 4.5}},   // an interior vertex out beyond the top edge
             {12, {2, 4}},     // onto a vertex: refused below
             {12, {6, 0}},     // beyond the corner, on the bottom edge's line
             {24, {2.5, 0}},   // the corner onto the bottom edge
             {6, {-3, -3}},    // far out beyond the corner
             {0, {1.5, 1.5}},  // a hull vertex moved in
             {4, {10, 10}}}) {
        const bool ok = ed.add(makeMove(v, to), message);
        if (to == Vec2{2, 4}) {
            EXPECT_FALSE(ok);
            EXPECT_NE(message.find("onto another vertex"), std::string::npos) << message;
            continue;
        }
        ASSERT_TRUE(ok) << message;
        ed.seek(ed.total());
        ASSERT_EQ(checkEdited(ed), "") << describe(ed.edits().back());
    }
    ed.seek(0);
    EXPECT_EQ(checkEdited(ed), "");
}

TEST(Editor, AVertexMovedOntoAConstrainedEdgeSplitsItAndBothHalvesStayConstrained) {
    Editor ed(finishedDelaunay(lattice(5)));
    std::string message;
    ASSERT_TRUE(ed.add(makeEdit(EditKind::Constrain, 5, 9), message)) << message;
    ASSERT_TRUE(ed.add(makeMove(12, {2.5, 1}), message)) << message;
    ed.seek(ed.total());
    EXPECT_EQ(checkEdited(ed), "");
    auto has = [&](std::int32_t a, std::int32_t b) {
        for (const auto& [u, w] : ed.constrainedEdges())
            if ((u == a && w == b) || (u == b && w == a)) return true;
        return false;
    };
    EXPECT_TRUE(has(7, 12) && has(12, 8)) << "7-8 split at 12, both halves constrained";
    EXPECT_FALSE(has(7, 8));
    EXPECT_FALSE(ed.add(makeMove(13, {3, 3}), message));
    EXPECT_NE(message.find("onto another vertex"), std::string::npos) << message;
    EXPECT_FALSE(ed.add(makeMove(7, {1, 3}), message));
    EXPECT_NE(message.find("take that constraint away first"), std::string::npos) << message;
    const auto e = parseEdit(describe(ed.edits()[1]));
    ASSERT_TRUE(e);
    EXPECT_EQ(describe(*e), "move vertex 12 to 2.5, 1");
    EXPECT_EQ(e->to.x, 2.5);
}

// A removal that leaves the other points collinear drops the constraints between them (no
// triangle holds them) and says how many; stepping back restores them.
TEST(Editor, ARemovalThatLeavesNoTriangleSaysWhichConstraintsItDrops) {
    Editor ed(finishedDelaunay({{0, 0}, {1, 0}, {2, 0}, {1, 1}}));
    std::string message;
    ASSERT_TRUE(ed.add(makeEdit(EditKind::Constrain, 0, 2), message)) << message;
    ed.seek(ed.total());
    ASSERT_EQ(ed.constrainedEdges().size(), 2u) << "0-2 through 1: two constrained edges";
    ASSERT_TRUE(ed.add(makeEdit(EditKind::RemoveVertex, 3), message)) << message;
    EXPECT_NE(message.find("no triangle, and the 2 constraints between them are dropped"),
              std::string::npos)
        << message;
    ed.seek(ed.total());
    EXPECT_TRUE(ed.constrainedEdges().empty());
    ed.seek(ed.editEnd(0));
    EXPECT_EQ(ed.constrainedEdges().size(), 2u);
}

// A hull vertex whose removal leaves the other points collinear (a triangle's corner, the apex
// over a row of points) still moves to any place off their line: the points there make
// triangles, so the move is made, not refused as "no triangle".
TEST(Editor, AVertexWhoseOtherPointsAreCollinearMovesOffTheirLine) {
    struct Case {
        std::vector<Vec2> pts;
        std::int32_t v;
        Vec2 to;
    };
    const std::vector<Case> cases{
        {{{2, 2}, {0, 3}, {2, 0}}, 0, {2, 3}},                   // a triangle's corner, a step
        {{{2, 2}, {0, 3}, {2, 0}}, 0, {5, 5}},                   // ... and far out
        {{{0, 0}, {1, 0}, {2, 0}, {3, 0}, {1, 1}}, 4, {2, 3}}};  // the apex over a row
    for (const Case& k : cases) {
        Editor ed(finishedDelaunay(k.pts));
        const Snapshot start = snap(ed);
        std::string message;
        const Edit move = makeMove(k.v, k.to);
        if (!ed.add(move, message)) {
            ADD_FAILURE() << describe(move) << ": " << message;
            continue;
        }
        ed.seek(ed.total());
        EXPECT_EQ(checkEdited(ed), "") << describe(move);
        EXPECT_EQ(ed.mesh().G[k.v], k.to);
        EXPECT_TRUE(usesVertex(ed.mesh(), k.v));
        EXPECT_EQ(ed.mesh().numTriangles(), static_cast<std::int32_t>(start.V.size() / 3));
        const auto& ops = ed.edits()[0].constraint.ops;
        const auto fan = std::find_if(ops.begin(), ops.end(), [](const ConstrainOp& op) {
            return op.type == ConstrainOpType::Fan;
        });
        ASSERT_NE(fan, ops.end()) << describe(move) << ": the others collinear, a fan";
        ed.seek(ed.edits()[0].removal.ops.size() + (fan - ops.begin()) + 1);
        EXPECT_NE(describeEditStep(ed).find(", off their line, makes a fan of triangles"),
                  std::string::npos)
            << describeEditStep(ed);
        ed.seek(0);
        EXPECT_EQ(snap(ed), start);
        // Onto their line, beyond the last two of them: no triangle would be left.
        Editor again(finishedDelaunay(k.pts));
        const auto n = static_cast<std::int32_t>(k.pts.size());
        const std::int32_t last = k.v == n - 1 ? n - 2 : n - 1;
        const std::int32_t before = k.v == last - 1 ? last - 2 : last - 1;
        const Vec2 a = k.pts[before], b = k.pts[last];
        EXPECT_FALSE(again.add(makeMove(k.v, {2 * b.x - a.x, 2 * b.y - a.y}), message));
        EXPECT_NE(message.find("onto the line of the other points"), std::string::npos) << message;
        EXPECT_EQ(snap(again), start);
    }
}
