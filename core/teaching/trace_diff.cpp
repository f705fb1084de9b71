// Trace comparison: a lenient reader for students' traces, a replay of the mesh each trace
// describes, and an incremental comparison (multiset of triangles, mismatching corners) so that
// long traces cost time linear in their length.
#include "core/teaching/trace_diff.h"

#include "core/engine/io_read.h"
#include "core/engine/predicates.h"
#include "core/engine/text_util.h"
#include "core/teaching/json_quote.h"
#include "core/teaching/mesh_check.h"
#include "core/teaching/trace.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <set>
#include <sstream>

namespace dlab {

namespace {

// Bounds for indices read from untrusted traces: 2^25 corners is the largest mesh a trace that
// fits in memory can describe, and keeps the replay's arrays small enough to allocate.
constexpr std::int64_t kMaxCorners = std::int64_t{1} << 25;
constexpr std::int64_t kMaxId = std::int64_t{1} << 30;

std::optional<OpType> opTypeLenient(const std::string& name) {
    if (auto t = parseOpType(name)) return t;
    const std::string s = looseName(name);
    for (int k = 0; k <= static_cast<int>(OpType::Finalize); ++k) {
        const auto t = static_cast<OpType>(k);
        if (s == looseName(toString(t))) return t;
    }
    if (s == "incircle") return OpType::InCircleTest;
    if (s == "duplicate" || s == "skip") return OpType::SkipDuplicate;
    return std::nullopt;
}

std::int64_t integer(const nlohmann::json& v, const std::string& what, std::int64_t lo,
                     std::int64_t hi, const std::string& name, int line) {
    if (!v.is_number_integer())
        throw InputError(name, line, what + " must be an integer, not " + quoteJson(v));
    std::int64_t x;
    if (v.is_number_unsigned()) {
        const auto u = v.get<std::uint64_t>();
        if (u > static_cast<std::uint64_t>(hi))
            throw InputError(name, line, what + " " + std::to_string(u) + " is out of range");
        x = static_cast<std::int64_t>(u);
    } else {
        x = v.get<std::int64_t>();
    }
    if (x < lo || x > hi)
        throw InputError(name, line, what + " " + std::to_string(x) + " is out of range");
    return x;
}

TraceOp parseLine(const std::string& text, const std::string& name, int line) {
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception&) {
        throw InputError(name, line, "not a JSON object (each line of a trace is one {...})");
    }
    if (!j.is_object())
        throw InputError(name, line, "not a JSON object (each line of a trace is one {...})");
    TraceOp op;
    op.line = line;
    if (!j.contains("op")) throw InputError(name, line, "missing \"op\" (e.g. \"op\": \"Flip\")");
    if (!j["op"].is_string()) throw InputError(name, line, "\"op\" must be a string");
    const auto type = opTypeLenient(j["op"].get<std::string>());
    if (!type) throw InputError(name, line, "unknown op " + quoteJson(j["op"]));
    op.type = *type;
    auto id = [&](const char* key) -> std::optional<std::int32_t> {
        if (!j.contains(key) || j[key].is_null()) return std::nullopt;
        return static_cast<std::int32_t>(integer(j[key], key, kNone, kMaxId, name, line));
    };
    if (j.contains("i") && !j["i"].is_null())
        op.index = integer(j["i"], "i", 0, INT64_MAX, name, line);
    op.vertex = id("vertex");
    op.a = id("a");
    op.b = id("b");
    if (j.contains("sign") && !j["sign"].is_null())
        op.sign = static_cast<int>(integer(j["sign"], "sign", -1, 1, name, line));
    if (j.contains("where") && j["where"].is_string()) op.where = j["where"].get<std::string>();
    if (j.contains("changes")) {
        if (!j["changes"].is_array()) throw InputError(name, line, "\"changes\" must be a list");
        op.hasChanges = true;
        op.changes.reserve(j["changes"].size());
        for (const auto& c : j["changes"]) {
            if (!c.is_array() || c.size() != 4 || !c[0].is_string() ||
                (c[0] != "V" && c[0] != "O")) {
                throw InputError(
                    name, line,
                    "a change is [\"V\" or \"O\", corner, before, after], not " + quoteJson(c));
            }
            const auto corner = static_cast<std::int32_t>(
                integer(c[1], "a corner", 0, kMaxCorners - 1, name, line));
            const auto before =
                static_cast<std::int32_t>(integer(c[2], "a cell value", kNone, kMaxId, name, line));
            const auto after =
                static_cast<std::int32_t>(integer(c[3], "a cell value", kNone, kMaxId, name, line));
            op.changes.push_back({2 * corner + (c[0] == "O" ? 1 : 0), before, after});
        }
    }
    if (j.contains("triangles")) {
        if (!j["triangles"].is_array())
            throw InputError(name, line, "\"triangles\" must be a list of [t, v0, v1, v2]");
        op.hasTriangles = true;
        op.triangles.reserve(j["triangles"].size());
        for (const auto& t : j["triangles"]) {
            if (!t.is_array() || t.size() != 4) {
                throw InputError(
                    name, line,
                    "a triangle is [t, v0, v1, v2] (t: your triangle number), not " + quoteJson(t));
            }
            std::array<std::int32_t, 4> v{};
            v[0] = static_cast<std::int32_t>(
                integer(t[0], "a triangle number", 0, kMaxCorners / 3 - 1, name, line));
            for (int k = 1; k < 4; ++k)
                v[k] = static_cast<std::int32_t>(integer(t[k], "a vertex", 0, kMaxId, name, line));
            op.triangles.push_back(v);
        }
        // Finalize with an empty list means "not given" (as our own traces write it), never
        // "the final mesh is empty": a finished run always has its triangles.
        if (op.type == OpType::Finalize && op.triangles.empty()) op.hasTriangles = false;
    }
    return op;
}

}  // namespace

