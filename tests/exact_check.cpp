#include "tests/exact_check.h"

#include <gmpxx.h>

#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <utility>

using dlab::Mesh;
using dlab::Vec2;

int orientGmp(Vec2 a, Vec2 b, Vec2 c) {
    const mpq_class ax(a.x), ay(a.y);
    const mpq_class d = (mpq_class(b.x) - ax) * (mpq_class(c.y) - ay) -
                        (mpq_class(b.y) - ay) * (mpq_class(c.x) - ax);
    return sgn(d);
}

int incircleGmp(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
    const mpq_class dx(d.x), dy(d.y);
    const mpq_class adx = a.x - dx, ady = a.y - dy, bdx = b.x - dx, bdy = b.y - dy, cdx = c.x - dx,
                    cdy = c.y - dy;
    const mpq_class al = adx * adx + ady * ady, bl = bdx * bdx + bdy * bdy,
                    cl = cdx * cdx + cdy * cdy;
    const mpq_class det =
        al * (bdx * cdy - cdx * bdy) + bl * (cdx * ady - adx * cdy) + cl * (adx * bdy - bdx * ady);
    return sgn(det);
}

std::vector<std::int32_t> firstOccurrences(const std::vector<Vec2>& pts) {
    std::map<std::pair<double, double>, std::int32_t> seen;
    std::vector<std::int32_t> out;
    for (std::int32_t i = 0; i < static_cast<std::int32_t>(pts.size()); ++i) {
        if (seen.emplace(std::make_pair(pts[i].x, pts[i].y), i).second) out.push_back(i);
    }
    return out;
}

bool allCollinearExact(const std::vector<Vec2>& points) {
    std::size_t i = 1;
    while (i < points.size() && points[i].x == points[0].x && points[i].y == points[0].y) ++i;
    if (i >= points.size()) return true;
    for (std::size_t k = i + 1; k < points.size(); ++k) {
        if (orientGmp(points[0], points[i], points[k]) != 0) return false;
    }
    return true;
}

std::string checkDelaunayExact(const Mesh& m, const std::vector<std::int32_t>* expectedVertices) {
    std::ostringstream err;
    const std::int32_t nc = m.numCorners();
    if (m.V.size() != m.O.size() || nc % 3 != 0)
        return "V and O sizes differ or are not a multiple of 3";
    const std::int32_t nt = nc / 3;
    auto vtx = [&](std::int32_t c) { return m.V[c]; };
    auto nx = [](std::int32_t c) { return c % 3 == 2 ? c - 2 : c + 1; };
    auto pv = [](std::int32_t c) { return c % 3 == 0 ? c + 2 : c - 1; };

    // Directed edges a->b (the edge opposite corner c runs V[n(c)] -> V[p(c)]).
    std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> edges;
    std::set<std::int32_t> used;
    for (std::int32_t c = 0; c < nc; ++c) {
        if (vtx(c) < 0 || vtx(c) >= m.numVertices())
            return "corner " + std::to_string(c) + ": vertex out of range";
        used.insert(vtx(c));
        if (!edges.emplace(std::make_pair(vtx(nx(c)), vtx(pv(c))), c).second) {
            err << "directed edge " << vtx(nx(c)) << "->" << vtx(pv(c)) << " used twice";
            return err.str();
        }
    }
    for (std::int32_t t = 0; t < nt; ++t) {
        if (orientGmp(m.G[vtx(3 * t)], m.G[vtx(3 * t + 1)], m.G[vtx(3 * t + 2)]) <= 0) {
            err << "triangle " << t << " (" << vtx(3 * t) << "," << vtx(3 * t + 1) << ","
                << vtx(3 * t + 2) << ") is not strictly counter-clockwise";
            return err.str();
        }
    }
    // O against the shared edges, and the boundary.
    std::map<std::int32_t, std::int32_t> hullNext;  // boundary edge a->b (the mesh is left of it)
    for (std::int32_t c = 0; c < nc; ++c) {
        const auto twin = edges.find({vtx(pv(c)), vtx(nx(c))});
        const std::int32_t expectO = twin == edges.end() ? -1 : twin->second;
        if (m.O[c] != expectO) {
            err << "O[" << c << "] = " << m.O[c] << ", the shared edge says " << expectO;
            return err.str();
        }
        if (expectO == -1) {
            if (!hullNext.emplace(vtx(nx(c)), vtx(pv(c))).second) {
                err << "vertex " << vtx(nx(c)) << " starts two boundary edges (not a disk)";
                return err.str();
            }
        }
    }
    if (nt > 0) {
        if (hullNext.size() < 3) return "boundary has fewer than 3 edges";
        // One loop, turning left or straight everywhere.
        const std::int32_t start = hullNext.begin()->first;
        std::int32_t a = start, steps = 0;
        do {
            const std::int32_t b = hullNext.at(a);
            const auto it = hullNext.find(b);
            if (it == hullNext.end())
                return "boundary is not closed at vertex " + std::to_string(b);
            if (orientGmp(m.G[a], m.G[b], m.G[it->second]) < 0) {
                err << "boundary turns right at vertex " << b << " (the hull is not convex)";
                return err.str();
            }
            a = b;
            if (++steps > static_cast<std::int32_t>(hullNext.size()))
                return "boundary loop does not close";
        } while (a != start);
        if (steps != static_cast<std::int32_t>(hullNext.size()))
            return "boundary has more than one loop";
        const std::int64_t expectT = 2 * static_cast<std::int64_t>(used.size()) -
                                     static_cast<std::int64_t>(hullNext.size()) - 2;
        if (nt != expectT) {
            err << nt << " triangles, Euler for " << used.size() << " vertices and "
                << hullNext.size() << " hull vertices needs " << expectT;
            return err.str();
        }
    }
    for (std::int32_t c = 0; c < nc; ++c) {
        const std::int32_t o = m.O[c];
        if (o < 0 || o < c) continue;
        const std::int32_t t = c / 3;
        if (incircleGmp(m.G[vtx(3 * t)], m.G[vtx(3 * t + 1)], m.G[vtx(3 * t + 2)], m.G[vtx(o)]) >
            0) {
            err << "edge " << vtx(nx(c)) << "-" << vtx(pv(c)) << " is not Delaunay: vertex "
                << vtx(o) << " is inside the circle of triangle " << t;
            return err.str();
        }
    }
    if (expectedVertices) {
        const std::set<std::int32_t> want(expectedVertices->begin(), expectedVertices->end());
        if (want != used) {
            err << "the mesh uses " << used.size() << " vertices, expected " << want.size();
            return err.str();
        }
    }
    return "";
}
