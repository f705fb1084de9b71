// Exact geometric predicates: orient2d and incircle, exact for every finite double input.
//
// Sign conventions (world coordinates, y up):
//   orient2d(a, b, c) = sign | bx-ax  by-ay |
//                            | cx-ax  cy-ay |
//     +1: a, b, c counter-clockwise (c strictly left of the directed line a->b)
//     -1: clockwise, 0: collinear (including coincident points).
//
//   incircle(a, b, c, d) = sign | ax-dx  ay-dy  (ax-dx)^2+(ay-dy)^2 |
//                               | bx-dx  by-dy  (bx-dx)^2+(by-dy)^2 |
//                               | cx-dx  cy-dy  (cx-dx)^2+(cy-dy)^2 |
//     For a, b, c counter-clockwise: +1 if d is strictly inside their circumcircle,
//     -1 strictly outside, 0 on it. The sign flips when a, b, c are clockwise.
//
// Evaluation is adaptive, each stage exact or bounded, cheapest first:
//   1. a floating-point filter with a forward error bound (almost every call ends here);
//   2. the coordinate differences, rounded, with their exact round-off (two-sum): when every
//      round-off is zero (integer lattices, most cocircular inputs) the determinant of the
//      rounded differences, computed exactly, is the answer ("zero tail");
//   3. otherwise that exact determinant of the rounded differences decides when its magnitude
//      exceeds a bound on what the round-off of the differences can change (Shewchuk's stage B);
//   4. the full determinant in floating-point expansions (after exact power-of-two scaling);
//   5. big integers for calls whose coordinates span an exponent range too wide for expansions
//      (e.g. 1e-300 next to 1e300).
// Stages 2 to 4 run on the scaled coordinates, where no product overflows or underflows.
#pragma once

#include "core/engine/geometry.h"

#include <cmath>
#include <cstdint>

