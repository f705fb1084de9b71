// Point-set readers: file loading, binary sniffing, line/field splitting, strict numbers, formats.
//
// [SECTION] Messages and errors
// [SECTION] Text checks (size, empty, binary)
// [SECTION] Lines and fields
// [SECTION] Numbers
// [SECTION] Triangle .node
// [SECTION] XY / CSV
// [SECTION] Rossignac .pts
// [SECTION] Files and format sniffing
#include "core/engine/io_read.h"

#include "core/engine/numbers.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <new>
#include <system_error>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace dlab {

namespace {

using LineNo = std::int64_t;  // 64-bit so that counting the lines of any buffer cannot overflow

//-----------------------------------------------------------------------------------------------
// [SECTION] Messages and errors
//-----------------------------------------------------------------------------------------------

// Messages quote the input, and the input may be anything: escape what could break the one-line
// what() or a terminal, and shorten long snippets. High bytes are kept for file names (UTF-8
// paths are common) but escaped in snippets of content (there they are usually garbage).
std::string printable(std::string_view s, std::size_t maxLen, bool keepHighBytes) {
    std::string out;
    const std::size_t n = std::min(s.size(), maxLen);
    out.reserve(n + 3);
    for (std::size_t i = 0; i < n; ++i) {
        const auto c = static_cast<unsigned char>(s[i]);
        if ((c >= 0x20 && c < 0x7f) || (keepHighBytes && c >= 0x80)) {
            out += static_cast<char>(c);
        } else {
            static constexpr char kHex[] = "0123456789ABCDEF";
            out += "\\x";
            out += kHex[c >> 4];
            out += kHex[c & 15];
        }
    }
    if (s.size() > maxLen) out += "...";
    return out;
}

// Built by appending: "'" + std::string trips GCC 12's -Wrestrict false positive at -O3.
std::string quoted(std::string_view s) {
    std::string out = "'";
    out += printable(s, 40, false);
    out += '\'';
    return out;
}

std::string formatWhat(const std::string& file, int line, const std::string& message) {
    std::string out = printable(file, 4096, true);
    if (line > 0) out += ":" + std::to_string(line);
    out += ": ";
    out += printable(message, 4096, true);
    return out;
}

[[noreturn]] void fail(const std::string& name, LineNo line, std::string message) {
    const int l = line <= 0 ? 0 : (line > INT_MAX ? INT_MAX : static_cast<int>(line));
    throw InputError(name, l, std::move(message));
}

}  // namespace

InputError::InputError(std::string file, int line, std::string message)
    : std::runtime_error(formatWhat(file, line, message)),
      m_file(std::move(file)),
      m_line(line),
      m_message(std::move(message)) {}

namespace {

//-----------------------------------------------------------------------------------------------
// [SECTION] Text checks (size, empty, binary)
//-----------------------------------------------------------------------------------------------

constexpr std::size_t kBinarySniffBytes = std::size_t{1} << 16;

// 1-based line of a byte offset, counting \n, \r\n and lone \r as line ends like LineReader.
LineNo lineOfOffset(std::string_view text, std::size_t offset) {
    LineNo line = 1;
    for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
        if (text[i] == '\n')
            ++line;
        else if (text[i] == '\r' && !(i + 1 < text.size() && text[i + 1] == '\n'))
            ++line;
    }
    return line;
}

// Counts bytes that no text file of ours contains: control characters other than whitespace,
// DEL, and bytes that are not part of a well-formed UTF-8 sequence (comments may be UTF-8).
// A sequence cut off by the end of the sample is not held against it.
std::size_t countNonTextBytes(std::string_view s) {
    std::size_t bad = 0;
    std::size_t i = 0;
    while (i < s.size()) {
        const auto c = static_cast<unsigned char>(s[i]);
        if (c < 0x80) {
            const bool ws = c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
            if ((c < 0x20 && !ws) || c == 0x7f) ++bad;
            ++i;
            continue;
        }
        std::size_t len = 0;
        if (c >= 0xC2 && c <= 0xDF)
            len = 2;
        else if (c >= 0xE0 && c <= 0xEF)
            len = 3;
        else if (c >= 0xF0 && c <= 0xF4)
            len = 4;
        if (len == 0) {
            ++bad;
            ++i;
            continue;
        }
        std::size_t k = 1;
        while (k < len && i + k < s.size() && (static_cast<unsigned char>(s[i + k]) & 0xC0) == 0x80)
            ++k;
        if (k == len || i + k == s.size()) {
            i += k;
        } else {
            ++bad;
            ++i;
        }
    }
    return bad;
}

// Text in UTF-16 (Windows' "Unicode"): a byte-order mark, or ASCII with a NUL beside every
// character. Named as such, with what to do, instead of "binary file".
void checkNotUtf16(std::string_view head, const std::string& name) {
    const char* order = nullptr;
    if (head.size() >= 2 && head[0] == '\xff' && head[1] == '\xfe') {
        order = "little-endian";
    } else if (head.size() >= 2 && head[0] == '\xfe' && head[1] == '\xff') {
        order = "big-endian";
    } else if (head.size() >= 4) {
        const std::size_t n = std::min<std::size_t>(head.size() & ~std::size_t{1}, 64);
        bool le = true, be = true;
        for (std::size_t i = 0; i < n; i += 2) {
            le = le && head[i] != 0 && head[i + 1] == 0;
            be = be && head[i] == 0 && head[i + 1] != 0;
        }
        order = le ? "little-endian" : be ? "big-endian" : nullptr;
    }
    if (order) {
        fail(name, 0,
             std::string("the file is UTF-16 text (") + order +
                 "); save it as UTF-8 or plain ASCII text");
    }
}