bool TraceOp::changesMesh() const {
    switch (type) {
        case OpType::Start:
        case OpType::Split:
        case OpType::SplitEdge:
        case OpType::Flip:
        case OpType::SkipDuplicate:
        case OpType::Finalize: return true;
        default: return false;
    }
}

namespace {

// One line of a trace into f (blank lines skipped).
void addLine(TraceFile& f, std::string& line, int number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) return;
    if (f.ops.size() >= kMaxTraceOps) {
        throw InputError(f.name, number,
                         "more than " + std::to_string(kMaxTraceOps) +
                             " operations, the most a trace compared may hold (the memory "
                             "limit of traces): compare a shorter run");
    }
    f.ops.push_back(parseLine(line, f.name, number));
}

void checkNotEmpty(const TraceFile& f) {
    if (f.ops.empty()) throw InputError(f.name, 0, "no operations: the trace is empty");
}

}  // namespace

TraceFile parseTraceText(std::istream& in, const std::string& name) {
    TraceFile f;
    f.name = name;
    std::string line;
    int number = 0;
    while (std::getline(in, line)) addLine(f, line, ++number);
    checkNotEmpty(f);
    return f;
}

TraceFile readTraceFile(const std::string& path) {
    // Line by line as the chunks come: the file's text is never held whole, only the operations.
    TraceFile f;
    f.name = path;
    std::string line;
    int number = 0;
    try {
        readRegularFileChunks(path, kMaxTraceFileBytes, [&](std::string_view piece) {
            for (std::size_t at = 0; at < piece.size();) {
                const std::size_t end = piece.find('\n', at);
                line.append(piece.substr(at, end == std::string_view::npos ? end : end - at));
                if (line.size() > kMaxTraceLineBytes) {
                    throw InputError(path, number + 1,
                                     "line longer than " +
                                         std::to_string(kMaxTraceLineBytes >> 20) +
                                         " MiB: not a trace line");
                }
                if (end == std::string_view::npos) break;
                addLine(f, line, ++number);
                line.clear();
                at = end + 1;
            }
        });
        if (!line.empty()) addLine(f, line, ++number);
    } catch (const std::bad_alloc&) {
        const std::size_t held = f.ops.size();
        f = TraceFile{};  // freed first: the message needs a little memory too
        line = std::string();
        throw InputError(path, number,
                         "not enough memory to hold the trace (" + std::to_string(held) +
                             " operations read, about " + std::to_string(kTraceBytesPerOp) +
                             " bytes each)");
    }
    checkNotEmpty(f);
    return f;
}

TraceFile traceOfRun(Inserter& ins, const std::string& name) {
    Journal journal(ins);
    MeshGeometry geometry;
    geometry.numInput = ins.numInput();
    geometry.ghost = ins.options().boundary == Boundary::Exact;
    // Each line read as a file's would be, as it is made: the text is never held whole.
    TraceFile f;
    f.name = name;
    int number = 0;
    while (journal.forward()) {
        // The virtual vertices' positions exist from Start until Finalize.
        if (ins.mesh().G.size() > geometry.points.size()) geometry.points = ins.mesh().G;
        std::string line = toJsonLine(traceRecord(journal, journal.position() - 1, ins.mesh()));
        addLine(f, line, ++number);
    }
    if (journal.budgetReached()) {
        throw InputError(name, 0,
                         "the reference run passes the history's memory budget (" +
                             std::to_string(journal.budget() >> 20) + " MiB) after " +
                             std::to_string(journal.recorded()) +
                             " operations: compare a smaller run" +
                             (ins.options().order == OrderKind::Brio
                                  ? std::string()
                                  : " or a brio-order one (it walks far less)"));
    }
    checkNotEmpty(f);
    f.geometry = std::move(geometry);
    return f;
}

std::int32_t largestVertex(const TraceFile& f) {
    std::int32_t most = kNone;
    for (const TraceOp& op : f.ops) {
        if (op.vertex) most = std::max(most, *op.vertex);
        for (const auto& t : op.triangles) most = std::max({most, t[1], t[2], t[3]});
        for (const CellChange& c : op.changes) {
            if (!c.isO()) most = std::max(most, c.after);
        }
    }
    return most;
}

// ============================================================================================
// [SECTION] Replay
// ============================================================================================

void TraceReplay::setTriangle(std::int32_t t, Triple tri) {
    const std::size_t need = 3 * static_cast<std::size_t>(t) + 3;
    if (m_V.size() < need) {
        m_V.resize(need, kNone);
        m_O.resize(need, kNone);
    }
    for (int k = 0; k < 3; ++k) m_V[3 * t + k] = tri[k];
}