namespace dlab {

// Inputs must be finite (the inserter refuses NaN and inf at its boundary).
inline int orient2d(Vec2 a, Vec2 b, Vec2 c);
inline int incircle(Vec2 a, Vec2 b, Vec2 c, Vec2 d);

// How a predicate reached its answer, for the GUI's predicate inspector and for tests.
enum class PredicateTier : std::uint8_t { Filter, ZeroTail, StageB, Expansion, BigInteger };
inline constexpr int kNumPredicateTiers = 5;
const char* toString(PredicateTier tier);  // "filter", "zero-tail", "stage-b", ...

struct PredicateReport {
    double approx = 0.0;      // the determinant evaluated in plain double arithmetic
    double errorBound = 0.0;  // the filter's bound on |approx - exact| (inf if not applicable)
    int naiveSign = 0;        // sign of approx: what a plain floating-point predicate says
    int exactSign = 0;        // the true sign
    PredicateTier tier = PredicateTier::Filter;
};

PredicateReport orient2dReport(Vec2 a, Vec2 b, Vec2 c);
PredicateReport incircleReport(Vec2 a, Vec2 b, Vec2 c, Vec2 d);

// How many calls of this thread the filter could not decide, and which stage decided them (for
// statistics). Only the slow path counts, so the filter's hot path stays a few flops: the
// Filter entries of the arrays stay zero.
struct PredicateCounters {
    std::uint64_t orientExact = 0;  // orient2d calls past the filter
    std::uint64_t incircleExact = 0;
    std::uint64_t orientByTier[kNumPredicateTiers] = {};
    std::uint64_t incircleByTier[kNumPredicateTiers] = {};
    PredicateCounters& operator+=(const PredicateCounters& o) {
        orientExact += o.orientExact;
        incircleExact += o.incircleExact;
        for (int t = 0; t < kNumPredicateTiers; ++t) {
            orientByTier[t] += o.orientByTier[t];
            incircleByTier[t] += o.incircleByTier[t];
        }
        return *this;
    }
};
// This thread's counters; a thread that works for another adds its own to that one's when done.
PredicateCounters& predicateCounters();

// ============================================================================================
// The filters, inline: they decide almost every call in a few flops, so they belong in the
// caller's loop. Every call they cannot decide goes to the exact tiers in predicates.cpp.
//
// Shewchuk's forward error bounds (|det - exact| <= k eps * permanent) assume no overflow and
// no underflow. Overflow needs no test: any overflowed product makes the permanent inf or NaN
// (it sums the absolute value of every product), and then no comparison succeeds. Underflow
// adds at most 2^-1075 absolute error per product; multiplied by what follows, the total stays
// below 2^-1072 * (spread + 1), where spread is the sum of the magnitudes each product is
// later multiplied by. We add 2^-90 * permanent to the bound and use the filter only when the
// permanent is large enough for that to cover the underflow error:
//   orient2d: permanent > 2^-900.
//   incircle: permanent > 2^-800 and permanent * 2^900 > spread (lifts plus cross magnitudes).
// These are two compares, where testing every coordinate difference against a safe band
// cost 10% of a whole triangulation.
// ============================================================================================

namespace detail {

int orient2dSlow(Vec2 a, Vec2 b, Vec2 c);          // stages 2-5; counts in predicateCounters()
int incircleSlow(Vec2 a, Vec2 b, Vec2 c, Vec2 d);  // stages 2-5; counts in predicateCounters()

constexpr double kEpsilon = 0x1p-53;
constexpr double kOrientBound = (3.0 + 16.0 * kEpsilon) * kEpsilon + 0x1p-90;
constexpr double kIncircleBound = (10.0 + 96.0 * kEpsilon) * kEpsilon + 0x1p-90;

struct Filtered {
    double det, bound;
    bool usable;  // the bound is valid (no overflow, underflow covered)
    bool decided() const { return usable && (det > bound || -det > bound); }
    int sign() const { return (det > 0) - (det < 0); }
};

inline Filtered orientFilter(Vec2 a, Vec2 b, Vec2 c) {
    const double bx = b.x - a.x, by = b.y - a.y, cx = c.x - a.x, cy = c.y - a.y;
    const double left = bx * cy, right = by * cx;
    const double permanent = std::fabs(left) + std::fabs(right);
    return {left - right, kOrientBound * permanent, permanent > 0x1p-900};
}

inline Filtered incircleFilter(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
    const double adx = a.x - d.x, ady = a.y - d.y;
    const double bdx = b.x - d.x, bdy = b.y - d.y;
    const double cdx = c.x - d.x, cdy = c.y - d.y;
    const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
    const double cdxady = cdx * ady, adxcdy = adx * cdy;
    const double adxbdy = adx * bdy, bdxady = bdx * ady;
    const double alift = adx * adx + ady * ady;
    const double blift = bdx * bdx + bdy * bdy;
    const double clift = cdx * cdx + cdy * cdy;
    const double det =
        alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
    const double sa = std::fabs(bdxcdy) + std::fabs(cdxbdy);
    const double sb = std::fabs(cdxady) + std::fabs(adxcdy);
    const double sc = std::fabs(adxbdy) + std::fabs(bdxady);
    const double permanent = sa * alift + sb * blift + sc * clift;
    const double spread = (alift + blift + clift) + (sa + sb + sc);
    const bool usable = (permanent > 0x1p-800) & (permanent * 0x1p900 > spread);
    return {det, kIncircleBound * permanent, usable};
}

}  // namespace detail

[[gnu::always_inline]] inline int orient2d(Vec2 a, Vec2 b, Vec2 c) {
    const detail::Filtered f = detail::orientFilter(a, b, c);
    if (f.decided()) [[likely]]
        return f.sign();
    return detail::orient2dSlow(a, b, c);
}

[[gnu::always_inline]] inline int incircle(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
    const detail::Filtered f = detail::incircleFilter(a, b, c, d);
    if (f.decided()) [[likely]]
        return f.sign();
    return detail::incircleSlow(a, b, c, d);
}

}  // namespace dlab
