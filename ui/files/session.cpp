// Session files: JSON out (nlohmann, points written by the core's shortest round-trip
// formatter), JSON in with every field checked before anything is applied.
#include "ui/files/session.h"

#include "core/engine/io_read.h"
#include "core/engine/io_write.h"
#include "core/engine/text_util.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <new>
#include <sstream>

namespace dlab::ui {

namespace {

// Read as nlohmann::json: its objects are std::maps, and a key added never moves the values
// before it. ordered_json keeps an object in a vector of pairs whose const keys make it copy them
// when it grows: one recursion per level of a deeply nested value, a crash at 200k levels.
// Written as ordered_json (the fields in our order).
using Json = nlohmann::json;
using OrderedJson = nlohmann::ordered_json;

// ============================================================================================
// [SECTION] Writing
// ============================================================================================

std::string number(double x) {
    // -0 must stay a double (JSON readers take "-0" for the integer 0 and lose the sign).
    if (x == 0 && std::signbit(x)) return "-0.0";
    std::string s;
    appendShortest(s, x);
    return s;
}

std::string hex64(std::uint64_t v) {
    char buf[24];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
    return buf;
}

// The overlay flags by their JSON names (reading and writing use the one table of overlays).
OrderedJson overlaysJson(const Overlays& ov) {
    OrderedJson j = OrderedJson::object();
    for (const OverlaySwitch& f : kOverlaySwitches) j[overlayKey(f)] = ov.*f.flag;
    return j;
}

// ============================================================================================
// [SECTION] Reading: errors located by JSON pointer, and the line where that value starts
// ============================================================================================

struct SessionError {
    std::string pointer;  // "/points/3"
    std::string message;
};

[[noreturn]] void fail(std::string pointer, std::string message) {
    throw SessionError{std::move(pointer), std::move(message)};
}

// "/points/3/1" -> "points[3][1]", as one would write it.
std::string readablePath(const std::string& pointer) {
    std::string out;
    std::size_t i = 1;
    while (i <= pointer.size()) {
        const std::size_t j = std::min(pointer.find('/', i), pointer.size());
        const std::string token = pointer.substr(i, j - i);
        const bool index =
            !token.empty() && token.find_first_not_of("0123456789") == std::string::npos;
        out += index ? "[" + token + "]" : (out.empty() ? "" : ".") + token;
        i = j + 1;
    }
    return out;
}

// A minimal scanner over text that nlohmann already accepted: finds where the value at a JSON
// pointer starts, so that a bad value is reported with its line.
class LineFinder {
public:
    explicit LineFinder(std::string_view text) : m_s(text) {}

    int lineOf(const std::string& pointer) {
        std::vector<std::string> tokens;
        for (std::size_t i = 1; i <= pointer.size() && !pointer.empty();) {
            const std::size_t j = pointer.find('/', i);
            tokens.push_back(pointer.substr(i, j == std::string::npos ? std::string::npos : j - i));
            if (j == std::string::npos) break;
            i = j + 1;
        }
        m_p = 0;
        if (!find(tokens, 0)) return 0;
        int line = 1;
        for (std::size_t k = 0; k < m_p && k < m_s.size(); ++k) line += m_s[k] == '\n';
        return line;
    }

private:
    void ws() {
        while (m_p < m_s.size() &&
               (m_s[m_p] == ' ' || m_s[m_p] == '\n' || m_s[m_p] == '\r' || m_s[m_p] == '\t'))
            ++m_p;
    }
    std::string string() {
        std::string out;
        ++m_p;  // opening quote
        while (m_p < m_s.size() && m_s[m_p] != '"') {
            if (m_s[m_p] == '\\') ++m_p;
            if (m_p < m_s.size()) out += m_s[m_p++];
        }
        ++m_p;
        return out;
    }
    // Past one value, however deeply nested: a count of open brackets, not a recursion (the
    // error path holds any file the parser held).
    void skip() {
        ws();
        if (m_p >= m_s.size()) return;
        const char first = m_s[m_p];
        if (first == '"') {
            string();
            return;
        }
        if (first != '{' && first != '[') {
            while (m_p < m_s.size() &&
                   std::string_view(",]} \n\r\t").find(m_s[m_p]) == std::string_view::npos)
                ++m_p;
            return;
        }
        std::size_t depth = 0;
        while (m_p < m_s.size()) {
            const char c = m_s[m_p];
            if (c == '"') {
                string();
                continue;
            }
            ++m_p;
            if (c == '{' || c == '[') {
                ++depth;
            } else if ((c == '}' || c == ']') && --depth == 0) {
                return;
            }
        }
    }
    bool find(const std::vector<std::string>& tokens, std::size_t depth) {
        ws();
        if (depth == tokens.size()) return true;
        if (m_p >= m_s.size()) return false;
        if (m_s[m_p] == '{') {
            ++m_p;
            while (m_p < m_s.size()) {
                ws();
                if (m_s[m_p] == '}') return false;
                const std::string key = string();
                ws();
                ++m_p;  // ':'
                if (key == tokens[depth]) return find(tokens, depth + 1);
                skip();
                ws();
                if (m_p < m_s.size() && m_s[m_p] == ',')
                    ++m_p;
                else
                    return false;
            }
            return false;
        }
        if (m_s[m_p] == '[') {
            std::size_t index = 0;
            try {
                index = std::stoul(tokens[depth]);
            } catch (...) {
                return false;
            }
            ++m_p;
            for (std::size_t k = 0; k < index; ++k) {
                skip();
                ws();
                if (m_p < m_s.size() && m_s[m_p] == ',')
                    ++m_p;
                else
                    return false;
            }
            return find(tokens, depth + 1);
        }
        return false;
    }

