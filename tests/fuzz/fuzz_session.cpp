// Fuzz target: session files (JSON), the bug report a user attaches; loadSessionText end to end.
//
// The bytes are the session's text. Either outcome is checked: refused, the error is one line
// that names the file and the state is exactly as before (points, options, step, mesh);
// accepted, the mesh validates, the step is within the run, and the session written back
// from the loaded state loads again to the same state (a round trip).
#include "tests/fuzz/fuzz_common.h"

#include "core/engine/mesh.h"
#include "ui/app_state.h"
#include "ui/files/session.h"

#include <algorithm>
#include <string>

namespace {

using namespace dlab;
using dlab::fuzz::require;

const std::string kName = "fuzz.json";

struct Fingerprint {
    std::vector<Vec2> points;
    std::size_t position = 0;
    std::uint64_t mesh = 0;
    int boundary = 0, locator = 0, order = 0;
    std::uint64_t seed = 0;
    bool operator==(const Fingerprint&) const = default;
};

Fingerprint fingerprintOf(const ui::AppState& st) {
    const InsertOptions& o = st.engine.options();
    return {st.engine.points(),
            st.engine.position(),
            ui::MeshFingerprint(st.engine.mesh()),
            static_cast<int>(o.boundary),
            static_cast<int>(o.locator),
            static_cast<int>(o.order),
            o.seed};
}

bool oneLine(const std::string& s) {
    return std::none_of(s.begin(), s.end(), [](char c) { return c == '\n' || c == '\r'; });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text = dlab::fuzz::asText(data, size);
    ui::AppState st;
    const std::vector<Vec2> start = {{0, 0}, {4, 0}, {0, 3}, {4, 3}, {2, 1}};
    require(st.loadPoints(start, "start"), "the start points load");
    st.engine.seek(7);
    const Fingerprint before = fingerprintOf(st);
    std::string error;
    if (!ui::loadSessionText(st, text, kName, error)) {
        require(!error.empty() && oneLine(error), "a refused session gives one line", error);
        require(error.find(kName) != std::string::npos, "a refused session's error names the file",
                error);
        require(fingerprintOf(st) == before, "a refused session leaves the state as it was", error);
        return 0;
    }
    // At any step the table is consistent and counter-clockwise (Delaunay only between insertions).
    ValidateOptions vo;
    vo.delaunay = false;
    vo.firstVirtual = st.engine.inserter().firstVirtual();
    const std::vector<Violation> broken = validate(st.engine.mesh(), vo);
    require(broken.empty(), "a loaded session's mesh validates",
            broken.empty() ? "" : broken[0].message);
    require(st.engine.batch() || st.engine.position() <= st.engine.recorded(),
            "the step is within the recorded run");
    const Fingerprint loaded = fingerprintOf(st);
    const std::string again = ui::sessionText(st);
    ui::AppState other;
    std::string error2;
    require(ui::loadSessionText(other, again, "again.json", error2),
            "a session written back loads again", error2);
    require(fingerprintOf(other) == loaded, "a session written back loads to the same state");
    return 0;
}