// Refuses binary content before any parsing: a NUL anywhere, or more than 10% non-text bytes in
// the first 64 KiB (a few Latin-1 accents in comments stay well below that).
void checkNotBinary(std::string_view text, const std::string& name) {
    checkNotUtf16(text, name);
    if (const void* nul = std::memchr(text.data(), 0, text.size())) {
        const auto offset = static_cast<std::size_t>(static_cast<const char*>(nul) - text.data());
        fail(name, lineOfOffset(text, offset),
             "binary file (NUL byte at offset " + std::to_string(offset) +
                 "); expected a text point file");
    }
    const std::string_view sample = text.substr(0, kBinarySniffBytes);
    const std::size_t bad = countNonTextBytes(sample);
    if (bad > 0 && bad * 10 > sample.size()) {
        fail(name, 0,
             "binary file (" + std::to_string(bad) + " of the first " +
                 std::to_string(sample.size()) +
                 " bytes are not text); expected a text point file");
    }
}

void checkText(std::string_view text, const std::string& name) {
    if (text.size() > kMaxFileBytes) {
        fail(name, 0,
             "input is " + std::to_string(text.size()) + " bytes; the maximum is " +
                 std::to_string(kMaxFileBytes) + " (kMaxFileBytes)");
    }
    if (text.empty()) fail(name, 0, "empty file");
    checkNotBinary(text, name);
}

//-----------------------------------------------------------------------------------------------
// [SECTION] Lines and fields
//-----------------------------------------------------------------------------------------------

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\f' || c == '\v'; }

std::string_view trim(std::string_view s) {
    while (!s.empty() && isBlank(s.front())) s.remove_prefix(1);
    while (!s.empty() && isBlank(s.back())) s.remove_suffix(1);
    return s;
}

struct Line {
    std::string_view text;  // comment removed, trimmed, never empty
    LineNo number = 0;      // 1-based
};

// Walks the text line by line and yields only lines with content once the comment ('#' to the
// end of the line) and surrounding blanks are removed. Line ends: \n, \r\n and a lone \r (old
// Mac files), so CRLF files never leave a '\r' inside the last field.
class LineReader {
public:
    explicit LineReader(std::string_view text) : m_text(text) {
        if (m_text.substr(0, 3) == "\xEF\xBB\xBF") m_pos = 3;  // spreadsheets write a UTF-8 BOM
    }

    bool next(Line& out) {
        while (m_pos < m_text.size()) {
            const std::size_t start = m_pos;
            std::size_t end = start;
            while (end < m_text.size() && m_text[end] != '\n' && m_text[end] != '\r') ++end;
            m_pos = end;
            if (m_pos < m_text.size()) {
                const bool crlf =
                    m_text[m_pos] == '\r' && m_pos + 1 < m_text.size() && m_text[m_pos + 1] == '\n';
                m_pos += crlf ? 2 : 1;
            }
            ++m_line;
            std::string_view content = m_text.substr(start, end - start);
            // A '#' glued to a number ("1.#INF", "1.#QNAN": old MSVC output) is part of the
            // field, which then fails as a number; elsewhere it starts a comment.
            for (std::size_t hash = content.find('#'); hash != std::string_view::npos;
                 hash = content.find('#', hash + 1)) {
                const char before = hash > 0 ? content[hash - 1] : ' ';
                if ((before >= '0' && before <= '9') || before == '.') continue;
                content = content.substr(0, hash);
                break;
            }
            content = trim(content);
            if (!content.empty()) {
                out.text = content;
                out.number = m_line;
                return true;
            }
        }
        return false;
    }

    std::string_view remainingText() const { return m_text.substr(m_pos); }
    LineNo linesRead() const { return m_line; }

private:
    std::string_view m_text;
    std::size_t m_pos = 0;
    LineNo m_line = 0;
};

enum class Sep { Blanks, Comma, Semicolon };

const char* sepName(Sep sep) {
    switch (sep) {
        case Sep::Comma: return "','";
        case Sep::Semicolon: return "';'";
        case Sep::Blanks: break;
    }
    return "spaces/tabs";
}

// Splits a trimmed line and returns the true field count, but stores at most `keep` fields: a
// line with a million fields then costs one pass and no million-entry vector.
std::size_t splitFields(std::string_view line, Sep sep, std::vector<std::string_view>& out,
                        std::size_t keep) {
    out.clear();
    std::size_t count = 0;
    if (sep == Sep::Blanks) {
        std::size_t i = 0;
        for (;;) {
            while (i < line.size() && isBlank(line[i])) ++i;
            if (i == line.size()) break;
            const std::size_t start = i;
            while (i < line.size() && !isBlank(line[i])) ++i;
            if (count < keep) out.push_back(line.substr(start, i - start));
            ++count;
        }
        return count;
    }
    const char d = sep == Sep::Comma ? ',' : ';';
    std::size_t start = 0;
    for (;;) {
        const std::size_t p = line.find(d, start);
        const std::string_view field = trim(
            line.substr(start, p == std::string_view::npos ? std::string_view::npos : p - start));
        if (count < keep) out.push_back(field);
        ++count;
        if (p == std::string_view::npos) break;
        start = p + 1;
    }
    return count;
}

