// Two triangulations at once, joined (see halves.h).
#include "core/engine/halves.h"

#include "core/engine/checks.h"
#include "core/engine/predicates.h"

#include <algorithm>
#include <numeric>
#include <unordered_map>
#include <utility>

namespace dlab {

namespace {

// Below this many points a split costs more than it saves.
constexpr std::size_t kSmallest = 4096;

bool lexLess(Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

}  // namespace

Halves splitAtMedian(const std::vector<Vec2>& points) {
    Halves h;
    if (points.size() < kSmallest) return h;
    std::vector<std::int32_t> order(points.size());
    std::iota(order.begin(), order.end(), 0);
    const auto mid = order.begin() + static_cast<std::ptrdiff_t>(order.size() / 2);
    auto less = [&](std::int32_t a, std::int32_t b) { return lexLess(points[a], points[b]); };
    std::nth_element(order.begin(), mid, order.end(), less);
    const Vec2 median = points[*mid];
    // Strictly below the median point on the left: a point equal to it goes right, with its
    // copies.
    for (std::int32_t i = 0; i < static_cast<std::int32_t>(points.size()); ++i)
        (lexLess(points[i], median) ? h.left : h.right).push_back(i);
    if (h.left.size() < kSmallest / 4 || h.right.size() < kSmallest / 4) return {};
    return h;
}

HalfTriangulation triangulateHalf(const std::vector<Vec2>& points,
                                  const std::vector<std::int32_t>& indices,
                                  const InsertOptions& options) {
    std::vector<Vec2> own;
    own.reserve(indices.size());
    for (const std::int32_t i : indices) own.push_back(points[i]);
    Inserter ins(std::move(own), options);
    ins.run();
    HalfTriangulation h;
    h.stats = ins.stats();
    h.mesh = ins.takeMesh();
    h.mesh.G = {};
    for (std::int32_t& v : h.mesh.V) v = indices[v];
    for (const std::int32_t i : ins.skipped()) h.skipped.push_back(indices[i]);
    return h;
}

namespace {

// The joined mesh under construction: both halves in one corner table, their hulls as cycles.
class Joiner {
public:
    Joiner(const std::vector<Vec2>& points, HalfTriangulation& left, HalfTriangulation& right)
        : m_points(points),
          m_succ(points.size(), kNone),
          m_pred(points.size(), kNone),
          m_boundary(points.size(), kNone) {
        // The left half's arrays take the right half's triangles, and then the zip's (at most
        // one per hull vertex of the two halves).
        m_mesh = std::move(left.mesh);
        const std::size_t leftCorners = m_mesh.V.size();
        const std::size_t corners = leftCorners + right.mesh.V.size();
        m_mesh.V.reserve(corners + 3 * 1024);
        m_mesh.O.reserve(m_mesh.V.capacity());
        const auto shift = static_cast<std::int32_t>(leftCorners);
        m_mesh.V.insert(m_mesh.V.end(), right.mesh.V.begin(), right.mesh.V.end());
        for (const std::int32_t o : right.mesh.O)
            m_mesh.O.push_back(o == kNone ? kNone : o + shift);
        right.mesh = {};
        recordHull(0, shift);
        recordHull(shift, static_cast<std::int32_t>(corners));
    }

    // Merges the two triangulations along the seam from the lower common tangent to the upper
    // one; false when the merge cannot close (then the caller triangulates the set in one).
    bool join(const std::vector<std::int32_t>& left, const std::vector<std::int32_t>& right,
              InsertStats& stats) {
        const auto [l0, r0] = lowerTangent(rightmost(left), leftmost(right));
        const auto [l1, r1] = upperTangent(rightmost(left), leftmost(right));
        m_flags.assign(m_mesh.V.size(), 0);
        if (!stitch(l0, r0, l1, r1, stats)) return false;
        return assemble();
    }

    Mesh take() { return std::move(m_mesh); }

private:
    Vec2 at(std::int32_t v) const { return m_points[v]; }
    int orient(std::int32_t a, std::int32_t b, std::int32_t c) const {
        return orient2d(at(a), at(b), at(c));
    }

