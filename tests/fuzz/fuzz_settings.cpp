// Fuzz target: the settings file (JSON) the GUI reads at start and merges on every write.
//
// The bytes are the file. Reading never throws; a warning is one line; a file that is not a
// settings object is kept aside under a new name with its bytes intact and the warning names
// it. Writing the progress back merges with what the file held and reads back to the same
// progress (every lesson of the file kept, none lost).
#include "tests/fuzz/fuzz_common.h"

#include "ui/app_state.h"
#include "ui/files/settings.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

using namespace dlab;
using dlab::fuzz::require;
namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

const fs::path& folder() {
    static const fs::path dir = [] {
        const fs::path d =
            fs::temp_directory_path() / ("dlab_fuzz_settings_" + std::to_string(::getpid()));
        fs::create_directories(d);
        return d;
    }();
    return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const fs::path dir = folder();
    for (const auto& e : fs::directory_iterator(dir)) fs::remove(e.path());
    const std::string path = (dir / "settings.json").string();
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    std::ofstream(path, std::ios::binary) << bytes;

    ui::AppState st;
    ui::WindowOptions window;
    std::string warning;
    ui::loadSettings(path, st, window, warning);
    require(warning.find_first_of("\r\n") == std::string::npos, "a settings warning is one line",
            warning);
    if (!warning.empty()) {
        // Kept aside, whole, under the name the warning gives.
        const auto at = warning.find("kept as ");
        require(at != std::string::npos, "a damaged settings file is kept aside", warning);
        require(!fs::exists(path), "the damaged file is no longer in the settings' place", warning);
        std::size_t aside = 0;
        for (const auto& e : fs::directory_iterator(dir)) {
            if (e.path().filename().string().rfind("settings.json.bad-", 0) != 0) continue;
            ++aside;
            require(slurp(e.path()) == bytes, "the file kept aside holds the damaged bytes");
        }
        require(aside == 1, "one file kept aside");
        return 0;
    }
    // Read: the progress written back (merged with the file's own) reads back to the same.
    const auto before = st.lessonPlayer.saved;
    st.lessonPlayer.settingsPath = path;
    std::string error;
    require(ui::saveLessonProgress(st, error), "progress is written over a good settings file",
            error);
    ui::AppState again;
    ui::WindowOptions window2;
    ui::loadSettings(path, again, window2, warning);
    require(warning.empty(), "settings written back read without a warning", warning);
    require(again.lessonPlayer.saved == before, "every lesson's progress survives a write");
    return 0;
}
