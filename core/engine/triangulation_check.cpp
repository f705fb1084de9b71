// The exact mesh checker (triangles, edges, O, points, coverage, Delaunay) and Lawson's repair.
//
// [SECTION] Names and the report
// [SECTION] Triangles, edges and O
// [SECTION] Points and the convex hull
// [SECTION] Coverage: outline, holes, overlaps
// [SECTION] Delaunay
// [SECTION] Lawson's flips
#include "core/engine/triangulation_check.h"

#include "core/engine/predicates.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>

namespace dlab {

//-----------------------------------------------------------------------------------------------
// [SECTION] Names and the report
//-----------------------------------------------------------------------------------------------

using Kind = MeshProblem::Kind;

const char* toString(Kind kind) {
    switch (kind) {
        case Kind::VertexRange: return "vertex-out-of-range";
        case Kind::RepeatedVertex: return "repeated-vertex";
        case Kind::FlatTriangle: return "flat-triangle";
        case Kind::ClockwiseTriangle: return "clockwise-triangle";
        case Kind::OppositeRange: return "opposite-out-of-range";
        case Kind::OppositeNotInvolution: return "opposite-not-involution";
        case Kind::OppositeWrongEdge: return "opposite-wrong-edge";
        case Kind::EdgeInManyTriangles: return "edge-in-many-triangles";
        case Kind::Overlap: return "overlap";
        case Kind::Hole: return "hole";
        case Kind::NonConvexOutline: return "non-convex-outline";
        case Kind::DuplicatePoint: return "duplicate-point";
        case Kind::UnusedPoint: return "unused-point";
        case Kind::UnusedDuplicate: return "unused-duplicate";
        case Kind::NotDelaunay: return "not-delaunay";
    }
    return "unknown";
}

bool blocksRepair(Kind kind) {
    return kind != Kind::UnusedPoint && kind != Kind::UnusedDuplicate && kind != Kind::NotDelaunay;
}

std::size_t CheckReport::count(Kind kind) const {
    return static_cast<std::size_t>(std::count_if(
        problems.begin(), problems.end(), [&](const MeshProblem& p) { return p.kind == kind; }));
}

bool CheckReport::isTriangulation() const {
    return std::none_of(problems.begin(), problems.end(),
                        [](const MeshProblem& p) { return blocksRepair(p.kind); });
}

bool CheckReport::isDelaunay() const {
    return std::all_of(problems.begin(), problems.end(),
                       [](const MeshProblem& p) { return p.kind == Kind::UnusedDuplicate; });
}

namespace {

// "3 holes", "1 clockwise triangle": a count of one kind in words.
std::string countWords(std::size_t n, Kind kind) {
    static const std::map<Kind, std::array<const char*, 2>> kWords = {
        {Kind::VertexRange, {"vertex id out of range", "vertex ids out of range"}},
        {Kind::RepeatedVertex, {"triangle repeating a vertex", "triangles repeating a vertex"}},
        {Kind::FlatTriangle, {"flat triangle", "flat triangles"}},
        {Kind::ClockwiseTriangle, {"clockwise triangle", "clockwise triangles"}},
        {Kind::OppositeRange, {"O out of range", "O entries out of range"}},
        {Kind::OppositeNotInvolution, {"O not an involution", "O entries not an involution"}},
        {Kind::OppositeWrongEdge, {"O on the wrong edge", "O entries on the wrong edge"}},
        {Kind::EdgeInManyTriangles, {"edge in 3+ triangles", "edges in 3+ triangles"}},
        {Kind::Overlap, {"overlap", "overlaps"}},
        {Kind::Hole, {"hole", "holes"}},
        {Kind::NonConvexOutline, {"non-convex outline", "non-convex outlines"}},
        {Kind::DuplicatePoint, {"duplicate point", "duplicate points"}},
        {Kind::UnusedPoint, {"unused point", "unused points"}},
        {Kind::UnusedDuplicate, {"unused duplicate", "unused duplicates"}},
        {Kind::NotDelaunay, {"edge not Delaunay", "edges not Delaunay"}},
    };
    return std::to_string(n) + " " + kWords.at(kind)[n == 1 ? 0 : 1];
}

}  // namespace

std::string CheckReport::summary() const {
    std::string counts;
    for (int k = 0; k <= static_cast<int>(Kind::NotDelaunay); ++k) {
        const auto kind = static_cast<Kind>(k);
        const std::size_t n = count(kind);
        if (n == 0 || kind == Kind::UnusedDuplicate) continue;
        counts += (counts.empty() ? "" : ", ") + countWords(n, kind);
    }
    const std::string of =
        " of " + std::to_string(points) + " points (" + std::to_string(triangles) + " triangles)";
    std::string out;
    if (isDelaunay())
        out = "valid Delaunay triangulation" + of;
    else if (isTriangulation())
        out = "valid triangulation" + of + ", " + counts;
    else
        out = "not a valid triangulation" + of + ": " + counts;
    if (const std::size_t d = count(Kind::UnusedDuplicate))
        out += "; " + std::to_string(d) + (d == 1 ? " duplicate point" : " duplicate points") +
               " left out (the first copy is the vertex)";
    return out;
}

namespace {

//-----------------------------------------------------------------------------------------------
// [SECTION] Triangles, edges and O
//-----------------------------------------------------------------------------------------------

enum class TriState : std::uint8_t { Good, Flat, Clockwise, Broken };

class Checker {
public:
    Checker(const Mesh& m, const CheckOptions& o) : m_m(m), m_o(o) {}

