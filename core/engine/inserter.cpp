// Lawson's incremental insertion on the corner table: walk, split, in-circle tests and flips,
// each a recorded operation that the Journal can undo exactly.
#include "core/engine/inserter.h"

#include "core/engine/checks.h"
#include "core/engine/predicates.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace dlab {

// ============================================================================================
// [SECTION] Names
// ============================================================================================

const char* toString(Boundary b) { return nameIn(kBoundaryNames, b).data(); }

std::optional<Boundary> parseBoundary(std::string_view name) {
    return parseIn(kBoundaryNames, name);
}

namespace {
constexpr const char* kOpNames[] = {"Start",     "LocateStep",   "Located", "Split",
                                    "SplitEdge", "InCircleTest", "Flip",    "SkipDuplicate",
                                    "Inserted",  "Finalize"};
}

const char* toString(OpType t) { return kOpNames[static_cast<int>(t)]; }

std::optional<OpType> parseOpType(std::string_view name) {
    for (int i = 0; i < 10; ++i) {
        if (name == kOpNames[i]) return static_cast<OpType>(i);
    }
    return std::nullopt;
}

const char* toString(Where w) {
    switch (w) {
        case Where::None: return "none";
        case Where::InTriangle: return "inside";
        case Where::OnEdge: return "edge";
        case Where::OnVertex: return "vertex";
        case Where::Outside: return "outside-hull";
    }
    return "?";
}

const char* toString(PredicateAsk ask) {
    switch (ask) {
        case PredicateAsk::FirstTriangle: return "first-triangle";
        case PredicateAsk::StartCentroid: return "start-centroid";
        case PredicateAsk::LineSide: return "line-side";
        case PredicateAsk::ExitEdge: return "exit-edge";
        case PredicateAsk::VisibilityEdge: return "visibility-edge";
        case PredicateAsk::HullEdge: return "hull-edge";
        case PredicateAsk::ClassifyEdge: return "classify-edge";
        case PredicateAsk::ClassifyHull: return "classify-hull";
        case PredicateAsk::InCircle: return "incircle";
        case PredicateAsk::GhostCircle: return "ghost-circle";
    }
    return "?";
}

bool RecordedPredicateCall::operator==(const RecordedPredicateCall& o) const {
    // Coordinates bit for bit (-0 is not 0 here).
    for (int k = 0; k < 4; ++k) {
        if (std::memcmp(&p[k], &o.p[k], sizeof(Vec2)) != 0) return false;
    }
    return ask == o.ask && sign == o.sign && v == o.v && corner == o.corner;
}

std::string describe(const RecordedPredicateCall& call) {
    // Appended, not "v" + to_string: GCC 12 gives a false -Wrestrict warning for that form.
    auto named = [](char letter, std::int32_t id) {
        std::string s(1, letter);
        s += std::to_string(id);
        return s;
    };
    auto n = [&](int k) { return call.v[k] == kNone ? std::string("q") : named('v', call.v[k]); };
    const std::string t = call.corner == kNone ? "" : named('t', tri(call.corner));
    const std::string edge = n(0) + " -> " + n(1);
    switch (call.ask) {
        case PredicateAsk::FirstTriangle:
            return "Start: are the first three points " + n(0) + ", " + n(1) + ", " + n(2) +
                   " counter-clockwise? (-1: the first triangle turns them round; 0: all points "
                   "are collinear, there is no triangle)";
        case PredicateAsk::StartCentroid:
            return "Walk start in " + t + ": is its centroid q left of the edge " + edge +
                   "? (the line walk starts from q only when q is strictly inside " + t + ")";
        case PredicateAsk::LineSide:
            return "Is " + n(2) + " left of the line L from q to p = " + n(1) + "? (L leaves " + t +
                   " on the far side of " + n(2) + "; on L counts as left)";
        case PredicateAsk::ExitEdge:
            return "Is p = " + n(2) + " inside the edge " + edge + " that L leaves " + t +
                   " through? (-1: beyond it, the walk crosses it; else p is in " + t + ")";
        case PredicateAsk::VisibilityEdge:
            return "Visibility walk in " + t + ": is p = " + n(2) + " left of the edge " + edge +
                   "? (-1: beyond it, the walk crosses it)";
        case PredicateAsk::HullEdge:
            return "Ghost triangle " + t + ": is p = " + n(2) + " beyond the hull edge " + edge +
                   "? (+1, or 0 on the edge itself: p is placed here; else the walk goes back "
                   "inside)";
        case PredicateAsk::ClassifyEdge:
            return "Where in " + t + " is p = " + n(2) + ": left of the edge " + edge +
                   " (+1), on it (0) or right of it (-1)?";
        case PredicateAsk::ClassifyHull:
            return "Where is p = " + n(2) + " against the hull edge " + edge +
                   " of ghost triangle " + t + ": beyond it (+1) or on it (0)?";
        case PredicateAsk::InCircle:
            return "In-circle: is P = " + n(3) + " inside the circle through " + n(0) + ", " +
                   n(1) + ", " + n(2) + "? (+1: the edge " + n(2) + " - " + n(1) +
                   " is not Delaunay, flip it)";
        case PredicateAsk::GhostCircle:
            return "Ghost triangle beyond the hull edge " + edge + ": is P = " + n(2) +
                   " beyond that edge? (the ghost's circle is the half-plane there; +1: flip)";
    }
    return "?";
}

// ============================================================================================
// [SECTION] Recorders: the batch path's recorder does nothing and compiles away
// ============================================================================================

namespace {

// Every orient2d and incircle call of the walk, the classification, the first triangle and the
// in-circle test goes through the recorder: with the arguments' vertex ids and the tested corner,
// which only a recorder that keeps calls reads (for the others they are dead loads).
using Ids3 = std::array<std::int32_t, 3>;
using Ids4 = std::array<std::int32_t, 4>;

// The batch path's: no cells, no calls. kReplay: the op is made again, not for the first time.
// The counters one op moves: the step path adds them, undo takes them back, redo adds them again
// (Start's, which depend on the points, are its own).
void countOp(InsertStats& s, const Op& op, int dir) {
    switch (op.type) {
        case OpType::LocateStep: s.walkSteps += dir; break;
        case OpType::SplitEdge: s.edgeSplits += dir; break;
        case OpType::InCircleTest:  // an edge on the boundary has nothing to test
            (op.b != kNone ? s.inCircleTests : s.boundaryPops) += dir;
            break;
        case OpType::Flip: s.flips += dir; break;
        case OpType::SkipDuplicate: s.duplicates += dir; break;
        case OpType::Inserted: s.inserted += dir; break;
        default: break;
    }
}

struct NullRec {
    static constexpr bool kOn = false;
    static constexpr bool kReplay = false;
    void cell(std::int32_t, std::int32_t, std::int32_t) {}
    void push(std::int32_t) {}
    [[gnu::always_inline]] int orient(PredicateAsk, Vec2 a, Vec2 b, Vec2 c, Ids3, std::int32_t) {
        return orient2d(a, b, c);
    }
    [[gnu::always_inline]] int inCircle(PredicateAsk, Vec2 a, Vec2 b, Vec2 c, Vec2 d, Ids4,
                                        std::int32_t) {
        return incircle(a, b, c, d);
    }
};

// Appends each call to `calls` when it is set.
struct CallRec {
    std::vector<RecordedPredicateCall>* calls = nullptr;
    int orient(PredicateAsk ask, Vec2 a, Vec2 b, Vec2 c, Ids3 v, std::int32_t corner) {
        const int s = orient2d(a, b, c);
        if (calls) {
            calls->push_back({ask,
                              static_cast<std::int8_t>(s),
                              {a, b, c, Vec2{}},
                              {v[0], v[1], v[2], kNone},
                              corner});
        }
        return s;
    }
    int inCircle(PredicateAsk ask, Vec2 a, Vec2 b, Vec2 c, Vec2 d, Ids4 v, std::int32_t corner) {
        const int s = incircle(a, b, c, d);
        if (calls) calls->push_back({ask, static_cast<std::int8_t>(s), {a, b, c, d}, v, corner});
        return s;
    }
};

// The stepping path's: cell changes into the journal, calls where asked for.
struct JournalRec : CallRec {
    static constexpr bool kOn = true;
    static constexpr bool kReplay = false;
    Journal* journal = nullptr;
    void cell(std::int32_t slot, std::int32_t before, std::int32_t after) {
        if (journal) journal->record({slot, before, after});
    }
    void push(std::int32_t corner) {
        if (journal) journal->recordPush(corner);
    }
};

// predicateCallsOf: an op made again for its calls; it changes no cell.
struct ReplayRec : CallRec {
    static constexpr bool kOn = false;
    static constexpr bool kReplay = true;
    void cell(std::int32_t, std::int32_t, std::int32_t) {}
    void push(std::int32_t) {}
};

// Within one triangle: the index of next(c) and prev(c) for c = 3t + k.
constexpr int kNext[3] = {1, 2, 0};
constexpr int kPrev[3] = {2, 0, 1};

// Calls f for every corner at the vertex of corner `start` (start first). Interior vertices
// have a closed ring; it is walked one way, then the other way if it is open.
template <class F>
void forEachCornerAround(const std::vector<std::int32_t>& O, std::int32_t start, F&& f) {
    std::int32_t c = start;
    do {
        f(c);
        const std::int32_t l = O[next(c)];
        c = l == kNone ? kNone : next(l);
    } while (c != kNone && c != start);
    if (c == kNone) {
        for (std::int32_t r = O[prev(start)]; r != kNone;) {
            const std::int32_t u = prev(r);
            f(u);
            r = O[prev(u)];
        }
    }
}

// A million-point run touches ~50 MB of fresh V/O memory; with 4 KiB pages the page faults
// alone cost tens of milliseconds. Transparent huge pages (where the kernel offers them on
// request) cut that. Only a hint: nothing depends on it.
void adviseHugePages(void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    const std::uintptr_t kHuge = 2u << 20;
    const std::uintptr_t begin =
        (reinterpret_cast<std::uintptr_t>(data) + kHuge - 1) & ~(kHuge - 1);
    const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(kHuge - 1);
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
    (void)data;
    (void)bytes;
#endif
}

}  // namespace

