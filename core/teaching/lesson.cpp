// Lessons: TOML loading with file/line/stop errors (tomlplusplus), safe points files, answers
// computed from the live state, the headless planner, and Markdown-light text.
#include "core/teaching/lesson.h"

#include "core/engine/io_read.h"
#include "core/engine/numbers.h"
#include "core/engine/predicates.h"
#include "core/engine/text_util.h"
#include "core/engine/triangulation_check.h"
#include "core/engine/voronoi.h"
#include "core/teaching/corner_expr.h"
#include "core/teaching/describe.h"
#include "core/teaching/describe_edit.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

namespace dlab {

namespace fs = std::filesystem;

// ============================================================================================
// [SECTION] Errors
// ============================================================================================

namespace {

// The corners of a view rect, as a message names them.
constexpr const char* kRectNames[] = {"x0", "y0", "x1", "y1"};

std::string composeMessage(const std::string& file, int line, int stop,
                           const std::string& message) {
    std::string s = file;
    if (line > 0) s += ":" + std::to_string(line);
    s += ": ";
    if (stop > 0) s += "stop " + std::to_string(stop) + ": ";
    return s + message;
}

template <class Names>
std::string joinNames(const Names& names) {
    std::string s;
    for (const char* n : names) s += std::string(s.empty() ? "" : ", ") + n;
    return s;
}

}  // namespace

LessonError::LessonError(std::string file, int line, int stop, std::string message)
    : std::runtime_error(composeMessage(file, line, stop, escapeControls(message))),
      m_file(std::move(file)),
      m_line(line),
      m_stop(stop),
      m_message(escapeControls(message)) {}

// ============================================================================================
// [SECTION] Markdown-light text
// ============================================================================================

namespace {

// Splits one block's text into spans. On an unclosed marker returns false with `why` and the
// marker's offset in `raw`.
bool parseInline(std::string_view raw, std::vector<TextSpan>& spans, std::string& why,
                 std::size_t& at) {
    TextSpan::Style style = TextSpan::Style::Plain;
    std::size_t boldAt = 0;
    std::string cur;
    auto flush = [&](TextSpan::Style s) {
        if (!cur.empty()) spans.push_back({s, cur});
        cur.clear();
    };
    for (std::size_t i = 0; i < raw.size(); ++i) {
        if (raw[i] == '`') {
            const std::size_t close = raw.find('`', i + 1);
            if (close == std::string_view::npos) {
                why = "unclosed ` (code)";
                at = i;
                return false;
            }
            flush(style);
            spans.push_back({TextSpan::Style::Code, std::string(raw.substr(i + 1, close - i - 1))});
            i = close;
        } else if (raw.compare(i, 2, "**") == 0) {
            flush(style);
            style = style == TextSpan::Style::Bold ? TextSpan::Style::Plain : TextSpan::Style::Bold;
            boldAt = i;
            ++i;
        } else {
            cur += raw[i];
        }
    }
    if (style == TextSpan::Style::Bold) {
        why = "unclosed ** (bold)";
        at = boldAt;
        return false;
    }
    flush(style);
    return true;
}

}  // namespace

std::optional<std::vector<TextBlock>> parseLessonText(std::string_view text, std::string* error) {
    struct RawBlock {
        TextBlock::Kind kind;
        int number;
        std::string raw;
        std::vector<std::pair<std::size_t, int>>
            lines;  // (offset in raw, line number) per joined line
    };
    std::vector<RawBlock> raws;
    bool open = false;
    int lineNo = 0;
    std::size_t pos = 0;
    while (pos <= text.size()) {
        const std::size_t nl = text.find('\n', pos);
        std::string_view line =
            text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
        pos = nl == std::string_view::npos ? text.size() + 1 : nl + 1;
        ++lineNo;
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        const std::string t = trimmed(line);
        if (t.empty()) {
            open = false;
            continue;
        }
        std::size_t digits = 0;
        while (digits < t.size() && std::isdigit(static_cast<unsigned char>(t[digits]))) ++digits;
        if ((t[0] == '-' || t[0] == '*') && t.size() > 1 && t[1] == ' ') {
            raws.push_back({TextBlock::Kind::Bullet,
                            0,
                            trimmed(std::string_view(t).substr(2)),
                            {{0, lineNo}}});
            open = true;
        } else if (digits > 0 && digits < 6 && digits + 1 < t.size() && t[digits] == '.' &&
                   t[digits + 1] == ' ') {
            raws.push_back({TextBlock::Kind::Numbered,
                            std::atoi(t.substr(0, digits).c_str()),
                            trimmed(std::string_view(t).substr(digits + 2)),
                            {{0, lineNo}}});
            open = true;
        } else if (open) {
            raws.back().raw += " ";
            raws.back().lines.emplace_back(raws.back().raw.size(), lineNo);
            raws.back().raw += t;
        } else {
            raws.push_back({TextBlock::Kind::Paragraph, 0, t, {{0, lineNo}}});
            open = true;
        }
    }
    std::vector<TextBlock> blocks;
    for (const RawBlock& r : raws) {
        TextBlock b{r.kind, r.number, {}};
        std::string why;
        std::size_t at = 0;
        if (!parseInline(r.raw, b.spans, why, at)) {
            int line = r.lines.front().second;
            for (const auto& [offset, number] : r.lines) {
                if (offset <= at) line = number;
            }
            if (error) *error = "line " + std::to_string(line) + " of the text: " + why;
            return std::nullopt;
        }
        blocks.push_back(std::move(b));
    }
    return blocks;
}

// ============================================================================================
// [SECTION] Answers
// ============================================================================================

namespace {

std::string formatNumber(double x) { return shortest(x); }

// Real numbers written in s ("(1.5, -2)" -> 1.5, -2).
std::vector<double> realRuns(std::string_view s) {
    std::vector<double> out;
    for (std::size_t i = 0; i < s.size();) {
        double v = 0;
        const auto [end, ec] = parseDouble(s.data() + i, s.data() + s.size(), v);
        if (ec == std::errc() && end != s.data() + i) {
            out.push_back(v);
            i = static_cast<std::size_t>(end - s.data());
        } else {
            ++i;
        }
    }
    return out;
}

}  // namespace

std::string Answer::display() const {
    switch (kind) {
        case Kind::Integer: return labelA.empty() ? std::to_string(a) : labelA;
        case Kind::Edge:
            return (labelA.empty() ? std::to_string(a) : labelA) + "-" +
                   (labelB.empty() ? std::to_string(b) : labelB);
        case Kind::Text: return text;
        case Kind::Truth: return truth ? "yes" : "no";
        case Kind::Point: return "(" + formatNumber(point.x) + ", " + formatNumber(point.y) + ")";
    }
    return "?";
}

namespace {

// Lower-case runs of letters and digits ("Edge 1-s0" -> edge, 1, s0).
std::vector<std::string> words(std::string_view s) {
    std::vector<std::string> out;
    std::string cur;
    for (char ch : s) {
        if (std::isalnum(static_cast<unsigned char>(ch))) {
            cur += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
        } else if (!cur.empty()) {
            out.push_back(std::move(cur));
            cur.clear();
        }
    }
    if (!cur.empty()) out.push_back(std::move(cur));
    return out;
}

bool isOneOf(std::string_view w, std::initializer_list<std::string_view> list) {
    return std::find(list.begin(), list.end(), w) != list.end();
}

// Number words as people type them ("three"), up to twenty.
std::optional<std::int64_t> numberWord(std::string_view w) {
    static constexpr std::string_view kWords[] = {
        "zero",     "one",     "two",     "three",     "four",     "five",     "six",
        "seven",    "eight",   "nine",    "ten",       "eleven",   "twelve",   "thirteen",
        "fourteen", "fifteen", "sixteen", "seventeen", "eighteen", "nineteen", "twenty"};
    for (std::size_t i = 0; i < std::size(kWords); ++i) {
        if (w == kWords[i]) return static_cast<std::int64_t>(i);
    }
    return std::nullopt;
}

// What a student typed without what surrounds the answer: trimmed, lower case, without the
// punctuation that ends a sentence ("Six." -> "six") and without quotes around it.
std::string withoutMarks(std::string_view in) {
    std::string t = lowered(trimmed(in));
    const auto isMark = [](char ch) { return std::strchr(".!?,;:\"'`", ch) != nullptr; };
    while (!t.empty() && (isMark(t.back()) || std::isspace(static_cast<unsigned char>(t.back()))))
        t.pop_back();
    std::size_t lead = 0;
    while (lead < t.size() && (t[lead] == '"' || t[lead] == '\'' || t[lead] == '`' ||
                               std::isspace(static_cast<unsigned char>(t[lead]))))
        ++lead;
    return t.substr(lead);
}

// `t` without one unit word the answer allows after its number: "8 steps" -> "8", "32°" -> "32",
// "six times" -> "six". A word unit needs a space or a digit before it ("8steps" too); anything
// else is left as it is, so that "8 triangles" stays wrong where steps are counted.
std::string withoutUnit(const std::string& t, const std::vector<std::string>& units) {
    for (const std::string& u : units) {
        if (u.empty() || t.size() <= u.size() || t.compare(t.size() - u.size(), u.size(), u) != 0)
            continue;
        const char before = t[t.size() - u.size() - 1];
        const bool word = std::isalpha(static_cast<unsigned char>(u[0])) != 0;
        if (word && before != ' ' && !std::isdigit(static_cast<unsigned char>(before))) continue;
        std::string rest = trimmed(std::string_view(t).substr(0, t.size() - u.size()));
        if (!rest.empty()) return rest;
    }
    return t;
}

// A whole number as typed: "17", "+17", "- 1", "t25" (a triangle), "seven".
std::optional<std::int64_t> typedInteger(std::string t) {
    for (const char* prefix : {"triangle", "corner", "vertex"}) {
        if (t.rfind(prefix, 0) == 0) t.erase(0, std::strlen(prefix));
    }
    std::string c;
    for (char ch : t) {
        if (ch != ' ') c += ch;
    }
    if (!c.empty() && c[0] == '+') c.erase(0, 1);
    if (c.size() > 1 && (c[0] == 't' || c[0] == 'c' || c[0] == 'v') &&
        std::isdigit(static_cast<unsigned char>(c[1])))
        c.erase(0, 1);
    if (auto w = numberWord(c)) return w;
    std::int64_t v = 0;
    const auto [end, ec] = std::from_chars(c.data(), c.data() + c.size(), v);
    if (ec != std::errc() || end != c.data() + c.size()) return std::nullopt;
    return v;
}

// A word in American spelling, as the tool writes its names: "finalise" -> "finalize",
// "neighbour" -> "neighbor", "centre" -> "center".
std::string americanSpelling(std::string w) {
    const auto endsWith = [&](std::string_view e) {
        return w.size() > e.size() + 2 && w.compare(w.size() - e.size(), e.size(), e) == 0;
    };
    for (const auto& [british, american] :
         {std::pair<std::string_view, std::string_view>{"isation", "ization"},
          {"ising", "izing"},
          {"ised", "ized"},
          {"ise", "ize"},
          {"our", "or"},
          {"ours", "ors"},
          {"tre", "ter"},
          {"tres", "ters"}}) {
        if (endsWith(british))
            return w.replace(w.size() - british.size(), british.size(), american);
    }
    return w;
}

// A phrase reduced to what it names: filler words dropped, then synonyms mapped, so that
// "on an edge" and "edge", "outside the hull" and "outside-hull", "on the boundary" and "edge",
// "in a ghost triangle" and "outside-hull", "empty pixel" and "empty" read the same.
std::string canonicalPhrase(std::string_view s) {
    std::string joined;
    for (const std::string& w : words(s)) {
        if (isOneOf(w, {"on", "an", "a", "the", "in", "at", "it", "its", "is", "of", "lies",
                        "exactly", "point", "found", "was", "will", "be", "by"}))
            continue;
        joined += americanSpelling(w);
    }
    if (isOneOf(joined, {"inside", "insidetriangle", "intriangle", "triangle", "interior"}))
        return "inside";
    if (isOneOf(joined, {"edge", "anedge", "insideedge", "boundary", "boundaryedge", "hulledge",
                         "edgehull", "boundarymesh", "meshboundary", "hullboundary"}))
        return "edge";
    if (isOneOf(joined, {"vertex", "duplicate", "existingvertex", "samevertex"})) return "vertex";
    if (isOneOf(joined, {"outside", "outsidehull", "beyondhull", "outsidemesh", "outsideconvexhull",
                         "beyondconvexhull", "ghost", "ghosttriangle", "outsideghosttriangle"}))
        return "outsidehull";
    if (isOneOf(joined, {"none", "noflip", "nothing", "noedge", "no"})) return "none";
    if (isOneOf(joined, {"empty", "emptypixel", "pixelempty", "unpainted", "unpaintedpixel",
                         "blank", "blankpixel"}))
        return "empty";
    if (isOneOf(joined, {"miss", "missed", "pixelmissed"})) return "miss";
    if (isOneOf(joined, {"hit", "hits", "pixelhit"})) return "hit";
    return joined;
}

bool sameVertex(const std::string& w, std::int64_t v, const std::string& label) {
    return w == std::to_string(v) || (!label.empty() && w == lowered(label));
}

}  // namespace

bool acceptsAnswer(const Answer& expected, std::string_view typedIn) {
    const std::string typed = withoutMarks(typedIn);
    if (typed.empty()) return false;
    switch (expected.kind) {
        case Answer::Kind::Integer: {
            if (expected.corner && expected.a == kNone) {
                // No corner across: "none", or where that happens ("boundary", "hull edge").
                const std::string said = canonicalPhrase(typed);
                if (isOneOf(said, {"none", "nocorner", "hull"}) ||
                    (said == "edge" && typed.find("edge") == std::string::npos) ||
                    isOneOf(looseName(typed), {"hulledge", "onthehulledge", "onhulledge"}))
                    return true;
            }
            if (!expected.labelA.empty() && looseName(typed) == looseName(expected.labelA))
                return true;
            const auto v = typedInteger(withoutUnit(typed, expected.units));
            return v && *v == expected.a;
        }
        case Answer::Kind::Edge: {
            std::vector<std::string> w;
            for (std::string& x : words(typed)) {
                if (!isOneOf(x,
                             {"edge", "from", "to", "and", "between", "the", "vertices", "vertex"}))
                    w.push_back(std::move(x));
            }
            const auto is = [&](const std::string& x, bool first) {
                return first ? sameVertex(x, expected.a, expected.labelA)
                             : sameVertex(x, expected.b, expected.labelB);
            };
            return w.size() == 2 &&
                   ((is(w[0], true) && is(w[1], false)) || (is(w[0], false) && is(w[1], true)));
        }
        case Answer::Kind::Text:
            return looseName(typed) == looseName(expected.text) ||
                   canonicalPhrase(typed) == canonicalPhrase(expected.text);
        case Answer::Kind::Truth: {
            const auto w = words(typed);
            if (w.empty()) return false;
            const bool yes = isOneOf(w[0], {"yes", "y", "true", "1", "yep", "yeah"});
            const bool no = isOneOf(w[0], {"no", "n", "false", "0", "nope"});
            return expected.truth ? yes : no;
        }
        case Answer::Kind::Point: {
            const auto v = realRuns(typed);
            const auto close = [](double x, double want) {
                return std::abs(x - want) <= 1e-9 * std::max(1.0, std::abs(want));
            };
            return v.size() == 2 && close(v[0], expected.point.x) && close(v[1], expected.point.y);
        }
    }
    return false;
}

// ============================================================================================
// [SECTION] Quantities: what an answer can ask about the live state
// ============================================================================================

namespace {

constexpr QuantityInfo kQuantities[] = {
    {"triangles", "real triangles in the mesh now (ghost / super-triangle ones not counted)"},
    {"all_triangles", "rows of the table / 3: every triangle, ghost or super ones included"},
    {"corners", "corners in the table (3 per triangle, virtual ones included)"},
    {"vertices", "input points that are vertices of the mesh now"},
    {"input_points", "points in the lesson's input, duplicates included"},
    {"position", "operations done so far"},
    {"op", "the type of the last operation (Flip, Split, ...)"},
    {"next_op", "the type of the next operation"},
    {"vertex", "the point the last operation worked on"},
    {"next_vertex", "the point the next operation works on"},
    {"flips", "flips so far"},
    {"tests", "in-circle tests so far"},
    {"insertion_flips", "flips of the insertion in progress (or the one that just ended)"},
    {"insertion_tests",
     "in-circle tests of the insertion in progress (or the one that just ended)"},
    {"queue", "edges waiting for their in-circle test (the flip queue)"},
    {"walk_steps", "walk steps so far, all locates together"},
    {"hint", "the triangle the latest locate started from (the locator's hint)"},
    {"locate_steps", "walk steps of the latest locate"},
    {"located", "the triangle the latest locate found"},
    {"where", "where the latest locate found its point: inside, edge, vertex or outside-hull"},
    {"test_edge", "the edge of the latest in-circle test (two vertices)"},
    {"test_result", "the latest in-circle test: 1 flip, 0 cocircular, -1 Delaunay"},
    {"previous_test_edge", "the edge of the in-circle test before the latest, in this insertion"},
    {"previous_test_result", "that test's answer: 1 flip, 0 cocircular, -1 Delaunay"},
    {"next_flip", "the edge that flips next in this insertion, or none"},
    {"flipped_edge", "the edge the latest flip removed"},
    {"new_edge", "the edge the latest flip made"},
    {"previous_flipped_edge", "the edge the flip before the latest removed"},
    {"previous_new_edge", "the edge the flip before the latest made"},
    {"duplicates", "duplicate points skipped so far"},
    {"edge_splits", "edge splits so far"},
    {"hull_edges", "edges of the real triangles with no real triangle across"},
    {"convex", "whether the real triangles cover a convex region (yes / no)"},
    {"delaunay_violations", "interior edges whose opposite vertex is strictly inside the circle"},
    {"degree", "triangles around the vertex of the selected corner, ghost ones included"},
    {"triangles_around", "real triangles around the vertex of the selected corner"},
    {"edges_around", "edges at the vertex of the selected corner (its degree in the graph)"},
    {"next_new_edge", "the edge the next flip of this insertion makes, or none"},
    {"next_test_edge", "the edge the next in-circle test of this insertion tests"},
    {"will_flip", "whether the next in-circle test of this insertion flips its edge (yes / no)"},
    {"next_where", "where the next locate will find its point: inside, edge, vertex, outside-hull"},
    {"next_located", "the triangle the next locate will find"},
    {"next_locate_steps", "the walk steps the next locate will take"},
    {"changed_corners",
     "corners whose V or O cell the last operation changed (back-pointers in neighbours too)"},
    {"min_angle", "the smallest angle of the real triangles, in whole degrees"},
    {"most_flips", "the most flips one insertion has taken so far"},
    {"most_flips_vertex", "the point whose insertion took the most flips (the first on a tie)"},
    {"flips_per_point", "flips so far per point inserted, to the nearest whole number"},
    {"incircle_det",
     "the in-circle determinant of the test just made (or next): rows (x, y, x² + y²) of the "
     "triangle's vertices minus the point; positive: the point is inside the circle"},
    {"pixel_outcome",
     "the latest ID-buffer locate: hit (the pixel's triangle holds the point), miss (a walk "
     "from it) or empty (no triangle painted there: a walk from the last insertion)"},
    {"circumcenter", "the circumcenter of the selected corner's triangle (its Voronoi vertex)"},
    {"pixel", "the triangle id the ID buffer holds under the point about to be located"},
    // Inside the lesson's edits only (core/teaching/lesson_edits.cpp): about the edit whose op
    // was just done, or the first edit at the run's end.
    {"removal_degree",
     "triangles around the vertex being removed when its removal began (ghost "
     "ones included): the size of its link"},
    {"degree_left", "triangles around the vertex being removed now (ghost ones included)"},
    {"ear_tests", "ear tests the whole removal makes"},
    {"ear_flips", "ear flips the whole removal makes"},
    {"ear_tip", "the link vertex at the tip of the ear just tested"},
    {"is_ear", "whether the ear just tested is an ear (yes / no)"},
    {"next_ear_tip", "the link vertex at the tip of the ear tested next"},
    {"next_is_ear", "whether the ear tested next is an ear (yes / no)"},
    {"crossed_edges", "edges the constrained segment crosses (the walk along it finds them)"},
    {"sloan_flips", "flips of crossing edges the whole constraint makes (Sloan)"},
    {"sloan_waits", "times a crossing edge waits (its quadrilateral is not convex)"},
    {"next_crossing_edge", "the edge crossing the segment that is looked at next (flip or wait)"},
    {"next_sloan_flips", "whether the next crossing edge looked at flips (yes) or waits (no)"},
    {"repair_tests", "in-circle tests of the edit's repair (Lawson, constrained edges skipped)"},
    {"repair_flips", "flips of the edit's repair"},
    {"edit_ops", "operations of the edit"},
};

bool isEditQuantity(std::string_view name) {
    bool after = false;
    for (const QuantityInfo& q : kQuantities) {
        if (std::string_view(q.name) == "removal_degree") after = true;
        if (after && name == q.name) return true;
    }
    return false;
}

// The canvas label of a virtual vertex ("g" for the ghost, "s0".."s2" for the super-triangle's);
// "" for an input point.
std::string vertexLabel(const Inserter& ins, std::int32_t v) {
    if (v < 0 || !ins.isVirtual(v) || ins.done()) return "";
    return ins.options().boundary == Boundary::Exact ? "g"
                                                     : "s" + std::to_string(v - ins.numInput());
}

struct Unavailable {
    std::string why;
};

// Puts the journal back where it was, whatever happens in between.
class PositionGuard {
public:
    explicit PositionGuard(Journal& j) : m_j(j), m_pos(j.position()) {}
    ~PositionGuard() { m_j.seek(m_pos); }
    PositionGuard(const PositionGuard&) = delete;
    PositionGuard& operator=(const PositionGuard&) = delete;

private:
    Journal& m_j;
    std::size_t m_pos;
};

Answer integer(std::int64_t v, bool corner = false) {
    Answer a;
    a.kind = Answer::Kind::Integer;
    a.a = v;
    a.corner = corner;
    return a;
}
Answer edge(std::int64_t x, std::int64_t y) {
    Answer a;
    a.kind = Answer::Kind::Edge;
    a.a = std::min(x, y);
    a.b = std::max(x, y);
    return a;
}
Answer text(std::string t) {
    Answer a;
    a.kind = Answer::Kind::Text;
    a.text = std::move(t);
    return a;
}
Answer truth(bool t) {
    Answer a;
    a.kind = Answer::Kind::Truth;
    a.truth = t;
    return a;
}

class Quantities {
public:
    Quantities(Inserter& ins, Journal& j, std::int32_t selected)
        : m_ins(ins), m_j(j), m_sel(selected) {}