    CheckReport run() {
        m_r.points = m_m.numVertices();
        m_r.triangles = m_m.numTriangles();
        checkTriangles();
        // A given O that pairs every shared edge consistently is the adjacency (the coverage
        // test below proves that no other triangle has those edges); else the edges are sorted.
        m_fast = m_o.hasOpposites && m_good && oppositesConsistent();
        if (m_fast) {
            m_r.opposites = m_m.O;
            for (std::int32_t c = 0; c < m_m.numCorners(); ++c)
                if (m_m.O[c] == kNone) m_boundary.push_back(c);
        } else {
            sortEdges();
        }
        checkPoints();
        checkCoverage();
        checkDelaunay();
        std::stable_sort(
            m_r.problems.begin(), m_r.problems.end(),
            [](const MeshProblem& a, const MeshProblem& b) { return a.kind < b.kind; });
        return std::move(m_r);
    }

private:
    std::string vid(std::int32_t v) const {
        return std::to_string(std::int64_t{v} + m_o.indexBase);
    }
    std::string tid(std::int32_t t) const {
        return "triangle " + std::to_string(std::int64_t{t} + m_o.indexBase);
    }
    std::string edge(std::int32_t a, std::int32_t b) const {
        return "edge " + vid(a) + "-" + vid(b);
    }
    std::string triVerts(std::int32_t t) const {
        return tid(t) + " (" + vid(m_m.V[3 * t]) + ", " + vid(m_m.V[3 * t + 1]) + ", " +
               vid(m_m.V[3 * t + 2]) + ")";
    }
    void add(Kind kind, std::vector<std::int32_t> tris, std::vector<std::int32_t> verts,
             std::vector<std::int32_t> corners, std::string message) {
        m_r.problems.push_back(
            {kind, std::move(tris), std::move(verts), std::move(corners), std::move(message)});
    }
    bool inRange(std::int32_t v) const { return v >= 0 && v < m_m.numVertices(); }
    Vec2 g(std::int32_t c) const { return m_m.G[m_m.V[c]]; }

    void checkTriangle(std::int32_t t) {
        const std::int32_t c = 3 * t;
        for (std::int32_t k = 0; k < 3; ++k) {
            if (inRange(m_m.V[c + k])) continue;
            add(Kind::VertexRange, {t}, {}, {c + k},
                tid(t) + ": vertex " + vid(m_m.V[c + k]) + " does not exist (the points are " +
                    vid(0) + " to " + vid(m_m.numVertices() - 1) + ")");
            m_state[t] = TriState::Broken;
        }
        if (m_state[t] == TriState::Broken) return;
        const std::int32_t a = m_m.V[c], b = m_m.V[c + 1], d = m_m.V[c + 2];
        if (a == b || b == d || a == d) {
            add(Kind::RepeatedVertex, {t}, {a == b ? a : d}, {}, triVerts(t) + " repeats a vertex");
            m_state[t] = TriState::Broken;
            return;
        }
        const int o = orient2d(m_m.G[a], m_m.G[b], m_m.G[d]);
        if (o > 0) return;
        m_state[t] = o == 0 ? TriState::Flat : TriState::Clockwise;
        add(o == 0 ? Kind::FlatTriangle : Kind::ClockwiseTriangle, {t}, {a, b, d}, {},
            triVerts(t) + (o == 0 ? " is flat: its vertices are collinear"
                                  : " is clockwise (y up): its corners must turn left"));
    }

