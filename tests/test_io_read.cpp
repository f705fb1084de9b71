// Point readers: every format and variant (.node bases, attributes, markers, comments, CRLF, BOM;
// CSV headers and separators; .pts), and every error with its line and "FILE:LINE:" prefix.
// Absurd counts must be refused before anything is allocated: this file replaces the global
// operator new/delete to record the largest request made while a check is armed.
#include "core/engine/io_read.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <new>
#include <random>
#include <string>

using namespace dlab;

//-----------------------------------------------------------------------------------------------
// Allocation probe
//-----------------------------------------------------------------------------------------------

namespace {
std::atomic<bool> gProbeArmed{false};
std::atomic<std::size_t> gProbeLargest{0};
}  // namespace

// malloc/free based, so they pair with each other under any sanitizer. Not inlined: GCC 12
// would otherwise see free() meet operator new and warn (-Wmismatched-new-delete).
[[gnu::noinline]] void* operator new(std::size_t n) {
    if (gProbeArmed.load(std::memory_order_relaxed)) {
        std::size_t seen = gProbeLargest.load(std::memory_order_relaxed);
        while (n > seen &&
               !gProbeLargest.compare_exchange_weak(seen, n, std::memory_order_relaxed)) {}
    }
    if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
    throw std::bad_alloc();
}
[[gnu::noinline]] void* operator new[](std::size_t n) { return ::operator new(n); }
[[gnu::noinline]] void operator delete(void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete[](void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete(void* p, std::size_t) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
// The nothrow forms too (std::stable_sort's buffer comes from one): every form that frees here
// must have allocated here.
[[gnu::noinline]] void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
    try {
        return ::operator new(n);
    } catch (...) {
        return nullptr;
    }
}
[[gnu::noinline]] void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
    return ::operator new(n, std::nothrow);
}
[[gnu::noinline]] void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

