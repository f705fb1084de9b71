// Two triangulations at once, joined (see halves.h).
#include "core/engine/halves.h"

#include "core/engine/order.h"
#include "core/engine/predicates.h"

#include <algorithm>
#include <unordered_map>
#include <utility>

namespace dlab {

namespace {

bool lexLess(Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

// The boundary corners of a finished triangulation (one disc, vertex ids below idBound) in
// counter-clockwise order: corner c faces the hull edge V[n(c)] -> V[p(c)].
std::vector<std::int32_t> hullCorners(const Mesh& mesh, std::size_t idBound) {
    std::vector<std::int32_t> from(idBound, kNone), hull;  // the boundary corner after each vertex
    std::int32_t first = kNone;
    std::size_t count = 0;
    for (std::int32_t c = 0; c < mesh.numCorners(); ++c) {
        if (mesh.O[c] != kNone) continue;
        from[mesh.V[next(c)]] = c;
        first = c;
        ++count;
    }
    for (std::int32_t c = first; c != kNone && hull.size() < count; c = from[mesh.V[prev(c)]]) {
        hull.push_back(c);
        if (from[mesh.V[prev(c)]] == first) break;
    }
    return hull;
}

}  // namespace

std::optional<Vec2> splitPoint(const std::vector<Vec2>& points, std::size_t smallest) {
    if (points.size() < std::max<std::size_t>(smallest, 1)) return std::nullopt;
    // The median of a sample drawn with a fixed seed (of every point, for a set no larger than
    // the sample): no pass over the set and the same split on every machine. The halves' sizes
    // are within about half a per cent of each other whatever the input's order; the two threads
    // wait for the larger half, and a sample of 4095 left them up to 8% apart.
    constexpr std::size_t kSample = 65535;
    std::vector<Vec2> sample;
    if (points.size() <= kSample) {
        sample = points;
    } else {
        SplitMix64 rng(0x5eedull);
        sample.resize(kSample);
        const auto n = static_cast<std::uint32_t>(points.size());
        for (Vec2& p : sample) p = points[rng.below(n)];
    }
    const auto mid = sample.begin() + static_cast<std::ptrdiff_t>(sample.size() / 2);
    std::nth_element(sample.begin(), mid, sample.end(), lexLess);
    return *mid;
}

namespace {

// The work of a run in predicate calls: each insertion costs about two beyond its walk and its
// in-circle tests (the split's orientation and the locate's last test).
std::int64_t workOf(const InsertStats& s) {
    return s.inCircleTests + s.walkSteps + 2 * (s.inserted + s.duplicates);
}

}  // namespace

double SplitPilot::ratio() const {
    return whole > 0 ? double(std::max(left, right) + join) / double(whole) : 0.0;
}

double SplitPilot::seamShare() const { return whole > 0 ? double(join) / double(whole) : 0.0; }

// The halves run at once, but two threads pay for starting, for a copy of the points each and
// for the merged arrays: the split must save a sixth of the one inserter's work. The span is
// 0.5 to 0.55 of it on uniform points, up to 0.72 on `curves` (whose halves differ: two
// threads still take 0.6 of one's time there), 1 to 2 on a parabola.
bool SplitPilot::pays() const { return joined && ratio() <= 0.85 && seamShare() <= 0.1; }

SplitPilot pilotSplit(const std::vector<Vec2>& points, Vec2 split, const InsertOptions& options,
                      std::size_t sample) {
    SplitPilot pilot;
    if (points.empty()) return pilot;
    std::vector<Vec2> pts(std::min(sample, points.size()));
    SplitMix64 rng(0x9170ull);
    const auto n = static_cast<std::uint32_t>(points.size());
    for (Vec2& p : pts) p = points[rng.below(n)];
    pilot.sample = pts.size();
    {
        Inserter whole(pts, options);
        whole.run();
        pilot.whole = workOf(whole.stats());
    }
    HalfTriangulation left = triangulateHalf(pts, split, true, options);
    HalfTriangulation right = triangulateHalf(pts, split, false, options);
    pilot.left = workOf(left.stats);
    pilot.right = workOf(right.stats);
    const std::int64_t halvesInCircle = left.stats.inCircleTests + right.stats.inCircleTests;
    const std::optional<JoinedTriangulation> joined =
        joinHalves(pts, std::move(left), std::move(right));
    pilot.joined = joined.has_value();
    // The join's work: its in-circle tests (one or two a seam triangle, one an erased edge).
    if (joined) {
        pilot.join = joined->stats.inCircleTests - halvesInCircle;
    }
    return pilot;
}

HalfTriangulation triangulateHalf(const std::vector<Vec2>& points, Vec2 split, bool left,
                                  const InsertOptions& options) {
    std::vector<std::int32_t> indices;
    std::vector<Vec2> own;
    indices.reserve(points.size() / 2 + points.size() / 16);
    own.reserve(indices.capacity());
    for (std::int32_t i = 0; i < static_cast<std::int32_t>(points.size()); ++i) {
        if (lexLess(points[i], split) == left) {
            indices.push_back(i);
            own.push_back(points[i]);
        }
    }
    Inserter ins(std::move(own), options);
    if (left) ins.reserveTriangles(maxTriangles(points.size()));
    ins.runForTopology(std::move(indices));  // the vertices come out as input indices
    HalfTriangulation h;
    h.stats = ins.stats();
    h.locatorStats = ins.locator()->stats();
    h.mesh = ins.takeMesh();
    h.hull = hullCorners(h.mesh, points.size());
    h.skipped = ins.skipped();
    return h;
}

namespace {

// The joined mesh under construction: both halves in one corner table, their hulls as lists.
class Joiner {
public:
    Joiner(const std::vector<Vec2>& points, HalfTriangulation& left, HalfTriangulation& right)
        : m_points(points) {
        // The left half's arrays (reserved for the whole result) take the right half's
        // triangles, then the seam's. Each of the right half's arrays goes as soon as it is
        // copied, so the peak holds one of them.
        m_mesh = std::move(left.mesh);
        const auto shift = static_cast<std::int32_t>(m_mesh.V.size());
        m_mesh.V.insert(m_mesh.V.end(), right.mesh.V.begin(), right.mesh.V.end());
        right.mesh.V = std::vector<std::int32_t>();  // (= {} would keep the capacity)
        m_mesh.O.resize(m_mesh.V.size());
        std::int32_t* o = m_mesh.O.data() + shift;
        for (const std::int32_t d : right.mesh.O) *o++ = d == kNone ? kNone : d + shift;
        right.mesh.O = std::vector<std::int32_t>();
        m_left = std::move(left.hull);
        m_right = std::move(right.hull);
        for (std::int32_t& c : m_right) c += shift;
    }