void TraceReplay::apply(const TraceOp& op) {
    m_touched.clear();
    std::set<std::int32_t> tris;
    // The slots the op writes, and their triples before it: touched() lists those that changed.
    std::map<std::int32_t, Triple> before;
    auto tripleAt = [&](std::int32_t t) {
        if (3 * static_cast<std::size_t>(t) + 2 >= m_V.size()) return Triple{kNone, kNone, kNone};
        return Triple{m_V[3 * t], m_V[3 * t + 1], m_V[3 * t + 2]};
    };
    if (op.hasChanges) {
        for (const CellChange& c : op.changes)
            before.emplace(tri(c.corner()), tripleAt(tri(c.corner())));
    } else if (op.hasTriangles) {
        for (const auto& t : op.triangles) before.emplace(t[0], tripleAt(t[0]));
    }
    if (op.hasChanges) {
        for (const CellChange& c : op.changes) {
            const std::size_t need = static_cast<std::size_t>(c.corner() / 3) * 3 + 3;
            if (m_V.size() < need) {
                m_V.resize(need, kNone);
                m_O.resize(need, kNone);
            }
            (c.isO() ? m_O : m_V)[c.corner()] = c.after;
            m_hasO = m_hasO || c.isO();
            tris.insert(tri(c.corner()));
        }
    } else if (op.hasTriangles) {
        if (op.type == OpType::Finalize) {  // the complete final list
            m_V.clear();
            m_O.clear();
        }
        for (const auto& t : op.triangles) {
            setTriangle(t[0], {t[1], t[2], t[3]});
            tris.insert(t[0]);
        }
    }
    // Trailing triangles whose cells were all cleared are gone (Finalize shrinks the table).
    while (m_V.size() >= 3 && m_V[m_V.size() - 1] == kNone && m_V[m_V.size() - 2] == kNone &&
           m_V[m_V.size() - 3] == kNone) {
        m_V.resize(m_V.size() - 3);
        m_O.resize(m_O.size() - 3);
    }
    for (std::int32_t t : tris) {
        const Triple now = tripleAt(t);
        const auto was = before.find(t);
        if (was != before.end() && was->second == now) continue;  // only its O cells changed
        if (now[0] != kNone && now[1] != kNone && now[2] != kNone)
            m_touched.push_back(canonical(now[0], now[1], now[2]));
    }
}

std::vector<Triple> TraceReplay::triangles() const {
    std::vector<Triple> out;
    for (std::size_t c = 0; c + 2 < m_V.size(); c += 3) {
        if (m_V[c] != kNone && m_V[c + 1] != kNone && m_V[c + 2] != kNone) {
            out.push_back(canonical(m_V[c], m_V[c + 1], m_V[c + 2]));
        }
    }
    std::sort(out.begin(), out.end());
    return out;
}

void TraceReplay::dropTrianglesOutside(const std::vector<bool>& keep) {
    std::vector<std::int32_t> V, O;
    for (std::size_t c = 0; c + 2 < m_V.size(); c += 3) {
        bool ok = true;
        for (int k = 0; k < 3; ++k) {
            const std::int32_t v = m_V[c + k];
            ok = ok && v >= 0 && static_cast<std::size_t>(v) < keep.size() && keep[v];
        }
        if (!ok) continue;
        V.insert(V.end(), m_V.begin() + c, m_V.begin() + c + 3);
        O.insert(O.end(), {kNone, kNone, kNone});
    }
    m_V = std::move(V);
    m_O = std::move(O);
}

// ============================================================================================
// [SECTION] Comparison
// ============================================================================================