    std::string_view m_s;
    std::size_t m_p = 0;
};

const Json* member(const Json& obj, const char* key) {
    const auto it = obj.find(key);
    return it == obj.end() ? nullptr : &*it;
}

double finiteNumber(const Json& v, const std::string& where) {
    if (!v.is_number()) fail(where, "expected a number");
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(where, "expected a finite number");
    return x;
}

std::uint64_t count(const Json& v, const std::string& where) {
    if (v.is_number_unsigned()) return v.get<std::uint64_t>();
    if (v.is_number_integer() && v.get<std::int64_t>() >= 0)
        return static_cast<std::uint64_t>(v.get<std::int64_t>());
    fail(where, "expected a whole number >= 0");
}

bool flag(const Json& v, const std::string& where) {
    if (!v.is_boolean()) fail(where, "expected true or false");
    return v.get<bool>();
}

std::string text(const Json& v, const std::string& where) {
    if (!v.is_string()) fail(where, "expected a string");
    return v.get<std::string>();
}

// Everything a session holds, checked, before any of it is applied.
struct Session {
    std::string source;
    std::vector<Vec2> points;
    InsertOptions options;
    std::size_t position = 0;
    bool hasView = false;
    glm::dvec2 center{0, 0};
    double scale = 1;
    std::int32_t corner = kNone;
    std::optional<Overlays> overlays;
    std::vector<BreakpointEntry> breakpoints;
    std::vector<Edit> edits;  // after the run's end, in order
    std::string live;
    std::vector<std::pair<std::string, bool>> watches;
    bool hasExpect = false;
    std::size_t expectPosition = 0;
    std::string expectFingerprint;
};

// "format" and "version": a Delaunay Lab session this build reads.
void checkFormat(const Json& j) {
    if (!j.is_object()) fail("", "not a Delaunay Lab session (the file is not a JSON object)");
    const Json* format = member(j, "format");
    if (!format || !format->is_string() || format->get<std::string>() != kSessionFormat) {
        fail("/format", std::string("not a Delaunay Lab session (\"format\" must be \"") +
                            kSessionFormat + "\")");
    }
    const Json* version = member(j, "version");
    if (!version) fail("", "no \"version\"");
    const std::uint64_t v = count(*version, "/version");
    if (v == 0) fail("/version", "version must be 1 or more");
    if (v > static_cast<std::uint64_t>(kSessionVersion)) {
        fail("/version", "session version " + std::to_string(v) +
                             " is newer than this Delaunay Lab reads (" +
                             std::to_string(kSessionVersion) + "): update Delaunay Lab");
    }
}

// The points, taken out of the JSON as the parser reads them: each [x, y] checked into `points`
// (the first bad one kept as `error`), none left in the tree. Held as JSON a point took about a
// hundred bytes, and a tree of millions of them needed a large buffer again to be destroyed
// (nlohmann frees a tree through a stack of its own): out of memory, that aborted.
struct PointsAside {
    std::vector<Vec2> points;
    std::optional<SessionError> error;
};

Json parseSessionJson(std::string_view text, PointsAside& aside) {
    std::string topKey;
    std::size_t index = 0;
    const Json::parser_callback_t take = [&](int depth, Json::parse_event_t event, Json& parsed) {
        if (depth == 1 && event == Json::parse_event_t::key) {
            topKey = parsed.is_string() ? parsed.get<std::string>() : std::string();
            if (topKey == "points") aside = {}, index = 0;  // the last "points" is the one
            return true;
        }
        // An element of the points array, complete: a value, or the end of an array or object.
        if (depth != 2 || topKey != "points" ||
            (event != Json::parse_event_t::value && event != Json::parse_event_t::array_end &&
             event != Json::parse_event_t::object_end))
            return true;
        const std::size_t k = index++;
        if (aside.error) return false;
        try {
            if (k >= kMaxPoints)
                fail("/points", "more than " + std::to_string(kMaxPoints) + " points");
            const std::string where = "/points/" + std::to_string(k);
            if (!parsed.is_array() || parsed.size() != 2) fail(where, "expected [x, y]");
            aside.points.push_back(
                {finiteNumber(parsed[0], where + "/0"), finiteNumber(parsed[1], where + "/1")});
        } catch (const SessionError& e) {
            aside.error = e;
            aside.points = {};
        }
        return false;  // not kept in the tree
    };
    return Json::parse(text.begin(), text.end(), take);
}

std::vector<Vec2> parsePoints(const Json& j, PointsAside& aside) {
    const Json* pts = member(j, "points");
    if (!pts) fail("", "no \"points\"");
    if (!pts->is_array()) fail("/points", "expected an array of [x, y] pairs");
    if (aside.error) throw *aside.error;
    return std::move(aside.points);
}

// A mode named by its text (`parse` reads it); an unknown name is the error, with the known
// `choices` when they are few.
template <class Parse>
auto parseMode(const Json& v, const std::string& where, Parse parse, const char* what,
               const char* choices) {
    const auto parsed = parse(text(v, where));
    if (!parsed)
        fail(where, std::string("unknown ") + what + " \"" + v.get<std::string>() + "\"" + choices);
    return *parsed;
}

void parseOptions(const Json& o, InsertOptions& options) {
    if (!o.is_object()) fail("/options", "expected an object");
    if (const Json* b = member(o, "boundary"))
        options.boundary =
            parseMode(*b, "/options/boundary", parseBoundary, "boundary mode", " (exact, super)");
    if (const Json* l = member(o, "locator"))
        options.locator = parseMode(*l, "/options/locator", parseLocatorKind, "locator", "");
    if (const Json* r = member(o, "order"))
        options.order = parseMode(*r, "/options/order", parseOrderKind, "insertion order",
                                  " (input, random, brio)");
    if (const Json* seed = member(o, "seed")) options.seed = count(*seed, "/options/seed");
    if (const Json* id = member(o, "id_buffer")) {
        if (!id->is_array() || id->size() != 2)
            fail("/options/id_buffer", "expected [width, height]");
        const std::uint64_t w = count((*id)[0], "/options/id_buffer/0"),
                            h = count((*id)[1], "/options/id_buffer/1");
        if (w < 1 || h < 1 || w > 16384 || h > 16384)
            fail("/options/id_buffer", "width and height must be 1 to 16384");
        options.locatorOptions.idBufferWidth = static_cast<int>(w);
        options.locatorOptions.idBufferHeight = static_cast<int>(h);
    }
}

void parseView(const Json& view, Session& s) {
    if (!view.is_object()) fail("/view", "expected an object");
    const Json* c = member(view, "center");
    const Json* sc = member(view, "scale");
    if (!c || !sc) fail("/view", "expected \"center\" and \"scale\"");
    if (!c->is_array() || c->size() != 2) fail("/view/center", "expected [x, y]");
    s.center = {finiteNumber((*c)[0], "/view/center/0"), finiteNumber((*c)[1], "/view/center/1")};
    s.scale = finiteNumber(*sc, "/view/scale");
    if (!(s.scale > 0)) fail("/view/scale", "the scale must be positive");
    s.hasView = true;
}

void parseSelection(const Json& sel, Session& s) {
    if (!sel.is_object()) fail("/selection", "expected an object");
    if (const Json* c = member(sel, "corner")) {
        if (!c->is_number_integer() || c->get<std::int64_t>() < -1 ||
            c->get<std::int64_t>() > INT32_MAX) {
            fail("/selection/corner", "expected a corner id (or -1 for none)");
        }
        s.corner = static_cast<std::int32_t>(c->get<std::int64_t>());
    }
}

Overlays parseOverlays(const Json& ov) {
    if (!ov.is_object()) fail("/overlays", "expected an object");
    Overlays o;
    for (const OverlaySwitch& f : kOverlaySwitches) {
        const std::string key = overlayKey(f);
        if (const Json* v = member(ov, key.c_str())) o.*f.flag = flag(*v, "/overlays/" + key);
    }
    return o;
}

std::vector<BreakpointEntry> parseBreakpoints(const Json& bps) {
    if (!bps.is_array()) fail("/breakpoints", "expected an array of breakpoint texts");
    std::vector<BreakpointEntry> out;
    for (std::size_t k = 0; k < bps.size(); ++k) {
        const std::string where = "/breakpoints/" + std::to_string(k);
        std::string why;
        const auto bp = parseBreakpoint(text(bps[k], where), &why);
        if (!bp) fail(where, why);
        out.push_back({*bp, true});
    }
    return out;
}

// The edits after the run: "remove vertex 5", "constrain 2-7", "unconstrain 2-7".
std::vector<Edit> parseEdits(const Json& edits) {
    if (!edits.is_array()) fail("/edits", "expected an array of edits (\"remove vertex 5\")");
    std::vector<Edit> out;
    for (std::size_t k = 0; k < edits.size(); ++k) {
        const std::string where = "/edits/" + std::to_string(k);
        const auto e = parseEdit(text(edits[k], where));
        if (!e)
            fail(where, "expected \"remove vertex V\", \"constrain A-B\" or \"unconstrain A-B\"");
        out.push_back(*e);
    }
    return out;
}

// A watch: {"text": a comparison, "enabled": true or false (true when absent)}.
std::pair<std::string, bool> parseWatch(const Json& w, const std::string& where) {
    if (!w.is_object() || !member(w, "text"))
        fail(where, "expected {\"text\": ..., \"enabled\": ...}");
    const std::string t = text(w["text"], where + "/text");
    ExprError err;
    const auto parsed = CornerExpr::parse(t, &err);
    if (!parsed || !parsed->isComparison())
        fail(where + "/text", parsed ? "a watch must be a comparison" : err.message);
    const bool enabled = member(w, "enabled") ? flag(w["enabled"], where + "/enabled") : true;
    return {t, enabled};
}

void parseExpressions(const Json& ex, Session& s) {
    if (!ex.is_object()) fail("/expressions", "expected an object");
    if (const Json* live = member(ex, "live")) s.live = text(*live, "/expressions/live");
    if (const Json* ws = member(ex, "watches")) {
        if (!ws->is_array()) fail("/expressions/watches", "expected an array");
        for (std::size_t k = 0; k < ws->size(); ++k)
            s.watches.push_back(parseWatch((*ws)[k], "/expressions/watches/" + std::to_string(k)));
    }
}

void parseExpect(const Json& ex, Session& s) {
    if (!ex.is_object()) fail("/expect", "expected an object");
    if (const Json* p = member(ex, "position")) {
        s.expectPosition = count(*p, "/expect/position");
        s.hasExpect = true;
    }
    if (const Json* f = member(ex, "fingerprint"))
        s.expectFingerprint = text(*f, "/expect/fingerprint");
}

// The session's fields in the file's order of importance; the first bad one is the error.
Session parseSession(const Json& j, PointsAside& aside) {
    Session s;
    checkFormat(j);
    if (const Json* src = member(j, "source")) s.source = text(*src, "/source");
    s.points = parsePoints(j, aside);
    if (const Json* o = member(j, "options")) parseOptions(*o, s.options);
    if (const Json* p = member(j, "position")) s.position = count(*p, "/position");
    if (const Json* view = member(j, "view")) parseView(*view, s);
    if (const Json* sel = member(j, "selection")) parseSelection(*sel, s);
    if (const Json* ov = member(j, "overlays")) s.overlays = parseOverlays(*ov);
    if (const Json* bps = member(j, "breakpoints")) s.breakpoints = parseBreakpoints(*bps);
    if (const Json* ed = member(j, "edits")) s.edits = parseEdits(*ed);
    if (const Json* ex = member(j, "expressions")) parseExpressions(*ex, s);
    if (const Json* ex = member(j, "expect")) parseExpect(*ex, s);
    return s;
}

}  // namespace

// ============================================================================================
// [SECTION] Public functions
// ============================================================================================

std::uint64_t MeshFingerprint(const Mesh& m) {
    std::uint64_t h = 1469598103934665603ull;
    auto mix = [&h](const void* data, std::size_t n) {
        const auto* b = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < n; ++i) {
            h ^= b[i];
            h *= 1099511628211ull;
        }
    };
    if (!m.G.empty()) mix(m.G.data(), m.G.size() * sizeof(Vec2));
    if (!m.V.empty()) mix(m.V.data(), m.V.size() * sizeof(std::int32_t));
    if (!m.O.empty()) mix(m.O.data(), m.O.size() * sizeof(std::int32_t));
    return h;
}