namespace {

// The largest single allocation made while f runs (f's exception, if any, is swallowed: the
// callers check the error separately).
template <class F>
std::size_t largestAllocation(F&& f) {
    gProbeLargest = 0;
    gProbeArmed = true;
    try {
        f();
    } catch (...) {}
    gProbeArmed = false;
    return gProbeLargest.load();
}

//-----------------------------------------------------------------------------------------------
// Helpers
//-----------------------------------------------------------------------------------------------

const std::string kData = std::string(DLAB_SOURCE_DIR) + "/tests/data/read/";

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Runs parse, expects an InputError blaming `line` (0: the whole file) whose what() is
// "NAME:LINE: message" ("NAME: message" for line 0) and whose message contains `fragment`.
template <class F>
void expectError(F&& parse, const std::string& name, int line, const std::string& fragment) {
    try {
        parse();
        ADD_FAILURE() << "no InputError; expected line " << line << ": " << fragment;
    } catch (const InputError& e) {
        EXPECT_EQ(e.line(), line) << e.what();
        EXPECT_EQ(e.file(), name);
        const std::string prefix =
            line > 0 ? name + ":" + std::to_string(line) + ": " : name + ": ";
        EXPECT_EQ(std::string(e.what()).rfind(prefix, 0), 0u)
            << "what() = " << e.what() << ", expected prefix " << prefix;
        EXPECT_NE(e.message().find(fragment), std::string::npos) << "message: " << e.message();
        EXPECT_EQ(std::string(e.what()), prefix + e.message());
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    } catch (const std::exception& e) {
        ADD_FAILURE() << "wrong exception type: " << e.what();
    }
}

void nodeError(const std::string& text, int line, const std::string& fragment) {
    SCOPED_TRACE(text);
    expectError([&] { parseNode(text, "in.node"); }, "in.node", line, fragment);
}
void xyError(const std::string& text, int line, const std::string& fragment) {
    SCOPED_TRACE(text);
    expectError([&] { parseXY(text, "in.csv"); }, "in.csv", line, fragment);
}
void ptsError(const std::string& text, int line, const std::string& fragment) {
    SCOPED_TRACE(text);
    expectError([&] { parsePts(text, "in.pts"); }, "in.pts", line, fragment);
}

// A fresh directory per process: ctest runs tests in parallel, possibly from several build trees.
std::filesystem::path scratchDir() {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("dlab_test_io_read_" + std::to_string(std::random_device{}()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

std::string writeBytes(const std::filesystem::path& dir, const std::string& name,
                       const std::string& bytes) {
    const auto p = dir / name;
    std::ofstream(p, std::ios::binary) << bytes;
    return p.string();
}

}  // namespace

//-----------------------------------------------------------------------------------------------
// Triangle .node
//-----------------------------------------------------------------------------------------------

TEST(ReadNode, BaseZeroAndOne) {
    const PointSet a = parseNode("3 2 0 0\n0 0 0\n1 1 0\n2 0 1\n", "a.node");
    EXPECT_EQ(a.indexBase, 0);
    EXPECT_EQ(a.path, "a.node");
    EXPECT_EQ(a.points, (std::vector<Vec2>{{0, 0}, {1, 0}, {0, 1}}));
    EXPECT_TRUE(a.warnings.empty());

    const PointSet b = parseNode("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n", "b.node");
    EXPECT_EQ(b.indexBase, 1);
    EXPECT_EQ(b.points, a.points);
}

TEST(ReadNode, AttributesMarkersCommentsAndShortHeaders) {
    const PointSet p = parseNode(
        "# comment line\n"
        "\n"
        "3 2 2 1  # header comment\n"
        "0  1.5 -2.5   0.1 7   1\n"
        "\t1\t+3\t4e1\t0 0\t0   # tabs\n"
        "   # an indented comment between vertices\n"
        "2 -0 .5 1e300 -1e300 1\n",
        "attr.node");
    EXPECT_EQ(p.indexBase, 0);
    ASSERT_EQ(p.points.size(), 3u);
    EXPECT_EQ(p.points[0], (Vec2{1.5, -2.5}));
    EXPECT_EQ(p.points[1], (Vec2{3, 40}));
    EXPECT_TRUE(std::signbit(p.points[2].x));
    EXPECT_EQ(p.points[2].y, 0.5);
    // Missing trailing header fields default to dimension 2, no attributes, no markers.
    EXPECT_EQ(parseNode("2\n1 5 6\n2 7 8\n", "n").points, (std::vector<Vec2>{{5, 6}, {7, 8}}));
    EXPECT_EQ(parseNode("2 2\n0 5 6\n1 7 8\n", "n").points, (std::vector<Vec2>{{5, 6}, {7, 8}}));
    EXPECT_EQ(parseNode("2 2 1\n0 5 6 9\n1 7 8 9\n", "n").points,
              (std::vector<Vec2>{{5, 6}, {7, 8}}));
    // Zero vertices: valid, with a warning.
    const PointSet none = parseNode("0 2 0 0\n", "n");
    EXPECT_TRUE(none.points.empty());
    EXPECT_EQ(none.warnings.size(), 1u);
}

TEST(ReadNode, LineEndingsAndByteOrderMark) {
    const std::vector<Vec2> want{{0.5, 1}, {2, 3}};
    for (const char* text :
         {"2 2 0 0\r\n0 0.5 1\r\n1 2 3\r\n",  // CRLF
          "2 2 0 0\r0 0.5 1\r1 2 3\r",        // old Mac: lone CR
          "\xEF\xBB\xBF"
          "2 2 0 0\n0 0.5 1\n1 2 3\n",                                         // UTF-8 BOM
          "\xEF\xBB\xBF# BOM, then a comment\r\n2 2 0 0\r\n0 0.5 1\r\n1 2 3",  // no final newline
          "2 2 0 0\n\n\n0 0.5 1\r\n\r\n1 2 3\n\n"}) {
        SCOPED_TRACE(text);
        EXPECT_EQ(parseNode(text, "n").points, want);
    }
    // Line numbers count every kind of line end.
    nodeError("2 2 0 0\r\n0 0 0\r1 x 0\n", 3, "malformed number 'x'");
    nodeError(
        "\xEF\xBB\xBF"
        "1 2 0 0\r\n\r\n0 0 nan\r\n",
        3, "non-finite");
}

TEST(ReadNode, CoordinatesAreBitExact) {
    const std::string text =
        "7 2 0 0\n"
        "0 0.1 -0.1\n"
        "1 1e-300 -1e-300\n"
        "2 -1.7976931348623157e+308 1.7976931348623157e308\n"
        "3 4.9406564584124654e-324 2.2250738585072009e-308\n"
        "4 5e-324 -5e-324\n"
        "5 0.30000000000000004 123456789012345678901234567890\n"
        "6 +2.5E+3 -0\n";
    const PointSet p = parseNode(text, "exact.node");
    ASSERT_EQ(p.points.size(), 7u);
    EXPECT_TRUE(sameBits(p.points[0].x, 0.1));
    EXPECT_TRUE(sameBits(p.points[0].y, -0.1));
    EXPECT_TRUE(sameBits(p.points[1].x, 1e-300));
    EXPECT_TRUE(sameBits(p.points[2].x, -DBL_MAX));
    EXPECT_TRUE(sameBits(p.points[2].y, DBL_MAX));
    EXPECT_TRUE(sameBits(p.points[3].x, std::numeric_limits<double>::denorm_min()));
    EXPECT_TRUE(sameBits(p.points[3].y, std::nextafter(DBL_MIN, 0.0)));  // largest subnormal
    EXPECT_TRUE(sameBits(p.points[4].y, -std::numeric_limits<double>::denorm_min()));
    EXPECT_TRUE(sameBits(p.points[5].x, 0.1 + 0.2));
    EXPECT_TRUE(sameBits(p.points[5].y, 1.2345678901234568e29));
    EXPECT_TRUE(sameBits(p.points[6].x, 2500.0));
    EXPECT_TRUE(sameBits(p.points[6].y, -0.0));
}

TEST(ReadNode, Errors) {
    nodeError("", 0, "empty file");
    nodeError("# only a comment\n\n   \n", 0, "no header line");
    // A NUL byte anywhere: binary, blamed on its line.
    nodeError(std::string("2 2 0 0\n0 0 0\n1 1\0 1\n", 20), 3,
              "binary file (NUL byte at offset 17)");
    nodeError(std::string("\0\0\0\0", 4), 1, "binary file");
    // Mostly non-text bytes, no NUL: binary, no single line to blame.
    nodeError(std::string(100, '\x01'), 0, "binary file");
    // Non-finite and out-of-range coordinates.
    nodeError("1 2 0 0\n0 nan 0\n", 2, "non-finite coordinate 'nan' for x coordinate");
    nodeError("1 2 0 0\n0 0 -inf\n", 2, "non-finite coordinate '-inf' for y coordinate");
    nodeError("1 2 0 0\n0 0 infinity\n", 2, "non-finite");
    nodeError("1 2 0 0\n0 1e999 0\n", 2, "out of the range of double");
    nodeError("1 2 0 0\n0 1e-999 0\n", 2, "out of the range of double");
    nodeError("1 2 1 0\n0 1 2 nan\n", 2, "non-finite value 'nan' for attribute 1");
    // Fewer vertex lines than the header says: caught at the header when the rest is too short
    // to hold them, else at the end of the file.
    nodeError("3 2 0 0\n0 0 0\n1 1 1\n", 1,
              "the header says 3 vertices but only 2 lines follow: the file is cut short");
    nodeError("3 2 0 0\n0 0.000000 0.0000\n1 1.000000 1.0000\n", 3,
              "end of file: expected 3 vertices");
    nodeError("3 2 0 0\n0 0.000000 0.0000\n1 1.000000 1.0000\n# trailing comment\n\n", 5,
              "found 2");
    // More vertex lines than the header says.
    nodeError("2 2 0 0\n0 0 0\n1 1 1\n2 2 2\n", 4, "extra vertex line");
    nodeError("0 2 0 0\n0 0 0\n", 2, "extra vertex line");
    // Absurd counts: refused at the header.
    nodeError("4000000000 2 0 0\n0 0 0\n", 1, "exceeds the maximum");
    nodeError("1e12 2 0 0\n0 0 0\n", 1, "expected an integer for vertex count");
    nodeError("99999999999999999999999999 2 0 0\n0 0 0\n", 1, "exceeds the maximum");
    nodeError("33554433 2 0 0\n0 0 0\n", 1, "exceeds the maximum");
    nodeError("33554432 2 0 0\n0 0 0\n", 1, "33554432 vertices but only 1 line follows");
    nodeError("-3 2 0 0\n0 0 0\n", 1, "must not be negative");
    nodeError("3.5 2 0 0\n0 0 0\n", 1, "expected an integer");
    // Header shape.
    nodeError("3 3 0 0\n0 0 0 0\n", 1, "dimension must be 2");
    nodeError("1 2 0 2\n0 0 0 0\n", 1, "boundary marker count must be 0 or 1");
    nodeError("1 2 -1 0\n0 0 0\n", 1, "attribute count");
    nodeError("1 2 0 0 0\n0 0 0\n", 1, "header has 5 fields");
    nodeError("1 2 2000000000 0\n0 0 0\n", 1, "attribute count");
    nodeError("1 2 1000000000 0\n0 0 0\n", 1, "too short to hold them");
    // Vertex indices: the first is 0 or 1, the rest consecutive.
    nodeError("3 2 0 0\n0 0 0\n2 1 1\n1 2 2\n", 3, "vertex index 2 out of sequence: expected 1");
    nodeError("3 2 0 0\n1 0 0\n2 1 1\n2 2 2\n", 4, "out of sequence: expected 3");
    nodeError("2 2 0 0\n5 0 0\n6 1 1\n", 2, "first vertex index must be 0 or 1");
    nodeError("2 2 0 0\n-1 0 0\n0 1 1\n", 2, "first vertex index must be 0 or 1");
    nodeError("2 2 0 0\n0.0 0 0\n1 1 1\n", 2, "expected an integer for vertex index");
    // Malformed numbers and missing fields.
    nodeError("2 2 0 0\n0 1.2.3 0\n1 1 1\n", 2, "trailing junk '.3'");
    nodeError("2 2 0 0\n0 0 0\n1 1 abc\n", 3, "malformed number 'abc' for y coordinate");
    nodeError("2 2 0 0\n0 0 0\n1 0x10 1\n", 3, "trailing junk 'x10'");
    nodeError("2 2 0 0\n0 0 0\n1 ++1 1\n", 3, "malformed number '++1'");
    nodeError("2 2 0 0\n0 1.5\n1 1 1\n", 2, "too few fields: expected 3 (index, x, y), found 2");
    nodeError("2 2 1 1\n0 1 2 3 1\n1 1.0 1.0 1.0\n", 3,
              "too few fields: expected 5 (index, x, y, 1 attribute, boundary marker)");
    nodeError("2 2 0 0\n0 1 2 3\n1 1 1\n", 2, "too many fields");
    nodeError("1 2 0 1\n0 1 2 x\n", 2, "expected an integer for boundary marker");
}

TEST(ReadNode, AbsurdCountsAllocateNothing) {
    // Each of these would need gigabytes if the header were trusted.
    for (const std::string& text : std::vector<std::string>{
             "4000000000 2 0 0\n0 0 0\n", "1e12 2 0 0\n0 0 0\n", "33554432 2 0 0\n0 0 0\n",
             "33554432 2 0 1\n" + std::string(1000, '#') + "\n0 0 0 0\n",
             "1 2 1000000000 1\n0 0 0\n"}) {
        SCOPED_TRACE(text.substr(0, 30));
        EXPECT_THROW(parseNode(text, "big.node"), InputError);
        EXPECT_LT(largestAllocation([&] { parseNode(text, "big.node"); }), std::size_t{64} << 10);
    }
    for (const std::string text : {"4000000000\n0,0\n", "33554432\n0,0\n1,1\n", "1e12\n0,0\n"}) {
        SCOPED_TRACE(text);
        EXPECT_THROW(parsePts(text, "big.pts"), InputError);
        EXPECT_LT(largestAllocation([&] { parsePts(text, "big.pts"); }), std::size_t{64} << 10);
    }
    // The probe works: an honest file of 10000 points does reserve for all of them.
    std::string honest = "10000 2 0 0\n";
    for (int i = 0; i < 10000; ++i) honest += std::to_string(i) + " " + std::to_string(i) + " 0\n";
    EXPECT_GE(largestAllocation([&] { parseNode(honest, "ok.node"); }), 10000 * sizeof(Vec2));
}

//-----------------------------------------------------------------------------------------------
// XY / CSV
//-----------------------------------------------------------------------------------------------

TEST(ReadXY, WithAndWithoutHeader) {
    const std::vector<Vec2> want{{1, 2}, {3.5, -4}};
    const PointSet bare = parseXY("1,2\n3.5,-4\n", "a.csv");
    EXPECT_EQ(bare.points, want);
    EXPECT_TRUE(bare.warnings.empty());
    EXPECT_EQ(bare.indexBase, 0);

    const PointSet header = parseXY("x,y\n1,2\n3.5,-4\n", "b.csv");
    EXPECT_EQ(header.points, want);
    ASSERT_EQ(header.warnings.size(), 1u);
    EXPECT_NE(header.warnings[0].find("header line 1"), std::string::npos);

    // Named columns in any order and number, any case, quoted; other columns not checked.
    EXPECT_EQ(parseXY("id,x,y\n7,1,2\n8,3.5,-4\n", "c.csv").points, want);
    EXPECT_EQ(parseXY("Y,label,X\n2,a,1\n-4,b,3.5\n", "d.csv").points, want);
    EXPECT_EQ(parseXY("\"x\",\"y\",\"z\"\n1,2,zzz\n3.5,-4,\n", "e.csv").points, want);
    // Two columns with other names: x then y. Names may start like inf/nan.
    EXPECT_EQ(parseXY("lon,lat\n1,2\n3.5,-4\n", "f.csv").points, want);
    EXPECT_EQ(parseXY("info;nanos\n1;2\n3.5;-4\n", "f.csv").points, want);
    EXPECT_EQ(parseXY("x,y,\n1,2,\n3.5,-4,\n", "f.csv").points,
              want);  // spreadsheets' trailing separators
    // Separators: ';' (with header), blanks/tabs.
    EXPECT_EQ(parseXY("x;y\n1;2\n3.5;-4\n", "g.csv").points, want);
    EXPECT_EQ(parseXY("id;y;x\n1;2;1\n2;-4;3.5\n", "h.csv").points, want);
    EXPECT_EQ(parseXY("1;2\n3.5 ; -4\n", "i.csv").points, want);
    EXPECT_EQ(parseXY("1 2\n3.5\t \t-4\n", "j.xy").points, want);
    EXPECT_EQ(parseXY("x y\n1 2\n3.5 -4\n", "k.xy").points, want);
    EXPECT_EQ(parseXY(" 1 , 2 \n 3.5,-4 # comment\n", "l.csv").points, want);
    // CRLF, BOM, comments.
    EXPECT_EQ(parseXY("\xEF\xBB\xBF# points\r\nx,y\r\n1,2\r\n\r\n3.5,-4\r\n", "m.csv").points,
              want);
}

TEST(ReadXY, Errors) {
    xyError("", 0, "empty file");
    xyError("# nothing\n\n", 0, "no data");
    xyError("x,y\n# no rows\n", 1, "no points after the header");
    xyError(std::string("1,2\n3,\0\n", 8), 2, "binary file");
    // Three bare numeric columns are refused, pointing at a header.
    xyError("1,2,3\n4,5,6\n", 1, "add a header line naming the 'x' and 'y' columns");
    // Missing y, malformed numbers, non-finite values.
    xyError("1,2\n3,\n", 2, "missing y coordinate (empty field)");
    xyError("1,2\n3\n", 2, "1 field separated by ','");
    xyError("1 2\n3\n", 2, "1 field separated by spaces/tabs");
    xyError("1,2\n1.2.3,4\n", 2, "trailing junk '.3'");
    xyError("1,2\n1,abc\n", 2, "malformed number 'abc' for y coordinate");
    xyError("1,2\nnan,4\n", 2, "non-finite coordinate 'nan' for x coordinate");
    xyError("1,2\n4,inf\n", 2, "non-finite coordinate 'inf' for y coordinate");
    xyError("1,2\n4,-1e400\n", 2, "out of the range of double");
    // Decimal commas with ';' get a hint, on the first line too (not taken for a header).
    xyError("1,5;2,5\n3,5;4,5\n", 1, "decimal commas are not supported");
    xyError("x;y\n1,5;2,5\n", 2, "decimal commas are not supported");
    // A first line of numbers gone wrong is bad data, not a header to skip silently.
    xyError("1.2.3,4.5.6\n7,8\n", 1, "trailing junk '.3'");
    xyError("-.5e,2\n3,4\n", 1, "trailing junk 'e'");
    // Rows must match the header.
    xyError("id,x,y\n1,2,3\n4,5\n", 3,
            "2 fields separated by ','; expected 3 as in the header on line 1");
    xyError("a,b,c\n1,2,3\n", 1, "header 'a,b,c' has 3 columns");
    xyError("x,y\n1,2,3\n", 2, "3 fields");
    // A count line first suggests .pts.
    xyError("2\n1,2\n3,4\n", 1, "Rossignac's .pts format");
    // Mixed words and numbers on the first line: bad data, not a header.
    xyError("x,2\n1,2\n", 1, "malformed number 'x'");
}

//-----------------------------------------------------------------------------------------------
// Rossignac .pts
//-----------------------------------------------------------------------------------------------

TEST(ReadPts, Formats) {
    const std::vector<Vec2> want{{1, 2}, {3.5, -4}};
    EXPECT_EQ(parsePts("2\n1,2\n3.5,-4\n", "a.pts").points, want);
    EXPECT_EQ(parsePts("2\r\n1 2\r\n3.5\t-4\r\n", "b.pts").points, want);
    EXPECT_EQ(parsePts("# saved by savePts\n2\n1,2,0\n3.5,-4,0\n", "c.pts").points, want);
    const PointSet z = parsePts("2\n1,2,0\n3.5,-4,7\n", "d.pts");
    EXPECT_EQ(z.points, want);
    ASSERT_EQ(z.warnings.size(), 1u);
    EXPECT_NE(z.warnings[0].find("line 3"), std::string::npos);
    const PointSet none = parsePts("0\n", "e.pts");
    EXPECT_TRUE(none.points.empty());
    EXPECT_EQ(none.warnings.size(), 1u);
}

TEST(ReadPts, Errors) {
    ptsError("", 0, "empty file");
    ptsError("#\n", 0, "no point count");
    ptsError("2,3\n1,2\n", 1, "the first line must be the point count alone");
    ptsError("2 3\n1,2\n", 1, "the first line must be the point count alone");
    ptsError("x\n1,2\n", 1, "expected an integer for point count");
    ptsError("4000000000\n1,2\n", 1, "exceeds the maximum");
    ptsError("1e12\n1,2\n", 1, "expected an integer");
    ptsError("3\n1,2\n3,4\n", 1, "says 3 points but only 2 lines follow");
    ptsError("3\n1.000000,2.000000\n3.000000,4.000000\n", 3, "end of file: expected 3 points");
    ptsError("1\n1,2\n3,4\n", 3, "extra point line");
    ptsError("2\n1,2\n3,4,5,6\n", 3, "4 fields separated by ','");
    ptsError("2\n1,2\n3.0000\n", 3, "1 field separated by spaces/tabs");
    ptsError("2\n1,2\n3,\n", 3, "missing y coordinate");
    ptsError("2\n1,2\n3,nan\n", 3, "non-finite coordinate");
    ptsError("2\n1,2\n3,4,inf\n", 3, "non-finite coordinate 'inf' for z coordinate");
    ptsError("2\n1,2\n1.2.3,4\n", 3, "trailing junk");
    ptsError(std::string("2\n1,2\n\0", 7), 3, "binary file");
}

//-----------------------------------------------------------------------------------------------
// Files
//-----------------------------------------------------------------------------------------------

TEST(ReadFile, FixturesByExtension) {
    const PointSet node = readPointsFile(kData + "base1_markers.node");
    EXPECT_EQ(node.indexBase, 1);
    EXPECT_EQ(node.points, (std::vector<Vec2>{{0, 0}, {1, 0}, {1, 1}, {0.25, 0.75}}));
    EXPECT_TRUE(node.warnings.empty());

    const PointSet csv = readPointsFile(kData + "crlf_bom.csv");
    EXPECT_EQ(csv.points, (std::vector<Vec2>{{0.5, 1.5}, {-2, 3e-5}, {1e300, -0.1}}));
    EXPECT_EQ(csv.warnings.size(), 1u);  // the header

    EXPECT_EQ(readPointsFile(kData + "semicolon.csv").points,
              (std::vector<Vec2>{{1.5, 2.5}, {4, -1}}));
    EXPECT_EQ(readPointsFile(kData + "sample.pts").points,
              (std::vector<Vec2>{{0.5, 0.25}, {1, 2}, {-3, 4}}));

    // No extension: sniffed, with a warning saying so.
    const PointSet sniffed = readPointsFile(kData + "sniffed_node");
    EXPECT_EQ(sniffed.points, (std::vector<Vec2>{{0, 0}, {1, 0}, {0, 1}}));
    ASSERT_FALSE(sniffed.warnings.empty());
    EXPECT_NE(sniffed.warnings[0].find("Triangle .node"), std::string::npos);

    expectError([&] { readPointsFile(kData + "empty.csv"); }, kData + "empty.csv", 0, "empty file");
}

TEST(ReadFile, ErrorsAndSniffing) {
    const auto dir = scratchDir();
    // Missing file, a directory.
    const std::string missing = (dir / "missing.node").string();
    expectError([&] { readPointsFile(missing); }, missing, 0, "cannot open file");
    const std::string asDir = (dir / "folder.csv").string();
    std::filesystem::create_directories(asDir);
    expectError([&] { readPointsFile(asDir); }, asDir, 0, "directory");
    // Binary content with a NUL, and an image-like file.
    const std::string bin =
        writeBytes(dir, "bin.node", std::string("3 2 0 0\n0 0 0\n\x89PNG\0\0\x1a", 21));
    expectError([&] { readPointsFile(bin); }, bin, 3, "binary file");
    std::string noise;
    for (int i = 0; i < 5000; ++i) noise += static_cast<char>(0x80 + (i * 7) % 0x40);
    const std::string img = writeBytes(dir, "noise.pts", noise);
    expectError([&] { readPointsFile(img); }, img, 0, "binary file");
    // Errors inside a file carry the path and line.
    const std::string bad = writeBytes(dir, "bad.csv", "x,y\n1,2\n3,oops\n");
    expectError([&] { readPointsFile(bad); }, bad, 3, "malformed number 'oops'");
    // Extensions are case-insensitive; .xy/.txt/.dat are XY.
    EXPECT_EQ(readPointsFile(writeBytes(dir, "upper.NODE", "1 2 0 0\n0 5 6\n")).points,
              (std::vector<Vec2>{{5, 6}}));
    EXPECT_EQ(readPointsFile(writeBytes(dir, "p.dat", "5 6\n")).points,
              (std::vector<Vec2>{{5, 6}}));
    // Sniffing: .pts shape, XY shape.
    const PointSet pts = readPointsFile(writeBytes(dir, "p.points", "2\n1,2\n3,4\n"));
    EXPECT_EQ(pts.points, (std::vector<Vec2>{{1, 2}, {3, 4}}));
    EXPECT_NE(pts.warnings[0].find("Rossignac .pts"), std::string::npos);
    const PointSet xy = readPointsFile(writeBytes(dir, "p", "1 2\n3 4\n"));
    EXPECT_EQ(xy.points, (std::vector<Vec2>{{1, 2}, {3, 4}}));
    EXPECT_NE(xy.warnings[0].find("XY"), std::string::npos);
    std::filesystem::remove_all(dir);
}

//-----------------------------------------------------------------------------------------------
// Quoted numbers, UTF-16 text, NUL bytes in any file read
//-----------------------------------------------------------------------------------------------

TEST(ReadXY, QuotedNumbersReadLikeAQuotedHeader) {
    const PointSet header = parseXY("\"x\",\"y\"\n\"0\",\"1.5\"\n'2', ' -3 '\n", "q.csv");
    ASSERT_EQ(header.points.size(), 2u);
    EXPECT_EQ(header.points[0], (Vec2{0, 1.5}));
    EXPECT_EQ(header.points[1], (Vec2{2, -3}));
    const PointSet bare = parseXY("\"1\",\"2\"\n\"3\",\"4\"\n", "q.csv");
    ASSERT_EQ(bare.points.size(), 2u);
    EXPECT_EQ(bare.points[1], (Vec2{3, 4}));
    // A quote left open is still a malformed number.
    xyError("\"1,2\n3,4\n", 1, "malformed number '\"1'");
}

TEST(ReadFile, Utf16TextIsNamedAsSuch) {
    const auto dir = scratchDir();
    auto utf16le = [](const std::string& s) {
        std::string out;
        for (char c : s) out += std::string{c, '\0'};
        return out;
    };
    const std::string bom = writeBytes(dir, "bom.csv", "\xff\xfe" + utf16le("x,y\r\n0,0\r\n"));
    expectError([&] { readPointsFile(bom); }, bom, 0, "the file is UTF-16 text (little-endian)");
    const std::string bare = writeBytes(dir, "bare.xy", utf16le("0 0\n1 0\n0 1\n"));
    expectError([&] { readPointsFile(bare); }, bare, 0, "save it as UTF-8");
    const std::string big = writeBytes(dir, "big.json", "\xfe\xff" + std::string("\0{", 2));
    expectError([&] { readRegularFile(big, 1 << 20); }, big, 0, "UTF-16 text (big-endian)");
    // In memory too (the parsers' own check).
    xyError(utf16le("0,0\n1,1\n"), 0, "UTF-16");
    std::filesystem::remove_all(dir);
}

TEST(ReadFile, ANulStopsTheReadingAtItsChunk) {
    // A sparse file: four bytes of text, then 256 MiB of holes (NULs on reading). Every reader
    // refuses it at the first chunk instead of reading it whole.
    const auto dir = scratchDir();
    const std::string sparse = writeBytes(dir, "sparse.json", "{}\n ");
    std::filesystem::resize_file(sparse, std::uintmax_t{256} << 20);
    std::size_t chunks = 0;
    expectError(
        [&] { readRegularFileChunks(sparse, std::size_t{1} << 30, [&](auto) { ++chunks; }); },
        sparse, 0, "binary file (NUL byte at offset 4)");
    EXPECT_EQ(chunks, 1u);
    expectError([&] { readRegularFile(sparse, std::size_t{1} << 30); }, sparse, 0,
                "binary file (NUL byte at offset 4)");
    std::filesystem::remove_all(dir);
}