//-----------------------------------------------------------------------------------------------
// [SECTION] Numbers
//-----------------------------------------------------------------------------------------------

// parseDouble (like from_chars) rejects a leading '+', which many writers emit; accept exactly one.
std::string_view dropPlus(std::string_view f) {
    if (f.size() >= 2 && f[0] == '+' && f[1] != '+' && f[1] != '-') f.remove_prefix(1);
    return f;
}

// A field counts as numeric when parseDouble consumes all of it, even if the value is out of
// range or not finite: such a line is data with a bad value, not a header.
bool isNumeric(std::string_view f) {
    f = dropPlus(f);
    double v = 0.0;
    const auto r = parseDouble(f.data(), f.data() + f.size(), v);
    return r.ec != std::errc::invalid_argument && r.ptr == f.data() + f.size() && !f.empty();
}

// A field that starts the way a decimal number does ("1,5", "1.2.3", "-.5x", "\"3\""): such a
// field is bad data, never a column name. Spelled-out inf/nan count only as whole fields (via
// isNumeric), so that names like "info" or "nanos" stay names.
bool startsLikeNumber(std::string_view f) {
    if (f.size() >= 2 && (f.front() == '"' || f.front() == '\'')) f.remove_prefix(1);
    f = trim(f);
    std::size_t i = 0;
    if (i < f.size() && (f[i] == '+' || f[i] == '-')) ++i;
    if (i < f.size() && f[i] == '.') ++i;
    return i < f.size() && f[i] >= '0' && f[i] <= '9';
}

bool isUnsignedDigits(std::string_view f) {
    return !f.empty() &&
           std::all_of(f.begin(), f.end(), [](char c) { return c >= '0' && c <= '9'; });
}

enum class ValueKind { Coordinate, Attribute };

// Parses one decimal floating-point field exactly (parseDouble rounds correctly), refusing
// everything else with a message that names the field.
double parseReal(std::string_view field, const std::string& name, LineNo line,
                 const std::string& what, ValueKind kind, Sep sep) {
    if (field.empty()) fail(name, line, "missing " + what + " (empty field)");
    const std::string_view f = dropPlus(field);
    double v = 0.0;
    const auto r = parseDouble(f.data(), f.data() + f.size(), v);
    if (r.ec == std::errc::invalid_argument) {
        fail(name, line, "malformed number " + quoted(field) + " for " + what);
    }
    if (r.ptr != f.data() + f.size()) {
        const std::string_view junk = f.substr(static_cast<std::size_t>(r.ptr - f.data()));
        std::string msg = "trailing junk " + quoted(junk) + " after the number in " + what +
                          " field " + quoted(field);
        if (sep == Sep::Semicolon && junk.front() == ',')
            msg += " (decimal commas are not supported; use '.')";
        fail(name, line, msg);
    }
    if (r.ec == std::errc::result_out_of_range) {
        fail(name, line,
             "number " + quoted(field) + " for " + what +
                 " is out of the range of double (overflow or underflow)");
    }
    if (!std::isfinite(v)) {
        fail(name, line,
             std::string(kind == ValueKind::Coordinate ? "non-finite coordinate "
                                                       : "non-finite value ") +
                 quoted(field) + " for " + what);
    }
    return v;
}

// Parses a decimal integer field (indices, markers, counts).
std::int64_t parseInteger(std::string_view field, const std::string& name, LineNo line,
                          const std::string& what) {
    if (field.empty()) fail(name, line, "missing " + what + " (empty field)");
    const std::string_view f = dropPlus(field);
    std::int64_t v = 0;
    const auto r = std::from_chars(f.data(), f.data() + f.size(), v);
    if (r.ec == std::errc::invalid_argument || r.ptr != f.data() + f.size()) {
        fail(name, line, "expected an integer for " + what + ", found " + quoted(field));
    }
    if (r.ec == std::errc::result_out_of_range) {
        fail(name, line, "integer " + quoted(field) + " for " + what + " is out of range");
    }
    return v;
}

// Parses a declared point count and refuses absurd ones before anything is allocated.
std::size_t parseCount(std::string_view field, const std::string& name, LineNo line,
                       const std::string& what) {
    const std::string_view f = dropPlus(field);
    const std::string limit =
        " exceeds the maximum of " + std::to_string(kMaxPoints) + " points (kMaxPoints)";
    if (isUnsignedDigits(f)) {
        // Compare digit strings first so that 10^30 says "too many", not "out of range".
        std::string_view digits = f;
        while (digits.size() > 1 && digits.front() == '0') digits.remove_prefix(1);
        if (digits.size() > 18) fail(name, line, what + " " + quoted(field) + limit);
    }
    const std::int64_t n = parseInteger(field, name, line, what);
    if (n < 0) fail(name, line, what + " must not be negative, found " + quoted(field));
    if (static_cast<std::uint64_t>(n) > kMaxPoints)
        fail(name, line, what + " " + std::to_string(n) + limit);
    return static_cast<std::size_t>(n);
}

