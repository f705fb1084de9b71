// Two triangulations at once, joined (see halves.h).
#include "core/engine/halves.h"

#include "core/engine/checks.h"
#include "core/engine/predicates.h"

#include <algorithm>
#include <numeric>
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

    // Zips the gap between the hulls and repairs the seam; false when no zip was found.
    bool join(const std::vector<std::int32_t>& left, const std::vector<std::int32_t>& right,
              InsertStats& stats) {
        const auto [l0, r0] = lowerTangent(rightmost(left), leftmost(right));
        const auto [l1, r1] = upperTangent(rightmost(left), leftmost(right));
        if (!zip(l0, r0, l1, r1)) return false;
        repair(stats);
        return true;
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

    // Whether the segment from hull vertex v (between hull vertices a and b, counter-clockwise)
    // to p starts into the hull: p strictly inside the corner a -> v -> b.
    bool enters(std::int32_t a, std::int32_t v, std::int32_t b, std::int32_t p) const {
        return orient(a, v, p) > 0 && orient(v, b, p) > 0;
    }

    std::int32_t newTriangle(std::int32_t a, std::int32_t b, std::int32_t c) {
        const auto t = static_cast<std::int32_t>(m_mesh.V.size() / 3);
        for (const std::int32_t v : {a, b, c}) {
            m_mesh.V.push_back(v);
            m_mesh.O.push_back(kNone);
        }
        return t;
    }
    void link(std::int32_t c, std::int32_t d) {
        m_mesh.O[c] = d;
        if (d != kNone) m_mesh.O[d] = c;
    }

    // Triangles between the left hull's chain l0 .. l1 (counter-clockwise) and the right hull's
    // r0 .. r1 (clockwise), from the lower tangent up. A candidate apex must make a
    // counter-clockwise triangle with the base and keep the new edge out of the other hull;
    // when both may, the one whose circle holds the other not (fewer flips after).
    bool zip(std::int32_t l, std::int32_t r, std::int32_t l1, std::int32_t r1) {
        std::int32_t below = kNone;  // the corner facing the base from the last triangle
        m_firstZip = static_cast<std::int32_t>(m_mesh.V.size() / 3);
        while (l != l1 || r != r1) {
            const std::int32_t lx = l != l1 ? m_succ[l] : kNone;
            const std::int32_t rx = r != r1 ? m_pred[r] : kNone;
            const bool leftOk =
                lx != kNone && orient(l, r, lx) > 0 && !enters(m_pred[r], r, m_succ[r], lx);
            const bool rightOk =
                rx != kNone && orient(l, r, rx) > 0 && !enters(m_pred[l], l, m_succ[l], rx);
            if (!leftOk && !rightOk) return false;
            const bool takeLeft =
                leftOk && (!rightOk || incircle(at(l), at(r), at(lx), at(rx)) <= 0);
            if (takeLeft) {
                // (l, r, lx): the base faces lx, the left hull edge l -> lx faces r.
                const std::int32_t t = newTriangle(l, r, lx);
                link(3 * t + 2, below);
                link(3 * t + 1, m_boundary[l]);
                below = 3 * t;  // the new base r - lx faces l
                l = lx;
            } else {
                // (l, r, rx): the right hull edge rx -> r faces l.
                const std::int32_t t = newTriangle(l, r, rx);
                link(3 * t + 2, below);
                link(3 * t, m_boundary[rx]);
                below = 3 * t + 1;  // the new base rx - l faces r
                r = rx;
            }
        }
        return below != kNone;  // the last base is the upper tangent: a hull edge
    }

    // Lawson: every edge of a zip triangle, and every edge a flip gives a new quadrilateral.
    void repair(InsertStats& stats) {
        std::vector<std::int32_t> stack;
        const auto nt = static_cast<std::int32_t>(m_mesh.V.size() / 3);
        for (std::int32_t c = 3 * m_firstZip; c < 3 * nt; ++c) stack.push_back(c);
        auto& V = m_mesh.V;
        auto& O = m_mesh.O;
        while (!stack.empty()) {
            const std::int32_t c = stack.back();
            stack.pop_back();
            const std::int32_t d = O[c];
            if (d == kNone) continue;
            ++stats.inCircleTests;
            if (incircle(at(V[d]), at(V[next(d)]), at(V[prev(d)]), at(V[c])) <= 0) continue;
            // t = (P, A, B), u = (D, B, A) -> (P, A, D), (D, B, P), as the inserter's flip.
            const std::int32_t cn = next(c), cp = prev(c), dn = next(d), dp = prev(d);
            const std::int32_t P = V[c], D = V[d];
            const std::int32_t ocn = O[cn], odn = O[dn];
            V[cp] = D;
            V[dp] = P;
            link(c, odn);
            link(d, ocn);
            link(cn, dn);
            ++stats.flips;
            for (const std::int32_t e : {c, cp, d, dp}) stack.push_back(e);
        }
    }

    const std::vector<Vec2>& m_points;
    Mesh m_mesh;
    std::vector<std::int32_t> m_succ, m_pred, m_boundary;  // hull cycles, by input index
    std::int32_t m_firstZip = 0;
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