namespace {

// The flip a Flip op made, from the two triangles it left: they share the new edge; their
// other vertices are the ends of the removed one.
std::optional<FlipMade> flipOf(const std::vector<Triple>& two) {
    if (two.size() != 2) return std::nullopt;
    std::vector<std::int32_t> shared, other;
    for (std::int32_t v : two[0])
        (std::count(two[1].begin(), two[1].end(), v) ? shared : other).push_back(v);
    for (std::int32_t v : two[1]) {
        if (!std::count(two[0].begin(), two[0].end(), v)) other.push_back(v);
    }
    if (shared.size() != 2 || other.size() != 2) return std::nullopt;
    return FlipMade{{other[0], other[1]}, {shared[0], shared[1]}};
}

// The flip's removed and new edges, from the two triangles it left ("" when they are no flip's).
std::string flipText(const std::vector<Triple>& two) {
    const std::optional<FlipMade> f = flipOf(two);
    if (!f) return "";
    auto edge = [](std::array<std::int32_t, 2> e) {
        return std::to_string(std::min(e[0], e[1])) + "-" + std::to_string(std::max(e[0], e[1]));
    };
    return "flipped edge " + edge(f->removed) + " to " + edge(f->added);
}

// Sorted multiset difference: in a but not b.
std::vector<Triple> minus(const std::vector<Triple>& a, const std::vector<Triple>& b) {
    std::vector<Triple> out;
    std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
    return out;
}

Triple reversed(const Triple& t) { return canonical(t[0], t[2], t[1]); }

// Keeps the difference of two triangle multisets up to date, op by op.
class TriangleBalance {
public:
    void add(const Triple& t, int side) {  // side +1: reference, -1: student
        int& n = m_count[t];
        if (n == 0) ++m_nonZero;
        n += side;
        if (n == 0) {
            --m_nonZero;
            m_count.erase(t);
        }
    }
    bool equal() const { return m_nonZero == 0; }

private:
    std::map<Triple, int> m_count;
    std::size_t m_nonZero = 0;
};

// The triangles (by slot) of a replay, kept in the balance as the replay changes.
class Tracked {
public:
    Tracked(TriangleBalance& balance, int side) : m_balance(balance), m_side(side) {}
    void apply(const TraceOp& op) {
        // Remove the triangles the op may change, replay, add them back as they are now.
        std::set<std::int32_t> slots;
        if (op.hasChanges) {
            for (const CellChange& c : op.changes) slots.insert(tri(c.corner()));
        } else if (op.hasTriangles) {
            for (const auto& t : op.triangles) slots.insert(t[0]);
        }
        const bool whole = op.type == OpType::Finalize && !op.hasChanges && op.hasTriangles;
        if (whole) {
            for (std::size_t t = 0; 3 * t + 2 < m_replay.V().size(); ++t)
                slots.insert(static_cast<std::int32_t>(t));
        }
        for (std::int32_t t : slots) account(t, -1);
        m_replay.apply(op);
        for (std::int32_t t : slots) account(t, +1);
    }
    void dropOutside(const std::vector<bool>& keep) {
        for (const Triple& t : m_replay.triangles()) m_balance.add(t, -m_side);
        m_replay.dropTrianglesOutside(keep);
        for (const Triple& t : m_replay.triangles()) m_balance.add(t, m_side);
    }
    const TraceReplay& replay() const { return m_replay; }

private:
    void account(std::int32_t t, int sign) {
        const auto& V = m_replay.V();
        if (3 * static_cast<std::size_t>(t) + 2 >= V.size()) return;
        if (V[3 * t] == kNone || V[3 * t + 1] == kNone || V[3 * t + 2] == kNone) return;
        m_balance.add(canonical(V[3 * t], V[3 * t + 1], V[3 * t + 2]), sign * m_side);
    }
    TriangleBalance& m_balance;
    int m_side;
    TraceReplay m_replay;
};

// First corner where two tables differ (kNone when they agree).
std::int32_t firstCornerDiff(const std::vector<std::int32_t>& a,
                             const std::vector<std::int32_t>& b) {
    const std::size_t n = std::max(a.size(), b.size());
    for (std::size_t c = 0; c < n; ++c) {
        const std::int32_t x = c < a.size() ? a[c] : kNone, y = c < b.size() ? b[c] : kNone;
        if (x != y) return static_cast<std::int32_t>(c);
    }
    return kNone;
}

std::string cell(const std::vector<std::int32_t>& t, std::int32_t c) {
    return static_cast<std::size_t>(c) < t.size() ? std::to_string(t[c]) : "(none)";
}

// The vertices the reference keeps at the end: a student's bare Finalize drops the others.
std::vector<bool> finalVertices(const TraceFile& ref) {
    std::vector<bool> real;
    TraceReplay end;
    for (const TraceOp& op : ref.ops) end.apply(op);
    for (const Triple& t : end.triangles()) {
        for (std::int32_t v : t) {
            if (static_cast<std::size_t>(v) >= real.size()) real.resize(v + 1, false);
            real[v] = true;
        }
    }
    return real;
}

bool bareFinalize(const TraceOp& op) {
    return op.type == OpType::Finalize && !op.hasChanges && !op.hasTriangles;
}

// ---- Insertion by insertion ------------------------------------------------------------------

bool startsStep(OpType t) {
    return t == OpType::Start || t == OpType::Split || t == OpType::SplitEdge ||
           t == OpType::SkipDuplicate || t == OpType::Finalize;
}

// One step of a run: the ops [begin, end), led by the op at `lead` (Start, a split, a skipped
// duplicate or Finalize), with the flips that follow it.
struct Step {
    std::size_t begin = 0, end = 0, lead = 0;
};

std::vector<Step> stepsOf(const TraceFile& f) {
    std::vector<Step> steps;
    for (std::size_t i = 0; i < f.ops.size(); ++i) {
        if (!startsStep(f.ops[i].type)) continue;
        // The walk that found this point belongs to its step, not to the one before.
        std::size_t begin = i;
        while (!steps.empty() && begin > steps.back().lead + 1 &&
               (f.ops[begin - 1].type == OpType::LocateStep ||
                f.ops[begin - 1].type == OpType::Located))
            --begin;
        if (!steps.empty()) steps.back().end = begin;
        steps.push_back({steps.empty() ? 0 : begin, f.ops.size(), i});
    }
    return steps;
}

// The step's last op that changed the mesh: after it, the mesh is the step's result.
std::size_t lastChange(const TraceFile& f, const Step& step) {
    for (std::size_t i = step.end; i-- > step.lead;) {
        if (f.ops[i].changesMesh()) return i;
    }
    return step.lead;
}

std::string stepName(const TraceOp& lead, int insertion, int insertions) {
    const std::string v = lead.vertex && *lead.vertex >= 0 ? std::to_string(*lead.vertex) : "?";
    switch (lead.type) {
        case OpType::Start: return "after the start (the first triangles)";
        case OpType::SkipDuplicate:
            return "after skipping duplicate point " + v + " (insertion " +
                   std::to_string(insertion) + " of " + std::to_string(insertions) + ")";
        case OpType::Finalize: return "after Finalize";
        default:
            return "after inserting point " + v + " (insertion " + std::to_string(insertion) +
                   " of " + std::to_string(insertions) + ")";
    }
}

// The insertions of a run: its steps but the start and Finalize.
int countInsertions(const TraceFile& ref, const std::vector<Step>& steps) {
    int insertions = 0;
    for (const Step& st : steps)
        insertions +=
            !(ref.ops[st.lead].type == OpType::Start || ref.ops[st.lead].type == OpType::Finalize);
    return insertions;
}

// A trace whose every step but Finalize was there: the last line is missing.
std::string endsBeforeFinalize(const std::string& who, const TraceFile& ref, const TraceOp& fin) {
    return who + " ends before Finalize: end it with {\"op\": \"Finalize\"}, which drops the " +
           "triangles that touch the super-triangle or the ghost vertex (ours: " + ref.name + ":" +
           std::to_string(fin.line) + ")";
}

// Step k exists in one trace only: which one ended, and what the other does next.
std::string stepEndMismatch(const TraceFile& ref, const TraceFile& student,
                            const std::vector<Step>& rs, const std::vector<Step>& ss,
                            std::size_t k) {
    if (k >= ss.size()) {
        const TraceOp& next = ref.ops[rs[k].lead];
        if (next.type == OpType::Finalize) return endsBeforeFinalize("your trace", ref, next);
        return "your trace ends early: ours goes on with " + std::string(toString(next.type)) +
               (next.vertex && *next.vertex >= 0 ? " of point " + std::to_string(*next.vertex)
                                                 : "") +
               " (" + ref.name + ":" + std::to_string(next.line) + ")";
    }
    return "your trace goes on after ours has ended, with " +
           std::string(toString(student.ops[ss[k].lead].type)) + " (" + student.name + ":" +
           std::to_string(student.ops[ss[k].lead].line) + ")";
}

// Whether every triangle an op left is counter-clockwise (true when that cannot be decided).
bool turnsLeft(const std::vector<Triple>& touched, const MeshGeometry& g) {
    for (const Triple& t : touched) {
        bool known = true;
        for (std::int32_t v : t)
            known =
                known && v >= 0 && static_cast<std::size_t>(v) < g.points.size() && !g.isGhost(v);
        if (known && orient2d(g.points[t[0]], g.points[t[1]], g.points[t[2]]) <= 0) return false;
    }
    return true;
}

// What the student's step did: its flips in order, and the first flip of an edge that was
// Delaunay when no op before it in the step had left a clockwise or flat triangle.
struct StudentStep {
    std::vector<FlipMade> flips;
    std::optional<MeshVerdict> wrongFlip;
};

// Replays the student's step (`newVertex`: the point ours inserts in it, -1 when none).
StudentStep replayStep(Tracked& s, const TraceFile& student, const Step& step,
                       const MeshGeometry& g, std::int32_t newVertex) {
    StudentStep out;
    bool judged = !g.known();  // a mistake was found (or nothing can be judged): stop looking
    for (std::size_t j = step.begin; j < step.end; ++j) {
        s.apply(student.ops[j]);
        const bool flip = student.ops[j].type == OpType::Flip;
        const std::optional<FlipMade> f =
            flip ? flipOf(s.replay().touched()) : std::optional<FlipMade>();
        if (f) out.flips.push_back(*f);
        if (judged) continue;
        if (f && (out.wrongFlip = checkFlipMade(*f, g, newVertex))) judged = true;
        if (!turnsLeft(s.replay().touched(), g)) judged = true;
    }
    return out;
}

// Replays both traces step by step (the start, each insertion, Finalize) and stops at the first
// step after which the student's triangles differ from ours, with the mesh check's reason.
TraceDiff diffInsertions(const TraceFile& ref, const TraceFile& student) {
    TraceDiff d;
    TriangleBalance balance;
    Tracked r(balance, +1), s(balance, -1);
    const std::vector<bool> realVertices = finalVertices(ref);
    const std::vector<Step> rs = stepsOf(ref), ss = stepsOf(student);
    const int insertions = countInsertions(ref, rs);
    int insertion = 0;
    for (std::size_t k = 0; k < std::max(rs.size(), ss.size()); ++k) {
        if (k >= rs.size() || k >= ss.size()) {
            d.refOp = k < rs.size() ? rs[k].lead : ref.ops.size();
            d.studentOp = k < ss.size() ? ss[k].lead : student.ops.size();
            d.equal = false;
            d.what = stepEndMismatch(ref, student, rs, ss, k);
            return d;
        }
        const TraceOp& lead = ref.ops[rs[k].lead];
        insertion = lead.type == OpType::Start      ? 0
                    : lead.type == OpType::Finalize ? insertions + 1
                                                    : insertion + 1;
        for (std::size_t i = rs[k].begin; i < rs[k].end; ++i) r.apply(ref.ops[i]);
        const bool inserts = lead.type == OpType::Split || lead.type == OpType::SplitEdge;
        const std::int32_t v = inserts && lead.vertex ? *lead.vertex : -1;
        const StudentStep done = replayStep(s, student, ss[k], ref.geometry, v);
        if (bareFinalize(student.ops[ss[k].lead])) s.dropOutside(realVertices);
        ++d.compared;
        if (balance.equal()) continue;
        const MeshVerdict verdict = checkStudentMesh(s.replay().triangles(), r.replay().triangles(),
                                                     ref.geometry, v, done.flips, done.wrongFlip);
        d.equal = false;
        d.insertion = insertion;
        d.vertex = lead.vertex && lead.type != OpType::Finalize ? *lead.vertex : -1;
        d.refOp = lastChange(ref, rs[k]);
        d.studentOp = lastChange(student, ss[k]);
        d.what = stepName(lead, insertion, insertions) + ": " + verdict.reason;
        const TraceOp& theirs = student.ops[ss[k].lead];
        if (theirs.type != lead.type)
            d.details.push_back(std::string("ours does ") + toString(lead.type) + " here, yours " +
                                toString(theirs.type));
        d.details.insert(d.details.end(), verdict.details.begin(), verdict.details.end());
        return d;
    }
    d.refOp = ref.ops.size();
    d.studentOp = student.ops.size();
    d.what = "the runs agree: the triangles are the same after each of the " +
             std::to_string(d.compared) + " steps (start, " + std::to_string(insertions) +
             " insertions, Finalize)";
    return d;
}

// ---- Op by op ----------------------------------------------------------------------------

// A difference found op by op: the line that names it and its evidence.
struct Mismatch {
    std::string what;
    std::vector<std::string> details;
    bool order = false;  // a difference the order of the ops may explain (not corners, walks)
};

// One trace has ended (i or j past its end) while the other goes on.
std::string endMismatch(const TraceFile& ref, const TraceFile& student, std::size_t i,
                        std::size_t j) {
    if (j == student.ops.size()) {
        if (ref.ops[i].type == OpType::Finalize)
            return endsBeforeFinalize("the student's trace", ref, ref.ops[i]);
        return "the student's trace ends early: the reference goes on with " +
               std::string(toString(ref.ops[i].type)) + " (" + ref.name + ":" +
               std::to_string(ref.ops[i].line) + ")";
    }
    return "the student's trace goes on after the reference has ended, with " +
           std::string(toString(student.ops[j].type)) + " (" + student.name + ":" +
           std::to_string(student.ops[j].line) + ")";
}

// The two ops themselves differ: type, vertex, or (all ops compared) the in-circle answer.
std::optional<std::string> opMismatch(const TraceOp& a, const TraceOp& b,
                                      const DiffOptions& options) {
    if (a.type != b.type) {
        return std::string("the reference does ") + toString(a.type) + ", the student " +
               toString(b.type);
    }
    if (a.vertex && b.vertex && *a.vertex != *b.vertex) {
        return std::string(toString(a.type)) + " of vertex " + std::to_string(*a.vertex) +
               " in the reference, of vertex " + std::to_string(*b.vertex) +
               " in the student's run";
    }
    if (options.allOps && a.sign && b.sign && *a.sign != *b.sign) {
        return "the in-circle test answers " + std::to_string(*a.sign) + " in the reference, " +
               std::to_string(*b.sign) + " in the student's run";
    }
    return std::nullopt;
}

// After op a the two sets of triangles differ: which triangles, and the flips that made them.
Mismatch triangleMismatch(const TraceOp& a, const Tracked& r, const Tracked& s) {
    const auto rt = r.replay().triangles(), st = s.replay().triangles();
    const auto onlyRef = minus(rt, st), onlyStu = minus(st, rt);
    Mismatch m{
        std::string("the triangles differ after ") + toString(a.type) +
            (a.vertex && *a.vertex != kNone ? " (vertex " + std::to_string(*a.vertex) + ")" : ""),
        {}};
    if (a.type == OpType::Flip) {
        const std::string fr = flipText(r.replay().touched()), fs = flipText(s.replay().touched());
        if (!fr.empty()) m.details.push_back("reference: " + fr);
        if (!fs.empty()) m.details.push_back("student:   " + fs);
    }
    m.details.push_back("triangles only in the reference: " + triplesText(onlyRef));
    m.details.push_back("triangles only in the student's: " + triplesText(onlyStu));
    std::size_t flippedOrientation = 0;
    for (const Triple& t : onlyStu)
        flippedOrientation += std::binary_search(onlyRef.begin(), onlyRef.end(), reversed(t));
    if (flippedOrientation) {
        m.details.push_back(
            std::to_string(flippedOrientation) +
            " of the student's triangles are reference triangles in the other orientation "
            "(clockwise): list corners counter-clockwise, y up");
    }
    return m;
}

// Same triangles after op a, compared corner by corner: the first V, then O, that differs.
std::optional<Mismatch> cornerMismatch(const TraceOp& a, const Tracked& r, const Tracked& s) {
    const std::int32_t cv = firstCornerDiff(r.replay().V(), s.replay().V());
    if (cv != kNone) {
        return Mismatch{
            std::string("same triangles, but the corners differ after ") + toString(a.type) +
                ": V[" + std::to_string(cv) + "] is " + cell(r.replay().V(), cv) +
                " in the reference, " + cell(s.replay().V(), cv) + " in the student's run",
            {"the paper's convention: a split keeps the old triangle's corners (it becomes "
             "(a, b, v)) "
             "and appends (b, c, v) and (c, a, v); a flip rewrites its two triangles in "
             "place"}};
    }
    if (!s.replay().hasO()) return std::nullopt;
    const std::int32_t co = firstCornerDiff(r.replay().O(), s.replay().O());
    if (co == kNone) return std::nullopt;
    return Mismatch{std::string("same triangles and V, but O differs after ") + toString(a.type) +
                        ": O[" + std::to_string(co) + "] is " + cell(r.replay().O(), co) +
                        " in the reference, " + cell(s.replay().O(), co) + " in the student's run",
                    {}};
}

// The step of a run (stepsOf) that op i belongs to.
std::size_t stepIndex(const std::vector<Step>& steps, std::size_t i) {
    std::size_t k = 0;
    while (k + 1 < steps.size() && steps[k + 1].lead <= i) ++k;
    return k;
}

// An op-by-op difference in a run whose insertions end with our triangles is one of order: say
// so, and where the first insertion that does not comes.
void explainOrder(TraceDiff& d, const TraceFile& ref, const TraceFile& student) {
    const TraceDiff steps = diffInsertions(ref, student);
    if (steps.equal) {
        d.what = "only the order differs: " + d.what;
        d.details.push_back(
            "after every insertion the student's triangles are ours: the same Delaunay "
            "triangulation, reached in another order (of flips: another order of popping the "
            "edges to test). That is no bug; --by-op asks for our order (the edge pushed last is "
            "tested first), and without --by-op the runs agree");
        return;
    }
    const std::vector<Step> rs = stepsOf(ref);
    if (stepIndex(rs, steps.refOp) > stepIndex(rs, d.refOp)) {
        d.what = "only the order differs at this insertion: " + d.what;
        d.details.push_back(
            "this insertion ends with our triangles; the first one that does not: " + steps.what);
    }
}

// The student's op b is a flip of an edge that was Delaunay (s has just applied it).
std::optional<MeshVerdict> wrongFlipOf(const TraceOp& b, const Tracked& s, const TraceFile& ref,
                                       std::int32_t newVertex) {
    if (b.type != OpType::Flip) return std::nullopt;
    const std::optional<FlipMade> f = flipOf(s.replay().touched());
    return f ? checkFlipMade(*f, ref.geometry, newVertex) : std::nullopt;
}

// The first difference of ops a (ours) and b (the student's), replayed in r and s; nullopt when
// they agree. `newVertex`: the point ours is inserting.
std::optional<Mismatch> compareOp(const TraceOp& a, const TraceOp& b, Tracked& r, Tracked& s,
                                  const TraceFile& ref, const DiffOptions& options,
                                  std::int32_t newVertex) {
    const bool maybeOrder = !options.allOps;  // walks and tests differ for other reasons
    if (auto what = opMismatch(a, b, options)) {
        s.apply(b);  // to name a wrong flip: the comparison stops here
        if (auto wrong = wrongFlipOf(b, s, ref, newVertex))
            return Mismatch{*what + "; the student's " + wrong->reason, wrong->details, false};
        return Mismatch{std::move(*what), {}, maybeOrder};
    }
    r.apply(a);
    s.apply(b);
    return std::nullopt;
}

// Replays both traces op by op (only the compared ops, unless options.allOps) and stops at the
// first op where the ops or the meshes they leave differ.
TraceDiff diffByOp(const TraceFile& ref, const TraceFile& student, const DiffOptions& options) {
    TraceDiff d;
    TriangleBalance balance;
    Tracked r(balance, +1), s(balance, -1);
    auto compared = [&](const TraceOp& op) { return options.allOps || op.changesMesh(); };
    const std::vector<bool> realVertices = finalVertices(ref);
    std::size_t i = 0, j = 0;
    std::int32_t inserting = kNone;
    auto fail = [&](Mismatch m) {
        d.equal = false;
        d.what = std::move(m.what);
        d.details = std::move(m.details);
        d.refOp = i;
        d.studentOp = j;
        if (m.order) explainOrder(d, ref, student);
        return d;
    };
    while (true) {
        // Replay up to and including the next compared op of each trace.
        while (i < ref.ops.size() && !compared(ref.ops[i])) r.apply(ref.ops[i++]);
        while (j < student.ops.size() && !compared(student.ops[j])) s.apply(student.ops[j++]);
        const bool refDone = i == ref.ops.size(), stuDone = j == student.ops.size();
        if (refDone && stuDone) break;
        if (refDone || stuDone) return fail({endMismatch(ref, student, i, j), {}, false});
        const TraceOp& a = ref.ops[i];
        const TraceOp& b = student.ops[j];
        if (a.vertex && *a.vertex >= 0 && a.type != OpType::Finalize) inserting = *a.vertex;
        if (auto m = compareOp(a, b, r, s, ref, options, inserting)) return fail(std::move(*m));
        if (bareFinalize(b)) s.dropOutside(realVertices);
        ++d.compared;
        if (!balance.equal()) {
            Mismatch m = triangleMismatch(a, r, s);
            m.order = !options.allOps;
            if (auto wrong = wrongFlipOf(b, s, ref, inserting)) {
                m.what = "the student's " + wrong->reason;
                m.details.insert(m.details.begin(), wrong->details.begin(), wrong->details.end());
                m.order = false;
            }
            return fail(std::move(m));
        }
        if (options.corners && !bareFinalize(b)) {
            if (auto m = cornerMismatch(a, r, s)) return fail(std::move(*m));
        }
        ++i;
        ++j;
    }
    d.refOp = ref.ops.size();
    d.studentOp = student.ops.size();
    d.what = "the runs agree: " + std::to_string(d.compared) + " operations compared" +
             (options.corners ? ", corner by corner" : ", by their triangles");
    return d;
}

bool hasWalkOrTests(const TraceFile& f) {
    return std::any_of(f.ops.begin(), f.ops.end(), [](const TraceOp& op) {
        return op.type == OpType::LocateStep || op.type == OpType::Located ||
               op.type == OpType::InCircleTest;
    });
}

// What the options do that a user may not expect, one line each.
std::vector<std::string> optionNotes(const TraceFile& ref, const TraceFile& student,
                                     const DiffOptions& o) {
    std::vector<std::string> notes;
    if (!o.byOp && (o.allOps || o.corners)) {
        notes.push_back(std::string("note: ") +
                        (o.allOps && o.corners ? "--all-ops and --corners compare"
                         : o.allOps            ? "--all-ops compares"
                                               : "--corners compares") +
                        " operation by operation: as with --by-op");
    }
    if (o.allOps && hasWalkOrTests(ref) && !hasWalkOrTests(student)) {
        notes.push_back("note: --all-ops compares the walk steps and in-circle tests too, but " +
                        student.name +
                        " has no LocateStep, Located or InCircleTest line (the assignment asks "
                        "only for the operations that change the mesh), so it cannot pass: "
                        "leave out --all-ops");
    }
    return notes;
}

}  // namespace