std::string sessionText(const AppState& st) {
    const Engine& e = st.engine;
    const InsertOptions& o = e.options();
    OrderedJson j;
    j["format"] = kSessionFormat;
    j["version"] = kSessionVersion;
    j["saved_by"] = "Delaunay Lab";
    j["source"] = st.source;
    j["points"] = "@POINTS@";
    j["options"] = {
        {"boundary", toString(o.boundary)},
        {"locator", toString(o.locator)},
        {"order", toString(o.order)},
        {"seed", o.seed},
        {"id_buffer", {o.locatorOptions.idBufferWidth, o.locatorOptions.idBufferHeight}}};
    j["position"] = e.position();
    j["view"] = {{"center", {st.view.center.x, st.view.center.y}}, {"scale", st.view.scale}};
    j["selection"] = {{"corner", st.selection.corner}};
    j["overlays"] = overlaysJson(st.overlays);
    OrderedJson bps = OrderedJson::array();
    for (const BreakpointEntry& b : st.run.breakpoints) {
        if (b.enabled) bps.push_back(toString(b.bp));
    }
    j["breakpoints"] = bps;
    OrderedJson edits = OrderedJson::array();
    for (const std::string& text : editTexts(e)) edits.push_back(text);
    if (!edits.empty()) j["edits"] = edits;
    OrderedJson watches = OrderedJson::array();
    for (const WatchEntry& w : st.expressions.watches)
        watches.push_back({{"text", w.text}, {"enabled", w.enabled}});
    j["expressions"] = {{"live", st.expressions.live}, {"watches", watches}};
    const Op* op = e.current();
    j["expect"] = {{"position", e.position()},
                   {"op", op ? toString(op->type) : "none"},
                   {"triangles", e.mesh().numTriangles()},
                   {"vertices", e.mesh().numVertices()},
                   {"fingerprint", hex64(MeshFingerprint(e.mesh()))}};
    std::string out = j.dump(2);
    // The points, one per line, in the core's shortest round-trip form (bit-exact).
    std::string pts = "[";
    const auto& P = e.points();
    pts.reserve(P.size() * 32 + 16);
    for (std::size_t k = 0; k < P.size(); ++k) {
        pts += k ? ",\n    [" : "\n    [";
        pts += number(P[k].x);
        pts += ", ";
        pts += number(P[k].y);
        pts += "]";
    }
    pts += P.empty() ? "]" : "\n  ]";
    const std::string placeholder = "\"@POINTS@\"";
    out.replace(out.find(placeholder), placeholder.size(), pts);
    out += "\n";
    return out;
}

