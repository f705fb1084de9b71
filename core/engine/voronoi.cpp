// The Voronoi diagram as the dual of the triangulation: circumcenters, dual edges and rays,
// cells by swinging around a vertex, and Liang–Barsky clipping for drawing.
#include "core/engine/voronoi.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace dlab {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// a*b - c*d with one rounding error at most a few ulps (Kahan's algorithm with an explicit fma;
// -ffp-contract=off keeps the compiler from fusing anything else).
double diffOfProducts(double a, double b, double c, double d) {
    const double w = c * d;
    const double e = std::fma(-c, d, w);  // exact: w - c*d
    const double f = std::fma(a, b, -w);  // a*b - w, rounded once
    return f + e;
}

bool finite(Vec2 p) { return std::isfinite(p.x) && std::isfinite(p.y); }

// ---- Exact arithmetic for the circumcenters the double formula cannot promise ---------------
// Every finite double is an integer multiple of 2^-1074, so in those units the circumcenter is
// a ratio of integers (of at most ~6,300 bits): computed exactly, then rounded once.

struct BigInt {
    bool negative = false;
    std::vector<std::uint32_t> mag;  // little-endian limbs, no leading zero limbs

    static BigInt ofDouble(double v, int unit) {  // v * 2^-unit, exactly (an integer)
        BigInt r;
        if (v == 0.0) return r;
        int e = 0;
        const double m = std::frexp(std::fabs(v), &e);  // |v| = m * 2^e, m in [0.5, 1)
        auto bits = static_cast<std::uint64_t>(std::ldexp(m, 53));
        int shift = e - 53 - unit;
        if (shift < 0) {  // the low bits of its 53 are zeros (unit <= the lowest bit set)
            bits >>= -shift;
            shift = 0;
        }
        r.mag = {static_cast<std::uint32_t>(bits), static_cast<std::uint32_t>(bits >> 32)};
        r.negative = v < 0;
        r.trim();
        return r.shifted(shift);
    }
    void trim() {
        while (!mag.empty() && mag.back() == 0) mag.pop_back();
        if (mag.empty()) negative = false;
    }
    bool zero() const { return mag.empty(); }
    std::size_t bitLength() const {
        if (mag.empty()) return 0;
        std::size_t n = 32 * (mag.size() - 1);
        for (std::uint32_t top = mag.back(); top; top >>= 1) ++n;
        return n;
    }
    BigInt shifted(int left) const {  // left >= 0
        BigInt r;
        r.negative = negative;
        const auto limbs = static_cast<std::size_t>(left / 32);
        const int bits = left % 32;
        r.mag.assign(limbs + mag.size() + 1, 0);
        for (std::size_t i = 0; i < mag.size(); ++i) {
            const std::uint64_t v = static_cast<std::uint64_t>(mag[i]) << bits;
            r.mag[i + limbs] |= static_cast<std::uint32_t>(v);
            r.mag[i + limbs + 1] |= static_cast<std::uint32_t>(v >> 32);
        }
        r.trim();
        return r;
    }
    static int compareMag(const BigInt& a, const BigInt& b) {
        if (a.mag.size() != b.mag.size()) return a.mag.size() < b.mag.size() ? -1 : 1;
        for (std::size_t i = a.mag.size(); i-- > 0;)
            if (a.mag[i] != b.mag[i]) return a.mag[i] < b.mag[i] ? -1 : 1;
        return 0;
    }
    static BigInt addMag(const BigInt& a, const BigInt& b) {
        BigInt r;
        r.mag.resize(std::max(a.mag.size(), b.mag.size()) + 1, 0);
        std::uint64_t carry = 0;
        for (std::size_t i = 0; i < r.mag.size(); ++i) {
            carry += (i < a.mag.size() ? a.mag[i] : 0u) +
                     std::uint64_t{i < b.mag.size() ? b.mag[i] : 0u};
            r.mag[i] = static_cast<std::uint32_t>(carry);
            carry >>= 32;
        }
        r.trim();
        return r;
    }
    static BigInt subMag(const BigInt& a, const BigInt& b) {  // |a| >= |b|
        BigInt r;
        r.mag.resize(a.mag.size(), 0);
        std::int64_t borrow = 0;
        for (std::size_t i = 0; i < a.mag.size(); ++i) {
            std::int64_t d = std::int64_t{a.mag[i]} - (i < b.mag.size() ? b.mag[i] : 0) - borrow;
            borrow = d < 0;
            r.mag[i] = static_cast<std::uint32_t>(d + (borrow << 32));
        }
        r.trim();
        return r;
    }
    void subtract(const BigInt& b) {  // |*this| -= |b|, |*this| >= |b|
        std::int64_t borrow = 0;
        for (std::size_t i = 0; i < mag.size(); ++i) {
            const std::int64_t d =
                std::int64_t{mag[i]} - (i < b.mag.size() ? b.mag[i] : 0) - borrow;
            borrow = d < 0;
            mag[i] = static_cast<std::uint32_t>(d + (borrow << 32));
        }
        trim();
    }
    void halve() {  // |*this| >>= 1
        for (std::size_t i = 0; i < mag.size(); ++i)
            mag[i] = (mag[i] >> 1) | (i + 1 < mag.size() ? mag[i + 1] << 31 : 0u);
        trim();
    }
    friend BigInt operator+(const BigInt& a, const BigInt& b) {
        if (a.negative == b.negative) {
            BigInt r = addMag(a, b);
            r.negative = a.negative && !r.zero();
            return r;
        }
        const bool aBigger = compareMag(a, b) >= 0;
        BigInt r = aBigger ? subMag(a, b) : subMag(b, a);
        r.negative = (aBigger ? a.negative : b.negative) && !r.zero();
        return r;
    }
    friend BigInt operator-(const BigInt& a, BigInt b) {
        b.negative = !b.negative && !b.zero();
        return a + b;
    }
    friend BigInt operator*(const BigInt& a, const BigInt& b) {
        BigInt r;
        if (a.zero() || b.zero()) return r;
        r.mag.assign(a.mag.size() + b.mag.size(), 0);
        for (std::size_t i = 0; i < a.mag.size(); ++i) {
            std::uint64_t carry = 0;
            for (std::size_t j = 0; j < b.mag.size(); ++j) {
                carry += std::uint64_t{a.mag[i]} * b.mag[j] + r.mag[i + j];
                r.mag[i + j] = static_cast<std::uint32_t>(carry);
                carry >>= 32;
            }
            r.mag[i + b.mag.size()] = static_cast<std::uint32_t>(carry);
        }
        r.negative = a.negative != b.negative;
        r.trim();
        return r;
    }
};

