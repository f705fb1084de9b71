// The predicate calls of each operation: what Journal::predicateCallsOf gives for an op, after
// stepping back and forth, equals what the inserter made while it made the op (every locator
// without GL, both boundary modes, degenerate sets), and a line-walk step makes the two tests of
// the paper's walk.
#include "core/engine/generators.h"
#include "core/engine/inserter.h"
#include "core/engine/predicates.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <vector>

using namespace dlab;

namespace {

using Calls = std::vector<RecordedPredicateCall>;

std::string show(const Calls& calls) {
    std::string s;
    for (const auto& c : calls) {
        s += "  " + std::string(toString(c.ask)) + " sign " + std::to_string(c.sign) + " corner " +
             std::to_string(c.corner) + ": " + describe(c) + "\n";
    }
    return s;
}

// A run made op by op with the calls of each op captured as it is made.
struct CapturedRun {
    std::unique_ptr<Inserter> ins;
    std::unique_ptr<Journal> journal;
    std::vector<Calls> made;  // per op
};

CapturedRun capture(const std::vector<Vec2>& pts, const InsertOptions& opt) {
    CapturedRun run;
    run.ins = std::make_unique<Inserter>(pts, opt);
    run.journal = std::make_unique<Journal>(*run.ins);
    while (!run.ins->done()) {
        Calls calls;
        run.ins->step(run.journal.get(), &calls);
        run.made.push_back(std::move(calls));
    }
    return run;
}

// The journal's calls for the op just done and the next one equal the captured ones.
void expectCallsAtPosition(const CapturedRun& run, const std::string& label) {
    const Journal& j = *run.journal;
    const std::size_t pos = j.position();
    for (std::size_t i : {pos - 1, pos}) {
        if (i >= j.recorded()) continue;  // pos - 1 wraps at 0
        const Calls got = j.predicateCallsOf(i);
        ASSERT_TRUE(got == run.made[i])
            << label << ": op " << i << " (" << toString(j.ops()[i].type) << ") at position " << pos
            << "\nmade:\n"
            << show(run.made[i]) << "given:\n"
            << show(got);
    }
}

// What the op's calls must agree with: the in-circle test's sign is its one call's.
void expectCallsMatchTheOp(const Op& op, const Calls& calls, const std::string& label) {
    for (const auto& c : calls) {
        ASSERT_TRUE(c.inCircle() ? incircle(c.p[0], c.p[1], c.p[2], c.p[3]) == c.sign
                                 : orient2d(c.p[0], c.p[1], c.p[2]) == c.sign)
            << label;
    }
    switch (op.type) {
        case OpType::InCircleTest:
            if (op.b == kNone) {
                ASSERT_TRUE(calls.empty()) << label << ": a boundary edge needs no test";
                break;
            }
            ASSERT_EQ(calls.size(), 1u) << label;
            ASSERT_EQ(calls[0].corner, op.a) << label;
            if (calls[0].ask == PredicateAsk::InCircle) {
                ASSERT_EQ(calls[0].sign, op.sign) << label;
            } else {
                ASSERT_EQ(calls[0].ask, PredicateAsk::GhostCircle) << label;
                ASSERT_EQ(calls[0].sign > 0, op.sign > 0) << label;
            }
            break;
        case OpType::LocateStep:
        case OpType::Located: ASSERT_FALSE(calls.empty()) << label; break;
        case OpType::Start: ASSERT_LE(calls.size(), 1u) << label; break;
        default: ASSERT_TRUE(calls.empty()) << label << ": " << toString(op.type); break;
    }
}

void checkRun(const std::vector<Vec2>& pts, const InsertOptions& opt, const std::string& label) {
    SCOPED_TRACE(label);
    CapturedRun run = capture(pts, opt);
    Journal& j = *run.journal;
    ASSERT_EQ(run.made.size(), j.recorded());
    for (std::size_t i = 0; i < j.recorded(); ++i)
        ASSERT_NO_FATAL_FAILURE(expectCallsMatchTheOp(j.ops()[i], run.made[i], label));
    // Back to the start one op at a time, forward again, then random jumps (long ones in bulk).
    do {
        ASSERT_NO_FATAL_FAILURE(expectCallsAtPosition(run, label + " back"));
    } while (j.back());
    while (j.forward()) ASSERT_NO_FATAL_FAILURE(expectCallsAtPosition(run, label + " forward"));
    std::mt19937_64 rng(7);
    for (int k = 0; k < 40; ++k) {
        j.seek(std::uniform_int_distribution<std::size_t>(0, j.recorded())(rng));
        ASSERT_NO_FATAL_FAILURE(expectCallsAtPosition(run, label + " seek"));
    }
}

std::vector<std::pair<std::string, std::vector<Vec2>>> sets() {
    std::vector<std::pair<std::string, std::vector<Vec2>>> s = {
        {"uniform", generatePoints(Generator::Uniform, 120, 3)},
        {"collinear", generatePoints(Generator::Collinear, 100, 3)},
        {"all-collinear", generatePoints(Generator::AllCollinear, 20, 3)},
        {"near-duplicates", generatePoints(Generator::NearDuplicates, 100, 3)},
        {"lattice", generatePoints(Generator::Grid, 100, 3)},
        {"ngon", generatePoints(Generator::Ngon, 40, 3)},
        {"circle", generatePoints(Generator::Circle, 60, 3)},
        {"demo", demoPoints()},
    };
    // Exact duplicates, and points on the hull edges and on the first triangle's edges.
    s.push_back({"duplicates",
                 {{0, 0},
                  {4, 0},
                  {0, 4},
                  {0, 0},
                  {4, 0},
                  {2, 0},
                  {2, 2},
                  {2, 2},
                  {4, 4},
                  {0, 2},
                  {1, 1},
                  {1, 1},
                  {8, 0},
                  {-4, 0},
                  {0, 4}}});
    return s;
}

}  // namespace