bool saveSession(const AppState& st, const std::string& path, std::string& error) {
    try {
        const std::string body = sessionText(st);
        writeTextFile(path, [&](std::ostream& os) { os << body; });
    } catch (const std::exception& e) {
        error = e.what();
        return false;
    }
    return true;
}

// nlohmann's out_of_range 406, "number overflow parsing '1e400'", has no position: the line
// is the number's first occurrence.
static std::string numberTooLarge(std::string_view text, const std::string& name,
                                  const std::string& what) {
    const auto q1 = what.find('\''), q2 = what.rfind('\'');
    const std::string number =
        q1 < q2 && q2 != std::string::npos ? what.substr(q1 + 1, q2 - q1 - 1) : "";
    int line = 0;
    if (const auto at = number.empty() ? std::string_view::npos : text.find(number);
        at != std::string_view::npos) {
        line = 1;
        for (std::size_t k = 0; k < at; ++k) line += text[k] == '\n';
    }
    return name + (line > 0 ? ":" + std::to_string(line) : "") + ": the number " +
           escapeControls(number) + " is too large (a coordinate must be a finite double)";
}

// Out of memory while a session of `bytes` bytes was read or checked: which limit, in one line.
static std::string outOfMemory(const std::string& name, std::size_t bytes) {
    const std::string need = bytes == 0
                                 ? std::string()
                                 : std::to_string(bytes >> 20) + " MiB of JSON needs about " +
                                       std::to_string((bytes >> 20) * kSessionMemoryPerByte) +
                                       " MiB while it is checked; ";
    return name + ": not enough memory to open the session (" + need + "sessions up to " +
           std::to_string(kMaxSessionFileBytes >> 20) + " MiB are accepted)";
}