TraceDiff diffTraces(const TraceFile& ref, const TraceFile& student, const DiffOptions& options) {
    TraceDiff d = options.byOp || options.corners || options.allOps
                      ? diffByOp(ref, student, options)
                      : diffInsertions(ref, student);
    d.notes = optionNotes(ref, student, options);
    return d;
}

std::string summarize(const TraceFile& f, std::size_t k) {
    if (k >= f.ops.size()) return f.name + ": (end of trace)";
    const TraceOp& op = f.ops[k];
    std::string s = f.name + ":" + std::to_string(op.line) + " ";
    if (op.index) s += "[" + std::to_string(*op.index) + "] ";
    s += toString(op.type);
    if (op.vertex && *op.vertex != kNone) s += " vertex " + std::to_string(*op.vertex);
    if (op.a) s += " a=" + std::to_string(*op.a);
    if (op.b) s += " b=" + std::to_string(*op.b);
    if (!op.where.empty()) s += " " + op.where;
    if (op.sign) s += " sign=" + std::to_string(*op.sign);
    if (op.hasTriangles && !op.triangles.empty()) {
        std::vector<Triple> ts;
        for (const auto& t : op.triangles) ts.push_back(canonical(t[1], t[2], t[3]));
        s += " -> " + triplesText(ts, 4);
    }
    return s;
}