    void checkTriangles() {
        m_state.assign(static_cast<std::size_t>(m_m.numTriangles()), TriState::Good);
        for (std::int32_t t = 0; t < m_m.numTriangles(); ++t) checkTriangle(t);
        m_good = std::all_of(m_state.begin(), m_state.end(),
                             [](TriState s) { return s == TriState::Good; });
    }

    // The corners grouped by the edge they face: a bucket sort by the lower vertex (read in
    // corner order), then a sort of each small, contiguous bucket by the higher one.
    struct EdgeRef {
        std::int32_t hi, corner;
    };
    std::vector<EdgeRef> cornersByEdge(std::vector<std::int32_t>& start) const {
        const Mesh& m = m_m;
        start.assign(static_cast<std::size_t>(m.numVertices()) + 1, 0);
        for (std::int32_t c = 0; c < m.numCorners(); ++c)
            if (m_state[tri(c)] != TriState::Broken)
                ++start[std::min(m.V[next(c)], m.V[prev(c)]) + 1];
        std::partial_sum(start.begin(), start.end(), start.begin());
        std::vector<EdgeRef> out(static_cast<std::size_t>(start.back()));
        std::vector<std::int32_t> fill(start.begin(), start.end() - 1);
        for (std::int32_t c = 0; c < m.numCorners(); ++c) {
            if (m_state[tri(c)] == TriState::Broken) continue;
            const std::int32_t a = m.V[next(c)], b = m.V[prev(c)];
            out[fill[std::min(a, b)]++] = {std::max(a, b), c};
        }
        for (std::size_t v = 0; v + 1 < start.size(); ++v)
            std::sort(out.begin() + start[v], out.begin() + start[v + 1],
                      [](const EdgeRef& x, const EdgeRef& y) { return x.hi < y.hi; });
        return out;
    }

    void pairEdge(const std::int32_t* run, std::size_t n) {
        const Mesh& m = m_m;
        const std::int32_t c = run[0];
        if (n == 1) {
            m_boundary.push_back(c);
            return;
        }
        const std::int32_t a = m.V[next(c)], b = m.V[prev(c)];
        if (n >= 3) {
            std::vector<std::int32_t> tris;
            for (std::size_t k = 0; k < n; ++k) tris.push_back(tri(run[k]));
            std::string names;
            for (const std::int32_t t : tris) names += (names.empty() ? "" : ", ") + tid(t);
            add(Kind::EdgeInManyTriangles, tris, {a, b}, {},
                edge(a, b) + " is in " + std::to_string(n) + " triangles: " + names);
            m_edgesBroken = true;
            return;
        }
        const std::int32_t d = run[1];
        if (m.V[next(d)] == b) {  // opposite directions: the edge between two neighbours
            m_r.opposites[c] = d;
            m_r.opposites[d] = c;
        } else if (m_state[tri(c)] == TriState::Good && m_state[tri(d)] == TriState::Good) {
            m_sameSide.push_back({tri(c), tri(d)});
        }
    }

    void groupEdges() {
        m_r.opposites.assign(m_m.V.size(), kNone);
        std::vector<std::int32_t> start;
        const std::vector<EdgeRef> order = cornersByEdge(start);
        std::vector<std::int32_t> run;
        for (std::size_t v = 0; v + 1 < start.size(); ++v) {
            const auto end = static_cast<std::size_t>(start[v + 1]);
            for (auto i = static_cast<std::size_t>(start[v]); i < end;) {
                run.clear();
                std::size_t j = i;
                for (; j < end && order[j].hi == order[i].hi; ++j) run.push_back(order[j].corner);
                pairEdge(run.data(), run.size());
                i = j;
            }
        }
    }

