// Mesh readers: lines and fields, strict numbers, .ele/.neigh, OFF, OBJ, corner tables, JSON.
//
// [SECTION] Messages, lines and numbers
// [SECTION] Triangle .ele and .neigh
// [SECTION] OFF and OBJ
// [SECTION] Corner table as text
// [SECTION] JSON: corner table and Delaunator
// [SECTION] Files
#include "core/engine/mesh_read.h"

#include "core/engine/numbers.h"
#include "core/engine/predicates.h"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <utility>

namespace dlab {

namespace {

using LineNo = std::int64_t;

//-----------------------------------------------------------------------------------------------
// [SECTION] Messages, lines and numbers
//-----------------------------------------------------------------------------------------------

[[noreturn]] void fail(const std::string& name, LineNo line, const std::string& message) {
    const int l = line <= 0 ? 0 : (line > INT_MAX ? INT_MAX : static_cast<int>(line));
    throw InputError(name, l, message);
}

// A snippet of the input for a message: printable ASCII, at most 40 characters.
std::string quoted(std::string_view s) {
    std::string out = "'";
    for (std::size_t i = 0; i < s.size() && i < 40; ++i) {
        const auto c = static_cast<unsigned char>(s[i]);
        out += c >= 0x20 && c < 0x7f ? static_cast<char>(c) : '?';
    }
    if (s.size() > 40) out += "...";
    out += '\'';
    return out;
}

// Refuses what no mesh file holds before any parsing: nothing at all, or a NUL byte.
void checkText(std::string_view text, const std::string& name) {
    if (text.empty()) fail(name, 0, "empty file");
    if (text.size() > kMaxFileBytes) fail(name, 0, "input is larger than 2 GiB (kMaxFileBytes)");
    if (const void* nul = std::memchr(text.data(), 0, text.size())) {
        const auto at = static_cast<std::size_t>(static_cast<const char*>(nul) - text.data());
        const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(at), '\n');
        fail(name, line, "binary file (NUL byte at offset " + std::to_string(at) + ")");
    }
}

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\f' || c == '\v'; }

struct Line {
    std::vector<std::string_view> fields;  // at least one
    LineNo number = 0;
};

// Lines with content, the comment ('#' to the end of the line) removed, split at blanks.
// Line ends \n, \r\n or a lone \r; a UTF-8 byte-order mark at the start is skipped.
class Lines {
public:
    Lines(std::string_view text, std::string name) : m_text(text), m_name(std::move(name)) {
        if (m_text.substr(0, 3) == "\xEF\xBB\xBF") m_pos = 3;
    }
    const std::string& name() const { return m_name; }
    LineNo linesRead() const { return m_line; }
    std::size_t bytesLeft() const { return m_text.size() - m_pos; }

    bool next(Line& out) {
        constexpr std::size_t keep = 64;
        while (m_pos < m_text.size()) {
            std::size_t end = m_pos;
            while (end < m_text.size() && m_text[end] != '\n' && m_text[end] != '\r') ++end;
            std::string_view content = m_text.substr(m_pos, end - m_pos);
            m_pos = end;
            if (m_pos < m_text.size())
                m_pos +=
                    m_text[m_pos] == '\r' && m_pos + 1 < m_text.size() && m_text[m_pos + 1] == '\n'
                        ? 2
                        : 1;
            ++m_line;
            content = content.substr(0, content.find('#'));
            split(content, out.fields, keep);
            if (!out.fields.empty()) {
                out.number = m_line;
                return true;
            }
        }
        return false;
    }

    // The first line with content; `what` names it when there is none.
    Line first(const char* what) {
        Line line;
        if (!next(line)) fail(m_name, 0, std::string(what) + ": the file holds no data");
        return line;
    }

private:
    // At most `keep` fields; one more tells the caller that there are too many.
    static void split(std::string_view s, std::vector<std::string_view>& out, std::size_t keep) {
        out.clear();
        std::size_t i = 0;
        while (out.size() <= keep) {
            while (i < s.size() && isBlank(s[i])) ++i;
            if (i == s.size()) break;
            const std::size_t start = i;
            while (i < s.size() && !isBlank(s[i])) ++i;
            out.push_back(s.substr(start, i - start));
        }
    }