std::string formatDiff(const TraceDiff& d, const TraceFile& ref, const TraceFile& student,
                       const DiffOptions& options) {
    std::ostringstream out;
    for (const std::string& note : d.notes) out << note << "\n";
    if (d.equal) {
        out << d.what << "\n";
        return out.str();
    }
    auto at = [](const TraceFile& f, std::size_t k) {
        return k < f.ops.size() ? "op " + std::to_string(k) + " (" + f.name + ":" +
                                      std::to_string(f.ops[k].line) + ")"
                                : std::string("the end of ") + f.name;
    };
    out << "first difference at reference " << at(ref, d.refOp) << ", student "
        << at(student, d.studentOp) << ":\n  " << d.what << "\n";
    for (const std::string& line : d.details) out << "  " << line << "\n";
    const auto context = [&](const TraceFile& f, std::size_t k, const char* who) {
        out << "context (" << who << "):\n";
        const std::size_t from =
            k > static_cast<std::size_t>(options.context) ? k - options.context : 0;
        for (std::size_t x = from; x <= k + 1 && x < f.ops.size(); ++x) {
            out << (x == k ? "  > " : "    ") << summarize(f, x) << "\n";
        }
        if (k >= f.ops.size()) out << "  > (end of trace)\n";
    };
    context(ref, d.refOp, "reference");
    context(student, d.studentOp, "student");
    return out.str();
}

}  // namespace dlab