// p / q * 2^unit rounded to a double (q != 0): a 64-bit quotient with a sticky bit, so the
// conversion to double rounds once; ±inf when the value is beyond DBL_MAX.
double ratioToDouble(const BigInt& p, const BigInt& q, int unit) {
    if (p.zero()) return 0.0;
    const int k = 63 + static_cast<int>(q.bitLength()) - static_cast<int>(p.bitLength());
    BigInt num = p.shifted(std::max(k, 0)), den = q.shifted(std::max(-k, 0));
    num.negative = den.negative = false;
    std::uint64_t quotient = 0;
    BigInt step = den.shifted(63);
    for (int bit = 63; bit >= 0; --bit) {
        if (BigInt::compareMag(num, step) >= 0) {
            num.subtract(step);
            quotient |= std::uint64_t{1} << bit;
        }
        step.halve();
    }
    if (!num.zero()) quotient |= 1;  // sticky: the exact value lies above
    const double v = std::ldexp(static_cast<double>(quotient), unit - k);
    return p.negative != q.negative ? -v : v;
}

// The weight of the lowest bit set in any of the coordinates (2^-1074 at the least): in that
// unit every coordinate is an integer, and small inputs keep small integers.
int commonUnit(std::initializer_list<double> values) {
    int unit = std::numeric_limits<int>::max();
    for (double v : values) {
        if (v == 0.0) continue;
        int e = 0;
        auto bits = static_cast<std::uint64_t>(std::ldexp(std::frexp(std::fabs(v), &e), 53));
        int low = e - 53;
        for (; (bits & 1) == 0; bits >>= 1) ++low;
        unit = std::min(unit, low);
    }
    return unit == std::numeric_limits<int>::max() ? 0 : unit;
}