TEST(PredicateCalls, EveryOpGivesTheCallsItMadeInEveryLocatorAndBoundaryMode) {
    for (const auto& [name, pts] : sets()) {
        for (Boundary boundary : {Boundary::Exact, Boundary::Super}) {
            for (LocatorKind loc : {LocatorKind::Naive, LocatorKind::Walk, LocatorKind::Grid,
                                    LocatorKind::IdBufferCpu}) {
                for (OrderKind order : {OrderKind::Brio, OrderKind::Input}) {
                    InsertOptions opt;
                    opt.boundary = boundary;
                    opt.locator = loc;
                    opt.order = order;
                    opt.locatorOptions.idBufferWidth = opt.locatorOptions.idBufferHeight = 64;
                    checkRun(pts, opt,
                             name + "/" + toString(boundary) + "/" + toString(loc) + "/" +
                                 toString(order));
                    if (HasFatalFailure()) return;
                }
            }
        }
    }
}

TEST(PredicateCalls, OnlyTheCurrentAndTheNextOpCanBeAsked) {
    Inserter ins(demoPoints());
    Journal j(ins);
    for (int k = 0; k < 30; ++k) j.forward();
    EXPECT_NO_THROW(j.predicateCallsOf(29));
    EXPECT_THROW(j.predicateCallsOf(28), std::out_of_range);
    EXPECT_THROW(j.predicateCallsOf(30), std::out_of_range);  // not recorded yet
    j.seek(10);
    EXPECT_NO_THROW(j.predicateCallsOf(9));
    EXPECT_NO_THROW(j.predicateCallsOf(10));
    EXPECT_THROW(j.predicateCallsOf(11), std::out_of_range);
    j.seek(0);
    EXPECT_NO_THROW(j.predicateCallsOf(0));
}

