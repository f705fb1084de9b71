// Exact orient2d and incircle: a floating-point filter, an adaptive stage on the rounded
// coordinate differences (zero tail, stage B), expansion arithmetic, and a big-integer tier for
// coordinates whose exponents span too wide a range for expansions.
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
#include <bit>
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
// Inside that range every product's round-off is representable (two-product is exact) and a
// rounded product or sum has relative error at most eps, which the stage-B bounds rely on.
// Sets k = 0 when the coordinates are already in range (the usual case: no scaling at all),
// else the exponent to scale by; returns false when no k fits (then: big integers).

// floor(log2 |x|) for finite nonzero x, from the bits (ilogb is a library call).
inline int exponentOf(double x) {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    const int biased = static_cast<int>((bits >> 52) & 0x7ff);
    return biased == 0 ? std::ilogb(x) : biased - 1023;
}

template <std::size_t N>
bool chooseScale(const double (&v)[N], int top, int bottom, int& k, bool& allZero) {
    int maxExp = 0, minLow = 0;
    allZero = true;
    for (double x : v) {
        if (!std::isfinite(x)) return false;  // outside the contract: the big-integer tier says 0
        if (x == 0.0) continue;
        const int e = exponentOf(x);
        maxExp = allZero ? e : std::max(maxExp, e);
        minLow = allZero ? e - 52 : std::min(minLow, e - 52);
        allZero = false;
    }
    k = 0;
    if (allZero || (maxExp <= top && minLow >= bottom)) return true;
    k = top - maxExp;
    return minLow + k >= bottom;
}

// A coordinate difference: x rounded, t its exact round-off (x + t = the exact difference).
struct Diff {
    double x, t;
};
inline Diff diff(double a, double b) {
    Diff d;
    twoSum(a, -b, d.x, d.t);
    return d;
}
// As an expansion of at most two components (zeros dropped).
inline int asExpansion(Diff d, double* h) {
    int k = 0;
    if (d.t != 0.0) h[k++] = d.t;
    if (d.x != 0.0) h[k++] = d.x;
    return k;
}

// Stage B's test: is |h| (an exact expansion) provably greater than bound? The components below
// the largest sum to less than it in magnitude; their sum is taken with a margin of 2^-40 for
// its own round-off, and the difference with a margin for its rounding, so a true answer is
// certain. (A false answer only sends the call to the next stage.)
inline bool exceedsBound(const double* h, int n, double bound) {
    if (n == 0) return false;
    double lower = 0.0;
    for (int i = 0; i < n - 1; ++i) lower += std::fabs(h[i]);
    const double magnitude = std::fabs(h[n - 1]) - lower * (1.0 + 0x1p-40);
    return magnitude * (1.0 - 0x1p-40) > bound;
}

// a * b exactly, as an expansion of at most two components.
inline int productOf(double a, double b, double* h) {
    double x, y;
    twoProduct(a, b, x, y);
    int k = 0;
    if (y != 0.0) h[k++] = y;
    if (x != 0.0) h[k++] = x;
    return k;
}

// Exponent of the lowest set bit of a finite nonzero x: x is an odd integer times 2^result.
inline int lowestSetBit(double x) {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    std::uint64_t mantissa = bits & ((std::uint64_t{1} << 52) - 1);
    int biased = static_cast<int>((bits >> 52) & 0x7ff);
    if (biased != 0)
        mantissa |= std::uint64_t{1} << 52;
    else
        biased = 1;  // subnormal: mantissa * 2^-1074
    return biased - 1075 + std::countr_zero(mantissa);
}

// Whether exact differences span at most `width` bits, from the highest set bit of the largest
// to the lowest set bit of any: then they are integers below 2^width in units of that lowest
// bit, and a determinant of low degree evaluates exactly in plain doubles (every product and
// sum an integer below 2^53 in units of a power of two that, in the safe range, stays at or
// above 2^-1074). Lattices and most grid-like inputs pass.
template <int N>
bool shortSpan(const double* d, int width) {
    int hi = 0, lo = 0;
    bool any = false;
    for (int i = 0; i < N; ++i) {
        if (d[i] == 0.0) continue;
        const int h = exponentOf(d[i]), l = lowestSetBit(d[i]);
        hi = any ? std::max(hi, h) : h;
        lo = any ? std::min(lo, l) : l;
        any = true;
    }
    return hi - lo < width;
}

inline int signOf(double x) { return (x > 0) - (x < 0); }

inline int signOf(const double* h, int n) { return n == 0 ? 0 : (h[n - 1] > 0) - (h[n - 1] < 0); }