    std::string_view m_text;
    std::string m_name;
    std::size_t m_pos = 0;
    LineNo m_line = 0;
};

std::string_view dropPlus(std::string_view f) {
    if (f.size() >= 2 && f[0] == '+' && f[1] != '-' && f[1] != '+') f.remove_prefix(1);
    return f;
}

std::int64_t parseInt(std::string_view field, const std::string& name, LineNo line,
                      const std::string& what) {
    const std::string_view f = dropPlus(field);
    std::int64_t v = 0;
    const auto r = std::from_chars(f.data(), f.data() + f.size(), v);
    if (r.ec == std::errc::result_out_of_range)
        fail(name, line, what + " " + quoted(field) + " is out of range");
    if (r.ec != std::errc{} || r.ptr != f.data() + f.size())
        fail(name, line, "expected an integer for " + what + ", found " + quoted(field));
    return v;
}

// A vertex or corner id, 0-based after subtracting `base`; what the checker can name must fit
// the corner table's int32.
std::int32_t parseId(std::string_view field, std::int64_t base, const std::string& name,
                     LineNo line, const std::string& what) {
    const std::int64_t v = parseInt(field, name, line, what) - base;
    if (v < INT32_MIN + 1 || v > INT32_MAX)
        fail(name, line, what + " " + quoted(field) + " is out of range");
    return static_cast<std::int32_t>(v);
}

double parseReal(std::string_view field, const std::string& name, LineNo line,
                 const std::string& what) {
    const std::string_view f = dropPlus(field);
    double v = 0.0;
    const auto r = parseDouble(f.data(), f.data() + f.size(), v);
    if (r.ec == std::errc::invalid_argument || r.ptr != f.data() + f.size())
        fail(name, line, "malformed number " + quoted(field) + " for " + what);
    if (r.ec == std::errc::result_out_of_range)
        fail(name, line, "number " + quoted(field) + " for " + what + " is out of range");
    if (!std::isfinite(v)) fail(name, line, "non-finite " + what + " " + quoted(field));
    return v;
}

// A declared count, at most `limit`, and no more records than the rest of the text can hold
// (each at least minBytes long), so that reserving it is bounded by the input's size.
std::size_t parseCount(std::string_view field, std::size_t limit, const Lines& lines,
                       std::size_t minBytes, LineNo line, const std::string& what) {
    const std::int64_t n = parseInt(field, lines.name(), line, what);
    if (n < 0) fail(lines.name(), line, what + " must not be negative, found " + quoted(field));
    if (static_cast<std::uint64_t>(n) > limit)
        fail(lines.name(), line,
             what + " " + std::to_string(n) + " exceeds the maximum of " + std::to_string(limit));
    const auto count = static_cast<std::size_t>(n);
    if (count > 0 && (count - 1) * minBytes >= lines.bytesLeft() + 1)
        fail(lines.name(), line,
             what + " " + std::to_string(n) +
                 " is more than the rest of the file can hold: it is cut short, or the count is "
                 "wrong");
    return count;
}

void requireFields(const Line& line, std::size_t lo, std::size_t hi, const std::string& name,
                   const std::string& layout) {
    const std::size_t n = line.fields.size();
    if (n >= lo && n <= hi) return;
    const std::string count = n > hi && n == 65 ? "more than 64" : std::to_string(n);
    fail(name, line.number, count + " fields; expected " + layout);
}

[[noreturn]] void failExtra(const std::string& name, LineNo line, const char* what,
                            std::size_t count, LineNo header) {
    fail(name, line,
         std::string("extra ") + what + " line: the header on line " + std::to_string(header) +
             " declares " + std::to_string(count));
}

[[noreturn]] void failShort(const Lines& lines, const char* what, std::size_t count,
                            std::size_t found) {
    fail(lines.name(), lines.linesRead(),
         std::string("end of file: expected ") + std::to_string(count) + " " + what +
             " lines, found " + std::to_string(found));
}

// One triangle's three vertex ids from fields [from, from + 3).
void pushTriangle(Mesh& m, const Line& line, std::size_t from, std::int64_t base,
                  const std::string& name) {
    for (std::size_t k = 0; k < 3; ++k)
        m.V.push_back(parseId(line.fields[from + k], base, name, line.number, "vertex id"));
}

// The z of a 2D mesh: the first one read, then every other must equal it.
struct FlatZ {
    double z = 0.0;
    LineNo line = 0;
    void check(double z2, const std::string& name, LineNo at) {
        if (line == 0) {
            z = z2;
            line = at;
        } else if (z2 != z) {
            fail(name, at,
                 "z = " + shortest(z2) + " differs from z = " + shortest(z) + " on line " +
                     std::to_string(line) +
                     ": the mesh is 3D; only flat meshes (z 0 or one constant) are read");
        }
    }
    void warn(ImportedMesh& im) const {
        if (line != 0 && z != 0.0)
            im.warnings.push_back("every z is " + shortest(z) + ": read as a 2D mesh");
    }
};

}  // namespace

//-----------------------------------------------------------------------------------------------
// [SECTION] Triangle .ele and .neigh
//-----------------------------------------------------------------------------------------------

