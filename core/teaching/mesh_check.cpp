// The checks run in the order a student would fix them: vertices, orientation, overlaps, holes,
// then the Delaunay property edge by edge; the first problem found is the reason, the triangles
// that differ are the evidence.
#include "core/teaching/mesh_check.h"

#include "core/engine/predicates.h"

#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <utility>

namespace dlab {

Triple canonical(std::int32_t v0, std::int32_t v1, std::int32_t v2) {
    if (v1 < v0 && v1 <= v2) return {v1, v2, v0};
    if (v2 < v0 && v2 < v1) return {v2, v0, v1};
    return {v0, v1, v2};
}

std::string edgeName(std::int32_t a, std::int32_t b) {
    return std::to_string(std::min(a, b)) + "\u2013" + std::to_string(std::max(a, b));
}

std::string tripleText(const Triple& t) {
    return "(" + std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " + std::to_string(t[2]) +
           ")";
}

std::string triplesText(const std::vector<Triple>& ts, std::size_t most) {
    std::string s;
    for (std::size_t i = 0; i < ts.size() && i < most; ++i) s += (i ? " " : "") + tripleText(ts[i]);
    if (ts.size() > most) s += " ... (" + std::to_string(ts.size()) + " in all)";
    return s.empty() ? "none" : s;
}

namespace {

using Edge = std::pair<std::int32_t, std::int32_t>;  // directed: the triangle is on its left
using Problem = std::optional<MeshVerdict>;

MeshVerdict verdict(std::string reason) {
    MeshVerdict v;
    v.ok = false;
    v.reason = std::move(reason);
    return v;
}

// The third vertex of triangle t, given two of its vertices.
std::int32_t third(const Triple& t, std::int32_t a, std::int32_t b) {
    for (std::int32_t v : t) {
        if (v != a && v != b) return v;
    }
    return t[0];
}

struct Edges {
    std::map<Edge, Triple> left;  // each directed edge -> its triangle
    Problem overlap;              // two triangles on the same side of one edge
};

Edges edgesOf(const std::vector<Triple>& ts) {
    Edges e;
    for (const Triple& t : ts) {
        for (int k = 0; k < 3; ++k) {
            const Edge ab{t[k], t[(k + 1) % 3]};
            const auto [it, fresh] = e.left.emplace(ab, t);
            if (!fresh && !e.overlap) {
                e.overlap = verdict("triangles " + tripleText(it->second) + " and " +
                                    tripleText(t) + " overlap: both lie on the same side of edge " +
                                    edgeName(ab.first, ab.second));
            }
        }
    }
    return e;
}

std::set<std::int32_t> verticesOf(const std::vector<Triple>& ts) {
    std::set<std::int32_t> vs;
    for (const Triple& t : ts) vs.insert(t.begin(), t.end());
    return vs;
}

Problem checkVertices(const std::vector<Triple>& student, const std::vector<Triple>& ours,
                      const MeshGeometry& g, std::int32_t newVertex) {
    for (const Triple& t : student) {
        for (std::int32_t v : t) {
            if (g.known() && (v < 0 || static_cast<std::size_t>(v) >= g.points.size()))
                return verdict("triangle " + tripleText(t) + " uses vertex " + std::to_string(v) +
                               ", which does not exist");
        }
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
            return verdict("triangle " + tripleText(t) + " uses a vertex twice");
    }
    const auto mine = verticesOf(student), theirs = verticesOf(ours);
    if (newVertex >= 0 && theirs.count(newVertex) && !mine.count(newVertex))
        return verdict("point " + std::to_string(newVertex) +
                       " was not inserted: none of your triangles has it as a corner");
    for (std::int32_t v : mine) {
        if (!theirs.count(v))
            return verdict("vertex " + std::to_string(v) +
                           " is in your mesh but not in ours at this point (not inserted yet, a "
                           "duplicate, or a super-triangle vertex that Finalize drops)");
    }
    for (std::int32_t v : theirs) {
        if (!mine.count(v))
            return verdict("vertex " + std::to_string(v) + " is missing from your mesh");
    }
    return std::nullopt;
}

bool strictlyBetween(Vec2 a, Vec2 b, Vec2 p) {
    return orient2d(a, b, p) == 0 && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) &&
           std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y) && !(p == a) && !(p == b);
}

const char* kOnEdgeRule = "a point on an edge splits the two triangles beside it (2 -> 4)";

