// Constrained edges: the walk along a segment, Sloan's flips of the crossed edges, the repair.
#include "core/engine/constrainer.h"

#include "core/engine/predicates.h"

#include <deque>
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

Constrainer::Constrainer(Mesh& mesh, std::int32_t firstVirtual)
    : m_mesh(mesh), m_firstVirtual(firstVirtual) {
    m_cornerOf.assign(mesh.G.size(), kNone);
    for (std::int32_t c = 0; c < mesh.numCorners(); ++c) m_cornerOf[mesh.V[c]] = c;
    m_flag.assign(mesh.V.size(), 0);
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
        if (l == kNone) return kNone;
        c = next(l);
    } while (c != start);
    return kNone;
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
        if (!isVirtual(p) && orient2d(G[a], G[b], G[p]) == 0 && between(G[a], G[b], G[p])) {
            stop = p;
            return true;
        }
        if (!isVirtual(p) && !isVirtual(q) && orient2d(G[a], G[p], G[b]) > 0 &&
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
    auto& V = m_mesh.V;
    auto& O = m_mesh.O;
    const std::int32_t d = O[c];
    const std::int32_t cn = next(c), cp = prev(c), dn = next(d), dp = prev(d);
    const std::int32_t P = V[c], A = V[cn], B = V[cp], D = V[d];
    const std::int32_t ocn = O[cn], odn = O[dn];
    const std::uint8_t fcn = m_flag[cn], fdn = m_flag[dn];
    V[cp] = D;
    V[dp] = P;
    O[c] = odn;
    if (odn != kNone) O[odn] = c;
    O[d] = ocn;
    if (ocn != kNone) O[ocn] = d;
    O[cn] = dn;
    O[dn] = cn;
    m_flag[c] = fdn;
    m_flag[d] = fcn;
    m_flag[cn] = m_flag[dn] = 0;
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
            queue.push_back({u, w});
            continue;
        }
        flip(c);
        const bool stillCrosses = P != a && P != b && D != a && D != b &&
                                  orient2d(G[a], G[b], G[P]) * orient2d(G[a], G[b], G[D]) < 0;
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
    m_flag[c] = 1;
    m_flag[m_mesh.O[c]] = 1;
}

// Lawson's flips from the new edges: an unconstrained edge between two finite triangles whose
// opposite vertex is strictly inside the circle is flipped, its quadrilateral's sides rechecked.
void Constrainer::restore(std::vector<Edge> stack) {
    const auto& G = m_mesh.G;
    while (!stack.empty()) {
        const auto [u, w] = stack.back();
        stack.pop_back();
        const std::int32_t c = edgeCorner(u, w);
        if (c == kNone || m_flag[c]) continue;
        const std::int32_t d = m_mesh.O[c];
        const std::int32_t P = m_mesh.V[c], A = m_mesh.V[next(c)], B = m_mesh.V[prev(c)];
        const std::int32_t D = m_mesh.V[d];
        if (isVirtual(P) || isVirtual(A) || isVirtual(B) || isVirtual(D)) continue;
        if (incircle(G[P], G[A], G[B], G[D]) <= 0) continue;
        flip(c);
        stack.insert(stack.end(), {{P, A}, {A, D}, {D, B}, {B, P}});
    }
}

ConstrainOutcome Constrainer::insert(std::int32_t a, std::int32_t b) {
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
    for (std::int32_t from = a, stop = kNone; from != b; from = stop) {
        crossed.clear();
        crossedEdges(from, b, crossed, stop, out);
        std::vector<Edge> fresh;
        flipOut(from, stop, crossed, fresh);
        mark(from, stop);
        restore(std::move(fresh));
    }
    return out;
}

}  // namespace dlab
