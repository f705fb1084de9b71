// Input limits and the bugs that fuzzing found in the readers, each pinned by a test named after
// it (the inputs themselves are replayed from tests/fuzz/corpus/ by the FuzzReplay.* tests).
#include "core/engine/io_read.h"
#include "core/teaching/corner_expr.h"
#include "core/teaching/lesson.h"
#include "core/teaching/trace.h"
#include "core/teaching/trace_diff.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

using namespace dlab;

namespace {

// The error a trace line raises (fails the test when it reads).
InputError traceError(const std::string& line) {
    try {
        parseTraceLine(line, "t.jsonl", 7);
    } catch (const InputError& e) {
        return e;
    }
    ADD_FAILURE() << "no InputError for " << line;
    return InputError("", 0, "");
}

bool isOneLine(const std::string& s) { return s.find_first_of("\n\r") == std::string::npos; }

// One counter-clockwise triangle, no neighbours: enough for a corner expression to run on.
Mesh oneTriangle() {
    Mesh m;
    m.G = {{0, 0}, {1, 0}, {0, 1}};
    m.V = {0, 1, 2};
    m.O = {kNone, kNone, kNone};
    return m;
}

}  // namespace

//-----------------------------------------------------------------------------------------------
// Limits: kMaxPoints and kMaxFileBytes, refused before anything is allocated or read
//-----------------------------------------------------------------------------------------------

TEST(Limits, NodeHeaderClaiming2To31PointsInATinyFileFailsOnItsHeaderLine) {
    const std::string text = "2147483648 2 0 0\n0 0 0\n";
    try {
        parseNode(text, "claims.node");
        FAIL() << "read a file that claims 2^31 points";
    } catch (const InputError& e) {
        EXPECT_EQ(e.line(), 1);
        EXPECT_EQ(std::string(e.what()),
                  "claims.node:1: vertex count 2147483648 exceeds the maximum of 33554432 points "
                  "(kMaxPoints)");
    }
}

TEST(Limits, CountsUpToKMaxPointsMustStillFitTheBytesThatFollow) {
    // 2^25 is allowed as a count, but 2^25 vertex lines cannot fit in 8 bytes: refused before
    // the reserve() that the count would ask for (512 MiB).
    for (const auto& [text, parse] : {std::pair{std::string("33554432 2 0 0\n0 1 2\n"), &parseNode},
                                      std::pair{std::string("33554432\n0,1\n"), &parsePts}}) {
        try {
            parse(text, "claims");
            ADD_FAILURE() << "read " << text;
        } catch (const InputError& e) {
            EXPECT_EQ(e.line(), 1) << e.what();
            EXPECT_NE(std::string(e.what()).find("the header says 33554432"), std::string::npos)
                << e.what();
            EXPECT_NE(std::string(e.what()).find("only 1 line follows"), std::string::npos)
                << e.what();
        }
    }
    // One more than the maximum is refused by the count itself.
    EXPECT_THROW(parsePts("33554433\n0,1\n", "p.pts"), InputError);
}

TEST(Limits, AFileLargerThanKMaxFileBytesIsRefusedBeforeItIsRead) {
    // A sparse file: 2 GiB + 1 of holes costs no disk and, refused by its size, no memory.
    const auto path = std::filesystem::temp_directory_path() /
                      ("dlab_limits_" + std::to_string(getpid()) + ".csv");
    { std::ofstream(path) << "0,0\n"; }
    std::error_code ec;
    std::filesystem::resize_file(path, kMaxFileBytes + 1, ec);
    if (ec) {
        std::filesystem::remove(path);
        GTEST_SKIP() << "cannot make a sparse file here: " << ec.message();
    }
    try {
        readPointsFile(path.string());
        ADD_FAILURE() << "read a file over kMaxFileBytes";
    } catch (const InputError& e) {
        EXPECT_EQ(e.line(), 0);
        EXPECT_EQ(e.message(), "file is 2147483649 bytes; the maximum is 2147483648");
    }
    std::filesystem::remove(path);
}

//-----------------------------------------------------------------------------------------------
// Trace reader (readTrace / parseTraceLine): found by the fuzz_trace target and its seeds
//-----------------------------------------------------------------------------------------------

TEST(Regression, TraceErrorsAreInputErrorsNamingFileAndLine) {
    // Before: std::runtime_error with a hand-built prefix; now the same InputError as the point
    // readers, so callers (and dtlab) report every bad input the same way.
    std::istringstream in("{\"i\":0,\"op\":\"Start\"}\n\n{\"i\":1,\n");
    try {
        readTrace(in, "run.jsonl");
        FAIL() << "read a truncated JSON line";
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), "run.jsonl");
        EXPECT_EQ(e.line(), 3);
        EXPECT_EQ(std::string(e.what()).rfind("run.jsonl:3: not valid JSON", 0), 0u) << e.what();
    }
}