namespace {

// The file's text parsed and checked; a problem is one line naming the file, its line and
// the field.
bool readSessionText(std::string_view textIn, const std::string& name, Session& s,
                     std::string& error) {
    try {
        PointsAside aside;
        const Json j = parseSessionJson(textIn, aside);
        s = parseSession(j, aside);
    } catch (const Json::parse_error& e) {
        // nlohmann says "[json.exception.parse_error.101] parse error at line 3, column 5: ...":
        // keep the part after the position, and give the line our way.
        int line = 1;
        for (std::size_t k = 0; k < e.byte && k < textIn.size(); ++k) line += textIn[k] == '\n';
        std::string what = e.what();
        if (const auto colon = what.find(": "); colon != std::string::npos)
            what = what.substr(colon + 2);
        error =
            name + ":" + std::to_string(line) + ": not valid JSON (" + escapeControls(what) + ")";
        return false;
    } catch (const Json::out_of_range& e) {
        error = numberTooLarge(textIn, name, e.what());
        return false;
    } catch (const std::bad_alloc&) {
        error = outOfMemory(name, textIn.size());
        return false;
    } catch (const SessionError& e) {
        LineFinder finder(textIn);
        const int line = e.pointer.empty() ? 0 : finder.lineOf(e.pointer);
        // The message may quote the file's own text (a bad mode name with a \n in it): one line.
        error = name + (line > 0 ? ":" + std::to_string(line) : "") +
                (e.pointer.empty() ? "" : ": " + readablePath(e.pointer)) + ": " +
                escapeControls(e.message);
        return false;
    } catch (const std::exception& e) {
        error = name + ": " + escapeControls(e.what());
        return false;
    }
    return true;
}

// The session's expressions: its watches (checked already) and the live expression.
void restoreExpressions(ExpressionState& ex, const Session& s) {
    ex.watches.clear();
    for (const auto& [t, enabled] : s.watches) {
        WatchEntry w;
        w.text = t;
        w.enabled = enabled;
        w.expr = std::make_shared<const CornerExpr>(*CornerExpr::parse(t));
        ex.watches.push_back(std::move(w));
    }
    ex.watchedVersion = ~std::uint64_t{0};
    ex.live = s.live;
    ex.liveVersion = ~std::uint64_t{0};
    ex.path.clear();
    ex.result.reset();
}

// What was restored, and where the run differs from the file: it ends early, or its mesh is
// not the one the file saved.
void logRestored(AppState& st, const Session& s, const std::string& name, std::size_t points) {
    const Engine& eng = st.engine;
    st.log(Message::Level::Info, name + ": session restored: " + std::to_string(points) +
                                     " points, operation " + std::to_string(eng.position()) +
                                     " of " + std::to_string(eng.recorded()));
    if (eng.position() != s.position) {
        st.log(Message::Level::Warning,
               name + ": the run ends after " + std::to_string(eng.position()) +
                   " operations, before the saved step " + std::to_string(s.position));
    }
    if (s.hasExpect && !s.expectFingerprint.empty() && s.expectPosition == eng.position() &&
        s.expectFingerprint != hex64(MeshFingerprint(eng.mesh()))) {
        st.log(Message::Level::Warning,
               name + ": the mesh at operation " + std::to_string(eng.position()) +
                   " differs from the one saved in the file: this build triangulates differently "
                   "(keep the file: it reproduces the difference)");
    }
}

}  // namespace

