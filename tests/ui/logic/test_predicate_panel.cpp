// The Predicates panel shows the calls the engine made: at every op of several runs, stepping
// forward and back, the panel's calls are the ones a run of the same points captured as its
// inserter made them, and a line-walk step shows the walk's two tests.
#include "core/engine/generators.h"
#include "tests/ui/ui_harness.h"
#include "ui/panels/panels.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

using dlab::InsertOptions;
using dlab::kNone;
using dlab::OpType;
using dlab::PredicateAsk;
using dlab::RecordedPredicateCall;
using dlab::Vec2;
using dlab::test::UiHarness;

namespace {

using Calls = std::vector<RecordedPredicateCall>;

// The same points and options run op by op in a core inserter, each op's calls captured as made.
std::vector<Calls> capturedRun(const std::vector<Vec2>& pts, const InsertOptions& opt) {
    dlab::Inserter ins(pts, opt);
    dlab::Journal journal(ins);
    std::vector<Calls> made;
    while (!ins.done()) {
        made.emplace_back();
        ins.step(&journal, &made.back());
    }
    return made;
}

void expectPanelShows(const dlab::ui::Engine& e, const Calls& made, const std::string& label) {
    const auto shown = dlab::ui::currentPredicateCalls(e);
    ASSERT_EQ(shown.size(), made.size()) << label;
    for (std::size_t i = 0; i < made.size(); ++i) {
        const auto& s = shown[i];
        const auto& m = made[i];
        const std::string at = label + " call " + std::to_string(i) + ": " + dlab::describe(m);
        ASSERT_TRUE(s.fromEngine) << at;
        ASSERT_EQ(s.inCircle, m.inCircle()) << at;
        ASSERT_EQ(s.what, dlab::describe(m)) << at;
        ASSERT_EQ(s.v, m.v) << at;
        ASSERT_EQ(std::memcmp(s.p.data(), m.p.data(), sizeof m.p), 0) << at;
        ASSERT_EQ(s.engineSign, m.sign) << at;
        // The details of the call are computed from its arguments: the same exact sign.
        ASSERT_EQ(s.report.exactSign, m.sign) << at;
        for (int k = 0; k < m.numArgs(); ++k) {
            ASSERT_EQ(s.labels[k].rfind(m.v[k] == kNone ? "q" : "v" + std::to_string(m.v[k]), 0),
                      0u)
                << at << " argument " << k << " labelled " << s.labels[k];
        }
    }
}

struct Case {
    std::string name;
    std::vector<Vec2> points;
    InsertOptions options;
};

std::vector<Case> cases() {
    std::vector<Case> out;
    InsertOptions demo = dlab::ui::demoOptions();
    out.push_back({"demo", dlab::demoPoints(), demo});
    InsertOptions exact;
    exact.locator = dlab::LocatorKind::Grid;
    out.push_back({"lattice/grid", dlab::generatePoints(dlab::Generator::Grid, 49, 2), exact});
    InsertOptions super;
    super.boundary = dlab::Boundary::Super;
    super.order = dlab::OrderKind::Input;
    out.push_back({"circle/super", dlab::generatePoints(dlab::Generator::Circle, 30, 2), super});
    InsertOptions naive;
    naive.locator = dlab::LocatorKind::Naive;
    out.push_back(
        {"duplicates/naive", dlab::generatePoints(dlab::Generator::NearDuplicates, 40, 2), naive});
    out.push_back(
        {"collinear", dlab::generatePoints(dlab::Generator::AllCollinear, 8, 2), InsertOptions{}});
    return out;
}

}  // namespace

TEST(PredicatePanel, ShowsTheCallsTheEngineMadeAtEveryOpForwardAndBack) {
    for (const Case& c : cases()) {
        SCOPED_TRACE(c.name);
        const std::vector<Calls> made = capturedRun(c.points, c.options);
        dlab::ui::Engine e;
        std::string error;
        ASSERT_TRUE(e.reset(c.points, c.options, error)) << error;
        EXPECT_TRUE(dlab::ui::currentPredicateCalls(e).empty());  // nothing done yet
        while (e.forward()) {
            ASSERT_LE(e.position(), made.size());
            ASSERT_NO_FATAL_FAILURE(expectPanelShows(e, made[e.position() - 1],
                                                     "forward to " + std::to_string(e.position())));
        }
        ASSERT_EQ(e.position(), made.size());
        while (e.back() && e.position() > 0) {
            ASSERT_NO_FATAL_FAILURE(expectPanelShows(e, made[e.position() - 1],
                                                     "back to " + std::to_string(e.position())));
        }
    }
}

TEST(PredicatePanel, ALocateStepShowsTheLineWalksTwoTests) {
    const auto pts = dlab::generatePoints(dlab::Generator::Uniform, 200, 4);
    InsertOptions opt;
    opt.order = dlab::OrderKind::Input;  // long walks
    dlab::ui::Engine e;
    std::string error;
    ASSERT_TRUE(e.reset(pts, opt, error)) << error;
    int seen = 0;
    while (e.forward()) {
        const dlab::Journal& j = *e.journal();
        if (e.current()->type != OpType::LocateStep) continue;
        const dlab::WalkState& walk = j.controlBefore(e.position() - 1).walk;
        if (walk.tri == kNone || walk.entry == kNone) continue;  // a walk's start
        const auto shown = dlab::ui::currentPredicateCalls(e);
        ASSERT_EQ(shown.size(), 2u) << "at op " << e.position();
        EXPECT_FALSE(shown[0].inCircle);
        EXPECT_EQ(shown[0].v[0], kNone);  // L's origin q
        EXPECT_EQ(shown[0].v[1], e.current()->vertex);
        EXPECT_EQ(shown[0].what.rfind("Is v", 0), 0u) << shown[0].what;
        EXPECT_NE(shown[0].what.find("left of the line L"), std::string::npos) << shown[0].what;
        EXPECT_EQ(shown[1].v[2], e.current()->vertex);
        EXPECT_EQ(shown[1].engineSign, -1);  // p beyond the exit edge: the walk moved on
        EXPECT_NE(shown[1].what.find("that L leaves"), std::string::npos) << shown[1].what;
        ++seen;
    }
    EXPECT_GT(seen, 100);
}

TEST(PredicatePanel, TheTabDrawsEveryKindOfOperation) {
    UiHarness h;
    auto& st = h.state();
    st.pendingTab = "predicates";
    h.frames(2);
    std::vector<bool> seen(10, false);
    while (st.engine.forward()) {
        const OpType t = st.engine.current()->type;
        if (seen[static_cast<int>(t)]) continue;
        seen[static_cast<int>(t)] = true;
        st.itemRects.erase("predicate-calls");
        h.frames(1);
        ASSERT_EQ(st.engine.current()->type, t);
        EXPECT_TRUE(st.itemRects.count("predicate-calls")) << "the panel is not on show";
    }
    EXPECT_TRUE(seen[static_cast<int>(OpType::InCircleTest)]);
    EXPECT_TRUE(seen[static_cast<int>(OpType::LocateStep)]);
}
