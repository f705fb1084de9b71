// Breakpoints: text round trips, every kind stops exactly where its definition says (checked
// against the recorded ops and against mesh snapshots), budgets, and running back restores state.
#include "core/engine/generators.h"
#include "core/teaching/breakpoint.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

using namespace dlab;

namespace {

// A point on an edge (2 on 0-1), a duplicate (11 = 4), cocircular quadruples (the unit square
// corners 12..15 around the circle through them) and ordinary flips.
std::vector<Vec2> testPoints() {
    std::vector<Vec2> pts = demoPoints();
    pts.insert(pts.end(), {{800, 800}, {900, 800}, {900, 900}, {800, 900}});
    return pts;
}

struct Cells {
    std::vector<std::int32_t> V, O;
    std::int32_t v(std::size_t c) const { return c < V.size() ? V[c] : kNone; }
    std::int32_t o(std::size_t c) const { return c < O.size() ? O[c] : kNone; }
    friend bool operator==(const Cells&, const Cells&) = default;
};

// Runs the whole journal once and keeps the cells at every position.
struct Recorded {
    InsertOptions options;
    std::vector<Cells> at;  // at[p] = cells after p ops
    std::size_t total = 0;
};

Recorded record(const std::vector<Vec2>& pts, const InsertOptions& opt) {
    Inserter ins(pts, opt);
    Journal j(ins);
    Recorded r{opt, {}, 0};
    r.at.push_back({ins.mesh().V, ins.mesh().O});
    while (j.forward()) r.at.push_back({ins.mesh().V, ins.mesh().O});
    r.total = j.position();
    return r;
}

// Every position where running forward with `bp` from the start stops.
std::vector<std::size_t> stopsForward(Inserter& ins, Journal& j, const Breakpoint& bp) {
    std::vector<std::size_t> stops;
    j.seek(0);
    while (true) {
        const RunResult r = runUntil(j, ins, std::span(&bp, 1), 1u << 30);
        if (r.reason != StopReason::Hit) break;
        stops.push_back(j.position());
    }
    return stops;
}

std::vector<std::size_t> positionsWhere(const Journal& j, auto pred) {
    std::vector<std::size_t> out;
    for (std::size_t p = 1; p <= j.recorded(); ++p) {
        if (pred(j.ops()[p - 1], p)) out.push_back(p);
    }
    return out;
}

Breakpoint bp(const char* text) {
    std::string error;
    auto b = parseBreakpoint(text, &error);
    EXPECT_TRUE(b) << text << ": " << error;
    return b.value_or(Breakpoint{});
}

}  // namespace

TEST(Breakpoint, TextRoundTripsForEveryKind) {
    for (const BreakKindInfo& k : breakKinds()) {
        EXPECT_EQ(&info(k.kind), &k);
        Breakpoint b{k.kind, std::nullopt};
        const bool sign = k.kind == BreakKind::InCircle || k.kind == BreakKind::EarTest ||
                          k.kind == BreakKind::EditInCircle;
        if (k.param != BreakParam::None) b.param = sign ? -1 : 17;
        const std::string text = toString(b);
        std::string error;
        const auto back = parseBreakpoint(text, &error);
        ASSERT_TRUE(back) << text << ": " << error;
        EXPECT_EQ(*back, b) << text;
        EXPECT_FALSE(explain(b).empty());
    }
    EXPECT_EQ(toString(bp("  Insert : 5 ")), "insert:5");
    EXPECT_EQ(toString(bp("incircle:+1")), "incircle:1");
    EXPECT_EQ(explain(bp("insert:5")), "vertex 5 is about to be inserted");
}

TEST(Breakpoint, ParseErrorsSayWhy) {
    struct Case {
        const char* text;
        const char* says;
    };
    for (const Case& c :
         {Case{"flop", "unknown breakpoint \"flop\""}, Case{"", "unknown breakpoint"},
          Case{"op", "needs a number"}, Case{"corner", "needs a number"},
          Case{"flip:3", "takes no number"}, Case{"insert:-2", "cannot be negative"},
          Case{"op:12x", "not a whole number"}, Case{"op:", "not a whole number"},
          Case{"incircle:2", "1, 0 or -1"},
          Case{"op:99999999999999999999", "not a whole number"}}) {
        std::string error;
        EXPECT_FALSE(parseBreakpoint(c.text, &error)) << c.text;
        EXPECT_NE(error.find(c.says), std::string::npos) << c.text << " -> " << error;
    }
    EXPECT_FALSE(parseBreakpoint("flop"));  // no error string wanted: still no crash
}