    void checkOpposite(std::int32_t c) {
        const Mesh& m = m_m;
        const std::int32_t o = m.O[c], computed = m_r.opposites[c];
        const std::int32_t a = m.V[next(c)], b = m.V[prev(c)];
        if (o != kNone && o == computed && m.O[o] == c) return;  // the pair the triangles make
        const std::string cs = "corner " + std::to_string(c) + " of " + tid(tri(c));
        if (o == kNone) {
            if (computed != kNone)
                add(Kind::OppositeWrongEdge, {tri(c), tri(computed)}, {a, b}, {c, computed},
                    cs + ": O = -1 but its " + edge(a, b) + " is shared with " +
                        tid(tri(computed)) + " (corner " + std::to_string(computed) + ")");
            return;
        }
        if (o < 0 || o >= m.numCorners()) {
            add(Kind::OppositeRange, {tri(c)}, {}, {c},
                cs + ": O = " + std::to_string(o) + " is not a corner (there are " +
                    std::to_string(m.numCorners()) + ")");
            return;
        }
        if (m.O[o] != c)
            add(Kind::OppositeNotInvolution, {tri(c), tri(o)}, {}, {c, o},
                cs + ": O = " + std::to_string(o) + " but O[" + std::to_string(o) +
                    "] = " + std::to_string(m.O[o]));
        if (tri(o) == tri(c) || m.V[prev(o)] != a || m.V[next(o)] != b)
            add(Kind::OppositeWrongEdge, {tri(c), tri(o)}, {a, b}, {c, o},
                cs + ": O = " + std::to_string(o) + " lies in " + triVerts(tri(o)) +
                    ", which does not run its " + edge(a, b) + " the other way");
    }

    void checkOpposites() {
        if (m_m.O.size() != m_m.V.size()) return;  // the readers never give such a mesh
        for (std::int32_t c = 0; c < m_m.numCorners(); ++c)
            if (m_state[tri(c)] != TriState::Broken) checkOpposite(c);
    }

    //-------------------------------------------------------------------------------------------
    // [SECTION] Points and the convex hull
    //-------------------------------------------------------------------------------------------

    void checkDuplicateGroup(const std::int32_t* group, std::size_t n) {
        std::vector<std::int32_t> used;
        for (std::size_t k = 0; k < n; ++k)
            if (m_used[group[k]]) used.push_back(group[k]);
        if (used.size() >= 2) {
            std::string names;
            for (const std::int32_t v : used) names += (names.empty() ? "" : ", ") + vid(v);
            add(Kind::DuplicatePoint, {}, used, {},
                "vertices " + names + " are the same point, and triangles use each of them");
        }
        const std::int32_t first = used.empty() ? group[0] : used[0];
        for (std::size_t k = 0; k < n; ++k) {
            const std::int32_t v = group[k];
            if (m_used[v] || v == first) continue;
            add(Kind::UnusedDuplicate, {}, {v, first}, {},
                "point " + vid(v) + " is point " + vid(first) + " again (unused, as it should be)");
        }
        if (used.empty())
            add(Kind::UnusedPoint, {}, {first}, {}, "point " + vid(first) + " is in no triangle");
    }

    void checkPoints() {
        const Mesh& m = m_m;
        m_used.assign(static_cast<std::size_t>(m.numVertices()), 0);
        for (std::int32_t c = 0; c < m.numCorners(); ++c)
            if (m_state[tri(c)] != TriState::Broken) m_used[m.V[c]] = 1;
        struct At {
            Vec2 p;
            std::int32_t v;
        };
        std::vector<At> at(static_cast<std::size_t>(m.numVertices()));
        for (std::int32_t v = 0; v < m.numVertices(); ++v) at[v] = {m.G[v], v};
        std::sort(at.begin(), at.end(), [](const At& a, const At& b) {
            return a.p.x < b.p.x ||
                   (a.p.x == b.p.x && (a.p.y < b.p.y || (a.p.y == b.p.y && a.v < b.v)));
        });
        m_sorted.resize(at.size());
        for (std::size_t i = 0; i < at.size(); ++i) m_sorted[i] = at[i].v;
        for (std::size_t i = 0; i < m_sorted.size();) {
            std::size_t j = i + 1;
            while (j < m_sorted.size() && m.G[m_sorted[j]] == m.G[m_sorted[i]]) ++j;
            if (j - i > 1 || !m_used[m_sorted[i]]) checkDuplicateGroup(m_sorted.data() + i, j - i);
            i = j;
        }
        m_r.usedPoints = static_cast<std::int32_t>(std::count(m_used.begin(), m_used.end(), 1));
    }

