// Point-set generators (deterministic for a seed on every platform).
#include "core/engine/generators.h"

#include "core/engine/mesh_build.h"
#include "core/engine/order.h"
#include "core/engine/predicates.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <iterator>
#include <numbers>
#include <stdexcept>

namespace dlab {

namespace {
constexpr const char* kNames[] = {
    "uniform",   "clusters",        "grid",          "rotated-grid",  "ngon",     "circle",
    "collinear", "near-duplicates", "huge-tiny-box", "all-collinear", "gaussian", "uneven-clusters",
    "kuzmin",    "log-radial",      "disc-in-box",   "curves",        "parabola", "facing-arcs",
    "spiral",    "convex-hull"};
constexpr int kCount = static_cast<int>(std::size(kNames));

double gaussian(SplitMix64& rng) {
    // Box-Muller; the first uniform is kept away from 0.
    const double u = (rng.next() >> 11) * 0x1.0p-53 + 0x1.0p-54;
    const double v = rng.uniform01();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2 * std::numbers::pi * v);
}

Vec2 onCircle(SplitMix64& rng, double r) {
    const double t = 2 * std::numbers::pi * rng.uniform01();
    return {r * std::cos(t), r * std::sin(t)};
}

// k clusters, cluster j drawing a point with probability 2^-(j+1) (the last takes the rest);
// their spreads are log-spaced from 100 down to 0.001 and dealt to the clusters at random, so
// sizes and densities differ by decades in every pairing.
void unevenClusters(std::vector<Vec2>& pts, std::size_t n, SplitMix64& rng) {
    const int k = std::max(1, static_cast<int>(std::bit_width(n)) - 1);
    std::vector<Vec2> centres;
    std::vector<double> sigma;
    for (int j = 0; j < k; ++j) {
        centres.push_back({rng.uniform01() * 1600, rng.uniform01() * 1600});
        sigma.push_back(std::pow(10.0, 2 - 5.0 * j / std::max(1, k - 1)));
    }
    for (int j = k - 1; j > 0; --j)
        std::swap(sigma[j], sigma[rng.below(static_cast<std::uint32_t>(j + 1))]);
    for (std::size_t i = 0; i < n; ++i) {
        const int j = std::min(std::countr_zero(rng.next() | (1ull << 63)), k - 1);
        pts.push_back(
            {centres[j].x + gaussian(rng) * sigma[j], centres[j].y + gaussian(rng) * sigma[j]});
    }
}

// A line, a circle and a spiral; the parameter of each is u^3 or u^2 for a uniform u, so that
// the points crowd towards one end of the curve.
Vec2 onCurve(SplitMix64& rng) {
    const double u = rng.uniform01();
    switch (rng.below(3)) {
        case 0: {
            const double t = u * u * u;
            return {100 + 1400 * t, 100 + 600 * t};
        }
        case 1: {
            const double t = 2 * std::numbers::pi * u * u;
            return {800 + 600 * std::cos(t), 800 + 600 * std::sin(t)};
        }
        default: {
            const double t = u * u * u, r = 20 + 500 * t, a = 6 * std::numbers::pi * t;
            return {800 + r * std::cos(a), 800 + r * std::sin(a)};
        }
    }
}
}  // namespace

const char* toString(Generator g) { return kNames[static_cast<int>(g)]; }

std::optional<Generator> parseGenerator(std::string_view name) {
    for (int i = 0; i < kCount; ++i) {
        if (name == kNames[i]) return static_cast<Generator>(i);
    }
    return std::nullopt;
}

std::string generatorNames() {
    std::string s;
    for (int i = 0; i < kCount; ++i) s += (i ? ", " : "") + std::string(kNames[i]);
    return s;
}

std::vector<Generator> allGenerators() {
    std::vector<Generator> all;
    for (int i = 0; i < kCount; ++i) all.push_back(static_cast<Generator>(i));
    return all;
}