// "1 vertex", "2 vertices": messages read as sentences.
std::string plural(std::size_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

// Refuses a declared count that the rest of the buffer cannot possibly hold, so that the
// reserve() that follows is bounded by the input size, never by what a header claims. The
// message says what is wrong in the file's terms: its lines, not bytes.
void checkCountFits(std::size_t count, std::uint64_t minBytesPerLine, std::string_view rest,
                    const std::string& name, LineNo line, const char* one, const char* many) {
    if (count == 0) return;
    // count <= 2^25 and minBytesPerLine <= 2^32: the product fits in 64 bits.
    const std::uint64_t need =
        static_cast<std::uint64_t>(count) * minBytesPerLine - 1;  // last line may lack its end
    if (need <= rest.size()) return;
    const auto lines = static_cast<std::size_t>(std::count(rest.begin(), rest.end(), '\n') +
                                                (!rest.empty() && rest.back() != '\n'));
    const std::string says = "the header says " + plural(count, one, many);
    if (lines < count) {
        fail(name, line,
             says + " but only " + plural(lines, "line follows", "lines follow") +
                 ": the file is cut short, or that count is wrong");
    }
    fail(name, line,
         says +
             " but the rest of the file is too short to hold them with the fields the header "
             "asks for on each line: a count in the header is wrong");
}

// The point set of the file `name`, empty, once its content is known to be text.
PointSet emptyPointSet(std::string_view text, const std::string& name) {
    checkText(text, name);
    PointSet ps;
    ps.path = name;
    return ps;
}

// The first line with content (the header, the count, the first row); `what` names it in the
// message for a file that has none: "no header line".
Line firstLine(LineReader& reader, const std::string& name, const char* what) {
    Line line;
    if (!reader.next(line))
        fail(name, 0, std::string(what) + ": the file holds only blank lines and comments");
    return line;
}

// A count that a file's first line declares (.node, .pts), with the words its messages use:
// by: "header" or "count"; one/many: "vertex"/"vertices", "point"/"points".
struct Declared {
    std::size_t count = 0;
    LineNo line = 0;
    const char* by = "header";
    const char* one = "vertex";
    const char* many = "vertices";

    // Refuses a count the rest of the text cannot hold (records of at least minBytesPerLine).
    void checkFits(std::uint64_t minBytesPerLine, const LineReader& reader,
                   const std::string& name) const {
        checkCountFits(count, minBytesPerLine, reader.remainingText(), name, line, one, many);
    }
    // Before reading record line `at`: refuses it when the declared records are all read.
    void checkNotExtra(std::size_t read, const std::string& name, LineNo at) const {
        if (read != count) return;
        fail(name, at,
             std::string("extra ") + one + " line: the " + by + " on line " + std::to_string(line) +
                 " declares " + plural(count, one, many));
    }
    // At the end of the text: every declared record read; a warning when none was declared.
    void checkAllRead(PointSet& ps, const LineReader& reader, const std::string& name) const {
        if (ps.points.size() < count) {
            fail(name, reader.linesRead(),
                 "end of file: expected " + plural(count, one, many) + " (" + by + " on line " +
                     std::to_string(line) + "), found " + std::to_string(ps.points.size()));
        }
        if (count == 0) {
            ps.warnings.push_back(std::string(by) + " on line " + std::to_string(line) +
                                  " declares 0 " + many);
        }
    }
};

//-----------------------------------------------------------------------------------------------
// [SECTION] Triangle .node
//-----------------------------------------------------------------------------------------------

}  // namespace

namespace {

// A .node header: '<#vertices> <dimension> <#attributes> <#boundary markers>' (the last three
// may be left out: 2, 0, 0).
struct NodeHeader {
    Declared vertices;
    std::int64_t attributes = 0, markers = 0;
    std::size_t fieldsPerLine = 3;  // index, x, y, the attributes, the marker

    // "index, x, y, 2 attributes, boundary marker": what a vertex line holds, for messages.
    std::string layout() const {
        return "index, x, y" +
               (attributes > 0
                    ? ", " + plural(static_cast<std::size_t>(attributes), "attribute", "attributes")
                    : std::string()) +
               (markers > 0 ? ", boundary marker" : "");
    }
};

NodeHeader parseNodeHeader(const Line& header, const std::string& name) {
    const LineNo at = header.number;
    std::vector<std::string_view> f;
    const std::size_t headerFields = splitFields(header.text, Sep::Blanks, f, 4);
    if (headerFields > 4) {
        fail(name, at,
             "header has " + std::to_string(headerFields) +
                 " fields; expected '<#vertices> <dimension> <#attributes> <#boundary markers>'");
    }
    NodeHeader h;
    h.vertices = {parseCount(f[0], name, at, "vertex count"), at, "header", "vertex", "vertices"};
    const std::int64_t dim = f.size() > 1 ? parseInteger(f[1], name, at, "dimension") : 2;
    if (dim != 2) fail(name, at, "dimension must be 2, found " + std::to_string(dim));
    h.attributes = f.size() > 2 ? parseInteger(f[2], name, at, "attribute count") : 0;
    // No line within kMaxFileBytes can hold more fields than this; the bound also keeps the
    // field arithmetic below far from overflow.
    constexpr std::int64_t kMaxAttributes = static_cast<std::int64_t>(kMaxFileBytes / 2);
    if (h.attributes < 0 || h.attributes > kMaxAttributes) {
        fail(name, at,
             "attribute count must be between 0 and " + std::to_string(kMaxAttributes) +
                 ", found " + quoted(f[2]));
    }
    h.markers = f.size() > 3 ? parseInteger(f[3], name, at, "boundary marker count") : 0;
    if (h.markers != 0 && h.markers != 1) {
        fail(name, at, "boundary marker count must be 0 or 1, found " + std::to_string(h.markers));
    }
    h.fieldsPerLine = static_cast<std::size_t>(3 + h.attributes + h.markers);
    return h;
}

// One vertex line, the `read`-th (0-based): its fields, its index in sequence (the first sets
// the index base), its coordinates, attributes and marker as numbers.
Vec2 parseNodeVertex(const Line& line, const NodeHeader& h, std::size_t read, std::int64_t& base,
                     std::vector<std::string_view>& f, const std::string& name) {
    const std::size_t n = splitFields(line.text, Sep::Blanks, f, h.fieldsPerLine);
    if (n != h.fieldsPerLine) {
        fail(name, line.number,
             std::string(n < h.fieldsPerLine ? "too few" : "too many") + " fields: expected " +
                 std::to_string(h.fieldsPerLine) + " (" + h.layout() + "), found " +
                 std::to_string(n));
    }
    const std::int64_t index = parseInteger(f[0], name, line.number, "vertex index");
    if (read == 0) {
        if (index != 0 && index != 1) {
            fail(name, line.number,
                 "first vertex index must be 0 or 1, found " + std::to_string(index));
        }
        base = index;
    } else if (index != base + static_cast<std::int64_t>(read)) {
        fail(name, line.number,
             "vertex index " + std::to_string(index) + " out of sequence: expected " +
                 std::to_string(base + static_cast<std::int64_t>(read)));
    }
    Vec2 p;
    p.x = parseReal(f[1], name, line.number, "x coordinate", ValueKind::Coordinate, Sep::Blanks);
    p.y = parseReal(f[2], name, line.number, "y coordinate", ValueKind::Coordinate, Sep::Blanks);
    for (std::int64_t a = 0; a < h.attributes; ++a) {
        parseReal(f[3 + static_cast<std::size_t>(a)], name, line.number,
                  "attribute " + std::to_string(a + 1), ValueKind::Attribute, Sep::Blanks);
    }
    if (h.markers > 0) parseInteger(f[h.fieldsPerLine - 1], name, line.number, "boundary marker");
    return p;
}

}  // namespace

