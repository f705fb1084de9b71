// A mesh's edges against the Delaunay triangulation of its points (sorted edge lists, merged).
#include "core/engine/mesh_diff.h"

#include "core/engine/inserter.h"
#include "core/engine/predicates.h"

#include <algorithm>
#include <numeric>

namespace dlab {

namespace {

// For every vertex id, the smallest id at the same position.
std::vector<std::int32_t> firstCopies(const std::vector<Vec2>& G) {
    std::vector<std::int32_t> ids(G.size());
    std::iota(ids.begin(), ids.end(), 0);
    std::sort(ids.begin(), ids.end(), [&](std::int32_t a, std::int32_t b) {
        if (G[a].x != G[b].x) return G[a].x < G[b].x;
        if (G[a].y != G[b].y) return G[a].y < G[b].y;
        return a < b;
    });
    std::vector<std::int32_t> first(G.size());
    for (std::size_t i = 0, j = 0; i < ids.size(); i = j) {
        for (j = i; j < ids.size() && G[ids[j]] == G[ids[i]]; ++j) first[ids[j]] = ids[i];
    }
    return first;
}

struct CornerEdge {
    MeshEdge edge;
    std::int32_t corner;  // the corner opposite it
    bool operator<(const CornerEdge& o) const { return edge < o.edge; }
};

// Each undirected edge once, with one corner opposite it.
std::vector<CornerEdge> edgesOf(const Mesh& m, const std::vector<std::int32_t>& first) {
    std::vector<CornerEdge> edges;
    edges.reserve(m.V.size());
    for (std::int32_t c = 0; c < static_cast<std::int32_t>(m.V.size()); ++c) {
        std::int32_t a = first[m.V[next(c)]], b = first[m.V[prev(c)]];
        if (a > b) std::swap(a, b);
        edges.push_back({{a, b}, c});
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(
        std::unique(edges.begin(), edges.end(),
                    [](const CornerEdge& x, const CornerEdge& y) { return x.edge == y.edge; }),
        edges.end());
    return edges;
}

bool cocircularAt(const Mesh& m, std::int32_t c) {
    const std::int32_t o = m.O[c];
    if (o == kNone) return false;
    return incircle(m.G[m.V[c]], m.G[m.V[next(c)]], m.G[m.V[prev(c)]], m.G[m.V[o]]) == 0;
}

}  // namespace

DelaunayDiff diffWithDelaunay(const Mesh& given) {
    Inserter ins(given.G, InsertOptions{});
    ins.run();
    const Mesh& ours = ins.mesh();
    const std::vector<std::int32_t> first = firstCopies(given.G);
    const std::vector<CornerEdge> a = edgesOf(given, first), b = edgesOf(ours, first);
    DelaunayDiff d;
    std::size_t i = 0, j = 0;
    while (i < a.size() || j < b.size()) {
        if (j == b.size() || (i < a.size() && a[i].edge < b[j].edge)) {
            d.onlyGiven.push_back(a[i++].edge);
        } else if (i == a.size() || b[j].edge < a[i].edge) {
            d.onlyDelaunay.push_back(b[j].edge);
            if (cocircularAt(ours, b[j].corner)) ++d.cocircular;
            ++j;
        } else {
            ++d.sharedEdges;
            ++i;
            ++j;
        }
    }
    return d;
}

}  // namespace dlab
