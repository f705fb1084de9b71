// Vertex removal by ear flips and a final merge, each a recorded operation; ghost-form helpers.
#include "core/engine/remover.h"

#include "core/engine/checks.h"
#include "core/engine/predicates.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace dlab {

const char* toString(RemoveOpType t) {
    switch (t) {
        case RemoveOpType::EarTest: return "EarTest";
        case RemoveOpType::Flip: return "Flip";
        case RemoveOpType::Merge: return "Merge";
        case RemoveOpType::Collapse: return "Collapse";
    }
    return "?";
}

const char* toString(RemoveResult r) {
    switch (r) {
        case RemoveResult::Removed: return "removed";
        case RemoveResult::Collapsed: return "removed; the points left make no triangle";
        case RemoveResult::NotInMesh: return "not a vertex of the mesh";
        case RemoveResult::Virtual: return "a virtual vertex";
    }
    return "?";
}

namespace {

// p is collinear with a and b: is it strictly between them?
bool onOpenSegment(Vec2 a, Vec2 b, Vec2 p) {
    if (a.x != b.x) return (a.x < p.x && p.x < b.x) || (b.x < p.x && p.x < a.x);
    return (a.y < p.y && p.y < b.y) || (b.y < p.y && p.y < a.y);
}

}  // namespace

int ghostInCircle(const std::vector<Vec2>& G, std::int32_t ghost, std::int32_t a, std::int32_t b,
                  std::int32_t c, std::int32_t w) {
    const auto isGhost = [ghost](std::int32_t u) { return u >= ghost; };
    if (isGhost(w)) return -1;
    if (!isGhost(a) && !isGhost(b) && !isGhost(c)) return incircle(G[a], G[b], G[c], G[w]);
    // The ghost triangle's hull edge x->y, the mesh on its right: its "circle" is the open
    // half-plane left of x->y (beyond the hull), plus the open edge.
    const std::int32_t x = isGhost(a) ? b : isGhost(b) ? c : a;
    const std::int32_t y = isGhost(a) ? c : isGhost(b) ? a : b;
    const int s = orient2d(G[x], G[y], G[w]);
    if (s != 0) return s;
    return onOpenSegment(G[x], G[y], G[w]) ? 1 : -1;
}

// ============================================================================================
// [SECTION] Construction and the vertex index
// ============================================================================================

Remover::Remover(Mesh& mesh, std::int32_t firstVirtual, Boundary boundary)
    : m_mesh(mesh), m_firstVirtual(firstVirtual), m_boundary(boundary) {}

void Remover::rebuildIndex() {
    m_cornerOf.assign(m_mesh.G.size(), kNone);
    m_live = 0;
    for (std::int32_t c = 0; c < m_mesh.numCorners(); ++c) {
        std::int32_t& at = m_cornerOf[m_mesh.V[c]];
        if (at == kNone && !isVirtual(m_mesh.V[c])) ++m_live;
        at = c;
    }
    m_stale = false;
}

std::int32_t Remover::cornerAt(std::int32_t v) {
    if (m_stale || m_cornerOf.size() != m_mesh.G.size()) rebuildIndex();
    if (v < 0 || v >= static_cast<std::int32_t>(m_cornerOf.size())) return kNone;
    return m_cornerOf[v];
}

std::int32_t Remover::liveVertices() {
    if (m_stale || m_cornerOf.size() != m_mesh.G.size()) rebuildIndex();
    return m_live;
}

// ============================================================================================
// [SECTION] Recorded cell writes
// ============================================================================================

void Remover::setV(std::int32_t c, std::int32_t v) {
    if (m_record) m_record->changes.push_back({2 * c, m_mesh.V[c], v});
    m_mesh.V[c] = v;
}

void Remover::setO(std::int32_t c, std::int32_t o) {
    if (m_record) m_record->changes.push_back({2 * c + 1, m_mesh.O[c], o});
    m_mesh.O[c] = o;
}

void Remover::link(std::int32_t c, std::int32_t d) {
    setO(c, d);
    if (d != kNone) setO(d, c);
}