Problem checkOrientation(const std::vector<Triple>& student, const MeshGeometry& g,
                         std::int32_t newVertex) {
    for (const Triple& t : student) {
        if (g.isGhost(t[0]) || g.isGhost(t[1]) || g.isGhost(t[2])) continue;
        const Vec2 a = g.points[t[0]], b = g.points[t[1]], c = g.points[t[2]];
        const int o = orient2d(a, b, c);
        if (o > 0) continue;
        if (o < 0)
            return verdict("triangle " + tripleText(t) +
                           " is clockwise: list every triangle counter-clockwise (y up)");
        for (int k = 0; k < 3; ++k) {
            const std::int32_t v = t[k], x = t[(k + 1) % 3], y = t[(k + 2) % 3];
            if (v == newVertex && strictlyBetween(g.points[x], g.points[y], g.points[v]))
                return verdict("triangle " + tripleText(t) + " is flat: point " +
                               std::to_string(v) + " lies on edge " + edgeName(x, y) + "; " +
                               kOnEdgeRule);
        }
        return verdict("triangle " + tripleText(t) + " is flat: its three corners are on one line");
    }
    return std::nullopt;
}

// A directed edge of the student's with no triangle on its right, where ours has one.
Problem checkHoles(const Edges& mine, const Edges& ours, const MeshGeometry& g,
                   std::int32_t newVertex) {
    for (const auto& [e, t] : mine.left) {
        const Edge back{e.second, e.first};
        if (mine.left.count(back)) continue;
        const bool oursHasBoundaryHere = ours.left.count(e) && !ours.left.count(back);
        if (oursHasBoundaryHere) continue;
        if (g.known() && newVertex >= 0 && !g.isGhost(e.first) && !g.isGhost(e.second) &&
            !g.isGhost(newVertex) &&
            strictlyBetween(g.points[e.first], g.points[e.second], g.points[newVertex])) {
            return verdict("point " + std::to_string(newVertex) + " lies on edge " +
                           edgeName(e.first, e.second) + " of triangle " + tripleText(t) +
                           ", which was not split: " + kOnEdgeRule);
        }
        const auto theirs = ours.left.find(back);
        if (theirs != ours.left.end())
            return verdict("a triangle is missing beside edge " + edgeName(e.first, e.second) +
                           ": ours has " + tripleText(theirs->second) + " there");
        return verdict("your mesh has a hole beside edge " + edgeName(e.first, e.second));
    }
    return std::nullopt;
}

struct Violation {
    std::int32_t a, b, c, d;  // edge a-b, triangles (a, b, c) and (b, a, d); d inside abc's circle
};

std::vector<Violation> nonDelaunayEdges(const Edges& mine, const MeshGeometry& g) {
    std::vector<Violation> out;
    for (const auto& [e, t] : mine.left) {
        if (e.first > e.second) continue;
        const auto other = mine.left.find({e.second, e.first});
        if (other == mine.left.end()) continue;
        const std::int32_t a = e.first, b = e.second, c = third(t, a, b),
                           d = third(other->second, a, b);
        if (g.isGhost(a) || g.isGhost(b) || g.isGhost(c) || g.isGhost(d)) continue;
        if (incircle(g.points[a], g.points[b], g.points[c], g.points[d]) > 0)
            out.push_back({a, b, c, d});
    }
    return out;
}

bool hasEdge(const Edges& e, std::int32_t a, std::int32_t b) {
    return e.left.count({a, b}) || e.left.count({b, a});
}

std::string insideText(const Violation& v) {
    return "vertex " + std::to_string(v.d) + " is inside the circle of " + std::to_string(v.a) +
           " " + std::to_string(v.b) + " " + std::to_string(v.c);
}