// The circumcenter computed exactly, rounded once per coordinate.
Vec2 exactCircumcenter(Vec2 a, Vec2 b, Vec2 c) {
    const int unit = commonUnit({a.x, a.y, b.x, b.y, c.x, c.y});
    auto big = [unit](double v) { return BigInt::ofDouble(v, unit); };
    const BigInt ax = big(a.x), ay = big(a.y);
    const BigInt bx = big(b.x) - ax, by = big(b.y) - ay;
    const BigInt cx = big(c.x) - ax, cy = big(c.y) - ay;
    const BigInt det = (bx * cy - by * cx).shifted(1);
    if (det.zero()) return {kNaN, kNaN};  // collinear
    const BigInt b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
    const BigInt ux = cy * b2 - by * c2, uy = bx * c2 - cx * b2;  // over det, in units
    return {ratioToDouble(ax * det + ux, det, unit), ratioToDouble(ay * det + uy, det, unit)};
}

// The double formula, when its error bound proves the answer within a few ulps; else nullopt.
std::optional<Vec2> fastCircumcenter(Vec2 a, Vec2 b, Vec2 c) {
    const double d[4] = {b.x - a.x, b.y - a.y, c.x - a.x, c.y - a.y};  // 1/2 ulp each
    double big = 0;
    for (double x : d) {
        if (!std::isfinite(x)) return std::nullopt;
        big = std::max(big, std::fabs(x));
    }
    if (big == 0.0) return Vec2{kNaN, kNaN};  // three coincident points
    // Scale so the largest difference lies in [1, 2): exact, as long as no component falls
    // under 2^-300 (checked: then no square or product below underflows either).
    const int e = std::ilogb(big);
    for (double x : d)
        if (x != 0.0 && std::ilogb(x) - e < -300) return std::nullopt;
    const double bx = std::ldexp(d[0], -e), by = std::ldexp(d[1], -e);
    const double cx = std::ldexp(d[2], -e), cy = std::ldexp(d[3], -e);
    const double det = 2.0 * diffOfProducts(bx, cy, by, cx);
    if (det == 0.0) return std::nullopt;  // collinear, or nearly: the exact path decides
    const double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
    const double ux = diffOfProducts(cy, b2, by, c2) / det;
    const double uy = diffOfProducts(bx, c2, cx, b2) / det;
    const Vec2 r{a.x + std::ldexp(ux, e), a.y + std::ldexp(uy, e)};
    if (!finite(r)) return std::nullopt;
    // First-order error of u in units of eps: the rounded differences and squares move the
    // numerator by at most 3 (|cy b2| + |by c2|) and the determinant by 2 (|bx cy| + |by cx|)
    // (relative), the products and the division add 4 |u|; doubled for safety. Accepted when
    // that stays within 2 eps of the answer (with the final rounding: 3 ulps).
    const double t = 2.0 * (std::fabs(bx * cy) + std::fabs(by * cx)) / std::fabs(det);
    const double sx = (std::fabs(cy * b2) + std::fabs(by * c2)) / std::fabs(det);
    const double sy = (std::fabs(bx * c2) + std::fabs(cx * b2)) / std::fabs(det);
    const double boundX = std::ldexp(2 * (3 * sx + (2 * t + 4) * std::fabs(ux)), e);
    const double boundY = std::ldexp(2 * (3 * sy + (2 * t + 4) * std::fabs(uy)), e);
    if (!(boundX <= 2.0 * std::fabs(r.x)) || !(boundY <= 2.0 * std::fabs(r.y))) return std::nullopt;
    return r;
}

}  // namespace