RemoveOp Remover::beginOp(RemoveOpType type, std::int32_t v) const {
    RemoveOp op;
    op.type = type;
    op.vertex = v;
    op.trianglesBefore = m_mesh.numTriangles();
    if (m_record) op.firstChange = static_cast<std::uint32_t>(m_record->changes.size());
    return op;
}

void Remover::endOp(RemoveOp op) {
    if (!m_record) return;
    op.trianglesAfter = m_mesh.numTriangles();
    op.numChanges = static_cast<std::uint32_t>(m_record->changes.size()) - op.firstChange;
    m_record->ops.push_back(op);
}

void Remover::replay(const RemovalRecord& record, std::size_t i, bool forward) {
    auto& V = m_mesh.V;
    auto& O = m_mesh.O;
    const RemoveOp& op = record.ops[i];
    const std::size_t big =
        3 * static_cast<std::size_t>(std::max(op.trianglesBefore, op.trianglesAfter));
    V.resize(big, kNone);
    O.resize(big, kNone);
    if (forward) {
        for (std::uint32_t k = 0; k < op.numChanges; ++k) {
            const CellChange& ch = record.changes[op.firstChange + k];
            (ch.isO() ? O : V)[ch.corner()] = ch.after;
        }
    } else {
        for (std::uint32_t k = op.numChanges; k-- > 0;) {
            const CellChange& ch = record.changes[op.firstChange + k];
            (ch.isO() ? O : V)[ch.corner()] = ch.before;
        }
    }
    const std::int32_t t = forward ? op.trianglesAfter : op.trianglesBefore;
    V.resize(3 * static_cast<std::size_t>(t));
    O.resize(3 * static_cast<std::size_t>(t));
    m_stale = true;
}

void Remover::undo(const RemovalRecord& record, std::size_t from) {
    for (std::size_t i = record.ops.size(); i-- > from;) replay(record, i, false);
}

// ============================================================================================
// [SECTION] Removal
// ============================================================================================

RemoveResult Remover::remove(std::int32_t v, RemovalRecord* record) {
    if (v >= m_firstVirtual && v < m_mesh.numVertices()) return RemoveResult::Virtual;
    const std::int32_t start = cornerAt(v);
    if (start == kNone) return RemoveResult::NotInMesh;
    m_record = record;
    gatherStar(v, start);
    if (m_boundary == Boundary::Exact && leavesNoTriangle(v)) {
        collapse(v);
        m_record = nullptr;
        return RemoveResult::Collapsed;
    }
    while (m_corners.size() > 3) cutEar(v, chooseEar(v));
    merge(v);
    m_cornerOf[v] = kNone;
    --m_live;
    m_record = nullptr;
    return RemoveResult::Removed;
}

// The star of v counter-clockwise: corner i at v in triangle (v, link[i], link[i+1]), from the
// lowest corner.
void Remover::gatherStar(std::int32_t v, std::int32_t start) {
    m_link.clear();
    m_corners.clear();
    std::int32_t c = start;
    do {
        m_corners.push_back(c);
        m_link.push_back(m_mesh.V[next(c)]);
        const std::int32_t l = m_mesh.O[next(c)];
        if (l == kNone) {
            throw std::logic_error("remove: the star of vertex " + std::to_string(v) +
                                   " is open (the mesh has no ghost or super triangles)");
        }
        c = next(l);
    } while (c != start && m_corners.size() <= static_cast<std::size_t>(m_mesh.numCorners()));
    DLAB_ASSERT(c == start && m_corners.size() >= 3, "the star of a vertex is not a ring");
    // Start at the lowest corner: the removal depends on V and O only, not on the index.
    const auto low = std::min_element(m_corners.begin(), m_corners.end()) - m_corners.begin();
    std::rotate(m_corners.begin(), m_corners.begin() + low, m_corners.end());
    std::rotate(m_link.begin(), m_link.begin() + low, m_link.end());
    m_ear.assign(m_link.size(), kUntested);
}

