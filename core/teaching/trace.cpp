// JSON Lines trace of the inserter's operations (nlohmann_json, header-only).
#include "core/teaching/trace.h"
#include "core/teaching/json_quote.h"

#include <nlohmann/json.hpp>

#include "core/engine/io_read.h"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <istream>
#include <limits>
#include <stdexcept>

namespace dlab {

bool operator==(const TraceRecord& x, const TraceRecord& y) {
    auto sameChanges = [](const std::vector<CellChange>& p, const std::vector<CellChange>& q) {
        return std::equal(p.begin(), p.end(), q.begin(), q.end(),
                          [](const CellChange& u, const CellChange& v) {
                              return u.slot == v.slot && u.before == v.before && u.after == v.after;
                          });
    };
    auto sameTris = [](const std::vector<TraceRecord::Tri>& p,
                       const std::vector<TraceRecord::Tri>& q) {
        return std::equal(p.begin(), p.end(), q.begin(), q.end(), [](const auto& u, const auto& v) {
            return u.t == v.t && u.v0 == v.v0 && u.v1 == v.v1 && u.v2 == v.v2;
        });
    };
    return x.index == y.index && x.type == y.type && x.vertex == y.vertex && x.a == y.a &&
           x.b == y.b && x.where == y.where && x.sign == y.sign && x.hasSign == y.hasSign &&
           x.trianglesBefore == y.trianglesBefore && x.trianglesAfter == y.trianglesAfter &&
           sameChanges(x.changes, y.changes) && sameTris(x.triangles, y.triangles);
}

TraceRecord traceRecord(const Journal& journal, std::size_t opIndex, const Mesh& mesh) {
    const Op& op = journal.ops().at(opIndex);
    TraceRecord r;
    r.index = opIndex;
    r.type = op.type;
    r.vertex = op.vertex;
    r.a = op.a;
    r.b = op.b;
    if (op.type == OpType::Located || op.type == OpType::Split || op.type == OpType::SplitEdge) {
        r.where = toString(op.where);
    }
    if (op.type == OpType::InCircleTest) {
        r.sign = op.sign;
        r.hasSign = true;
    }
    r.trianglesBefore = op.trianglesBefore;
    r.trianglesAfter = op.trianglesAfter;
    const auto& all = journal.changes();
    r.changes.assign(all.begin() + op.firstChange, all.begin() + op.firstChange + op.numChanges);
    if (op.type != OpType::Finalize) {
        std::vector<std::int32_t> tris;
        for (const CellChange& c : r.changes) tris.push_back(tri(c.corner()));
        std::sort(tris.begin(), tris.end());
        tris.erase(std::unique(tris.begin(), tris.end()), tris.end());
        for (std::int32_t t : tris) {
            if (t < mesh.numTriangles()) {
                r.triangles.push_back({t, mesh.V[3 * t], mesh.V[3 * t + 1], mesh.V[3 * t + 2]});
            }
        }
    }
    return r;
}

std::string toJsonLine(const TraceRecord& r) {
    nlohmann::ordered_json j;
    j["i"] = r.index;
    j["op"] = toString(r.type);
    j["vertex"] = r.vertex;
    j["a"] = r.a;
    j["b"] = r.b;
    if (!r.where.empty()) j["where"] = r.where;
    if (r.hasSign) j["sign"] = r.sign;
    j["triangles_before"] = r.trianglesBefore;
    j["triangles_after"] = r.trianglesAfter;
    auto changes = nlohmann::json::array();
    for (const CellChange& c : r.changes) {
        changes.push_back(
            nlohmann::json::array({c.isO() ? "O" : "V", c.corner(), c.before, c.after}));
    }
    j["changes"] = std::move(changes);
    auto tris = nlohmann::json::array();
    for (const auto& t : r.triangles) tris.push_back({t.t, t.v0, t.v1, t.v2});
    j["triangles"] = std::move(tris);
    return j.dump();
}

namespace {

// Integer fields are read exactly: a float ("1e300", "2.5") or a value outside the field's range
// is an error. nlohmann's get<int>() would convert or truncate silently, and converting an
// out-of-range float to an integer is undefined behaviour.
std::int64_t integerField(const nlohmann::json& v, const std::string& what, std::int64_t lo,
                          std::int64_t hi,
                          const std::function<InputError(const std::string&)>& fail) {
    if (!v.is_number_integer()) throw fail(what + " must be an integer, found " + quoteJson(v));
    if (v.is_number_unsigned()) {
        const auto u = v.get<std::uint64_t>();
        if (u > static_cast<std::uint64_t>(hi))
            throw fail(what + " " + std::to_string(u) + " is out of range");
        return static_cast<std::int64_t>(u);
    }
    const auto s = v.get<std::int64_t>();
    if (s < lo || s > hi) throw fail(what + " " + std::to_string(s) + " is out of range");
    return s;
}

}  // namespace

TraceRecord parseTraceLine(const std::string& line, const std::string& name, int lineNumber) {
    const std::function<InputError(const std::string&)> fail = [&](const std::string& what) {
        return InputError(name, lineNumber, what);
    };
    constexpr std::int64_t kMaxI32 = std::numeric_limits<std::int32_t>::max();
    const auto int32Field = [&](const nlohmann::json& j, const char* key, std::int64_t lo) {
        return static_cast<std::int32_t>(
            j.contains(key) ? integerField(j[key], key, lo, kMaxI32, fail) : kNone);
    };
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(line);
    } catch (const nlohmann::json::exception& e) {
        throw fail(std::string("not valid JSON (") + e.what() + ")");
    }
    if (!j.is_object()) throw fail("a trace line must be a JSON object");
    try {
        TraceRecord r;
        if (!j.contains("i")) throw fail("missing \"i\" (the op's index)");
        r.index = static_cast<std::size_t>(
            integerField(j["i"], "i", 0, std::numeric_limits<std::int64_t>::max(), fail));
        const auto type = parseOpType(j.at("op").get<std::string>());
        if (!type) throw fail("unknown op " + quoteJson(j.at("op")));
        r.type = *type;
        r.vertex = int32Field(j, "vertex", kNone);
        r.a = int32Field(j, "a", kNone);
        r.b = int32Field(j, "b", kNone);
        r.where = j.value("where", std::string());
        if (j.contains("sign")) {
            r.sign = static_cast<int>(integerField(j["sign"], "sign", -1, 1, fail));
            r.hasSign = true;
        }
        r.trianglesBefore =
            j.contains("triangles_before") ? int32Field(j, "triangles_before", 0) : 0;
        r.trianglesAfter = j.contains("triangles_after") ? int32Field(j, "triangles_after", 0) : 0;
        // By reference: value() would copy the field, one recursion per level of its nesting.
        static const nlohmann::json kNoList = nlohmann::json::array();
        const auto listOf = [&](const char* key) -> const nlohmann::json& {
            const auto it = j.find(key);
            return it == j.end() ? kNoList : *it;
        };
        for (const auto& c : listOf("changes")) {
            if (!c.is_array() || c.size() != 4)
                throw fail("a change must be [\"V\"|\"O\", corner, before, after]");
            const std::string table = c[0].get<std::string>();
            if (table != "V" && table != "O")
                throw fail("a change names table V or O, not " + quoteJson(c[0]));
            const auto corner =
                static_cast<std::int32_t>(integerField(c[1], "corner", 0, 1 << 29, fail));
            r.changes.push_back(
                {2 * corner + (table == "O" ? 1 : 0),
                 static_cast<std::int32_t>(integerField(c[2], "before", kNone, kMaxI32, fail)),
                 static_cast<std::int32_t>(integerField(c[3], "after", kNone, kMaxI32, fail))});
        }
        for (const auto& t : listOf("triangles")) {
            if (!t.is_array() || t.size() != 4) throw fail("a triangle must be [t, v0, v1, v2]");
            std::int32_t v[4];
            for (int k = 0; k < 4; ++k)
                v[k] = static_cast<std::int32_t>(integerField(t[k], "triangle", 0, kMaxI32, fail));
            r.triangles.push_back({v[0], v[1], v[2], v[3]});
        }
        return r;
    } catch (const nlohmann::json::exception& e) {
        throw fail(std::string("bad field (") + e.what() + ")");
    }
}

std::vector<TraceRecord> readTrace(std::istream& in, const std::string& name) {
    std::vector<TraceRecord> out;
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
        ++number;
        if (line.empty() || line == "\r") continue;
        out.push_back(parseTraceLine(line, name, number));
    }
    return out;
}

}  // namespace dlab
