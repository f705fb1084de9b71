// Removal and constrained edges against CGAL, an implementation that shares nothing with ours:
// after every removal of every vertex in random order (down to 3 points) and after 1000
// constraints on 10^4 points, our triangulation and CGAL's have the same edges, except where four
// points lie on one circle (either diagonal is Delaunay there), decided exactly; the constrained
// edges are the same.
#include "core/engine/constrainer.h"
#include "core/engine/generators.h"
#include "core/engine/inserter.h"
#include "core/engine/predicates.h"
#include "core/engine/remover.h"
#include "tests/distinct_points.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

using namespace dlab;
using dlab::testutil::distinct;

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::int32_t, K>;
using Dt = CGAL::Delaunay_triangulation_2<K, CGAL::Triangulation_data_structure_2<Vb>>;
using CdtVb = CGAL::Triangulation_vertex_base_with_info_2<std::int32_t, K>;
using CdtFb = CGAL::Constrained_triangulation_face_base_2<K>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<
    K, CGAL::Triangulation_data_structure_2<CdtVb, CdtFb>, CGAL::Exact_predicates_tag>;
using Edge = std::pair<std::int32_t, std::int32_t>;
using EdgeSet = std::set<Edge>;

Edge edge(std::int32_t a, std::int32_t b) { return {std::min(a, b), std::max(a, b)}; }

template <class T>
EdgeSet cgalEdges(const T& t, bool constrainedOnly = false) {
    EdgeSet out;
    for (auto e = t.finite_edges_begin(); e != t.finite_edges_end(); ++e) {
        if constexpr (std::is_same_v<T, Cdt>) {
            if (constrainedOnly && !t.is_constrained(*e)) continue;
        }
        const auto f = e->first;
        out.insert(edge(f->vertex(T::cw(e->second))->info(), f->vertex(T::ccw(e->second))->info()));
    }
    return out;
}

// The closed mesh's edges between finite vertices (ids below n), and why each of ours that CGAL
// lacks may differ: "" when its two triangles' four points are cocircular and it is not
// constrained, else what is wrong. Every difference of CGAL's must be matched by one of ours.
std::string compare(const Mesh& m, std::int32_t n, const EdgeSet& theirs,
                    const std::vector<std::uint8_t>* constrained = nullptr) {
    EdgeSet ours;
    std::size_t onlyOurs = 0;
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        const std::int32_t a = m.V[next(c)], b = m.V[prev(c)];
        if (a < 0 || b < 0 || a >= n || b >= n || !ours.insert(edge(a, b)).second) continue;
        if (theirs.count(edge(a, b))) continue;
        ++onlyOurs;
        const std::int32_t o = m.O[c];
        const bool finite = o != kNone && m.V[c] < n && m.V[o] < n;
        const bool free = !constrained || ((*constrained)[c] == 0 && (*constrained)[o] == 0);
        if (!finite || !free || incircle(m.G[m.V[c]], m.G[a], m.G[b], m.G[m.V[o]]) != 0) {
            return "edge " + std::to_string(a) + "-" + std::to_string(b) +
                   " is ours only, and its quadrilateral is not cocircular";
        }
    }
    std::size_t onlyTheirs = 0;
    for (const Edge& e : theirs) onlyTheirs += ours.count(e) ? 0 : 1;
    if (onlyTheirs != onlyOurs) {
        return std::to_string(onlyOurs) + " edges only ours, " + std::to_string(onlyTheirs) +
               " only CGAL's";
    }
    return "";
}

// The inserter's mesh before Finalize: the exact mode's ghost triangles still in.
Mesh closedMesh(const std::vector<Vec2>& pts) {
    Inserter ins(pts);
    while (ins.control().phase != Phase::Finalize && !ins.done()) ins.step();
    return ins.mesh();
}

void removeAllAgainstCgal(const std::vector<Vec2>& input, std::uint64_t seed,
                          const std::string& label) {
    SCOPED_TRACE(label);
    const std::vector<Vec2> pts = distinct(input);
    const auto n = static_cast<std::int32_t>(pts.size());
    Mesh mesh = closedMesh(pts);
    Remover remover(mesh, n, Boundary::Exact);
    Dt dt;
    std::vector<Dt::Vertex_handle> handle(pts.size());
    for (std::int32_t i = 0; i < n; ++i) {
        handle[i] = dt.insert(K::Point_2(pts[i].x, pts[i].y));
        handle[i]->info() = i;
    }
    std::vector<std::int32_t> order(pts.size());
    for (std::int32_t i = 0; i < n; ++i) order[i] = i;
    std::mt19937_64 rng(seed);
    std::shuffle(order.begin(), order.end(), rng);
    int compared = 0;
    for (std::size_t step = 0; step + 3 < order.size(); ++step) {
        const std::int32_t v = order[step];
        remover.remove(v);
        dt.remove(handle[v]);
        if (dt.dimension() < 2) continue;  // the points left are collinear: no triangle
        const std::string err = compare(mesh, n, cgalEdges(dt));
        ASSERT_EQ(err, "") << "after removing vertex " << v << " (step " << step << ")";
        ++compared;
    }
    EXPECT_GT(compared, 0);
}

}  // namespace