// Exact boundary: after v the points left are fewer than three or on one line. Every finite
// triangle then used v, so every point left is in v's link.
bool Remover::leavesNoTriangle(std::int32_t) const {
    std::vector<Vec2> left;
    for (const std::int32_t w : m_link) {
        if (!isVirtual(w)) left.push_back(m_mesh.G[w]);
    }
    if (m_live - 1 != static_cast<std::int32_t>(left.size())) return false;
    for (std::size_t k = 2; k < left.size(); ++k) {
        if (orient2d(left[0], left[1], left[k]) != 0) return false;
    }
    return true;
}

// Is w strictly inside the circle of the triangle (a, b, c) (counter-clockwise)? With the ghost
// vertex, the ghost triangle (x, y, g)'s circle is the open half-plane left of x->y plus the open
// segment x-y; the ghost vertex itself is inside no circle.
int Remover::inCircleOf(std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t w) const {
    if (m_boundary != Boundary::Exact) {
        const auto& G = m_mesh.G;
        return incircle(G[a], G[b], G[c], G[w]);
    }
    return ghostInCircle(m_mesh.G, m_firstVirtual, a, b, c, w);
}

// The ear with tip link[i]: +1 it can be cut, 0 only leaving a flat triangle (v, a, c) at v,
// -1 it is not a triangle of the result or the flip is not possible.
int Remover::earSign(std::int32_t v, std::size_t i) const {
    const std::size_t k = m_link.size();
    const std::int32_t a = m_link[(i + k - 1) % k], b = m_link[i], c = m_link[(i + 1) % k];
    const auto& G = m_mesh.G;
    const bool finite = !isGhost(a) && !isGhost(b) && !isGhost(c);
    if (finite && orient2d(G[a], G[b], G[c]) <= 0) return -1;  // reflex or flat at b
    // The flip leaves (v, a, c): a finite one must not turn clockwise.
    int legal = 1;
    if (!isGhost(a) && !isGhost(c)) {
        legal = orient2d(G[v], G[a], G[c]);
        if (legal < 0) return -1;
    }
    for (std::size_t j = 0; j + 3 < k; ++j) {
        const std::int32_t w = m_link[(i + 2 + j) % k];
        if (inCircleOf(a, b, c, w) > 0) return -1;
    }
    return legal;
}

// The ear with tip link[i] tested (and recorded): its sign is kept until a cut next to it.
int Remover::testEar(std::int32_t v, std::size_t i) {
    const int sign = earSign(v, i);
    m_ear[i] = static_cast<std::int8_t>(sign);
    if (m_record) {
        RemoveOp op = beginOp(RemoveOpType::EarTest, v);
        op.a = m_corners[(i + m_link.size() - 1) % m_link.size()];
        op.b = m_link[i];
        op.sign = static_cast<std::int8_t>(sign);
        endOp(op);
    }
    return sign;
}

// An ear to cut: one that leaves a proper triangle at v, else one that leaves a flat one (v in the
// middle of a-c: a square's centre, a hull vertex between collinear neighbours). A cut changes
// only the two ears beside it, and shrinks the link, so an ear stays an ear: the signs are kept,
// untested ones tested first, refused ones again only when nothing else is left (O(k) tests per
// cut instead of O(k^2) on a vertex of degree k).
std::size_t Remover::chooseEar(std::int32_t v) {
    const std::size_t k = m_link.size();
    for (std::size_t i = 0; i < k; ++i) {
        if (m_ear[i] == 1 || (m_ear[i] == kUntested && testEar(v, i) > 0)) return i;
    }
    for (std::size_t i = 0; i < k; ++i) {
        if (m_ear[i] < 0 && testEar(v, i) > 0) return i;
    }
    for (std::size_t i = 0; i < k; ++i) {
        if (m_ear[i] == 0) return i;
    }
    throw std::logic_error("remove: no ear to cut around vertex " + std::to_string(v) +
                           " (the mesh around it is not Delaunay)");
}