    Answer get(std::string_view name) {
        if (isEditQuantity(name))
            throw Unavailable{
                "it is about an edit: ask it at a stop inside the lesson's edits "
                "(run_to an edit target such as edit:1 or ear-test)"};
        const Mesh& m = m_ins.mesh();
        const InsertStats& st = m_ins.stats();
        if (name == "triangles") return integer(realTriangles());
        if (name == "all_triangles") return integer(m.numTriangles());
        if (name == "corners") return integer(m.numCorners());
        if (name == "vertices") return integer(realVertices());
        if (name == "input_points") return integer(m_ins.numInput());
        if (name == "position") return integer(static_cast<std::int64_t>(m_j.position()));
        if (name == "op") return text(toString(last().type));
        if (name == "next_op") return text(toString(peek().type));
        if (name == "vertex") return vertexAnswer(needVertex(last().vertex, "the last operation"));
        if (name == "next_vertex")
            return vertexAnswer(needVertex(peek().vertex, "the next operation"));
        if (name == "flips") return integer(st.flips);
        if (name == "tests") return integer(st.inCircleTests);
        if (name == "insertion_flips") return integer(insertionCount(OpType::Flip));
        if (name == "insertion_tests") return integer(insertionCount(OpType::InCircleTest));
        if (name == "queue") return integer(static_cast<std::int64_t>(m_ins.flipStack().size()));
        if (name == "walk_steps") return integer(st.walkSteps);
        if (name == "hint" || name == "locate_steps") return latestLocate(name == "hint");
        if (name == "located" || name == "where") {
            const Op& op = latest(OpType::Located, "no locate has ended yet");
            return name == "located" ? triangleAnswer(op.a) : text(toString(op.where));
        }
        if (name == "test_edge" || name == "test_result") {
            const std::size_t q = latestIndex(OpType::InCircleTest, "no in-circle test yet");
            const Op& op = m_j.ops()[q];
            if (name == "test_result") return integer(op.sign);
            return atPosition(
                q + 1, [&] { return edgeAnswer(mesh().V[next(op.a)], mesh().V[prev(op.a)]); });
        }
        if (std::optional<Answer> a = earlierOps(name)) return *a;
        if (name == "flipped_edge" || name == "new_edge" || name == "previous_flipped_edge" ||
            name == "previous_new_edge") {
            const bool previous = name.starts_with("previous_");
            const std::size_t q =
                previous ? previousFlipIndex() : latestIndex(OpType::Flip, "no flip yet");
            const Op& op = m_j.ops()[q];
            const bool old = name.ends_with("flipped_edge");
            return atPosition(q + 1, [&] {
                const auto& V = mesh().V;
                return old ? edgeAnswer(V[next(op.a)], V[next(op.b)])
                           : edgeAnswer(V[op.a], V[op.b]);
            });
        }
        if (name == "next_flip") return nextFlip(false);
        if (name == "next_new_edge") return nextFlip(true);
        if (name == "duplicates") return integer(st.duplicates);
        if (name == "edge_splits") return integer(st.edgeSplits);
        if (name == "hull_edges") return integer(hullEdges());
        if (name == "convex") return truth(convex());
        if (name == "delaunay_violations") return integer(delaunayViolations());
        if (name == "degree") return integer(degree());
        if (name == "triangles_around" || name == "edges_around")
            return integer(around(name == "edges_around"));
        if (name == "next_test_edge" || name == "will_flip") return nextTest(name == "will_flip");
        if (name == "next_where" || name == "next_located") return nextLocate(name == "next_where");
        if (name == "next_locate_steps") return integer(nextLocateSteps());
        if (name == "changed_corners") return integer(changedCorners());
        if (name == "min_angle") return integer(minAngle());
        if (name == "flips_per_point") {
            if (realVertices() == 0) throw Unavailable{"no point is inserted yet"};
            return integer(
                std::llround(static_cast<double>(st.flips) / static_cast<double>(realVertices())));
        }
        if (name == "incircle_det") return incircleDeterminant();
        if (name == "pixel_outcome") return pixelOutcome();
        if (name == "circumcenter") return circumcenterOfSelection();
        if (name == "pixel") return pixel();
        throw Unavailable{"unknown quantity"};
    }

private:
    const Mesh& mesh() const { return m_ins.mesh(); }
    // The determinant the in-circle test decides by the sign of, as a student works it by hand
    // (exact for small integer coordinates, where its sign is the exact predicate's).
    Answer incircleDeterminant() const {
        const auto f = liftingMapAt(m_ins, m_j.position() ? &last() : nullptr);
        if (!f) throw Unavailable{"no in-circle test of a real triangle here"};
        long double r[3][3];
        for (int k = 0; k < 3; ++k) {
            const long double x = static_cast<long double>(f->triangle[k].x) - f->point.x,
                              y = static_cast<long double>(f->triangle[k].y) - f->point.y;
            r[k][0] = x;
            r[k][1] = y;
            r[k][2] = x * x + y * y;
        }
        const long double det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) -
                                r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) +
                                r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
        if (det != std::nearbyint(det) || std::fabs(det) > 1e15L || (det > 0) != (f->sign > 0))
            throw Unavailable{"the determinant is not a small whole number here"};
        return integer(static_cast<std::int64_t>(det));
    }
    Answer vertexAnswer(std::int64_t v) const {
        Answer a = integer(v);
        a.labelA = vertexLabel(m_ins, static_cast<std::int32_t>(v));
        return a;
    }
    Answer edgeAnswer(std::int32_t x, std::int32_t y) const {
        Answer a = edge(x, y);
        a.labelA = vertexLabel(m_ins, static_cast<std::int32_t>(a.a));
        a.labelB = vertexLabel(m_ins, static_cast<std::int32_t>(a.b));
        return a;
    }
    static Answer triangleAnswer(std::int64_t t) {
        Answer a = integer(t, t < 0);  // no triangle: "none" reads -1 too
        a.triangle = true;
        return a;
    }
    bool virtualTri(std::int32_t t) const {
        const auto& V = mesh().V;
        return m_ins.isVirtual(V[3 * t]) || m_ins.isVirtual(V[3 * t + 1]) ||
               m_ins.isVirtual(V[3 * t + 2]);
    }
    std::int64_t realTriangles() const {
        std::int64_t n = 0;
        for (std::int32_t t = 0; t < mesh().numTriangles(); ++t) n += !virtualTri(t);
        return n;
    }
    std::int64_t realVertices() const {
        std::set<std::int32_t> seen;
        for (std::int32_t v : mesh().V) {
            if (!m_ins.isVirtual(v)) seen.insert(v);
        }
        return static_cast<std::int64_t>(seen.size());
    }
    const Op& last() const {
        if (m_j.position() == 0) throw Unavailable{"nothing has happened yet (operation 0)"};
        return *m_j.current();
    }
    Op peek() {
        if (m_j.atEnd()) throw Unavailable{"the run is finished: there is no next operation"};
        PositionGuard g(m_j);
        return *m_j.forward();
    }
    static std::int64_t needVertex(std::int32_t v, const char* which) {
        if (v == kNone) throw Unavailable{std::string(which) + " works on no point"};
        return v;
    }
    std::size_t latestIndex(OpType type, const char* none) const {
        for (std::size_t q = m_j.position(); q-- > 0;) {
            if (m_j.ops()[q].type == type) return q;
        }
        throw Unavailable{none};
    }
    // The quantities about ops before the latest of their kind: the test before the latest,
    // the insertion with the most flips; nullopt for other names.
    std::optional<Answer> earlierOps(std::string_view name) {
        if (name == "previous_test_edge" || name == "previous_test_result") {
            const std::size_t q = previousTestIndex();
            const Op& op = m_j.ops()[q];
            if (name == "previous_test_result") return integer(op.sign);
            return atPosition(
                q + 1, [&] { return edgeAnswer(mesh().V[next(op.a)], mesh().V[prev(op.a)]); });
        }
        if (name == "most_flips" || name == "most_flips_vertex") {
            const auto [flips, vertex] = mostFlips();
            return name == "most_flips" ? integer(flips) : vertexAnswer(vertex);
        }
        return std::nullopt;
    }
    // The most flips one insertion took up to now, and its point.
    std::pair<std::int64_t, std::int64_t> mostFlips() const {
        std::int64_t most = -1, mostVertex = kNone, flips = 0;
        for (std::size_t q = 0; q < m_j.position(); ++q) {
            const Op& op = m_j.ops()[q];
            if (op.type == OpType::Flip) ++flips;
            if (!endsInsertion(op.type)) continue;
            if (op.vertex != kNone && flips > most) {
                most = flips;
                mostVertex = op.vertex;
            }
            flips = 0;
        }
        if (mostVertex == kNone) throw Unavailable{"no insertion has ended yet"};
        return {most, mostVertex};
    }
    // The flip before the latest one.
    std::size_t previousFlipIndex() const {
        std::size_t q = latestIndex(OpType::Flip, "no flip yet");
        while (q-- > 0) {
            if (m_j.ops()[q].type == OpType::Flip) return q;
        }
        throw Unavailable{"the latest flip is the first"};
    }
    // The in-circle test before the latest one, within the insertion of the latest.
    std::size_t previousTestIndex() const {
        std::size_t q = latestIndex(OpType::InCircleTest, "no in-circle test yet");
        while (q-- > 0) {
            const OpType t = m_j.ops()[q].type;
            if (t == OpType::InCircleTest) return q;
            if (endsInsertion(t)) break;
        }
        throw Unavailable{"the latest in-circle test is the first of its insertion"};
    }
    const Op& latest(OpType type, const char* none) const {
        return m_j.ops()[latestIndex(type, none)];
    }
    template <class F>
    Answer atPosition(std::size_t p, F&& f) {
        PositionGuard g(m_j);
        m_j.seek(p);
        return f();
    }
    std::int64_t insertionCount(OpType type) const {
        std::size_t q = m_j.position();
        if (q > 0 && endsInsertion(m_j.ops()[q - 1].type)) --q;  // the insertion that just ended
        std::int64_t n = 0;
        while (q > 0 && !endsInsertion(m_j.ops()[q - 1].type)) {
            const Op& op = m_j.ops()[--q];
            // An edge on the boundary comes off the stack with nothing to test: not a test.
            n += op.type == type && (type != OpType::InCircleTest || op.b != kNone);
        }
        return n;
    }
    Answer latestLocate(bool wantHint) const {
        std::size_t q = m_j.position();
        while (q > 0 && m_j.ops()[q - 1].type != OpType::LocateStep &&
               m_j.ops()[q - 1].type != OpType::Located)
            --q;
        if (q == 0) throw Unavailable{"no locate yet"};
        std::size_t first = q - 1;
        const std::int32_t v = m_j.ops()[first].vertex;
        while (first > 0 && m_j.ops()[first - 1].type == OpType::LocateStep &&
               m_j.ops()[first - 1].vertex == v)
            --first;
        if (wantHint) return triangleAnswer(m_j.ops()[first].a);
        std::int64_t steps = 0;
        for (std::size_t i = first; i < q; ++i) steps += m_j.ops()[i].type == OpType::LocateStep;
        return integer(steps);
    }
    Answer nextFlip(bool made) {
        if (m_j.atEnd()) throw Unavailable{"the run is finished: nothing flips any more"};
        PositionGuard g(m_j);
        while (const Op* op = m_j.forward()) {
            if (op->type == OpType::Flip) {
                const auto& V = mesh().V;
                return made ? edgeAnswer(V[op->a], V[op->b])
                            : edgeAnswer(V[next(op->a)], V[next(op->b)]);
            }
            if (endsInsertion(op->type)) break;
        }
        return text("none");
    }
    bool hullCorner(std::int32_t c) const {
        const std::int32_t o = mesh().O[c];
        return o == kNone || virtualTri(tri(o));
    }
    std::int64_t hullEdges() const {
        std::int64_t n = 0;
        for (std::int32_t c = 0; c < mesh().numCorners(); ++c)
            n += !virtualTri(tri(c)) && hullCorner(c);
        return n;
    }
    bool convex() const {
        const Mesh& m = mesh();
        std::set<std::int32_t> verts;
        for (std::int32_t c = 0; c < m.numCorners(); ++c) {
            if (!virtualTri(tri(c))) verts.insert(m.V[c]);
        }
        for (std::int32_t c = 0; c < m.numCorners(); ++c) {
            if (virtualTri(tri(c)) || !hullCorner(c)) continue;
            const Vec2 a = m.G[m.V[next(c)]], b = m.G[m.V[prev(c)]];
            for (std::int32_t w : verts) {
                if (orient2d(a, b, m.G[w]) < 0) return false;
            }
        }
        return true;
    }
    std::int64_t delaunayViolations() const {
        ValidateOptions o;
        o.geometry = false;
        o.firstVirtual = m_ins.done() ? -1 : m_ins.firstVirtual();
        o.maxViolations = std::numeric_limits<std::size_t>::max();
        std::set<std::int32_t> edges;  // each bad edge may be found from both sides: count it once
        for (const Violation& v : validate(mesh(), o)) {
            if (v.kind != Violation::Kind::NotDelaunay) continue;
            const std::int32_t other = mesh().O[v.corner];
            edges.insert(other == kNone ? v.corner : std::min(v.corner, other));
        }
        return static_cast<std::int64_t>(edges.size());
    }
    std::int64_t degree() const {
        const Mesh& m = mesh();
        if (m_sel < 0 || m_sel >= m.numCorners())
            throw Unavailable{"degree needs a selected corner"};
        std::int64_t n = 1;
        std::int32_t c = m.s(m_sel);
        for (; c != kNone && c != m_sel && n <= m.numCorners(); c = m.s(c)) ++n;
        if (c == kNone) {  // open fan: count the other way too
            for (c = m.u(m_sel); c != kNone && n <= m.numCorners(); c = m.u(c)) ++n;
        }
        return n;
    }
    // The corners around the selected corner's vertex (all of them, virtual triangles too).
    std::vector<std::int32_t> fan() const {
        const Mesh& m = mesh();
        if (m_sel < 0 || m_sel >= m.numCorners()) throw Unavailable{"this needs a selected corner"};
        std::vector<std::int32_t> out{m_sel};
        std::int32_t c = m.s(m_sel);
        for (; c != kNone && c != m_sel && out.size() <= std::size_t(m.numCorners()); c = m.s(c))
            out.push_back(c);
        if (c == kNone) {
            for (c = m.u(m_sel); c != kNone && out.size() <= std::size_t(m.numCorners());
                 c = m.u(c))
                out.push_back(c);
        }
        return out;
    }
    std::int64_t around(bool edges) const {
        const Mesh& m = mesh();
        std::set<std::int32_t> neighbours;
        std::int64_t triangles = 0;
        for (std::int32_t c : fan()) {
            triangles += !virtualTri(tri(c));
            for (std::int32_t w : {m.V[next(c)], m.V[prev(c)]}) {
                if (!m_ins.isVirtual(w)) neighbours.insert(w);
            }
        }
        return edges ? static_cast<std::int64_t>(neighbours.size()) : triangles;
    }
    // The next op of `type` in this insertion, with the journal just after it (restored by g).
    const Op* findAhead(OpType type) {
        while (const Op* op = m_j.forward()) {
            if (op->type == type) return op;
            if (endsInsertion(op->type)) break;
        }
        return nullptr;
    }
    Answer nextTest(bool wantFlip) {
        PositionGuard g(m_j);
        const Op* op = findAhead(OpType::InCircleTest);
        if (!op) throw Unavailable{"no in-circle test follows in this insertion"};
        if (wantFlip) return truth(op->sign > 0);
        return edgeAnswer(mesh().V[next(op->a)], mesh().V[prev(op->a)]);
    }
    Answer nextLocate(bool wantWhere) {
        PositionGuard g(m_j);
        const Op* op = findAhead(OpType::Located);
        if (!op) throw Unavailable{"no locate follows in this insertion"};
        return wantWhere ? text(toString(op->where)) : triangleAnswer(op->a);
    }
    std::int64_t nextLocateSteps() {
        PositionGuard g(m_j);
        std::int64_t steps = 0;
        while (const Op* op = m_j.forward()) {
            steps += op->type == OpType::LocateStep;
            if (op->type == OpType::Located) return steps;
            if (endsInsertion(op->type)) break;
        }
        throw Unavailable{"no locate follows in this insertion"};
    }
    std::int64_t changedCorners() const {
        const Op& op = last();
        std::set<std::int32_t> corners;
        for (std::uint32_t i = 0; i < op.numChanges; ++i)
            corners.insert(m_j.changes()[op.firstChange + i].corner());
        return static_cast<std::int64_t>(corners.size());
    }
    // The smallest angle of the real triangles in whole degrees (a measurement to show, not a
    // decision: no predicate depends on it).
    std::int64_t minAngle() const {
        const Mesh& m = mesh();
        double least = 180;
        bool any = false;
        for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
            if (virtualTri(t)) continue;
            for (int k = 0; k < 3; ++k) {
                const Vec2 a = m.G[m.V[3 * t + k]], b = m.G[m.V[3 * t + (k + 1) % 3]],
                           c = m.G[m.V[3 * t + (k + 2) % 3]];
                const double ux = b.x - a.x, uy = b.y - a.y, vx = c.x - a.x, vy = c.y - a.y;
                const double angle = std::atan2(std::abs(ux * vy - uy * vx), ux * vx + uy * vy) *
                                     180 / 3.14159265358979;
                least = std::min(least, angle);
                any = true;
            }
        }
        if (!any) throw Unavailable{"there is no real triangle yet"};
        return static_cast<std::int64_t>(std::floor(least + 0.5));
    }
    Answer pixelOutcome() {
        auto* buffer = dynamic_cast<IdBufferCpu*>(m_ins.locator());
        if (!buffer) throw Unavailable{"pixel_outcome needs locator = \"idbuffer-cpu\""};
        const Op& located = latest(OpType::Located, "no locate has ended yet");
        const std::int64_t steps = latestLocate(false).a;
        std::size_t first = latestIndex(OpType::Located, "");
        while (first > 0 && m_j.ops()[first - 1].type == OpType::LocateStep) --first;
        const std::int32_t v = located.vertex;
        const std::int32_t inTri = located.a;
        PositionGuard g(m_j);
        m_j.seek(first);
        const std::int32_t pixel = buffer->pixelAt(mesh().G[v]);
        if (pixel < 0) return text("empty");
        return text(steps == 0 && pixel == inTri ? "hit" : "miss");
    }
    Answer circumcenterOfSelection() const {
        const Mesh& m = mesh();
        if (m_sel < 0 || m_sel >= m.numCorners())
            throw Unavailable{"circumcenter needs a selected corner"};
        const std::int32_t t = tri(m_sel);
        if (virtualTri(t))
            throw Unavailable{"the selected corner's triangle is a ghost or super triangle"};
        Answer a;
        a.kind = Answer::Kind::Point;
        a.point = circumcenter(m.G[m.V[3 * t]], m.G[m.V[3 * t + 1]], m.G[m.V[3 * t + 2]]);
        return a;
    }
    Answer pixel() {
        auto* buffer = dynamic_cast<IdBufferCpu*>(m_ins.locator());
        if (!buffer) throw Unavailable{"pixel needs locator = \"idbuffer-cpu\""};
        const Op next = peek();
        if (next.type != OpType::LocateStep && next.type != OpType::Located) {
            throw Unavailable{"pixel: the next operation locates no point"};
        }
        return triangleAnswer(buffer->pixelAt(mesh().G[next.vertex]));
    }

    Inserter& m_ins;
    Journal& m_j;
    std::int32_t m_sel;
};