namespace {

// Reads the triangle id of a record line: consecutive from the first, which is 0 or 1.
void checkRecordId(const Line& line, std::size_t read, std::int64_t& base, const std::string& name,
                   const char* what) {
    const std::int64_t id = parseInt(line.fields[0], name, line.number, std::string(what) + " id");
    if (read == 0) {
        if (id != 0 && id != 1)
            fail(name, line.number,
                 std::string("first ") + what + " id must be 0 or 1, found " + std::to_string(id));
        base = id;
    } else if (id != base + static_cast<std::int64_t>(read)) {
        fail(name, line.number,
             std::string(what) + " id " + std::to_string(id) + " out of sequence: expected " +
                 std::to_string(base + static_cast<std::int64_t>(read)));
    }
}

// O from Triangle's neighbours: the corner of neighbour u that faces the same two vertices (the
// first corner of u when none does: the checker then names the mismatch).
void oppositesFromNeighbours(Mesh& m, const std::vector<std::int32_t>& neighbour) {
    m.O.assign(m.V.size(), kNone);
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        const std::int32_t u = neighbour[static_cast<std::size_t>(c)];
        if (u == kNone) continue;
        const std::int32_t a = m.V[next(c)], b = m.V[prev(c)];
        m.O[c] = 3 * u;
        for (std::int32_t k = 0; k < 3; ++k) {
            const std::int32_t e = 3 * u + k;
            const std::int32_t x = m.V[next(e)], y = m.V[prev(e)];
            if ((x == a && y == b) || (x == b && y == a)) m.O[c] = e;
        }
    }
}

}  // namespace

void parseNeigh(std::string_view text, const std::string& name, ImportedMesh& im) {
    checkText(text, name);
    Lines lines(text, name);
    const Line header = lines.first("no header line");
    requireFields(header, 1, 2, name, "<#triangles> [3]");
    const std::int64_t count = parseInt(header.fields[0], name, header.number, "triangle count");
    const std::int32_t triangles = im.mesh.numTriangles();
    if (count != triangles)
        fail(name, header.number,
             "declares " + std::to_string(count) + " triangles; the .ele has " +
                 std::to_string(triangles));
    if (header.fields.size() == 2 && header.fields[1] != "3")
        fail(name, header.number,
             "neighbours per triangle must be 3, found " + quoted(header.fields[1]));
    std::vector<std::int32_t> neighbour;
    neighbour.reserve(im.mesh.V.size());
    std::int64_t base = 0;
    for (Line line; lines.next(line);) {
        const std::size_t read = neighbour.size() / 3;
        if (read == static_cast<std::size_t>(triangles))
            failExtra(name, line.number, "triangle", read, header.number);
        requireFields(line, 4, 4, name, "4 (triangle id, then the neighbours across its 3 edges)");
        checkRecordId(line, read, base, name, "triangle");
        for (std::size_t k = 1; k <= 3; ++k) {
            std::int64_t u = parseInt(line.fields[k], name, line.number, "neighbour");
            if (u != -1) u -= im.indexBase;
            if (u < -1 || u >= triangles)
                fail(name, line.number,
                     "neighbour " + quoted(line.fields[k]) + " is not a triangle of the .ele (" +
                         std::to_string(triangles) + " triangles, -1 for none)");
            neighbour.push_back(static_cast<std::int32_t>(u));
        }
    }
    if (neighbour.size() != im.mesh.V.size())
        failShort(lines, "triangle", static_cast<std::size_t>(triangles), neighbour.size() / 3);
    oppositesFromNeighbours(im.mesh, neighbour);
    im.hasOpposites = true;
    im.inputs.push_back(name);
}

ImportedMesh parseEle(std::string_view ele, const std::string& eleName, const PointSet& nodes,
                      std::string_view neigh, const std::string& neighName) {
    checkText(ele, eleName);
    ImportedMesh im;
    im.format = "Triangle .ele";
    im.indexBase = nodes.indexBase;
    im.inputs = {nodes.path, eleName};
    im.mesh.G = nodes.points;
    Lines lines(ele, eleName);
    const Line header = lines.first("no header line");
    requireFields(header, 1, 3, eleName, "<#triangles> [<corners = 3> [<#attributes>]]");
    const std::size_t count =
        parseCount(header.fields[0], kMaxTriangles, lines, 8, header.number, "triangle count");
    if (header.fields.size() >= 2 && header.fields[1] != "3")
        fail(eleName, header.number,
             "corners per triangle must be 3, found " + quoted(header.fields[1]) +
                 " (higher-order triangles are not read)");
    const std::int64_t attributes =
        header.fields.size() == 3
            ? parseInt(header.fields[2], eleName, header.number, "attribute count")
            : 0;
    if (attributes < 0 || attributes > 60)
        fail(eleName, header.number,
             "attribute count must be 0 to 60, found " + quoted(header.fields[2]));
    const auto fields = static_cast<std::size_t>(4 + attributes);
    im.mesh.V.reserve(3 * count);
    std::int64_t base = 0;
    for (Line line; lines.next(line);) {
        const std::size_t read = im.mesh.V.size() / 3;
        if (read == count) failExtra(eleName, line.number, "triangle", count, header.number);
        requireFields(line, fields, fields, eleName,
                      std::to_string(fields) + " (triangle id, 3 vertex ids, attributes)");
        checkRecordId(line, read, base, eleName, "triangle");
        pushTriangle(im.mesh, line, 1, im.indexBase, eleName);
        for (std::size_t k = 4; k < fields; ++k)
            parseReal(line.fields[k], eleName, line.number, "attribute");
    }
    if (im.mesh.V.size() != 3 * count) failShort(lines, "triangle", count, im.mesh.V.size() / 3);
    im.mesh.O.assign(im.mesh.V.size(), kNone);
    if (!neighName.empty()) parseNeigh(neigh, neighName, im);
    return im;
}

