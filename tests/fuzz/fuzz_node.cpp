// Fuzz target: the Triangle .node reader (parseNode).
// Any bytes either read (and round-trip bit for bit) or fail with one InputError line naming
// the input and a line of it.
#include "tests/fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    dlab::fuzz::checkReader(data, size, &dlab::parseNode, "node");
    return 0;
}
