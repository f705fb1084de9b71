// Inserter, Journal and locators: validity and exact Delaunay on degenerate sets in every mode,
// step-by-step equals batch, and exact undo.
#include "core/engine/generators.h"
#include "core/engine/inserter.h"
#include "core/engine/predicates.h"
#include "core/teaching/trace.h"
#include "tests/exact_check.h"

#include <gtest/gtest.h>

#include <cstring>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

using namespace dlab;

namespace {

struct Snapshot {
    std::vector<Vec2> G;
    std::vector<std::int32_t> V, O;
    bool operator==(const Snapshot& s) const {
        return V == s.V && O == s.O && G.size() == s.G.size() &&
               std::equal(G.begin(), G.end(), s.G.begin(),
                          [](Vec2 a, Vec2 b) { return std::memcmp(&a, &b, sizeof a) == 0; });
    }
};
Snapshot snap(const Mesh& m) { return {m.G, m.V, m.O}; }

// Every field of the state machine's control state, the walk's origin bit for bit.
bool sameControl(const Control& a, const Control& b) {
    return a.phase == b.phase && a.cursor == b.cursor && a.walk.tri == b.walk.tri &&
           a.walk.entry == b.walk.entry && a.walk.steps == b.walk.steps &&
           a.walk.straight == b.walk.straight &&
           std::memcmp(&a.walk.origin, &b.walk.origin, sizeof(Vec2)) == 0 && a.where == b.where &&
           a.whereCorner == b.whereCorner && a.flipCorner == b.flipCorner && a.lastTri == b.lastTri;
}

// Triangulates in batch and checks everything the exact mode promises.
void expectExactDelaunay(const std::vector<Vec2>& pts, const InsertOptions& opt,
                         const std::string& label) {
    SCOPED_TRACE(label);
    Inserter ins(pts, opt);
    ins.run();
    ASSERT_TRUE(ins.done());
    const Mesh& m = ins.mesh();
    ASSERT_EQ(m.numVertices(), static_cast<std::int32_t>(pts.size()));
    const auto violations = validate(m, {});
    ASSERT_TRUE(violations.empty()) << violations[0].message;
    const auto distinct = firstOccurrences(pts);
    if (allCollinearExact(pts)) {
        EXPECT_EQ(m.numTriangles(), 0);
        return;
    }
    ASSERT_EQ(checkDelaunayExact(m, &distinct), "");
    // Duplicates: the first occurrence is the vertex, every later copy is reported skipped.
    EXPECT_EQ(ins.stats().duplicates, static_cast<std::int64_t>(pts.size() - distinct.size()));
    std::set<std::int32_t> used(m.V.begin(), m.V.end());
    for (std::int32_t v : distinct) EXPECT_TRUE(used.count(v)) << "vertex " << v << " missing";
    for (std::int32_t s : ins.skipped()) EXPECT_FALSE(used.count(s)) << "skipped " << s << " used";
}

std::vector<std::pair<std::string, std::vector<Vec2>>> degenerateSets() {
    std::vector<std::pair<std::string, std::vector<Vec2>>> sets;
    for (Generator g :
         {Generator::Uniform, Generator::Clusters, Generator::Grid, Generator::RotatedGrid,
          Generator::Ngon, Generator::Circle, Generator::Collinear, Generator::NearDuplicates,
          Generator::HugeTinyBox, Generator::AllCollinear}) {
        sets.emplace_back(toString(g), generatePoints(g, 300, 7));
    }
    sets.emplace_back("demo", demoPoints());
    sets.emplace_back("empty", std::vector<Vec2>{});
    sets.emplace_back("one", std::vector<Vec2>{{1, 2}});
    sets.emplace_back("two", std::vector<Vec2>{{1, 2}, {3, 4}});
    sets.emplace_back("same-point", std::vector<Vec2>(20, Vec2{5, 5}));
    sets.emplace_back("triangle", std::vector<Vec2>{{0, 0}, {1, 0}, {0, 1}});
    sets.emplace_back("collinear-then-off",
                      std::vector<Vec2>{{0, 0}, {1, 1}, {2, 2}, {3, 3}, {0, 0}, {5, 0}});
    // Rescaled fixtures: the same grid from 1e-9 to 1e9 and at the extremes of double.
    for (double scale : {1e-300, 1e-200, 1e-9, 1.0, 1e9, 1e200, 1e300}) {
        auto g = generatePoints(Generator::Grid, 100, 1);
        for (Vec2& p : g) {
            p.x *= scale;
            p.y *= scale;
        }
        std::ostringstream name;
        name << "grid*" << scale;
        sets.emplace_back(name.str(), g);
    }
    auto offset = generatePoints(Generator::Uniform, 200, 3);
    for (Vec2& p : offset) {
        p.x = 1e9 + p.x * 1e-6;
        p.y = 1e9 + p.y * 1e-6;
    }
    sets.emplace_back("offset-1e9", offset);
    return sets;
}

}  // namespace

