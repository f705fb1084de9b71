// Trace diff: identical runs agree; a student's minimal trace (op + triangles) is understood; the
// first difference is found at the right op (wrong triangle, missing flip, truncation, extra ops,
// other corner layout, clockwise triangles); bad files fail with file:line; dtlab diff-trace
// exits 0 / 1 / 2.
#include "core/teaching/trace_diff.h"

#include "core/engine/generators.h"
#include "core/engine/io_read.h"
#include "core/teaching/lesson.h"
#include "core/teaching/trace.h"

#include "tests/run_dtlab.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>
#include <cstdio>
#include <filesystem>
#include <fstream>
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

TEST(TraceDiff, IdenticalRunsAgreeInBothModes) {
    for (Boundary b : {Boundary::Exact, Boundary::Super}) {
        InsertOptions opt;
        opt.boundary = b;
        const TraceFile ref = ourTrace(testPoints(), opt);
        for (bool corners : {false, true}) {
            DiffOptions o;
            o.corners = corners;
            const TraceDiff d = diffTraces(ref, ourTrace(testPoints(), opt), o);
            EXPECT_TRUE(d.equal) << d.what;
            std::size_t meshOps = 0;
            for (const TraceOp& op : ref.ops) meshOps += op.changesMesh();
            EXPECT_EQ(d.compared, meshOps);
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
        const TraceDiff d = diffTraces(ref, student);
        ASSERT_FALSE(d.equal) << toString(type);
        EXPECT_EQ(d.refOp, meshOpIndex(ref, k)) << toString(type);
        EXPECT_EQ(d.studentOp, k);
        EXPECT_NE(d.what.find(std::string("the triangles differ after ") + toString(type)),
                  std::string::npos)
            << d.what;
        const std::string report = formatDiff(d, ref, student);
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
    const TraceDiff d = diffTraces(ref, student);
    ASSERT_FALSE(d.equal);
    EXPECT_EQ(d.refOp, meshOpIndex(ref, k));
    EXPECT_NE(d.what.find("the reference does Flip, the student"), std::string::npos) << d.what;
}

TEST(TraceDiff, TruncatedAndOverlongStudentTraces) {
    const TraceFile ref = ourTrace(testPoints());
    const TraceFile cut =
        parse(minimalText(ref, [](std::size_t m, nlohmann::json&) { return m < 40; }));
    TraceDiff d = diffTraces(ref, cut);
    ASSERT_FALSE(d.equal);
    EXPECT_EQ(d.refOp, meshOpIndex(ref, 40));
    EXPECT_EQ(d.studentOp, cut.ops.size());
    EXPECT_NE(d.what.find("the student's trace ends early"), std::string::npos) << d.what;
    EXPECT_NE(formatDiff(d, ref, cut).find("(end of trace)"), std::string::npos);
    // The reference cut short instead: the student goes on.
    d = diffTraces(cut, parse(minimalText(ref)));
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
    const TraceDiff c = diffTraces(ref, clockwise);
    ASSERT_FALSE(c.equal);
    EXPECT_EQ(c.studentOp, 7u);
    EXPECT_NE(formatDiff(c, ref, clockwise).find("other orientation (clockwise)"),
              std::string::npos);
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
