// Shared checks of the fuzz targets: reader error rules and the write/read round trip.
#include "tests/fuzz/fuzz_common.h"

#include "core/engine/io_write.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>

namespace dlab::fuzz {

void fail(const std::string& what, const std::string& detail) {
    std::fprintf(stderr, "fuzz property failed: %s\n", what.c_str());
    if (!detail.empty()) std::fprintf(stderr, "  %s\n", detail.c_str());
    std::fflush(stderr);
    std::abort();
}

std::int64_t countLines(std::string_view text) {
    std::int64_t lines = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '\n')
            ++lines;
        else if (text[i] == '\r' && !(i + 1 < text.size() && text[i + 1] == '\n'))
            ++lines;
    }
    // A last line without its end still counts.
    if (!text.empty() && text.back() != '\n' && text.back() != '\r') ++lines;
    return lines;
}

namespace {

bool isOneLine(std::string_view s) {
    for (const char c : s) {
        const auto u = static_cast<unsigned char>(c);
        if (u < 0x20 || u == 0x7f) return false;  // a newline, a tab, an escape sequence...
    }
    return true;
}

}  // namespace

void checkInputError(const InputError& e, std::string_view text, const std::string& name) {
    const std::string what = e.what();
    require(isOneLine(what), "an input error is one line of printable text", what);
    require(what.rfind(name + ":", 0) == 0, "an input error starts with the file name", what);
    require(e.file() == name, "InputError::file() is the name given", e.file());
    require(!e.message().empty(), "an input error says what is wrong", what);
    require(e.line() >= 0 && e.line() <= countLines(text),
            "an input error blames a line of the input",
            what + " (the input has " + std::to_string(countLines(text)) + " lines)");
}

std::string writePoints(const std::vector<Vec2>& points, std::string_view format, int indexBase) {
    if (format == "node") {
        std::ostringstream os;
        writeNode(os, points, indexBase);
        return os.str();
    }
    std::string out;
    if (format == "pts") out += std::to_string(points.size()) + "\n";
    for (const Vec2& p : points) {
        appendShortest(out, p.x);
        out += ',';
        appendShortest(out, p.y);
        out += '\n';
    }
    return out;
}

void checkPointSet(const PointSet& ps, const std::string& name, Reparse reparse,
                   std::string_view format) {
    require(ps.path == name, "PointSet::path is the name given", ps.path);
    require(ps.points.size() <= kMaxPoints, "at most kMaxPoints points");
    require(ps.indexBase == 0 || ps.indexBase == 1, "the index base is 0 or 1",
            std::to_string(ps.indexBase));
    for (const Vec2& p : ps.points) {
        require(std::isfinite(p.x) && std::isfinite(p.y), "every coordinate read is finite");
    }
    for (const std::string& w : ps.warnings) require(isOneLine(w), "a warning is one line", w);
    if (ps.points.empty()) return;  // an empty .node/.pts is legal, an empty XY file is not

    // Round trip: what we read, written in the same format, reads back bit for bit.
    const std::string again = writePoints(ps.points, format, ps.indexBase);
    requireSamePoints(
        mustRead(reparse, again, name, "points that were read can be written and read back"), ps,
        "the write/read round trip");
}

PointSet mustRead(Reparse parse, std::string_view text, const std::string& name, const char* what) {
    try {
        return parse(text, name);
    } catch (const InputError& e) {
        fail(what, e.what());
    }
}

void requireSamePoints(const PointSet& a, const PointSet& b, const std::string& what) {
    require(a.points.size() == b.points.size(), "same point count", what);
    require(a.indexBase == b.indexBase, "same index base", what);
    require(a.points.empty() ||
                std::memcmp(a.points.data(), b.points.data(), a.points.size() * sizeof(Vec2)) == 0,
            "same coordinates, bit for bit", what);
}

void checkReader(const std::uint8_t* data, std::size_t size, Reparse parse,
                 std::string_view format) {
    const std::string name = std::string("fuzz.") + std::string(format);
    const std::string_view text = asText(data, size);
    PointSet ps;
    try {
        ps = parse(text, name);
    } catch (const InputError& e) {
        checkInputError(e, text, name);
        return;
    }
    checkPointSet(ps, name, parse, format);
}

}  // namespace dlab::fuzz