// The words that may follow a quantity's number: what it counts ("8 steps", "32 degrees").
std::vector<std::string> quantityUnits(std::string_view name) {
    struct Units {
        const char* name;
        std::initializer_list<const char*> words;
    };
    static const Units kUnits[] = {
        {"triangles", {"triangles", "triangle"}},
        {"all_triangles", {"triangles", "triangle"}},
        {"corners", {"corners", "corner", "rows", "row"}},
        {"vertices", {"vertices", "vertex", "points", "point"}},
        {"input_points", {"points", "point"}},
        {"position", {"operations", "operation", "ops", "op"}},
        {"flips", {"flips", "flip", "times", "time"}},
        {"insertion_flips", {"flips", "flip", "times", "time"}},
        {"tests",
         {"in-circle tests", "incircle tests", "in circle tests", "tests", "test", "times",
          "time"}},
        {"insertion_tests",
         {"in-circle tests", "incircle tests", "in circle tests", "tests", "test", "times",
          "time"}},
        {"queue", {"edges", "edge"}},
        {"walk_steps", {"steps", "step"}},
        {"locate_steps", {"steps", "step"}},
        {"next_locate_steps", {"steps", "step"}},
        {"duplicates", {"duplicates", "duplicate", "points", "point"}},
        {"edge_splits", {"splits", "split"}},
        {"hull_edges", {"edges", "edge", "sides", "side"}},
        {"delaunay_violations", {"edges", "edge"}},
        {"degree", {"triangles", "triangle"}},
        {"triangles_around", {"triangles", "triangle", "times", "time", "presses", "press"}},
        {"edges_around", {"edges", "edge", "neighbours", "neighbour", "neighbors", "neighbor"}},
        {"changed_corners", {"corners", "corner"}},
        {"min_angle", {"degrees", "degree", "deg", "\u00b0"}},
        {"removal_degree", {"triangles", "triangle"}},
        {"degree_left", {"triangles", "triangle"}},
        {"ear_tests", {"ear tests", "ear test", "tests", "test"}},
        {"ear_flips", {"flips", "flip", "ear flips", "ear flip"}},
        {"crossed_edges", {"edges", "edge"}},
        {"sloan_flips", {"flips", "flip"}},
        {"sloan_waits", {"times", "time", "waits", "wait"}},
        {"repair_tests", {"in-circle tests", "incircle tests", "tests", "test"}},
        {"repair_flips", {"flips", "flip"}},
        {"edit_ops", {"operations", "operation", "ops", "op"}},
    };
    for (const Units& u : kUnits) {
        if (name == u.name) return {u.words.begin(), u.words.end()};
    }
    return {};
}