    // The convex hull of the used vertices, counter-clockwise, collinear points on its edges
    // included (Andrew's monotone chain, popping only on a right turn).
    std::vector<std::int32_t> hull() const {
        std::vector<std::int32_t> pts;
        for (const std::int32_t v : m_sorted)
            if (m_used[v] && (pts.empty() || !(m_m.G[pts.back()] == m_m.G[v]))) pts.push_back(v);
        if (pts.size() < 3) return pts;
        std::vector<std::int32_t> h;
        const auto chain = [&](auto first, auto last) {
            const std::size_t base = h.size();
            for (auto it = first; it != last; ++it) {
                while (h.size() >= base + 2 &&
                       orient2d(m_m.G[h[h.size() - 2]], m_m.G[h.back()], m_m.G[*it]) < 0)
                    h.pop_back();
                h.push_back(*it);
            }
            h.pop_back();  // the next chain starts there
        };
        chain(pts.begin(), pts.end());
        chain(pts.rbegin(), pts.rend());
        return h;
    }

    //-------------------------------------------------------------------------------------------
    // [SECTION] Coverage: outline, holes, overlaps
    //-------------------------------------------------------------------------------------------

    // Boundary edges leaving each vertex (a CSR list of corners, the edge V[n(c)] -> V[p(c)]).
    void indexBoundary() {
        m_outStart.assign(static_cast<std::size_t>(m_m.numVertices()) + 1, 0);
        for (const std::int32_t c : m_boundary) ++m_outStart[m_m.V[next(c)] + 1];
        std::partial_sum(m_outStart.begin(), m_outStart.end(), m_outStart.begin());
        m_out.resize(m_boundary.size());
        std::vector<std::int32_t> fill(m_outStart.begin(), m_outStart.end() - 1);
        for (const std::int32_t c : m_boundary) m_out[fill[m_m.V[next(c)]]++] = c;
    }

    std::int32_t boundaryEdge(std::int32_t a, std::int32_t b) const {
        for (std::int32_t k = m_outStart[a]; k < m_outStart[a + 1]; ++k)
            if (m_m.V[prev(m_out[k])] == b) return m_out[k];
        return kNone;
    }

    // Every O in range, an involution across two triangles that run the edge both ways.
    bool oppositesConsistent() const {
        const Mesh& m = m_m;
        for (std::int32_t c = 0; c < m.numCorners(); ++c) {
            const std::int32_t o = m.O[c];
            if (o == kNone) continue;
            if (o < 0 || o >= m.numCorners() || tri(o) == tri(c) || m.O[o] != c ||
                m.V[prev(o)] != m.V[next(c)] || m.V[next(o)] != m.V[prev(c)])
                return false;
        }
        return true;
    }

    void sortEdges() {
        groupEdges();
        if (m_o.hasOpposites) checkOpposites();
    }

    // The boundary edges are the hull's, no two triangles on one side of an edge, Euler's count.
    bool covered(const std::vector<std::int32_t>& h) {
        indexBoundary();
        m_outlineIsHull = m_boundary.size() == h.size();
        for (std::size_t i = 0; i < h.size() && m_outlineIsHull; ++i)
            m_outlineIsHull = boundaryEdge(h[i], h[(i + 1) % h.size()]) != kNone;
        const std::int64_t euler = 2 * std::int64_t{m_r.usedPoints} - std::int64_t(h.size()) - 2;
        return m_outlineIsHull && m_sameSide.empty() && euler == m_m.numTriangles();
    }

    void checkCoverage() {
        if (!m_good || m_edgesBroken || m_m.numTriangles() == 0) {
            std::vector<std::int32_t> h;
            if (m_m.numTriangles() == 0 && (h = hull()).size() >= 3)
                add(Kind::Hole, {}, h, {}, "no triangles: the points' hull is not covered");
            return;
        }
        const std::vector<std::int32_t> h = hull();
        if (covered(h)) return;
        if (m_fast) {  // name what is wrong from the triangles themselves
            m_fast = false;
            m_boundary.clear();
            sortEdges();
            if (m_edgesBroken || covered(h)) return;
        }
        const bool outlineIsHull = m_outlineIsHull;
        const std::int64_t euler = 2 * std::int64_t{m_r.usedPoints} - std::int64_t(h.size()) - 2;
        findOverlaps();
        if (!outlineIsHull) traceOutline(h);
        if (outlineIsHull && m_r.count(Kind::Overlap) == 0 && !m_r.overlapSearchCut)
            add(Kind::Overlap, {}, {}, {},
                "the triangles cover part of their hull more than once: " +
                    std::to_string(m_m.numTriangles()) + " triangles where a triangulation of " +
                    std::to_string(m_r.usedPoints) + " points with " + std::to_string(h.size()) +
                    " on the hull has " + std::to_string(euler));
    }