// Flip the edge v-b (b = link[i]) between (v, a, b) and (v, b, c): the first becomes the ear
// (a, b, c), the second (v, a, c). The corner at a in (v, a, b) faces the edge.
//
//            b                        b
//          / | \                    /   \            (v, a, b) -> (a, b, c)
//         a  |  c       ==>        a --- c           (v, b, c) -> (v, a, c)
//          \ | /                    \   /
//            v                        v
void Remover::cutEar(std::int32_t v, std::size_t i) {
    const std::size_t k = m_link.size();
    const std::size_t before = (i + k - 1) % k;
    const std::int32_t c = next(m_corners[before]);  // at a
    const std::int32_t d = m_mesh.O[c];              // at c, in (v, b, c)
    RemoveOp op = beginOp(RemoveOpType::Flip, v);
    op.a = c;
    op.b = m_link[i];
    const std::int32_t cn = next(c), cp = prev(c), dn = next(d), dp = prev(d);
    const std::int32_t P = m_mesh.V[c], D = m_mesh.V[d];
    const std::int32_t ocn = m_mesh.O[cn], odn = m_mesh.O[dn];
    setV(cp, D);
    setV(dp, P);
    link(c, odn);
    link(d, ocn);
    link(cn, dn);
    endOp(op);
    m_cornerOf[P] = c;
    m_cornerOf[m_mesh.V[cn]] = cn;
    m_cornerOf[D] = d;
    m_cornerOf[v] = dn;
    // Triangle j stays (v, link[j], link[j + 1]): (v, a, c) takes the place of (v, a, b).
    m_link.erase(m_link.begin() + static_cast<std::ptrdiff_t>(i));
    m_corners.erase(m_corners.begin() + static_cast<std::ptrdiff_t>(before));
    if (i == 0) std::rotate(m_corners.begin(), m_corners.begin() + 1, m_corners.end());
    m_ear.erase(m_ear.begin() + static_cast<std::ptrdiff_t>(i));
    m_ear[(i + k - 2) % (k - 1)] = kUntested;  // the ears with tips a and c
    m_ear[i % (k - 1)] = kUntested;
}

// Degree 3: (v, L0, L1), (v, L1, L2), (v, L2, L0) become (L2, L0, L1) in the first one's slot;
// the other two slots are filled by the last triangles.
void Remover::merge(std::int32_t v) {
    DLAB_ASSERT(m_corners.size() == 3, "merge of a vertex of degree other than 3");
    const std::int32_t c0 = m_corners[0], c1 = m_corners[1], c2 = m_corners[2];
    RemoveOp op = beginOp(RemoveOpType::Merge, v);
    setV(c0, m_link[2]);
    link(next(c0), m_mesh.O[c1]);
    link(prev(c0), m_mesh.O[c2]);
    m_cornerOf[m_link[2]] = c0;
    m_cornerOf[m_link[0]] = next(c0);
    m_cornerOf[m_link[1]] = prev(c0);
    std::int32_t t1 = tri(c1), t2 = tri(c2);
    if (t1 < t2) std::swap(t1, t2);
    std::int32_t merged = tri(c0);
    const std::int32_t last = m_mesh.numTriangles() - 1;
    // The triangle that lands in t1's slot, then in t2's: track where the merged one ends up.
    if (merged == last) merged = t1;
    freeTriangle(t1);
    if (merged == m_mesh.numTriangles() - 1) merged = t2;
    freeTriangle(t2);
    op.a = merged;
    endOp(op);
}

// Triangle t is no longer used: the last triangle moves into its slot (its neighbours follow),
// the table shrinks by one. The cells past the end are recorded as cleared, for undo.
void Remover::freeTriangle(std::int32_t t) {
    const std::int32_t last = m_mesh.numTriangles() - 1;
    if (t != last) {
        for (int k = 0; k < 3; ++k) {
            const std::int32_t from = 3 * last + k, to = 3 * t + k;
            const std::int32_t o = m_mesh.O[from];
            setV(to, m_mesh.V[from]);
            setO(to, o);
            if (o != kNone) setO(o, to);
            m_cornerOf[m_mesh.V[to]] = to;
        }
    }
    if (m_record) {
        for (std::int32_t c = 3 * last; c < 3 * last + 3; ++c) {
            setV(c, kNone);
            setO(c, kNone);
        }
    }
    m_mesh.V.resize(3 * static_cast<std::size_t>(last));
    m_mesh.O.resize(3 * static_cast<std::size_t>(last));
}

