// Fuzz target: the trace reader (readTrace, JSON Lines).
//
// Any bytes either read or fail with one line "NAME:LINE: ..." naming a line of the input; every
// record read writes back (toJsonLine) to a line that reads as the same record.
#include "tests/fuzz/fuzz_common.h"

#include "core/teaching/trace.h"

#include <sstream>
#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace dlab;
    using namespace dlab::fuzz;
    const std::string name = "fuzz.jsonl";
    const std::string_view text = asText(data, size);
    std::istringstream in{std::string(text)};
    std::vector<TraceRecord> records;
    try {
        records = readTrace(in, name);
    } catch (const InputError& e) {
        // Trace lines end at '\n' only (std::getline): count those for the line bound.
        std::int64_t lines = 0;
        for (const char c : text) lines += c == '\n';
        if (!text.empty() && text.back() != '\n') ++lines;
        require(e.line() >= 1 && e.line() <= lines, "a trace error blames a line of the input",
                e.what());
        std::string asLines(text);
        for (char& c : asLines) c = c == '\r' ? ' ' : c;  // keep countLines in step with getline
        checkInputError(e, asLines, name);
        return 0;
    } catch (const std::exception& e) {
        fail("a bad trace raises InputError, nothing else", e.what());
    }
    for (const TraceRecord& r : records) {
        const std::string line = toJsonLine(r);
        require(line.find('\n') == std::string::npos, "a trace record is written on one line",
                line);
        TraceRecord back;
        try {
            back = parseTraceLine(line, name, 1);
        } catch (const std::exception& e) {
            fail("a record that was read can be written and read back", line + " -> " + e.what());
        }
        require(back == r, "a trace record round-trips through toJsonLine", line);
    }
    return 0;
}
