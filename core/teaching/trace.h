// The operation trace as JSON Lines: one object per recorded operation, written by dtlab trace
// and read back for round trips and for comparing a student's run with ours.
//
// Each line: {"i":k, "op":"Flip", "vertex":v, "a":c, "b":d, "where":"edge", "sign":1,
//             "triangles_before":T0, "triangles_after":T1,
//             "changes":[["V",corner,before,after], ["O",corner,before,after], ...],
//             "triangles":[[t, v0, v1, v2], ...]}
// "where" is present for Located/Split/SplitEdge, "sign" for InCircleTest; "triangles" lists
// the triangles the op touched, as they are after it (vertex triples, counter-clockwise).
#pragma once

#include "core/engine/inserter.h"

#include <iosfwd>
#include <string>
#include <vector>

namespace dlab {

struct TraceRecord {
    std::size_t index = 0;
    OpType type = OpType::Start;
    std::int32_t vertex = kNone, a = kNone, b = kNone;
    std::string where;  // empty when not applicable
    int sign = 0;
    bool hasSign = false;
    std::int32_t trianglesBefore = 0, trianglesAfter = 0;
    std::vector<CellChange> changes;
    struct Tri {
        std::int32_t t, v0, v1, v2;
    };
    std::vector<Tri> triangles;
    friend bool operator==(const TraceRecord& x, const TraceRecord& y);
};

// The record of ops [from, to) of a journal, with the triangles as the mesh holds them at the
// journal's current position (call with the journal at `to`... or use traceRecord per step).
TraceRecord traceRecord(const Journal& journal, std::size_t opIndex, const Mesh& meshAfterOp);
std::string toJsonLine(const TraceRecord& record);
// Throws InputError ("NAME:LINE: ...", core/engine/io_read.h) on a malformed line: bad JSON, a
// missing
// or mistyped field, or an integer out of its range (never truncated).
TraceRecord parseTraceLine(const std::string& line, const std::string& name, int lineNumber);
std::vector<TraceRecord> readTrace(std::istream& in, const std::string& name);

}  // namespace dlab