TEST(Inserter, ExactModeIsDelaunayOnDegenerateSetsForEveryLocatorAndOrder) {
    for (const auto& [name, pts] : degenerateSets()) {
        for (LocatorKind loc :
             {LocatorKind::Naive, LocatorKind::Walk, LocatorKind::Grid, LocatorKind::IdBufferCpu}) {
            for (OrderKind order : {OrderKind::Input, OrderKind::Random, OrderKind::Brio}) {
                InsertOptions opt;
                opt.locator = loc;
                opt.order = order;
                opt.locatorOptions.idBufferWidth = opt.locatorOptions.idBufferHeight = 128;
                expectExactDelaunay(pts, opt, name + "/" + toString(loc) + "/" + toString(order));
            }
        }
    }
}

TEST(Inserter, LargerRandomSetsAreDelaunay) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
        expectExactDelaunay(generatePoints(Generator::Uniform, 20000, seed), {}, "uniform-20k");
        expectExactDelaunay(generatePoints(Generator::Grid, 10000, seed), {}, "grid-10k");
    }
}

TEST(Inserter, EveryDistributionIsExactlyDelaunayAt2To14Points) {
    for (Generator g : allGenerators())
        expectExactDelaunay(generatePoints(g, 1 << 14, 5), {}, toString(g));
}

TEST(Inserter, TriangleCountMatchesEuler) {
    // t = 2n - h - 2 for n distinct points with h of them on the hull (collinear ones included).
    auto pts = generatePoints(Generator::Grid, 100, 1);  // 10 x 10 lattice: 36 hull points
    Inserter ins(pts);
    ins.run();
    EXPECT_EQ(ins.mesh().numTriangles(), 2 * 100 - 36 - 2);
}

TEST(Inserter, SuperModeKeepsWhatItPromises) {
    for (const auto& [name, pts] : degenerateSets()) {
        SCOPED_TRACE(name);
        InsertOptions opt;
        opt.boundary = Boundary::Super;
        Inserter ins(pts, opt);
        ins.run();
        // Valid, counter-clockwise, locally Delaunay between the triangles it kept.
        const auto v = validate(ins.mesh(), {});
        EXPECT_TRUE(v.empty()) << v[0].message;
        EXPECT_EQ(ins.mesh().numVertices(), static_cast<std::int32_t>(pts.size()));
    }
}

TEST(Inserter, SuperModeRefusesCoordinatesWithoutAFiniteSuperTriangle) {
    InsertOptions opt;
    opt.boundary = Boundary::Super;
    std::vector<Vec2> pts{{-1e308, -1e308}, {1e308, -1e308}, {0, 1e308}};
    EXPECT_THROW(Inserter(pts, opt), std::domain_error);
}

// The paper's finite super-triangle loses the thin hull triangle (0, 1, 2): its circumcircle is
// so large that it holds a super vertex. Exact mode keeps it.
TEST(Inserter, SuperModeFlawNearTheHullIsDocumented) {
    // (50, 0.001) sits just above the hull edge (0,0)-(100,0). The sliver (0,0),(100,0),(50,0.001)
    // is Delaunay (its huge circle bulges downward, away from every input point), but that circle
    // swallows the paper's super-triangle's lower vertices, so super mode flips the sliver away
    // and the hull loses its bottom edge: the result is missing a triangle and is not convex.
    const std::vector<Vec2> pts{{0, 0}, {50, 0.001}, {100, 0}, {50, 50}};
    InsertOptions super;
    super.boundary = Boundary::Super;
    Inserter s(pts, super);
    s.run();
    Inserter e(pts);
    e.run();
    EXPECT_EQ(e.mesh().numTriangles(), 3);
    EXPECT_EQ(checkDelaunayExact(e.mesh()), "");
    EXPECT_EQ(s.mesh().numTriangles(), 2);
    EXPECT_NE(checkDelaunayExact(s.mesh()).find("not convex"), std::string::npos)
        << checkDelaunayExact(s.mesh());
    EXPECT_TRUE(validate(s.mesh()).empty());  // still a valid, locally Delaunay corner table
}