PointSet parseNode(std::string_view text, const std::string& name) {
    PointSet ps = emptyPointSet(text, name);
    LineReader reader(text);
    const NodeHeader h = parseNodeHeader(firstLine(reader, name, "no header line"), name);
    h.vertices.checkFits(2 * static_cast<std::uint64_t>(h.fieldsPerLine), reader, name);
    ps.points.reserve(h.vertices.count);
    std::int64_t base = 0;
    std::vector<std::string_view> f;
    for (Line line; reader.next(line);) {
        h.vertices.checkNotExtra(ps.points.size(), name, line.number);
        ps.points.push_back(parseNodeVertex(line, h, ps.points.size(), base, f, name));
    }
    h.vertices.checkAllRead(ps, reader, name);
    ps.indexBase = static_cast<int>(base);
    return ps;
}

namespace {

// The segment section of a .poly: its header, then one 'i a b [marker]' line a segment.
void parsePolySegments(LineReader& reader, PolyFile& out, std::int64_t base,
                       const std::string& name) {
    Line line;
    if (!reader.next(line)) fail(name, 0, "no segment section after the vertices");
    std::vector<std::string_view> f;
    splitFields(line.text, Sep::Blanks, f, 2);
    const std::int64_t count = parseInteger(f[0], name, line.number, "segment count");
    const std::int64_t markers =
        f.size() > 1 ? parseInteger(f[1], name, line.number, "segment marker count") : 0;
    const auto n = static_cast<std::int64_t>(out.points.points.size());
    if (count < 0 || count > 2 * static_cast<std::int64_t>(kMaxPoints))
        fail(name, line.number, "segment count " + std::to_string(count) + " is out of range");
    for (std::int64_t k = 0; k < count; ++k) {
        if (!reader.next(line)) {
            fail(name, reader.linesRead(),
                 "end of file: expected " + std::to_string(count) + " segments, found " +
                     std::to_string(k));
        }
        const std::size_t fields = splitFields(line.text, Sep::Blanks, f, 4);
        if (fields < 3 || fields > static_cast<std::size_t>(markers > 0 ? 4 : 3)) {
            fail(name, line.number,
                 std::string("a segment line holds: index, first vertex, second vertex") +
                     (markers > 0 ? ", boundary marker" : ""));
        }
        std::int32_t ends[2];
        for (int e = 0; e < 2; ++e) {
            const std::int64_t id = parseInteger(f[1 + e], name, line.number, "segment vertex");
            if (id < base || id - base >= n) {
                fail(name, line.number,
                     "segment vertex " + std::to_string(id) + " is not a vertex (ids run " +
                         std::to_string(base) + " to " + std::to_string(n + base - 1) + ")");
            }
            ends[e] = static_cast<std::int32_t>(id - base);
        }
        out.segments.push_back({ends[0], ends[1]});
    }
    if (reader.next(line)) {
        splitFields(line.text, Sep::Blanks, f, 1);
        if (parseInteger(f[0], name, line.number, "hole count") != 0)
            fail(name, line.number, "holes are not supported (the result covers the convex hull)");
    }
}

}  // namespace

