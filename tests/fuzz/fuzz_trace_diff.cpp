// Fuzz target: a student's trace read leniently (parseTraceText) and compared with ours
// (diffTraces).
//
// Byte [0] picks the diff options; the rest is the student's trace. Either outcome is checked: an
// InputError follows the one-line rules; a trace that reads is replayed (TraceReplay) and diffed
// against our own run of a small degenerate point set, and the verdict and its evidence are one
// line each. No triangle or corner number in the input may size memory beyond what the input
// holds (libFuzzer's -malloc_limit_mb and the replay's allocation check catch that).
#include "tests/fuzz/fuzz_common.h"

#include "core/teaching/trace_diff.h"

#include <sstream>

namespace {

using namespace dlab;
using dlab::fuzz::fail;
using dlab::fuzz::require;

bool oneLine(const std::string& s) { return s.find_first_of("\r\n") == std::string::npos; }

const TraceFile& reference() {
    static const TraceFile ref = [] {
        // A square with its centre, a point on an edge and a duplicate: splits, an edge split,
        // flips and a skip.
        Inserter ins({{0, 0}, {4, 0}, {4, 4}, {0, 4}, {2, 2}, {2, 0}, {2, 2}, {1, 3}});
        return traceOfRun(ins, "ours.jsonl");
    }();
    return ref;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    DiffOptions options;
    options.allOps = data[0] & 1;
    options.corners = (data[0] >> 1) & 1;
    options.context = (data[0] >> 2) % 5;
    const std::string_view text = dlab::fuzz::asText(data + 1, size - 1);
    const std::string name = "student.jsonl";
    std::istringstream in{std::string(text)};
    TraceFile student;
    try {
        student = parseTraceText(in, name);
    } catch (const InputError& e) {
        std::string asLines(text);  // trace lines end at '\n' only (std::getline)
        for (char& c : asLines) c = c == '\r' ? ' ' : c;
        dlab::fuzz::checkInputError(e, asLines, name);
        return 0;
    } catch (const std::exception& e) {
        fail("a bad student trace raises InputError, nothing else", e.what());
    }
    for (const TraceOp& op : student.ops) {
        require(op.line >= 1, "every op knows its line");
    }
    TraceDiff diff;
    try {
        diff = diffTraces(reference(), student, options);
    } catch (const InputError& e) {
        // A trace can read and still describe an impossible mesh: that is reported, not a crash.
        require(oneLine(e.what()), "a diff error is one line", e.what());
        return 0;
    }
    require(oneLine(diff.what), "the verdict is one line", diff.what);
    for (const std::string& d : diff.details)
        require(oneLine(d), "each piece of evidence is one line", d);
    require(diff.refOp <= reference().ops.size() && diff.studentOp <= student.ops.size(),
            "the difference points into both traces");
    const std::string report = formatDiff(diff, reference(), student, options);
    require(diff.equal || !report.empty(), "a difference is reported");
    return 0;
}