TEST(Inserter, RunForTopologyGivesRunsMeshUnderTheCallersNames) {
    // Copies of points (the lowest name must stay, as the lowest index does) and a lattice
    // (cocircular: the very triangles must match, not only the triangulation).
    for (Generator g : {Generator::NearDuplicates, Generator::Grid, Generator::Uniform}) {
        SCOPED_TRACE(toString(g));
        const std::vector<Vec2> pts = generatePoints(g, 3000, 6);
        std::vector<std::int32_t> names(pts.size());
        for (std::size_t i = 0; i < names.size(); ++i) names[i] = 7 + 3 * static_cast<int>(i);
        Inserter whole(pts);
        whole.run();
        Inserter named(pts);
        named.runForTopology(names);
        EXPECT_TRUE(named.mesh().G.empty());
        std::vector<std::int32_t> V = whole.mesh().V;
        for (std::int32_t& v : V) v = names[v];
        EXPECT_EQ(named.mesh().V, V);
        EXPECT_EQ(named.mesh().O, whole.mesh().O);
        std::vector<std::int32_t> skipped = whole.skipped();
        for (std::int32_t& v : skipped) v = names[v];
        EXPECT_EQ(named.skipped(), skipped);
        if (g == Generator::NearDuplicates) {
            EXPECT_FALSE(skipped.empty());
        }
    }
}

TEST(Inserter, RejectsNonFinitePoints) {
    EXPECT_THROW(Inserter({{0, 0}, {NAN, 1}, {1, 1}}), std::invalid_argument);
    EXPECT_THROW(Inserter({{0, 0}, {INFINITY, 1}, {1, 1}}), std::invalid_argument);
}

TEST(Journal, StepByStepEqualsBatchInBothModes) {
    for (const auto& [name, pts] : degenerateSets()) {
        for (Boundary b : {Boundary::Exact, Boundary::Super}) {
            SCOPED_TRACE(name + "/" + toString(b));
            InsertOptions opt;
            opt.boundary = b;
            opt.order = OrderKind::Random;
            Inserter batch(pts, opt);
            batch.run();
            Inserter stepped(pts, opt);
            Journal journal(stepped);
            std::size_t ops = 0;
            while (journal.forward()) ++ops;
            ASSERT_TRUE(stepped.done());
            EXPECT_TRUE(snap(batch.mesh()) == snap(stepped.mesh()));
            EXPECT_EQ(batch.stats().flips, stepped.stats().flips);
            EXPECT_EQ(batch.stats().inCircleTests, stepped.stats().inCircleTests);
            EXPECT_EQ(batch.stats().walkSteps, stepped.stats().walkSteps);
            EXPECT_EQ(journal.recorded(), ops);
        }
    }
}

// The GUI finishes a recorded run in one batch when its history grows too long: run() from any
// point of a stepped run gives the same mesh and statistics as a batch from the start.
TEST(Journal, RunFinishesAStepByStepRunFromAnyPointAsABatchWould) {
    for (const auto& [name, pts] : degenerateSets()) {
        for (Boundary b : {Boundary::Exact, Boundary::Super}) {
            for (OrderKind order : {OrderKind::Random, OrderKind::Input, OrderKind::Brio}) {
                SCOPED_TRACE(name + "/" + toString(b) + "/" +
                             std::to_string(static_cast<int>(order)));
                InsertOptions opt;
                opt.boundary = b;
                opt.order = order;
                Inserter batch(pts, opt);
                batch.run();
                Inserter probe(pts, opt);
                Journal all(probe);
                while (all.forward()) {}
                for (const std::size_t stop : {std::size_t{1}, all.recorded() / 3,
                                               all.recorded() / 2 + 1, all.recorded() - 1}) {
                    Inserter stepped(pts, opt);
                    Journal journal(stepped);
                    journal.seek(stop);
                    stepped.run();
                    ASSERT_TRUE(stepped.done()) << "stopped at " << stop;
                    EXPECT_TRUE(snap(batch.mesh()) == snap(stepped.mesh()))
                        << "stopped at " << stop;
                    EXPECT_EQ(batch.stats().inserted, stepped.stats().inserted);
                    EXPECT_EQ(batch.stats().duplicates, stepped.stats().duplicates);
                    EXPECT_EQ(batch.stats().flips, stepped.stats().flips);
                }
            }
        }
    }
    // And a larger random set in random order (long walks), checked exactly.
    const std::vector<Vec2> pts = generatePoints(Generator::Uniform, 3000, 9);
    InsertOptions opt;
    opt.order = OrderKind::Random;
    Inserter stepped(pts, opt);
    Journal journal(stepped);
    journal.seek(20000);
    stepped.run();
    ASSERT_TRUE(stepped.done());
    EXPECT_EQ(stepped.mesh().numVertices(), 3000);
    EXPECT_TRUE(validate(stepped.mesh()).empty());
    EXPECT_EQ(checkDelaunayExact(stepped.mesh()), "");
}