//-----------------------------------------------------------------------------------------------
// [SECTION] OFF and OBJ
//-----------------------------------------------------------------------------------------------

namespace {

void readOffVertices(Lines& lines, std::size_t count, ImportedMesh& im, FlatZ& z) {
    const std::string& name = lines.name();
    im.mesh.G.reserve(count);
    Line line;
    while (im.mesh.G.size() < count) {
        if (!lines.next(line)) failShort(lines, "vertex", count, im.mesh.G.size());
        requireFields(line, 3, 3, name, "3 (x y z)");
        const double x = parseReal(line.fields[0], name, line.number, "x coordinate");
        const double y = parseReal(line.fields[1], name, line.number, "y coordinate");
        z.check(parseReal(line.fields[2], name, line.number, "z coordinate"), name, line.number);
        im.mesh.G.push_back({x, y});
    }
}

void readOffFaces(Lines& lines, std::size_t count, ImportedMesh& im) {
    const std::string& name = lines.name();
    im.mesh.V.reserve(3 * count);
    Line line;
    while (im.mesh.V.size() < 3 * count) {
        if (!lines.next(line)) failShort(lines, "face", count, im.mesh.V.size() / 3);
        const std::int64_t k = parseInt(line.fields[0], name, line.number, "corner count");
        if (k != 3)
            fail(name, line.number,
                 "a face of " + std::to_string(k) + " corners: only triangles are read");
        requireFields(line, 4, 8, name, "'3 a b c', optionally followed by a colour");
        pushTriangle(im.mesh, line, 1, 0, name);
        for (std::size_t f = 4; f < line.fields.size(); ++f)
            parseReal(line.fields[f], name, line.number, "colour component");
    }
    if (lines.next(line))
        fail(name, line.number, "extra line after the " + std::to_string(count) + " faces");
}

}  // namespace

ImportedMesh parseOff(std::string_view text, const std::string& name) {
    checkText(text, name);
    ImportedMesh im;
    im.format = "OFF";
    im.inputs = {name};
    Lines lines(text, name);
    Line line = lines.first("no OFF header");
    if (line.fields[0] != "OFF") fail(name, line.number, "the first line must be 'OFF'");
    line.fields.erase(line.fields.begin());
    if (line.fields.empty() && !lines.next(line))
        fail(name, lines.linesRead(), "no vertex and face counts after 'OFF'");
    requireFields(line, 2, 3, name, "'<#vertices> <#faces> [<#edges>]'");
    const std::size_t nv =
        parseCount(line.fields[0], kMaxPoints, lines, 6, line.number, "vertex count");
    const std::size_t nf =
        parseCount(line.fields[1], kMaxTriangles, lines, 8, line.number, "face count");
    if (line.fields.size() == 3) parseInt(line.fields[2], name, line.number, "edge count");
    FlatZ z;
    readOffVertices(lines, nv, im, z);
    readOffFaces(lines, nf, im);
    z.warn(im);
    im.mesh.O.assign(im.mesh.V.size(), kNone);
    return im;
}