bool loadSessionText(AppState& st, std::string_view textIn, const std::string& name,
                     std::string& error) {
    Session s;
    if (!readSessionText(textIn, name, s, error)) return false;

    // Everything checked: restart the run at the saved step (the engine changes nothing when it
    // cannot), then the rest.
    Engine& eng = st.engine;
    std::vector<Vec2> previous = eng.points();
    std::string why;
    const std::size_t n = s.points.size();
    if (!eng.resetAt(std::move(s.points), s.options, s.position, why)) {
        error = name + ": cannot restart the run: " +
                (why == std::bad_alloc().what()
                     ? "not enough memory to triangulate its " + std::to_string(n) + " points"
                     : why);
        return false;
    }
    for (const Edit& edit : s.edits) {  // the edits after the run, then the saved step
        std::string said;
        if (!eng.edit(edit, said))
            st.log(Message::Level::Warning, name + ": " + describe(edit) + " refused: " + said);
    }
    if (!s.edits.empty()) eng.seek(s.position);
    if (!previous.empty()) {
        st.undoPoints.push_back(std::move(previous));
        st.redoPoints.clear();
    }
    st.source = name + (s.source.empty() ? "" : " (" + s.source + ")");
    st.run.running = false;
    st.run.stopReason.clear();
    st.run.breakpoints = std::move(s.breakpoints);
    st.selection = {};
    st.select(s.corner);
    st.selection.jumpToCorner = st.selection.corner;
    if (s.hasView) {
        st.view.center = s.center;
        st.view.scale = s.scale;
        st.fitPending = false;
    } else {
        st.fitPending = true;
    }
    if (s.overlays) st.overlays = *s.overlays;
    restoreExpressions(st.expressions, s);
    logRestored(st, s, name, n);
    return true;
}