PolyFile parsePoly(std::string_view text, const std::string& name) {
    PolyFile out;
    out.points = emptyPointSet(text, name);
    LineReader reader(text);
    const NodeHeader h = parseNodeHeader(firstLine(reader, name, "no header line"), name);
    if (h.vertices.count == 0)
        fail(name, h.vertices.line, "vertices in a separate .node file are not supported");
    h.vertices.checkFits(2 * static_cast<std::uint64_t>(h.fieldsPerLine), reader, name);
    auto& points = out.points.points;
    points.reserve(h.vertices.count);
    std::int64_t base = 0;
    std::vector<std::string_view> f;
    for (Line line; points.size() < h.vertices.count;) {
        if (!reader.next(line)) h.vertices.checkAllRead(out.points, reader, name);
        points.push_back(parseNodeVertex(line, h, points.size(), base, f, name));
    }
    out.points.indexBase = static_cast<int>(base);
    parsePolySegments(reader, out, base, name);
    return out;
}

//-----------------------------------------------------------------------------------------------
// [SECTION] XY / CSV
//-----------------------------------------------------------------------------------------------

namespace {

Sep detectSeparator(std::string_view line) {
    if (line.find(';') != std::string_view::npos) return Sep::Semicolon;
    if (line.find(',') != std::string_view::npos) return Sep::Comma;
    return Sep::Blanks;
}

std::string_view unquote(std::string_view s) {
    if (s.size() >= 2 && (s.front() == '"' || s.front() == '\'') && s.back() == s.front()) {
        s = trim(s.substr(1, s.size() - 2));
    }
    return s;
}

bool namesColumn(std::string_view field, char letter) {
    const std::string_view s = unquote(field);
    return s.size() == 1 && (s[0] == letter || s[0] == letter - 'a' + 'A');
}

// The columns of an XY/CSV file: the separator, how many fields a row has and which are x and y;
// the header's line (0: none).
struct XYColumns {
    Sep sep = Sep::Blanks;
    std::size_t count = 2, x = 0, y = 1;
    LineNo headerLine = 0;
};

// The columns, from the first line: a header when it holds no number (a warning says it was
// skipped), else the first row of data with x and y alone.
XYColumns xyColumns(const Line& first, const std::string& name, PointSet& ps) {
    XYColumns c;
    c.sep = detectSeparator(first.text);
    // A first line without a single number in it is a header ("x,y", "id;x;y", "lon lat").
    // A line mixing words and numbers is bad data and is reported as such below. A field
    // that merely starts like a number ("1,5" with ';' separators, "1.2.3", "\"3\"") is a
    // number gone wrong, not a column name: taking such a line for a header would silently
    // drop a row of data (and blame a later line for the decimal commas of the first).
    constexpr std::size_t kMaxHeaderColumns = 4096;
    std::vector<std::string_view> f;
    const std::size_t n = splitFields(first.text, c.sep, f, kMaxHeaderColumns);
    const auto numberLike = [](std::string_view field) {
        return isNumeric(field) || startsLikeNumber(field);
    };
    if (std::any_of(f.begin(), f.end(), numberLike) || n > kMaxHeaderColumns) return c;
    c.headerLine = first.number;
    c.count = n;
    const auto x =
        std::find_if(f.begin(), f.end(), [](std::string_view s) { return namesColumn(s, 'x'); });
    const auto y =
        std::find_if(f.begin(), f.end(), [](std::string_view s) { return namesColumn(s, 'y'); });
    if (x != f.end() && y != f.end()) {
        c.x = static_cast<std::size_t>(x - f.begin());
        c.y = static_cast<std::size_t>(y - f.begin());
    } else if (n != 2) {
        fail(name, first.number,
             "header " + quoted(first.text) + " has " + plural(n, "column", "columns") +
                 "; expected two, or columns named 'x' and 'y'");
    }
    ps.warnings.push_back("skipped header line " + std::to_string(first.number) + ": " +
                          printable(first.text, 80, false));
    return c;
}

// A row with n fields where c.count are expected, the first row when firstRow: what is wrong,
// with a hint at what the file may be.
std::string fieldCountError(const XYColumns& c, std::size_t n, std::string_view firstField,
                            bool firstRow) {
    std::string msg = plural(n, "field", "fields") + " separated by " + sepName(c.sep) +
                      "; expected " + std::to_string(c.count);
    if (c.headerLine) return msg + " as in the header on line " + std::to_string(c.headerLine);
    msg += " (x, y)";
    if (n == 3)
        msg += "; for id,x,y or x,y,z columns add a header line naming the 'x' and 'y' columns";
    if (n == 1 && firstRow && isUnsignedDigits(firstField))
        msg += "; a point count on the first line suggests Rossignac's .pts format";
    return msg;
}

}  // namespace

PointSet parseXY(std::string_view text, const std::string& name) {
    PointSet ps = emptyPointSet(text, name);
    LineReader reader(text);
    Line line = firstLine(reader, name, "no data");
    const XYColumns c = xyColumns(line, name, ps);
    if (c.headerLine && !reader.next(line)) fail(name, c.headerLine, "no points after the header");
    std::vector<std::string_view> f;
    do {
        const std::size_t n = splitFields(line.text, c.sep, f, c.count);
        if (n != c.count)
            fail(name, line.number,
                 fieldCountError(c, n, f.empty() ? "" : f[0], ps.points.empty()));
        if (ps.points.size() == kMaxPoints) {
            fail(name, line.number,
                 "more than " + std::to_string(kMaxPoints) + " points (kMaxPoints)");
        }
        // Quoted numbers ("0","1.5"), as spreadsheets write CSV, read like a quoted header does.
        Vec2 p;
        p.x = parseReal(unquote(f[c.x]), name, line.number, "x coordinate", ValueKind::Coordinate,
                        c.sep);
        p.y = parseReal(unquote(f[c.y]), name, line.number, "y coordinate", ValueKind::Coordinate,
                        c.sep);
        ps.points.push_back(p);
    } while (reader.next(line));
    return ps;
}

