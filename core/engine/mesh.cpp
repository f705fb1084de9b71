// Corner-table invariants: validate() reports broken rules by corner.
#include "core/engine/mesh.h"

#include "core/engine/predicates.h"

#include <string>

namespace dlab {

const char* toString(Violation::Kind kind) {
    switch (kind) {
        case Violation::Kind::BadSize: return "bad-size";
        case Violation::Kind::VertexRange: return "vertex-range";
        case Violation::Kind::OppositeRange: return "opposite-range";
        case Violation::Kind::OppositeSelf: return "opposite-self";
        case Violation::Kind::OppositeSymmetry: return "opposite-symmetry";
        case Violation::Kind::EdgeMismatch: return "edge-mismatch";
        case Violation::Kind::DegenerateTri: return "degenerate-triangle";
        case Violation::Kind::NotCounterClockwise: return "not-counter-clockwise";
        case Violation::Kind::NotDelaunay: return "not-delaunay";
    }
    return "unknown";
}

namespace {

class Checker {
public:
    Checker(const Mesh& mesh, const ValidateOptions& options) : m_mesh(mesh), m_options(options) {}

    std::vector<Violation> run() {
        const Mesh& m = m_mesh;
        if (m.V.size() != m.O.size() || m.V.size() % 3 != 0) {
            add(Violation::Kind::BadSize, kNone,
                "|V| = " + std::to_string(m.V.size()) + ", |O| = " + std::to_string(m.O.size()) +
                    " (must be equal multiples of 3)");
            return m_out;
        }
        const std::int32_t nc = m.numCorners();
        for (std::int32_t c = 0; c < nc && !full(); ++c) checkCombinatorics(c);
        if (!m_out.empty()) return m_out;  // geometry is meaningless on a broken table
        for (std::int32_t t = 0; t < m.numTriangles() && !full(); ++t) checkTriangle(t);
        return m_out;
    }

private:
    bool full() const { return m_out.size() >= m_options.maxViolations; }
    void add(Violation::Kind kind, std::int32_t c, std::string message) {
        if (!full()) m_out.push_back({kind, c, std::move(message)});
    }
    bool isVirtual(std::int32_t v) const {
        return m_options.firstVirtual >= 0 && v >= m_options.firstVirtual;
    }
    static std::string cs(std::int32_t c) { return "corner " + std::to_string(c); }

    void checkCombinatorics(std::int32_t c) {
        const Mesh& m = m_mesh;
        const std::int32_t v = m.V[c];
        if (v < 0 || v >= m.numVertices()) {
            add(Violation::Kind::VertexRange, c,
                cs(c) + ": V = " + std::to_string(v) +
                    " is not a vertex (|G| = " + std::to_string(m.numVertices()) + ")");
            return;
        }
        const std::int32_t o = m.O[c];
        if (o == kNone) return;
        if (o < 0 || o >= m.numCorners()) {
            add(Violation::Kind::OppositeRange, c,
                cs(c) + ": O = " + std::to_string(o) + " is not a corner");
            return;
        }
        if (tri(o) == tri(c)) {
            add(Violation::Kind::OppositeSelf, c,
                cs(c) + ": O = " + std::to_string(o) + " is in the same triangle");
            return;
        }
        if (m.O[o] != c) {
            add(Violation::Kind::OppositeSymmetry, c,
                cs(c) + ": O[c] = " + std::to_string(o) + " but O[" + std::to_string(o) +
                    "] = " + std::to_string(m.O[o]));
            return;
        }
        // The edge opposite c runs n(c)->p(c); seen from o it must run n(o)->p(o) reversed.
        if (m.V[next(c)] != m.V[prev(o)] || m.V[prev(c)] != m.V[next(o)]) {
            add(Violation::Kind::EdgeMismatch, c,
                cs(c) + ": edge " + std::to_string(m.V[next(c)]) + "-" +
                    std::to_string(m.V[prev(c)]) + " does not match the reversed edge " +
                    std::to_string(m.V[prev(o)]) + "-" + std::to_string(m.V[next(o)]) +
                    " across O[c] = " + std::to_string(o));
        }
    }

    void checkTriangle(std::int32_t t) {
        const Mesh& m = m_mesh;
        const std::int32_t c = 3 * t;
        const std::int32_t a = m.V[c], b = m.V[c + 1], d = m.V[c + 2];
        if (a == b || b == d || a == d) {
            add(Violation::Kind::DegenerateTri, c,
                "triangle " + std::to_string(t) + " repeats a vertex");
            return;
        }
        const bool virt = isVirtual(a) || isVirtual(b) || isVirtual(d);
        if (m_options.geometry && !virt && orient2d(m.G[a], m.G[b], m.G[d]) <= 0) {
            add(Violation::Kind::NotCounterClockwise, c,
                "triangle " + std::to_string(t) + " (" + std::to_string(a) + ", " +
                    std::to_string(b) + ", " + std::to_string(d) + ") is not counter-clockwise");
            return;
        }
        if (!m_options.delaunay || virt) return;
        for (std::int32_t k = 0; k < 3 && !full(); ++k) {
            const std::int32_t ck = c + k;
            const std::int32_t o = m.O[ck];
            if (o == kNone || o < ck) continue;  // each interior edge once
            const std::int32_t w = m.V[o];
            if (isVirtual(w)) continue;
            if (incircle(m.G[a], m.G[b], m.G[d], m.G[w]) > 0) {
                add(Violation::Kind::NotDelaunay, ck,
                    cs(ck) + ": vertex " + std::to_string(w) + " (across the edge " +
                        std::to_string(m.V[next(ck)]) + "-" + std::to_string(m.V[prev(ck)]) +
                        ") lies inside the circumcircle of triangle " + std::to_string(t));
            }
        }
    }

    const Mesh& m_mesh;
    const ValidateOptions& m_options;
    std::vector<Violation> m_out;
};

}  // namespace

std::vector<Violation> validate(const Mesh& mesh, const ValidateOptions& options) {
    return Checker(mesh, options).run();
}

}  // namespace dlab