namespace {

// One vertex reference of an OBJ face ("7", "7/2", "7//3", "-1/2/3"), 0-based; out-of-range
// references are kept for the checker to name.
std::int32_t objVertex(std::string_view ref, std::size_t vertices, const std::string& name,
                       LineNo line) {
    const std::string_view head = ref.substr(0, ref.find('/'));
    const std::int64_t v = parseInt(head, name, line, "vertex reference");
    const std::int64_t id = v < 0 ? static_cast<std::int64_t>(vertices) + v : v - 1;
    if (id < INT32_MIN + 1 || id > INT32_MAX)
        fail(name, line, "vertex reference " + quoted(ref) + " is out of range");
    return static_cast<std::int32_t>(id);
}

void objStatement(const Line& line, ImportedMesh& im, FlatZ& z, const std::string& name) {
    const std::string_view kw = line.fields[0];
    if (kw == "v") {
        requireFields(line, 3, 5, name, "'v x y [z [w]]'");
        if (im.mesh.G.size() == kMaxPoints)
            fail(name, line.number, "more than " + std::to_string(kMaxPoints) + " vertices");
        const double x = parseReal(line.fields[1], name, line.number, "x coordinate");
        const double y = parseReal(line.fields[2], name, line.number, "y coordinate");
        const double zz = line.fields.size() >= 4
                              ? parseReal(line.fields[3], name, line.number, "z coordinate")
                              : 0.0;
        z.check(zz, name, line.number);
        im.mesh.G.push_back({x, y});
    } else if (kw == "f") {
        if (line.fields.size() != 4)
            fail(name, line.number,
                 "a face of " + std::to_string(line.fields.size() - 1) +
                     " corners: only triangles are read");
        if (im.mesh.V.size() == 3 * kMaxTriangles)
            fail(name, line.number, "more than " + std::to_string(kMaxTriangles) + " faces");
        for (std::size_t k = 1; k <= 3; ++k)
            im.mesh.V.push_back(objVertex(line.fields[k], im.mesh.G.size(), name, line.number));
    } else if (!std::all_of(kw.begin(), kw.end(), [](char c) {
                   return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
               })) {
        fail(name, line.number, "not an OBJ statement: " + quoted(kw));
    }  // vt, vn, g, o, s, usemtl, mtllib, l, ...: not part of a 2D triangle mesh
}

}  // namespace

ImportedMesh parseObj(std::string_view text, const std::string& name) {
    checkText(text, name);
    ImportedMesh im;
    im.format = "OBJ";
    im.indexBase = 1;
    im.inputs = {name};
    Lines lines(text, name);
    FlatZ z;
    for (Line line; lines.next(line);) objStatement(line, im, z, name);
    if (im.mesh.G.empty()) fail(name, 0, "no vertex ('v' line)");
    z.warn(im);
    im.mesh.O.assign(im.mesh.V.size(), kNone);
    return im;
}

//-----------------------------------------------------------------------------------------------
// [SECTION] Corner table as text
//-----------------------------------------------------------------------------------------------

ImportedMesh parseCornerText(std::string_view text, const std::string& name) {
    checkText(text, name);
    ImportedMesh im;
    im.format = "corner table (text)";
    im.inputs = {name};
    Mesh& m = im.mesh;
    Lines lines(text, name);
    for (Line line; lines.next(line);) {
        const std::string_view kw = line.fields[0];
        if (kw == "g") {
            requireFields(line, 3, 3, name, "'g x y'");
            if (m.G.size() == kMaxPoints)
                fail(name, line.number, "more than " + std::to_string(kMaxPoints) + " vertices");
            m.G.push_back({parseReal(line.fields[1], name, line.number, "x coordinate"),
                           parseReal(line.fields[2], name, line.number, "y coordinate")});
        } else if (kw == "v" || kw == "o") {
            requireFields(line, 4, 4, name, "'" + std::string(kw) + " a b c'");
            std::vector<std::int32_t>& out = kw == "v" ? m.V : m.O;
            if (out.size() == 3 * kMaxTriangles)
                fail(name, line.number,
                     "more than " + std::to_string(kMaxTriangles) + " triangles");
            for (std::size_t k = 1; k <= 3; ++k)
                out.push_back(parseId(line.fields[k], 0, name, line.number,
                                      kw == "v" ? "vertex id" : "opposite corner"));
        } else {
            fail(name, line.number,
                 "expected 'g x y', 'v a b c' or 'o a b c', found " + quoted(kw));
        }
    }
    if (m.G.empty()) fail(name, lines.linesRead(), "no vertex ('g x y' line)");
    if (!m.O.empty() && m.O.size() != m.V.size())
        fail(name, lines.linesRead(),
             std::to_string(m.O.size() / 3) + " 'o' lines for " + std::to_string(m.V.size() / 3) +
                 " 'v' lines: give the O of every triangle or of none");
    im.hasOpposites = !m.O.empty();
    if (!im.hasOpposites) m.O.assign(m.V.size(), kNone);
    return im;
}

//-----------------------------------------------------------------------------------------------
// [SECTION] JSON: corner table and Delaunator
//-----------------------------------------------------------------------------------------------

namespace {

// The JSON that these two formats use, read strictly (RFC 8259): an object at the top, arrays
// of numbers or of pairs of numbers under the keys we read, any value under other keys.
class Json {
public:
    Json(std::string_view text, std::string name) : m_text(text), m_name(std::move(name)) {}
    const std::string& name() const { return m_name; }
    LineNo line() const { return m_line; }

