// Decimal text <-> double with fast_float and {fmt} (header-only, private to this file).
#include "core/engine/numbers.h"

#include <fast_float/fast_float.h>
#include <fmt/format.h>

#include <cmath>
#include <iterator>

namespace dlab {

namespace {

// Whether the mantissa of a decimal number (the text before its exponent) has a non-zero digit:
// such a number that reads as zero has underflowed.
bool nonZeroMantissa(const char* first, const char* last) {
    for (const char* p = first; p != last && *p != 'e' && *p != 'E'; ++p) {
        if (*p >= '1' && *p <= '9') return true;
    }
    return false;
}

bool spelledOut(const char* first, const char* last) {
    for (const char* p = first; p != last; ++p) {
        if (*p == 'i' || *p == 'I' || *p == 'n' || *p == 'N') return true;
    }
    return false;
}

}  // namespace

ParseResult parseDouble(const char* first, const char* last, double& value) {
    double v = 0.0;
    const auto r = fast_float::from_chars(first, last, v);
    if (r.ec != std::errc()) return {r.ptr, r.ec};
    const bool overflow = std::isinf(v) && !spelledOut(first, r.ptr);
    const bool underflow = v == 0.0 && nonZeroMantissa(first, r.ptr);
    if (overflow || underflow) return {r.ptr, std::errc::result_out_of_range};
    value = v;
    return {r.ptr, std::errc()};
}

void appendShortest(std::string& out, double x) {
    fmt::format_to(std::back_inserter(out), "{}", x);
}

std::string shortest(double x) { return fmt::format("{}", x); }

void appendFixed(std::string& out, double x, int decimals) {
    fmt::format_to(std::back_inserter(out), "{:.{}f}", x, decimals);
}

void appendGeneral(std::string& out, double x, int significant) {
    fmt::format_to(std::back_inserter(out), "{:.{}g}", x, significant);
}

}  // namespace dlab