TEST(Breakpoint, OpTypeKindsStopExactlyAtTheirOps) {
    for (Boundary b : {Boundary::Exact, Boundary::Super}) {
        SCOPED_TRACE(toString(b));
        InsertOptions opt;
        opt.boundary = b;
        opt.order = OrderKind::Input;
        Inserter ins(testPoints(), opt);
        Journal j(ins);
        j.seek(1u << 30);
        const auto of = [&](OpType t) {
            return positionsWhere(j, [t](const Op& op, std::size_t) { return op.type == t; });
        };
        EXPECT_EQ(stopsForward(ins, j, bp("flip")), of(OpType::Flip));
        EXPECT_EQ(stopsForward(ins, j, bp("split")), of(OpType::Split));
        EXPECT_EQ(stopsForward(ins, j, bp("split-edge")), of(OpType::SplitEdge));
        EXPECT_EQ(stopsForward(ins, j, bp("walk")), of(OpType::LocateStep));
        EXPECT_EQ(stopsForward(ins, j, bp("located")), of(OpType::Located));
        EXPECT_EQ(stopsForward(ins, j, bp("incircle")), of(OpType::InCircleTest));
        EXPECT_EQ(stopsForward(ins, j, bp("duplicate")), of(OpType::SkipDuplicate));
        EXPECT_EQ(stopsForward(ins, j, bp("finalize")), std::vector<std::size_t>{j.recorded()});
        EXPECT_EQ(stopsForward(ins, j, bp("end")), std::vector<std::size_t>{j.recorded()});
        EXPECT_EQ(stopsForward(ins, j, bp("step")).size(), j.recorded());
        EXPECT_FALSE(of(OpType::Flip).empty());
        EXPECT_FALSE(of(OpType::SplitEdge).empty());
        EXPECT_FALSE(of(OpType::SkipDuplicate).empty());
        // Sign-filtered in-circle tests partition the tests.
        const auto pos = stopsForward(ins, j, bp("incircle:1")),
                   zero = stopsForward(ins, j, bp("incircle:0")),
                   neg = stopsForward(ins, j, bp("incircle:-1"));
        EXPECT_EQ(pos.size() + zero.size() + neg.size(), of(OpType::InCircleTest).size());
        for (std::size_t p : pos)
            EXPECT_EQ(j.ops()[p].type, OpType::Flip) << "a positive test is followed by its flip";
        EXPECT_EQ(pos.size(), of(OpType::Flip).size());
    }
}

TEST(Breakpoint, DegenerateStopsOnEdgePointsDuplicatesAndCocircularTests) {
    InsertOptions opt;
    opt.order = OrderKind::Input;
    Inserter ins(testPoints(), opt);
    Journal j(ins);
    const auto stops = stopsForward(ins, j, bp("degenerate"));
    std::size_t onEdge = 0, onVertex = 0, cocircular = 0;
    for (std::size_t p : stops) {
        const Op& op = j.ops()[p - 1];
        if (op.type == OpType::Located && op.where == Where::OnEdge) {
            ++onEdge;
            EXPECT_EQ(j.ops()[p].type, OpType::SplitEdge);
        } else if (op.type == OpType::Located && op.where == Where::OnVertex) {
            ++onVertex;
            EXPECT_EQ(j.ops()[p].type, OpType::SkipDuplicate);
        } else {
            ASSERT_EQ(op.type, OpType::InCircleTest) << "position " << p;
            EXPECT_EQ(op.sign, 0);
            ++cocircular;
        }
    }
    EXPECT_EQ(static_cast<std::int64_t>(onEdge), ins.stats().edgeSplits);
    EXPECT_EQ(static_cast<std::int64_t>(onVertex), ins.stats().duplicates);
    EXPECT_EQ(onVertex, 1u);    // 11 duplicates 4
    EXPECT_GE(onEdge, 1u);      // 2 lies on 0-1
    EXPECT_GE(cocircular, 1u);  // the square 12..15
}

