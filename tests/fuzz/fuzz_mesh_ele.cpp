// Fuzz target: the Triangle .ele (+ .neigh) mesh reader against a fixed 3x3 lattice .node, and
// the exact checker on what it reads. The bytes before a first '@' are the .ele, those after it
// the .neigh (none without an '@').
#include "tests/fuzz/fuzz_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text = dlab::fuzz::asText(data, size);
    const std::size_t at = text.find('@');
    const std::string_view ele = text.substr(0, at);
    const std::string_view neigh = at == std::string_view::npos ? "" : text.substr(at + 1);
    static const dlab::PointSet nodes = dlab::parseNode(
        "9 2 0 0\n0 0 0\n1 1 0\n2 2 0\n3 0 1\n4 1 1\n5 2 1\n6 0 2\n7 1 2\n8 2 2\n", "lattice.node");
    dlab::ImportedMesh im;
    try {
        im = dlab::parseEle(ele, "mesh.ele", nodes, neigh,
                            at == std::string_view::npos ? "" : "mesh.neigh");
    } catch (const dlab::InputError& e) {
        dlab::fuzz::checkInputError(e, e.file() == "mesh.ele" ? ele : neigh, e.file());
        dlab::fuzz::require(e.file() == "mesh.ele" || at != std::string_view::npos,
                            "a .neigh error only with a .neigh");
        return 0;
    }
    dlab::fuzz::checkImportedMesh(im);
    return 0;
}