    // At the end of a text that ends with its last line's end, the last line is to blame.
    [[noreturn]] void error(const std::string& what) const {
        const bool pastLastLine =
            m_pos >= m_text.size() && !m_text.empty() && m_text.back() == '\n';
        fail(m_name, m_line - (pastLastLine ? 1 : 0), what);
    }

    void ws() {
        while (m_pos < m_text.size()) {
            const char c = m_text[m_pos];
            if (c == '\n') ++m_line;
            if (c != ' ' && c != '\t' && c != '\n' && c != '\r') break;
            ++m_pos;
        }
    }
    char peek() {
        ws();
        return m_pos < m_text.size() ? m_text[m_pos] : '\0';
    }
    void expect(char c) {
        if (peek() != c) error(std::string("expected '") + c + "', found " + found());
        ++m_pos;
    }
    bool accept(char c) {
        if (peek() != c) return false;
        ++m_pos;
        return true;
    }
    std::string found() {
        if (peek() == '\0') return "the end of the file";
        return quoted(m_text.substr(m_pos, 12));
    }
    bool atEnd() { return peek() == '\0' && m_pos == m_text.size(); }

    std::string string() {
        expect('"');
        std::string out;
        while (m_pos < m_text.size() && m_text[m_pos] != '"') {
            const char c = m_text[m_pos++];
            if (static_cast<unsigned char>(c) < 0x20) error("control character inside a string");
            if (c == '\\') {
                if (m_pos == m_text.size()) break;
                const char e = m_text[m_pos++];
                if (e == 'u') {
                    if (m_pos + 4 > m_text.size()) error("cut-off \\u escape in a string");
                    m_pos += 4;
                    out += '?';
                    continue;
                }
                if (std::strchr("\"\\/bfnrt", e) == nullptr) error("bad escape in a string");
            }
            out += c;
        }
        if (m_pos == m_text.size()) error("unterminated string");
        ++m_pos;
        return out;
    }

    // A number token as written (validated by its user).
    std::string_view token() {
        ws();
        const std::size_t start = m_pos;
        while (m_pos < m_text.size() && std::strchr("+-.0123456789eE", m_text[m_pos]) != nullptr &&
               m_text[m_pos] != '\0')
            ++m_pos;
        if (m_pos == start) error("expected a number, found " + found());
        return m_text.substr(start, m_pos - start);
    }
    double real(const char* what) { return parseReal(token(), m_name, m_line, what); }
    std::int32_t id(const char* what) { return parseId(token(), 0, m_name, m_line, what); }

    void skipValue(int depth = 0) {
        if (depth > 64) error("values nested more than 64 deep");
        const char c = peek();
        if (c == '"') {
            string();
        } else if (c == '[' || c == '{') {
            ++m_pos;
            const char close = c == '[' ? ']' : '}';
            if (accept(close)) return;
            do {
                if (c == '{') {
                    string();
                    expect(':');
                }
                skipValue(depth + 1);
            } while (accept(','));
            expect(close);
        } else if (literal("true") || literal("false") || literal("null")) {
        } else {
            token();
        }
    }

    // Reads "[item, item, ...]", calling item() for each; at most `limit` items.
    template <class F>
    void array(const std::string& key, std::size_t limit, F item) {
        expect('[');
        if (accept(']')) return;
        std::size_t n = 0;
        do {
            if (++n > limit)
                error("\"" + key + "\" holds more than " + std::to_string(limit) + " values");
            item();
        } while (accept(','));
        expect(']');
    }

private:
    bool literal(std::string_view word) {
        if (m_text.substr(m_pos, word.size()) != word) return false;
        m_pos += word.size();
        return true;
    }