TEST(Regression, TraceFloatWhereAnIntegerBelongsIsRefusedNotConverted) {
    // Before: get<int>() on 1e300 converted a double out of int's range (undefined behaviour,
    // UBSan: "1e+300 is outside the range of representable values of type 'int'") and gave
    // sign = INT_MIN; the op index 1e300 did the same for size_t.
    for (const std::string& line : {std::string("{\"i\":0,\"op\":\"InCircleTest\",\"sign\":1e300}"),
                                    std::string("{\"i\":1e300,\"op\":\"Flip\"}"),
                                    std::string("{\"i\":0,\"op\":\"Flip\",\"a\":2.5}")}) {
        const InputError e = traceError(line);
        EXPECT_EQ(e.line(), 7);
        EXPECT_NE(e.message().find("must be an integer"), std::string::npos) << e.what();
    }
    EXPECT_NE(traceError("{\"i\":0,\"op\":\"InCircleTest\",\"sign\":2}")
                  .message()
                  .find("sign 2 is out of range"),
              std::string::npos);
}

TEST(Regression, TraceIntegersBeyondInt32AreRefusedNotTruncated) {
    // Before: corner 4294967297 was read as corner 1 and vertex 5000000000 as 705032704.
    EXPECT_NE(traceError("{\"i\":0,\"op\":\"Flip\",\"changes\":[[\"O\",4294967297,0,1]]}")
                  .message()
                  .find("corner"),
              std::string::npos);
    EXPECT_NE(traceError("{\"i\":0,\"op\":\"Flip\",\"vertex\":5000000000}")
                  .message()
                  .find("vertex 5000000000"),
              std::string::npos);
    EXPECT_NE(traceError("{\"i\":0,\"op\":\"Flip\",\"triangles\":[[0,1,2,-3]]}")
                  .message()
                  .find("out of range"),
              std::string::npos);
    // The limits themselves still read.
    const TraceRecord r = parseTraceLine(
        "{\"i\":0,\"op\":\"Flip\",\"vertex\":2147483647,\"changes\":[[\"V\",536870912,-1,"
        "2147483647]]}",
        "t", 1);
    EXPECT_EQ(r.vertex, 2147483647);
    ASSERT_EQ(r.changes.size(), 1u);
    EXPECT_EQ(r.changes[0].corner(), 536870912);
    EXPECT_EQ(r.changes[0].after, 2147483647);
}

// A value nested 200000 deep where an integer belongs: the error names it by its kind (quoting
// it whole would recurse once per level), in both trace readers.
TEST(Regression, TraceErrorsQuoteADeeplyNestedValueByItsKind) {
    const std::string deep = std::string(200000, '[') + std::string(200000, ']');
    const InputError e = traceError("{\"i\":0,\"op\":\"Flip\",\"a\":" + deep + "}");
    EXPECT_NE(e.message().find("a must be an integer, found an array of 1 values"),
              std::string::npos)
        << e.what();
    std::istringstream in("{\"op\":\"Flip\",\"changes\":[" + deep + "]}\n");
    try {
        parseTraceText(in, "s.jsonl");
        FAIL() << "read a change nested 200000 deep";
    } catch (const InputError& e2) {
        EXPECT_EQ(std::string(e2.what()),
                  "s.jsonl:1: a change is [\"V\" or \"O\", corner, before, after], not an array "
                  "of 1 values");
    }
}

TEST(Regression, TraceErrorQuotingAnOpNameWithANewlineStaysOneLine) {
    // Before: the unknown op was pasted raw into the message, so "Flip\nrm -rf" split it.
    const InputError e = traceError("{\"i\":0,\"op\":\"Flip\\nrm -rf\"}");
    EXPECT_TRUE(isOneLine(e.what())) << e.what();
    EXPECT_NE(e.message().find("unknown op"), std::string::npos) << e.what();
}

TEST(Regression, CornerExpressionErrorQuotingANewlineStaysOneLine) {
    // Before: the evaluation error quoted the source span raw ("G[9.n.\nn]" split the message).
    const Mesh m = oneTriangle();
    const auto e = CornerExpr::parse("G[9.n.\nn]");
    ASSERT_TRUE(e.has_value());
    const ExprResult r = e->evaluate(m);
    ASSERT_FALSE(r.ok());
    EXPECT_TRUE(isOneLine(r.error.message)) << r.error.message;
}

TEST(Regression, CornerExpressionWatchMessageWithANewlineStaysOneLine) {
    // Before: the watch's failure message pasted the watch text raw ("o(o(c)) ==\nzc").
    const Mesh m = oneTriangle();
    const auto w = CornerExpr::parse("n(c) ==\n p(c)");
    ASSERT_TRUE(w.has_value());
    const WatchReport rep = checkWatch(*w, m);
    EXPECT_FALSE(rep.ok);
    EXPECT_TRUE(isOneLine(rep.message)) << rep.message;
}

TEST(Regression, LessonTomlErrorQuotingANewlineStaysOneLine) {
    // Before: toml++'s own description ("saw 't\n'") reached the message raw.
    try {
        parseLesson("title = \"t\"\nflag = t\n", "bad.toml");
        ADD_FAILURE() << "a bad lesson was accepted";
    } catch (const LessonError& e) {
        EXPECT_TRUE(isOneLine(e.what())) << e.what();
        EXPECT_NE(std::string(e.what()).find("bad.toml:2"), std::string::npos) << e.what();
    }
}