// The stage-B bounds. With exact differences x(1 + d), |d| <= eps, a product of two differences
// moves by at most (2 eps + eps^2) of its magnitude, a lift times a cross term by at most
// (4 eps + 6 eps^2 + ...); the permanents are computed in floating point (a few eps of relative
// error each). The constants keep a wide margin over all of that: 2 eps and 4 eps plus 256 eps^2.
constexpr double kEps = 0x1p-53;
constexpr double kOrientBoundB = (2.0 + 256.0 * kEps) * kEps;
constexpr double kIncircleBoundB = (4.0 + 256.0 * kEps) * kEps;

// orient2d on coordinates in the safe range (s = ax, ay, bx, by, cx, cy).
int orient2dStages(const double* s, PredicateTier& tier) {
    const Diff bx = diff(s[2], s[0]), by = diff(s[3], s[1]);
    const Diff cx = diff(s[4], s[0]), cy = diff(s[5], s[1]);
    const bool zeroTail = bx.t == 0.0 && by.t == 0.0 && cx.t == 0.0 && cy.t == 0.0;
    // Degree 2: integers below 2^26 make products below 2^52 and their difference below 2^53.
    const double d[4] = {bx.x, by.x, cx.x, cy.x};
    if (zeroTail && shortSpan<4>(d, 26)) {
        tier = PredicateTier::ZeroTail;
        return signOf(bx.x * cy.x - by.x * cx.x);
    }
    // B = bx.x cy.x - by.x cx.x, exactly: two two-products and their difference.
    double l[2], r[2], det[4];
    const int ln = productOf(bx.x, cy.x, l), rn = productOf(-by.x, cx.x, r);
    const int dn = expansionSum(l, ln, r, rn, det);
    if (zeroTail) {
        tier = PredicateTier::ZeroTail;
        return signOf(det, dn);
    }
    if (exceedsBound(det, dn, kOrientBoundB * (std::fabs(bx.x * cy.x) + std::fabs(by.x * cx.x)))) {
        tier = PredicateTier::StageB;
        return signOf(det, dn);
    }
    tier = PredicateTier::Expansion;
    double ex[4][2], h[32];
    int en[4];
    const Diff full[4] = {bx, by, cx, cy};
    for (int i = 0; i < 4; ++i) en[i] = asExpansion(full[i], ex[i]);
    const int hn = crossTerm(ex[0], en[0], ex[3], en[3], ex[1], en[1], ex[2], en[2], h);
    return signOf(h, hn);
}

// lift(i) * cross(j, m) summed over the three rotations, each factor an expansion.
int incircleSum(const double (*dx)[2], const int* dxn, const double (*dy)[2], const int* dyn,
                double* out) {
    static thread_local Expansion terms[3], partial;
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
    return expansionSum(partial.e, partial.n, terms[2].e, terms[2].n, out);
}

// The same sum when every difference is one double: lift(i) * cross(j, m) as
// dx(i) * (dx(i) * cross) + dy(i) * (dy(i) * cross), four scalings of a four-component cross
// term instead of general products (Shewchuk's way; about half the work of incircleSum).
int incircleSumOfDoubles(const double* dx, const double* dy, double* out) {
    double terms[3][32];
    int termn[3];
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3, m = (i + 2) % 3;
        double l[2], r[2], cross[4], x1[8], x2[16], y1[8], y2[16];
        const int ln = productOf(dx[j], dy[m], l), rn = productOf(-dx[m], dy[j], r);
        const int cn = expansionSum(l, ln, r, rn, cross);
        const int x1n = scaleExpansion(cross, cn, dx[i], x1);
        const int x2n = scaleExpansion(x1, x1n, dx[i], x2);
        const int y1n = scaleExpansion(cross, cn, dy[i], y1);
        const int y2n = scaleExpansion(y1, y1n, dy[i], y2);
        termn[i] = expansionSum(x2, x2n, y2, y2n, terms[i]);
    }
    double partial[64];
    const int pn = expansionSum(terms[0], termn[0], terms[1], termn[1], partial);
    return expansionSum(partial, pn, terms[2], termn[2], out);
}

