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
// Evaluation has three tiers: a floating-point filter with a forward error bound (almost
// every call ends here), an exact evaluation with floating-point expansions (after exact
// power-of-two scaling), and an exact big-integer evaluation for calls whose coordinates
// span an exponent range too wide for expansions (e.g. 1e-300 next to 1e300).
#pragma once

#include "core/geometry.h"

#include <cstdint>

namespace dlab {

int orient2d(Vec2 a, Vec2 b, Vec2 c);
int incircle(Vec2 a, Vec2 b, Vec2 c, Vec2 d);

// How a predicate reached its answer, for the GUI's predicate inspector and for tests.
enum class PredicateTier : std::uint8_t { Filter, Expansion, BigInteger };

struct PredicateReport {
    double approx = 0.0;      // the determinant evaluated in plain double arithmetic
    double errorBound = 0.0;  // the filter's bound on |approx - exact| (inf if not applicable)
    int naiveSign = 0;        // sign of approx: what a plain floating-point predicate says
    int exactSign = 0;        // the true sign
    PredicateTier tier = PredicateTier::Filter;
};

PredicateReport orient2dReport(Vec2 a, Vec2 b, Vec2 c);
PredicateReport incircleReport(Vec2 a, Vec2 b, Vec2 c, Vec2 d);

// Counters of how often each tier decided (for statistics; not thread-safe, cheap).
struct PredicateCounters {
    std::uint64_t orientCalls = 0, orientExact = 0;
    std::uint64_t incircleCalls = 0, incircleExact = 0;
};
PredicateCounters& predicateCounters();

}  // namespace dlab