TEST(Breakpoint, InsertStopsJustBeforeTheVertexFirstOpAndInsertedWhenItAppears) {
    for (Boundary b : {Boundary::Exact, Boundary::Super}) {
        SCOPED_TRACE(toString(b));
        InsertOptions opt;
        opt.boundary = b;
        opt.order = OrderKind::Random;
        opt.seed = 3;
        const auto pts = testPoints();
        Inserter ins(pts, opt);
        Journal j(ins);
        const Recorded rec = record(pts, opt);
        for (std::int32_t v = 0; v < static_cast<std::int32_t>(pts.size()); ++v) {
            SCOPED_TRACE("vertex " + std::to_string(v));
            // inserted:v stops once, at the op that ends v's turn: Start (exact mode's first
            // triangle), its Inserted, or its SkipDuplicate (a duplicate of a vertex already in).
            const auto in = stopsForward(ins, j, Breakpoint{BreakKind::Inserted, v});
            ASSERT_EQ(in.size(), 1u);
            const Op& last = j.ops()[in[0] - 1];
            const OpType t = last.type;
            const auto inV = [&](std::size_t p) {
                return std::count(rec.at[p].V.begin(), rec.at[p].V.end(), v) > 0;
            };
            if (t == OpType::Start) {
                EXPECT_EQ(b, Boundary::Exact);
                EXPECT_EQ(in[0], 1u);
                EXPECT_TRUE(inV(1));
            } else {
                ASSERT_TRUE(t == OpType::Inserted || t == OpType::SkipDuplicate) << toString(t);
                EXPECT_EQ(last.vertex, v);
                // Its ops run back to the previous insertion's end; v is in V at the stop
                // unless it duplicates an earlier-index vertex.
                std::size_t first = in[0] - 1;
                while (j.ops()[first - 1].vertex == v) --first;
                EXPECT_FALSE(inV(first));
                const bool keptOther = t == OpType::SkipDuplicate && last.b < v;
                EXPECT_EQ(inV(in[0]), !keptOther);
            }

            // insert:v stops right before v's first operation (never, for Start's vertices).
            const auto before = stopsForward(ins, j, Breakpoint{BreakKind::Insert, v});
            if (t == OpType::Start) {
                EXPECT_TRUE(before.empty());
                continue;
            }
            ASSERT_EQ(before.size(), 1u);
            EXPECT_NE(j.ops()[before[0] - 1].vertex, v);
            EXPECT_EQ(j.ops()[before[0]].vertex, v);
            j.seek(before[0]);
            EXPECT_EQ(ins.currentVertex(), v);
        }
    }
}

TEST(Breakpoint, InsertAtTheUnrecordedTipAsksTheInserter) {
    InsertOptions opt;
    opt.order = OrderKind::Input;
    Inserter ins(testPoints(), opt);
    Journal j(ins);
    const Breakpoint b{BreakKind::Insert, 5};
    const RunResult r = runUntil(j, ins, std::span(&b, 1), 1000);
    ASSERT_EQ(r.reason, StopReason::Hit);
    const std::size_t p = j.position();
    EXPECT_EQ(p, j.recorded()) << "the op of vertex 5 is not recorded yet";
    // Away from the tip, the same position is still recognised (from the insertion order).
    j.back();
    EXPECT_TRUE(hitsAt(b, j, ins, p));
    EXPECT_FALSE(hitsAt(b, j, ins, p - 1));
    EXPECT_FALSE(hitsAt(Breakpoint{BreakKind::Insert, 6}, j, ins, p));
    j.forward();
    EXPECT_EQ(j.forward()->vertex, 5);
}

TEST(Breakpoint, CornerStopsExactlyWhereItsCellsChange) {
    InsertOptions opt;
    opt.order = OrderKind::Input;
    const auto pts = testPoints();
    const Recorded rec = record(pts, opt);
    Inserter ins(pts, opt);
    Journal j(ins);
    const std::int32_t maxCorner = static_cast<std::int32_t>(
        std::max_element(rec.at.begin(), rec.at.end(), [](const Cells& a, const Cells& b) {
            return a.V.size() < b.V.size();
        })->V.size());
    for (std::int32_t c = 0; c < maxCorner; ++c) {
        std::vector<std::size_t> expected;
        for (std::size_t p = 1; p < rec.at.size(); ++p) {
            if (rec.at[p].v(c) != rec.at[p - 1].v(c) || rec.at[p].o(c) != rec.at[p - 1].o(c))
                expected.push_back(p);
        }
        EXPECT_EQ(stopsForward(ins, j, Breakpoint{BreakKind::Corner, c}), expected)
            << "corner " << c;
    }
}

