// Fuzz target: the Wavefront OBJ (parseObj) mesh reader and the exact checker on what it reads.
#include "tests/fuzz/fuzz_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text = dlab::fuzz::asText(data, size);
    dlab::fuzz::checkMeshReader(text, "mesh.obj", [&] { return dlab::parseObj(text, "mesh.obj"); });
    return 0;
}
