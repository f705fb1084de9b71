// Exact orient2d and incircle: a floating-point filter, expansion arithmetic, and a big-integer
// tier for coordinates whose exponents span too wide a range for expansions.
//
// Index
//   [SECTION] Error-free transformations (two-sum, two-product by Dekker's split)
//   [SECTION] Expansions (nonoverlapping, increasing magnitude, zeros eliminated)
//   [SECTION] Big integers (the last tier: only for exponent spans of hundreds of binades)
//   [SECTION] Exact evaluation: choose a power-of-two scale, or fall to big integers
//   [SECTION] The slow paths of the public predicates (the filters are inline in the header)
//
// Why three tiers: the filter decides almost every call in a few flops. Expansion arithmetic
// (Priest, Shewchuk) is exact as long as no product overflows or underflows; multiplying every
// coordinate by the same power of two is exact and keeps the sign, so we scale the inputs into
// the safe range first. Only when the coordinates of one call span more binades than the safe
// range holds (e.g. 1e-300 next to 1e300) do we fall back to integers of a few thousand bits.
#include "core/engine/predicates.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

namespace dlab {

namespace {

// ============================================================================================
// [SECTION] Error-free transformations
// ============================================================================================

// a + b = x + y exactly, |y| <= ulp(x)/2. Valid for any finite a, b (no overflow).
inline void twoSum(double a, double b, double& x, double& y) {
    x = a + b;
    const double bv = x - a;
    const double av = x - bv;
    y = (a - av) + (b - bv);
}

// As twoSum, but requires |a| >= |b| (or a == 0).
inline void fastTwoSum(double a, double b, double& x, double& y) {
    x = a + b;
    y = b - (x - a);
}

// a = hi + lo with hi, lo of at most 26 significant bits each. Requires |a| < 2^995.
inline void split(double a, double& hi, double& lo) {
    constexpr double kSplitter = 134217729.0;  // 2^27 + 1
    const double c = kSplitter * a;
    const double big = c - a;
    hi = c - big;
    lo = a - hi;
}

// a * b = x + y exactly (Dekker), provided the product neither overflows nor underflows.
// Written without fma on purpose: the build has no -mfma, and a library fma is slow.
inline void twoProduct(double a, double b, double& x, double& y) {
    x = a * b;
    double ahi, alo, bhi, blo;
    split(a, ahi, alo);
    split(b, bhi, blo);
    const double err1 = x - ahi * bhi;
    const double err2 = err1 - alo * bhi;
    const double err3 = err2 - ahi * blo;
    y = alo * blo - err3;
}

// ============================================================================================
// [SECTION] Expansions
// ============================================================================================
//
// An expansion is a sum of doubles e[0] + e[1] + ... stored in increasing magnitude, no two of
// which overlap; its sign is the sign of its last (largest) component. Every routine drops the
// zero components it produces, so an exact cancellation makes expansions shorter, not longer:
// on integer grids most of them stay one or two components long.

// Capacities. The incircle determinant is a sum of three products of a 16-component lift by a
// 16-component cross term: at most 3 * 16 * 16 * 2 = 1536 components.
constexpr int kMaxTerms = 1536;

struct Expansion {
    int n = 0;
    double e[kMaxTerms];
    int sign() const { return n == 0 ? 0 : (e[n - 1] > 0) - (e[n - 1] < 0); }
};

// h = e + f. h may not alias e or f.
int expansionSum(const double* e, int en, const double* f, int fn, double* h) {
    // Merge by magnitude, then sweep with two-sum, keeping the nonzero round-off terms.
    int i = 0, j = 0, k = 0;
    double q;
    auto take = [&]() {
        if (j >= fn || (i < en && std::fabs(e[i]) <= std::fabs(f[j]))) return e[i++];
        return f[j++];
    };
    if (en + fn == 0) return 0;
    q = take();
    while (i < en || j < fn) {
        double sum, err;
        twoSum(q, take(), sum, err);
        if (err != 0.0) h[k++] = err;
        q = sum;
    }
    if (q != 0.0 || k == 0) h[k++] = q;
    if (k == 1 && h[0] == 0.0) return 0;
    return k;
}

// h = e * b. h may not alias e.
int scaleExpansion(const double* e, int en, double b, double* h) {
    if (en == 0 || b == 0.0) return 0;
    int k = 0;
    double q, err;
    twoProduct(e[0], b, q, err);
    if (err != 0.0) h[k++] = err;
    for (int i = 1; i < en; ++i) {
        double hi, lo, sum;
        twoProduct(e[i], b, hi, lo);
        twoSum(q, lo, sum, err);
        if (err != 0.0) h[k++] = err;
        fastTwoSum(hi, sum, q, err);
        if (err != 0.0) h[k++] = err;
    }
    if (q != 0.0) h[k++] = q;
    return k;
}

// h = e * f, accumulating one scaled copy of e per component of f. h may not alias e or f.
int multiply(const double* e, int en, const double* f, int fn, double* h) {
    double scaled[2 * kMaxTerms / 3];
    double acc[kMaxTerms];
    int hn = 0;
    for (int j = 0; j < fn; ++j) {
        const int sn = scaleExpansion(e, en, f[j], scaled);
        const int an = expansionSum(h, hn, scaled, sn, acc);
        std::memcpy(h, acc, sizeof(double) * static_cast<std::size_t>(an));
        hn = an;
    }
    return hn;
}

// The exact difference a - b as an expansion of at most two components.
int difference(double a, double b, double* h) {
    double x, y;
    twoSum(a, -b, x, y);
    int k = 0;
    if (y != 0.0) h[k++] = y;
    if (x != 0.0) h[k++] = x;
    return k;
}

// e * e' - f * f' for two-component factors: the 2x2 determinant of exact differences.
int crossTerm(const double* a, int an, const double* b, int bn, const double* c, int cn,
              const double* d, int dn, double* h) {
    double ab[8], cd[8];
    const int abn = multiply(a, an, b, bn, ab);
    const int cdn = multiply(c, cn, d, dn, cd);
    for (int i = 0; i < cdn; ++i) cd[i] = -cd[i];
    return expansionSum(ab, abn, cd, cdn, h);
}

// ============================================================================================
// [SECTION] Big integers
// ============================================================================================

// A signed integer of 32-bit limbs, least significant first; just enough for the determinants.
struct BigInt {
    bool negative = false;
    std::vector<std::uint32_t> mag;