//-----------------------------------------------------------------------------------------------
// [SECTION] Rossignac .pts
//-----------------------------------------------------------------------------------------------

PointSet parsePts(std::string_view text, const std::string& name) {
    PointSet ps = emptyPointSet(text, name);
    LineReader reader(text);
    std::vector<std::string_view> f;

    Line line = firstLine(reader, name, "no point count");
    if (splitFields(line.text, Sep::Blanks, f, 1) != 1 ||
        line.text.find(',') != std::string_view::npos) {
        fail(name, line.number,
             "the first line must be the point count alone, found " + quoted(line.text));
    }
    const Declared points{parseCount(f[0], name, line.number, "point count"), line.number, "count",
                          "point", "points"};
    points.checkFits(4, reader, name);  // "0,0\n" is the shortest line
    ps.points.reserve(points.count);

    bool warnedZ = false;
    while (reader.next(line)) {
        points.checkNotExtra(ps.points.size(), name, line.number);
        // savePts writes "x,y" (or "x,y,z"); hand-made files often use blanks instead.
        const Sep sep = line.text.find(',') != std::string_view::npos ? Sep::Comma : Sep::Blanks;
        const std::size_t n = splitFields(line.text, sep, f, 3);
        if (n < 2 || n > 3) {
            fail(name, line.number,
                 plural(n, "field", "fields") + " separated by " + sepName(sep) +
                     "; expected 2 (x,y) or 3 (x,y,z)");
        }
        Vec2 p;
        p.x = parseReal(f[0], name, line.number, "x coordinate", ValueKind::Coordinate, sep);
        p.y = parseReal(f[1], name, line.number, "y coordinate", ValueKind::Coordinate, sep);
        if (n == 3) {
            const double z =
                parseReal(f[2], name, line.number, "z coordinate", ValueKind::Coordinate, sep);
            if (z != 0.0 && !warnedZ) {
                warnedZ = true;
                ps.warnings.push_back("z coordinates ignored (first nonzero z on line " +
                                      std::to_string(line.number) + ")");
            }
        }
        ps.points.push_back(p);
    }
    points.checkAllRead(ps, reader, name);
    return ps;
}

//-----------------------------------------------------------------------------------------------
// [SECTION] Files and format sniffing
//-----------------------------------------------------------------------------------------------

namespace {

enum class Format { Node, XY, Pts };

// Guesses the format of a file with an unknown extension from its first two content lines.
//   "N [2 [A [M]]]" then "i x y ..."  -> .node  (Triangle's header shape, then an indexed vertex)
//   "N"             then "x,y" / "x y" -> .pts
//   anything else                      -> XY
Format sniffFormat(std::string_view text) {
    LineReader reader(text);
    Line first, second;
    if (!reader.next(first)) return Format::XY;  // the XY parser reports "no data"
    const bool hasSecond = reader.next(second);
    std::vector<std::string_view> f1, f2;
    const std::size_t n1 = splitFields(first.text, Sep::Blanks, f1, 4);
    const std::size_t n2 = hasSecond ? splitFields(second.text, Sep::Blanks, f2, 1) : 0;
    const bool secondIsVertex = hasSecond && second.text.find(',') == std::string_view::npos &&
                                second.text.find(';') == std::string_view::npos && n2 >= 3 &&
                                isUnsignedDigits(f2[0]);
    const bool allUnsigned = n1 <= 4 && std::all_of(f1.begin(), f1.end(), isUnsignedDigits);
    if (n1 == 1 && allUnsigned) return secondIsVertex ? Format::Node : Format::Pts;
    if (n1 >= 2 && allUnsigned && f1[1] == "2" && (!hasSecond || secondIsVertex))
        return Format::Node;
    return Format::XY;
}

std::string errnoText(int e) { return std::generic_category().message(e); }

// What a path is when it is not a regular file, in a user's words.
const char* kindOfFile(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a named pipe (FIFO)";
    if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

struct FdCloser {
    int fd;
    ~FdCloser() {
        if (fd >= 0) ::close(fd);
    }
};

}  // namespace

namespace {

// The file's chunks in order, after the checks of readRegularFile; onSize sees the size stat()
// gave before the first read.
void readChunks(const std::string& path, std::size_t maxBytes,
                const std::function<void(std::uintmax_t)>& onSize,
                const std::function<void(std::string_view)>& onChunk) {
    // O_NONBLOCK: opening a FIFO without a writer returns at once (and is refused below).
    const FdCloser file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY)};
    if (file.fd < 0) fail(path, 0, "cannot open file: " + errnoText(errno));
    struct stat st {};
    if (::fstat(file.fd, &st) != 0) fail(path, 0, "cannot read the file: " + errnoText(errno));
    if (!S_ISREG(st.st_mode)) {
        fail(path, 0,
             std::string("cannot read: it is ") + kindOfFile(st.st_mode) + ", not a regular file");
    }
    const auto size = static_cast<std::uintmax_t>(st.st_size);
    const std::string tooLarge = " bytes; the maximum is " + std::to_string(maxBytes);
    if (size > maxBytes) fail(path, 0, "file is " + std::to_string(size) + tooLarge);
    if (onSize) onSize(size);
    std::vector<char> chunk(kBinarySniffBytes);
    std::size_t total = 0;
    for (;;) {
        const ssize_t got = ::read(file.fd, chunk.data(), chunk.size());
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) fail(path, 0, "cannot read the file: " + errnoText(errno));
        if (got == 0) break;
        const auto n = static_cast<std::size_t>(got);
        if (total + n > maxBytes)  // the file grew while it was read
            fail(path, 0, "file is more than " + std::to_string(maxBytes) + " bytes long");
        const std::string_view piece(chunk.data(), n);
        if (total == 0) checkNotUtf16(piece, path);
        onChunk(piece);
        // No text file of ours holds a NUL: a sparse or binary file stops at the first chunk
        // that has one, not after the whole file.
        if (const void* nul = std::memchr(piece.data(), 0, n)) {
            const std::size_t at =
                total + static_cast<std::size_t>(static_cast<const char*>(nul) - piece.data());
            fail(path, 0, "binary file (NUL byte at offset " + std::to_string(at) + ")");
        }
        total += n;
    }
}

}  // namespace

