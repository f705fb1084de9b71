// Point-set readers: Triangle .node, CSV/whitespace XY and Rossignac's .pts, with typed errors.
//
// Every reader is strict and fuzz-safe: any byte sequence either yields a PointSet or throws
// InputError ("FILE:LINE: message"); nothing else escapes, nothing is undefined, and the work is
// linear in the input size. Coordinates are read with parseDouble (numbers.h), so every finite
// double written with enough digits (17 significant, or the shortest round-trip form) comes back
// bit-for-bit, subnormals and ±DBL_MAX included.
//
// Formats (comments start with '#' anywhere on a line, except one glued to a number, as in
// MSVC's "1.#INF", which is refused as a number; blank lines are ignored; lines may end
// in \n, \r\n or a lone \r; a UTF-8 byte-order mark at the start is skipped):
//
//   .node  Shewchuk's Triangle. First line: <#vertices> [<dimension = 2> [<#attributes>
//          [<#boundary markers = 0|1>]]] (missing trailing fields default to 2, 0, 0, as in
//          Triangle). Then exactly #vertices lines: <index> <x> <y> [attributes] [marker],
//          fields separated by spaces or tabs. The first index (0 or 1) sets indexBase; the
//          others must follow consecutively. Attributes and markers are checked, not kept.
//
//   .csv .xy .txt .dat  One point per line. The separator is fixed by the first non-comment
//          line: ';' if it has one, else ',' if it has one, else runs of spaces/tabs. Without a
//          header every line has exactly two numbers, x then y. A first line with no number in
//          it is a header and is skipped with a warning; it may name the columns: with a header
//          naming columns "x" and "y" (any case, optionally quoted) any number of columns is
//          allowed (id,x,y / x,y,z / label,y,x ...), only x and y are read, the other columns
//          are not checked, and every row must have as many fields as the header. A two-column
//          header with other names (e.g. "lon,lat") means x then y. Three bare numeric columns
//          are refused rather than guessed (id,x,y and x,y,z look the same); the error says to
//          add a header.
//
//   .pts   Rossignac's Processing "pts" class (savePts/loadPts): first line the point count,
//          then exactly that many lines "x,y". Separators may also be spaces/tabs. A third
//          field (the z that the 3D variants of savePts write) is accepted and dropped, with a
//          warning if any z is nonzero; more fields are an error.
//
//   other  The content is sniffed: a Triangle header shape (integers, dimension 2, then vertex
//          lines with an index) reads as .node, a lone count followed by point lines as .pts,
//          anything else as XY. A warning records the guess.
#pragma once

#include "core/engine/geometry.h"

#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace dlab {

struct PointSet {
    std::vector<Vec2> points;
    int indexBase = 0;  // 0 or 1: the index of the first vertex in a .node file, else 0
    std::string path;   // where it came from (file path or the name given to parse*)
    std::vector<std::string> warnings;  // non-fatal remarks, e.g. "skipped header line 1: x,y"
};

// Bad input, raised only at the loading boundary. what() is one line, "FILE:LINE: message", or
// "FILE: message" when no single line is to blame (line() == 0).
class InputError : public std::runtime_error {
public:
    InputError(std::string file, int line, std::string message);
    const std::string& file() const noexcept { return m_file; }
    int line() const noexcept { return m_line; }
    const std::string& message() const noexcept { return m_message; }

private:
    std::string m_file;
    int m_line = 0;
    std::string m_message;
};

// 2 GiB. A point line with two full-precision doubles ("-1.7976931348623157e+308") plus an
// index, attributes and a marker is at most ~64 bytes, so kMaxPoints points fit; the reader
// holds the whole file in memory, so this also caps that buffer. Larger inputs are refused
// before they are read.
inline constexpr std::size_t kMaxFileBytes = std::size_t{1} << 31;

// Reads a whole regular file of at most maxBytes bytes: the one reader of every file the tools
// take (points, sessions, lessons, traces, settings). Without blocking it refuses what is not a
// regular file, also behind a symbolic link: "FILE: cannot read: it is a named pipe (FIFO), not
// a regular file" (a directory, a device, a socket alike). The size is checked before reading
// and again while reading, so /dev/zero behind a link or a growing file cannot exhaust memory.
// firstChunk, when given, sees the first chunk read (up to 64 KiB) and may throw, e.g. to refuse
// binary content early. Throws InputError(path, 0, ...).
// Every file it reads is text: UTF-16 text is refused as such ("the file is UTF-16 text
// (little-endian); save it as UTF-8 ..."), and a NUL byte stops the reading at the chunk that holds
// it ("binary file (NUL byte at offset N)"), so a sparse file is not read whole first. Running out
// of memory for the text is one more InputError, naming the limit.
std::string readRegularFile(const std::string& path, std::size_t maxBytes,
                            const std::function<void(std::string_view)>& firstChunk = {});
// The same reading and checks, the file handed over chunk by chunk (up to 64 KiB each) instead
// of held whole: for readers that keep less than the text (traces, line by line).
void readRegularFileChunks(const std::string& path, std::size_t maxBytes,
                           const std::function<void(std::string_view)>& chunkFn);

// Reads a file and dispatches on its extension (case-insensitive): .node, .pts,
// .csv/.xy/.txt/.dat; anything else is sniffed. Refuses unreadable, empty, oversized and binary
// files before parsing.
PointSet readPointsFile(const std::string& path);

// Parsers over in-memory text; `name` is used in error messages and as PointSet::path.
PointSet parseNode(std::string_view text, const std::string& name);
PointSet parseXY(std::string_view text, const std::string& name);
PointSet parsePts(std::string_view text, const std::string& name);

// Triangle's .poly (a planar straight-line graph): the vertices as in a .node, then
// '<#segments> <#boundary markers>' and 'i a b [marker]' lines, then '<#holes>'. The vertices
// must be in the file itself, and holes are refused (the result is the constrained Delaunay
// triangulation of the convex hull). Segment ends are 0-based ids.
struct PolyFile {
    PointSet points;
    std::vector<std::pair<std::int32_t, std::int32_t>> segments;
};
PolyFile parsePoly(std::string_view text, const std::string& name);
PolyFile readPolyFile(const std::string& path);

// A list of point ids, one a line, in the points' index base (blank lines and text after '#'
// ignored): the 0-based ids in the file's order. Refuses a line that is not one whole number,
// an id outside [base, base + count) and an id listed twice, naming the line.
std::vector<std::int32_t> parseIdList(std::string_view text, const std::string& name, int base,
                                      std::size_t count);

}  // namespace dlab
