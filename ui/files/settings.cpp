// Settings as JSON (nlohmann): every field optional, unknown fields ignored, ranges clamped. Lesson
// progress is merged with the file's under a lock on every write, so that two instances, or an
// instance and its earlier self, never lose each other's progress.
#include "ui/files/settings.h"

#include "core/engine/io_read.h"
#include "core/engine/io_write.h"
#include "core/engine/text_util.h"

#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <filesystem>

namespace dlab::ui {

namespace {

using Json = nlohmann::json;

template <class T>
void read(const Json& j, const char* key, T& out) {
    const auto it = j.find(key);
    if (it == j.end()) return;
    try {
        out = it->get<T>();
    } catch (const Json::exception&) {
        // A wrong type keeps the default.
    }
}

// Holds an exclusive flock on PATH.lock while it lives (the settings file itself is replaced by
// rename, so a lock on it would lock the old file). No lock (an error opening it) only loses the
// protection against a writer at the same moment.
class SettingsLock {
public:
    explicit SettingsLock(const std::string& path) {
        m_fd = ::open((path + ".lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
        if (m_fd >= 0) {
            while (::flock(m_fd, LOCK_EX) != 0 && errno == EINTR) {}
        }
    }
    ~SettingsLock() {
        if (m_fd >= 0) ::close(m_fd);  // releases the lock
    }
    SettingsLock(const SettingsLock&) = delete;
    SettingsLock& operator=(const SettingsLock&) = delete;

private:
    int m_fd = -1;
};

// PATH renamed to PATH.bad-YYYYMMDD-HHMMSS (a number after it when that exists): the new name,
// or empty when it could not be renamed.
std::string keepAside(const std::string& path) {
    const std::time_t now = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&now, &tm);
    char stamp[32];
    std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &tm);
    std::error_code ec;
    for (int k = 0; k < 100; ++k) {
        const std::string aside =
            path + ".bad-" + stamp + (k ? "-" + std::to_string(k) : std::string());
        if (std::filesystem::exists(aside, ec)) continue;
        std::filesystem::rename(path, aside, ec);
        return ec ? std::string() : aside;
    }
    return {};
}

enum class SettingsFile { Missing, Read, Damaged, Unreadable };

// The settings file as JSON. A regular file that is not a settings object (a typo, a truncated
// write, binary junk) is renamed aside, and `warning` says where; one that cannot be read (a pipe,
// a device, no permission) is left where it is, with a warning.
SettingsFile readSettingsFile(const std::string& path, Json& out, std::string& warning) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return SettingsFile::Missing;
    std::string why;
    try {
        out = Json::parse(readRegularFile(path, kMaxSettingsFileBytes));
        if (out.is_object()) return SettingsFile::Read;
        why = "not a JSON object";
    } catch (const InputError& e) {
        // Not a file's content but its kind or its access ("cannot open file: Permission
        // denied", "cannot read: it is a named pipe"): left where it is.
        if (!std::filesystem::is_regular_file(path, ec) || e.message().rfind("cannot ", 0) == 0) {
            warning = escapeControls(e.what()) + " (settings ignored)";
            return SettingsFile::Unreadable;
        }
        why = e.message();
    } catch (const Json::exception& e) {
        why = e.what();
    }
    const std::string aside = keepAside(path);
    warning = escapeControls(path) + ": damaged settings file (" + escapeControls(why) + "); " +
              (aside.empty() ? "it could not be renamed, and is replaced at the next save"
                             : "kept as " + escapeControls(aside)) +
              ", the defaults are used";
    return SettingsFile::Damaged;
}

LessonProgress progressFrom(const std::string& lesson, const Json& v) {
    LessonProgress p;
    p.lesson = lesson;
    read(v, "title", p.title);
    read(v, "stop", p.stop);
    read(v, "furthest", p.furthest);
    read(v, "answers", p.answers);
    return p;
}

std::map<std::string, LessonProgress> lessonsFrom(const Json& j) {
    std::map<std::string, LessonProgress> out;
    const auto ls = j.find("lessons");
    if (ls == j.end() || !ls->is_object()) return out;
    for (const auto& [lesson, v] : ls->items()) {
        if (v.is_object()) out[lesson] = progressFrom(lesson, v);
    }
    return out;
}

Json lessonsJson(const std::map<std::string, LessonProgress>& saved) {
    Json lessons = Json::object();
    for (const auto& [file, p] : saved) {
        lessons[file] = {
            {"title", p.title}, {"stop", p.stop}, {"furthest", p.furthest}, {"answers", p.answers}};
    }
    return lessons;
}

// Everything but the lessons; the window only when it is given.
namespace {
Json overlaysJson(const Overlays& ov) {
    Json j = Json::object();
    for (const OverlaySwitch& f : kOverlaySwitches) j[overlayKey(f)] = ov.*f.flag;
    return j;
}
}  // namespace

Json settingsJson(const AppState& st, const WindowOptions* window) {
    const Overlays& ov = userOverlays(st);  // not a lesson's
    Json j = {
        {"layout",
         {{"right_width", st.layout.rightWidth},
          {"bottom_height", st.layout.bottomHeight},
          {"inspector_height", st.layout.inspectorHeight}}},
        {"overlays", overlaysJson(ov)},
        {"presentation", st.presentation},
        {"ops_per_second", st.run.opsPerSecond},
        {"snap_to_grid", st.snapToGrid},
        {"grid_step", st.gridStep},
    };
    if (window) {
        j["window"] = {{"x", window->x},
                       {"y", window->y},
                       {"width", window->width},
                       {"height", window->height},
                       {"maximized", window->maximized}};
    }
    return j;
}

// Writes `j` over PATH through the atomic writer (a unique temporary, then rename).
bool writeSettingsFile(const std::string& path, const Json& j, std::string& error) {
    std::error_code ec;
    std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
    try {
        const std::string body = j.dump(2) + "\n";
        writeTextFile(path, [&](std::ostream& os) { os << body; });
    } catch (const std::exception& e) {
        error = escapeControls(e.what());
        return false;
    }
    return true;
}

}  // namespace