    static BigInt fromShifted(std::int64_t mantissa, int shift) {  // mantissa * 2^shift
        BigInt r;
        r.negative = mantissa < 0;
        std::uint64_t m = static_cast<std::uint64_t>(mantissa < 0 ? -mantissa : mantissa);
        if (m == 0) return r;
        const int words = shift / 32, bits = shift % 32;
        r.mag.assign(static_cast<std::size_t>(words), 0u);
        std::uint64_t carry = 0;
        for (int i = 0; i < 2; ++i) {  // the mantissa's two 32-bit halves, shifted left by `bits`
            const std::uint64_t x = (((m >> (32 * i)) & 0xffffffffu) << bits) | carry;
            r.mag.push_back(static_cast<std::uint32_t>(x));
            carry = x >> 32;
        }
        r.mag.push_back(static_cast<std::uint32_t>(carry));
        r.trim();
        return r;
    }
    int sign() const { return mag.empty() ? 0 : (negative ? -1 : 1); }
    void trim() {
        while (!mag.empty() && mag.back() == 0) mag.pop_back();
        if (mag.empty()) negative = false;
    }
    static int compareMagnitude(const BigInt& a, const BigInt& b) {
        if (a.mag.size() != b.mag.size()) return a.mag.size() < b.mag.size() ? -1 : 1;
        for (std::size_t i = a.mag.size(); i-- > 0;) {
            if (a.mag[i] != b.mag[i]) return a.mag[i] < b.mag[i] ? -1 : 1;
        }
        return 0;
    }
    static std::vector<std::uint32_t> addMagnitudes(const BigInt& a, const BigInt& b) {
        std::vector<std::uint32_t> r(std::max(a.mag.size(), b.mag.size()) + 1, 0u);
        std::uint64_t carry = 0;
        for (std::size_t i = 0; i < r.size(); ++i) {
            const std::uint64_t s =
                carry + (i < a.mag.size() ? a.mag[i] : 0u) + (i < b.mag.size() ? b.mag[i] : 0u);
            r[i] = static_cast<std::uint32_t>(s);
            carry = s >> 32;
        }
        return r;
    }
    // |a| - |b| for |a| >= |b|.
    static std::vector<std::uint32_t> subtractMagnitudes(const BigInt& a, const BigInt& b) {
        std::vector<std::uint32_t> r(a.mag.size(), 0u);
        std::int64_t borrow = 0;
        for (std::size_t i = 0; i < r.size(); ++i) {
            std::int64_t d =
                static_cast<std::int64_t>(a.mag[i]) - borrow - (i < b.mag.size() ? b.mag[i] : 0u);
            borrow = d < 0;
            if (d < 0) d += std::int64_t{1} << 32;
            r[i] = static_cast<std::uint32_t>(d);
        }
        return r;
    }
    friend BigInt operator+(const BigInt& a, const BigInt& b) {
        BigInt r;
        if (a.negative == b.negative) {
            r.mag = addMagnitudes(a, b);
            r.negative = a.negative;
        } else if (compareMagnitude(a, b) >= 0) {
            r.mag = subtractMagnitudes(a, b);
            r.negative = a.negative;
        } else {
            r.mag = subtractMagnitudes(b, a);
            r.negative = b.negative;
        }
        r.trim();
        return r;
    }
    friend BigInt operator-(const BigInt& a, BigInt b) {
        b.negative = !b.negative;
        return a + b;
    }
    friend BigInt operator*(const BigInt& a, const BigInt& b) {
        BigInt r;
        if (a.mag.empty() || b.mag.empty()) return r;
        r.mag.assign(a.mag.size() + b.mag.size(), 0u);
        for (std::size_t i = 0; i < a.mag.size(); ++i) {
            std::uint64_t carry = 0;
            for (std::size_t j = 0; j < b.mag.size(); ++j) {
                const std::uint64_t t =
                    static_cast<std::uint64_t>(a.mag[i]) * b.mag[j] + r.mag[i + j] + carry;
                r.mag[i + j] = static_cast<std::uint32_t>(t);
                carry = t >> 32;
            }
            r.mag[i + b.mag.size()] = static_cast<std::uint32_t>(carry);
        }
        r.negative = a.negative != b.negative;
        r.trim();
        return r;
    }
};

// The lowest binade any nonzero coordinate reaches: the exponent of its last mantissa bit.
int lowestBit(double x) { return std::ilogb(x) - 52; }

// Coordinates as integers in units of 2^minLow (exact: every finite double is m * 2^e).
template <std::size_t N>
void toIntegers(const double (&v)[N], BigInt (&out)[N]) {
    int minLow = 0;
    bool any = false;
    for (double x : v) {
        if (x == 0.0 || !std::isfinite(x)) continue;
        const int low = lowestBit(x);
        minLow = any ? std::min(minLow, low) : low;
        any = true;
    }
    for (std::size_t i = 0; i < N; ++i) {
        if (v[i] == 0.0 || !std::isfinite(v[i])) continue;
        int exp = 0;
        const double frac = std::frexp(v[i], &exp);  // v = frac * 2^exp, 0.5 <= |frac| < 1
        const auto mantissa = static_cast<std::int64_t>(std::ldexp(frac, 53));  // exact
        out[i] = BigInt::fromShifted(mantissa, exp - 53 - minLow);
    }
}

int orient2dBig(Vec2 a, Vec2 b, Vec2 c) {
    const double v[6] = {a.x, a.y, b.x, b.y, c.x, c.y};
    BigInt z[6];
    toIntegers(v, z);
    const BigInt bx = z[2] - z[0], by = z[3] - z[1], cx = z[4] - z[0], cy = z[5] - z[1];
    return (bx * cy - by * cx).sign();
}

int incircleBig(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
    const double v[8] = {a.x, a.y, b.x, b.y, c.x, c.y, d.x, d.y};
    BigInt z[8];
    toIntegers(v, z);
    const BigInt adx = z[0] - z[6], ady = z[1] - z[7];
    const BigInt bdx = z[2] - z[6], bdy = z[3] - z[7];
    const BigInt cdx = z[4] - z[6], cdy = z[5] - z[7];
    const BigInt alift = adx * adx + ady * ady;
    const BigInt blift = bdx * bdx + bdy * bdy;
    const BigInt clift = cdx * cdx + cdy * cdy;
    return (alift * (bdx * cdy - cdx * bdy) + blift * (cdx * ady - adx * cdy) +
            clift * (adx * bdy - bdx * ady))
        .sign();
}

// ============================================================================================
// [SECTION] Exact evaluation
// ============================================================================================
//
// Scaling by 2^k is exact while every scaled coordinate keeps all its bits, and keeps the sign
// of a homogeneous determinant. After scaling, the largest coordinate is below 2^(top+1) and
// every nonzero bit is at or above 2^bottom:
//   orient2d (degree 2): products < 2^(2 top + 4), sum < 2^(2 top + 6); Dekker's split needs
//     factors < 2^995. Products are exact down to 2^-1074, so bottom >= -537. top = 500.
//   incircle (degree 4): sum < 2^(4 top + 12) < 2^1023, so top = 250; bottom >= -268.
// Returns the exponent k to scale by, or false when no k fits (then: big integers).
template <std::size_t N>
bool chooseScale(const double (&v)[N], int top, int bottom, int& k, bool& allZero) {
    int maxExp = 0, minLow = 0;
    allZero = true;
    for (double x : v) {
        if (!std::isfinite(x)) return false;  // outside the contract: the big-integer tier says 0
        if (x == 0.0) continue;
        const int e = std::ilogb(x);
        maxExp = allZero ? e : std::max(maxExp, e);
        minLow = allZero ? e - 52 : std::min(minLow, e - 52);
        allZero = false;
    }
    if (allZero) return true;
    k = top - maxExp;
    return minLow + k >= bottom;
}

int orient2dExact(Vec2 a, Vec2 b, Vec2 c, PredicateTier& tier) {
    const double v[6] = {a.x, a.y, b.x, b.y, c.x, c.y};
    int k = 0;
    bool allZero = false;
    if (!chooseScale(v, 500, -537, k, allZero)) {
        tier = PredicateTier::BigInteger;
        return orient2dBig(a, b, c);
    }
    tier = PredicateTier::Expansion;
    if (allZero) return 0;
    double s[6];
    for (int i = 0; i < 6; ++i) s[i] = std::ldexp(v[i], k);
    double bx[2], by[2], cx[2], cy[2], h[32];
    const int bxn = difference(s[2], s[0], bx), byn = difference(s[3], s[1], by);
    const int cxn = difference(s[4], s[0], cx), cyn = difference(s[5], s[1], cy);
    const int hn = crossTerm(bx, bxn, cy, cyn, by, byn, cx, cxn, h);
    return hn == 0 ? 0 : (h[hn - 1] > 0) - (h[hn - 1] < 0);
}

int incircleExact(Vec2 a, Vec2 b, Vec2 c, Vec2 d, PredicateTier& tier) {
    const double v[8] = {a.x, a.y, b.x, b.y, c.x, c.y, d.x, d.y};
    int k = 0;
    bool allZero = false;
    if (!chooseScale(v, 250, -268, k, allZero)) {
        tier = PredicateTier::BigInteger;
        return incircleBig(a, b, c, d);
    }
    tier = PredicateTier::Expansion;
    if (allZero) return 0;
    double s[8];
    for (int i = 0; i < 8; ++i) s[i] = std::ldexp(v[i], k);
    double dx[3][2], dy[3][2];
    int dxn[3], dyn[3];
    for (int i = 0; i < 3; ++i) {
        dxn[i] = difference(s[2 * i], s[6], dx[i]);
        dyn[i] = difference(s[2 * i + 1], s[7], dy[i]);
    }
    // det = lift(a) * cross(b, c) + lift(b) * cross(c, a) + lift(c) * cross(a, b), with
    // lift(p) = dx^2 + dy^2 and cross(p, q) = dx(p) dy(q) - dx(q) dy(p).
    static thread_local Expansion terms[3], total, partial;
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3, m = (i + 2) % 3;
        double xx[8], yy[8], lift[16], cross[16];
        const int xxn = multiply(dx[i], dxn[i], dx[i], dxn[i], xx);
        const int yyn = multiply(dy[i], dyn[i], dy[i], dyn[i], yy);
        const int liftn = expansionSum(xx, xxn, yy, yyn, lift);
        const int crossn =
            crossTerm(dx[j], dxn[j], dy[m], dyn[m], dx[m], dxn[m], dy[j], dyn[j], cross);
        terms[i].n = multiply(lift, liftn, cross, crossn, terms[i].e);
    }
    partial.n = expansionSum(terms[0].e, terms[0].n, terms[1].e, terms[1].n, partial.e);
    total.n = expansionSum(partial.e, partial.n, terms[2].e, terms[2].n, total.e);
    return total.sign();
}

// ============================================================================================
// [SECTION] The slow paths of the public predicates (the filters are inline in the header)
// ============================================================================================

thread_local PredicateCounters t_counters;

}  // namespace