TEST(Breakpoint, RunningBackRestoresTheStateOfEachStop) {
    for (Boundary b : {Boundary::Exact, Boundary::Super}) {
        SCOPED_TRACE(toString(b));
        InsertOptions opt;
        opt.boundary = b;
        opt.locator = LocatorKind::IdBufferCpu;
        const auto pts = generatePoints(Generator::NearDuplicates, 80, 5);
        const Recorded rec = record(pts, opt);
        Inserter ins(pts, opt);
        Journal j(ins);
        j.seek(rec.total);
        const Breakpoint flip = bp("flip");
        std::size_t stops = 0;
        while (true) {
            const RunResult r = runBackUntil(j, ins, std::span(&flip, 1), 1u << 30);
            if (r.reason == StopReason::Start) break;
            ASSERT_EQ(r.reason, StopReason::Hit);
            ASSERT_EQ(j.current()->type, OpType::Flip);
            EXPECT_TRUE((Cells{ins.mesh().V, ins.mesh().O} == rec.at[j.position()]))
                << j.position();
            ++stops;
        }
        Inserter batch(pts, opt);
        batch.run();
        EXPECT_EQ(static_cast<std::int64_t>(stops), batch.stats().flips);
        EXPECT_GT(stops, 0u);
        EXPECT_EQ(j.position(), 0u);
        EXPECT_TRUE((Cells{ins.mesh().V, ins.mesh().O} == rec.at[0]));
        // op:N back from the end lands on N with N's state.
        j.seek(rec.total);
        const Breakpoint op = Breakpoint{BreakKind::Op, static_cast<std::int64_t>(rec.total / 3)};
        const RunResult r = runBackUntil(j, ins, std::span(&op, 1), 1u << 30);
        EXPECT_EQ(r.reason, StopReason::Hit);
        EXPECT_EQ(r.steps, rec.total - rec.total / 3);
        EXPECT_TRUE((Cells{ins.mesh().V, ins.mesh().O} == rec.at[rec.total / 3]));
    }
}

TEST(Breakpoint, BudgetStopsAndResumes) {
    InsertOptions opt;
    Inserter ins(generatePoints(Generator::Uniform, 300, 2), opt);
    Journal j(ins);
    std::size_t calls = 0, steps = 0;
    RunResult r;
    do {
        r = runUntil(j, ins, {}, 50);
        steps += r.steps;
        ++calls;
        if (r.reason == StopReason::Budget) {
            EXPECT_EQ(r.steps, 50u);
        }
    } while (r.reason == StopReason::Budget);
    EXPECT_EQ(r.reason, StopReason::End);
    EXPECT_EQ(steps, j.recorded());
    EXPECT_TRUE(j.atEnd());
    EXPECT_EQ(calls, (j.recorded() + 49) / 50 + (j.recorded() % 50 == 0 ? 1 : 0));
    // At the end: nothing to do.
    r = runUntil(j, ins, {}, 50);
    EXPECT_EQ(r.reason, StopReason::End);
    EXPECT_EQ(r.steps, 0u);
    // Zero budget does nothing.
    r = runBackUntil(j, ins, {}, 0);
    EXPECT_EQ(r.reason, StopReason::Budget);
    EXPECT_EQ(r.steps, 0u);
    // op:N ahead of the run's end never hits: the run ends.
    j.seek(0);
    const Breakpoint far{BreakKind::Op, 1 << 30};
    EXPECT_EQ(runUntil(j, ins, std::span(&far, 1), 1u << 30).reason, StopReason::End);
    const Breakpoint ten{BreakKind::Op, 10};
    j.seek(0);
    r = runUntil(j, ins, std::span(&ten, 1), 1u << 30);
    EXPECT_EQ(r.reason, StopReason::Hit);
    EXPECT_EQ(j.position(), 10u);
}

