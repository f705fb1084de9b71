// Trace diff: identical runs agree; a student's minimal trace (op + triangles) is understood; op
// by op, the first difference is found at the right op (wrong triangle, missing flip, truncation,
// extra ops, other corner layout, clockwise triangles); bad files fail with file:line; dtlab
// diff-trace exits 0 / 1 / 2. The assignment checker (insertion by insertion) passes an
// independent correct implementation and names the insertion and the reason of planted bugs.
#include "core/teaching/trace_diff.h"

#include "core/engine/generators.h"
#include "core/engine/io_read.h"
#include "core/engine/predicates.h"
#include "core/teaching/lesson.h"
#include "core/teaching/trace.h"

#include "tests/run_dtlab.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

using namespace dlab;
namespace fs = std::filesystem;

namespace {

TraceFile ourTrace(const std::vector<Vec2>& pts, InsertOptions opt = {},
                   const std::string& name = "ref.jsonl") {
    Inserter ins(pts, opt);
    return traceOfRun(ins, name);
}

std::vector<Vec2> testPoints() {
    // A lattice (points on edges, cocircular quadruples), random points and the demo (with a
    // duplicate).
    auto pts = generatePoints(Generator::Grid, 64, 9);
    const auto more = generatePoints(Generator::Uniform, 60, 9), demo = demoPoints();
    pts.insert(pts.end(), more.begin(), more.end());
    pts.insert(pts.end(), demo.begin(), demo.end());
    return pts;
}

// A student's minimal trace: only "op" and "triangles" on the lines that change the mesh, as
// JSON Lines text (so the reader is exercised too). `edit` may change each line's JSON.
template <class Edit>
std::string minimalText(const TraceFile& ref, Edit edit) {
    std::ostringstream out;
    std::size_t meshOp = 0;
    for (const TraceOp& op : ref.ops) {
        if (!op.changesMesh()) continue;
        nlohmann::json j;
        j["op"] = toString(op.type);
        if (op.type != OpType::Finalize) {
            // Our trace lists the triangles whose cells changed; the student lists them too.
            j["triangles"] = nlohmann::json::array();
            for (const auto& t : op.triangles) j["triangles"].push_back({t[0], t[1], t[2], t[3]});
        }
        if (edit(meshOp++, j)) out << j.dump() << "\n";
    }
    return out.str();
}
std::string minimalText(const TraceFile& ref) {
    return minimalText(ref, [](std::size_t, nlohmann::json&) { return true; });
}

TraceFile parse(const std::string& text, const std::string& name = "student.jsonl") {
    std::istringstream in(text);
    return parseTraceText(in, name);
}

// Index in ref.ops of the k-th op that changes the mesh.
std::size_t meshOpIndex(const TraceFile& f, std::size_t k) {
    for (std::size_t i = 0; i < f.ops.size(); ++i) {
        if (f.ops[i].changesMesh() && k-- == 0) return i;
    }
    return f.ops.size();
}

std::size_t firstOfType(const TraceFile& f, OpType t, std::size_t from = 0) {
    std::size_t k = 0;
    for (std::size_t i = 0; i < f.ops.size(); ++i) {
        if (f.ops[i].changesMesh()) {
            if (f.ops[i].type == t && k >= from) return k;
            ++k;
        }
    }
    return k;
}

std::string inputError(const std::string& text) {
    try {
        parse(text, "s.jsonl");
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << "accepted: " << text;
    return "";
}

using Result = dlab::testutil::DtlabResult;
Result dtlab(const std::string& args) { return dlab::testutil::runDtlab(args); }

fs::path scratch() {
    const fs::path d = fs::temp_directory_path() / ("dlab_diff_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

}  // namespace

TEST(TraceDiff, IdenticalRunsAgreeInEveryMode) {
    for (Boundary b : {Boundary::Exact, Boundary::Super}) {
        InsertOptions opt;
        opt.boundary = b;
        const TraceFile ref = ourTrace(testPoints(), opt);
        std::size_t meshOps = 0, steps = 0;
        for (const TraceOp& op : ref.ops) {
            meshOps += op.changesMesh();
            steps += op.changesMesh() && op.type != OpType::Flip;
        }
        for (int mode = 0; mode < 3; ++mode) {
            DiffOptions o;
            o.byOp = mode == 1;
            o.corners = mode == 2;
            const TraceDiff d = diffTraces(ref, ourTrace(testPoints(), opt), o);
            EXPECT_TRUE(d.equal) << d.what;
            // Insertion by insertion: the start, every insertion and Finalize.
            EXPECT_EQ(d.compared, mode == 0 ? steps : meshOps);
            o.allOps = true;
            EXPECT_TRUE(diffTraces(ref, ref, o).equal);
        }
    }
}

TEST(TraceDiff, MinimalStudentTraceIsEnough) {
    const TraceFile ref = ourTrace(testPoints());
    const TraceFile student = parse(minimalText(ref));
    EXPECT_FALSE(student.ops.back().hasTriangles) << "a bare Finalize";
    const TraceDiff d = diffTraces(ref, student);
    EXPECT_TRUE(d.equal) << formatDiff(d, ref, student);
    // Given as triangles with the student's own ids, V is known too: corners compare as well.
    DiffOptions corners;
    corners.corners = true;
    EXPECT_TRUE(diffTraces(ref, student, corners).equal)
        << formatDiff(diffTraces(ref, student, corners), ref, student);
    // Op names in other spellings are accepted.
    const TraceFile lower = parse(minimalText(ref, [](std::size_t, nlohmann::json& j) {
        std::string op = j["op"];
        if (op == "SplitEdge") j["op"] = "split_edge";
        if (op == "Flip") j["op"] = "flip";
        return true;
    }));
    EXPECT_TRUE(diffTraces(ref, lower).equal);
}

TEST(TraceDiff, OurOwnTraceWithoutChangesAgrees) {
    // "changes" is optional: without it, Finalize's empty "triangles" means "not given", not
    // "the final mesh is empty".
    Inserter ins(testPoints(), InsertOptions{});
    Journal journal(ins);
    std::ostringstream text;
    while (journal.forward()) {
        auto j = nlohmann::json::parse(
            toJsonLine(traceRecord(journal, journal.position() - 1, ins.mesh())));
        j.erase("changes");
        text << j.dump() << "\n";
    }
    const TraceFile student = parse(text.str());
    ASSERT_EQ(student.ops.back().type, OpType::Finalize);
    const TraceFile ref = ourTrace(testPoints());
    const TraceDiff d = diffTraces(ref, student);
    EXPECT_TRUE(d.equal) << formatDiff(d, ref, student);
}

TEST(TraceDiff, FirstWrongTriangleIsFoundAtItsOp) {
    const TraceFile ref = ourTrace(testPoints());
    for (OpType type : {OpType::Split, OpType::Flip, OpType::SplitEdge}) {
        const std::size_t k = firstOfType(ref, type, type == OpType::SplitEdge ? 0 : 30);
        ASSERT_LT(meshOpIndex(ref, k), ref.ops.size()) << toString(type);
        const TraceFile student = parse(minimalText(ref, [&](std::size_t m, nlohmann::json& j) {
            if (m == k) j["triangles"][0][1] = static_cast<int>(j["triangles"][0][1]) + 1;
            return true;
        }));
        DiffOptions byOp;
        byOp.byOp = true;
        const TraceDiff d = diffTraces(ref, student, byOp);
        ASSERT_FALSE(d.equal) << toString(type);
        EXPECT_EQ(d.refOp, meshOpIndex(ref, k)) << toString(type);
        EXPECT_EQ(d.studentOp, k);
        EXPECT_NE(d.what.find(std::string("the triangles differ after ") + toString(type)),
                  std::string::npos)
            << d.what;
        const std::string report = formatDiff(d, ref, student, byOp);
        EXPECT_NE(report.find("triangles only in the reference"), std::string::npos) << report;
        EXPECT_NE(report.find("> ref.jsonl:" + std::to_string(ref.ops[d.refOp].line)),
                  std::string::npos)
            << report;
        EXPECT_NE(report.find("> student.jsonl:" + std::to_string(k + 1)), std::string::npos)
            << report;
        if (type == OpType::Flip) {
            EXPECT_NE(report.find("reference: flipped edge"), std::string::npos) << report;
        }
    }
}

TEST(TraceDiff, MissingFlipShowsAsTheWrongOperation) {
    const TraceFile ref = ourTrace(testPoints());
    // A flip that ends its cascade: without it, the student's next operation is no flip.
    std::size_t k = firstOfType(ref, OpType::Flip, 10);
    while (ref.ops[meshOpIndex(ref, k + 1)].type == OpType::Flip)
        k = firstOfType(ref, OpType::Flip, k + 1);
    const TraceFile student =
        parse(minimalText(ref, [&](std::size_t m, nlohmann::json&) { return m != k; }));
    DiffOptions byOp;
    byOp.byOp = true;
    const TraceDiff d = diffTraces(ref, student, byOp);
    ASSERT_FALSE(d.equal);
    EXPECT_EQ(d.refOp, meshOpIndex(ref, k));
    EXPECT_NE(d.what.find("the reference does Flip, the student"), std::string::npos) << d.what;
}

TEST(TraceDiff, TruncatedAndOverlongStudentTraces) {
    const TraceFile ref = ourTrace(testPoints());
    const TraceFile cut =
        parse(minimalText(ref, [](std::size_t m, nlohmann::json&) { return m < 40; }));
    DiffOptions byOp;
    byOp.byOp = true;
    TraceDiff d = diffTraces(ref, cut, byOp);
    ASSERT_FALSE(d.equal);
    EXPECT_EQ(d.refOp, meshOpIndex(ref, 40));
    EXPECT_EQ(d.studentOp, cut.ops.size());
    EXPECT_NE(d.what.find("the student's trace ends early"), std::string::npos) << d.what;
    EXPECT_NE(formatDiff(d, ref, cut).find("(end of trace)"), std::string::npos);
    // The reference cut short instead: the student goes on.
    d = diffTraces(cut, parse(minimalText(ref)), byOp);
    ASSERT_FALSE(d.equal);
    EXPECT_NE(d.what.find("goes on after the reference has ended"), std::string::npos) << d.what;
}

TEST(TraceDiff, CornerLayoutAndOrientation) {
    const TraceFile ref = ourTrace(testPoints());
    // Same triangles listed from another corner: equal by triangles, not by corners.
    const TraceFile rotated = parse(minimalText(ref, [](std::size_t m, nlohmann::json& j) {
        if (m == 5) {
            for (auto& t : j["triangles"]) t = {t[0], t[2], t[3], t[1]};
        }
        return true;
    }));
    EXPECT_TRUE(diffTraces(ref, rotated).equal);
    DiffOptions corners;
    corners.corners = true;
    const TraceDiff d = diffTraces(ref, rotated, corners);
    ASSERT_FALSE(d.equal);
    EXPECT_EQ(d.studentOp, 5u);
    EXPECT_NE(d.what.find("same triangles, but the corners differ"), std::string::npos) << d.what;
    // Clockwise triangles are named as such.
    const TraceFile clockwise = parse(minimalText(ref, [](std::size_t m, nlohmann::json& j) {
        if (m == 7) {
            for (auto& t : j["triangles"]) t = {t[0], t[1], t[3], t[2]};
        }
        return true;
    }));
    DiffOptions byOp;
    byOp.byOp = true;
    const TraceDiff c = diffTraces(ref, clockwise, byOp);
    ASSERT_FALSE(c.equal);
    EXPECT_EQ(c.studentOp, 7u);
    EXPECT_NE(formatDiff(c, ref, clockwise, byOp).find("other orientation (clockwise)"),
              std::string::npos);
    // Insertion by insertion, the clockwise triangle is named.
    const TraceDiff w = diffTraces(ref, clockwise);
    ASSERT_FALSE(w.equal);
    EXPECT_NE(w.what.find("is clockwise"), std::string::npos) << w.what;
}

TEST(TraceDiff, LocatorsDifferOnlyInTheWalk) {
    // Every point strictly inside the first triangle: whatever the walk, each point lands in
    // the same triangle, so the mesh operations are the same. (Points outside the hull or on an
    // edge can be placed through different triangles.)
    std::vector<Vec2> pts{{-1000, -1000}, {3000, -1000}, {800, 3000}};
    for (const Vec2& p : generatePoints(Generator::Uniform, 150, 4))
        pts.push_back({p.x / 2 + 200, p.y / 2 + 200});
    InsertOptions walk, naive;
    walk.order = naive.order = OrderKind::Input;
    naive.locator = LocatorKind::Naive;
    const TraceFile ref = ourTrace(pts, walk), other = ourTrace(pts, naive, "naive.jsonl");
    EXPECT_TRUE(diffTraces(ref, other).equal) << "the same mesh operations";
    DiffOptions all;
    all.allOps = true;
    const TraceDiff d = diffTraces(ref, other, all);
    EXPECT_FALSE(d.equal);
    EXPECT_TRUE(ref.ops[d.refOp].type == OpType::LocateStep ||
                other.ops[d.studentOp].type == OpType::LocateStep ||
                ref.ops[d.refOp].type == OpType::Located)
        << d.what;
}

TEST(TraceDiff, BadTracesFailWithFileAndLine) {
    const std::string ok = "{\"op\": \"Start\", \"triangles\": [[0, 0, 1, 2]]}\n";
    EXPECT_EQ(inputError(ok + "{\"op\": \"Start\"\n"),
              "s.jsonl:2: not a JSON object (each line of a trace is one {...})");
    EXPECT_EQ(inputError(ok + "\n[1, 2]\n"),
              "s.jsonl:3: not a JSON object (each line of a trace is one {...})");
    EXPECT_EQ(inputError("{\"i\": 0}\n"), "s.jsonl:1: missing \"op\" (e.g. \"op\": \"Flip\")");
    EXPECT_EQ(inputError("{\"op\": \"Flop\"}\n"), "s.jsonl:1: unknown op \"Flop\"");
    EXPECT_EQ(inputError("{\"op\": 3}\n"), "s.jsonl:1: \"op\" must be a string");
    EXPECT_NE(inputError("{\"op\": \"Split\", \"triangles\": [[0, 1, 2]]}\n")
                  .find("s.jsonl:1: a triangle is [t, v0, v1, v2]"),
              std::string::npos);
    EXPECT_NE(inputError("{\"op\": \"Split\", \"triangles\": [[99999999999, 1, 2, 3]]}\n")
                  .find("out of range"),
              std::string::npos);
    EXPECT_NE(inputError("{\"op\": \"Split\", \"triangles\": [[0, 1.5, 2, 3]]}\n")
                  .find("must be an integer"),
              std::string::npos);
    EXPECT_NE(
        inputError("{\"op\": \"Flip\", \"changes\": [[\"X\", 1, 2, 3]]}\n").find("a change is"),
        std::string::npos);
    EXPECT_NE(inputError("{\"op\": \"Flip\", \"changes\": [[\"V\", 1000000000, 2, 3]]}\n")
                  .find("out of range"),
              std::string::npos);
    EXPECT_NE(inputError("{\"op\": \"Flip\", \"vertex\": -5}\n").find("vertex -5 is out of range"),
              std::string::npos);
    EXPECT_EQ(inputError("\n\n"), "s.jsonl: no operations: the trace is empty");
    EXPECT_EQ(inputError(std::string("\x89PNG\r\n\x1a\n", 8)),
              "s.jsonl:1: not a JSON object (each line of a trace is one {...})");
    // Fields of the wrong kind that the comparison does not need are ignored; others are errors.
    EXPECT_NO_THROW(parse("{\"op\": \"Start\", \"where\": 5, \"comment\": \"mine\"}\n"));
}

TEST(TraceDiff, DtlabDiffTraceExitCodes) {
    const fs::path dir = scratch();
    const std::string pts = (dir / "p.csv").string();
    {
        std::ofstream out(pts);
        for (const Vec2& p : generatePoints(Generator::Uniform, 60, 3))
            out << p.x << "," << p.y << "\n";
    }
    const std::string ref = (dir / "ref.jsonl").string(), again = (dir / "again.jsonl").string();
    ASSERT_EQ(dtlab("trace " + pts + " -o " + ref).status, 0);
    ASSERT_EQ(dtlab("trace " + pts + " -o " + again).status, 0);
    Result r = dtlab("diff-trace " + ref + " " + again);
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("the runs agree"), std::string::npos) << r.out;
    const std::string other = (dir / "other.jsonl").string();
    ASSERT_EQ(dtlab("trace " + pts + " -o " + other + " --order random --seed 5").status, 0);
    r = dtlab("diff-trace " + ref + " " + other);
    EXPECT_EQ(r.status, 1) << r.out;
    EXPECT_NE(r.out.find("first difference at reference op"), std::string::npos) << r.out;
    const std::string bad = (dir / "bad.jsonl").string();
    std::ofstream(bad) << "{\"op\": \"Start\"}\nnot json\n";
    r = dtlab("diff-trace " + ref + " " + bad);
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_NE(r.out.find(bad + ":2: not a JSON object"), std::string::npos) << r.out;
    r = dtlab("diff-trace " + ref + " " + (dir / "missing.jsonl").string());
    EXPECT_EQ(r.status, 2) << r.out;
    // A lesson or assignment as the reference: its run is traced on the fly.
    const std::string lesson = std::string(DLAB_SOURCE_DIR) + "/lessons/04_split.toml";
    Lesson l = loadLesson(lesson);
    const TraceFile fromLesson = ourTrace(l.points, l.options);
    const std::string stu = (dir / "stu.jsonl").string();
    std::ofstream(stu) << minimalText(fromLesson);
    r = dtlab("diff-trace --corners " + lesson + " " + stu);
    EXPECT_EQ(r.status, 0) << r.out;
}

// ---- The assignment, checked insertion by insertion --------------------------------------------
//
// A student's implementation written from the assignment's text alone
// (lessons/10_assignment_insertion.toml): a plain triangle list with an edge map, no corner
// table; a brute-force point location; its own numbering and slot use (a split keeps the old
// triangle's number for a different new triangle than ours, a flip swaps the two numbers). It
// writes the minimal trace format. `Bug` plants one of the classic mistakes.

namespace {

enum class Bug {
    None,
    MissingFlip,
    FlipDelaunayEdge,
    ForgottenPush,
    OnEdgeOneSide,
    SkipPoint,
    WrongInCircleSign
};

// The first flip the WrongInCircleSign bug made: edge a-b between (v, a, b) and (b, a, d).
struct WrongFlip {
    int v = -1, a = -1, b = -1, d = -1;
    bool convex = false;  // the quadrilateral v a d b was convex (no clockwise triangle came of it)
};

class StudentTriangulator {
public:
    // fifo: the edges to test wait in a queue (first pushed, first tested), not on a stack.
    StudentTriangulator(std::vector<Vec2> points, Bug bug, int bugFrom, bool fifo = false)
        : m_p(std::move(points)),
          m_n(static_cast<int>(m_p.size())),
          m_bug(bug),
          m_bugFrom(bugFrom),
          m_fifo(fifo) {
        // The super-triangle from the text, stored after the input points.
        m_p.push_back({-1650, -1089});
        m_p.push_back({1710, -1089});
        m_p.push_back({30, 1711});
        setTriangle(0, {m_n, m_n + 1, m_n + 2});
        emit("Start", {0});
    }

    void run() {
        for (int i = 0; i < m_n; ++i) {
            insert(i);
            // A wrong in-circle sign may leave a mesh the brute-force walk cannot go on with.
            if (m_bug == Bug::WrongInCircleSign && i + 1 == m_bugFrom) break;
        }
        m_out << "{\"op\": \"Finalize\", \"triangles\": []}\n";
    }
    const WrongFlip& wrongFlip() const { return m_wrongFlip; }
    std::string trace() const { return m_out.str(); }
    // The 1-based insertion at which the planted bug first acted (0: never).
    int bugAt() const { return m_bugAt; }
    // The triangles after each insertion: the ground truth the planted bugs are judged by.
    const std::vector<std::vector<Triple>>& history() const { return m_history; }

private:
    using Tri = std::array<int, 3>;

    bool bugOn(int insertion) const { return m_bug != Bug::None && insertion >= m_bugFrom; }
    void acted(int insertion) {
        if (m_bugAt == 0) m_bugAt = insertion;
    }

    void setTriangle(int t, Tri tri) {
        if (t >= static_cast<int>(m_t.size())) m_t.resize(t + 1, Tri{-1, -1, -1});
        if (m_t[t][0] >= 0) {  // its old edges, unless another triangle has one now
            for (int k = 0; k < 3; ++k) {
                const auto it = m_edge.find({m_t[t][k], m_t[t][(k + 1) % 3]});
                if (it != m_edge.end() && it->second == t) m_edge.erase(it);
            }
        }
        m_t[t] = tri;
        for (int k = 0; k < 3; ++k) m_edge[{tri[k], tri[(k + 1) % 3]}] = t;
    }

    void emit(const char* op, std::initializer_list<int> tris) {
        nlohmann::json j;
        j["op"] = op;
        if (tris.size()) {
            j["triangles"] = nlohmann::json::array();
            for (int t : tris) j["triangles"].push_back({t, m_t[t][0], m_t[t][1], m_t[t][2]});
        }
        m_out << j.dump() << "\n";
    }

    void snapshot() {
        std::vector<Triple> ts;
        for (const Tri& t : m_t) ts.push_back(canonical(t[0], t[1], t[2]));
        std::sort(ts.begin(), ts.end());
        m_history.push_back(ts);
    }

    void insert(int v) {
        const int insertion = v + 1;
        for (int w = 0; w < v; ++w) {
            if (m_p[w] == m_p[v]) {  // a duplicate: the point that came first stays
                emit("SkipDuplicate", {});
                snapshot();
                return;
            }
        }
        if (m_bug == Bug::SkipPoint && bugOn(insertion)) {
            acted(insertion);
            emit("SkipDuplicate", {});
            snapshot();
            return;
        }
        // Brute force: the first triangle with v on no edge's right.
        for (int t = 0; t < static_cast<int>(m_t.size()); ++t) {
            const Tri tri = m_t[t];
            int zeroEdge = -1, outside = 0;
            for (int k = 0; k < 3; ++k) {
                const int o = orient2d(m_p[tri[k]], m_p[tri[(k + 1) % 3]], m_p[v]);
                if (o < 0) outside = 1;
                if (o == 0) zeroEdge = k;
            }
            if (outside) continue;
            if (zeroEdge < 0) {
                splitInside(t, v);
            } else if (m_bug == Bug::OnEdgeOneSide && bugOn(insertion)) {
                acted(insertion);
                splitOneSide(t, zeroEdge, v);
            } else {
                splitOnEdge(t, zeroEdge, v);
            }
            break;
        }
        legalize(v, insertion);
        snapshot();
    }

    // 1 -> 3: t = (a, b, c) keeps its number for (v, b, c); (v, c, a) and (v, a, b) are new.
    void splitInside(int t, int v) {
        const auto [a, b, c] = m_t[t];
        const int t1 = static_cast<int>(m_t.size()), t2 = t1 + 1;
        setTriangle(t, {v, b, c});
        setTriangle(t1, {v, c, a});
        setTriangle(t2, {v, a, b});
        emit("Split", {t, t1, t2});
        m_stack.push_back({a, b});
        m_stack.push_back({b, c});
        m_stack.push_back({c, a});
    }

    // 2 -> 4: v on edge x-y of t = (x, y, z); u = (y, x, w) across it.
    void splitOnEdge(int t, int k, int v) {
        const int x = m_t[t][k], y = m_t[t][(k + 1) % 3], z = m_t[t][(k + 2) % 3];
        const int u = m_edge.at({y, x});
        const int w = third(m_t[u], x, y);
        const int t1 = static_cast<int>(m_t.size()), t2 = t1 + 1;
        setTriangle(t, {v, z, x});
        setTriangle(u, {v, x, w});
        setTriangle(t1, {v, y, z});
        setTriangle(t2, {v, w, y});
        emit("SplitEdge", {t, u, t1, t2});
        for (std::pair<int, int> e : {std::pair{y, z}, {z, x}, {x, w}, {w, y}})
            m_stack.push_back(e);
    }

    // The planted bug: only the triangle the point was found in is split (1 -> 2), the one
    // across the edge is left as it was.
    void splitOneSide(int t, int k, int v) {
        const int x = m_t[t][k], y = m_t[t][(k + 1) % 3], z = m_t[t][(k + 2) % 3];
        const int t1 = static_cast<int>(m_t.size());
        setTriangle(t, {v, z, x});
        setTriangle(t1, {v, y, z});
        emit("Split", {t, t1});
        m_stack.push_back({y, z});
        m_stack.push_back({z, x});
    }

    static int third(const Tri& t, int a, int b) {
        for (int v : t) {
            if (v != a && v != b) return v;
        }
        return -1;
    }

    // The edges opposite v wait on the stack; the last pushed is tested first (or, fifo, the
    // first pushed).
    void legalize(int v, int insertion) {
        while (!m_stack.empty()) {
            const auto [a, b] = m_fifo ? m_stack.front() : m_stack.back();
            if (m_fifo)
                m_stack.erase(m_stack.begin());
            else
                m_stack.pop_back();
            const auto across = m_edge.find({b, a});
            if (across == m_edge.end()) continue;  // the super-triangle's edge
            const int t = m_edge.at({a, b}), u = across->second;
            const int d = third(m_t[u], a, b);
            bool flip = incircle(m_p[a], m_p[b], m_p[v], m_p[d]) > 0;
            if (m_bug == Bug::WrongInCircleSign && insertion == m_bugFrom) {  // this one only
                flip = incircle(m_p[a], m_p[b], m_p[v], m_p[d]) < 0;
                if (flip && m_bugAt == 0) {
                    acted(insertion);
                    m_wrongFlip = {v, a, b, d,
                                   orient2d(m_p[v], m_p[a], m_p[d]) > 0 &&
                                       orient2d(m_p[v], m_p[d], m_p[b]) > 0};
                }
            }
            if (flip && m_bug == Bug::MissingFlip && bugOn(insertion) && m_bugAt == 0) {
                acted(insertion);
                continue;
            }
            if (!flip && m_bug == Bug::FlipDelaunayEdge && bugOn(insertion) && m_bugAt == 0 &&
                orient2d(m_p[v], m_p[a], m_p[d]) > 0 && orient2d(m_p[v], m_p[d], m_p[b]) > 0) {
                acted(insertion);
                flip = true;
            }
            if (!flip) continue;
            // (v, a, b) and (b, a, d) become (v, d, b) in t and (v, a, d) in u.
            setTriangle(t, {v, d, b});
            setTriangle(u, {v, a, d});
            emit("Flip", {t, u});
            if (m_bug == Bug::ForgottenPush && bugOn(insertion)) {
                acted(insertion);
                continue;
            }
            m_stack.push_back({a, d});
            m_stack.push_back({d, b});
        }
    }

    std::vector<Vec2> m_p;
    int m_n;
    Bug m_bug;
    int m_bugFrom;
    bool m_fifo;
    int m_bugAt = 0;
    WrongFlip m_wrongFlip;
    std::vector<Tri> m_t;
    std::map<std::pair<int, int>, int> m_edge;  // directed edge -> the triangle on its left
    std::vector<std::pair<int, int>> m_stack;
    std::ostringstream m_out;
    std::vector<std::vector<Triple>> m_history;
};

const std::string kAssignment =
    std::string(DLAB_SOURCE_DIR) + "/lessons/10_assignment_insertion.toml";

TraceFile assignmentReference() {
    Lesson l = loadLesson(kAssignment);
    auto ins = makeInserter(l);
    return traceOfRun(*ins, "ours");
}

std::vector<Vec2> assignmentPoints() { return loadLesson(kAssignment).points; }

// Runs a student with `bug` from insertion `from` on; the insertion where the student's mesh
// first differs from the correct student's (by the test's own bookkeeping, not the checker's).
struct Planted {
    TraceDiff diff;
    int wrongFrom = 0;
    int bugAt = 0;
    std::string report;
};

Planted plant(Bug bug, int from) {
    StudentTriangulator good(assignmentPoints(), Bug::None, 0), bad(assignmentPoints(), bug, from);
    good.run();
    bad.run();
    Planted p;
    p.bugAt = bad.bugAt();
    for (std::size_t k = 0; k < good.history().size(); ++k) {
        if (good.history()[k] != bad.history()[k]) {
            p.wrongFrom = static_cast<int>(k) + 1;
            break;
        }
    }
    const TraceFile ref = assignmentReference(), student = parse(bad.trace());
    p.diff = diffTraces(ref, student);
    p.report = formatDiff(p.diff, ref, student);
    return p;
}

}  // namespace

TEST(AssignmentChecker, IndependentCorrectImplementationPasses) {
    StudentTriangulator student(assignmentPoints(), Bug::None, 0);
    student.run();
    const TraceFile ref = assignmentReference(), theirs = parse(student.trace());
    const TraceDiff d = diffTraces(ref, theirs);
    EXPECT_TRUE(d.equal) << formatDiff(d, ref, theirs);
    EXPECT_NE(d.what.find("the runs agree"), std::string::npos) << d.what;
    // The conventions differ: op by op, corner by corner, it is not ours.
    DiffOptions corners;
    corners.corners = true;
    EXPECT_FALSE(diffTraces(ref, theirs, corners).equal);
    // The same through the command line, the assignment as the reference.
    const fs::path file = scratch() / "student.jsonl";
    std::ofstream(file) << student.trace();
    const Result r = dtlab("diff-trace " + kAssignment + " " + file.string());
    EXPECT_EQ(r.status, 0) << r.out;
}

TEST(AssignmentChecker, EmptyFinalizeListIsNotAnEmptyMesh) {
    const TraceFile ref = assignmentReference();
    std::string text = minimalText(ref);
    for (bool byOp : {false, true}) {
        DiffOptions o;
        o.byOp = byOp;
        const TraceFile withList =
            parse(text + "{\"op\": \"Finalize\", \"triangles\": []}\n", "s.jsonl");
        const TraceFile bare = parse(text, "s.jsonl");
        // minimalText ends with a bare Finalize; swap it for the empty list.
        TraceFile swapped = bare;
        swapped.ops.back() = withList.ops.back();
        const TraceDiff d = diffTraces(ref, swapped, o);
        EXPECT_TRUE(d.equal) << formatDiff(d, ref, swapped, o);
    }
}

TEST(AssignmentChecker, MissingFlipIsNamedAtItsInsertion) {
    const Planted p = plant(Bug::MissingFlip, 10);
    ASSERT_GT(p.bugAt, 0);
    ASSERT_FALSE(p.diff.equal);
    EXPECT_EQ(p.diff.insertion, p.bugAt) << p.report;
    EXPECT_EQ(p.diff.insertion, p.wrongFrom);
    EXPECT_EQ(p.diff.vertex, p.bugAt - 1);
    EXPECT_NE(p.diff.what.find("not Delaunay at edge"), std::string::npos) << p.report;
    EXPECT_NE(p.diff.what.find("is inside the circle of"), std::string::npos) << p.report;
    EXPECT_NE(p.diff.what.find("missing flip of edge"), std::string::npos) << p.report;
    // The message README.md quotes.
    EXPECT_EQ(p.diff.what,
              "after inserting point 9 (insertion 10 of 38): not Delaunay at edge 1\u20136: vertex "
              "4 is inside the circle of 1 6 9; missing flip of edge 1\u20136 (expected 4\u20139)");
}

TEST(AssignmentChecker, FlipOfADelaunayEdgeIsNamed) {
    const Planted p = plant(Bug::FlipDelaunayEdge, 10);
    ASSERT_GT(p.bugAt, 0);
    ASSERT_FALSE(p.diff.equal);
    EXPECT_EQ(p.diff.insertion, p.bugAt) << p.report;
    EXPECT_NE(p.diff.what.find("which was Delaunay (it should stay): point " +
                               std::to_string(p.bugAt - 1) + " is "),
              std::string::npos)
        << p.report;
}

TEST(AssignmentChecker, ForgottenPushAfterAFlipIsNamed) {
    const Planted p = plant(Bug::ForgottenPush, 1);
    ASSERT_GT(p.wrongFrom, 0) << "the bug changes the result";
    ASSERT_FALSE(p.diff.equal);
    EXPECT_EQ(p.diff.insertion, p.wrongFrom) << p.report;
    EXPECT_NE(p.diff.what.find("missing flip of edge"), std::string::npos) << p.report;
    EXPECT_NE(p.report.find("after a flip, push both edges opposite the new point"),
              std::string::npos)
        << p.report;
}

TEST(AssignmentChecker, WrongOnEdgeSplitIsNamed) {
    const Planted p = plant(Bug::OnEdgeOneSide, 1);
    ASSERT_GT(p.bugAt, 0) << "the assignment has a point on an edge";
    ASSERT_FALSE(p.diff.equal);
    EXPECT_EQ(p.diff.insertion, p.bugAt) << p.report;
    EXPECT_NE(p.diff.what.find("point " + std::to_string(p.bugAt - 1) + " lies on edge"),
              std::string::npos)
        << p.report;
    EXPECT_NE(p.diff.what.find("which was not split"), std::string::npos) << p.report;
    EXPECT_NE(p.diff.what.find("splits the two triangles beside it"), std::string::npos);
}

TEST(AssignmentChecker, PointNotInsertedIsNamed) {
    const Planted p = plant(Bug::SkipPoint, 7);
    ASSERT_FALSE(p.diff.equal);
    EXPECT_EQ(p.diff.insertion, 7) << p.report;
    EXPECT_NE(p.diff.what.find("point 6 was not inserted"), std::string::npos) << p.report;
}

// An in-circle test with the wrong sign flips an edge whose opposite vertex is outside the
// circle; where the quadrilateral is not convex a triangle turns clockwise, but the cause is the
// flip, and that is what the checker names (edge, triangles, point), insertion by insertion.
TEST(AssignmentChecker, WrongInCircleSignIsNamedAsTheFlipNotTheClockwiseTriangle) {
    const TraceFile ref = assignmentReference();
    StudentTriangulator good(assignmentPoints(), Bug::None, 0);
    good.run();
    int tried = 0;
    for (int from = 2; from <= 38; ++from) {
        StudentTriangulator bad(assignmentPoints(), Bug::WrongInCircleSign, from);
        bad.run();
        const WrongFlip& w = bad.wrongFlip();
        if (bad.bugAt() != from || w.convex) continue;
        // The reported case: judged by the mesh alone, the first problem is a clockwise triangle.
        const std::size_t k = static_cast<std::size_t>(from);
        ASSERT_LE(k, bad.history().size());
        const MeshVerdict byMesh =
            checkStudentMesh(bad.history()[k - 1], good.history()[k - 1], ref.geometry, w.v, {});
        if (byMesh.reason.find("is clockwise") == std::string::npos) continue;
        ++tried;
        const TraceFile student = parse(bad.trace());
        const TraceDiff d = diffTraces(ref, student);
        ASSERT_FALSE(d.equal);
        EXPECT_EQ(d.insertion, from) << formatDiff(d, ref, student);
        const std::string expected =
            "flip of edge " + edgeName(w.a, w.b) + ", which was Delaunay (it should stay): point " +
            std::to_string(w.v) + " is outside the circle of triangle " +
            tripleText(canonical(w.b, w.a, w.d)) + ", across the edge from triangle " +
            tripleText(canonical(w.v, w.a, w.b));
        EXPECT_NE(d.what.find(expected), std::string::npos) << d.what << "\nexpected: " << expected;
        EXPECT_EQ(d.what.find("clockwise"), std::string::npos) << d.what;
        const std::string report = formatDiff(d, ref, student);
        EXPECT_NE(report.find("check the sign of your in-circle test"), std::string::npos)
            << report;
    }
    EXPECT_GT(tried, 0) << "no insertion of the assignment where the wrong sign turns a triangle";
}

// Op by op (a student in our order, who flips an edge our test kept): the student's flip is
// named, not the order.
TEST(AssignmentChecker, AFlipOfADelaunayEdgeIsNamedOpByOp) {
    const std::vector<Vec2> pts = testPoints();
    const TraceFile ref = ourTrace(pts);
    const auto n = static_cast<std::int32_t>(pts.size());
    TraceReplay replay;
    std::size_t at = 0, meshOps = 0;
    std::int32_t P = -1, A = -1, B = -1, D = -1;
    for (std::size_t i = 0; i < ref.ops.size() && at == 0; ++i) {
        const TraceOp& op = ref.ops[i];
        if (i > 30 && op.type == OpType::InCircleTest && op.sign == -1 && op.b >= 0) {
            // Corner a holds the new point P in (P, A, B); corner b holds D in (D, B, A).
            const auto& V = replay.V();
            P = V[*op.a], A = V[next(*op.a)], B = V[prev(*op.a)], D = V[*op.b];
            if (std::max({P, A, B, D}) < n) at = i;
        }
        replay.apply(op);
        meshOps += op.changesMesh() && at == 0;
    }
    ASSERT_GT(at, 0u);
    std::string text =
        minimalText(ref, [&](std::size_t m, nlohmann::json&) { return m < meshOps; });
    nlohmann::json flip;
    flip["op"] = "Flip";
    flip["triangles"] = {{*ref.ops[at].a / 3, P, A, D}, {*ref.ops[at].b / 3, D, B, P}};
    text += flip.dump() + "\n";
    const TraceFile student = parse(text);
    DiffOptions byOp;
    byOp.byOp = true;
    const TraceDiff d = diffTraces(ref, student, byOp);
    ASSERT_FALSE(d.equal);
    EXPECT_NE(
        d.what.find("the student's flip of edge " + edgeName(A, B) +
                    ", which was Delaunay (it should stay): point " + std::to_string(P) + " is "),
        std::string::npos)
        << formatDiff(d, ref, student, byOp);
    EXPECT_EQ(d.what.find("order"), std::string::npos) << d.what;
}

// A flip decided exactly: four cocircular points are "on" the circle, a point just outside it
// is "outside", a point inside is a right flip.
TEST(AssignmentChecker, AFlipIsJudgedByTheExactInCircleTest) {
    MeshGeometry g;
    g.points = {{0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 1.5}, {2.5, 2.5}};
    g.numInput = 6;
    // Edge 0-2 between (0, 2, 3) and (2, 0, 1), flipped to 1-3.
    const FlipMade cocircular{{0, 2}, {1, 3}};
    const auto on = checkFlipMade(cocircular, g, 3);
    ASSERT_TRUE(on);
    EXPECT_NE(on->reason.find("point 3 is on the circle of triangle (0, 1, 2)"), std::string::npos)
        << on->reason;
    EXPECT_NE(on->details.front().find("four points on one circle"), std::string::npos);
    // Point 5 far outside the circle of (0, 1, 2): not convex either.
    const auto outside = checkFlipMade({{0, 2}, {1, 5}}, g, 5);
    ASSERT_TRUE(outside);
    EXPECT_NE(outside->reason.find("point 5 is outside the circle of triangle (0, 1, 2)"),
              std::string::npos)
        << outside->reason;
    // Point 4 inside the circle of (0, 1, 2): a right flip.
    EXPECT_FALSE(checkFlipMade({{0, 2}, {1, 4}}, g, 4));
    // The ghost vertex has no position: nothing is judged.
    g.ghost = true;
    g.numInput = 5;
    EXPECT_FALSE(checkFlipMade({{0, 2}, {1, 5}}, g, 5));
}

// Another order of the edges to test (a queue, not a stack): the same triangles after every
// insertion. Op by op the runs differ, and the checker says it is the order, not a bug.
TEST(AssignmentChecker, AnotherFlipOrderIsNamedAsTheOrderOpByOp) {
    StudentTriangulator fifo(assignmentPoints(), Bug::None, 0, /*fifo=*/true);
    fifo.run();
    const TraceFile ref = assignmentReference(), student = parse(fifo.trace());
    const TraceDiff steps = diffTraces(ref, student);
    ASSERT_TRUE(steps.equal) << formatDiff(steps, ref, student);
    DiffOptions byOp;
    byOp.byOp = true;
    const TraceDiff d = diffTraces(ref, student, byOp);
    ASSERT_FALSE(d.equal) << "the queue changes the order of the flips";
    EXPECT_EQ(d.what.rfind("only the order differs: ", 0), 0u) << d.what;
    const std::string report = formatDiff(d, ref, student, byOp);
    EXPECT_NE(report.find("the same Delaunay triangulation"), std::string::npos) << report;
    EXPECT_NE(report.find("That is no bug"), std::string::npos) << report;
    // A real mistake later (this student pushes a split's edges in another order than ours
    // too): the order is named where it differs, and the insertion that is wrong after it.
    StudentTriangulator missed(assignmentPoints(), Bug::MissingFlip, 10);
    missed.run();
    const TraceFile wrong = parse(missed.trace());
    const TraceDiff m = diffTraces(ref, wrong, byOp);
    ASSERT_FALSE(m.equal);
    EXPECT_EQ(m.what.rfind("only the order differs at this insertion: ", 0), 0u) << m.what;
    const std::string said = formatDiff(m, ref, wrong, byOp);
    EXPECT_NE(said.find("the first one that does not: after inserting point 9 (insertion 10 of "
                        "38): not Delaunay at edge"),
              std::string::npos)
        << said;
    EXPECT_EQ(said.find("That is no bug"), std::string::npos) << said;
}

// A trace without its last line: named as such, never as "Finalize of point -1".
TEST(AssignmentChecker, ATraceWithoutFinalizeSaysSo) {
    StudentTriangulator student(assignmentPoints(), Bug::None, 0);
    student.run();
    std::string text = student.trace();
    text.erase(text.rfind("{\"op\": \"Finalize\""));
    const TraceFile ref = assignmentReference();
    // Op by op, a trace in our order (the independent student tests its edges in another).
    std::string ours = minimalText(ref);
    ours.erase(ours.rfind("{\"op\":\"Finalize\""));
    for (int mode = 0; mode < 3; ++mode) {
        DiffOptions o;
        o.byOp = mode == 1;
        o.corners = mode == 2;
        const TraceFile cut = parse(mode == 0 ? text : ours);
        const TraceDiff d = diffTraces(ref, cut, o);
        ASSERT_FALSE(d.equal);
        EXPECT_NE(d.what.find("trace ends before Finalize: end it with {\"op\": \"Finalize\"}"),
                  std::string::npos)
            << d.what;
        const std::string report = formatDiff(d, ref, cut, o);
        EXPECT_EQ(report.find("point -1"), std::string::npos) << report;
        EXPECT_EQ(report.find("vertex -1"), std::string::npos) << report;
        EXPECT_EQ(report.find("ends early"), std::string::npos) << report;
    }
}

// --all-ops and --corners compare op by op, and say so; --all-ops says why a trace written to
// the assignment (no walk or test lines) cannot pass.
TEST(AssignmentChecker, OptionsThatCannotPassOrImplyByOpSaySo) {
    StudentTriangulator student(assignmentPoints(), Bug::None, 0);
    student.run();
    const fs::path file = scratch() / "student_all_ops.jsonl";
    std::ofstream(file) << student.trace();
    Result r = dtlab("diff-trace --all-ops " + kAssignment + " " + file.string());
    EXPECT_EQ(r.status, 1) << r.out;
    EXPECT_EQ(r.out.rfind("note: --all-ops compares operation by operation: as with --by-op\n", 0),
              0u)
        << r.out;
    EXPECT_NE(r.out.find("note: --all-ops compares the walk steps and in-circle tests too, but " +
                         file.string() +
                         " has no LocateStep, Located or InCircleTest line (the assignment asks "
                         "only for the operations that change the mesh), so it cannot pass"),
              std::string::npos)
        << r.out;
    r = dtlab("diff-trace --by-op --all-ops " + kAssignment + " " + file.string());
    EXPECT_EQ(r.out.find("as with --by-op"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("so it cannot pass"), std::string::npos) << r.out;
    r = dtlab("diff-trace --corners " + kAssignment + " " + file.string());
    EXPECT_EQ(r.out.rfind("note: --corners compares operation by operation: as with --by-op\n", 0),
              0u)
        << r.out;
    EXPECT_EQ(r.out.find("cannot pass"), std::string::npos) << r.out;
    // Our own trace has every line: --all-ops passes it, with no note but the first.
    const TraceFile ref = assignmentReference();
    DiffOptions all;
    all.allOps = true;
    const TraceDiff d = diffTraces(ref, ref, all);
    EXPECT_TRUE(d.equal);
    ASSERT_EQ(d.notes.size(), 1u);
    r = dtlab("diff-trace " + kAssignment + " " + file.string());
    EXPECT_EQ(r.out.find("note:"), std::string::npos) << r.out;
    r = dtlab("diff-trace --help");
    EXPECT_NE(r.out.find("implies --by-op"), std::string::npos) << r.out;
}

TEST(TraceDiff, AStudentTraceWithoutAStepSaysWhatOursDoesNext) {
    // Only walk lines: no step at all. Ours goes on with Start, which inserts no point.
    const TraceFile ref = ourTrace({{0, 0}, {4, 0}, {0, 4}, {3, 3}});
    std::istringstream in("{\"op\": \"LocateStep\"}\n");
    const TraceFile student = parseTraceText(in, "s.jsonl");
    const TraceDiff d = diffTraces(ref, student);
    EXPECT_FALSE(d.equal);
    const std::string report = formatDiff(d, ref, student);
    EXPECT_NE(report.find("ours goes on with Start (ref.jsonl:1)"), std::string::npos) << report;
    EXPECT_EQ(report.find("point -1"), std::string::npos) << report;
}

// A trace larger than the memory the process may use: one line naming the file and the limit,
// exit status 2, never an abort. 2 million short lines (98 MB) each side, 600 MB of address
// space: the operations do not fit.
TEST(TraceDiff, ATraceBeyondTheMemoryLimitIsRefusedInOneLine) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "ASan reserves terabytes of address space: no limit can be set";
#endif
    const fs::path dir =
        fs::temp_directory_path() / ("dlab_big_trace_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string big = (dir / "big.jsonl").string();
    {
        std::ofstream out(big, std::ios::binary);
        const std::string line = "{\"op\":\"Flip\",\"triangles\":[[0,1,2,3],[1,2,3,4]]}\n";
        std::string block;
        for (int i = 0; i < 1000; ++i) block += line;
        for (int i = 0; i < 2000; ++i) out << block;
    }
    const auto r = testutil::runDtlab("diff-trace " + big + " " + big, "ulimit -v 600000; ");
    fs::remove_all(dir);
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
    EXPECT_NE(r.out.find(big + ":"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("not enough memory to hold the trace"), std::string::npos) << r.out;
}