Vec2 circumcenter(Vec2 a, Vec2 b, Vec2 c) {
    if (!finite(a) || !finite(b) || !finite(c)) return {kNaN, kNaN};
    if (const std::optional<Vec2> fast = fastCircumcenter(a, b, c)) return *fast;
    return exactCircumcenter(a, b, c);
}

Vec2 edgeNormal(const Mesh& m, std::int32_t c) {
    const Vec2 p = m.G[m.V[next(c)]];
    const Vec2 q = m.G[m.V[prev(c)]];
    double dx = q.x - p.x, dy = q.y - p.y;
    if (!std::isfinite(dx) || !std::isfinite(dy)) {
        // An edge longer than DBL_MAX (ends near +-DBL_MAX): the same direction at a quarter of
        // the length, which is finite (a ray's direction has no length).
        dx = q.x * 0.25 - p.x * 0.25;
        dy = q.y * 0.25 - p.y * 0.25;
    }
    return {dy + 0.0, -dx + 0.0};  // + 0.0: no -0 written
}

VoronoiDiagram buildVoronoi(const Mesh& m) {
    VoronoiDiagram d;
    const std::int32_t nt = m.numTriangles();
    d.vertices.resize(static_cast<std::size_t>(nt));
    for (std::int32_t t = 0; t < nt; ++t) {
        d.vertices[t] =
            circumcenter(m.point(corner(t, 0)), m.point(corner(t, 1)), m.point(corner(t, 2)));
    }
    // A triangulation has |corners|/2 edges plus half the hull edges: reserve the upper bound.
    d.edges.reserve(static_cast<std::size_t>(m.numCorners()));
    forEachEdge(m, [&](std::int32_t c) {
        VoronoiDiagram::Edge e;
        e.a = tri(c);
        e.b = m.O[c] == kNone ? kNone : tri(m.O[c]);
        e.direction = edgeNormal(m, c);
        e.corner = c;
        d.edges.push_back(e);
    });
    return d;
}

VoronoiCell voronoiCell(const Mesh& m, std::int32_t cornerAtVertex) {
    const std::int32_t nc = m.numCorners();
    if (m.O.size() != m.V.size()) {
        throw std::invalid_argument("voronoiCell: |O| = " + std::to_string(m.O.size()) +
                                    " differs from |V| = " + std::to_string(m.V.size()));
    }
    if (cornerAtVertex < 0 || cornerAtVertex >= nc) {
        throw std::invalid_argument("voronoiCell: corner " + std::to_string(cornerAtVertex) +
                                    " outside [0, " + std::to_string(nc) + ")");
    }
    const std::int32_t v = m.V[cornerAtVertex];
    // One step of a swing, checked: a corrupt O must end in an exception, never out of bounds.
    auto checked = [&](std::int32_t c, std::int32_t from) {
        if (c == kNone) return c;
        if (c < 0 || c >= nc || m.V[c] != v) {
            throw std::invalid_argument("voronoiCell: swinging around vertex " + std::to_string(v) +
                                        " from corner " + std::to_string(from) +
                                        " reached corner " + std::to_string(c) +
                                        ", not a corner of that vertex (inconsistent O)");
        }
        return c;
    };
    auto tooLong = [&] {
        throw std::invalid_argument("voronoiCell: the swing around vertex " + std::to_string(v) +
                                    " from corner " + std::to_string(cornerAtVertex) +
                                    " does not close within " + std::to_string(nc) +
                                    " steps (inconsistent O)");
    };

    VoronoiCell cell;
    // Unswing (clockwise) to the hull, or all the way around back to the start.
    std::int32_t first = cornerAtVertex;
    bool closed = false;
    for (std::int32_t steps = 0;; ++steps) {
        if (steps > nc) tooLong();
        const std::int32_t u =
            checked(m.O[prev(first)] == kNone ? kNone : prev(m.O[prev(first)]), first);
        if (u == kNone) break;
        if (u == cornerAtVertex) {
            closed = true;
            first = cornerAtVertex;
            break;
        }
        first = u;
    }
    // Swing (counter-clockwise) from there, collecting the fan.
    std::int32_t c = first;
    for (std::int32_t steps = 0;; ++steps) {
        if (steps > nc) tooLong();
        cell.corners.push_back(c);
        cell.triangles.push_back(tri(c));
        const std::int32_t s = checked(m.O[next(c)] == kNone ? kNone : next(m.O[next(c)]), c);
        if (s == kNone) {
            if (closed) tooLong();  // went around one way but not the other: O is not symmetric
            break;
        }
        if (s == first) {
            if (!closed) tooLong();
            break;
        }
        c = s;
    }
    cell.closed = closed;
    return cell;
}