const QuantityInfo* findQuantity(std::string_view name) {
    for (const QuantityInfo& q : kQuantities) {
        if (name == q.name) return &q;
    }
    return nullptr;
}

std::string quantityNames() {
    std::string s;
    for (const QuantityInfo& q : kQuantities) s += std::string(s.empty() ? "" : ", ") + q.name;
    return s;
}

ExprContext exprContext(const Inserter& ins) {
    return ExprContext{ins.firstVirtual(),
                       ins.options().boundary == Boundary::Exact && !ins.done()};
}

std::vector<ExprBinding> selectionBinding(std::int32_t selected) {
    if (selected == kNone) return {};
    return {ExprBinding{"c", ExprValue{ValueKind::Corner, selected, {}, false}}};
}

}  // namespace

std::span<const QuantityInfo> lessonQuantities() { return kQuantities; }

std::optional<Answer> computeAnswer(std::string_view specIn, Inserter& ins, Journal& journal,
                                    std::int32_t selected, std::string* error, Editor* edits) {
    if (edits) {
        std::optional<Answer> a = computeEditAnswer(specIn, *edits, error);
        if (a && a->kind == Answer::Kind::Integer) a->units = quantityUnits(trimmed(specIn));
        return a;
    }
    const std::string spec = trimmed(specIn);
    auto fail = [&](const std::string& why) -> std::optional<Answer> {
        if (error) *error = why;
        return std::nullopt;
    };
    if (findQuantity(spec)) {
        try {
            Answer a = Quantities(ins, journal, selected).get(spec);
            if (a.kind == Answer::Kind::Integer) a.units = quantityUnits(spec);
            return a;
        } catch (const Unavailable& u) {
            return fail(spec + " is not available here: " + u.why);
        }
    }
    ExprError perr;
    const auto expr = CornerExpr::parse(spec, &perr);
    if (!expr) {
        return fail("\"" + spec + "\" is neither a quantity (" + quantityNames() +
                    ") nor a corner expression (column " + std::to_string(perr.column + 1) + ": " +
                    perr.message + ")");
    }
    const auto bindings = selectionBinding(selected);
    const ExprResult r = expr->evaluate(ins.mesh(), bindings, exprContext(ins));
    if (!r.ok()) return fail(spec + ": " + r.error.message);
    const ExprValue& v = *r.value;
    switch (v.kind) {
        case ValueKind::Point: {
            Answer a;
            a.kind = Answer::Kind::Point;
            a.point = v.point;
            return a;
        }
        case ValueKind::Truth: return truth(v.truth);
        case ValueKind::Vertex: {
            Answer a = integer(v.i);
            a.labelA = vertexLabel(ins, static_cast<std::int32_t>(v.i));
            return a;
        }
        case ValueKind::Triangle: {
            Answer a = integer(v.i);
            a.triangle = true;
            return a;
        }
        default: return integer(v.i, v.kind == ValueKind::Corner);
    }
}

// ============================================================================================
// [SECTION] Loading
// ============================================================================================