void mergeProgress(LessonProgress& into, const LessonProgress& other) {
    if (into.title != other.title) return;  // another lesson at the same path: ours stands
    into.furthest = std::max(into.furthest, other.furthest);
    if (into.answers.size() < other.answers.size()) into.answers.resize(other.answers.size(), 0);
    for (std::size_t k = 0; k < other.answers.size(); ++k)
        into.answers[k] = std::max(into.answers[k], other.answers[k]);
}

std::string defaultSettingsPath() {
    if (const char* x = std::getenv("XDG_CONFIG_HOME"); x && *x)
        return std::string(x) + "/delaunay-lab/settings.json";
    if (const char* h = std::getenv("HOME"); h && *h)
        return std::string(h) + "/.config/delaunay-lab/settings.json";
    return {};
}

namespace {

void readWindowAndLayout(const Json& j, AppState& st, WindowOptions& window) {
    if (const auto w = j.find("window"); w != j.end() && w->is_object()) {
        read(*w, "x", window.x);
        read(*w, "y", window.y);
        read(*w, "width", window.width);
        read(*w, "height", window.height);
        read(*w, "maximized", window.maximized);
        window.width = std::clamp(window.width, 640, 16384);
        window.height = std::clamp(window.height, 400, 16384);
    }
    if (const auto l = j.find("layout"); l != j.end() && l->is_object()) {
        read(*l, "right_width", st.layout.rightWidth);
        read(*l, "bottom_height", st.layout.bottomHeight);
        read(*l, "inspector_height", st.layout.inspectorHeight);
        st.layout.rightWidth = std::clamp(st.layout.rightWidth, 0.15f, 0.7f);
        st.layout.bottomHeight = std::clamp(st.layout.bottomHeight, 0.05f, 0.6f);
        st.layout.inspectorHeight = std::clamp(st.layout.inspectorHeight, 0.1f, 0.9f);
    }
}

void readOverlays(const Json& j, Overlays& ov) {
    const auto o = j.find("overlays");
    if (o == j.end() || !o->is_object()) return;
    for (const OverlaySwitch& f : kOverlaySwitches) read(*o, overlayKey(f).c_str(), ov.*f.flag);
}

}  // namespace