TEST(Journal, ForwardToEndAndBackRestoresTheEmptyStateBitForBit) {
    for (Boundary b : {Boundary::Exact, Boundary::Super}) {
        const auto pts = generatePoints(Generator::NearDuplicates, 200, 11);
        InsertOptions opt;
        opt.boundary = b;
        opt.locator = LocatorKind::IdBufferCpu;
        Inserter ins(pts, opt);
        const Snapshot empty = snap(ins.mesh());
        Journal journal(ins);
        std::vector<Snapshot> states{empty};
        std::vector<InsertStats> stats{ins.stats()};
        std::vector<Control> controls{ins.control()};
        std::vector<std::vector<std::int32_t>> stacks{ins.flipStack()}, skipped{ins.skipped()};
        while (journal.forward()) {
            states.push_back(snap(ins.mesh()));
            stats.push_back(ins.stats());
            controls.push_back(ins.control());
            stacks.push_back(ins.flipStack());
            skipped.push_back(ins.skipped());
        }
        ASSERT_GT(stats.back().duplicates, 0);
        const std::size_t total = journal.position();
        // Random seeks compare with the state recorded on the way forward.
        SplitMix64 rng(5);
        for (int k = 0; k < 300; ++k) {
            const std::size_t target = rng.below(static_cast<std::uint32_t>(total + 1));
            journal.seek(target);
            ASSERT_EQ(journal.position(), target);
            ASSERT_TRUE(states[target] == snap(ins.mesh())) << "after seeking to " << target;
            ASSERT_EQ(stats[target].flips, ins.stats().flips);
            ASSERT_EQ(stats[target].duplicates, ins.stats().duplicates);
            ASSERT_TRUE(sameControl(controls[target], ins.control())) << "at op " << target;
            ASSERT_EQ(stacks[target], ins.flipStack()) << "at op " << target;
            ASSERT_EQ(skipped[target], ins.skipped()) << "at op " << target;
            // Every intermediate state is a valid corner table (ghost/super triangles included).
            ValidateOptions vo;
            vo.firstVirtual = static_cast<std::int32_t>(pts.size());
            vo.delaunay = false;
            const auto v = validate(ins.mesh(), vo);
            ASSERT_TRUE(v.empty()) << v[0].message << " at op " << target;
        }
        journal.seek(0);
        EXPECT_TRUE(empty == snap(ins.mesh()));
        EXPECT_TRUE(ins.flipStack().empty());
        // And forward again to the same end.
        journal.seek(total);
        EXPECT_TRUE(states.back() == snap(ins.mesh()));
        EXPECT_TRUE(ins.done());
    }
}