std::string resolveLessonFile(const std::string& lessonPath, const std::string& relative,
                              int line) {
    auto fail = [&](const std::string& why) -> LessonError {
        return LessonError(lessonPath, line, 0, why);
    };
    if (relative.empty()) throw fail("points_file is empty");
    if (relative.find('\0') != std::string::npos)
        throw fail("points_file contains a NUL character");
    const fs::path rel(relative);
    if (rel.is_absolute() || relative[0] == '/' || relative[0] == '\\' || rel.has_root_name()) {
        throw fail("points_file \"" + relative +
                   "\" must be relative to the lesson's folder, not absolute");
    }
    for (const fs::path& part : rel) {
        if (part == "..")
            throw fail("points_file \"" + relative +
                       "\" must stay inside the lesson's folder (no \"..\")");
    }
    std::error_code ec;
    fs::path base = fs::path(lessonPath).parent_path();
    if (base.empty()) base = ".";
    const fs::path folder = fs::canonical(base, ec);
    if (ec) throw fail("cannot resolve the lesson's folder: " + ec.message());
    const fs::path target = fs::canonical(folder / rel, ec);
    if (ec)
        throw fail("points_file \"" + relative + "\" not found beside the lesson (" + ec.message() +
                   ")");
    // Compare component by component: /a/lessons-evil is not inside /a/lessons.
    auto t = target.begin();
    for (auto f = folder.begin(); f != folder.end(); ++f, ++t) {
        if (t == target.end() || *t != *f) {
            throw fail("points_file \"" + relative +
                       "\" leads outside the lesson's folder (through a symbolic link)");
        }
    }
    if (!fs::is_regular_file(target, ec))
        throw fail("points_file \"" + relative + "\" is not a regular file");
    return target.string();
}

namespace {

int lineOf(const toml::node& n) { return static_cast<int>(n.source().begin.line); }

// Why `text` cannot be a lesson's corner expression ("" when it can): a syntax error, or a name
// other than c (the selected corner), caught at load time rather than at the stop.
std::string expressionProblem(const std::string& text) {
    ExprError e;
    const auto expr = CornerExpr::parse(text, &e);
    if (!expr) return "column " + std::to_string(e.column + 1) + ": " + e.message;
    for (const std::string& v : expr->variables()) {
        if (v != "c") return "unknown name '" + v + "': the only name is c, the selected corner";
    }
    return "";
}

class LessonReader {
public:
    explicit LessonReader(const std::string& file) : m_file(file) {}

    [[noreturn]] void fail(int line, const std::string& message) const {
        throw LessonError(m_file, line, m_stop, message);
    }

    void checkKeys(const toml::table& t, std::initializer_list<const char*> known,
                   const char* where) {
        for (auto&& [key, value] : t) {
            // A plain copy for the lambda: clang 14 cannot capture a structured binding.
            const std::string_view name = key.str();
            const bool ok =
                std::any_of(known.begin(), known.end(), [&](const char* k) { return name == k; });
            if (!ok) {
                fail(static_cast<int>(key.source().begin.line),
                     "unknown key \"" + std::string(key.str()) + "\" " + where +
                         " (known: " + joinNames(known) + ")");
            }
        }
    }

    std::optional<std::string> string(const toml::table& t, const char* key) {
        const toml::node* n = t.get(key);
        if (!n) return std::nullopt;
        if (!n->is_string()) fail(lineOf(*n), std::string("\"") + key + "\" must be a string");
        return n->as_string()->get();
    }

    std::optional<std::int64_t> integer(const toml::table& t, const char* key, std::int64_t lo,
                                        std::int64_t hi) {
        const toml::node* n = t.get(key);
        if (!n) return std::nullopt;
        if (!n->is_integer())
            fail(lineOf(*n), std::string("\"") + key + "\" must be a whole number");
        const std::int64_t v = n->as_integer()->get();
        if (v < lo || v > hi) {
            fail(lineOf(*n), std::string("\"") + key + "\" must be between " + std::to_string(lo) +
                                 " and " + std::to_string(hi));
        }
        return v;
    }

    std::vector<std::string> names(const toml::table& t, const char* key,
                                   std::span<const char* const> known) {
        std::vector<std::string> out;
        const toml::node* n = t.get(key);
        if (!n) return out;
        const toml::array* a = n->as_array();
        if (!a)
            fail(lineOf(*n), std::string("\"") + key + "\" must be a list of names, e.g. [\"" +
                                 known[0] + "\"]");
        for (const toml::node& e : *a) {
            if (!e.is_string())
                fail(lineOf(e), std::string("\"") + key + "\" must hold names (strings)");
            const std::string name = e.as_string()->get();
            if (std::none_of(known.begin(), known.end(),
                             [&](const char* k) { return name == k; })) {
                fail(lineOf(e), std::string("unknown ") +
                                    (std::string(key) == "panels" ? "panel" : "overlay") + " \"" +
                                    name + "\" (known: " + joinNames(known) + ")");
            }
            out.push_back(name);
        }
        return out;
    }

    void text(const std::string& s, int line) {
        std::string why;
        if (!parseLessonText(s, &why)) fail(line, why);
    }

    // objectives = ["...", ...]: one line each, Markdown-light, at most 8.
    std::vector<std::string> objectives(const toml::table& t, bool required) {
        std::vector<std::string> out;
        const toml::node* n = t.get("objectives");
        if (!n) {
            if (required) fail(1, "the track needs \"objectives\" = [\"...\", ...]");
            return out;
        }
        const toml::array* a = n->as_array();
        if (!a || a->empty() || a->size() > 8)
            fail(lineOf(*n), "\"objectives\" must be a list of 1 to 8 sentences (strings)");
        for (const toml::node& e : *a) {
            const int line = lineOf(e) ? lineOf(e) : lineOf(*n);
            if (!e.is_string() || trimmed(e.as_string()->get()).empty())
                fail(line, "\"objectives\" must hold sentences (strings that are not empty)");
            const std::string o = trimmed(e.as_string()->get());
            if (o.find('\n') != std::string::npos) fail(line, "an objective is one line");
            text(o, line);
            out.push_back(o);
        }
        return out;
    }

    // The file's TOML, refused when too large or not valid TOML ("lesson" or "track" file).
    toml::table parseToml(std::string_view source, const std::string& path, const char* what) {
        if (source.size() > kMaxLessonFileBytes)
            fail(0, std::string(what) + " file too large (at most 1 MiB)");
        try {
            return toml::parse(source, path);
        } catch (const toml::parse_error& e) {
            fail(static_cast<int>(e.source().begin.line),
                 "not valid TOML: " + std::string(e.description()));
        }
    }

    // A track: [[item]] lesson / stops / minutes, each lesson loaded and its stops checked.
    Track track(std::string_view source, const std::string& path) {
        Track T;
        T.file = path;
        toml::table root = parseToml(source, path, "track");
        checkKeys(root, {"title", "summary", "kind", "objectives", "minutes", "item"},
                  "at the top level of a track");
        if (string(root, "kind").value_or("") != "track") fail(1, "a track says kind = \"track\"");
        T.title = string(root, "title").value_or("");
        if (trimmed(T.title).empty()) fail(1, "the track needs a \"title\"");
        T.summary = string(root, "summary").value_or("");
        T.objectives = objectives(root, true);
        const auto minutes = integer(root, "minutes", 1, 300);
        if (!minutes) fail(1, "the track needs \"minutes\": the lecture's length");
        T.minutes = static_cast<int>(*minutes);
        const toml::node* items = root.get("item");
        const toml::array* a = items ? items->as_array() : nullptr;
        if (!a || !a->is_array_of_tables() || a->empty())
            fail(items ? lineOf(*items) : 1, "a track lists its stops as [[item]] tables");
        int total = 0;
        for (const toml::node& n : *a) {
            T.items.push_back(trackItem(*n.as_table(), path));
            total += T.items.back().minutes;
            if (total > T.minutes)
                fail(T.items.back().line, "the items' minutes add up to " + std::to_string(total) +
                                              " here, more than the track's " +
                                              std::to_string(T.minutes));
        }
        if (T.slides() > kMaxLessonStops) fail(1, "too many stops in the track");
        return T;
    }

    TrackItem trackItem(const toml::table& t, const std::string& path) {
        TrackItem item;
        item.line = lineOf(t);
        checkKeys(t, {"lesson", "stops", "minutes"}, "in an [[item]]");
        const auto written = string(t, "lesson");
        if (!written) fail(item.line, "an [[item]] needs \"lesson\" (a lesson file)");
        item.written = *written;
        item.lesson = resolveLessonFile(path, *written, lineOf(*t.get("lesson")));
        const auto minutes = integer(t, "minutes", 1, 300);
        if (!minutes) fail(item.line, "an [[item]] needs \"minutes\"");
        item.minutes = static_cast<int>(*minutes);
        Lesson lesson;
        try {
            lesson = loadLesson(item.lesson);
        } catch (const LessonError& e) {
            fail(item.line, "lesson " + *written + ": " + e.what());
        }
        if (lesson.objectives.empty() || lesson.minutes == 0)
            fail(item.line, "lesson " + *written +
                                " states no objectives or minutes (objectives = [...], minutes = "
                                "N): a lesson in a track needs both");
        const toml::node* stops = t.get("stops");
        const toml::array* list = stops ? stops->as_array() : nullptr;
        if (!list || list->empty())
            fail(stops ? lineOf(*stops) : item.line, "an [[item]] needs \"stops\" = [1, 2, ...]");
        for (const toml::node& e : *list) {
            const int line = lineOf(e) ? lineOf(e) : lineOf(*stops);
            const auto k = e.value<std::int64_t>();
            if (!e.is_integer() || !k || *k < 1 ||
                *k > static_cast<std::int64_t>(lesson.stops.size()))
                fail(line, "lesson " + *written + " has stops 1 to " +
                               std::to_string(lesson.stops.size()) + ": no stop " +
                               (e.is_integer() ? std::to_string(*k) : std::string("there")));
            if (!item.stops.empty() && static_cast<std::size_t>(*k - 1) <= item.stops.back())
                fail(line, "an item's stops go forward: " + std::to_string(*k) + " after " +
                               std::to_string(item.stops.back() + 1));
            item.stops.push_back(static_cast<std::size_t>(*k - 1));
        }
        return item;
    }

    void options(const toml::table& t, InsertOptions& o) {
        checkKeys(t, {"boundary", "locator", "order", "seed", "idbuffer_size"}, "in [options]");
        if (auto s = string(t, "boundary")) {
            const auto b = parseBoundary(*s);
            if (!b)
                fail(lineOf(*t.get("boundary")),
                     "boundary must be \"exact\" or \"super\", not \"" + *s + "\"");
            o.boundary = *b;
        }
        if (auto s = string(t, "locator")) {
            const auto k = parseLocatorKind(*s);
            if (!k)
                fail(lineOf(*t.get("locator")),
                     "locator must be naive, walk, grid or idbuffer-cpu, not \"" + *s + "\"");
            o.locator = *k;
        }
        if (auto s = string(t, "order")) {
            const auto k = parseOrderKind(*s);
            if (!k)
                fail(lineOf(*t.get("order")),
                     "order must be input, random or brio, not \"" + *s + "\"");
            o.order = *k;
        }
        if (auto v = integer(t, "seed", 0, std::numeric_limits<std::int64_t>::max()))
            o.seed = static_cast<std::uint64_t>(*v);
        if (auto v = integer(t, "idbuffer_size", 1, 4096)) {
            o.locatorOptions.idBufferWidth = o.locatorOptions.idBufferHeight = static_cast<int>(*v);
        }
    }

    std::vector<Vec2> points(const toml::node& n) {
        const toml::array* a = n.as_array();
        if (!a) fail(lineOf(n), "\"points\" must be a list of [x, y] pairs");
        if (a->size() > kMaxLessonPoints) {
            fail(lineOf(n),
                 "too many points for a lesson (at most " + std::to_string(kMaxLessonPoints) + ")");
        }
        std::vector<Vec2> out;
        for (const toml::node& p : *a) {
            const toml::array* xy = p.as_array();
            if (!xy || xy->size() != 2)
                fail(lineOf(p), "point " + std::to_string(out.size()) + " must be [x, y]");
            double c[2];
            for (int k = 0; k < 2; ++k) {
                const toml::node& e = *xy->get(static_cast<std::size_t>(k));
                if (e.is_integer()) {
                    c[k] = static_cast<double>(e.as_integer()->get());
                } else if (e.is_floating_point()) {
                    c[k] = e.as_floating_point()->get();
                } else {
                    fail(lineOf(e),
                         "point " + std::to_string(out.size()) + ": coordinates must be numbers");
                }
                if (!std::isfinite(c[k]))
                    fail(lineOf(e),
                         "point " + std::to_string(out.size()) + ": coordinates must be finite");
            }
            out.push_back({c[0], c[1]});
        }
        return out;
    }