void readRegularFileChunks(const std::string& path, std::size_t maxBytes,
                           const std::function<void(std::string_view)>& chunkFn) {
    readChunks(path, maxBytes, {}, chunkFn);
}

std::string readRegularFile(const std::string& path, std::size_t maxBytes,
                            const std::function<void(std::string_view)>& firstChunk) {
    std::string text;
    try {
        readChunks(
            path, maxBytes,
            [&](std::uintmax_t size) { text.reserve(static_cast<std::size_t>(size)); },
            [&](std::string_view piece) {
                const bool first = text.empty();
                text.append(piece);
                if (first && firstChunk) firstChunk(text);
            });
    } catch (const std::bad_alloc&) {
        fail(path, 0,
             "not enough memory to read the file (" + std::to_string(text.size()) +
                 " bytes read; the largest accepted is " + std::to_string(maxBytes) + " bytes)");
    }
    return text;
}

namespace {

// Reads the whole point file, refusing oversized files before reading and binary ones after the
// first chunk: a stray image fails fast instead of being slurped and parsed.
std::string readFileText(const std::string& path) {
    return readRegularFile(path, kMaxFileBytes,
                           [&](std::string_view head) { checkNotBinary(head, path); });
}

std::string lowercaseExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) {
        return static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
    });
    return ext;
}

}  // namespace

PointSet readPointsFile(const std::string& path) {
    const std::string ext = lowercaseExtension(path);
    const std::string text = readFileText(path);
    if (ext == ".node") return parseNode(text, path);
    if (ext == ".pts") return parsePts(text, path);
    if (ext == ".csv" || ext == ".xy" || ext == ".txt" || ext == ".dat") return parseXY(text, path);

    checkText(text, path);  // sniff only text that passed the same checks the parsers make
    const Format format = sniffFormat(text);
    const char* guess = format == Format::Node  ? "Triangle .node"
                        : format == Format::Pts ? "Rossignac .pts"
                                                : "XY";
    const std::string shown =
        ext.empty() ? "no extension" : "unknown extension '" + printable(ext, 20, false) + "'";
    PointSet ps;
    try {
        ps = format == Format::Node  ? parseNode(text, path)
             : format == Format::Pts ? parsePts(text, path)
                                     : parseXY(text, path);
    } catch (const InputError& e) {  // say what the file was taken for, and how to choose
        throw InputError(e.file(), e.line(),
                         e.message() + " (" + shown + ": read as " + guess +
                             " by its content; name it .node, .csv, .xy or .pts to choose)");
    }
    ps.warnings.insert(ps.warnings.begin(), shown + ": read as " + guess + " by its content");
    return ps;
}

PolyFile readPolyFile(const std::string& path) { return parsePoly(readFileText(path), path); }

std::vector<std::int32_t> parseIdList(std::string_view text, const std::string& name, int base,
                                      std::size_t count) {
    std::vector<std::int32_t> ids;
    std::vector<int> lineOf(count, 0);
    int lineNo = 0;
    while (!text.empty()) {
        const std::size_t eol = text.find('\n');
        std::string_view line = text.substr(0, eol);
        text = eol == std::string_view::npos ? std::string_view{} : text.substr(eol + 1);
        ++lineNo;
        line = line.substr(0, line.find('#'));
        while (!line.empty() && std::isspace(static_cast<unsigned char>(line.front())))
            line.remove_prefix(1);
        while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back())))
            line.remove_suffix(1);
        if (line.empty()) continue;
        long long id = 0;
        const auto [end, ec] = std::from_chars(line.data(), line.data() + line.size(), id);
        if (ec != std::errc{} || end != line.data() + line.size()) {
            throw InputError(name, lineNo,
                             "\"" + printable(line, 40, false) +
                                 "\" is not a point id (a whole "
                                 "number, one a line)");
        }
        if (id < base || id - base >= static_cast<long long>(count)) {
            throw InputError(name, lineNo,
                             "point id " + std::to_string(id) + " is not in the input (ids run " +
                                 std::to_string(base) + " to " +
                                 std::to_string(static_cast<long long>(count) + base - 1) + ")");
        }
        const auto i = static_cast<std::int32_t>(id - base);
        if (lineOf[i] != 0) {
            throw InputError(name, lineNo,
                             "point id " + std::to_string(id) + " is listed twice (line " +
                                 std::to_string(lineOf[i]) + " too)");
        }
        lineOf[i] = lineNo;
        ids.push_back(i);
    }
    return ids;
}

}  // namespace dlab
