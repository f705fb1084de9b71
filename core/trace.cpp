// JSON Lines trace of the inserter's operations (nlohmann_json, header-only).
#include "core/trace.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <istream>
#include <stdexcept>

namespace dlab {

bool operator==(const TraceRecord& x, const TraceRecord& y) {
    auto sameChanges = [](const std::vector<CellChange>& p, const std::vector<CellChange>& q) {
        return std::equal(p.begin(), p.end(), q.begin(), q.end(), [](const CellChange& u, const CellChange& v) {
            return u.slot == v.slot && u.before == v.before && u.after == v.after;
        });
    };
    auto sameTris = [](const std::vector<TraceRecord::Tri>& p, const std::vector<TraceRecord::Tri>& q) {
        return std::equal(p.begin(), p.end(), q.begin(), q.end(), [](const auto& u, const auto& v) {
            return u.t == v.t && u.v0 == v.v0 && u.v1 == v.v1 && u.v2 == v.v2;
        });
    };
    return x.index == y.index && x.type == y.type && x.vertex == y.vertex && x.a == y.a && x.b == y.b &&
           x.where == y.where && x.sign == y.sign && x.hasSign == y.hasSign &&
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
        changes.push_back(nlohmann::json::array({c.isO() ? "O" : "V", c.corner(), c.before, c.after}));
    }
    j["changes"] = std::move(changes);
    auto tris = nlohmann::json::array();
    for (const auto& t : r.triangles) tris.push_back({t.t, t.v0, t.v1, t.v2});
    j["triangles"] = std::move(tris);
    return j.dump();
}

TraceRecord parseTraceLine(const std::string& line, const std::string& name, int lineNumber) {
    auto fail = [&](const std::string& what) {
        return std::runtime_error(name + ":" + std::to_string(lineNumber) + ": " + what);
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
        r.index = j.at("i").get<std::size_t>();
        const auto type = parseOpType(j.at("op").get<std::string>());
        if (!type) throw fail("unknown op \"" + j.at("op").get<std::string>() + "\"");
        r.type = *type;
        r.vertex = j.value("vertex", kNone);
        r.a = j.value("a", kNone);
        r.b = j.value("b", kNone);
        r.where = j.value("where", std::string());
        if (j.contains("sign")) {
            r.sign = j.at("sign").get<int>();
            r.hasSign = true;
        }
        r.trianglesBefore = j.value("triangles_before", 0);
        r.trianglesAfter = j.value("triangles_after", 0);
        for (const auto& c : j.value("changes", nlohmann::json::array())) {
            if (!c.is_array() || c.size() != 4) throw fail("a change must be [\"V\"|\"O\", corner, before, after]");
            const std::string table = c[0].get<std::string>();
            if (table != "V" && table != "O") throw fail("a change names table V or O, not \"" + table + "\"");
            const std::int32_t corner = c[1].get<std::int32_t>();
            if (corner < 0 || corner > (1 << 29)) throw fail("corner out of range");
            r.changes.push_back({2 * corner + (table == "O" ? 1 : 0), c[2].get<std::int32_t>(), c[3].get<std::int32_t>()});
        }
        for (const auto& t : j.value("triangles", nlohmann::json::array())) {
            if (!t.is_array() || t.size() != 4) throw fail("a triangle must be [t, v0, v1, v2]");
            r.triangles.push_back({t[0].get<std::int32_t>(), t[1].get<std::int32_t>(), t[2].get<std::int32_t>(),
                                   t[3].get<std::int32_t>()});
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