    // points = [...] or points_file = "...": exactly one of them.
    void lessonPoints(const toml::table& root, const std::string& path, Lesson& L) {
        const toml::node* inl = root.get("points");
        const auto file = string(root, "points_file");
        if (inl && file) fail(lineOf(*inl), "give either \"points\" or \"points_file\", not both");
        if (!inl && !file)
            fail(1, "the lesson needs \"points\" (a list of [x, y]) or \"points_file\"");
        if (inl) {
            L.points = points(*inl);
            return;
        }
        const int line = lineOf(*root.get("points_file"));
        L.pointsFile = resolveLessonFile(path, *file, line);
        try {
            PointSet set = readPointsFile(L.pointsFile);
            L.points = std::move(set.points);
        } catch (const InputError& e) {
            fail(line, "cannot read points_file: " + std::string(e.what()));
        }
        if (L.points.size() > kMaxLessonPoints) {
            fail(line,
                 "too many points for a lesson (at most " + std::to_string(kMaxLessonPoints) + ")");
        }
    }

    // triangles = [[0, 1, 2], ...]: the flip algorithm's start, a valid triangulation of the
    // points as checkMesh finds it (its O is the one checkMesh computes).
    Inserter::StartMesh startMesh(const toml::node& n, const std::vector<Vec2>& pts) {
        const toml::array* a = n.as_array();
        if (!a || a->empty())
            fail(lineOf(n), "\"triangles\" must be a list of [a, b, c] vertex ids");
        if (a->size() > 2 * kMaxLessonPoints) fail(lineOf(n), "too many triangles for a lesson");
        const auto at = [&](const toml::node& x) { return lineOf(x) ? lineOf(x) : lineOf(n); };
        Mesh mesh;
        mesh.G = pts;
        for (const toml::node& t : *a) {
            const std::string which = "triangle " + std::to_string(mesh.numTriangles());
            const toml::array* abc = t.as_array();
            if (!abc || abc->size() != 3)
                fail(at(t), which + " must be [a, b, c]: three vertex ids");
            for (const toml::node& e : *abc) {
                if (!e.is_integer()) fail(at(e), which + ": vertex ids must be whole numbers");
                const std::int64_t v = e.as_integer()->get();
                if (v < 0 || v >= static_cast<std::int64_t>(pts.size()))
                    fail(at(e), which + " names vertex " + std::to_string(v) +
                                    ", but the points are numbered from 0 to " +
                                    std::to_string(static_cast<std::int64_t>(pts.size()) - 1));
                mesh.V.push_back(static_cast<std::int32_t>(v));
            }
        }
        mesh.O.assign(mesh.V.size(), kNone);  // not given: checkMesh computes it
        CheckReport report = checkMesh(mesh);
        if (!report.isTriangulation())
            fail(lineOf(n), "\"triangles\" refused: " + report.summary() + firstProblem(report));
        Inserter::StartMesh start;
        start.V = std::move(mesh.V);
        start.O = std::move(report.opposites);
        return start;
    }

    // " (first: ...)": the first problem that blocks the flip algorithm, in its own words.
    static std::string firstProblem(const CheckReport& report) {
        for (const MeshProblem& p : report.problems) {
            if (blocksRepair(p.kind) && !p.message.empty()) return " (first: " + p.message + ")";
        }
        return "";
    }

    LessonStop stop(const toml::table& t) {
        LessonStop s;
        s.line = lineOf(t);
        checkKeys(t,
                  {"run_to", "count", "panels", "overlays", "select", "text", "question", "answer",
                   "hint", "view", "tab", "expect", "figure", "needs"},
                  "in a [[stop]]");
        if (auto r = string(t, "run_to")) {
            std::string why;
            s.runTo = parseBreakpoint(*r, &why);
            if (!s.runTo) fail(lineOf(*t.get("run_to")), "run_to: " + why);
        }
        if (auto c = integer(t, "count", 1, 1000000)) {
            if (!s.runTo) fail(lineOf(*t.get("count")), "\"count\" needs a \"run_to\"");
            if (s.runTo->kind == BreakKind::Op && *c != 1)
                fail(lineOf(*t.get("count")), "\"count\" makes no sense with op:N");
            s.count = static_cast<int>(*c);
        }
        s.panels = names(t, "panels", kPanelNames);
        s.overlays = names(t, "overlays", kOverlayNames);
        if (auto sel = string(t, "select")) {
            const std::string why = expressionProblem(*sel);
            if (!why.empty()) fail(lineOf(*t.get("select")), "select \"" + *sel + "\": " + why);
            s.select = *sel;
        }
        if (auto x = string(t, "text")) {
            text(*x, lineOf(*t.get("text")));
            s.text = *x;
        }
        s.question = string(t, "question").value_or("");
        s.hint = string(t, "hint").value_or("");
        if (auto a = string(t, "answer")) {
            s.answer = trimmed(*a);
            s.answerLine = lineOf(*t.get("answer"));
        }
        if (!s.question.empty() && s.answer.empty())
            fail(s.line, "the question has no \"answer\" (a quantity or a corner expression)");
        if (s.question.empty() && !s.answer.empty())
            fail(s.answerLine, "an \"answer\" needs a \"question\"");
        if (!s.hint.empty() && s.question.empty())
            fail(lineOf(*t.get("hint")), "a \"hint\" needs a \"question\"");
        if (!s.answer.empty() && !findQuantity(s.answer)) {
            const std::string why = expressionProblem(s.answer);
            if (!why.empty()) {
                fail(s.answerLine, "answer \"" + s.answer + "\" is neither a quantity (" +
                                       quantityNames() + ") nor a corner expression (" + why + ")");
            }
        }
        if (s.text.empty() && s.question.empty())
            fail(s.line, "a stop needs a \"text\" or a \"question\"");
        stopView(t, s);
        stopTab(t, s);
        s.textLine = contentLine(t, "text");
        s.questionLine = contentLine(t, "question");
        s.hintLine = contentLine(t, "hint");
        embedded(s.text, s.textLine, "text");
        embedded(s.question, s.questionLine, "question");
        embedded(s.hint, s.hintLine, "hint");
        s.expect = expectations(t);
        s.figure = figure(t);
        stopNeeds(t, s);
        return s;
    }

    // view = { fit = [0, 4, 7] } (vertex ids) or view = { rect = [x0, y0, x1, y1] }.
    void stopView(const toml::table& t, LessonStop& s) {
        const toml::node* n = t.get("view");
        if (!n) return;
        const char* form =
            "view = { fit = [0, 4, 7] } (vertices) or view = { rect = [x0, y0, "
            "x1, y1] }";
        const toml::table* v = n->as_table();
        if (!v) fail(lineOf(*n), std::string("\"view\" must be ") + form);
        checkKeys(*v, {"fit", "rect"}, "in a view");
        const toml::array* fit = v->get("fit") ? v->get("fit")->as_array() : nullptr;
        const toml::array* rect = v->get("rect") ? v->get("rect")->as_array() : nullptr;
        if ((v->get("fit") && !fit) || (v->get("rect") && !rect) || (!fit && !rect) ||
            (fit && rect))
            fail(lineOf(*n), std::string("\"view\" must be ") + form);
        if (fit) {
            for (const toml::node& e : *fit) {
                const auto id = e.value<std::int64_t>();
                if (!e.is_integer() || !id || *id < 0 ||
                    *id >= static_cast<std::int64_t>(m_numVertices))
                    fail(lineOf(e), "view: fit takes vertex numbers from 0 to " +
                                        std::to_string(m_numVertices - 1));
                s.view.fit.push_back(static_cast<std::int32_t>(*id));
            }
            if (s.view.fit.empty()) fail(lineOf(*n), "view: fit needs at least one vertex");
        }
        if (rect) {
            std::array<double, 4> r{};
            if (rect->size() != 4)
                fail(lineOf(*n), "view: rect is [x0, y0, x1, y1] with x0 < x1 and y0 < y1");
            for (std::size_t k = 0; k < 4; ++k) {
                const auto x = (*rect)[k].value<double>();
                if (!x) fail(lineOf(*n), "view: rect holds numbers only ([x0, y0, x1, y1])");
                if (!std::isfinite(*x)) {
                    fail(lineOf(*n), "view: rect's " + std::string(kRectNames[k]) +
                                         " is not a finite number (inf and nan have no place)");
                }
                r[k] = *x;
            }
            if (!(r[0] < r[2]) || !(r[1] < r[3]))
                fail(lineOf(*n), "view: rect is [x0, y0, x1, y1] with x0 < x1 and y0 < y1");
            s.view.rect = r;
        }
    }

    void stopTab(const toml::table& t, LessonStop& s) {
        const auto tab = string(t, "tab");
        if (!tab) return;
        if (std::none_of(std::begin(kTabNames), std::end(kTabNames),
                         [&](const char* k) { return *tab == k; }))
            fail(lineOf(*t.get("tab")),
                 "unknown tab \"" + *tab + "\" (known: " + joinNames(kTabNames) + ")");
        s.tab = *tab;
    }

    Lesson lesson(std::string_view source, const std::string& path) {
        Lesson L;
        L.file = path;
        m_source = source;
        L.options.order = OrderKind::Input;
        toml::table root = parseToml(source, path, "lesson");
        if (string(root, "kind").value_or("") == "track")
            fail(lineOf(*root.get("kind")),
                 "this is a track (kind = \"track\"): stops of other lessons, not a lesson");
        checkKeys(root,
                  {"title", "summary", "kind", "text", "objectives", "minutes", "points",
                   "points_file", "triangles", "options", "edits", "stop"},
                  "at the top level");
        L.title = string(root, "title").value_or("");
        if (trimmed(L.title).empty()) fail(1, "the lesson needs a \"title\"");
        L.summary = string(root, "summary").value_or("");
        if (auto k = string(root, "kind")) {
            if (*k != "lesson" && *k != "assignment")
                fail(lineOf(*root.get("kind")), "kind must be \"lesson\" or \"assignment\"");
            L.assignment = *k == "assignment";
        }
        L.objectives = objectives(root, false);
        L.minutes = static_cast<int>(integer(root, "minutes", 1, 300).value_or(0));
        if (auto x = string(root, "text")) {
            text(*x, lineOf(*root.get("text")));
            L.text = *x;
        }
        if (const toml::node* o = root.get("options")) {
            if (!o->is_table()) fail(lineOf(*o), "\"options\" must be a table: [options]");
            options(*o->as_table(), L.options);
        }
        lessonPoints(root, path, L);
        if (const toml::node* t = root.get("triangles")) {
            if (const toml::node* o = root.get("options"))
                fail(lineOf(*o),
                     "a lesson with \"triangles\" runs Lawson's flip algorithm from them: "
                     "[options] (boundary, locator, order) does not apply; leave it out");
            L.start = startMesh(*t, L.points);
        }
        lessonEdits(root, L);
        if (const toml::node* st = root.get("stop")) {
            const toml::array* a = st->as_array();
            if (!a || !a->is_array_of_tables())
                fail(lineOf(*st), "stops are written as [[stop]] tables");
            if (a->size() > kMaxLessonStops)
                fail(lineOf(*st),
                     "too many stops (at most " + std::to_string(kMaxLessonStops) + ")");
            m_numVertices = L.points.size() + 3;  // the super-triangle's (or the ghost) follow
            for (const toml::node& n : *a) {
                m_stop = static_cast<int>(L.stops.size()) + 1;
                L.stops.push_back(stop(*n.as_table()));
            }
            m_stop = 0;
        }
        if (L.stops.empty() && !L.assignment)
            fail(1, "a lesson needs at least one [[stop]] (or kind = \"assignment\")");
        return L;
    }

private:
    // edits = ["remove vertex 7", "constrain 2-9"]: after the run's end.
    void lessonEdits(const toml::table& root, Lesson& L) {
        const toml::node* n = root.get("edits");
        if (!n) return;
        L.editsLine = lineOf(*n);
        const toml::array* a = n->as_array();
        if (!a || a->empty() || a->size() > 50)
            fail(L.editsLine,
                 "\"edits\" must be a list of 1 to 50 edits, e.g. "
                 "[\"remove vertex 7\", \"constrain 2-9\"]");
        if (L.start)
            fail(L.editsLine, "edits need a run that inserts the points (no \"triangles\")");
        for (const toml::node& e : *a) {
            const auto parsed = e.is_string() ? parseEdit(e.as_string()->get()) : std::nullopt;
            if (!parsed)
                fail(lineOf(e),
                     "an edit is \"remove vertex N\", \"constrain A-B\", "
                     "\"unconstrain A-B\" or \"move vertex N to X, Y\"");
            if (parsed->a >= static_cast<std::int32_t>(L.points.size()) ||
                parsed->b >= static_cast<std::int32_t>(L.points.size()))
                fail(lineOf(e), "edit \"" + describe(*parsed) + "\": the lesson has points 0 to " +
                                    std::to_string(L.points.size() - 1));
            L.edits.push_back(*parsed);
        }
    }