// Stepped back op by op (no bulk repaint) and forward again, the CPU ID buffer holds what
// painting the current mesh afresh holds: kNone outside the hull (where ghost triangles are), a
// live real triangle inside. A pixel centre on an edge may name either of two triangles, so any
// live real id counts there.
TEST(Journal, IdBufferStepByStepMatchesAFreshPaintOfTheMesh) {
    for (Generator g : {Generator::Uniform, Generator::Gaussian, Generator::NearDuplicates}) {
        InsertOptions opt;
        opt.boundary = Boundary::Exact;
        opt.locator = LocatorKind::IdBufferCpu;
        Inserter ins(generatePoints(g, 300, 4), opt);
        Journal journal(ins);
        while (journal.forward()) {}
        auto* buffer = dynamic_cast<IdBufferCpu*>(ins.locator());
        ASSERT_NE(buffer, nullptr);
        auto live = [&](std::int32_t t) {
            return t != kNone && t < ins.mesh().numTriangles() && !ins.isVirtualTriangle(t);
        };
        // Every 37th position on the way back, then on the way forward again.
        auto check = [&] {
            const std::vector<std::int32_t> stepped = buffer->pixels();
            buffer->resync();
            const std::vector<std::int32_t>& fresh = buffer->pixels();
            for (std::size_t i = 0; i < fresh.size(); ++i) {
                if (fresh[i] == kNone) {
                    ASSERT_EQ(stepped[i], kNone) << "pixel " << i << " at op " << journal.position()
                                                 << " holds t" << stepped[i] << " outside the hull";
                } else {
                    ASSERT_TRUE(live(stepped[i])) << "pixel " << i << " at op "
                                                  << journal.position() << " holds " << stepped[i];
                }
            }
        };
        while (journal.back()) {
            if (journal.position() % 37 == 0) {
                ASSERT_NO_FATAL_FAILURE(check());
            }
        }
        while (journal.forward()) {
            if (journal.position() % 37 == 0) {
                ASSERT_NO_FATAL_FAILURE(check());
            }
        }
        // A long seek back to the start repaints once; the steps forward from there repaint
        // only what they change.
        journal.seek(0);
        for (int k = 0; k < 100 && journal.forward(); ++k) {}
        ASSERT_NO_FATAL_FAILURE(check());
    }
}

TEST(Journal, ControlStateBeforeEveryOpIsRecoveredExactly) {
    for (Generator g : {Generator::Uniform, Generator::NearDuplicates, Generator::Grid}) {
        Inserter ins(generatePoints(g, 300, 3));
        Journal journal(ins);
        std::vector<Control> before;
        while (!ins.done()) {
            before.push_back(ins.control());
            journal.forward();
        }
        ASSERT_EQ(before.size(), journal.recorded());
        for (std::size_t i = 0; i < before.size(); ++i) {
            ASSERT_TRUE(sameControl(before[i], journal.controlBefore(i)))
                << "op " << i << " " << toString(journal.ops()[i].type);
        }
        // Snapshots only where the control state cannot be derived: far fewer than ops.
        EXPECT_LT(journal.controlSnapshots() * 2, journal.recorded());
    }
}

// README, Limits: "about N bytes per recorded operation" for 2^14 uniform points.
TEST(Journal, BytesPerRecordedOperationMatchTheReadme) {
    Inserter ins(generatePoints(Generator::Uniform, 1 << 14, 1));
    Journal journal(ins);
    while (journal.forward()) {}
    const double perOp = static_cast<double>(journal.bytesUsed()) / journal.recorded();
    std::ifstream readme(std::string(DLAB_SOURCE_DIR) + "/README.md");
    std::stringstream text;
    text << readme.rdbuf();
    const std::string s = text.str();
    const std::string key = " bytes per recorded operation";
    const std::size_t at = s.find(key);
    ASSERT_NE(at, std::string::npos) << "README.md states no history size";
    std::size_t start = at;
    while (start > 0 && std::isdigit(static_cast<unsigned char>(s[start - 1]))) --start;
    ASSERT_LT(start, at) << "no number before \"" << key << "\"";
    const int claimed = std::stoi(s.substr(start, at - start));
    EXPECT_NEAR(perOp, claimed, 1.0) << "README says " << claimed;
    EXPECT_LE(sizeof(Op), 44u);
}

TEST(Inserter, StraightWalkReachesEveryPointWithoutFallingBack) {
    // Points in general position on a Delaunay mesh: the line walk from the centroid of the hint
    // finds each point without the visibility-walk fallback, and a walk step never stays put.
    Inserter ins(generatePoints(Generator::Uniform, 3000, 8));
    Journal journal(ins);
    std::int64_t steps = 0, fallbacks = 0;
    while (const Op* op = journal.forward()) {
        if (op->type != OpType::LocateStep) continue;
        ++steps;
        fallbacks += !ins.control().walk.straight;
        EXPECT_NE(op->a, op->b);
    }
    EXPECT_GT(steps, 3000);
    EXPECT_EQ(fallbacks, 0);
}

TEST(Journal, UndoThenNewStepsContinueCorrectly) {
    // Step back into the middle of the recorded run, then go past the recorded end.
    const auto pts = generatePoints(Generator::Uniform, 60, 2);
    Inserter ref(pts);
    ref.run();
    Inserter ins(pts);
    Journal journal(ins);
    for (int i = 0; i < 200; ++i) journal.forward();
    journal.seek(120);
    while (journal.forward()) {}
    EXPECT_TRUE(snap(ref.mesh()) == snap(ins.mesh()));
}

