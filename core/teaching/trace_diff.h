// Comparing two runs by their traces (JSON Lines, core/teaching/trace.h): ours and a student's.
// By default, insertion by insertion: after each insertion the student's triangles (vertex
// triples, up to rotation) must be ours, and where they are not, the student's mesh is checked
// (core/teaching/mesh_check.h) to say why in triangle terms. Every correct implementation agrees
// on these, whatever its triangle numbering, corner order, walk or flip order. As options: op by
// op (the flips made), and, for a student who follows the paper's corner-reuse convention, corner
// by corner.
//
// A student's trace may hold only some fields. The minimum, one JSON object per line:
//   {"op": "Split", "triangles": [[t, v0, v1, v2], ...]}
// where "op" is one of Start, Split, SplitEdge, Flip, SkipDuplicate, Finalize (the operations
// that change the mesh; LocateStep, Located, InCircleTest and Inserted lines may be present
// and are shown as context), and "triangles" lists the triangles the operation created or
// changed, as they are after it: t is the student's own triangle number, so that a later line
// can replace triangle t. Instead of "triangles" a line may give "changes" (V/O cell changes,
// as dtlab trace writes them). Finalize may list every final triangle, or nothing (no
// "triangles", or an empty list): then the triangles that touch a ghost/super vertex are
// dropped. "vertex", "a", "b", "i" are optional.
#pragma once

#include "core/engine/inserter.h"
#include "core/teaching/mesh_check.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <iosfwd>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace dlab {

// One line of a trace, with what it had.
struct TraceOp {
    int line = 0;  // 1-based line in its file
    OpType type = OpType::Start;
    std::optional<std::int64_t> index;  // "i"
    std::optional<std::int32_t> vertex, a, b;
    std::optional<int> sign;
    std::string where;
    bool hasChanges = false;
    std::vector<CellChange> changes;
    bool hasTriangles = false;
    std::vector<std::array<std::int32_t, 4>> triangles;  // t, v0, v1, v2
    bool changesMesh() const;  // Start, Split, SplitEdge, Flip, SkipDuplicate, Finalize
};

struct TraceFile {
    std::string name;
    // A deque: it grows a block at a time, never holding an old and a new copy of every op at
    // once as a vector's doubling does (the peak of reading a large trace).
    std::deque<TraceOp> ops;
    MeshGeometry geometry;  // known for our own runs (traceOfRun), not for a file
};

// The largest trace file read: 1 GiB (about 5 million operations of a few hundred bytes each).
// The file is read line by line; what is held is its operations, about kTraceBytesPerOp each
// (measured on dtlab trace's output), at most kMaxTraceOps of them: two traces of the most
// operations (diff-trace) hold about 2 x 2^23 x 200 B = 3.4 GB.
inline constexpr std::size_t kMaxTraceFileBytes = std::size_t{1} << 30;
inline constexpr std::size_t kMaxTraceOps = std::size_t{1} << 23;
inline constexpr std::size_t kTraceBytesPerOp = 200;
// The longest line: a Finalize that lists every final triangle of a large run fits.
inline constexpr std::size_t kMaxTraceLineBytes = std::size_t{64} << 20;

// Reads a trace leniently (only "op" is required on each line; blank lines are skipped).
// Throws InputError ("NAME:LINE: what") on anything that is not such a trace.
TraceFile readTraceFile(const std::string& path);
TraceFile parseTraceText(std::istream& in, const std::string& name);
// Our own run as a trace (what dtlab trace writes), without going through a file.
TraceFile traceOfRun(Inserter& ins, const std::string& name);
// The largest vertex id a trace names (in "vertex", "triangles" and V changes); -1 when none.
std::int32_t largestVertex(const TraceFile& f);

// The mesh a trace describes, op by op: V and O from "changes", or triangle t -> triple from
// "triangles".
class TraceReplay {
public:
    void apply(const TraceOp& op);
    // The live triangles (no cell unset), canonical and sorted.
    std::vector<Triple> triangles() const;
    // The triangles whose vertices the last op set or changed, as they are after it.
    const std::vector<Triple>& touched() const { return m_touched; }
    const std::vector<std::int32_t>& V() const { return m_V; }
    const std::vector<std::int32_t>& O() const { return m_O; }
    bool hasO() const { return m_hasO; }
    // Keeps only the triangles all of whose vertices are in `keep` (Finalize without data).
    void dropTrianglesOutside(const std::vector<bool>& keep);

private:
    void setTriangle(std::int32_t t, Triple tri);
    std::vector<std::int32_t> m_V, m_O;
    bool m_hasO = false;
    std::vector<Triple> m_touched;
};

// allOps and corners compare op by op, as byOp does (they mean nothing insertion by insertion).
struct DiffOptions {
    bool byOp = false;     // compare op by op (each flip), not insertion by insertion
    bool allOps = false;   // compare every op one to one (types, vertices), not only mesh changes
    bool corners = false;  // the student follows the corner-reuse convention: compare V (and O)
    int context = 3;       // lines of context before the difference
};

struct TraceDiff {
    bool equal = true;
    std::size_t compared = 0;  // operations compared
    // Where the first difference is: indices into ref.ops / student.ops (== size(): past the end).
    std::size_t refOp = 0, studentOp = 0;
    // Insertion by insertion: the step whose result is wrong (0: the start, 1..n: the n-th
    // insertion or skipped duplicate, n + 1: Finalize; -1 op by op) and the point it inserts.
    int insertion = -1;
    std::int32_t vertex = -1;
    std::string what;                  // one line: "the triangles differ after Flip"
    std::vector<std::string> details;  // the evidence, one line each
    // What the options do that the user may not expect ("--corners compares operation by
    // operation"), one line each, printed first.
    std::vector<std::string> notes;
};

TraceDiff diffTraces(const TraceFile& ref, const TraceFile& student,
                     const DiffOptions& options = {});
// The report dtlab diff-trace prints: the difference, its evidence, the ops around it in both.
std::string formatDiff(const TraceDiff& diff, const TraceFile& ref, const TraceFile& student,
                       const DiffOptions& options = {});
// One op as a short line for context: "ref.jsonl:58 [57] Flip vertex 9 a=12 b=20".
std::string summarize(const TraceFile& file, std::size_t op);

}  // namespace dlab