    // The line where a string's content starts: a """ string that opens with a line break
    // starts on the next line.
    int contentLine(const toml::table& t, const char* key) const {
        const toml::node* n = t.get(key);
        if (!n) return 0;
        const int line = lineOf(*n);
        std::size_t pos = 0;
        for (int l = 1; l < line && pos != std::string_view::npos; ++l) {
            pos = m_source.find('\n', pos);
            if (pos != std::string_view::npos) ++pos;
        }
        if (pos == std::string_view::npos) return line;
        const std::string_view rest = m_source.substr(pos, m_source.find('\n', pos) - pos);
        const std::string tail = trimmed(rest);
        const bool opens = tail.ends_with("\"\"\"") || tail.ends_with("'''");
        const bool once =
            rest.find("\"\"\"") == rest.rfind("\"\"\"") && rest.find("'''") == rest.rfind("'''");
        return opens && once ? line + 1 : line;
    }

    // Every {{name}} of a text names a quantity or a corner expression.
    void embedded(const std::string& text, int line, const char* what) {
        std::string why;
        const auto values = findEmbeddedValues(text, &why);
        if (!values) fail(line, std::string("in the ") + what + ": " + why);
        for (const EmbeddedValue& v : *values) {
            if (findQuantity(v.spec)) continue;
            const std::string problem = expressionProblem(v.spec);
            if (problem.empty()) continue;
            fail(line + v.line - 1, std::string("unknown value {{") + v.spec + "}} in the " + what +
                                        ": neither a quantity (" + quantityNames() +
                                        ") nor a corner expression (" + problem + ")");
        }
    }

    static std::string expectedValue(const toml::node& value) {
        if (value.is_string()) return value.as_string()->get();
        if (value.is_integer()) return std::to_string(value.as_integer()->get());
        if (value.is_boolean()) return value.as_boolean()->get() ? "yes" : "no";
        if (value.is_floating_point()) return shortest(value.as_floating_point()->get());
        return "";
    }

    // expect = { name = value, ... }: values as a student would type them.
    std::vector<LessonExpect> expectations(const toml::table& t) {
        std::vector<LessonExpect> out;
        const toml::node* n = t.get("expect");
        if (!n) return out;
        const toml::table* table = n->as_table();
        if (!table)
            fail(lineOf(*n), "\"expect\" must be a table, e.g. expect = { walk_steps = 0 }");
        for (auto&& [key, value] : *table) {
            LessonExpect e;
            e.spec = trimmed(key.str());
            e.line = static_cast<int>(key.source().begin.line);
            if (e.line == 0) e.line = lineOf(*n);
            if (!findQuantity(e.spec)) {
                const std::string problem = expressionProblem(e.spec);
                if (!problem.empty())
                    fail(e.line, "expect \"" + e.spec + "\": neither a quantity (" +
                                     quantityNames() + ") nor a corner expression (" + problem +
                                     ")");
            }
            e.value = expectedValue(value);
            if (e.value.empty())
                fail(e.line, "expect \"" + e.spec +
                                 "\": the value must be a string, a number or true/false");
            out.push_back(std::move(e));
        }
        return out;
    }

    // needs = ["vertex:4", "corner:7", "triangle:3", "panel:corner-table"]: what the slide must
    // show beyond what lesson check reads from the text.
    void stopNeeds(const toml::table& t, LessonStop& s) {
        const toml::node* n = t.get("needs");
        if (!n) return;
        s.needsLine = lineOf(*n);
        const char* form =
            "\"needs\" must be a list like [\"vertex:4\", \"corner:7\", \"triangle:3\", "
            "\"panel:corner-table\"]";
        const toml::array* a = n->as_array();
        if (!a) fail(s.needsLine, form);
        for (const toml::node& e : *a) {
            if (!e.is_string()) fail(lineOf(e), form);
            const std::string need = e.as_string()->get();
            const std::size_t colon = need.find(':');
            const std::string kind = need.substr(0, colon);
            const std::string what = colon == std::string::npos ? "" : need.substr(colon + 1);
            if (kind == "panel") {
                if (std::none_of(std::begin(kPanelNames), std::end(kPanelNames),
                                 [&](const char* p) { return what == p; }))
                    fail(lineOf(e), "needs \"" + need + "\": unknown panel \"" + what +
                                        "\" (known: " + joinNames(kPanelNames) + ")");
            } else if (kind == "vertex" || kind == "corner" || kind == "triangle") {
                if (what.empty() || what.size() > 9 ||
                    !std::all_of(what.begin(), what.end(),
                                 [](char c) { return c >= '0' && c <= '9'; }))
                    fail(lineOf(e), "needs \"" + need + "\": " + kind + " needs an id, e.g. \"" +
                                        kind + ":4\"");
            } else {
                fail(lineOf(e),
                     "needs \"" + need + "\": write vertex:N, corner:N, triangle:N or panel:NAME");
            }
            s.needs.push_back(need);
        }
    }

    // figure = "lifting-map": a drawing beside the text (kFigureNames).
    std::string figure(const toml::table& t) {
        const auto name = string(t, "figure");
        if (!name) return "";
        if (std::none_of(std::begin(kFigureNames), std::end(kFigureNames),
                         [&](const char* k) { return *name == k; }))
            fail(lineOf(*t.get("figure")),
                 "unknown figure \"" + *name + "\" (known: " + joinNames(kFigureNames) + ")");
        return *name;
    }

    const std::string& m_file;
    std::string_view m_source;
    int m_stop = 0;
    std::size_t m_numVertices = 0;  // vertex ids a stop's view may name
};

}  // namespace

Lesson parseLesson(std::string_view text, const std::string& path) {
    return LessonReader(path).lesson(text, path);
}

std::size_t Track::slides() const {
    std::size_t n = 0;
    for (const TrackItem& i : items) n += i.stops.size();
    return n;
}

bool isTrackFile(const std::string& path) {
    try {
        const std::string text = readRegularFile(path, kMaxLessonFileBytes);
        const toml::table root = toml::parse(text, path);
        const toml::node* kind = root.get("kind");
        return kind && kind->value<std::string>() == "track";
    } catch (const std::exception&) {
        return false;
    }
}

Track loadTrack(const std::string& path) {
    std::string text;
    try {
        text = readRegularFile(path, kMaxLessonFileBytes);
    } catch (const InputError& e) {
        throw LessonError(path, 0, 0, e.message());
    }
    return LessonReader(path).track(text, path);
}

std::vector<std::pair<std::size_t, std::size_t>> trackSlides(const Track& track) {
    std::vector<std::pair<std::size_t, std::size_t>> out;
    for (std::size_t i = 0; i < track.items.size(); ++i)
        for (std::size_t k : track.items[i].stops) out.emplace_back(i, k);
    return out;
}

std::string objectivesText(const std::vector<std::string>& objectives) {
    if (objectives.empty()) return "";
    // One paragraph: a slide's first column has little room to spare.
    std::string out = "**Objectives:**";
    for (std::size_t k = 0; k < objectives.size(); ++k) out += (k ? "; " : " ") + objectives[k];
    return out + ".\n\n";
}

Lesson loadLesson(const std::string& path) {
    std::string text;
    try {
        text = readRegularFile(path, kMaxLessonFileBytes);
    } catch (const InputError& e) {
        throw LessonError(path, 0, 0, e.message());
    }
    return parseLesson(text, path);
}

// ============================================================================================
// [SECTION] Planning
// ============================================================================================

std::unique_ptr<Inserter> makeInserter(const Lesson& lesson) {
    try {
        if (lesson.start) return std::make_unique<Inserter>(lesson.points, *lesson.start);
        return std::make_unique<Inserter>(lesson.points, lesson.options);
    } catch (const std::exception& e) {
        throw LessonError(lesson.file, 0, 0, std::string("cannot start the run: ") + e.what());
    }
}

std::optional<LiftingMap> liftingMapAt(const Inserter& ins, const Op* current) {
    const Mesh& m = ins.mesh();
    std::int32_t c = kNone, d = kNone;
    if (current && current->type == OpType::InCircleTest) {
        c = current->a;
        d = current->b;
    } else if (!ins.flipStack().empty()) {
        c = ins.flipStack().back();
        d = m.O[c];
    }
    if (c == kNone || d == kNone) return std::nullopt;
    const std::int32_t t = tri(d);
    LiftingMap f;
    for (int k = 0; k < 3; ++k) {
        const std::int32_t v = m.V[3 * t + k];
        if (ins.isVirtual(v)) return std::nullopt;
        f.triangle[k] = m.G[v];
        f.vertices[k] = v;
    }
    if (ins.isVirtual(m.V[c])) return std::nullopt;
    f.point = m.G[m.V[c]];
    f.vertex = m.V[c];
    f.sign = incircle(f.triangle[0], f.triangle[1], f.triangle[2], f.point);
    return f;
}

namespace {

// The stop's text, question and hint with the engine's values in place of {{...}}.
void renderStopText(const Lesson& lesson, std::size_t k, Inserter& ins, Journal& journal,
                    std::int32_t selected, StopState& state, Editor* edits) {
    const LessonStop& s = lesson.stops[k];
    const auto render = [&](const std::string& in, int line, std::string& out) {
        std::string why;
        const auto r = renderEmbeddedValues(in, ins, journal, selected, &why, edits);
        if (!r) throw LessonError(lesson.file, line, static_cast<int>(k) + 1, why);
        out = *r;
    };
    render(s.text, s.textLine, state.text);
    render(s.question, s.questionLine, state.question);
    render(s.hint, s.hintLine, state.hint);
}

// Every `expect` of the stop holds in the engine's state there.
void checkExpectations(const Lesson& lesson, std::size_t k, Inserter& ins, Journal& journal,
                       std::int32_t selected, Editor* edits) {
    for (const LessonExpect& e : lesson.stops[k].expect) {
        const auto fail = [&](const std::string& why) {
            throw LessonError(lesson.file, e.line, static_cast<int>(k) + 1, why);
        };
        std::string why;
        const auto got = computeAnswer(e.spec, ins, journal, selected, &why, edits);
        if (!got) fail("expect " + e.spec + " = \"" + e.value + "\": " + why);
        if (!acceptsAnswer(*got, e.value)) {
            fail("the lesson expects " + e.spec + " = " + e.value + ", but the engine says " +
                 got->display() + " here");
        }
    }
}

}  // namespace

// Why a stop cannot be reached: the history is full (target 0: the stop's breakpoint).
static std::string historyFull(const Journal& journal, std::size_t target, OrderKind order) {
    return "this stop" + (target ? " (op " + std::to_string(target) + ")" : std::string()) +
           " lies past the step-by-step history's memory budget of " +
           std::to_string(journal.budget() >> 20) + " MiB, reached after " +
           std::to_string(journal.recorded()) + " operations; stop earlier, or use fewer points" +
           (order == OrderKind::Brio ? "" : " or the brio order (it walks far less)");
}