Problem checkDelaunay(const Edges& mine, const Edges& ours, const MeshGeometry& g,
                      std::int32_t newVertex, const std::vector<FlipMade>& flips) {
    const std::vector<Violation> bad = nonDelaunayEdges(mine, g);
    if (bad.empty()) return std::nullopt;
    // A flip the student made that ours did not: the edge it removed was Delaunay.
    for (const FlipMade& f : flips) {
        for (const Violation& v : bad) {
            const bool made = std::min(v.a, v.b) == std::min(f.added[0], f.added[1]) &&
                              std::max(v.a, v.b) == std::max(f.added[0], f.added[1]);
            if (made && hasEdge(ours, f.removed[0], f.removed[1])) {
                MeshVerdict out = verdict("flip of edge " + edgeName(f.removed[0], f.removed[1]) +
                                          ", which is Delaunay (it should stay): at the new edge " +
                                          edgeName(v.a, v.b) + ", " + insideText(v));
                return out;
            }
        }
    }
    const Violation* pick = &bad.front();
    for (const Violation& v : bad) {
        if (hasEdge(ours, v.c, v.d)) {
            pick = &v;
            break;
        }
    }
    const Violation& v = *pick;
    std::string reason = "not Delaunay at edge " + edgeName(v.a, v.b) + ": " + insideText(v);
    if (hasEdge(ours, v.c, v.d))
        reason += "; missing flip of edge " + edgeName(v.a, v.b) + " (expected " +
                  edgeName(v.c, v.d) + ")";
    MeshVerdict out = verdict(reason);
    const bool facesNewPoint = v.c == newVertex || v.d == newVertex;
    for (const FlipMade& f : flips) {
        const std::int32_t x = f.removed[0], y = f.removed[1], p = f.added[0], q = f.added[1];
        const Edge outer[4] = {{x, p}, {p, y}, {y, q}, {q, x}};
        for (const Edge& o : outer) {
            if (facesNewPoint && std::min(o.first, o.second) == std::min(v.a, v.b) &&
                std::max(o.first, o.second) == std::max(v.a, v.b)) {
                out.details.push_back("edge " + edgeName(v.a, v.b) +
                                      " came to face the new point when edge " + edgeName(x, y) +
                                      " was flipped to " + edgeName(p, q) +
                                      ": after a flip, push both edges opposite the new point");
                return out;
            }
        }
    }
    if (bad.size() > 1)
        out.details.push_back(std::to_string(bad.size()) + " edges of your mesh are not Delaunay");
    return out;
}

std::vector<Triple> minus(const std::vector<Triple>& a, const std::vector<Triple>& b) {
    std::vector<Triple> out;
    std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
    return out;
}

}  // namespace

std::optional<MeshVerdict> checkFlipMade(const FlipMade& f, const MeshGeometry& g,
                                         std::int32_t newVertex) {
    const std::int32_t a = f.removed[0], b = f.removed[1];
    // q is the point tested against the circle of (a, b, p), the triangle across the edge.
    std::int32_t p = f.added[0], q = f.added[1];
    if (p == newVertex) std::swap(p, q);
    for (std::int32_t v : {a, b, p, q}) {
        if (!g.known() || v < 0 || static_cast<std::size_t>(v) >= g.points.size() || g.isGhost(v))
            return std::nullopt;
    }
    const int o = orient2d(g.points[a], g.points[b], g.points[p]);
    if (o == 0) return std::nullopt;
    const Triple across = o > 0 ? canonical(a, b, p) : canonical(b, a, p);
    const Triple near = o > 0 ? canonical(b, a, q) : canonical(a, b, q);
    const int s =
        incircle(g.points[across[0]], g.points[across[1]], g.points[across[2]], g.points[q]);
    if (s > 0) return std::nullopt;
    MeshVerdict v = verdict(
        "flip of edge " + edgeName(a, b) + ", which was Delaunay (it should stay): point " +
        std::to_string(q) + " is " + (s < 0 ? "outside" : "on") + " the circle of triangle " +
        tripleText(across) + ", across the edge from triangle " + tripleText(near));
    v.details.push_back(
        "the flip replaced edge " + edgeName(a, b) + " by " + edgeName(p, q) +
        (s < 0 ? ": flip only when the point is strictly inside the circle (check the sign of "
                 "your in-circle test)"
               : ": with four points on one circle, flip only when the point is strictly "
                 "inside"));
    return v;
}

MeshVerdict checkStudentMesh(const std::vector<Triple>& student, const std::vector<Triple>& ours,
                             const MeshGeometry& g, std::int32_t newVertex,
                             const std::vector<FlipMade>& flips,
                             const std::optional<MeshVerdict>& wrongFlip) {
    if (student == ours) return {};
    Problem p = checkVertices(student, ours, g, newVertex);
    if (!p && wrongFlip) p = *wrongFlip;
    if (!p && g.known()) p = checkOrientation(student, g, newVertex);
    const Edges mine = edgesOf(student), theirs = edgesOf(ours);
    if (!p && mine.overlap) p = *mine.overlap;
    if (!p) p = checkHoles(mine, theirs, g, newVertex);
    if (!p && g.known()) p = checkDelaunay(mine, theirs, g, newVertex, flips);
    if (!p) {
        p = verdict(
            "your triangles differ from ours, though your mesh is a Delaunay "
            "triangulation: with four points on one circle, flip only when the point is "
            "strictly inside");
        if (!g.known()) p->reason = "your triangles differ from ours";
    }
    p->details.push_back("triangles only in ours:  " + triplesText(minus(ours, student)));
    p->details.push_back("triangles only in yours: " + triplesText(minus(student, ours)));
    return *p;
}

}  // namespace dlab