// ============================================================================================
// [SECTION] Construction
// ============================================================================================

Inserter::Inserter(std::vector<Vec2> points, const InsertOptions& options,
                   std::unique_ptr<Locator> locator)
    : m_options(options), m_locator(std::move(locator)) {
    if (points.size() > kMaxPoints) {
        throw std::invalid_argument("too many points: " + std::to_string(points.size()) +
                                    " (the limit is " + std::to_string(kMaxPoints) + ")");
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (!std::isfinite(points[i].x) || !std::isfinite(points[i].y)) {
            throw std::invalid_argument("point " + std::to_string(i) +
                                        " has a non-finite coordinate");
        }
    }
    if (!m_locator) m_locator = makeLocator(options.locator, options.locatorOptions);
    m_numInput = static_cast<std::int32_t>(points.size());
    m_bounds = Bounds::of(points);
    m_mesh.G = std::move(points);
    m_order = insertionOrder(m_mesh.G, options.order, options.seed, options.threads);
    const auto& G = m_mesh.G;

    if (options.boundary == Boundary::Exact) {
        // Bring the first non-degenerate triple to the front of the order (the rest keeps its
        // relative order); the ghost vertex g = n needs no coordinates, it gets the centre.
        const std::int32_t n = m_numInput;
        if (n >= 3) {
            const std::int32_t a = m_order[0];
            std::int32_t ib = kNone, ic = kNone;
            for (std::int32_t i = 1; i < n && ib == kNone; ++i) {
                if (!(G[m_order[i]] == G[a])) ib = i;
            }
            for (std::int32_t i = ib == kNone ? n : ib + 1; i < n && ic == kNone; ++i) {
                if (orient2d(G[a], G[m_order[ib]], G[m_order[i]]) != 0) ic = i;
            }
            if (ic != kNone) {
                const std::int32_t b = m_order[ib], c = m_order[ic];
                m_order.erase(m_order.begin() + ic);
                m_order.erase(m_order.begin() + ib);
                m_order.insert(m_order.begin() + 1, {b, c});
            }
        }
        m_virtualPoints = {
            {m_bounds.lo.x / 2 + m_bounds.hi.x / 2, m_bounds.lo.y / 2 + m_bounds.hi.y / 2}};
    } else {
        // The paper's super-triangle: large, finite, strictly containing every input point
        // (checked exactly, grown until true).
        const double cx = m_bounds.lo.x / 2 + m_bounds.hi.x / 2;
        const double cy = m_bounds.lo.y / 2 + m_bounds.hi.y / 2;
        double size =
            std::max(m_bounds.hi.x / 2 - m_bounds.lo.x / 2, m_bounds.hi.y / 2 - m_bounds.lo.y / 2) *
            2;
        size = std::max({size, std::abs(cx) * 0x1p-40, std::abs(cy) * 0x1p-40, 1e-300});
        for (int attempt = 0;; ++attempt) {
            const Vec2 s0{cx - 30 * size, cy - 20 * size}, s1{cx + 30 * size, cy - 20 * size},
                s2{cx, cy + 30 * size};
            bool ok = std::isfinite(s0.x) && std::isfinite(s0.y) && std::isfinite(s1.x) &&
                      std::isfinite(s2.y) && orient2d(s0, s1, s2) > 0;
            for (std::int32_t i = 0; ok && i < m_numInput; ++i) {
                ok = orient2d(s0, s1, G[i]) > 0 && orient2d(s1, s2, G[i]) > 0 &&
                     orient2d(s2, s0, G[i]) > 0;
            }
            if (ok) {
                m_virtualPoints = {s0, s1, s2};
                break;
            }
            if (!std::isfinite(size) || attempt > 2000) {
                throw std::domain_error(
                    "super mode: no finite super-triangle contains these coordinates; use the "
                    "exact boundary mode");
            }
            size *= 16;
        }
    }
    m_mesh.G.insert(m_mesh.G.end(), m_virtualPoints.begin(), m_virtualPoints.end());
}

Inserter::Inserter(std::vector<Vec2> points, StartMesh start, const InsertOptions& options)
    : Inserter(std::move(points), [&] {
          InsertOptions o = options;
          o.boundary = Boundary::Exact;
          o.locator = LocatorKind::Walk;
          return o;
      }()) {
    const std::size_t corners = start.V.size();
    if (corners % 3 != 0 || start.O.size() != corners || corners / 3 > 2 * kMaxPoints)
        throw std::invalid_argument("a start mesh needs three corners a triangle and O for each");
    for (std::size_t c = 0; c < corners; ++c) {
        if (start.V[c] < 0 || start.V[c] >= m_numInput)
            throw std::invalid_argument("corner " + std::to_string(c) + " names vertex " +
                                        std::to_string(start.V[c]) + ", which does not exist");
        const std::int32_t o = start.O[c];
        if (o != kNone && (o < 0 || static_cast<std::size_t>(o) >= corners ||
                           start.O[o] != static_cast<std::int32_t>(c)))
            throw std::invalid_argument("O of corner " + std::to_string(c) +
                                        " is not an opposite corner");
    }
    m_repair = true;
    m_start = std::move(start);
}

Inserter::~Inserter() = default;

std::int32_t Inserter::currentVertex() const {
    if (m_repair) return kNone;
    switch (m_ctl.phase) {
        case Phase::Locate:
        case Phase::Place:
        case Phase::Test:
        case Phase::Flip:
        case Phase::Finish:
            return m_ctl.cursor < static_cast<std::int32_t>(m_order.size()) ? m_order[m_ctl.cursor]
                                                                            : kNone;
        default: return kNone;
    }
}

// ============================================================================================
// [SECTION] Cell writes: every change of V and O goes through here
// ============================================================================================

template <class Rec>
void Inserter::setV(Rec& rec, std::int32_t c, std::int32_t v) {
    if constexpr (Rec::kOn) rec.cell(2 * c, m_mesh.V[c], v);
    m_mesh.V[c] = v;
}

template <class Rec>
void Inserter::setO(Rec& rec, std::int32_t c, std::int32_t o) {
    if constexpr (Rec::kOn) rec.cell(2 * c + 1, m_mesh.O[c], o);
    m_mesh.O[c] = o;
}

template <class Rec>
void Inserter::link(Rec& rec, std::int32_t c, std::int32_t d) {
    setO(rec, c, d);
    if (d != kNone) setO(rec, d, c);
}

template <class Rec>
std::int32_t Inserter::appendTriangles(Rec&, int count) {
    const std::int32_t t = m_mesh.numTriangles();
    m_mesh.V.resize(m_mesh.V.size() + 3 * count, kNone);
    m_mesh.O.resize(m_mesh.O.size() + 3 * count, kNone);
    return t;
}

template <class Rec>
void Inserter::pushTest(Rec& rec, std::int32_t c) {
    if constexpr (Rec::kOn) rec.push(c);
    m_stack.push_back(c);
}

void Inserter::notifyChanged(const std::int32_t* tris, int count) {
    if (m_locatorWantsChanges && !m_bulk) m_locator->trianglesChanged(tris, count);
}

void Inserter::setBulk(bool on) {
    // Back at the start the mesh is empty and the resync clears the locator's index.
    if (m_bulk && !on && m_locatorWantsChanges) m_locator->resync();
    m_bulk = on;
}