namespace {

// A stop that cannot be planned: the lesson's file, the line, the stop's number (1-based).
[[noreturn]] void stopError(const Lesson& lesson, std::size_t k, int line, const std::string& why) {
    throw LessonError(lesson.file, line, static_cast<int>(k) + 1, why);
}

// run_to op:N: seeks the journal to operation N, after the previous stop and before the end.
void runToOp(const Lesson& lesson, std::size_t k, Journal& journal, std::size_t target) {
    const int line = lesson.stops[k].line;
    if (target < journal.position()) {
        stopError(lesson, k, line,
                  "run_to op:" + std::to_string(target) + " is before the previous stop (op " +
                      std::to_string(journal.position()) + ")");
    }
    journal.seek(target);
    if (journal.budgetReached())
        stopError(lesson, k, line, historyFull(journal, target, lesson.options.order));
    if (journal.position() != target) {
        stopError(lesson, k, line,
                  "run_to op:" + std::to_string(target) + " is past the end of the run (" +
                      std::to_string(journal.position()) + " operations)");
    }
}

// run_to a breakpoint: runs until it is hit `count` times.
void runToBreakpoint(const Lesson& lesson, std::size_t k, Journal& journal, Inserter& ins) {
    const LessonStop& s = lesson.stops[k];
    const Breakpoint& bp = *s.runTo;
    for (int i = 0; i < s.count; ++i) {
        const RunResult r =
            runUntil(journal, ins, std::span(&bp, 1), std::numeric_limits<std::size_t>::max());
        if (journal.budgetReached())
            stopError(lesson, k, s.line, historyFull(journal, 0, lesson.options.order));
        if (r.reason != StopReason::Hit) {
            stopError(
                lesson, k, s.line,
                "run_to \"" + toString(bp) + "\" (" + explain(bp) + ") is not reached" +
                    (s.count > 1
                         ? " " + std::to_string(s.count) + " times (only " + std::to_string(i) + ")"
                         : "") +
                    ": the run ends after " + std::to_string(journal.position()) + " operations");
        }
    }
}

// The corner selected at stop k: the stop's `select` evaluated (with the previous selection
// bound), else the previous selection while the mesh still has it.
std::int32_t selectAtStop(const Lesson& lesson, std::size_t k, Inserter& ins,
                          std::int32_t selected) {
    if (selected >= ins.mesh().numCorners()) selected = kNone;  // the table shrank (Finalize)
    const LessonStop& s = lesson.stops[k];
    if (s.select.empty()) return selected;
    const auto expr = CornerExpr::parse(s.select);
    const auto bindings = selectionBinding(selected);
    const ExprResult r = expr->evaluate(ins.mesh(), bindings, exprContext(ins));
    if (!r.ok()) stopError(lesson, k, s.line, "select \"" + s.select + "\": " + r.error.message);
    const ExprValue& v = *r.value;
    if ((v.kind != ValueKind::Corner && v.kind != ValueKind::Number) || v.i < 0 ||
        v.i >= ins.mesh().numCorners()) {
        const std::int32_t corners = ins.mesh().numCorners();
        stopError(lesson, k, s.line,
                  "select \"" + s.select + "\" is " + formatValue(v) +
                      ", not a corner of the mesh " +
                      (corners == 0 ? std::string("(it has no triangles at this stop)")
                                    : "(0.." + std::to_string(corners - 1) + ")"));
    }
    return static_cast<std::int32_t>(v.i);
}

// The noun a "How many ..." question counts, as units its answer may carry: "How many walk
// steps ..." lets "8 walk steps" and "8 steps" through, "How many times ..." "6 times".
void addQuestionUnits(Answer& a, std::string_view question) {
    const std::vector<std::string> w = words(question);
    for (std::size_t i = 0; i + 2 < w.size(); ++i) {
        if (w[i] != "how" || w[i + 1] != "many") continue;
        std::size_t j = i + 2;
        while (j < w.size() && isOneOf(w[j], {"of", "the"})) ++j;
        if (j >= w.size()) continue;
        std::vector<std::string> nouns{w[j]};
        if (j + 1 < w.size() && w[j + 1].size() > 1 && w[j + 1].back() == 's' &&
            !isOneOf(w[j + 1], {"is", "was", "has", "does"})) {
            nouns.push_back(w[j] + " " + w[j + 1]);
            nouns.push_back(w[j + 1]);
        }
        for (const std::string& n : nouns) {
            a.units.push_back(n);
            if (n.size() > 1 && n.back() == 's') a.units.push_back(n.substr(0, n.size() - 1));
        }
    }
    // Longest first: "8 walk steps" loses "walk steps", not only "steps".
    std::stable_sort(
        a.units.begin(), a.units.end(),
        [](const std::string& x, const std::string& y) { return x.size() > y.size(); });
}

// The caption and banner of the op just done: the run's, or inside the edits the edit's.
void captionAt(StopState& state, Inserter& ins, Journal& journal, const Editor* edits) {
    if (edits) {
        const EditStep e = edits->current();
        if (!e.edit) return;
        state.caption = describeEditStep(*edits);
        state.banner = "[op " + std::to_string(state.position) + "] " + state.caption;
        return;
    }
    if (const Op* op = journal.current()) {
        state.caption = describe(*op, ins);
        // "[op N]": the N-th operation done, as the GUI's caption and timeline number it.
        state.banner = "[op " + std::to_string(journal.position()) + "] " + toString(op->type) +
                       ": " + state.caption;
    }
}

// What the player shows at stop k: position, caption, answer and the rendered text, after
// checking the stop's figure and expectations. Inside the edits (`edits`), the position counts
// the run's `runOps` and the edits' ops done, and the answers are the edits'.
StopState stopStateAt(const Lesson& lesson, std::size_t k, Inserter& ins, Journal& journal,
                      std::int32_t selected, Editor* edits, std::size_t runOps) {
    const LessonStop& s = lesson.stops[k];
    StopState state;
    state.position = edits ? runOps + edits->position() : journal.position();
    state.selected = selected;
    captionAt(state, ins, journal, edits);
    if (!s.question.empty()) {
        std::string why;
        state.answer = computeAnswer(s.answer, ins, journal, selected, &why, edits);
        if (!state.answer)
            stopError(lesson, k, s.answerLine, "the answer cannot be computed: " + why);
        if (state.answer->kind == Answer::Kind::Integer)
            addQuestionUnits(*state.answer, s.question);
    }
    if (s.figure == "lifting-map" && (edits || !liftingMapAt(ins, journal.current()))) {
        stopError(lesson, k, s.line,
                  "the lifting-map figure needs an in-circle test of a real triangle at "
                  "the stop (just done, or next on the flip stack)");
    }
    renderStopText(lesson, k, ins, journal, selected, state, edits);
    checkExpectations(lesson, k, ins, journal, selected, edits);
    return state;
}

// run_to an edit target: the editor steps until it is hit `count` times (edit:0: the run's end).
void runToEditTarget(const Lesson& lesson, std::size_t k, Editor& editor) {
    const LessonStop& s = lesson.stops[k];
    const Breakpoint& bp = *s.runTo;
    if (bp.kind == BreakKind::Edit && bp.param && *bp.param == 0) {
        if (editor.position() != 0)
            stopError(lesson, k, s.line,
                      "run_to edit:0 (the run's end) is before the previous stop");
        return;
    }
    if (bp.kind == BreakKind::Edit && bp.param) {  // edit:N is a position, as op:N is
        const auto n = static_cast<std::size_t>(*bp.param);
        if (n > lesson.edits.size())
            stopError(lesson, k, s.line,
                      "run_to " + toString(bp) + ": the lesson has " +
                          std::to_string(lesson.edits.size()) + " edits");
        if (editor.editEnd(n - 1) < editor.position())
            stopError(lesson, k, s.line, "run_to " + toString(bp) + " is before the previous stop");
        editor.seek(editor.editEnd(n - 1));
        return;
    }
    for (int i = 0; i < s.count; ++i) {
        bool hit = false;
        while (!hit && editor.forward()) hit = hitsEditAt(bp, editor);
        if (!hit)
            stopError(lesson, k, s.line,
                      "run_to \"" + toString(bp) + "\" (" + explain(bp) +
                          ") is not reached in the edits" +
                          (s.count > 1 ? " " + std::to_string(s.count) + " times" : "") +
                          ": they end after " + std::to_string(editor.total()) + " operations");
    }
}

}  // namespace

namespace {

// Where the planner is: in the run, or (once a stop runs to an edit target) in the edits.
struct Planner {
    const Lesson& lesson;
    std::unique_ptr<Inserter> ins;
    std::unique_ptr<Journal> journal;
    std::unique_ptr<Editor> editor;
    std::size_t runOps = 0;  // the run's operations: the edits' positions follow them
    std::int32_t selected = kNone;

    StopState stop(std::size_t k) {
        const LessonStop& s = lesson.stops[k];
        if (s.runTo && isEditBreak(s.runTo->kind)) {
            if (lesson.edits.empty())
                stopError(lesson, k, s.line,
                          "run_to \"" + toString(*s.runTo) +
                              "\" is a target inside the edits: the lesson has no edits = [...]");
            if (!editor) {
                editor = startEdits(lesson, *journal, *ins);
                runOps = journal->position();
            }
            runToEditTarget(lesson, k, *editor);
        } else if (editor && s.runTo) {
            stopError(lesson, k, s.line,
                      "after a stop inside the edits, run_to is an edit target (edit:N, "
                      "ear-test, sloan-flip, ...): the run is over");
        } else if (s.runTo && s.runTo->kind == BreakKind::Op) {
            runToOp(lesson, k, *journal, static_cast<std::size_t>(*s.runTo->param));
        } else if (s.runTo) {
            runToBreakpoint(lesson, k, *journal, *ins);
        }
        if (editor && !s.select.empty())
            stopError(lesson, k, s.line, "select is not available inside the edits");
        selected = editor ? kNone : selectAtStop(lesson, k, *ins, selected);
        return stopStateAt(lesson, k, *ins, *journal, selected, editor.get(), runOps);
    }
};

}  // namespace

// The lesson's edits recorded after the run's end (the journal is run to it); the editor is
// back at their start. A refused edit is the lesson's error.
std::unique_ptr<Editor> startEdits(const Lesson& lesson, Journal& journal, Inserter& ins) {
    runUntil(journal, ins, {}, std::numeric_limits<std::size_t>::max());
    if (journal.budgetReached() || !ins.done())
        throw LessonError(
            lesson.file, lesson.editsLine, 0,
            "the edits start at the run's end: " + historyFull(journal, 0, lesson.options.order));
    if (ins.mesh().numTriangles() == 0)
        throw LessonError(lesson.file, lesson.editsLine, 0,
                          "the edits need triangles: the points are collinear or fewer than 3");
    auto editor = editorAtRunEnd(journal, ins);
    for (const Edit& e : lesson.edits) {
        std::string message;
        if (!editor->add(e, message))
            throw LessonError(lesson.file, lesson.editsLine, 0,
                              "edit \"" + describe(e) + "\" is refused: " + message);
    }
    editor->seek(0);
    return editor;
}

LessonPlan planLesson(const Lesson& lesson) {
    Planner p{lesson, makeInserter(lesson), nullptr, nullptr};
    p.journal = std::make_unique<Journal>(*p.ins);
    LessonPlan plan;
    for (std::size_t k = 0; k < lesson.stops.size(); ++k) plan.stops.push_back(p.stop(k));
    // The objectives come first, above the first stop's text.
    if (!plan.stops.empty())
        plan.stops[0].text = objectivesText(lesson.objectives) + plan.stops[0].text;
    Journal& journal = *p.journal;
    runUntil(journal, *p.ins, {}, std::numeric_limits<std::size_t>::max());
    plan.totalOps = journal.position();
    // The edits are checked even when no stop goes into them.
    if (!p.editor && !lesson.edits.empty()) p.editor = startEdits(lesson, journal, *p.ins);
    if (p.editor) plan.editOps = p.editor->total();
    // Past the history's budget the rest of the run is only counted.
    for (; journal.budgetReached() && !p.ins->done(); ++plan.totalOps) p.ins->step(nullptr);
    return plan;
}

}  // namespace dlab
