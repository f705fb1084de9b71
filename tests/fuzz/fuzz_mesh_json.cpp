// Fuzz target: the JSON mesh reader (corner table or Delaunator) and the exact checker.
#include "tests/fuzz/fuzz_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text = dlab::fuzz::asText(data, size);
    dlab::fuzz::checkMeshReader(text, "mesh.json",
                                [&] { return dlab::parseMeshJson(text, "mesh.json"); });
    return 0;
}