// The paper's line walk: a step into a triangle through an edge asks which side of L the third
// vertex lies on, then whether p is beyond the one edge L leaves through: two orientation tests,
// never the three edge tests of a visibility walk. The first step of each walk tests the start
// triangle's centroid q (three), L against its vertices (two or three) and the exit edge (one).
TEST(PredicateCalls, ALineWalkStepMakesTheTwoTestsOfTheStraightWalk) {
    Inserter ins(generatePoints(Generator::Uniform, 3000, 8));
    Journal j(ins);
    std::int64_t steps = 0, starts = 0, ghosts = 0, needles = 0;
    while (!ins.done()) {
        const Control before = ins.control();
        Calls calls;
        const Op op = ins.step(&j, &calls);
        if (op.type != OpType::LocateStep && op.type != OpType::Located) continue;
        ASSERT_TRUE(before.walk.straight);
        const Mesh& m = ins.mesh();
        const std::string label = "op " + std::to_string(j.recorded() - 1) + "\n" + show(calls);
        ASSERT_FALSE(calls.empty()) << label;
        for (const auto& c : calls) EXPECT_NE(c.ask, PredicateAsk::VisibilityEdge) << label;
        if (calls[0].ask == PredicateAsk::HullEdge) {
            // In a ghost triangle: p against its hull edge, which also places p when beyond it.
            ++ghosts;
            EXPECT_EQ(calls.size(), 1u) << label;
        } else if (before.walk.tri != kNone && before.walk.entry != kNone) {
            ++steps;
            // Entered through the edge opposite `entry`: L against the vertex at entry.
            ASSERT_GE(calls.size(), 2u) << label;
            ASSERT_EQ(calls[0].ask, PredicateAsk::LineSide) << label;
            EXPECT_EQ(std::memcmp(&calls[0].p[0], &before.walk.origin, sizeof(Vec2)), 0) << label;
            EXPECT_EQ(calls[0].v[1], op.vertex) << label;
            EXPECT_EQ(calls[0].v[2], m.V[before.walk.entry]) << label;
            ASSERT_EQ(calls[1].ask, PredicateAsk::ExitEdge) << label;
            EXPECT_EQ(calls[1].v[2], op.vertex) << label;
            const std::int32_t exit = calls[1].corner;
            EXPECT_EQ(exit, calls[0].sign >= 0 ? next(before.walk.entry) : prev(before.walk.entry))
                << label;
            if (op.type == OpType::LocateStep) {
                EXPECT_EQ(calls.size(), 2u) << label;
                EXPECT_LT(calls[1].sign, 0) << label;
                EXPECT_EQ(op.b, tri(m.O[exit])) << label;
            } else {
                // Inside: the entry edge is known, the exit edge tested, the third one left.
                ASSERT_EQ(calls.size(), 3u) << label;
                EXPECT_EQ(calls[2].ask, PredicateAsk::ClassifyEdge) << label;
            }
        } else {
            // The start: is the centroid q strictly inside (the tests stop at the first no)?
            std::size_t k = 0;
            bool inside = true;
            for (; k < calls.size() && calls[k].ask == PredicateAsk::StartCentroid; ++k)
                inside = inside && calls[k].sign > 0;
            if (!inside) {
                ++needles;  // the visibility tests decide
                continue;
            }
            ++starts;
            ASSERT_EQ(k, 3u) << label;
            while (k < calls.size() && calls[k].ask == PredicateAsk::LineSide) ++k;
            EXPECT_TRUE(k == 5 || k == 6) << label;
            ASSERT_LT(k, calls.size()) << label;
            EXPECT_EQ(calls[k].ask, PredicateAsk::ExitEdge) << label;
            EXPECT_EQ(calls.size(), op.type == OpType::LocateStep ? k + 1 : k + 3) << label;
        }
    }
    EXPECT_LT(needles * 100, starts);
    EXPECT_GT(ghosts, 0);
    EXPECT_GT(steps, 3000);
    EXPECT_GT(starts, 500);
}