    // The boundary loops: clockwise ones bound holes; counter-clockwise ones are outlines,
    // which must turn left everywhere and run along the hull's edges.
    void traceOutline(const std::vector<std::int32_t>& h) {
        std::vector<char> seen(m_m.V.size(), 0);
        for (const std::int32_t start : m_boundary) {
            if (seen[start]) continue;
            std::vector<std::int32_t> loop;  // the vertices, in order
            std::vector<std::int32_t> tris;
            for (std::int32_t c = start; c != kNone && !seen[c];) {
                seen[c] = 1;
                loop.push_back(m_m.V[next(c)]);
                tris.push_back(tri(c));
                const std::int32_t b = m_m.V[prev(c)];
                std::int32_t nextEdge = kNone;
                for (std::int32_t k = m_outStart[b]; k < m_outStart[b + 1]; ++k)
                    if (!seen[m_out[k]]) nextEdge = m_out[k];
                c = nextEdge;
            }
            reportLoop(loop, tris);
        }
        for (std::size_t i = 0; i < h.size(); ++i) {
            const std::int32_t a = h[i], b = h[(i + 1) % h.size()];
            if (boundaryEdge(a, b) == kNone && !m_overlapping.count(a))
                add(Kind::Hole, {}, {a, b}, {},
                    "the convex hull's " + edge(a, b) + " is not covered: no triangle has it");
        }
    }

    std::string loopNames(const std::vector<std::int32_t>& loop) const {
        std::string names;
        for (std::size_t i = 0; i < loop.size() && i < 12; ++i)
            names += (i ? ", " : "") + vid(loop[i]);
        return names + (loop.size() > 12 ? ", ..." : "");
    }

    void reportLoop(const std::vector<std::int32_t>& loop, const std::vector<std::int32_t>& tris) {
        const std::size_t n = loop.size();
        const auto at = [&](std::size_t i) { return m_m.G[loop[(i + n) % n]]; };
        std::size_t low = 0;  // the lowest, then leftmost vertex: a convex corner of the loop
        for (std::size_t i = 1; i < n; ++i)
            if (at(i).y < at(low).y || (at(i).y == at(low).y && at(i).x < at(low).x)) low = i;
        if (orient2d(at(low - 1), at(low), at(low + 1)) < 0) {
            add(Kind::Hole, tris, loop, {}, "a hole bounded by vertices " + loopNames(loop));
            return;
        }
        std::vector<std::int32_t> reflex;
        for (std::size_t i = 0; i < n; ++i)
            if (orient2d(at(i - 1), at(i), at(i + 1)) < 0) reflex.push_back(loop[i]);
        const bool overlapping = std::any_of(tris.begin(), tris.end(), [&](std::int32_t t) {
            return m_overlappingTris.count(t) != 0;
        });
        if (!reflex.empty())
            add(Kind::NonConvexOutline, tris, reflex, {},
                "the outline turns right at " +
                    std::string(reflex.size() == 1 ? "vertex " : "vertices ") + loopNames(reflex));
        else if (!overlapping && n != 0 && m_outlines++ > 0)
            add(Kind::Hole, tris, loop, {},
                "a separate piece, outlined by vertices " + loopNames(loop) +
                    ": the hull between the pieces is not covered");
    }

    // Do the interiors of two counter-clockwise triangles intersect? Not when an edge of one
    // has the whole other triangle on its outer side (exact: the separating-axis test).
    bool overlap(std::int32_t s, std::int32_t t) const {
        const auto separates = [&](std::int32_t x, std::int32_t y) {
            for (std::int32_t k = 0; k < 3; ++k) {
                const Vec2 a = g(3 * x + k), b = g(3 * x + (k + 1) % 3);
                if (orient2d(a, b, g(3 * y)) <= 0 && orient2d(a, b, g(3 * y + 1)) <= 0 &&
                    orient2d(a, b, g(3 * y + 2)) <= 0)
                    return true;
            }
            return false;
        };
        return !separates(s, t) && !separates(t, s);
    }