    std::string_view m_text;
    std::string m_name;
    std::size_t m_pos = 0;
    LineNo m_line = 1;
};

struct JsonArrays {
    std::vector<Vec2> G;
    std::vector<double> coords;
    std::vector<std::int32_t> V, O, triangles, halfedges;
    std::vector<std::string> seen;  // keys read, in order
    LineNo line(const std::string& key) const {
        const auto it = std::find(seen.begin(), seen.end(), key);
        return it == seen.end() ? 0 : lines[static_cast<std::size_t>(it - seen.begin())];
    }
    std::vector<LineNo> lines;  // where each key of `seen` was
    bool has(const std::string& key) const { return line(key) != 0; }
};

void readJsonMember(Json& j, const std::string& key, JsonArrays& a) {
    constexpr std::size_t kCorners = 3 * kMaxTriangles;
    if (key == "G") {
        j.array(key, kMaxPoints, [&] {
            j.expect('[');
            const double x = j.real("x coordinate");
            j.expect(',');
            const double y = j.real("y coordinate");
            j.expect(']');
            a.G.push_back({x, y});
        });
    } else if (key == "coords") {
        j.array(key, 2 * kMaxPoints, [&] { a.coords.push_back(j.real("coordinate")); });
    } else if (key == "V" || key == "triangles") {
        auto& out = key == "V" ? a.V : a.triangles;
        j.array(key, kCorners, [&] { out.push_back(j.id("vertex id")); });
    } else if (key == "O" || key == "halfedges") {
        auto& out = key == "O" ? a.O : a.halfedges;
        j.array(key, kCorners, [&] { out.push_back(j.id(key == "O" ? "corner" : "half-edge")); });
    } else {
        j.skipValue();
    }
}

JsonArrays readJsonArrays(Json& j) {
    JsonArrays a;
    j.expect('{');
    if (!j.accept('}')) {
        do {
            j.peek();  // the key's own line
            const LineNo at = j.line();
            const std::string key = j.string();
            if (std::find(a.seen.begin(), a.seen.end(), key) != a.seen.end())
                j.error("key \"" + key + "\" appears twice");
            a.seen.push_back(key);
            a.lines.push_back(at);
            j.expect(':');
            readJsonMember(j, key, a);
        } while (j.accept(','));
        j.expect('}');
    }
    if (!j.atEnd()) j.error("text after the end of the JSON object: " + j.found());
    return a;
}

void requireKey(const Json& j, const JsonArrays& a, const char* key, const char* format) {
    if (!a.has(key))
        fail(j.name(), 0, std::string("no \"") + key + "\" array (a " + format + " needs it)");
}

void requireMultipleOf3(const Json& j, const JsonArrays& a, const std::string& key,
                        std::size_t size) {
    if (size % 3 != 0)
        fail(j.name(), a.line(key),
             "\"" + key + "\" holds " + std::to_string(size) +
                 " values: not a multiple of 3 (three corners per triangle)");
}

ImportedMesh cornerTableFromJson(const Json& j, JsonArrays& a) {
    requireKey(j, a, "V", "corner table");
    requireMultipleOf3(j, a, "V", a.V.size());
    ImportedMesh im;
    im.format = "corner table (JSON)";
    im.mesh.G = std::move(a.G);
    im.mesh.V = std::move(a.V);
    im.hasOpposites = a.has("O");
    if (im.hasOpposites && a.O.size() != im.mesh.V.size())
        fail(j.name(), a.line("O"),
             "\"O\" holds " + std::to_string(a.O.size()) + " corners; \"V\" holds " +
                 std::to_string(im.mesh.V.size()));
    im.mesh.O =
        im.hasOpposites ? std::move(a.O) : std::vector<std::int32_t>(im.mesh.V.size(), kNone);
    return im;
}

// Most triangles clockwise with y up (their vertices in range and not collinear)?
bool mostlyClockwise(const Mesh& m) {
    std::int64_t balance = 0;
    for (std::int32_t c = 0; c + 2 < m.numCorners(); c += 3) {
        const auto in = [&](std::int32_t v) { return v >= 0 && v < m.numVertices(); };
        if (!in(m.V[c]) || !in(m.V[c + 1]) || !in(m.V[c + 2])) continue;
        balance += orient2d(m.G[m.V[c]], m.G[m.V[c + 1]], m.G[m.V[c + 2]]);
    }
    return balance < 0;
}

// Delaunator's arrays as a corner table: O[c] = prev(halfedges[next(c)]) (see mesh_read.h),
// then corners 1 and 2 swapped in every triangle when most triangles are clockwise.
ImportedMesh delaunatorFromJson(const Json& j, JsonArrays& a) {
    for (const char* key : {"coords", "triangles", "halfedges"})
        requireKey(j, a, key, "Delaunator output");
    if (a.coords.size() % 2 != 0)
        fail(j.name(), a.line("coords"),
             "\"coords\" holds " + std::to_string(a.coords.size()) + " numbers: not x, y pairs");
    requireMultipleOf3(j, a, "triangles", a.triangles.size());
    if (a.halfedges.size() != a.triangles.size())
        fail(j.name(), a.line("halfedges"),
             "\"halfedges\" holds " + std::to_string(a.halfedges.size()) +
                 " values; \"triangles\" holds " + std::to_string(a.triangles.size()));
    ImportedMesh im;
    im.format = "Delaunator JSON";
    im.hasOpposites = true;
    Mesh& m = im.mesh;
    for (std::size_t i = 0; i + 1 < a.coords.size(); i += 2)
        m.G.push_back({a.coords[i], a.coords[i + 1]});
    m.V = std::move(a.triangles);
    m.O.resize(m.V.size());
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        const std::int32_t h = a.halfedges[static_cast<std::size_t>(next(c))];
        m.O[c] = h >= 0 ? prev(h) : h;
    }
    if (!mostlyClockwise(m)) {
        im.warnings.push_back(
            "Delaunator half-edges read as O[c] = prev(halfedges[next(c)]); "
            "the triangles are counter-clockwise with y up, kept as they are");
        return im;
    }
    const auto swap12 = [](std::int32_t c) {
        return c < 0 || c % 3 == 0 ? c : (c % 3 == 1 ? c + 1 : c - 1);
    };
    std::vector<std::int32_t> V(m.V.size()), O(m.O.size());
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        V[static_cast<std::size_t>(swap12(c))] = m.V[c];
        O[static_cast<std::size_t>(swap12(c))] = m.O[c] >= m.numCorners() ? m.O[c] : swap12(m.O[c]);
    }
    m.V = std::move(V);
    m.O = std::move(O);
    im.warnings.push_back(
        "Delaunator half-edges read as O[c] = prev(halfedges[next(c)]); the "
        "triangles are clockwise with y up (counter-clockwise on a y-down "
        "screen): corners 1 and 2 of every triangle swapped");
    return im;
}

}  // namespace

