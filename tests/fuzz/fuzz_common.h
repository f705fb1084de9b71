// Shared checks of the fuzz targets: a failed property aborts with a message, and the rules every
// reader error must follow (one line, names the input, a line number inside the input).
//
// Each target defines LLVMFuzzerTestOneInput. Built with clang -fsanitize=fuzzer it is a
// libFuzzer executable; built with any compiler next to replay_main.cpp it is a plain program
// that runs every file of a corpus through the same function (the regression tests in CTest).
#pragma once

#include "core/engine/io_read.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace dlab::fuzz {

// Prints "fuzz property failed: WHAT" (plus detail) to stderr and aborts: libFuzzer then saves
// the input as a crash artifact, and the replay program fails its CTest test.
[[noreturn]] void fail(const std::string& what, const std::string& detail = {});

inline void require(bool condition, const char* what, const std::string& detail = {}) {
    if (!condition) fail(what, detail);
}

// The text a reader sees: the fuzz bytes as they are (NUL and invalid UTF-8 included).
inline std::string_view asText(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

// Number of lines as the readers count them (\n, \r\n and a lone \r end a line).
std::int64_t countLines(std::string_view text);

// Checks an InputError raised while reading `text` under the name `name`: what() is one line of
// printable text that starts with the name, and the line it blames exists in the input.
void checkInputError(const InputError& e, std::string_view text, const std::string& name);

// Checks a successful read: every coordinate finite, at most kMaxPoints points, warnings one
// line each, and the points survive a write/read round trip through `reparse` bit for bit.
using Reparse = PointSet (*)(std::string_view text, const std::string& name);
void checkPointSet(const PointSet& ps, const std::string& name, Reparse reparse,
                   std::string_view format);

// Reads `text` with `parse`; an InputError fails the property `what`.
PointSet mustRead(Reparse parse, std::string_view text, const std::string& name, const char* what);

// Same points bit for bit and the same index base; else fails naming `what`.
void requireSamePoints(const PointSet& a, const PointSet& b, const std::string& what);

// The points written in `format` ("node", "xy", "pts"), shortest round-trip decimal form.
std::string writePoints(const std::vector<Vec2>& points, std::string_view format, int indexBase);

// Runs one reader on the bytes and checks either outcome.
void checkReader(const std::uint8_t* data, std::size_t size, Reparse parse,
                 std::string_view format);

}  // namespace dlab::fuzz