void loadSettings(const std::string& path, AppState& st, WindowOptions& window,
                  std::string& warning) {
    if (path.empty()) return;
    Json j;
    {
        SettingsLock lock(path);  // not half of another instance's write
        if (readSettingsFile(path, j, warning) != SettingsFile::Read) return;
    }
    readWindowAndLayout(j, st, window);
    readOverlays(j, st.overlays);
    for (auto& [lesson, p] : lessonsFrom(j)) st.lessonPlayer.saved[lesson] = std::move(p);
    read(j, "presentation", st.presentation);
    read(j, "ops_per_second", st.run.opsPerSecond);
    st.run.opsPerSecond = std::clamp(st.run.opsPerSecond, 0.5f, RunControl::kFullSpeed);
    read(j, "snap_to_grid", st.snapToGrid);
    read(j, "grid_step", st.gridStep);
    if (!(st.gridStep > 0)) st.gridStep = 10;
}

void clampWindowToWorkArea(WindowOptions& window, int areaX, int areaY, int areaWidth,
                           int areaHeight) {
    if (areaWidth <= 0 || areaHeight <= 0) return;
    window.width = std::clamp(window.width, 1, areaWidth);
    window.height = std::clamp(window.height, 1, areaHeight);
    if (window.x < 0 || window.y < 0) return;  // the window manager places it
    window.x = std::clamp(window.x, areaX, areaX + areaWidth - window.width);
    window.y = std::clamp(window.y, areaY, areaY + areaHeight - window.height);
}

bool saveSettings(const std::string& path, const AppState& st, const WindowOptions& window,
                  std::string& error) {
    if (path.empty()) return true;
    SettingsLock lock(path);
    Json disk;
    std::string warning;
    auto lessons = st.lessonPlayer.saved;
    if (readSettingsFile(path, disk, warning) == SettingsFile::Read) {
        for (const auto& [lesson, p] : lessonsFrom(disk)) {
            const auto [it, added] = lessons.emplace(lesson, p);
            if (!added) mergeProgress(it->second, p);
        }
    }
    Json j = settingsJson(st, &window);
    j["lessons"] = lessonsJson(lessons);
    if (!writeSettingsFile(path, j, error)) return false;
    if (!warning.empty()) error = warning;  // written; what was found is still worth saying
    return warning.empty();
}

bool saveLessonProgress(AppState& st, std::string& error) {
    LessonState& L = st.lessonPlayer;
    if (L.settingsPath.empty()) return true;
    SettingsLock lock(L.settingsPath);
    // The file as another instance may have left it: its settings stay, its lessons merge.
    Json j;
    std::string warning;
    if (readSettingsFile(L.settingsPath, j, warning) == SettingsFile::Read) {
        for (const auto& [lesson, p] : lessonsFrom(j)) {
            const auto [it, added] = L.saved.emplace(lesson, p);
            if (!added) mergeProgress(it->second, p);
        }
    } else {
        j = settingsJson(st, nullptr);
    }
    j["lessons"] = lessonsJson(L.saved);
    if (!writeSettingsFile(L.settingsPath, j, error)) return false;
    if (!warning.empty()) error = warning;
    return warning.empty();
}

void saveLessonProgressIfChanged(AppState& st) {
    LessonState& L = st.lessonPlayer;
    if (L.settingsPath.empty() || L.changes == L.changesSaved) return;
    L.changesSaved = L.changes;  // a failure is said once, not every frame
    std::string error;
    if (!saveLessonProgress(st, error)) {
        st.log(Message::Level::Warning, error.find("damaged settings") != std::string::npos
                                            ? error
                                            : "lesson progress not saved: " + error);
    }
}

}  // namespace dlab::ui