ImportedMesh parseMeshJson(std::string_view text, const std::string& name) {
    checkText(text, name);
    Json j(text.substr(0, 3) == "\xEF\xBB\xBF" ? text.substr(3) : text, name);
    JsonArrays a = readJsonArrays(j);
    const bool corner = a.has("G") || a.has("V");
    const bool delaunator = a.has("coords") || a.has("triangles") || a.has("halfedges");
    if (corner == delaunator)
        fail(name, 0,
             corner ? "holds both a corner table (G, V) and Delaunator arrays (coords, triangles)"
                    : "neither a corner table (\"G\", \"V\", \"O\") nor Delaunator's output "
                      "(\"coords\", \"triangles\", \"halfedges\")");
    if (corner) requireKey(j, a, "G", "corner table");
    ImportedMesh im = corner ? cornerTableFromJson(j, a) : delaunatorFromJson(j, a);
    if (im.mesh.G.empty()) fail(name, 0, "no vertices");
    im.inputs = {name};
    return im;
}

//-----------------------------------------------------------------------------------------------
// [SECTION] Files
//-----------------------------------------------------------------------------------------------

namespace {

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
    return ext;
}

std::string readText(const std::string& path) { return readRegularFile(path, kMaxFileBytes); }

bool fileExists(const std::string& path) {
    std::error_code ec;
    return std::filesystem::exists(path, ec);
}

ImportedMesh readEleFile(const std::string& path, const std::string& pointsPath) {
    const std::filesystem::path p(path);
    const std::string stem = (p.parent_path() / p.stem()).string();
    const std::string nodePath = pointsPath.empty() ? stem + ".node" : pointsPath;
    if (pointsPath.empty() && !fileExists(nodePath))
        fail(path, 0, "no " + nodePath + " beside it for the points (or name one with --points)");
    const PointSet nodes = readPointsFile(nodePath);
    const std::string neighPath = stem + ".neigh";
    ImportedMesh im = parseEle(readText(path), path, nodes);  // one file's text at a time
    if (fileExists(neighPath)) parseNeigh(readText(neighPath), neighPath, im);
    return im;
}

}  // namespace

bool isMeshPath(const std::string& path) {
    const std::string ext = lowerExtension(path);
    return ext == ".ele" || ext == ".off" || ext == ".obj" || ext == ".corners" || ext == ".json";
}

ImportedMesh readMeshFile(const std::string& path) { return readMeshFile(path, {}); }

ImportedMesh readMeshFile(const std::string& path, const std::string& pointsPath) {
    const std::string ext = lowerExtension(path);
    if (ext == ".ele") return readEleFile(path, pointsPath);
    ImportedMesh im;
    if (ext == ".off")
        im = parseOff(readText(path), path);
    else if (ext == ".obj")
        im = parseObj(readText(path), path);
    else if (ext == ".corners")
        im = parseCornerText(readText(path), path);
    else if (ext == ".json")
        im = parseMeshJson(readText(path), path);
    else
        fail(path, 0,
             "not a mesh file: the mesh formats are .ele (with .node and .neigh), .off, .obj, "
             ".corners and .json (corner table or Delaunator)");
    if (pointsPath.empty()) return im;
    PointSet points = readPointsFile(pointsPath);
    if (points.points.size() != im.mesh.G.size())
        fail(pointsPath, 0,
             "holds " + std::to_string(points.points.size()) + " points; " + path + " has " +
                 std::to_string(im.mesh.G.size()) + " vertices");
    im.mesh.G = std::move(points.points);
    im.inputs.push_back(pointsPath);
    return im;
}

}  // namespace dlab
