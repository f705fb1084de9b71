// Building a corner table from triangles alone: O from V, and one starting corner per vertex.
#include "core/engine/mesh_build.h"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

namespace dlab {

namespace {

// The edge opposite corner c runs from V[n(c)] to V[p(c)] (counter-clockwise around t(c)).
std::int32_t edgeFrom(const Mesh& m, std::int32_t c) { return m.V[next(c)]; }
std::int32_t edgeTo(const Mesh& m, std::int32_t c) { return m.V[prev(c)]; }

std::string edgeName(std::int32_t a, std::int32_t b) {
    return std::to_string(a) + "->" + std::to_string(b);
}

void checkTriangles(const Mesh& m) {
    if (m.V.size() % 3 != 0) {
        throw std::invalid_argument("computeOpposites: |V| = " + std::to_string(m.V.size()) +
                                    " is not a multiple of 3");
    }
    if (m.V.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
        throw std::invalid_argument("computeOpposites: too many corners for int32 ids");
    }
    const std::int32_t nv = m.numVertices();
    for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
        const std::int32_t a = m.V[corner(t, 0)], b = m.V[corner(t, 1)], c = m.V[corner(t, 2)];
        for (std::int32_t v : {a, b, c}) {
            if (v < 0 || v >= nv) {
                throw std::invalid_argument("computeOpposites: triangle " + std::to_string(t) +
                                            " uses vertex " + std::to_string(v) + ", outside [0, " +
                                            std::to_string(nv) + ")");
            }
        }
        if (a == b || b == c || c == a) {
            throw std::invalid_argument("computeOpposites: triangle " + std::to_string(t) +
                                        " repeats a vertex (" + std::to_string(a) + ", " +
                                        std::to_string(b) + ", " + std::to_string(c) + ")");
        }
    }
}

}  // namespace

void computeOpposites(Mesh& m) {
    checkTriangles(m);
    const std::int32_t nc = m.numCorners();
    const std::int32_t nv = m.numVertices();

    // Bucket every corner by the smaller endpoint of its opposite edge (a counting sort), so
    // the two corners facing one undirected edge land in the same, small bucket: the buckets
    // hold about 6 corners on average in a triangulation, which keeps this linear without a
    // hash table.
    std::vector<std::int32_t> start(static_cast<std::size_t>(nv) + 1, 0);
    for (std::int32_t c = 0; c < nc; ++c) ++start[std::min(edgeFrom(m, c), edgeTo(m, c)) + 1];
    for (std::int32_t v = 0; v < nv; ++v) start[v + 1] += start[v];
    std::vector<std::int32_t> bucket(static_cast<std::size_t>(nc));
    {
        std::vector<std::int32_t> fill(start.begin(), start.end() - 1);
        for (std::int32_t c = 0; c < nc; ++c) {
            bucket[fill[std::min(edgeFrom(m, c), edgeTo(m, c))]++] = c;
        }
    }

    auto larger = [&](std::int32_t c) { return std::max(edgeFrom(m, c), edgeTo(m, c)); };
    std::vector<std::int32_t> opposite(static_cast<std::size_t>(nc), kNone);
    for (std::int32_t lo = 0; lo < nv; ++lo) {
        const auto first = bucket.begin() + start[lo];
        const auto last = bucket.begin() + start[lo + 1];
        // Ties broken by corner id so the error messages do not depend on the sort.
        std::sort(first, last, [&](std::int32_t x, std::int32_t y) {
            const std::int32_t hx = larger(x), hy = larger(y);
            return hx != hy ? hx < hy : x < y;
        });
        for (auto run = first; run != last;) {
            auto end = run + 1;
            while (end != last && larger(*end) == larger(*run)) ++end;
            const std::int32_t hi = larger(*run);
            if (end - run > 2) {
                std::string tris;
                for (auto it = run; it != end; ++it) {
                    tris += (it == run ? "" : ", ") + std::to_string(tri(*it));
                }
                throw std::invalid_argument(
                    "computeOpposites: edge " + std::to_string(lo) + "-" + std::to_string(hi) +
                    " is shared by " + std::to_string(end - run) + " triangles (" + tris +
                    "); a triangulation shares an edge between at most two");
            }
            if (end - run == 2) {
                const std::int32_t c = run[0], d = run[1];
                if (edgeFrom(m, c) == edgeFrom(m, d)) {
                    throw std::invalid_argument(
                        "computeOpposites: triangles " + std::to_string(tri(c)) + " and " +
                        std::to_string(tri(d)) + " both traverse edge " +
                        edgeName(edgeFrom(m, c), edgeTo(m, c)) +
                        " in the same direction (inconsistent orientation: one of them is "
                        "clockwise)");
                }
                opposite[c] = d;
                opposite[d] = c;
            }
            run = end;
        }
    }
    m.O = std::move(opposite);
}

std::vector<std::int32_t> vertexCorners(const Mesh& m) {
    if (m.O.size() != m.V.size()) {
        throw std::invalid_argument("vertexCorners: |O| = " + std::to_string(m.O.size()) +
                                    " differs from |V| = " + std::to_string(m.V.size()) +
                                    " (call computeOpposites first)");
    }
    std::vector<std::int32_t> out(static_cast<std::size_t>(m.numVertices()), kNone);
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        // r(c) == kNone: the edge V[c]-V[n(c)], the clockwise side of c's wedge, is on the
        // boundary, so nothing lies further clockwise and s() from c reaches the whole fan.
        // Such a corner wins over any interior one; among several (a vertex where two fans
        // touch: not a triangulation) the last one is kept.
        if (out[m.V[c]] == kNone || m.r(c) == kNone) out[m.V[c]] = c;
    }
    return out;
}

}  // namespace dlab