// ============================================================================================
// [SECTION] The three mesh operations
// ============================================================================================

// Split 1->3. Triangle t = (a, b, c) keeps its corners as (a, b, v); two triangles are
// appended: t1 = (b, c, v) and t2 = (c, a, v). The corners at v face the three old edges.
//
//          c                       c
//          |`.                     |`.
//          |  `.          ==>      | t2`.      t  = (a, b, v)
//          | t  `.                 |  v--`.    t1 = (b, c, v)
//          |      `.               | / t1  `.  t2 = (c, a, v)
//          a -------b              a ------- b
template <class Rec>
void Inserter::split(Rec& rec, std::int32_t t, std::int32_t v) {
    DLAB_ASSERT(t >= 0 && t < m_mesh.numTriangles() && m_mesh.V[3 * t] != kNone,
                "split of a triangle that is not in the mesh");
    const std::int32_t c0 = 3 * t, c1 = c0 + 1, c2 = c0 + 2;
    const std::int32_t a = m_mesh.V[c0], b = m_mesh.V[c1], c = m_mesh.V[c2];
    const std::int32_t oa = m_mesh.O[c0], ob = m_mesh.O[c1];
    const std::int32_t t1 = appendTriangles(rec, 2), t2 = t1 + 1;
    const std::int32_t d0 = 3 * t1, e0 = 3 * t2;
    setV(rec, c2, v);  // O[c2] still faces a->b
    setV(rec, d0, b);
    setV(rec, d0 + 1, c);
    setV(rec, d0 + 2, v);
    setV(rec, e0, c);
    setV(rec, e0 + 1, a);
    setV(rec, e0 + 2, v);
    link(rec, c0, d0 + 1);  // edge b-v
    link(rec, c1, e0);      // edge v-a
    link(rec, d0, e0 + 1);  // edge c-v
    link(rec, d0 + 2, oa);  // old edge b->c
    link(rec, e0 + 2, ob);  // old edge c->a
    pushTest(rec, c2);
    pushTest(rec, d0 + 2);
    pushTest(rec, e0 + 2);
    const std::int32_t tris[3] = {t, t1, t2};
    notifyChanged(tris, 3);
}

// Split 2->4 (1->2 without a neighbour). v lies on the edge A-B opposite corner c.
//   t = (C, A, B) becomes (C, A, v), appended t' = (C, v, B);
//   u = (D, B, A) becomes (D, B, v), appended u' = (D, v, A).
template <class Rec>
void Inserter::splitEdge(Rec& rec, std::int32_t c, std::int32_t v) {
    DLAB_ASSERT(c >= 0 && c < m_mesh.numCorners() && m_mesh.V[c] != kNone,
                "edge split at a corner that is not in the mesh");
    DLAB_ASSERT(m_mesh.O[c] == kNone || m_mesh.O[m_mesh.O[c]] == c,
                "edge split across corners that are not opposite");
    const std::int32_t cn = next(c), cp = prev(c);
    const std::int32_t d = m_mesh.O[c];
    const std::int32_t C = m_mesh.V[c], B = m_mesh.V[cp];
    const std::int32_t ocn = m_mesh.O[cn];
    const std::int32_t tp = appendTriangles(rec, d == kNone ? 1 : 2);
    const std::int32_t x = 3 * tp;  // t' = (C, v, B)
    setV(rec, cp, v);
    setV(rec, x, C);
    setV(rec, x + 1, v);
    setV(rec, x + 2, B);
    link(rec, cn, x + 2);   // edge v-C
    link(rec, x + 1, ocn);  // old edge B->C
    if (d == kNone) {
        setO(rec, c, kNone);
        setO(rec, x, kNone);
        pushTest(rec, cp);
        pushTest(rec, x + 1);
        const std::int32_t tris[2] = {tri(c), tp};
        notifyChanged(tris, 2);
        return;
    }
    const std::int32_t dn = next(d), dp = prev(d);
    const std::int32_t D = m_mesh.V[d], A = m_mesh.V[dp];
    const std::int32_t odn = m_mesh.O[dn];
    const std::int32_t y = x + 3;  // u' = (D, v, A)
    setV(rec, dp, v);
    setV(rec, y, D);
    setV(rec, y + 1, v);
    setV(rec, y + 2, A);
    link(rec, c, y);        // edge A-v
    link(rec, x, d);        // edge v-B
    link(rec, dn, y + 2);   // edge v-D
    link(rec, y + 1, odn);  // old edge A->D
    pushTest(rec, cp);
    pushTest(rec, x + 1);
    pushTest(rec, dp);
    pushTest(rec, y + 1);
    const std::int32_t tris[4] = {tri(c), tp, tri(d), tp + 1};
    notifyChanged(tris, 4);
}

// Flip the edge A-B opposite corner c (at the new vertex P) in place:
//
//            B                        B
//          / | `.                   /   `.
//         P  |  D       ==>        P ----- D      the edge A-B becomes P-D
//          `.| /                    `.   /
//            A                        A
//   t = (P, A, B) -> (P, A, D)      u = (D, B, A) -> (D, B, P)
// Only V[p(c)], V[p(d)] and the O of c, n(c), d, n(d) (plus two back-pointers) change.
template <class Rec>
void Inserter::flip(Rec& rec, std::int32_t c) {
    const std::int32_t d = m_mesh.O[c];
    DLAB_ASSERT(d != kNone && m_mesh.O[d] == c, "flip of corners that are not opposite");
    DLAB_ASSERT(tri(c) != tri(d), "flip of two corners of one triangle");
    const std::int32_t cn = next(c), cp = prev(c), dn = next(d), dp = prev(d);
    const std::int32_t P = m_mesh.V[c], D = m_mesh.V[d];
    const std::int32_t ocn = m_mesh.O[cn], odn = m_mesh.O[dn];
    setV(rec, cp, D);
    setV(rec, dp, P);
    link(rec, c, odn);
    link(rec, d, ocn);
    link(rec, cn, dn);
    if (m_repair) {
        // Lawson: the four edges around the new one may have stopped being Delaunay.
        for (const std::int32_t e : {c, cp, d, dp})
            if (m_mesh.O[e] != kNone) pushTest(rec, e);
    } else {
        pushTest(rec, c);  // the two edges facing the new vertex
        pushTest(rec, dp);
    }
    const std::int32_t tris[2] = {tri(c), tri(d)};
    notifyChanged(tris, 2);
}

// The flip algorithm's start: the given triangles, and every interior edge on the stack. Only
// the phase of the control state changes (so the tests and flips that follow recover it from
// the snapshot before Start, as they do from a Place op's).
template <class Rec>
void Inserter::doStartRepair(Rec& rec, Op& op) {
    const std::int32_t corners = static_cast<std::int32_t>(m_start.V.size());
    appendTriangles(rec, corners / 3);
    for (std::int32_t c = 0; c < corners; ++c) setV(rec, c, m_start.V[c]);
    for (std::int32_t c = 0; c < corners; ++c) setO(rec, c, m_start.O[c]);
    for (std::int32_t c = 0; c < corners; ++c)
        if (m_start.flip && m_start.O[c] > c) pushTest(rec, c);
    op.a = corners / 3;
    m_ctl.phase = m_stack.empty() ? Phase::Finalize : Phase::Test;
}

// The lower input index of two equal points stays the vertex: rename it around its star.
template <class Rec>
void Inserter::keepFirstOccurrence(Rec& rec, std::int32_t cornerAt, std::int32_t v) {
    const std::int32_t existing = m_mesh.V[cornerAt];
    if (inputId(v) > inputId(existing)) {
        m_skipped.push_back(inputId(v));
        return;
    }
    m_skipped.push_back(inputId(existing));
    forEachCornerAround(m_mesh.O, cornerAt, [&](std::int32_t c) { setV(rec, c, v); });
}

// The stars of the virtual vertices, sorted. A corner of each is found by scanning back from
// the newest triangles: the hull changes until the end, so the scan stops early.
std::vector<std::int32_t> Inserter::virtualTriangles() const {
    const auto& V = m_mesh.V;
    const std::int32_t numVirtual = m_mesh.numVertices() - m_numInput;
    std::vector<std::int32_t> cornerOf(static_cast<std::size_t>(std::max(numVirtual, 0)), kNone);
    std::int32_t missing = numVirtual;
    for (std::int32_t c = m_mesh.numCorners() - 1; c >= 0 && missing > 0; --c) {
        if (isVirtual(V[c]) && cornerOf[V[c] - m_numInput] == kNone) {
            cornerOf[V[c] - m_numInput] = c;
            --missing;
        }
    }
    std::vector<std::int32_t> tris;
    for (const std::int32_t start : cornerOf) {
        if (start != kNone)
            forEachCornerAround(m_mesh.O, start, [&](std::int32_t c) { tris.push_back(tri(c)); });
    }
    std::sort(tris.begin(), tris.end());
    tris.erase(std::unique(tris.begin(), tris.end()), tris.end());
    return tris;
}