    // Merges the two triangulations along the seam from the lower common tangent to the upper
    // one; false when the merge cannot close (then the caller triangulates the set in one).
    bool join(InsertStats& stats) {
        const Ends start{extreme(m_left, true), extreme(m_right, false)};
        const Ends lower = tangent(start, true), upper = tangent(start, false);
        m_flags.assign(m_mesh.V.size(), 0);
        if (!stitch(lower, upper, stats)) return false;
        return assemble();
    }

    Mesh take() { return std::move(m_mesh); }

private:
    Vec2 at(std::int32_t v) const { return m_points[v]; }
    int orient(std::int32_t a, std::int32_t b, std::int32_t c) const {
        return orient2d(at(a), at(b), at(c));
    }

    // Positions on a hull list: corner hull[i] faces the hull edge from vertex(hull, i) to
    // vertex(hull, i + 1), counter-clockwise.
    std::int32_t vertex(const std::vector<std::int32_t>& hull, std::size_t i) const {
        return m_mesh.V[next(hull[i])];
    }
    static std::size_t succ(const std::vector<std::int32_t>& hull, std::size_t i) {
        return i + 1 == hull.size() ? 0 : i + 1;
    }
    static std::size_t pred(const std::vector<std::int32_t>& hull, std::size_t i) {
        return i == 0 ? hull.size() - 1 : i - 1;
    }
    // The position of the hull's lexicographically greatest vertex (or least).
    std::size_t extreme(const std::vector<std::int32_t>& hull, bool greatest) const {
        std::size_t best = 0;
        for (std::size_t i = 1; i < hull.size(); ++i) {
            const Vec2 p = at(vertex(hull, i)), b = at(vertex(hull, best));
            if (greatest ? lexLess(b, p) : lexLess(p, b)) best = i;
        }
        return best;
    }