TEST(Journal, EveryOpRecordsTheCellsItChanged) {
    const auto pts = generatePoints(Generator::Uniform, 80, 4);
    Inserter ins(pts);
    Journal journal(ins);
    Snapshot before = snap(ins.mesh());
    std::map<OpType, int> seen;
    while (const Op* op = journal.forward()) {
        ++seen[op->type];
        const Snapshot after = snap(ins.mesh());
        // Apply the recorded changes to the old state: must give the new state exactly.
        Snapshot rebuilt = before;
        const std::size_t n =
            3 * static_cast<std::size_t>(std::max(op->trianglesBefore, op->trianglesAfter));
        rebuilt.V.resize(n, kNone);
        rebuilt.O.resize(n, kNone);
        for (std::uint32_t i = 0; i < op->numChanges; ++i) {
            const CellChange& c = journal.changes()[op->firstChange + i];
            auto& table = c.isO() ? rebuilt.O : rebuilt.V;
            if (c.corner() < op->trianglesBefore * 3) {
                ASSERT_EQ(table[c.corner()], c.before);
            }
            table[c.corner()] = c.after;
        }
        rebuilt.V.resize(3 * op->trianglesAfter);
        rebuilt.O.resize(3 * op->trianglesAfter);
        rebuilt.G = after.G;
        ASSERT_TRUE(rebuilt == after) << toString(op->type) << " at " << journal.position();
        if (op->type == OpType::Flip) {
            EXPECT_LE(op->numChanges, 8u);
        }  // 6 corners + 2 back-pointers
        if (op->type == OpType::Split) {
            EXPECT_EQ(op->trianglesAfter, op->trianglesBefore + 2);
        }
        before = after;
    }
    EXPECT_GT(seen[OpType::Flip], 0);
    EXPECT_GT(seen[OpType::InCircleTest], seen[OpType::Flip]);
    EXPECT_EQ(seen[OpType::Finalize], 1);
}

// The flip-stack pushes of every op are in the record, in order, and are exactly what the op
// put on the stack: a split's three new edges, an edge split's two or four, a flip's two. Undo
// and redo move the stack by them (ForwardToEndAndBack... checks the stacks after seeks).
TEST(Journal, EveryOpRecordsTheFlipStackPushesItMade) {
    for (Generator g : {Generator::Uniform, Generator::Grid, Generator::Collinear}) {
        for (Boundary b : {Boundary::Exact, Boundary::Super}) {
            InsertOptions opt;
            opt.boundary = b;
            Inserter ins(generatePoints(g, 300, 6), opt);
            Journal journal(ins);
            std::map<int, int> edgeSplitPushes;
            std::size_t at = 0;
            std::vector<std::int32_t> before = ins.flipStack();
            while (const Op* op = journal.forward()) {
                std::vector<std::int32_t> expected = before;
                if (op->type == OpType::InCircleTest) {
                    ASSERT_EQ(expected.back(), op->a);
                    expected.pop_back();
                }
                const auto& pushes = journal.pushes();
                ASSERT_LE(at + pushCount(*op), pushes.size());
                expected.insert(expected.end(), pushes.begin() + static_cast<std::ptrdiff_t>(at),
                                pushes.begin() + static_cast<std::ptrdiff_t>(at + pushCount(*op)));
                at += pushCount(*op);
                ASSERT_EQ(expected, ins.flipStack())
                    << toString(op->type) << " at " << journal.position();
                switch (op->type) {
                    case OpType::Split: ASSERT_EQ(op->pushes, 3); break;
                    case OpType::SplitEdge: ++edgeSplitPushes[op->pushes]; break;
                    case OpType::Flip: ASSERT_EQ(op->pushes, 2); break;
                    default: ASSERT_EQ(op->pushes, 0) << toString(op->type);
                }
                before = ins.flipStack();
            }
            EXPECT_EQ(at, journal.pushes().size());
            for (const auto& [count, times] : edgeSplitPushes) {
                EXPECT_TRUE(count == 2 || count == 4) << count;
            }
            if (g == Generator::Grid) {
                EXPECT_GT(edgeSplitPushes[4], 0);
            }
        }
    }
}