    void reportOverlap(std::int32_t s, std::int32_t t) {
        if (!m_pairs.insert({std::min(s, t), std::max(s, t)}).second) return;
        m_overlappingTris.insert(s);
        m_overlappingTris.insert(t);
        for (std::int32_t k = 0; k < 3; ++k) {
            m_overlapping.insert(m_m.V[3 * s + k]);
            m_overlapping.insert(m_m.V[3 * t + k]);
        }
        add(Kind::Overlap, {s, t}, {}, {}, triVerts(s) + " and " + triVerts(t) + " overlap");
    }

    struct Box {
        int cx0, cy0, cx1, cy1;
    };
    void findOverlaps();
    std::vector<Box> boxes();
    void checkDelaunay();

    const Mesh& m_m;
    const CheckOptions& m_o;
    CheckReport m_r;
    std::vector<TriState> m_state;
    bool m_good = true, m_edgesBroken = false, m_fast = false, m_outlineIsHull = false;
    std::vector<std::int32_t> m_boundary;  // corners facing an edge of one triangle
    std::vector<std::array<std::int32_t, 2>> m_sameSide;
    std::vector<char> m_used;
    std::vector<std::int32_t> m_sorted;  // vertices by x, then y
    std::vector<std::int32_t> m_outStart, m_out;
    std::set<std::pair<std::int32_t, std::int32_t>> m_pairs;
    std::set<std::int32_t> m_overlappingTris, m_overlapping;
    int m_outlines = 0;
    int m_side = 1;
};

// The overlapping pairs: triangles binned in a grid of about T cells by their bounding boxes,
// each pair that shares a cell tested once (in the first cell both boxes cover), exactly.
void Checker::findOverlaps() {
    for (const auto& st : m_sameSide) reportOverlap(st[0], st[1]);
    const std::vector<Box> box = boxes();
    const std::size_t cells = static_cast<std::size_t>(m_side) * m_side;
    std::vector<std::size_t> start(cells + 1, 0);
    for (const Box& b : box)
        for (int y = b.cy0; y <= b.cy1; ++y)
            for (int x = b.cx0; x <= b.cx1; ++x) ++start[std::size_t(y) * m_side + x + 1];
    std::partial_sum(start.begin(), start.end(), start.begin());
    if (start.back() > std::size_t{1} << 26) {  // huge boxes: too many entries to hold
        m_r.overlapSearchCut = true;
        return;
    }
    std::vector<std::int32_t> in(start.back());
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::int32_t t = 0; t < static_cast<std::int32_t>(box.size()); ++t)
        for (int y = box[t].cy0; y <= box[t].cy1; ++y)
            for (int x = box[t].cx0; x <= box[t].cx1; ++x)
                in[fill[std::size_t(y) * m_side + x]++] = t;
    std::size_t tests = 0;
    for (std::size_t c = 0; c < cells; ++c) {
        const int cx = static_cast<int>(c % m_side), cy = static_cast<int>(c / m_side);
        for (std::size_t i = start[c]; i < start[c + 1]; ++i)
            for (std::size_t j = i + 1; j < start[c + 1]; ++j) {
                const Box &a = box[in[i]], &b = box[in[j]];
                if (std::max(a.cx0, b.cx0) != cx || std::max(a.cy0, b.cy0) != cy) continue;
                if (++tests > m_o.maxOverlapTests) {
                    m_r.overlapSearchCut = true;
                    return;
                }
                if (overlap(in[i], in[j])) reportOverlap(in[i], in[j]);
            }
    }
}

// Each triangle's range of cells in a grid of about T cells over the vertices' bounding box.
std::vector<Checker::Box> Checker::boxes() {
    const std::int32_t nt = m_m.numTriangles();
    double x0 = m_m.G[m_m.V[0]].x, x1 = x0, y0 = m_m.G[m_m.V[0]].y, y1 = y0;
    for (const std::int32_t v : m_m.V) {
        x0 = std::min(x0, m_m.G[v].x), x1 = std::max(x1, m_m.G[v].x);
        y0 = std::min(y0, m_m.G[v].y), y1 = std::max(y1, m_m.G[v].y);
    }
    m_side = std::clamp(static_cast<int>(std::sqrt(double(nt))), 1, 2048);
    const auto cell = [&](double v, double lo, double hi) {  // binning only, no decision
        const double f = (v / 2 - lo / 2) / (hi / 2 - lo / 2) * m_side;
        return std::isfinite(f) ? std::clamp(static_cast<int>(f), 0, m_side - 1) : 0;
    };
    std::vector<Box> box(static_cast<std::size_t>(nt));
    for (std::int32_t t = 0; t < nt; ++t) {
        Box b{m_side, m_side, -1, -1};
        for (std::int32_t k = 0; k < 3; ++k) {
            const Vec2 p = g(3 * t + k);
            b.cx0 = std::min(b.cx0, cell(p.x, x0, x1)), b.cx1 = std::max(b.cx1, cell(p.x, x0, x1));
            b.cy0 = std::min(b.cy0, cell(p.y, y0, y1)), b.cy1 = std::max(b.cy1, cell(p.y, y0, y1));
        }
        box[t] = b;
    }
    return box;
}

//-----------------------------------------------------------------------------------------------
// [SECTION] Delaunay
//-----------------------------------------------------------------------------------------------

void Checker::checkDelaunay() {
    const Mesh& m = m_m;
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        const std::int32_t d = m_r.opposites[c];
        if (d < c || m_state[tri(c)] != TriState::Good || m_state[tri(d)] != TriState::Good)
            continue;
        const std::int32_t t = tri(c);
        if (incircle(g(3 * t), g(3 * t + 1), g(3 * t + 2), g(d)) <= 0) continue;
        const std::int32_t a = m.V[next(c)], b = m.V[prev(c)];
        add(Kind::NotDelaunay, {t, tri(d)}, {a, b, m.V[d]}, {c, d},
            edge(a, b) + " (" + tid(t) + " and " + tid(tri(d)) + "): vertex " + vid(m.V[d]) +
                " lies inside the circle through " + vid(m.V[3 * t]) + ", " + vid(m.V[3 * t + 1]) +
                ", " + vid(m.V[3 * t + 2]));
    }
}

}  // namespace