namespace detail {

int orient2dSlow(Vec2 a, Vec2 b, Vec2 c) {
    ++t_counters.orientExact;
    PredicateTier tier;
    return orient2dExact(a, b, c, tier);
}

int incircleSlow(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
    ++t_counters.incircleExact;
    PredicateTier tier;
    return incircleExact(a, b, c, d, tier);
}

}  // namespace detail

namespace {
template <class Exact>
PredicateReport report(const detail::Filtered& f, Exact exact) {
    PredicateReport r;
    r.approx = f.det;
    r.errorBound = f.usable ? f.bound : HUGE_VAL;
    r.naiveSign = std::isnan(f.det) ? 0 : f.sign();
    if (f.decided()) {
        r.exactSign = f.sign();
        r.tier = PredicateTier::Filter;
    } else {
        r.exactSign = exact(r.tier);
    }
    return r;
}
}  // namespace

PredicateReport orient2dReport(Vec2 a, Vec2 b, Vec2 c) {
    return report(detail::orientFilter(a, b, c),
                  [&](PredicateTier& t) { return orient2dExact(a, b, c, t); });
}

PredicateReport incircleReport(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
    return report(detail::incircleFilter(a, b, c, d),
                  [&](PredicateTier& t) { return incircleExact(a, b, c, d, t); });
}

PredicateCounters& predicateCounters() { return t_counters; }

}  // namespace dlab
