// Constrained edges: the walk along a segment, Sloan's flips of the crossed edges, the repair.
#include "core/engine/constrainer.h"

#include "core/engine/predicates.h"

#include <deque>
#include <limits>
#include <stdexcept>
#include <string>

namespace dlab {

namespace {

// p is collinear with a and b: is it strictly between them?
bool between(Vec2 a, Vec2 b, Vec2 p) {
    if (a.x != b.x) return (a.x < p.x && p.x < b.x) || (b.x < p.x && p.x < a.x);
    return (a.y < p.y && p.y < b.y) || (b.y < p.y && p.y < a.y);
}

}  // namespace

const char* toString(ConstrainOpType t) {
    switch (t) {
        case ConstrainOpType::Walk: return "Walk";
        case ConstrainOpType::SloanFlip: return "SloanFlip";
        case ConstrainOpType::SloanWait: return "SloanWait";
        case ConstrainOpType::Mark: return "Mark";
        case ConstrainOpType::Reflag: return "Reflag";
        case ConstrainOpType::Unmark: return "Unmark";
        case ConstrainOpType::InCircleTest: return "InCircleTest";
        case ConstrainOpType::Flip: return "Flip";
        case ConstrainOpType::MoveVertex: return "MoveVertex";
        case ConstrainOpType::Locate: return "Locate";
        case ConstrainOpType::Split: return "Split";
        case ConstrainOpType::SplitEdge: return "SplitEdge";
        case ConstrainOpType::Fan: return "Fan";
    }
    return "?";
}

Constrainer::Constrainer(Mesh& mesh, std::int32_t firstVirtual, Boundary boundary)
    : m_mesh(mesh),
      m_firstVirtual(firstVirtual),
      m_ghost(boundary == Boundary::Exact ? firstVirtual
                                          : std::numeric_limits<std::int32_t>::max()) {
    rebuildIndex();
    m_flag.assign(mesh.V.size(), 0);
}

void Constrainer::rebuildIndex() {
    m_cornerOf.assign(m_mesh.G.size(), kNone);
    for (std::int32_t c = 0; c < m_mesh.numCorners(); ++c) m_cornerOf[m_mesh.V[c]] = c;
    m_stale = false;
}

void Constrainer::setV(std::int32_t c, std::int32_t v) {
    if (m_record) m_record->changes.push_back({2 * c, m_mesh.V[c], v});
    m_mesh.V[c] = v;
}

void Constrainer::setO(std::int32_t c, std::int32_t o) {
    if (m_record) m_record->changes.push_back({2 * c + 1, m_mesh.O[c], o});
    m_mesh.O[c] = o;
}

void Constrainer::setFlag(std::int32_t c, std::uint8_t f) {
    if (m_flag[c] == f) return;
    if (m_record) m_record->flagChanges.push_back({c, m_flag[c], f});
    m_flag[c] = f;
}

ConstrainOp* Constrainer::beginOp(ConstrainOpType type, std::int32_t a, std::int32_t b, int sign) {
    if (!m_record) return nullptr;
    ConstrainOp op;
    op.type = type;
    op.a = a;
    op.b = b;
    op.sign = static_cast<std::int8_t>(sign);
    op.segmentA = m_segA;
    op.segmentB = m_segB;
    op.trianglesBefore = op.trianglesAfter = m_mesh.numTriangles();
    op.firstChange = static_cast<std::uint32_t>(m_record->changes.size());
    op.firstFlag = static_cast<std::uint32_t>(m_record->flagChanges.size());
    m_record->ops.push_back(op);
    return &m_record->ops.back();
}

void Constrainer::endOp() {
    if (!m_record) return;
    ConstrainOp& op = m_record->ops.back();
    op.trianglesAfter = m_mesh.numTriangles();
    op.numChanges = static_cast<std::uint32_t>(m_record->changes.size()) - op.firstChange;
    op.numFlags = static_cast<std::uint32_t>(m_record->flagChanges.size()) - op.firstFlag;
}

void Constrainer::replay(const ConstraintRecord& record, std::size_t i, bool forward) {
    const ConstrainOp& op = record.ops[i];
    const auto corners = [](std::int32_t t) { return 3 * static_cast<std::size_t>(t); };
    const std::size_t big = corners(std::max(op.trianglesBefore, op.trianglesAfter));
    if (m_mesh.V.size() < big) {  // a split's new triangles, or those it took away again
        m_mesh.V.resize(big, kNone);
        m_mesh.O.resize(big, kNone);
    }
    if (m_flag.size() < big) m_flag.resize(big, 0);
    if (forward) {
        for (std::uint32_t k = 0; k < op.numChanges; ++k) {
            const CellChange& ch = record.changes[op.firstChange + k];
            (ch.isO() ? m_mesh.O : m_mesh.V)[ch.corner()] = ch.after;
        }
        for (std::uint32_t k = 0; k < op.numFlags; ++k) {
            const FlagChange& f = record.flagChanges[op.firstFlag + k];
            if (m_flag.size() <= static_cast<std::size_t>(f.corner)) m_flag.resize(f.corner + 1, 0);
            m_flag[f.corner] = f.after;
        }
    } else {
        for (std::uint32_t k = op.numFlags; k-- > 0;) {
            const FlagChange& f = record.flagChanges[op.firstFlag + k];
            m_flag[f.corner] = f.before;
        }
        for (std::uint32_t k = op.numChanges; k-- > 0;) {
            const CellChange& ch = record.changes[op.firstChange + k];
            (ch.isO() ? m_mesh.O : m_mesh.V)[ch.corner()] = ch.before;
        }
    }
    if (op.trianglesBefore != op.trianglesAfter) {
        const std::size_t n = corners(forward ? op.trianglesAfter : op.trianglesBefore);
        m_mesh.V.resize(n);
        m_mesh.O.resize(n);
    }
    m_stale = true;
}

void Constrainer::undo(const ConstraintRecord& record, std::size_t from) {
    for (std::size_t i = record.ops.size(); i-- > from;) replay(record, i, false);
    rebuildIndex();
}

// The corner facing the edge u-w (in the triangle where it runs w -> ... seen from u's corner
// c with V[next(c)] = w: the corner prev(c)); kNone when u-w is no edge.
std::int32_t Constrainer::edgeCorner(std::int32_t u, std::int32_t w) const {
    const std::int32_t start = m_cornerOf[u];
    if (start == kNone) return kNone;
    std::int32_t c = start;
    do {
        if (m_mesh.V[next(c)] == w) return prev(c);
        const std::int32_t l = m_mesh.O[next(c)];
        if (l == kNone) {  // an open star (a super-triangle vertex): the other way round
            c = kNone;
            break;
        }
        c = next(l);
    } while (c != start);
    if (c != kNone) return kNone;  // the whole ring
    for (c = start;;) {
        if (m_mesh.V[prev(c)] == w) return next(c);
        const std::int32_t l = m_mesh.O[prev(c)];
        if (l == kNone) return kNone;
        c = prev(l);
    }
}

// Around a: the edge a-b itself, a vertex on the open segment (stop), or the triangle whose far
// edge the segment crosses first (corner at a).
bool Constrainer::firstCrossing(std::int32_t a, std::int32_t b, std::int32_t& corner,
                                std::int32_t& stop) const {
    const auto& G = m_mesh.G;
    const std::int32_t start = m_cornerOf[a];
    std::int32_t c = start;
    do {
        const std::int32_t p = m_mesh.V[next(c)], q = m_mesh.V[prev(c)];
        if (p == b) {
            stop = b;
            return true;
        }
        if (!isGhost(p) && orient2d(G[a], G[b], G[p]) == 0 && between(G[a], G[b], G[p])) {
            stop = p;
            return true;
        }
        if (!isGhost(p) && !isGhost(q) && orient2d(G[a], G[p], G[b]) > 0 &&
            orient2d(G[a], G[q], G[b]) < 0) {
            corner = c;
            return true;
        }
        c = next(m_mesh.O[next(c)]);
    } while (c != start);
    return false;
}

// The edges the open segment a-b crosses, in order, up to the first vertex on it (stop: b or a
// vertex in between). False, with `out` saying which, when it crosses a constrained edge.
bool Constrainer::crossedEdges(std::int32_t a, std::int32_t b, std::vector<Edge>& crossed,
                               std::int32_t& stop, ConstrainOutcome& out) const {
    const auto& G = m_mesh.G;
    std::int32_t c = kNone;
    stop = kNone;
    if (!firstCrossing(a, b, c, stop)) throw std::logic_error("constrain: no way out of a vertex");
    if (stop != kNone) return true;
    while (true) {
        // The edge p-q opposite c: p right of a->b, q left.
        const std::int32_t p = m_mesh.V[next(c)], q = m_mesh.V[prev(c)];
        if (m_flag[c]) {
            out.result = ConstrainResult::Crosses;
            out.crossed = {p, q};
            return false;
        }
        crossed.push_back({p, q});
        const std::int32_t o = m_mesh.O[c];
        const std::int32_t w = m_mesh.V[o];  // the triangle across is (w, q, p)
        if (w == b) {
            stop = b;
            return true;
        }
        const int s = orient2d(G[a], G[b], G[w]);
        if (s == 0) {
            stop = w;
            return true;
        }
        c = s > 0 ? next(o) : prev(o);  // out through w-p (w left) or q-w (w right)
    }
}

// Flip the edge opposite c (as the inserter does); the constrained flags follow their edges.
void Constrainer::flip(std::int32_t c) {
    const auto& V = m_mesh.V;
    const auto& O = m_mesh.O;
    const std::int32_t d = O[c];
    const std::int32_t cn = next(c), cp = prev(c), dn = next(d), dp = prev(d);
    const std::int32_t P = V[c], A = V[cn], B = V[cp], D = V[d];
    const std::int32_t ocn = O[cn], odn = O[dn];
    const std::uint8_t fcn = m_flag[cn], fdn = m_flag[dn];
    setV(cp, D);
    setV(dp, P);
    setO(c, odn);
    if (odn != kNone) setO(odn, c);
    setO(d, ocn);
    if (ocn != kNone) setO(ocn, d);
    setO(cn, dn);
    setO(dn, cn);
    setFlag(c, fdn);
    setFlag(d, fcn);
    setFlag(cn, 0);
    setFlag(dn, 0);
    m_cornerOf[P] = c;
    m_cornerOf[A] = cn;
    m_cornerOf[D] = d;
    m_cornerOf[B] = dn;
}

// Sloan: flip each crossed edge whose quadrilateral is convex; the new edge goes back in the
// queue while it still crosses a-b, else into `fresh`; a non-convex one waits its turn again.
void Constrainer::flipOut(std::int32_t a, std::int32_t b, std::vector<Edge> edges,
                          std::vector<Edge>& fresh) {
    const auto& G = m_mesh.G;
    std::deque<Edge> queue(edges.begin(), edges.end());
    std::size_t guard = 0;
    const std::size_t most = 64 * (queue.size() + 4) * (queue.size() + 4);
    while (!queue.empty()) {
        if (++guard > most) throw std::logic_error("constrain: the flips do not end");
        const auto [u, w] = queue.front();
        queue.pop_front();
        const std::int32_t c = edgeCorner(u, w);
        const std::int32_t P = m_mesh.V[c], D = m_mesh.V[m_mesh.O[c]];
        if (orient2d(G[P], G[D], G[u]) * orient2d(G[P], G[D], G[w]) >= 0) {
            beginOp(ConstrainOpType::SloanWait, c, kNone);
            endOp();
            queue.push_back({u, w});
            continue;
        }
        const bool stillCrosses = P != a && P != b && D != a && D != b &&
                                  orient2d(G[a], G[b], G[P]) * orient2d(G[a], G[b], G[D]) < 0;
        beginOp(ConstrainOpType::SloanFlip, c, stillCrosses ? 1 : 0);
        flip(c);
        endOp();
        if (stillCrosses) {
            queue.push_back({P, D});
        } else {
            fresh.push_back({P, D});
        }
    }
}

void Constrainer::mark(std::int32_t a, std::int32_t b) {
    const std::int32_t c = edgeCorner(a, b);
    if (c == kNone) throw std::logic_error("constrain: the segment is not an edge after the flips");
    if (m_flag[c] == 255) throw std::logic_error("constrain: an edge in 255 constraints");
    beginOp(ConstrainOpType::Mark, a, b);
    setFlag(c, static_cast<std::uint8_t>(m_flag[c] + 1));
    setFlag(m_mesh.O[c], m_flag[c]);
    endOp();
}

// Lawson's flips from the new edges: an unconstrained edge whose opposite vertex is strictly inside
// the circle is flipped, its quadrilateral's sides rechecked. A ghost triangle's circle is the
// half-plane beyond its hull edge, so a vertex put in outside the hull takes in the hull vertices
// it makes reflex.
void Constrainer::restore(std::vector<Edge> stack) {
    const auto& G = m_mesh.G;
    while (!stack.empty()) {
        const auto [u, w] = stack.back();
        stack.pop_back();
        const std::int32_t c = edgeCorner(u, w);
        if (c == kNone || m_flag[c]) continue;
        const std::int32_t d = m_mesh.O[c];
        if (d == kNone) continue;  // the super-triangle's side
        const std::int32_t P = m_mesh.V[c], A = m_mesh.V[next(c)], B = m_mesh.V[prev(c)];
        const std::int32_t D = m_mesh.V[d];
        if (isGhost(P) || isGhost(D)) continue;  // a hull edge: the outside never flips in
        // Between two ghost triangles (A or B the ghost vertex): D beyond P's hull edge, the
        // hull turns the wrong way at the edge's other end and the flip takes it in.
        const int inside = ghostInCircle(G, m_ghost, P, A, B, D);
        beginOp(ConstrainOpType::InCircleTest, c, d, inside);
        endOp();
        if (inside <= 0) continue;
        beginOp(ConstrainOpType::Flip, c, d);
        flip(c);
        endOp();
        stack.insert(stack.end(), {{P, A}, {A, D}, {D, B}, {B, P}});
    }
}

ConstrainOutcome Constrainer::insert(std::int32_t a, std::int32_t b, ConstraintRecord* record) {
    if (m_stale) rebuildIndex();
    ConstrainOutcome out;
    const auto n = static_cast<std::int32_t>(m_cornerOf.size());
    if (a == b) {
        out.result = ConstrainResult::SameVertex;
        return out;
    }
    for (const std::int32_t v : {a, b}) {
        if (v < 0 || v >= n || isVirtual(v) || m_cornerOf[v] == kNone) {
            out.result = ConstrainResult::NotInMesh;
            return out;
        }
    }
    // First the whole walk on the mesh as it is (constrained edges never move): refuse before
    // any change.
    std::vector<Edge> crossed;
    for (std::int32_t from = a, stop = kNone; from != b; from = stop) {
        crossed.clear();
        if (!crossedEdges(from, b, crossed, stop, out)) return out;
    }
    struct Recording {  // the record is this call's only, even when it throws
        Constrainer& self;
        ~Recording() { self.m_record = nullptr; }
    } recording{*this};
    beginRecording(record, a, b);
    for (std::int32_t from = a, stop = kNone; from != b; from = stop) {
        crossed.clear();
        crossedEdges(from, b, crossed, stop, out);
        if (ConstrainOp* walk = beginOp(ConstrainOpType::Walk, from, stop))
            walk->count = static_cast<std::int32_t>(crossed.size());
        endOp();
        std::vector<Edge> fresh;
        flipOut(from, stop, crossed, fresh);
        mark(from, stop);
        restore(std::move(fresh));
    }
    return out;
}

// The edges from a to b along the segment, vertex to vertex; false when one is missing or not
// constrained.
bool Constrainer::pieces(std::int32_t a, std::int32_t b, std::vector<Edge>& out) const {
    for (std::int32_t from = a; from != b;) {
        std::int32_t corner = kNone, stop = kNone;
        if (!firstCrossing(from, b, corner, stop) || stop == kNone) return false;
        const std::int32_t c = edgeCorner(from, stop);
        if (c == kNone || !m_flag[c]) return false;
        out.push_back({from, stop});
        from = stop;
    }
    return true;
}

ConstrainOutcome Constrainer::remove(std::int32_t a, std::int32_t b, ConstraintRecord* record) {
    if (m_stale) rebuildIndex();
    ConstrainOutcome out;
    const auto n = static_cast<std::int32_t>(m_cornerOf.size());
    for (const std::int32_t v : {a, b}) {
        if (v < 0 || v >= n || isVirtual(v) || m_cornerOf[v] == kNone) {
            out.result = ConstrainResult::NotInMesh;
            return out;
        }
    }
    std::vector<Edge> edges;
    if (a == b || !pieces(a, b, edges)) {
        out.result = a == b ? ConstrainResult::SameVertex : ConstrainResult::NotConstrained;
        return out;
    }
    struct Recording {  // the record is this call's only, even when it throws
        Constrainer& self;
        ~Recording() { self.m_record = nullptr; }
    } recording{*this};
    beginRecording(record, a, b);
    std::vector<Edge> freed;
    for (const auto& [u, w] : edges) {
        const std::int32_t c = edgeCorner(u, w);
        beginOp(ConstrainOpType::Unmark, u, w);
        setFlag(c, static_cast<std::uint8_t>(m_flag[c] - 1));
        setFlag(m_mesh.O[c], m_flag[c]);
        endOp();
        if (m_flag[c] == 0) freed.push_back({u, w});
    }
    restore(std::move(freed));
    return out;
}

void Constrainer::beginRecording(ConstraintRecord* record, std::int32_t a, std::int32_t b) {
    m_record = record;
    m_segA = a;
    m_segB = b;
}

// ============================================================================================
// [SECTION] A vertex put into the mesh
// ============================================================================================

// The triangle to split for p: a finite one that holds p strictly inside (edge kNone) or on the
// open edge opposite corner `edge` (a hull edge has a ghost triangle across); outside the hull,
// a ghost triangle whose hull edge has p strictly beyond it. False (and why) when p is on a
// vertex or the mesh has no triangle.
bool Constrainer::locate(Vec2 p, std::int32_t& tri, std::int32_t& edge,
                         PlaceResult& refused) const {
    const auto& G = m_mesh.G;
    const auto& V = m_mesh.V;
    refused = PlaceResult::NoTriangle;
    std::int32_t beyond = kNone;  // a ghost triangle that sees p
    for (std::int32_t t = 0; t < m_mesh.numTriangles(); ++t) {
        const std::int32_t a = V[3 * t], b = V[3 * t + 1], c = V[3 * t + 2];
        if (isGhost(a) || isGhost(b) || isGhost(c)) {
            // (g, y, x) in some rotation: the hull edge x->y, the mesh on its left.
            const std::int32_t g = 3 * t + (isGhost(a) ? 0 : isGhost(b) ? 1 : 2);
            const std::int32_t x = V[prev(g)], y = V[next(g)];
            if (beyond == kNone && orient2d(G[x], G[y], p) < 0) beyond = t;
            continue;
        }
        const int s[3] = {orient2d(G[b], G[c], p), orient2d(G[c], G[a], p),
                          orient2d(G[a], G[b], p)};
        if (s[0] < 0 || s[1] < 0 || s[2] < 0) continue;
        const int zeros = (s[0] == 0) + (s[1] == 0) + (s[2] == 0);
        if (zeros >= 2) {
            refused = PlaceResult::OnVertex;
            return false;
        }
        tri = t;
        edge = kNone;
        for (int k = 0; k < 3; ++k) {
            if (s[k] == 0) edge = 3 * t + k;
        }
        return edge == kNone || m_mesh.O[edge] != kNone;  // not on the super-triangle's side
    }
    if (beyond == kNone) return false;
    tri = beyond;
    edge = kNone;
    return true;
}

std::int32_t Constrainer::appendTriangles(int count) {
    const std::int32_t first = m_mesh.numTriangles();
    m_mesh.V.resize(m_mesh.V.size() + 3 * static_cast<std::size_t>(count), kNone);
    m_mesh.O.resize(m_mesh.O.size() + 3 * static_cast<std::size_t>(count), kNone);
    if (m_flag.size() < m_mesh.V.size()) m_flag.resize(m_mesh.V.size(), 0);
    return first;
}

// (a, b, c) becomes (a, b, v), (b, c, v), (c, a, v): the outer edges keep their opposites and
// constraints.
void Constrainer::splitTriangle(std::int32_t t, std::int32_t v) {
    const auto& V = m_mesh.V;
    const std::int32_t a = V[3 * t], b = V[3 * t + 1], c = V[3 * t + 2];
    const std::int32_t oa = m_mesh.O[3 * t], ob = m_mesh.O[3 * t + 1];
    const std::uint8_t fa = m_flag[3 * t], fb = m_flag[3 * t + 1];
    const std::int32_t t1 = appendTriangles(2), t2 = t1 + 1;
    setV(3 * t + 2, v);
    setV(3 * t1, b);
    setV(3 * t1 + 1, c);
    setV(3 * t1 + 2, v);
    setV(3 * t2, c);
    setV(3 * t2 + 1, a);
    setV(3 * t2 + 2, v);
    const auto link = [&](std::int32_t x, std::int32_t y) {
        setO(x, y);
        if (y != kNone) setO(y, x);
    };
    link(3 * t, 3 * t1 + 1);
    link(3 * t + 1, 3 * t2);
    link(3 * t1, 3 * t2 + 1);
    link(3 * t1 + 2, oa);
    link(3 * t2 + 2, ob);
    setFlag(3 * t, 0);
    setFlag(3 * t + 1, 0);
    setFlag(3 * t1 + 2, fa);
    setFlag(3 * t2 + 2, fb);
    m_cornerOf[a] = 3 * t;
    m_cornerOf[b] = 3 * t1;
    m_cornerOf[c] = 3 * t2;
    m_cornerOf[v] = 3 * t + 2;
}

// The edge A-B opposite corner c (apex X, and Y across) split at v: (X, A, B) becomes (X, A, v)
// and (X, v, B), (Y, B, A) becomes (Y, B, v) and (Y, v, A); both halves keep A-B's constraints.
void Constrainer::splitEdge(std::int32_t c, std::int32_t v) {
    const auto& V = m_mesh.V;
    const std::int32_t d = m_mesh.O[c];
    const std::int32_t X = V[c], A = V[next(c)], B = V[prev(c)], Y = V[d];
    const std::int32_t ocn = m_mesh.O[next(c)], odn = m_mesh.O[next(d)];
    const std::uint8_t fe = m_flag[c], fcn = m_flag[next(c)], fdn = m_flag[next(d)];
    const std::int32_t t1 = appendTriangles(2), t2 = t1 + 1;
    setV(prev(c), v);
    setV(prev(d), v);
    setV(3 * t1, X);
    setV(3 * t1 + 1, v);
    setV(3 * t1 + 2, B);
    setV(3 * t2, Y);
    setV(3 * t2 + 1, v);
    setV(3 * t2 + 2, A);
    const auto link = [&](std::int32_t x, std::int32_t y) {
        setO(x, y);
        if (y != kNone) setO(y, x);
    };
    link(c, 3 * t2);
    link(next(c), 3 * t1 + 2);
    link(3 * t1, d);
    link(3 * t1 + 1, ocn);
    link(next(d), 3 * t2 + 2);
    link(3 * t2 + 1, odn);
    setFlag(3 * t2, fe);
    setFlag(3 * t1, fe);
    setFlag(next(c), 0);
    setFlag(next(d), 0);
    setFlag(3 * t1 + 2, 0);
    setFlag(3 * t2 + 2, 0);
    setFlag(3 * t1 + 1, fcn);
    setFlag(3 * t2 + 1, fdn);
    m_cornerOf[X] = c;
    m_cornerOf[A] = next(c);
    m_cornerOf[B] = 3 * t1 + 2;
    m_cornerOf[Y] = d;
    m_cornerOf[v] = prev(c);
}

PlaceResult Constrainer::insertVertex(std::int32_t v, ConstraintRecord* record) {
    if (m_stale) rebuildIndex();
    if (v < 0 || v >= m_mesh.numVertices() || isVirtual(v) ||
        (v < static_cast<std::int32_t>(m_cornerOf.size()) && m_cornerOf[v] != kNone))
        throw std::logic_error("insertVertex: the vertex must be finite and in no triangle");
    std::int32_t t = kNone, edge = kNone;
    PlaceResult refused{};
    if (!locate(m_mesh.G[v], t, edge, refused)) return refused;
    if (m_cornerOf.size() < m_mesh.G.size()) m_cornerOf.resize(m_mesh.G.size(), kNone);
    struct Recording {  // the record is this call's only, even when it throws
        Constrainer& self;
        ~Recording() { self.m_record = nullptr; }
    } recording{*this};
    beginRecording(record, v, kNone);
    ConstrainOp* op = beginOp(ConstrainOpType::Locate, v, t);
    if (op) op->count = edge;
    endOp();
    std::vector<Edge> link;
    if (edge == kNone) {
        const auto& V = m_mesh.V;
        link = {{V[3 * t], V[3 * t + 1]}, {V[3 * t + 1], V[3 * t + 2]}, {V[3 * t + 2], V[3 * t]}};
        beginOp(ConstrainOpType::Split, v, t);
        splitTriangle(t, v);
    } else {
        const auto& V = m_mesh.V;
        const std::int32_t d = m_mesh.O[edge];
        link = {{V[edge], V[next(edge)]},
                {V[prev(edge)], V[edge]},
                {V[d], V[next(d)]},
                {V[prev(d)], V[d]}};
        beginOp(ConstrainOpType::SplitEdge, v, edge);
        splitEdge(edge, v);
    }
    endOp();
    restore(std::move(link));
    return PlaceResult::Placed;
}

PlaceResult Constrainer::fanOut(std::int32_t v, const std::vector<std::int32_t>& left,
                                ConstraintRecord* record) {
    if (m_stale) rebuildIndex();
    const auto& G = m_mesh.G;
    if (m_mesh.numTriangles() != 0 || left.size() < 2)
        throw std::logic_error("fanOut: the mesh must be empty, two vertices or more left");
    std::vector<Vec2> pts;  // the points left, then v: the fan is their Delaunay triangulation
    for (const std::int32_t u : left) {
        if (G[u] == G[v]) return PlaceResult::OnVertex;
        pts.push_back(G[u]);
    }
    pts.push_back(G[v]);
    Inserter fan(pts);
    fan.run();
    Mesh made = fan.takeMesh();
    if (made.numTriangles() == 0) return PlaceResult::NoTriangle;  // v on their line
    addGhosts(made);
    const auto local = static_cast<std::int32_t>(left.size());  // v; the ghost is local + 1
    const auto id = [&](std::int32_t i) {
        return i < local ? left[i] : i == local ? v : m_firstVirtual;
    };
    if (m_cornerOf.size() < G.size()) m_cornerOf.resize(G.size(), kNone);
    struct Recording {  // the record is this call's only, even when it throws
        Constrainer& self;
        ~Recording() { self.m_record = nullptr; }
    } recording{*this};
    beginRecording(record, v, kNone);
    if (ConstrainOp* op = beginOp(ConstrainOpType::Fan, v, kNone)) op->count = made.numTriangles();
    appendTriangles(made.numTriangles());
    for (std::int32_t c = 0; c < made.numCorners(); ++c) {
        setV(c, id(made.V[c]));
        setO(c, made.O[c]);
        setFlag(c, 0);
        m_cornerOf[id(made.V[c])] = c;
    }
    endOp();
    return PlaceResult::Placed;
}

bool Constrainer::inKernel(std::int32_t v, Vec2 to) {
    if (m_stale) rebuildIndex();
    if (v < 0 || v >= static_cast<std::int32_t>(m_cornerOf.size()) || isVirtual(v) ||
        m_cornerOf[v] == kNone)
        return false;
    const auto& G = m_mesh.G;
    const std::int32_t start = m_cornerOf[v];
    std::int32_t c = start;
    do {
        const std::int32_t a = m_mesh.V[next(c)], b = m_mesh.V[prev(c)];
        if (isGhost(a) || isGhost(b) || orient2d(to, G[a], G[b]) <= 0) return false;
        c = next(m_mesh.O[next(c)]);
    } while (c != start);
    return true;
}

void Constrainer::follow(std::int32_t v, ConstraintRecord* record) {
    if (m_stale) rebuildIndex();
    struct Recording {  // the record is this call's only, even when it throws
        Constrainer& self;
        ~Recording() { self.m_record = nullptr; }
    } recording{*this};
    beginRecording(record, v, kNone);
    std::vector<Edge> star;  // the spokes and the link
    const std::int32_t start = m_cornerOf[v];
    std::int32_t c = start;
    do {
        const std::int32_t a = m_mesh.V[next(c)], b = m_mesh.V[prev(c)];
        star.push_back({a, b});
        star.push_back({v, a});
        c = next(m_mesh.O[next(c)]);
    } while (c != start);
    restore(std::move(star));
}

VertexRemoval Constrainer::removeVertex(Remover& remover, std::int32_t v, RemovalRecord* removal,
                                        ConstraintRecord* record) {
    VertexRemoval out;
    if (m_stale) rebuildIndex();
    struct Held {
        std::int32_t u, w;
        std::uint8_t count;
    };
    std::vector<Held> held;  // every constrained edge once, by its vertices
    for (std::int32_t c = 0; c < m_mesh.numCorners(); ++c) {
        const std::int32_t o = m_mesh.O[c];
        if (!m_flag[c] || (o != kNone && o < c)) continue;
        const std::int32_t u = m_mesh.V[next(c)], w = m_mesh.V[prev(c)];
        if (u == v || w == v) {
            out.refused = true;
            out.constrained = {u, w};
            return out;
        }
        held.push_back({u, w, m_flag[c]});
    }
    std::vector<std::int32_t> rim;  // v's neighbours: the hole's new edges all join two of them
    if (v >= 0 && v < static_cast<std::int32_t>(m_cornerOf.size()) && !isVirtual(v) &&
        m_cornerOf[v] != kNone) {
        const std::int32_t start = m_cornerOf[v];
        std::int32_t c = start;
        do {
            rim.push_back(m_mesh.V[next(c)]);
            c = next(m_mesh.O[next(c)]);
        } while (c != start);
    }
    remover.meshChanged();
    out.removed = remover.remove(v, removal);
    rebuildIndex();
    struct Recording {  // the record is this call's only, even when it throws
        Constrainer& self;
        ~Recording() { self.m_record = nullptr; }
    } recording{*this};
    beginRecording(record, v, kNone);
    if (m_flag.size() < m_mesh.V.size()) m_flag.resize(m_mesh.V.size(), 0);
    beginOp(ConstrainOpType::Reflag, v, kNone);
    for (std::size_t c = 0; c < m_flag.size(); ++c) setFlag(static_cast<std::int32_t>(c), 0);
    std::vector<Edge> around;
    for (const Held& h : held) {
        const std::int32_t c = edgeCorner(h.u, h.w);
        if (c == kNone) {  // Collapsed: no triangle is left to hold it
            ++out.droppedConstraints;
            continue;
        }
        setFlag(c, h.count);
        setFlag(m_mesh.O[c], h.count);
    }
    endOp();
    // The hole's new edges and its rim: every edge at a vertex of the rim.
    if (out.removed == RemoveResult::Removed) {
        for (const std::int32_t u : rim) {
            if (isVirtual(u)) continue;  // a super-triangle vertex's edges: from the others
            const std::int32_t start = m_cornerOf[u];
            std::int32_t c = start;
            do {  // not the edges to the ghost vertex: the Remover left the hull convex
                if (!isGhost(m_mesh.V[next(c)])) around.push_back({u, m_mesh.V[next(c)]});
                c = next(m_mesh.O[next(c)]);
            } while (c != start);
        }
    }
    restore(std::move(around));
    return out;
}

}  // namespace dlab