// ============================================================================================
// [SECTION] Predicates with the ghost vertex
// ============================================================================================

bool Inserter::onOpenSegment(Vec2 a, Vec2 b, Vec2 p) const {
    // p is known to be collinear with a and b.
    if (a.x != b.x) return (a.x < p.x && p.x < b.x) || (b.x < p.x && p.x < a.x);
    return (a.y < p.y && p.y < b.y) || (b.y < p.y && p.y < a.y);
}

// Sign of "the new vertex V[c] lies inside the circle of the triangle across the edge opposite
// c": +1 flip, 0 cocircular (no flip), -1 Delaunay (also for a boundary edge).
// Inlined: the flip loop runs it nine times per point.
template <class Rec>
[[gnu::always_inline]] inline int Inserter::inCircleSign(Rec& rec, std::int32_t c) const {
    const std::int32_t d = m_mesh.O[c];
    if (d == kNone) return -1;
    const auto& G = m_mesh.G;
    const std::int32_t P = m_mesh.V[c];
    std::int32_t D = m_mesh.V[d], B = m_mesh.V[next(d)], A = m_mesh.V[prev(d)];
    const bool ghostMode = m_options.boundary == Boundary::Exact;
    if (!ghostMode || (!isVirtual(D) && !isVirtual(B) && !isVirtual(A))) {
        return rec.inCircle(PredicateAsk::InCircle, G[D], G[B], G[A], G[P], Ids4{D, B, A, P}, c);
    }
    // Ghost triangle (u, w, g): its circle is the open half-plane left of w->u... i.e. the side
    // of the hull edge away from the mesh, plus the open segment u-w itself.
    std::int32_t u, w;
    if (isVirtual(D)) {
        u = B;
        w = A;
    } else if (isVirtual(B)) {
        u = A;
        w = D;
    } else {
        u = D;
        w = B;
    }
    const int s = rec.orient(PredicateAsk::GhostCircle, G[u], G[w], G[P], Ids3{u, w, P}, c);
    // P on the open hull edge u-w cannot happen: the walk finds a point on a hull edge (from the
    // triangle inside with a zero side, or from the ghost outside with orient2d 0 on the open
    // segment) and splits that edge, so the edge no longer exists when P's flips test it, and
    // every other point is on it only if it was located there. Were it reachable, P would be in
    // the ghost's "circle" (the open segment belongs to it) and the answer 1.
    DLAB_ASSERT(s != 0 || !onOpenSegment(G[u], G[w], G[P]),
                "new vertex on a hull edge that should have been split");
    return s > 0 ? 1 : -1;
}

// ============================================================================================
// [SECTION] Walking (the paper's line walk, with a visibility-walk fallback)
// ============================================================================================

// A ghost triangle 3t..3t+2 (exact mode): its ghost corner's index and the hull edge x->y
// opposite it.
Inserter::HullEdge Inserter::hullEdgeOf(std::int32_t c0) const {
    const auto& V = m_mesh.V;
    int k = 0;
    while (!isVirtual(V[c0 + k])) ++k;
    return {k, m_mesh.G[V[c0 + kNext[k]]], m_mesh.G[V[c0 + kPrev[k]]]};
}

void Inserter::beginLocate() {
    std::int32_t t = m_locator->hint(currentPoint(), m_ctl.lastTri);
    if (t < 0 || t >= m_mesh.numTriangles()) t = 0;
    m_ctl.walk = walkFrom(t, m_ctl.walk);
    m_ctl.where = Where::None;
    m_ctl.whereCorner = kNone;
}

Inserter::Query Inserter::currentQuery() const {
    const std::int32_t v = vertexAt(m_ctl.cursor);
    return {v, m_mesh.G[v]};
}

// The start triangle of the line walk: L runs from q, the centroid, to p. When q is strictly
// inside t, L leaves t through one edge (its start right of L, its end left) and p on L not
// beyond that edge lies in the closed triangle, so one test of p decides. Returns false when q
// is not strictly inside (a needle): then the visibility walk takes over, with L's origin kept.
template <class Rec>
[[gnu::always_inline]] inline Inserter::StartStep Inserter::walkStart(Rec& rec, WalkState& w,
                                                                      Query p,
                                                                      KnownSides& known) const {
    const auto& G = m_mesh.G;
    const auto& V = m_mesh.V;
    const std::int32_t c0 = 3 * w.tri;
    const Ids3 id = {V[c0], V[c0 + 1], V[c0 + 2]};
    const Vec2 v[3] = {G[id[0]], G[id[1]], G[id[2]]};
    const Vec2 q{v[0].x / 3 + v[1].x / 3 + v[2].x / 3, v[0].y / 3 + v[1].y / 3 + v[2].y / 3};
    constexpr PredicateAsk kCentroid = PredicateAsk::StartCentroid;
    if (!(rec.orient(kCentroid, v[0], v[1], q, Ids3{id[0], id[1], kNone}, c0 + 2) > 0 &&
          rec.orient(kCentroid, v[1], v[2], q, Ids3{id[1], id[2], kNone}, c0) > 0 &&
          rec.orient(kCentroid, v[2], v[0], q, Ids3{id[2], id[0], kNone}, c0 + 1) > 0)) {
        return StartStep::Undecided;
    }
    // Only one edge goes from right of L to left of L (three vertices in a cycle): when v0 is
    // right and v1 left it is v0->v1 (opposite corner 2), and v2 needs no test.
    // (Written out, not a lambda: GCC does not inline a lambda into the batch loop.)
    constexpr PredicateAsk kLine = PredicateAsk::LineSide;
    const bool left0 = rec.orient(kLine, q, p.p, v[0], Ids3{kNone, p.v, id[0]}, c0) >= 0;
    const bool left1 = rec.orient(kLine, q, p.p, v[1], Ids3{kNone, p.v, id[1]}, c0 + 1) >= 0;
    int k = 2;
    if (left0 || !left1) {
        const bool left[3] = {
            left0, left1, rec.orient(kLine, q, p.p, v[2], Ids3{kNone, p.v, id[2]}, c0 + 2) >= 0};
        for (k = 0; k < 3 && !(!left[kNext[k]] && left[kPrev[k]]); ++k) {}
        // No exit edge: p == q (both sides of L hold a vertex of a triangle around q
        // otherwise), strictly inside t; the side tests say so.
        if (k == 3) return StartStep::Undecided;
    }
    const int s = rec.orient(PredicateAsk::ExitEdge, v[kNext[k]], v[kPrev[k]], p.p,
                             Ids3{id[kNext[k]], id[kPrev[k]], p.v}, c0 + k);
    if (s >= 0) {
        walkFound(known, w.tri, c0 + k, s, kNone, 0);
        return StartStep::Found;
    }
    w.origin = q;
    walkMove<Rec>(w, c0 + k, true);
    return StartStep::Moved;
}

[[gnu::always_inline]] inline bool Inserter::walkFound(KnownSides& known, std::int32_t t,
                                                       std::int32_t c1, int s1, std::int32_t c2,
                                                       int s2) {
    known = {t, {kUnknownSide, kUnknownSide, kUnknownSide}};
    if (c1 != kNone) known.side[c1 - 3 * t] = static_cast<std::int8_t>(s1);
    if (c2 != kNone) known.side[c2 - 3 * t] = static_cast<std::int8_t>(s2);
    return true;
}

template <class Rec>
[[gnu::always_inline]] inline bool Inserter::walkMove(WalkState& w, std::int32_t corner,
                                                      bool keepEntry) const {
    const std::int32_t o = m_mesh.O[corner];
    DLAB_ASSERT(o != kNone, "the walk leaves the mesh");
#if DLAB_CHECKS_ON
    // A straight walk crosses each triangle at most once (its line meets a triangle in one
    // segment): a revisit means inconsistent orientation decisions. The list restarts with every
    // line (the start triangle, or inside again after a ghost) and with another point or inserter.
    // A step made again for its predicate calls is no step of the walk.
    static thread_local struct {
        const Inserter* owner = nullptr;
        std::int32_t cursor = kNone;
        std::vector<std::int32_t> tris;
    } visited;
    if (!Rec::kReplay &&
        (visited.owner != this || visited.cursor != m_ctl.cursor || w.entry == kNone)) {
        visited.owner = this;
        visited.cursor = m_ctl.cursor;
        visited.tris.assign(1, w.tri);
    }
    if (!Rec::kReplay && w.straight && keepEntry) {
        DLAB_ASSERT(
            std::find(visited.tris.begin(), visited.tris.end(), tri(o)) == visited.tris.end(),
            "the straight walk enters a triangle it has left");
        visited.tris.push_back(tri(o));
    }
#endif
    w.tri = tri(o);
    w.entry = keepEntry ? o : kNone;
    ++w.steps;
    return false;
}