namespace {
constexpr double kBox = 1600.0;  // the paper's square

// The generators whose points are drawn independently of each other, one point per call.
Vec2 uniformPoint(SplitMix64& rng) { return {rng.uniform01() * kBox, rng.uniform01() * kBox}; }

Vec2 circlePoint(SplitMix64& rng) {
    const double t = 2 * std::numbers::pi * rng.uniform01();
    return {800 + 700 * std::cos(t), 800 + 700 * std::sin(t)};
}

// Three lines (y = 0, x = 0, y = x) with integer positions, and one point in four anywhere.
Vec2 collinearPoint(SplitMix64& rng) {
    const std::uint32_t line = rng.below(4);
    const double t = double(rng.below(1000));
    switch (line) {
        case 0: return {t, 0};
        case 1: return {0, t};
        case 2: return {t, t};
        default: return {rng.uniform01() * 1000, rng.uniform01() * 1000};
    }
}

// ulp(1e15) = 0.125: only 512 distinct values per axis, every test is close.
Vec2 hugeTinyBoxPoint(SplitMix64& rng) {
    return {1e15 + rng.uniform01() * 64, -3e15 + rng.uniform01() * 64};
}

// Integer x and y = x/2 + 3: exactly on one line (no rounding anywhere).
Vec2 allCollinearPoint(SplitMix64& rng) {
    const double t = double(rng.below(100000));
    return {t, 0.5 * t + 3};
}

Vec2 gaussianPoint(SplitMix64& rng) {
    return {800 + 200 * gaussian(rng), 800 + 200 * gaussian(rng)};
}

// The inverse of Kuzmin's mass function; 1 - s > 0, so r is finite (at most ~2^53).
Vec2 kuzminPoint(SplitMix64& rng) {
    const double s = rng.uniform01();
    return onCircle(rng, std::sqrt(1 / ((1 - s) * (1 - s)) - 1));
}

Vec2 logRadialPoint(SplitMix64& rng) {
    return onCircle(rng, std::pow(10.0, -12 * rng.uniform01()));
}

// One point in ten anywhere in the box, the rest in a disc of radius 4 at its centre.
Vec2 discInBoxPoint(SplitMix64& rng) {
    if (rng.below(10) == 0) return uniformPoint(rng);
    const Vec2 d = onCircle(rng, 4 * std::sqrt(rng.uniform01()));
    return {800 + d.x, 800 + d.y};
}

// y = x^2 for x uniform over [-1, 1], scaled to the box: the hull holds every point.
Vec2 parabolaPoint(SplitMix64& rng) {
    const double x = 2 * rng.uniform01() - 1;
    return {800 + 800 * x, 1600 * x * x};
}

// Two arcs of radius 1000, a third of a turn each, bulging towards each other: their points face
// across the middle of the box, 40 apart at the closest.
Vec2 facingArcsPoint(SplitMix64& rng) {
    const double t = (rng.uniform01() - 0.5) * 2 * std::numbers::pi / 3;
    const double side = rng.below(2) ? 1.0 : -1.0;
    return {800 + side * (20 + 1000 * (1 - std::cos(t))), 800 + 1000 * std::sin(t)};
}

// r = 700 s, angle 12 pi s, with s = sqrt(u) for a uniform u: evenly spread along the curve.
Vec2 spiralPoint(SplitMix64& rng) {
    const double s = std::sqrt(rng.uniform01());
    const double a = 12 * std::numbers::pi * s;
    return {800 + 700 * s * std::cos(a), 800 + 700 * s * std::sin(a)};
}

// Integer x in [-2^20, 2^20) and y = x^2 < 2^40: exact, so every distinct point is a hull vertex.
Vec2 convexHullPoint(SplitMix64& rng) {
    const double x = double(rng.below(1u << 21)) - double(1u << 20);
    return {x, x * x};
}

// About sqrt(n/16) clusters of spread 20, each point in one picked at random.
void clusters(std::vector<Vec2>& pts, std::size_t n, SplitMix64& rng) {
    const std::size_t k = std::max<std::size_t>(1, static_cast<std::size_t>(std::sqrt(n / 16.0)));
    std::vector<Vec2> centres;
    for (std::size_t i = 0; i < k; ++i) centres.push_back(uniformPoint(rng));
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 c = centres[rng.below(static_cast<std::uint32_t>(k))];
        pts.push_back({c.x + gaussian(rng) * 20, c.y + gaussian(rng) * 20});
    }
}

// A square integer lattice, rotated by `angle` radians.
void lattice(std::vector<Vec2>& pts, std::size_t n, double angle) {
    const std::size_t side =
        std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(std::sqrt(double(n)))));
    for (std::size_t i = 0; i < n; ++i) {
        const double x = double(i % side), y = double(i / side);
        pts.push_back(
            {x * std::cos(angle) - y * std::sin(angle), x * std::sin(angle) + y * std::cos(angle)});
    }
}

// A regular n-gon: multiples of 45 degrees are exact; the rest are within an ulp of the circle.
void ngon(std::vector<Vec2>& pts, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
        const double t = 2 * std::numbers::pi * double(i) / double(n);
        pts.push_back({800 + 700 * std::cos(t), 800 + 700 * std::sin(t)});
    }
}