    // The hull edges of the corners [from, to): the hull edge a -> b (counter-clockwise, the
    // triangle on its left) is opposite corner c.
    void recordHull(std::int32_t from, std::int32_t to) {
        for (std::int32_t c = from; c < to; ++c) {
            if (m_mesh.O[c] != kNone) continue;
            const std::int32_t a = m_mesh.V[next(c)], b = m_mesh.V[prev(c)];
            m_succ[a] = b;
            m_pred[b] = a;
            m_boundary[a] = c;
        }
    }

    std::int32_t rightmost(const std::vector<std::int32_t>& ids) const {
        std::int32_t best = kNone;
        for (const std::int32_t i : ids) {
            if (m_succ[i] != kNone && (best == kNone || lexLess(at(best), at(i)))) best = i;
        }
        return best;
    }
    std::int32_t leftmost(const std::vector<std::int32_t>& ids) const {
        std::int32_t best = kNone;
        for (const std::int32_t i : ids) {
            if (m_succ[i] != kNone && (best == kNone || lexLess(at(i), at(best)))) best = i;
        }
        return best;
    }

    // The lower common tangent l -> r: every point on it or left of it, and of the points on
    // it, l and r the nearest to each other (the segment holds no other point).
    std::pair<std::int32_t, std::int32_t> lowerTangent(std::int32_t l, std::int32_t r) const {
        for (bool moved = true; moved;) {
            moved = false;
            while (orient(l, r, m_pred[l]) < 0) {
                l = m_pred[l];
                moved = true;
            }
            while (orient(l, r, m_succ[r]) < 0) {
                r = m_succ[r];
                moved = true;
            }
        }
        while (m_succ[l] != r && orient(l, r, m_succ[l]) == 0) l = m_succ[l];
        while (m_pred[r] != l && orient(l, r, m_pred[r]) == 0) r = m_pred[r];
        return {l, r};
    }
    // The upper one: every point on it or right of l -> r; l and r the nearest.
    std::pair<std::int32_t, std::int32_t> upperTangent(std::int32_t l, std::int32_t r) const {
        for (bool moved = true; moved;) {
            moved = false;
            while (orient(l, r, m_succ[l]) > 0) {
                l = m_succ[l];
                moved = true;
            }
            while (orient(l, r, m_pred[r]) > 0) {
                r = m_pred[r];
                moved = true;
            }
        }
        while (m_pred[l] != r && orient(l, r, m_pred[l]) == 0) l = m_pred[l];
        while (m_succ[r] != l && orient(l, r, m_succ[r]) == 0) r = m_succ[r];
        return {l, r};
    }

    // A spoke: the edge from the vertex of corner c to a neighbour in the same half, named by the
    // triangle of c. Its wedge at that vertex runs counter-clockwise from V[n(c)] (the near end)
    // to V[p(c)] (the far end); the spoke is one of the two.
    struct Spoke {
        std::int32_t c = kNone;
        bool far = false;
    };
    std::int32_t tip(Spoke s) const { return m_mesh.V[s.far ? prev(s.c) : next(s.c)]; }
    static std::int32_t across(Spoke s) { return s.far ? next(s.c) : prev(s.c); }  // faces it
    bool erased(Spoke s) const { return (m_flags[across(s)] & kErased) != 0; }
    void erase(Spoke s) {
        const std::int32_t e = across(s);
        m_flags[e] |= kErased;
        if (m_mesh.O[e] != kNone) m_flags[m_mesh.O[e]] |= kErased;
    }
    // The next neighbour counter-clockwise; past a hull vertex's last one, its first one.
    Spoke ccw(Spoke s) const {
        if (!s.far) return {s.c, true};
        const std::int32_t o = m_mesh.O[next(s.c)];  // across the far edge
        if (o != kNone) return {next(o), true};
        std::int32_t c = s.c;
        for (std::int32_t b = m_mesh.O[prev(c)]; b != kNone; b = m_mesh.O[prev(c)]) c = prev(b);
        return {c, false};
    }
    // The next neighbour clockwise; past a hull vertex's first one, its last one.
    Spoke cw(Spoke s) const {
        if (s.far) return {s.c, false};
        const std::int32_t o = m_mesh.O[prev(s.c)];  // across the near edge
        if (o != kNone) return {prev(o), false};
        std::int32_t c = s.c;
        for (std::int32_t b = m_mesh.O[next(c)]; b != kNone; b = m_mesh.O[next(c)]) c = next(b);
        return {c, true};
    }
    // The first spoke after s that is not erased: counter-clockwise on the left half, clockwise
    // on the right one. It ends at the latest where it started.
    template <bool Left>
    Spoke turn(Spoke s) const {
        do {
            s = Left ? ccw(s) : cw(s);
        } while (erased(s));
        return s;
    }
    // The same edge seen from its other end.
    static Spoke reversed(Spoke s) {
        return s.far ? Spoke{prev(s.c), false} : Spoke{next(s.c), true};
    }