// incircle on coordinates in the safe range (s = ax, ay, bx, by, cx, cy, dx, dy).
// det = lift(a) * cross(b, c) + lift(b) * cross(c, a) + lift(c) * cross(a, b), with
// lift(p) = dx^2 + dy^2 and cross(p, q) = dx(p) dy(q) - dx(q) dy(p), differences taken from d.
int incircleStages(const double* s, PredicateTier& tier) {
    Diff x[3], y[3];
    bool zeroTail = true;
    for (int i = 0; i < 3; ++i) {
        x[i] = diff(s[2 * i], s[6]);
        y[i] = diff(s[2 * i + 1], s[7]);
        zeroTail = zeroTail && x[i].t == 0.0 && y[i].t == 0.0;
    }
    // Degree 4: integers below 2^12 make lifts and cross terms below 2^25, their products
    // below 2^50 and the sum of three below 2^53.
    const double d[6] = {x[0].x, y[0].x, x[1].x, y[1].x, x[2].x, y[2].x};
    if (zeroTail && shortSpan<6>(d, 12)) {
        tier = PredicateTier::ZeroTail;
        double det = 0.0;
        for (int i = 0; i < 3; ++i) {
            const int j = (i + 1) % 3, m = (i + 2) % 3;
            det += (d[2 * i] * d[2 * i] + d[2 * i + 1] * d[2 * i + 1]) *
                   (d[2 * j] * d[2 * m + 1] - d[2 * m] * d[2 * j + 1]);
        }
        return signOf(det);
    }
    static thread_local Expansion total;
    const double rx[3] = {x[0].x, x[1].x, x[2].x}, ry[3] = {y[0].x, y[1].x, y[2].x};
    total.n = incircleSumOfDoubles(rx, ry, total.e);  // the rounded differences alone
    if (zeroTail) {
        tier = PredicateTier::ZeroTail;
        return total.sign();
    }
    double permanent = 0.0;
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3, m = (i + 2) % 3;
        const double lift = x[i].x * x[i].x + y[i].x * y[i].x;
        permanent += lift * (std::fabs(x[j].x * y[m].x) + std::fabs(x[m].x * y[j].x));
    }
    if (exceedsBound(total.e, total.n, kIncircleBoundB * permanent)) {
        tier = PredicateTier::StageB;
        return total.sign();
    }
    tier = PredicateTier::Expansion;
    double dx[3][2], dy[3][2];
    int dxn[3], dyn[3];
    for (int i = 0; i < 3; ++i) {
        dxn[i] = asExpansion(x[i], dx[i]);
        dyn[i] = asExpansion(y[i], dy[i]);
    }
    total.n = incircleSum(dx, dxn, dy, dyn, total.e);
    return total.sign();
}

template <std::size_t N>
void scaleInto(const double (&v)[N], int k, double (&s)[N]) {
    for (std::size_t i = 0; i < N; ++i) s[i] = k == 0 ? v[i] : std::ldexp(v[i], k);
}

int orient2dExact(Vec2 a, Vec2 b, Vec2 c, PredicateTier& tier) {
    const double v[6] = {a.x, a.y, b.x, b.y, c.x, c.y};
    int k = 0;
    bool allZero = false;
    if (!chooseScale(v, 500, -537, k, allZero)) {
        tier = PredicateTier::BigInteger;
        return orient2dBig(a, b, c);
    }
    double s[6];
    scaleInto(v, k, s);
    return orient2dStages(s, tier);
}

int incircleExact(Vec2 a, Vec2 b, Vec2 c, Vec2 d, PredicateTier& tier) {
    const double v[8] = {a.x, a.y, b.x, b.y, c.x, c.y, d.x, d.y};
    int k = 0;
    bool allZero = false;
    if (!chooseScale(v, 250, -268, k, allZero)) {
        tier = PredicateTier::BigInteger;
        return incircleBig(a, b, c, d);
    }
    double s[8];
    scaleInto(v, k, s);
    return incircleStages(s, tier);
}

// ============================================================================================
// [SECTION] The slow paths of the public predicates (the filters are inline in the header)
// ============================================================================================

thread_local PredicateCounters t_counters;

}  // namespace

namespace detail {

int orient2dSlow(Vec2 a, Vec2 b, Vec2 c) {
    PredicateTier tier = PredicateTier::Expansion;
    const int sign = orient2dExact(a, b, c, tier);
    ++t_counters.orientExact;
    ++t_counters.orientByTier[static_cast<int>(tier)];
    return sign;
}

int incircleSlow(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
    PredicateTier tier = PredicateTier::Expansion;
    const int sign = incircleExact(a, b, c, d, tier);
    ++t_counters.incircleExact;
    ++t_counters.incircleByTier[static_cast<int>(tier)];
    return sign;
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

const char* toString(PredicateTier tier) {
    switch (tier) {
        case PredicateTier::Filter: return "filter";
        case PredicateTier::ZeroTail: return "zero-tail";
        case PredicateTier::StageB: return "stage-b";
        case PredicateTier::Expansion: return "expansion";
        case PredicateTier::BigInteger: return "big-integer";
    }
    return "?";
}

}  // namespace dlab