// One point in three on an integer position; the others copy an earlier point and move it by
// 0 to 4 ulps in x and 0 to 2 in y (0: an exact duplicate).
void nearDuplicates(std::vector<Vec2>& pts, std::size_t n, SplitMix64& rng) {
    for (std::size_t i = 0; i < n; ++i) {
        if (i % 3 == 0 || pts.empty()) {
            pts.push_back({std::round(rng.uniform01() * 100), std::round(rng.uniform01() * 100)});
            continue;
        }
        Vec2 p = pts[rng.below(static_cast<std::uint32_t>(pts.size()))];
        const std::uint32_t ulps = rng.below(5);
        for (std::uint32_t k = 0; k < ulps; ++k) p.x = std::nextafter(p.x, 1e300);
        for (std::uint32_t k = 0; k < rng.below(3); ++k) p.y = std::nextafter(p.y, -1e300);
        pts.push_back(p);
    }
}

using PointFn = Vec2 (*)(SplitMix64&);

// The per-point function of an independent generator; nullptr for those that need the whole set.
PointFn pointFunction(Generator kind) {
    switch (kind) {
        case Generator::Uniform: return uniformPoint;
        case Generator::Circle: return circlePoint;
        case Generator::Collinear: return collinearPoint;
        case Generator::HugeTinyBox: return hugeTinyBoxPoint;
        case Generator::AllCollinear: return allCollinearPoint;
        case Generator::Gaussian: return gaussianPoint;
        case Generator::Kuzmin: return kuzminPoint;
        case Generator::LogRadial: return logRadialPoint;
        case Generator::DiscInBox: return discInBoxPoint;
        case Generator::Curves: return onCurve;
        case Generator::Parabola: return parabolaPoint;
        case Generator::FacingArcs: return facingArcsPoint;
        case Generator::Spiral: return spiralPoint;
        case Generator::ConvexHull: return convexHullPoint;
        default: return nullptr;
    }
}
}  // namespace

std::vector<Vec2> generatePoints(Generator kind, std::size_t n, std::uint64_t seed) {
    SplitMix64 rng(seed);
    std::vector<Vec2> pts;
    pts.reserve(n);
    if (const PointFn point = pointFunction(kind)) {
        for (std::size_t i = 0; i < n; ++i) pts.push_back(point(rng));
        return pts;
    }
    switch (kind) {
        case Generator::Clusters: clusters(pts, n, rng); break;
        case Generator::Grid: lattice(pts, n, 0.0); break;
        case Generator::RotatedGrid: lattice(pts, n, 0.5); break;  // radians, irrational-ish
        case Generator::Ngon: ngon(pts, n); break;
        case Generator::NearDuplicates: nearDuplicates(pts, n, rng); break;
        case Generator::UnevenClusters: unevenClusters(pts, n, rng); break;
        default: break;
    }
    return pts;
}

Mesh flipWorstCase(std::size_t n) {
    if (n < 6 || n % 2 != 0 || n > (std::size_t{1} << 16))
        throw std::invalid_argument(
            "the flip worst case takes an even number of points, 6 to 65536");
    const auto m = static_cast<std::int32_t>(n / 2);
    // Bow i * (m - 1 - i) peaks at (m - 1)^2 / 4; the chains are 6 peaks apart, points 2 apart.
    const double peak = static_cast<double>(m - 1) * (m - 1) / 4.0;
    const double height = 6.0 * std::ceil(peak), step = 2.0 * std::ceil(peak);
    Mesh mesh;
    for (std::int32_t i = 0; i < m; ++i)  // lower chain: vertices 0 .. m-1
        mesh.G.push_back({i * step, static_cast<double>(i) * (m - 1 - i)});
    for (std::int32_t i = 0; i < m; ++i)  // upper chain: vertices m .. 2m-1
        mesh.G.push_back({i * step, height - static_cast<double>(i) * (m - 1 - i)});
    auto add = [&mesh](std::int32_t a, std::int32_t b, std::int32_t c) {
        if (orient2d(mesh.G[a], mesh.G[b], mesh.G[c]) < 0) std::swap(b, c);
        mesh.V.insert(mesh.V.end(), {a, b, c});
    };
    for (std::int32_t i = 0; i + 1 < m; ++i) add(m, i, i + 1);              // upper first to lower
    for (std::int32_t j = 0; j + 1 < m; ++j) add(m - 1, m + j, m + j + 1);  // lower last to upper
    for (std::int32_t j = 1; j + 1 < m; ++j) add(m, m + j, m + j + 1);      // upper cap
    for (std::int32_t i = 1; i + 1 < m; ++i) add(0, i, i + 1);              // lower cap
    computeOpposites(mesh);
    return mesh;
}

std::vector<Vec2> demoPoints() {
    // Hand-placed: (2) lands on the edge 0-1, (7)-(8) trigger flip cascades, (11) duplicates (4).
    return {{100, 100}, {700, 120}, {400, 110}, {380, 560}, {220, 330}, {560, 360},
            {640, 520}, {150, 520}, {420, 300}, {300, 200}, {520, 180}, {220, 330}};
}

}  // namespace dlab