TEST(Journal, PointOnEdgeSplitsTwoIntoFour) {
    // (0.5, 0.5) lies on the diagonal of the square; (1, 0.5) on its hull edge.
    const std::vector<Vec2> pts{{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}, {1, 0.5}};
    InsertOptions opt;
    opt.order = OrderKind::Input;
    Inserter ins(pts, opt);
    Journal journal(ins);
    int edgeSplits = 0;
    while (const Op* op = journal.forward()) {
        if (op->type == OpType::SplitEdge) {
            ++edgeSplits;
            EXPECT_EQ(op->trianglesAfter, op->trianglesBefore + 2);
        }
    }
    EXPECT_GE(edgeSplits, 1);
    EXPECT_EQ(checkDelaunayExact(ins.mesh()), "");
    EXPECT_EQ(ins.mesh().numTriangles(), 5);  // 2n - h - 2 = 12 - 5 - 2
}

TEST(Trace, RoundTripsThroughJsonLines) {
    const auto pts = generatePoints(Generator::NearDuplicates, 40, 9);
    Inserter ins(pts);
    Journal journal(ins);
    std::vector<TraceRecord> records;
    std::string text;
    while (journal.forward()) {
        records.push_back(traceRecord(journal, journal.position() - 1, ins.mesh()));
        text += toJsonLine(records.back()) + "\n";
    }
    std::istringstream in(text);
    const auto back = readTrace(in, "mem.jsonl");
    ASSERT_EQ(back.size(), records.size());
    for (std::size_t i = 0; i < back.size(); ++i)
        ASSERT_TRUE(back[i] == records[i]) << "record " << i;
    std::istringstream bad("{\"i\":0,\"op\":\"Teleport\"}\n");
    try {
        readTrace(bad, "bad.jsonl");
        FAIL() << "expected an error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("bad.jsonl:1:"), std::string::npos) << e.what();
    }
}

TEST(Locators, IdBufferCpuHintsAreUsuallyRight) {
    InsertOptions opt;
    opt.locator = LocatorKind::IdBufferCpu;
    opt.order = OrderKind::Random;
    opt.locatorOptions.idBufferWidth = opt.locatorOptions.idBufferHeight = 512;
    Inserter ins(generatePoints(Generator::Uniform, 5000, 3), opt);
    ins.run();
    const auto& s = ins.locator()->stats();
    EXPECT_EQ(s.queries, 5000u - 3u);
    EXPECT_GT(static_cast<double>(s.hits) / s.queries, 0.8);
}

TEST(Locators, BrioWalkIsShort) {
    Inserter ins(generatePoints(Generator::Uniform, 20000, 3));
    ins.run();
    EXPECT_LT(static_cast<double>(ins.stats().walkSteps) / 20000, 4.0);
    EXPECT_LT(static_cast<double>(ins.stats().flips) / 20000, 4.0);
}

TEST(Journal, StopsRecordingAtItsMemoryBudget) {
    // Input order on a lattice walks far: a small budget is reached long before the end.
    const auto pts = generatePoints(Generator::Grid, 2500, 1);
    InsertOptions o;
    o.order = OrderKind::Input;
    Inserter ins(pts, o);
    Journal journal(ins);
    journal.setBudget(std::size_t{1} << 20);
    while (journal.forward()) {}
    EXPECT_TRUE(journal.budgetReached());
    EXPECT_FALSE(ins.done());
    EXPECT_LE(journal.memoryBytes(), journal.budget());
    EXPECT_GT(journal.memoryBytes(), journal.budget() / 4);  // it did use the room it had
    // Undo still works over what was recorded, and the run can go on unrecorded.
    const std::size_t recorded = journal.recorded();
    journal.seek(recorded / 2);
    EXPECT_EQ(journal.position(), recorded / 2);
    journal.seek(recorded);
    while (!ins.done()) ins.step(nullptr);
    EXPECT_EQ(checkDelaunayExact(ins.mesh()), "");
    // The default budget is the documented one.
    Journal fresh(ins);
    EXPECT_EQ(fresh.budget(), kHistoryBudgetBytes);
    EXPECT_EQ(kHistoryBudgetBytes, std::size_t{1} << 30);
}

TEST(Inserter, RefusesMorePointsThanTheReadersAccept) {
    std::vector<Vec2> pts(kMaxPoints + 1);
    try {
        Inserter ins(std::move(pts));
        ADD_FAILURE() << "accepted kMaxPoints + 1 points";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find(std::to_string(kMaxPoints)), std::string::npos);
    }
}