    // The candidate apex on one side of base l -> r, from spoke s on (Guibas and Stolfi): while
    // the next spoke's end lies inside the circle of (l, r, candidate), the candidate's edge
    // cannot stay and is erased.
    template <bool Left>
    Spoke settle(std::int32_t l, std::int32_t r, Spoke s, InsertStats& stats) {
        for (Spoke nx = turn<Left>(s); tip(nx) != tip(s); nx = turn<Left>(s)) {
            ++stats.inCircleTests;
            if (incircle(at(l), at(r), at(tip(s)), at(tip(nx))) <= 0) break;
            erase(s);
            s = nx;
        }
        return s;
    }

    // One triangle of the seam, (l, r, apex) counter-clockwise, its apex on the left half or the
    // right one. Its side edge (l-apex or r-apex) stays from that half: `far` is the corner facing
    // it from beyond (kNone on the hull), `inner` the one facing it from the seam's side, in a
    // triangle the seam replaces.
    struct SeamTriangle {
        std::int32_t l, r, apex;
        bool left;
        std::int32_t far, inner;
    };
    SeamTriangle seamTriangle(std::int32_t l, std::int32_t r, Spoke s, bool left) const {
        // The spoke's own triangle lies counter-clockwise of it: beyond the seam on the left
        // half when it is the wedge's near end, on the right half when it is the far end.
        const std::int32_t e = across(s), o = m_mesh.O[e];
        const bool ownIsFar = left != s.far;
        return {l, r, tip(s), left, ownIsFar ? e : o, ownIsFar ? o : e};
    }

    // The merge (Guibas and Stolfi), on the two corner tables as they are: an erased edge is only
    // marked, and a base's candidate on either side is the first spoke not erased after the base.
    bool stitch(std::int32_t l, std::int32_t r, std::int32_t l1, std::int32_t r1,
                InsertStats& stats) {
        Spoke sl{next(m_boundary[l]), false};         // l's first neighbour
        Spoke sr{prev(m_boundary[m_pred[r]]), true};  // r's last neighbour
        for (std::size_t guard = m_mesh.V.size(); guard > 0; --guard) {
            const bool lValid = orient(l, r, tip(sl)) > 0;
            if (lValid) sl = settle<true>(l, r, sl, stats);
            const bool rValid = orient(l, r, tip(sr)) > 0;
            if (rValid) sr = settle<false>(l, r, sr, stats);
            if (!lValid && !rValid) return l == l1 && r == r1 && !m_seam.empty();
            const std::int32_t lv = tip(sl), rv = tip(sr);
            ++stats.inCircleTests;
            if (!lValid || (rValid && incircle(at(l), at(r), at(lv), at(rv)) > 0)) {
                m_seam.push_back(seamTriangle(l, r, sr, false));
                sr = turn<false>(reversed(sr));
                r = rv;
            } else {
                m_seam.push_back(seamTriangle(l, r, sl, true));
                sl = turn<true>(reversed(sl));
                l = lv;
            }
        }
        return false;
    }