bool loadSession(AppState& st, const std::string& path, std::string& error) {
    std::string body;
    try {
        body = readRegularFile(path, kMaxSessionFileBytes);
        return loadSessionText(st, body, path, error);
    } catch (const InputError& e) {
        error = escapeControls(e.what());
    } catch (const std::bad_alloc&) {  // applying it (the run restarted at the saved step)
        error = outOfMemory(escapeControls(path), body.size());
    }
    return false;
}

bool peekSession(const std::string& path, SessionSummary& out, std::string& error) {
    try {
        PointsAside aside;
        const Json j = parseSessionJson(readRegularFile(path, kMaxSessionFileBytes), aside);
        const Session s = parseSession(j, aside);
        out.points = s.points.size();
        out.position = s.position;
        out.source = s.source;
    } catch (const InputError& e) {
        error = escapeControls(e.what());
        return false;
    } catch (const SessionError& e) {
        error = path + (e.pointer.empty() ? "" : ": " + readablePath(e.pointer)) + ": " +
                escapeControls(e.message);
        return false;
    } catch (const std::bad_alloc&) {
        error = outOfMemory(escapeControls(path), 0);
        return false;
    } catch (const std::exception& e) {
        error = path + ": " + escapeControls(e.what());
        return false;
    }
    return true;
}

}  // namespace dlab::ui