CheckReport checkMesh(const Mesh& mesh, const CheckOptions& options) {
    if (mesh.V.size() % 3 != 0 || mesh.O.size() != mesh.V.size())
        throw std::invalid_argument("checkMesh: |V| must be a multiple of 3 and |O| = |V|");
    return Checker(mesh, options).run();
}

//-----------------------------------------------------------------------------------------------
// [SECTION] Lawson's flips
//-----------------------------------------------------------------------------------------------

namespace {

void link(Mesh& m, std::int32_t a, std::int32_t b) {
    m.O[a] = b;
    if (b != kNone) m.O[b] = a;
}

// The edge opposite c, shared with d = O[c], replaced by the edge V[c]-V[d]; the same cell
// changes as the inserter's flip.
void flipEdge(Mesh& m, std::int32_t c) {
    const std::int32_t d = m.O[c];
    const std::int32_t cn = next(c), cp = prev(c), dn = next(d), dp = prev(d);
    const std::int32_t ocn = m.O[cn], odn = m.O[dn];
    m.V[cp] = m.V[d];
    m.V[dp] = m.V[c];
    link(m, c, odn);
    link(m, d, ocn);
    link(m, cn, dn);
}

}  // namespace

RepairResult repairByFlips(const Mesh& mesh, const CheckReport& report) {
    if (!report.isTriangulation()) {
        std::string why;
        for (const MeshProblem& p : report.problems)
            if (blocksRepair(p.kind) && why.size() < 400)
                why += (why.empty() ? "" : "; ") + p.message;
        throw std::invalid_argument("not a valid triangulation, no repair: " + why);
    }
    RepairResult r;
    r.mesh.G = mesh.G;
    r.mesh.V = mesh.V;
    r.mesh.O = report.opposites;
    Mesh& m = r.mesh;
    std::vector<std::int32_t> stack;
    for (std::int32_t c = 0; c < m.numCorners(); ++c)
        if (m.O[c] > c) stack.push_back(c);
    while (!stack.empty()) {
        const std::int32_t c = stack.back();
        stack.pop_back();
        const std::int32_t d = m.O[c];
        if (d == kNone) continue;
        ++r.incircleTests;
        const std::int32_t t = tri(c);
        if (incircle(m.G[m.V[3 * t]], m.G[m.V[3 * t + 1]], m.G[m.V[3 * t + 2]], m.G[m.V[d]]) <= 0)
            continue;
        r.flips.push_back({c, d, {m.V[next(c)], m.V[prev(c)]}, {m.V[c], m.V[d]}});
        flipEdge(m, c);
        for (const std::int32_t e : {c, prev(c), d, prev(d)})
            if (m.O[e] != kNone) stack.push_back(e);
    }
    return r;
}

}  // namespace dlab