    // A base's ends: positions on the left hull and on the right one.
    struct Ends {
        std::size_t l, r;
    };
    // A common tangent of the two hulls, l -> r: the lower one (every point on it or left of
    // it) or the upper one (on it or right of it); of the points on it, l and r the nearest to
    // each other (the segment holds no other point).
    Ends tangent(Ends e, bool lower) const {
        const auto& L = m_left;
        const auto& R = m_right;
        // Outward: down both hulls for the lower tangent (clockwise round the left one,
        // counter-clockwise round the right one), up both for the upper one.
        auto alongL = [&](std::size_t i, bool out) {
            return out == lower ? pred(L, i) : succ(L, i);
        };
        auto alongR = [&](std::size_t i, bool out) {
            return out == lower ? succ(R, i) : pred(R, i);
        };
        auto outside = [&](std::int32_t x) {  // > 0: x is on the side no point may be on
            return orient(vertex(L, e.l), vertex(R, e.r), x) * (lower ? -1 : 1);
        };
        for (bool moved = true; moved;) {
            moved = false;
            for (; outside(vertex(L, alongL(e.l, true))) > 0; moved = true) e.l = alongL(e.l, true);
            for (; outside(vertex(R, alongR(e.r, true))) > 0; moved = true) e.r = alongR(e.r, true);
        }
        while (outside(vertex(L, alongL(e.l, false))) == 0) e.l = alongL(e.l, false);
        while (outside(vertex(R, alongR(e.r, false))) == 0) e.r = alongR(e.r, false);
        return e;
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
    bool stitch(Ends lower, Ends upper, InsertStats& stats) {
        std::int32_t l = vertex(m_left, lower.l), r = vertex(m_right, lower.r);
        const std::int32_t l1 = vertex(m_left, upper.l), r1 = vertex(m_right, upper.r);
        Spoke sl{next(m_left[lower.l]), false};                 // l's first neighbour
        Spoke sr{prev(m_right[pred(m_right, lower.r)]), true};  // r's last neighbour
        // Each seam triangle has a side edge from a half, and an edge is a side edge at most
        // twice (a seam on both sides): the seam has at most as many triangles as the halves
        // have edge sides, 3 a triangle plus 1 a hull edge, and one more pass finds the top.
        // (Corners alone are too few where the halves are single needles: 6 points, 2
        // triangles, 6 seam triangles.)
        const std::size_t most = m_mesh.V.size() + m_left.size() + m_right.size() + 1;
        for (std::size_t guard = most; guard > 0; --guard) {
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
        for (const SeamTriangle& s : m_seam) {
            if (s.inner == kNone) continue;
            m_flags[s.inner] |= kSide;
            drop(tri(s.inner));
        }
        while (!stack.empty()) {
            const std::int32_t t = stack.back();
            stack.pop_back();
            for (std::int32_t c = 3 * t; c < 3 * t + 3; ++c) {
                if (!(m_flags[c] & kSide) && O[c] != kNone) drop(tri(O[c]));
            }
        }
        const std::vector<std::size_t> partner = partners();
        for (std::size_t i = 0; i < m_seam.size(); ++i) {
            const std::int32_t far = m_seam[i].far;
            if (far != kNone && (m_flags[3 * tri(far)] & kGone) && partner[i] == kAlone)
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
            link(sideCorner(i), partner[i] == kAlone ? s.far : sideCorner(partner[i]));
            below = s.left ? c : c + 1;
            O[below] = kNone;
        }
        return true;
    }
    // For each seam triangle, the one across its side edge when that edge has the seam on both
    // sides (kAlone otherwise). The two name the edge by the same corners, swapped: its corner in
    // a triangle of the half, or the two of them.
    static constexpr std::size_t kAlone = ~std::size_t{0};
    std::vector<std::size_t> partners() const {
        std::vector<std::size_t> partner(m_seam.size(), kAlone);
        std::unordered_map<std::int32_t, std::size_t> first;  // edge -> its first seam triangle
        for (std::size_t i = 0; i < m_seam.size(); ++i) {
            const SeamTriangle& s = m_seam[i];
            const std::int32_t edge = s.inner == kNone ? s.far
                                      : s.far == kNone ? s.inner
                                                       : std::min(s.inner, s.far);
            const auto [it, isNew] = first.emplace(edge, i);
            if (!isNew) {
                partner[i] = it->second;
                partner[it->second] = i;
            }
        }
        return partner;
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
    std::vector<std::int32_t> m_left, m_right;  // the halves' hulls (see vertex())
    std::vector<std::uint8_t> m_flags;          // per corner, see kErased
    std::vector<SeamTriangle> m_seam;
};

}  // namespace

std::optional<JoinedTriangulation> joinHalves(std::vector<Vec2>& points, HalfTriangulation left,
                                              HalfTriangulation right) {
    if (left.mesh.numTriangles() == 0 || right.mesh.numTriangles() == 0) return std::nullopt;
    JoinedTriangulation out;
    out.stats = left.stats;
    out.stats += right.stats;
    out.locatorStats = left.locatorStats;
    out.locatorStats += right.locatorStats;
    out.skipped = std::move(left.skipped);
    out.skipped.insert(out.skipped.end(), right.skipped.begin(), right.skipped.end());
    std::sort(out.skipped.begin(), out.skipped.end());
    Joiner joiner(points, left, right);
    if (!joiner.join(out.stats)) return std::nullopt;
    out.mesh = joiner.take();
    out.mesh.G = std::move(points);
    return out;
}

}  // namespace dlab