TEST(Breakpoint, WholeInsertionsForwardAndBack) {
    InsertOptions opt;
    opt.order = OrderKind::Input;
    Inserter ins(testPoints(), opt);
    Journal j(ins);
    std::vector<std::size_t> boundaries{0};
    while (true) {
        const RunResult r = forwardInsertion(j, ins, 1u << 30);
        if (r.reason == StopReason::End) break;
        ASSERT_EQ(r.reason, StopReason::Hit);
        const OpType t = j.current()->type;
        EXPECT_TRUE(t == OpType::Start || t == OpType::Inserted || t == OpType::SkipDuplicate ||
                    t == OpType::Finalize);
        // Every op of the insertion just stepped over belongs to one vertex.
        for (std::size_t p = boundaries.back() + 1; p + 1 < j.position(); ++p) {
            EXPECT_EQ(j.ops()[p].vertex, j.ops()[boundaries.back()].vertex);
        }
        boundaries.push_back(j.position());
    }
    EXPECT_EQ(boundaries.back(), j.recorded());
    // From the middle of an insertion, back goes to its start; from its start, to the one before.
    const std::size_t mid = (boundaries[4] + boundaries[5]) / 2;
    ASSERT_GT(mid, boundaries[4]);
    j.seek(mid);
    EXPECT_EQ(backInsertion(j, ins, 1u << 30).reason, StopReason::Hit);
    EXPECT_EQ(j.position(), boundaries[4]);
    EXPECT_EQ(backInsertion(j, ins, 1u << 30).reason, StopReason::Hit);
    EXPECT_EQ(j.position(), boundaries[3]);
    j.seek(boundaries[1]);
    EXPECT_EQ(backInsertion(j, ins, 1u << 30).reason, StopReason::Start);
    EXPECT_EQ(j.position(), 0u);
}

TEST(Breakpoint, EditTargetsHitTheEditorsOpsAndNeverTheRun) {
    InsertOptions o;
    o.order = OrderKind::Input;
    Inserter ins({{0, 0}, {6, 0}, {5, 4}, {1, 3}, {3, 1}}, o);
    ins.run();
    Editor ed(ins.mesh());
    std::string message;
    ASSERT_TRUE(ed.add(*parseEdit("remove vertex 4"), message)) << message;
    ASSERT_TRUE(ed.add(*parseEdit("constrain 0-2"), message)) << message;
    ed.seek(0);
    EXPECT_TRUE(hitsEditAt(bp("edit:0"), ed));
    EXPECT_FALSE(hitsEditAt(bp("edit"), ed));
    const auto& removal = ed.edits()[0].removal.ops;
    const auto& constraint = ed.edits()[1].constraint.ops;
    int earFlips = 0, merges = 0, ends = 0, walks = 0, marks = 0, sloan = 0;
    while (ed.forward()) {
        earFlips += hitsEditAt(bp("ear-flip"), ed);
        merges += hitsEditAt(bp("merge"), ed);
        ends += hitsEditAt(bp("edit"), ed);
        walks += hitsEditAt(bp("segment-walk"), ed);
        marks += hitsEditAt(bp("constrain-mark"), ed);
        sloan += hitsEditAt(bp("sloan-flip"), ed) + hitsEditAt(bp("sloan-wait"), ed);
        if (ed.position() == ed.editEnd(0)) {
            EXPECT_TRUE(hitsEditAt(bp("edit:1"), ed));
        }
        EXPECT_EQ(hitsEditAt(bp("edit:2"), ed), ed.position() == ed.total());
    }
    const auto count = [](const auto& ops, auto type) {
        return static_cast<int>(
            std::count_if(ops.begin(), ops.end(), [&](const auto& op) { return op.type == type; }));
    };
    EXPECT_EQ(earFlips, count(removal, RemoveOpType::Flip));
    EXPECT_EQ(merges, 1);
    EXPECT_EQ(ends, 2);
    EXPECT_EQ(walks, count(constraint, ConstrainOpType::Walk));
    EXPECT_EQ(marks, 1);
    EXPECT_EQ(sloan, count(constraint, ConstrainOpType::SloanFlip) +
                         count(constraint, ConstrainOpType::SloanWait));
    // The run's journal never hits an edit target.
    Inserter run({{0, 0}, {6, 0}, {5, 4}, {1, 3}, {3, 1}}, o);
    Journal journal(run);
    const Breakpoint flips = bp("ear-flip");
    EXPECT_EQ(runUntil(journal, run, std::span(&flips, 1), 1u << 20).reason, StopReason::End);
    std::string error;
    EXPECT_FALSE(parseBreakpoint("ear-test:2", &error));
    EXPECT_NE(error.find("1, 0 or -1"), std::string::npos) << error;
    EXPECT_EQ(explain(bp("edit:0")), "the run's end, before the edits");
}