// One step: true when w.tri contains the point (closed); otherwise moves to a neighbour.
//
// The line walk follows L from q (inside the start triangle) to p. Entering triangle t through
// the edge opposite corner e, its third vertex w = V[e] is left or right of L: L leaves through
// the edge on the far side of w (c.l or c.r in the paper). A vertex exactly on L counts as left,
// the same as moving L an infinitesimal amount to the right, so every decision stays consistent.
// A step in the line walk costs two orientation tests: the edge it entered through is never
// tested again (p is strictly beyond it, seen from the triangle before).
template <class Rec>
[[gnu::always_inline]] inline bool Inserter::walkOnce(Rec& rec, WalkState& w, Query p,
                                                      KnownSides& known) const {
    const auto& G = m_mesh.G;
    const auto& V = m_mesh.V;
    const std::int32_t t = w.tri;
    const std::int32_t c0 = 3 * t;
    known.tri = kNone;

    // Corners are c0 + k; the edge opposite c0 + k runs from c0 + kNext[k] to c0 + kPrev[k]
    // (index arithmetic instead of next()/prev(), whose % 3 costs more than the rest of a step).
    if (m_options.boundary == Boundary::Exact && isVirtualTriangle(t)) {
        const auto [k, x, y] = hullEdgeOf(c0);
        const std::int32_t g = c0 + k;
        const int s = rec.orient(PredicateAsk::HullEdge, x, y, p.p,
                                 Ids3{V[c0 + kNext[k]], V[c0 + kPrev[k]], p.v}, g);
        if (s > 0 || (s == 0 && (onOpenSegment(x, y, p.p) || p.p == x || p.p == y))) {
            return walkFound(known, t, g, s, kNone, 0);
        }
        // Not beyond this hull edge: restart the walk inside the mesh, across the edge.
        return walkMove<Rec>(w, g, false);
    }

    // We entered t across the edge opposite w.entry because p is strictly beyond it: seen
    // from t, p is strictly inside that edge (orient2d is exact, hence antisymmetric).
    const std::int32_t entry = w.entry;
    if (w.straight && entry != kNone) {
        const int k = entry - c0;
        const Ids3 id = {V[entry], V[c0 + kNext[k]], V[c0 + kPrev[k]]};
        const Vec2 a = G[id[0]], b = G[id[1]], c = G[id[2]];
        const bool left = rec.orient(PredicateAsk::LineSide, w.origin, p.p, a,
                                     Ids3{kNone, p.v, id[0]}, entry) >= 0;
        // Left: L leaves through the edge p(e)->e (opposite n(e)); right: e->n(e) (opposite p(e)).
        const std::int32_t exitCorner = c0 + (left ? kNext[k] : kPrev[k]);
        const Vec2 from = left ? c : a, to = left ? a : b;
        const Ids3 edge = {left ? id[2] : id[0], left ? id[0] : id[1], p.v};
        const int s = rec.orient(PredicateAsk::ExitEdge, from, to, p.p, edge, exitCorner);
        if (s < 0) return walkMove<Rec>(w, exitCorner, true);
        return walkFound(known, t, entry, 1, exitCorner, s);
    }
    if (w.straight) {
        const StartStep start = walkStart(rec, w, p, known);
        if (start != StartStep::Undecided) return start == StartStep::Found;
    }

    // The visibility walk (or a start triangle whose centroid test failed): every side but the
    // one we came through.
    int side[3];
    for (int k = 0; k < 3; ++k) {
        const std::int32_t c = c0 + k, a = V[c0 + kNext[k]], b = V[c0 + kPrev[k]];
        side[k] = c == entry ? 1
                             : rec.orient(PredicateAsk::VisibilityEdge, G[a], G[b], p.p,
                                          Ids3{a, b, p.v}, c);
    }
    if (side[0] >= 0 && side[1] >= 0 && side[2] >= 0) {
        known = {t,
                 {static_cast<std::int8_t>(side[0]), static_cast<std::int8_t>(side[1]),
                  static_cast<std::int8_t>(side[2])}};
        return true;
    }
    w.straight = false;  // needle triangle or a degenerate case: walk by visibility
    for (int k = 0; k < 3; ++k) {
        if (side[k] < 0) return walkMove<Rec>(w, c0 + k, true);
    }
    return true;
}

template <class Rec>
bool Inserter::walk(Rec& rec, bool oneStep, KnownSides& known) {
    const Query p = currentQuery();
    WalkState w = m_ctl.walk;  // a local copy: the batch path keeps it in registers
    bool found = walkOnce(rec, w, p, known);
    while (!found && !oneStep) found = walkOnce(rec, w, p, known);
    m_ctl.walk = w;
    return found;
}

template <class Rec>
Inserter::Placement Inserter::classify(Rec& rec, std::int32_t t, Query p,
                                       const KnownSides& known) const {
    const auto& G = m_mesh.G;
    const auto& V = m_mesh.V;
    const std::int32_t c0 = 3 * t;
    // The side of p for the edge opposite c0 + k: from the walk when it knows it.
    auto sideOf = [&](PredicateAsk ask, int k) {
        const std::int32_t a = V[c0 + kNext[k]], b = V[c0 + kPrev[k]];
        return known.tri == t && known.side[k] != kUnknownSide
                   ? int{known.side[k]}
                   : rec.orient(ask, G[a], G[b], p.p, Ids3{a, b, p.v}, c0 + k);
    };
    if (m_options.boundary == Boundary::Exact && isVirtualTriangle(t)) {
        const auto [k, x, y] = hullEdgeOf(c0);
        const int s = sideOf(PredicateAsk::ClassifyHull, k);
        if (s > 0) return {Where::Outside, c0 + k};
        if (s == 0 && p.p == x) return {Where::OnVertex, c0 + kNext[k]};
        if (s == 0 && p.p == y) return {Where::OnVertex, c0 + kPrev[k]};
        if (s == 0 && onOpenSegment(x, y, p.p)) return {Where::OnEdge, c0 + k};
        return {};
    }
    int side[3], zeros = 0;
    for (int k = 0; k < 3; ++k) {
        side[k] = sideOf(PredicateAsk::ClassifyEdge, k);
        if (side[k] < 0) return {};
        zeros += side[k] == 0;
    }
    if (zeros == 0) return {Where::InTriangle, c0};
    if (zeros == 1) return {Where::OnEdge, c0 + (side[0] == 0 ? 0 : side[1] == 0 ? 1 : 2)};
    return {Where::OnVertex, c0 + (side[0] != 0 ? 0 : side[1] != 0 ? 1 : 2)};
}

// ============================================================================================
// [SECTION] The state machine: one operation per step
// ============================================================================================

template <class Rec>
void Inserter::doStart(Rec& rec, Op& op) {
    const std::int32_t n = m_numInput;
    if (m_options.boundary == Boundary::Super) {
        appendTriangles(rec, 1);
        setV(rec, 0, n);
        setV(rec, 1, n + 1);
        setV(rec, 2, n + 2);
        m_ctl.cursor = 0;
    } else {
        const int sign = firstTriangleSign(rec);
        if (sign == 0) {
            // Fewer than three points, or all collinear: there is no triangle to make. Equal
            // points are still reported, as the triangulating path would.
            collectDuplicatesWithoutMesh();
            m_ctl.cursor = n;
            m_ctl.phase = Phase::Finalize;
            op.a = kNone;
            return;
        }
        std::int32_t a = vertexAt(0), b = vertexAt(1), c = vertexAt(2);
        if (sign < 0) std::swap(b, c);
        const std::int32_t g = n;
        appendTriangles(rec, 4);
        // t0 = (a, b, c); ghosts t1 = (b, a, g), t2 = (c, b, g), t3 = (a, c, g).
        const std::int32_t vs[12] = {a, b, c, b, a, g, c, b, g, a, c, g};
        for (int k = 0; k < 12; ++k) setV(rec, k, vs[k]);
        link(rec, 2, 5);
        link(rec, 0, 8);
        link(rec, 1, 11);  // finite edges <-> ghosts
        link(rec, 3, 10);
        link(rec, 4, 6);
        link(rec, 7, 9);  // ghost edges to g
        m_ctl.cursor = 3;
        m_stats.inserted += 3;
    }
    op.a = 0;
    LocatorContext ctx{&m_mesh, m_numInput, m_options.boundary == Boundary::Exact,
                       static_cast<std::size_t>(m_numInput)};
    m_locator->reset(ctx, m_bounds);
    m_locatorWantsChanges = m_locator->wantsChanges();
    m_ctl.lastTri = 0;
    m_ctl.phase = m_ctl.cursor < n ? Phase::Locate : Phase::Finalize;
}