// The exact boundary has no triangle for collinear points: the table empties, as the inserter's
// does for a collinear input.
void Remover::collapse(std::int32_t v) {
    RemoveOp op = beginOp(RemoveOpType::Collapse, v);
    if (m_record) {
        for (std::int32_t c = 0; c < m_mesh.numCorners(); ++c) {
            setV(c, kNone);
            setO(c, kNone);
        }
    }
    m_mesh.V.clear();
    m_mesh.O.clear();
    endOp(op);
    std::fill(m_cornerOf.begin(), m_cornerOf.end(), kNone);
    m_live = 0;
}

// ============================================================================================
// [SECTION] The closed form of a finished exact mesh, and back
// ============================================================================================

void addGhosts(Mesh& mesh) {
    const std::int32_t g = mesh.numVertices();
    mesh.G.push_back(mesh.G.empty() ? Vec2{} : mesh.G[0]);
    // ghostOf[x]: the ghost beside the boundary edge that starts at x.
    std::vector<std::int32_t> ghostOf(static_cast<std::size_t>(g), kNone);
    std::vector<std::int32_t> boundary;
    for (std::int32_t c = 0; c < mesh.numCorners(); ++c) {
        if (mesh.O[c] == kNone) boundary.push_back(c);
    }
    std::int32_t t = mesh.numTriangles();
    mesh.V.resize(mesh.V.size() + 3 * boundary.size());
    mesh.O.resize(mesh.O.size() + 3 * boundary.size());
    for (const std::int32_t c : boundary) {
        const std::int32_t x = mesh.V[next(c)], y = mesh.V[prev(c)];
        mesh.V[3 * t] = y;
        mesh.V[3 * t + 1] = x;
        mesh.V[3 * t + 2] = g;
        mesh.O[3 * t + 2] = c;
        mesh.O[c] = 3 * t + 2;
        ghostOf[x] = t++;
    }
    // The ghost of x->y and the ghost of y->z share the edge y-g.
    for (std::int32_t u = t - static_cast<std::int32_t>(boundary.size()); u < t; ++u) {
        const std::int32_t y = mesh.V[3 * u];
        const std::int32_t w = ghostOf[y];
        mesh.O[3 * u + 1] = 3 * w;
        mesh.O[3 * w] = 3 * u + 1;
    }
}

void dropVirtual(Mesh& mesh, std::int32_t firstVirtual) {
    const std::int32_t nt = mesh.numTriangles();
    std::vector<std::int32_t> newId(static_cast<std::size_t>(nt), kNone);
    std::int32_t kept = 0;
    for (std::int32_t t = 0; t < nt; ++t) {
        const bool virt = mesh.V[3 * t] >= firstVirtual || mesh.V[3 * t + 1] >= firstVirtual ||
                          mesh.V[3 * t + 2] >= firstVirtual;
        if (!virt) newId[t] = kept++;
    }
    for (std::int32_t t = 0; t < nt; ++t) {
        if (newId[t] == kNone) continue;
        for (int k = 0; k < 3; ++k) {
            const std::int32_t o = mesh.O[3 * t + k];
            const std::int32_t ot = o == kNone ? kNone : newId[tri(o)];
            mesh.V[3 * newId[t] + k] = mesh.V[3 * t + k];
            mesh.O[3 * newId[t] + k] = ot == kNone ? kNone : 3 * ot + o % 3;
        }
    }
    mesh.V.resize(3 * static_cast<std::size_t>(kept));
    mesh.O.resize(3 * static_cast<std::size_t>(kept));
    if (mesh.numVertices() > firstVirtual) mesh.G.resize(static_cast<std::size_t>(firstVirtual));
}

}  // namespace dlab
