// Decimal text <-> double, exact and the same on every target: fast_float reads (correctly
// rounded, as std::from_chars does), {fmt} writes the shortest text that reads back to the same
// double. One code path for the desktop and the browser build (the libc++ of emscripten has no
// floating-point std::from_chars or std::to_chars). Both libraries are header-only and private
// to numbers.cpp: nothing of them reaches a user of the engine.
#pragma once

#include <string>
#include <system_error>

namespace dlab {

struct ParseResult {
    const char* ptr;  // one past the last character used (first when nothing was read)
    std::errc ec;     // {}, invalid_argument (no number), result_out_of_range
};

// As std::from_chars(first, last, value) for a double in the general format: no leading spaces or
// '+'; "inf", "infinity" and "nan" (any case) read as such; a decimal that overflows to infinity
// or underflows to zero gives result_out_of_range and leaves `value` as it was.
ParseResult parseDouble(const char* first, const char* last, double& value);

// Appends the shortest decimal form of x that reads back bit-exact ("0.1", "1e-300",
// "-1.7976931348623157e+308"; non-finite values as "inf", "-inf", "nan").
void appendShortest(std::string& out, double x);
std::string shortest(double x);
// Appends x with exactly `decimals` digits after the point ("12.50"), as printf's %.*f.
void appendFixed(std::string& out, double x, int decimals);
// Appends x with `significant` significant digits, as printf's %.*g ("1.23456789e+12").
void appendGeneral(std::string& out, double x, int significant);

}  // namespace dlab