template <class Rec>
int Inserter::firstTriangleSign(Rec& rec) const {
    if (m_numInput < 3) return 0;
    const auto& G = m_mesh.G;
    const std::int32_t a = vertexAt(0), b = vertexAt(1), c = vertexAt(2);
    return rec.orient(PredicateAsk::FirstTriangle, G[a], G[b], G[c], Ids3{a, b, c}, kNone);
}

void Inserter::collectDuplicatesWithoutMesh() {
    const auto& G = m_mesh.G;
    std::vector<std::int32_t> ids(static_cast<std::size_t>(m_numInput));
    for (std::int32_t v = 0; v < m_numInput; ++v) ids[v] = v;
    std::sort(ids.begin(), ids.end(), [&](std::int32_t a, std::int32_t b) {
        if (G[a].x != G[b].x) return G[a].x < G[b].x;
        if (G[a].y != G[b].y) return G[a].y < G[b].y;
        return inputId(a) < inputId(b);
    });
    m_skipped.clear();
    for (std::size_t i = 1; i < ids.size(); ++i) {
        if (G[ids[i]] == G[ids[i - 1]]) m_skipped.push_back(inputId(ids[i]));
    }
    std::sort(m_skipped.begin(), m_skipped.end());
    m_stats.duplicates = static_cast<std::int64_t>(m_skipped.size());
}

template <class Rec>
void Inserter::doPlace(Rec& rec, Op& op) {
    const std::int32_t v = vertexAt(m_ctl.cursor);
    const std::int32_t c = m_ctl.whereCorner;
    op.where = m_ctl.where;
    switch (m_ctl.where) {
        case Where::InTriangle:
        case Where::Outside:
            op.type = OpType::Split;
            op.a = tri(c);
            split(rec, tri(c), v);
            break;
        case Where::OnEdge:
            op.type = OpType::SplitEdge;
            op.a = c;
            op.b = m_mesh.O[c];
            splitEdge(rec, c, v);
            break;
        default:
            op.type = OpType::SkipDuplicate;
            op.a = c;
            op.b = m_mesh.V[c];
            keepFirstOccurrence(rec, c, v);
            ++m_ctl.cursor;
            m_ctl.walk.tri = kNone;
            m_ctl.phase = m_ctl.cursor < m_numInput ? Phase::Locate : Phase::Finalize;
            return;
    }
    m_ctl.phase = Phase::Test;
}

template <class Rec>
void Inserter::doFinalize(Rec& rec, Op& op) {
    // Only the virtual triangles change: they are the stars of the virtual vertices (a few per
    // hull edge), found by turning around each virtual vertex. The last triangles fill their
    // slots (swap-remove), so the work is O(hull), not a pass over the whole mesh.
    auto& V = m_mesh.V;
    auto& O = m_mesh.O;
    const std::int32_t nt = m_mesh.numTriangles();
    const std::vector<std::int32_t> gone = virtualTriangles();
    const std::int32_t kept = nt - static_cast<std::int32_t>(gone.size());
    op.a = nt - kept;  // triangles removed
    // Cut the links from kept triangles into virtual ones: those edges are the boundary now.
    for (const std::int32_t t : gone) {
        for (std::int32_t c = 3 * t; c < 3 * t + 3; ++c) {
            const std::int32_t o = O[c];
            if (o != kNone && !isVirtualTriangle(tri(o))) setO(rec, o, kNone);
        }
    }
    // Kept triangles at or past the new end move, in increasing order, into the slots below it
    // that virtual triangles leave, in increasing order; their neighbours follow them.
    // (Both walk `gone` in increasing order: with every point on the hull it holds about n.)
    auto hole = gone.begin();
    auto next = std::lower_bound(gone.begin(), gone.end(), kept);
    for (std::int32_t s = kept; s < nt; ++s) {
        if (next != gone.end() && *next == s) {
            ++next;
            continue;
        }
        const std::int32_t t = *hole++;
        for (int k = 0; k < 3; ++k) {
            const std::int32_t o = O[3 * s + k];
            setV(rec, 3 * t + k, V[3 * s + k]);
            setO(rec, 3 * t + k, o);
            if (o != kNone) setO(rec, o, 3 * t + k);
        }
    }
    if constexpr (Rec::kOn) {
        // Cells past the new end disappear: record them so that undo can bring them back.
        for (std::int32_t c = 3 * kept; c < 3 * nt; ++c) {
            setV(rec, c, kNone);
            setO(rec, c, kNone);
        }
    }
    V.resize(3 * static_cast<std::size_t>(kept));
    O.resize(3 * static_cast<std::size_t>(kept));
    m_mesh.G.resize(m_numInput);
    m_ctl.phase = Phase::Done;
    // The kept triangles moved into the ghosts' slots: a recorded run's locator (the GUI shows
    // it) names them by their new ids.
    if constexpr (Rec::kOn) {
        if (m_locatorWantsChanges && !m_bulk) m_locator->resync();
    }
}

// Locate: one step of the walk, or the verdict once the walk stands on the point's triangle.
template <class Rec>
void Inserter::doLocate(Rec& rec, Op& op) {
    if (m_ctl.walk.tri == kNone) beginLocate();
    const std::int32_t from = m_ctl.walk.tri;
    op.a = from;
    KnownSides known;
    if (!walk(rec, true, known)) {
        op.type = OpType::LocateStep;
        op.b = m_ctl.walk.tri;
        return;
    }
    const Placement at = classify(rec, m_ctl.walk.tri, currentQuery(), known);
    m_ctl.where = at.where;
    m_ctl.whereCorner = at.corner;
    if (m_ctl.where == Where::None) {  // cannot happen with exact predicates; stay safe
        m_ctl.walk.straight = false;
        op.type = OpType::LocateStep;
        op.b = from;
        return;
    }
    op.type = OpType::Located;
    op.where = m_ctl.where;
    op.b = m_ctl.whereCorner;
    m_locator->located(currentPoint(), m_ctl.walk.tri, m_ctl.walk.steps);
    m_ctl.phase = Phase::Place;
}

// Test: the in-circle test of the edge on top of the flip stack; a positive sign flips it next.
template <class Rec>
void Inserter::doTest(Rec& rec, Op& op) {
    const std::int32_t c = m_stack.back();
    m_stack.pop_back();
    op.type = OpType::InCircleTest;
    op.a = c;
    op.b = m_mesh.O[c];
    op.sign = static_cast<std::int8_t>(inCircleSign(rec, c));
    if (op.sign > 0) {
        m_ctl.flipCorner = c;
        m_ctl.phase = Phase::Flip;
    } else {
        m_ctl.phase = !m_stack.empty() ? Phase::Test : m_repair ? Phase::Finalize : Phase::Finish;
    }
}

// Finish: the point is in and every edge around it is Delaunay; on to the next point.
void Inserter::doFinish(Op& op) {
    op.type = OpType::Inserted;
    // Flips keep the new vertex in both triangles they touch, so the last appended triangle
    // still has it: it is the next walk's start.
    const std::int32_t t = m_mesh.numTriangles() - 1;
    for (std::int32_t c = 3 * t; c < 3 * t + 3; ++c) {
        if (m_mesh.V[c] == op.vertex) op.a = c;
    }
    m_ctl.lastTri = t;
    ++m_ctl.cursor;
    m_ctl.walk.tri = kNone;
    m_ctl.phase = m_ctl.cursor < m_numInput ? Phase::Locate : Phase::Finalize;
}

template <class Rec>
Op Inserter::stepImpl(Rec& rec) {
    Op op;
    op.vertex = currentVertex();
    op.trianglesBefore = m_mesh.numTriangles();
    op.verticesBefore = m_mesh.numVertices();
    switch (m_ctl.phase) {
        case Phase::Start:
            op.type = OpType::Start;
            if (m_repair) {
                doStartRepair(rec, op);
            } else {
                doStart(rec, op);
            }
            break;
        case Phase::Locate: doLocate(rec, op); break;
        case Phase::Place: doPlace(rec, op); break;
        case Phase::Test: doTest(rec, op); break;
        case Phase::Flip:
            op.type = OpType::Flip;
            op.a = m_ctl.flipCorner;
            op.b = m_mesh.O[op.a];
            flip(rec, op.a);
            m_ctl.flipCorner = kNone;
            m_ctl.phase = !m_stack.empty() ? Phase::Test : Phase::Finalize;
            break;
        case Phase::Finish: doFinish(op); break;
        case Phase::Finalize:
            op.type = OpType::Finalize;
            if (m_repair) {  // no virtual triangle: only the ghost vertex's placeholder goes
                op.a = 0;
                m_mesh.G.resize(m_numInput);
                m_ctl.phase = Phase::Done;
            } else {
                doFinalize(rec, op);
            }
            break;
        case Phase::Done: throw std::logic_error("Inserter::step called after the end");
    }
    op.trianglesAfter = m_mesh.numTriangles();
    op.verticesAfter = m_mesh.numVertices();
    countOp(m_stats, op, +1);
    return op;
}