TEST(AgainstCgal, RemovingEveryVertexInRandomOrderKeepsCgalsTriangulation) {
    const Generator general[] = {
        Generator::Uniform,        Generator::Clusters,  Generator::Gaussian, Generator::Kuzmin,
        Generator::UnevenClusters, Generator::DiscInBox, Generator::LogRadial};
    int sets = 0;
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
        for (const Generator g : general) {
            removeAllAgainstCgal(generatePoints(g, 90, seed), seed,
                                 std::string(toString(g)) + " seed " + std::to_string(seed));
            ++sets;
        }
    }
    // Degenerate: cocircular lattices and polygons, collinear runs.
    for (const Generator g : {Generator::Grid, Generator::Ngon, Generator::Collinear}) {
        removeAllAgainstCgal(generatePoints(g, 80, 2), 2, toString(g));
        ++sets;
    }
    EXPECT_GE(sets, 20);
}

namespace {

// Inserts segments between points at most `reach` apart until `want` are accepted (ours refuses
// one that crosses a constrained edge; CGAL then gets only the accepted ones), and compares.
void constrainAgainstCgal(const std::vector<Vec2>& input, int want, double reach,
                          std::uint64_t seed, const std::string& label) {
    SCOPED_TRACE(label);
    const std::vector<Vec2> pts = distinct(input);
    const auto n = static_cast<std::int32_t>(pts.size());
    Inserter ins(pts);
    ins.run();
    Mesh mesh = ins.takeMesh();
    addGhosts(mesh);
    Constrainer con(mesh, n);
    Cdt cdt;
    std::vector<Cdt::Vertex_handle> handle(pts.size());
    for (std::int32_t i = 0; i < n; ++i) {
        handle[i] = cdt.insert(K::Point_2(pts[i].x, pts[i].y));
        handle[i]->info() = i;
    }
    std::vector<std::int32_t> byX(pts.size());  // b is drawn among a's neighbours in x
    for (std::int32_t i = 0; i < n; ++i) byX[i] = i;
    std::sort(byX.begin(), byX.end(), [&](std::int32_t i, std::int32_t j) {
        return pts[i].x < pts[j].x || (pts[i].x == pts[j].x && pts[i].y < pts[j].y);
    });
    std::mt19937_64 rng(seed);
    int accepted = 0;
    for (int tries = 0; accepted < want && tries < 100 * want; ++tries) {
        const auto r = static_cast<std::int32_t>(rng() % n);
        const std::int32_t s =
            std::clamp(r + static_cast<std::int32_t>(rng() % 301) - 150, 0, n - 1);
        const std::int32_t a = byX[r], b = byX[s];
        const double dx = pts[a].x - pts[b].x, dy = pts[a].y - pts[b].y;
        if (a == b || dx * dx + dy * dy > reach * reach) continue;
        if (con.insert(a, b).result != ConstrainResult::Inserted) continue;
        cdt.insert_constraint(handle[a], handle[b]);
        ++accepted;
    }
    ASSERT_EQ(accepted, want);
    ASSERT_EQ(compare(mesh, n, cgalEdges(cdt), &con.flags()), "");
    EdgeSet ours;
    for (std::int32_t c = 0; c < mesh.numCorners(); ++c) {
        if (con.isConstrained(c)) ours.insert(edge(mesh.V[next(c)], mesh.V[prev(c)]));
    }
    EXPECT_EQ(ours, cgalEdges(cdt, true));
}

}  // namespace

TEST(AgainstCgal, AThousandConstraintsOnTenThousandPointsGiveCgalsConstrainedTriangulation) {
    constrainAgainstCgal(generatePoints(Generator::Uniform, 10000, 4), 1000, 60, 4, "uniform 10^4");
    // A lattice: segments through vertices (split there), collinear runs, cocircular squares.
    std::vector<Vec2> lattice;
    for (int y = 0; y < 40; ++y) {
        for (int x = 0; x < 40; ++x) lattice.push_back({double(x), double(y)});
    }
    constrainAgainstCgal(lattice, 200, 6, 5, "lattice 40x40");
}