    // Replaces the triangles inside the seam (flooded from the side edges' inner corners, up to
    // the side edges and the hulls) by the seam's. A vertex of one half can end up with only the
    // seam's triangles around it: then its edge to the chain is a side edge twice, with the seam
    // on both sides, and the two seam triangles face each other across it. False when the seam
    // does not close.
    bool assemble() {
        auto& V = m_mesh.V;
        auto& O = m_mesh.O;
        std::vector<std::int32_t> slot, stack;
        auto drop = [&](std::int32_t t) {
            if (m_flags[3 * t] & kGone) return;
            m_flags[3 * t] |= kGone;
            slot.push_back(t);
            stack.push_back(t);
        };
        std::unordered_map<std::int32_t, std::size_t> seamAt;  // inner corner -> seam triangle
        for (std::size_t i = 0; i < m_seam.size(); ++i) {
            if (m_seam[i].inner == kNone) continue;
            m_flags[m_seam[i].inner] |= kSide;
            seamAt.emplace(m_seam[i].inner, i);
            drop(tri(m_seam[i].inner));
        }
        while (!stack.empty()) {
            const std::int32_t t = stack.back();
            stack.pop_back();
            for (std::int32_t c = 3 * t; c < 3 * t + 3; ++c) {
                if (!(m_flags[c] & kSide) && O[c] != kNone) drop(tri(O[c]));
            }
        }
        for (const SeamTriangle& s : m_seam) {
            if (s.far != kNone && (m_flags[3 * tri(s.far)] & kGone) && !seamAt.count(s.far))
                return false;
        }
        // The seam has more triangles than it replaces (two more, plus one for every hull vertex
        // of a half that is not one of the whole set's): the rest go at the end.
        if (slot.size() > m_seam.size()) return false;
        std::sort(slot.begin(), slot.end());
        auto end = static_cast<std::int32_t>(V.size() / 3);
        while (slot.size() < m_seam.size()) slot.push_back(end++);
        V.resize(3 * static_cast<std::size_t>(end));
        O.resize(V.size());
        // Seam triangle (l, r, apex) in slot t: corner 3t + 2 faces the base below, the side
        // edge is opposite r (apex on the left) or l, the base above opposite the other one.
        auto sideCorner = [&](std::size_t i) { return 3 * slot[i] + (m_seam[i].left ? 1 : 0); };
        std::int32_t below = kNone;
        for (std::size_t i = 0; i < m_seam.size(); ++i) {
            const SeamTriangle& s = m_seam[i];
            const std::int32_t c = 3 * slot[i];
            V[c] = s.l;
            V[c + 1] = s.r;
            V[c + 2] = s.apex;
            link(c + 2, below);
            const auto across = s.far == kNone ? seamAt.end() : seamAt.find(s.far);
            link(sideCorner(i), across == seamAt.end() ? s.far : sideCorner(across->second));
            below = s.left ? c : c + 1;
            O[below] = kNone;
        }
        return true;
    }
    void link(std::int32_t c, std::int32_t d) {
        m_mesh.O[c] = d;
        if (d != kNone) m_mesh.O[d] = c;
    }

    static constexpr std::uint8_t kErased = 1;  // the edge opposite this corner is erased
    static constexpr std::uint8_t kSide = 2;    // ... is a side edge of the seam
    static constexpr std::uint8_t kGone = 4;    // (first corner) the seam replaces this triangle

    const std::vector<Vec2>& m_points;
    Mesh m_mesh;
    std::vector<std::int32_t> m_succ, m_pred, m_boundary;  // hull cycles, by input index
    std::vector<std::uint8_t> m_flags;                     // per corner, see kErased
    std::vector<SeamTriangle> m_seam;
};

}  // namespace

std::optional<JoinedTriangulation> joinHalves(std::vector<Vec2>& points, const Halves& halves,
                                              HalfTriangulation left, HalfTriangulation right) {
    if (left.mesh.numTriangles() == 0 || right.mesh.numTriangles() == 0) return std::nullopt;
    JoinedTriangulation out;
    out.stats = left.stats;
    const InsertStats& rs = right.stats;
    out.stats.inserted += rs.inserted;
    out.stats.duplicates += rs.duplicates;
    out.stats.flips += rs.flips;
    out.stats.inCircleTests += rs.inCircleTests;
    out.stats.walkSteps += rs.walkSteps;
    out.stats.edgeSplits += rs.edgeSplits;
    out.skipped = std::move(left.skipped);
    out.skipped.insert(out.skipped.end(), right.skipped.begin(), right.skipped.end());
    std::sort(out.skipped.begin(), out.skipped.end());
    Joiner joiner(points, left, right);
    if (!joiner.join(halves.left, halves.right, out.stats)) return std::nullopt;
    out.mesh = joiner.take();
    out.mesh.G = std::move(points);
    return out;
}

}  // namespace dlab