Op Inserter::step(Journal* journal, std::vector<RecordedPredicateCall>* calls) {
    JournalRec rec;
    rec.journal = journal;
    rec.calls = calls;
    const std::uint32_t first = journal ? journal->changeCount() : 0;
    const std::size_t firstPush = journal ? journal->pushCount() : 0;
    const Control before = m_ctl;
    Op op = stepImpl(rec);
    if (journal) {
        op.firstChange = first;
        op.numChanges = journal->changeCount() - first;
        const std::size_t pushed = journal->pushCount() - firstPush;
        if (pushed < kPushesInB) {
            op.pushes = static_cast<std::uint8_t>(pushed);
        } else {
            DLAB_ASSERT(op.type == OpType::Start && op.b == kNone,
                        "only the flip algorithm's Start queues that many edges");
            op.pushes = kPushesInB;
            op.b = static_cast<std::int32_t>(pushed);
        }
        journal->push(op, before);
    }
    return op;
}

std::vector<RecordedPredicateCall> Inserter::predicateCallsOf(const Op& op,
                                                              const Control& before) const {
    std::vector<RecordedPredicateCall> calls;
    ReplayRec rec;
    rec.calls = &calls;
    switch (op.type) {
        case OpType::Start:
            if (m_options.boundary == Boundary::Exact && !m_repair) firstTriangleSign(rec);
            break;
        case OpType::LocateStep:
        case OpType::Located: {
            // As doLocate: one walk step from where the walk stood (or from the hint, which is
            // the op's start triangle) and, where it stops, the classification.
            WalkState w = before.walk.tri == kNone ? walkFrom(op.a, before.walk) : before.walk;
            const std::int32_t v = vertexAt(before.cursor);
            const Query p{v, m_mesh.G[v]};
            KnownSides known;
            if (walkOnce(rec, w, p, known)) classify(rec, w.tri, p, known);
            break;
        }
        case OpType::InCircleTest: inCircleSign(rec, op.a); break;
        default: break;
    }
    return calls;
}

// ============================================================================================
// [SECTION] The batch path: the same primitives, no records, no per-op dispatch
// ============================================================================================

// The batch path stores the points in insertion order while it runs (vertex id = rank), so
// that consecutive insertions touch neighbouring memory: with BRIO/Hilbert order this halves
// the cache misses of a million-point run. The points in input order are kept aside (G never
// changes during a run) and put back at the end, where the ids are mapped back, so the result
// is bit for bit the one the recorded path makes.
void Inserter::permuteForBatch(std::vector<std::int32_t> names) {
    const std::int32_t n = m_numInput;
    std::vector<Vec2> byRank;
    byRank.reserve(m_mesh.G.size());
    adviseHugePages(byRank.data(), m_mesh.G.size() * sizeof(Vec2));
    for (std::int32_t k = 0; k < n; ++k) byRank.push_back(m_mesh.G[m_order[k]]);
    byRank.insert(byRank.end(), m_mesh.G.begin() + n, m_mesh.G.end());
    if (m_keepPoints) m_byInput = std::move(m_mesh.G);
    m_mesh.G = std::move(byRank);
    m_permuted = true;
    // From here on m_order only names the vertices (inputId, unpermute): the caller's names
    // keep every comparison between input indices, and the result carries them.
    if (!names.empty()) {
        for (std::int32_t& i : m_order) i = names[i];
    }
}

void Inserter::unpermute() {
    const std::int32_t n = m_numInput;
    const std::size_t size = m_mesh.G.size();  // Finalize may have dropped the virtual points
    m_mesh.G = std::move(m_byInput);
    m_byInput = {};
    if (m_keepPoints) m_mesh.G.resize(size);
    for (std::int32_t& v : m_mesh.V) {
        if (v < n) v = m_order[v];
    }
    m_ctl.lastTri = 0;
    m_permuted = false;
}

void Inserter::reserveTriangles(std::size_t count) {
    const std::size_t corners = 3 * count;
    if (m_mesh.V.capacity() >= corners) return;
    m_mesh.V.reserve(corners);
    m_mesh.O.reserve(corners);
    adviseHugePages(m_mesh.V.data(), corners * sizeof(std::int32_t));
    adviseHugePages(m_mesh.O.data(), corners * sizeof(std::int32_t));
}

void Inserter::runForTopology(std::vector<std::int32_t> names) {
    DLAB_ASSERT(names.empty() || (m_ctl.phase == Phase::Start &&
                                  names.size() == static_cast<std::size_t>(m_numInput)),
                "names for a run that has begun, or not one a point");
    m_keepPoints = m_ctl.phase != Phase::Start;  // only a run from the start works by rank
    if (!m_keepPoints) permuteForBatch(std::move(names));
    run();
    m_mesh.G = std::vector<Vec2>();  // (= {} would keep the capacity)
    m_keepPoints = true;
}

void Inserter::run() {
    NullRec rec;
    if (m_repair) {
        while (m_ctl.phase != Phase::Done) stepImpl(rec);
        return;
    }
    if (m_ctl.phase == Phase::Start && !m_permuted) permuteForBatch({});
    // Finish whatever the state machine was in the middle of.
    while (m_ctl.phase != Phase::Done &&
           !(m_ctl.phase == Phase::Locate && m_ctl.walk.tri == kNone)) {
        if (m_ctl.phase == Phase::Finalize) break;
        stepImpl(rec);
    }
    const std::int32_t n = m_numInput;
    if (m_ctl.phase == Phase::Locate) {
        reserveTriangles(maxTriangles(static_cast<std::size_t>(n)));
        m_stack.reserve(64);
        for (; m_ctl.cursor < n; ++m_ctl.cursor) {
            if (m_ctl.cursor % kProgressEvery == 0 && m_progress) m_progress(m_ctl.cursor);
            beginLocate();
            while (true) {
                KnownSides known;
                walk(rec, false, known);
                const Placement at = classify(rec, m_ctl.walk.tri, currentQuery(), known);
                m_ctl.where = at.where;
                m_ctl.whereCorner = at.corner;
                if (m_ctl.where != Where::None) break;
                m_ctl.walk.straight = false;
            }
            m_stats.walkSteps += m_ctl.walk.steps;
            m_locator->located(currentPoint(), m_ctl.walk.tri, m_ctl.walk.steps);
            // Permuted (a batch from the start): vertex id = insertion rank; a run finishing a
            // recorded one mid-way keeps the input ids.
            const std::int32_t v = vertexAt(m_ctl.cursor);
            const std::int32_t c = m_ctl.whereCorner;
            if (m_ctl.where == Where::OnVertex) {
                keepFirstOccurrence(rec, c, v);
                ++m_stats.duplicates;
                continue;
            }
            if (m_ctl.where == Where::OnEdge) {
                splitEdge(rec, c, v);
                ++m_stats.edgeSplits;
            } else {
                split(rec, tri(c), v);
            }
            while (!m_stack.empty()) {
                const std::int32_t e = m_stack.back();
                m_stack.pop_back();
                ++(m_mesh.O[e] != kNone ? m_stats.inCircleTests : m_stats.boundaryPops);
                if (inCircleSign(rec, e) > 0) {
                    flip(rec, e);
                    ++m_stats.flips;
                }
            }
            m_ctl.lastTri = m_mesh.numTriangles() - 1;
            ++m_stats.inserted;
        }
        m_ctl.walk.tri = kNone;
        m_ctl.phase = Phase::Finalize;
    }
    if (m_ctl.phase == Phase::Finalize) {
        Op op;
        doFinalize(rec, op);
    }
    if (m_permuted) unpermute();
}

// ============================================================================================
// [SECTION] Undo / redo of recorded ops
// ============================================================================================