std::optional<std::pair<Vec2, Vec2>> clipToBox(Vec2 p, Vec2 d, double tMax, Vec2 lo, Vec2 hi) {
    if (!finite(p) || !finite(d) || std::isnan(tMax) || tMax < 0.0 || !finite(lo) || !finite(hi))
        return std::nullopt;
    if (!(lo.x <= hi.x && lo.y <= hi.y)) return std::nullopt;
    double t0 = 0.0, t1 = tMax;
    // One slab per axis: p + t*d stays within [l, h] along that axis.
    auto slab = [&](double pc, double dc, double l, double h) {
        if (dc == 0.0) return l <= pc && pc <= h;
        double ta = (l - pc) / dc, tb = (h - pc) / dc;
        if (dc < 0.0) std::swap(ta, tb);
        // ta/tb may be ±inf after an overflow; the comparisons below still order them right.
        if (ta > t0) t0 = ta;
        if (tb < t1) t1 = tb;
        return t0 <= t1;
    };
    if (!slab(p.x, d.x, lo.x, hi.x) || !slab(p.y, d.y, lo.y, hi.y)) return std::nullopt;
    auto at = [&](double t) {
        // Components along which the line does not move stay exactly where they are (no 0 * inf).
        Vec2 q{d.x == 0.0 ? p.x : p.x + t * d.x, d.y == 0.0 ? p.y : p.y + t * d.y};
        if (t == 0.0) q = p;
        // Rounding may put a computed end a hair outside the closed box: clamp it back.
        q.x = std::clamp(q.x, lo.x, hi.x);
        q.y = std::clamp(q.y, lo.y, hi.y);
        return q;
    };
    if (d.x == 0.0 && d.y == 0.0) return std::make_pair(p, p);  // a point (t1 may be infinite)
    const Vec2 a = at(t0), b = at(t1);
    if (!finite(a) || !finite(b)) return std::nullopt;
    return std::make_pair(a, b);
}

std::vector<std::pair<Vec2, Vec2>> clippedSegments(const VoronoiDiagram& diagram, Vec2 lo,
                                                   Vec2 hi) {
    std::vector<std::pair<Vec2, Vec2>> out;
    const auto nv = static_cast<std::int64_t>(diagram.vertices.size());
    auto inside = [&](Vec2 q) { return lo.x <= q.x && q.x <= hi.x && lo.y <= q.y && q.y <= hi.y; };
    for (const VoronoiDiagram::Edge& e : diagram.edges) {
        if (e.a < 0 || e.a >= nv || (!e.isRay() && e.b >= nv)) continue;
        const Vec2 p = diagram.vertices[e.a];
        if (!finite(p)) continue;
        if (e.isRay()) {
            if (!finite(e.direction) || (e.direction.x == 0.0 && e.direction.y == 0.0)) continue;
            if (auto s =
                    clipToBox(p, e.direction, std::numeric_limits<double>::infinity(), lo, hi)) {
                if (inside(p)) s->first = p;
                out.push_back(*s);
            }
            continue;
        }
        const Vec2 q = diagram.vertices[e.b];
        if (!finite(q)) continue;
        const Vec2 d{q.x - p.x, q.y - p.y};
        if (!finite(d)) continue;
        if (auto s = clipToBox(p, d, 1.0, lo, hi)) {
            // Ends inside the box are kept exactly (p + 1*d need not round back to q).
            if (inside(p)) s->first = p;
            if (inside(q)) s->second = q;
            out.push_back(*s);
        }
    }
    return out;
}

}  // namespace dlab