void Inserter::undo(const Op& op, const std::vector<CellChange>& changes,
                    std::span<const std::int32_t> pushes, const Control& before) {
    const std::size_t big =
        3 * static_cast<std::size_t>(std::max(op.trianglesBefore, op.trianglesAfter));
    m_mesh.V.resize(big, kNone);
    m_mesh.O.resize(big, kNone);
    for (std::uint32_t i = op.numChanges; i-- > 0;) {
        const CellChange& ch = changes[op.firstChange + i];
        (ch.isO() ? m_mesh.O : m_mesh.V)[ch.corner()] = ch.before;
    }
    m_mesh.V.resize(3 * static_cast<std::size_t>(op.trianglesBefore));
    m_mesh.O.resize(3 * static_cast<std::size_t>(op.trianglesBefore));
    if (op.verticesBefore > m_mesh.numVertices()) {
        m_mesh.G.insert(m_mesh.G.end(), m_virtualPoints.begin(), m_virtualPoints.end());
    }
    DLAB_ASSERT(pushes.size() == pushCount(op) && m_stack.size() >= pushes.size() &&
                    std::equal(pushes.begin(), pushes.end(), m_stack.end() - pushes.size()),
                "undo of an op whose flip-stack pushes are not on top of the stack");
    m_stack.resize(m_stack.size() - pushes.size());
    if (op.type == OpType::InCircleTest) m_stack.push_back(op.a);  // the test popped it
    countOp(m_stats, op, -1);
    if (op.type == OpType::Start) {
        m_stats = {};
        m_skipped.clear();
    }
    if (op.type == OpType::SkipDuplicate) m_skipped.pop_back();
    m_ctl = before;
    notifyReplayed(op, changes);
}

// After an undo or redo: the triangles the op touched repaint (the ones it removed too: they
// take their ids off the locator's cells). Finalize renumbers the triangles: resync instead.
void Inserter::notifyReplayed(const Op& op, const std::vector<CellChange>& changes) {
    if (!m_locatorWantsChanges || m_bulk) return;
    if (op.type == OpType::Finalize) {
        m_locator->resync();
        return;
    }
    std::vector<std::int32_t> tris;
    for (std::uint32_t i = 0; i < op.numChanges; ++i)
        tris.push_back(tri(changes[op.firstChange + i].corner()));
    std::sort(tris.begin(), tris.end());
    tris.erase(std::unique(tris.begin(), tris.end()), tris.end());
    notifyChanged(tris.data(), static_cast<int>(tris.size()));
}

void Inserter::redo(const Op& op, const std::vector<CellChange>& changes,
                    std::span<const std::int32_t> pushes, const Control& after) {
    const std::size_t big =
        3 * static_cast<std::size_t>(std::max(op.trianglesBefore, op.trianglesAfter));
    m_mesh.V.resize(big, kNone);
    m_mesh.O.resize(big, kNone);
    for (std::uint32_t i = 0; i < op.numChanges; ++i) {
        const CellChange& ch = changes[op.firstChange + i];
        (ch.isO() ? m_mesh.O : m_mesh.V)[ch.corner()] = ch.after;
    }
    m_mesh.V.resize(3 * static_cast<std::size_t>(op.trianglesAfter));
    m_mesh.O.resize(3 * static_cast<std::size_t>(op.trianglesAfter));
    if (op.verticesAfter < m_mesh.numVertices()) m_mesh.G.resize(op.verticesAfter);
    if (op.type == OpType::InCircleTest) {
        DLAB_ASSERT(!m_stack.empty() && m_stack.back() == op.a,
                    "redo of an in-circle test whose edge is not on top of the flip stack");
        m_stack.pop_back();
    }
    DLAB_ASSERT(pushes.size() == pushCount(op), "redo with another op's flip-stack pushes");
    m_stack.insert(m_stack.end(), pushes.begin(), pushes.end());
    countOp(m_stats, op, +1);
    if (op.type == OpType::Start && !m_repair) {
        if (m_options.boundary == Boundary::Exact && op.a != kNone) m_stats.inserted += 3;
        if (op.a == kNone) collectDuplicatesWithoutMesh();
    }
    if (op.type == OpType::SkipDuplicate) m_skipped.push_back(std::max(op.vertex, op.b));
    m_ctl = after;
    notifyReplayed(op, changes);
}

// ============================================================================================
// [SECTION] Journal
// ============================================================================================

void Journal::push(Op op, const Control& before) {
    if (hasControlSnapshot(op.type)) {
        op.control = static_cast<std::uint32_t>(m_controls.size());
        m_controls.push_back(before);
    } else {
        // Back to this insertion's Place op: the ops between are tests, flips and Inserted.
        std::size_t place = m_ops.size();
        while (place > 0 && !hasControlSnapshot(m_ops[place - 1].type)) --place;
        op.control = static_cast<std::uint32_t>(m_ops.size() - (place - 1));
    }
    m_ops.push_back(op);
    ++m_pos;
    m_pushEnd = m_pushes.size();
}

namespace {
Phase phaseBefore(OpType t) {
    switch (t) {
        case OpType::InCircleTest: return Phase::Test;
        case OpType::Flip: return Phase::Flip;
        case OpType::Inserted: return Phase::Finish;
        default: return Phase::Place;
    }
}
}  // namespace

Control Journal::controlBefore(std::size_t i) const {
    const Op& op = m_ops[i];
    if (hasControlSnapshot(op.type)) return m_controls[op.control];
    // After the Place op (a split: SkipDuplicate is followed by a walk or Finalize) only the
    // phase and the flip corner change until the next point.
    Control c = m_controls[m_ops[i - op.control].control];
    c.phase = phaseBefore(op.type);
    c.flipCorner = op.type == OpType::Flip ? op.a : kNone;
    return c;
}

std::vector<RecordedPredicateCall> Journal::predicateCallsOf(std::size_t i) const {
    if (i >= m_ops.size() || (i + 1 != m_pos && i != m_pos)) {
        throw std::out_of_range("Journal::predicateCallsOf: op " + std::to_string(i) +
                                " is neither the current op nor the next one");
    }
    return m_ins->predicateCallsOf(m_ops[i], controlBefore(i));
}

const Op* Journal::forward() {
    if (m_pos < m_ops.size()) {
        const Op& op = m_ops[m_pos];
        const Control after = m_pos + 1 < m_ops.size() ? controlBefore(m_pos + 1) : m_tip;
        m_ins->redo(op, m_changes, {m_pushes.data() + m_pushEnd, dlab::pushCount(op)}, after);
        m_pushEnd += dlab::pushCount(op);
        ++m_pos;
        return &op;
    }
    if (m_ins->done()) return nullptr;
    if (!fitsBudget()) {
        m_budgetReached = true;
        return nullptr;
    }
    const PredicateCounters& counters = predicateCounters();
    const std::uint64_t orient = counters.orientExact, incircle = counters.incircleExact;
    const std::array<std::uint32_t, 2> before = exactFallbacksAt(m_ops.size());
    m_ins->step(this);
    while (m_exact.size() < m_ops.size()) {
        m_exact.push_back(
            {before[0] + static_cast<std::uint32_t>(counters.orientExact - orient),
             before[1] + static_cast<std::uint32_t>(counters.incircleExact - incircle)});
    }
    return &m_ops.back();
}

bool Journal::fitsBudget() const {
    // What the vectors hold after one more op if they grow (doubling; an op records at most a
    // few dozen cell changes and one control snapshot).
    constexpr std::size_t kChangesPerOpAtMost = 64;
    auto grown = [](std::size_t size, std::size_t capacity, std::size_t more) {
        return size + more <= capacity ? capacity : std::max(2 * capacity, size + more);
    };
    const std::size_t ops = grown(m_ops.size(), m_ops.capacity(), 1);
    const std::size_t controls = grown(m_controls.size(), m_controls.capacity(), 1);
    const std::size_t changes = grown(m_changes.size(), m_changes.capacity(), kChangesPerOpAtMost);
    const std::size_t pushes = grown(m_pushes.size(), m_pushes.capacity(), 4);
    const std::size_t exact = grown(m_exact.size(), m_exact.capacity(), 1);
    return ops * sizeof(Op) + controls * sizeof(Control) + changes * sizeof(CellChange) +
               pushes * sizeof(std::int32_t) + exact * sizeof(m_exact[0]) <=
           m_budget;
}

const Op* Journal::back() {
    if (m_pos == 0) return nullptr;
    if (m_pos == m_ops.size()) m_tip = m_ins->control();
    --m_pos;
    const Op& op = m_ops[m_pos];
    m_pushEnd -= dlab::pushCount(op);
    m_ins->undo(op, m_changes, {m_pushes.data() + m_pushEnd, dlab::pushCount(op)},
                controlBefore(m_pos));
    return &m_ops[m_pos];
}

void Journal::seek(std::size_t position) {
    // Long jumps repaint the locator's index once at the end instead of after every op.
    // Only replays are bulk: new steps need an up-to-date locator.
    const std::size_t target = std::min(position, m_ops.size());
    const bool bulk = (m_pos > target ? m_pos - target : target - m_pos) > 64;
    if (bulk) m_ins->setBulk(true);
    while (m_pos > target && back()) {}
    while (m_pos < target && forward()) {}
    if (bulk) m_ins->setBulk(false);
    while (m_pos < position && forward()) {}
}

}  // namespace dlab
