// delaunay-lab in the browser (WebAssembly): the same GUI as the desktop on a WebGL2 canvas.
// The page (ui/platform/platform_web.html, platform_web.js) calls the dlab_web_* functions:
//   files    the file picker and drops go through openFile (points, sessions, lessons, traces);
//            every file the app writes (save, export, screenshot, GIF) lands in /downloads and
//            is handed to the browser as a download
//   storage  settings, lesson progress and the autosave live in /persist, an IndexedDB folder
//            synced after changes and when the page is hidden; an autosave left by a closed tab
//            is offered back
//   URL      ?lesson=05_flips (&stop=K, 1-based), ?points=scattered24 (a bundled point set),
//            ?step=N (operations), ?presentation=1
//   Table 1  dlab_web_table1_run times one method at one size on this WebGL2 context
//   tests    dlab_web_test_* report the run's state and the last operation's trace line
#include "core/engine/generators.h"
#include "core/teaching/trace.h"
#include "ui/files/files.h"
#include "ui/files/settings.h"
#include "ui/gl/gl_api.h"
#include "ui/gl/idbuffer_gl.h"
#include "ui/gui.h"
#include "ui/lesson_player.h"
#include "ui/panels/panels.h"
#include "ui/platform/platform_web.h"

#include <emscripten/emscripten.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

constexpr const char* kPersist = "/persist";
constexpr const char* kDownloads = "/downloads";

struct WebApp {
    dlab::ui::AppState state;
    std::unique_ptr<dlab::ui::Platform> platform;
    std::unique_ptr<dlab::ui::Gui> gui;
    std::string settingsPath;
    std::string persisted;  // what /persist held at the last sync
    double lastSync = 0;
    // Files in /downloads seen at the end of the last frame, with their sizes.
    std::map<std::string, std::uintmax_t> pending;
    long frames = 0;  // frames drawn (the test hook waits on it)
};

WebApp* g_app = nullptr;

double nowSeconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

// clang-format off
EM_JS(char*, pageQuery, (), {
    return stringToNewUTF8(window.location.search || "");
});
EM_JS(int, pageWidth, (), { return window.innerWidth | 0; });
EM_JS(int, pageHeight, (), { return window.innerHeight | 0; });
EM_JS(void, syncPersist, (), {
    FS.syncfs(false, function(err) {
        if (err) console.warn("IndexedDB: " + err);
        if (window.dlab) window.dlab.syncs = (window.dlab.syncs || 0) + 1;
    });
});
EM_JS(void, offerDownload, (const char* path), {
    const p = UTF8ToString(path);
    const name = p.substring(p.lastIndexOf("/") + 1);
    if (Module.onDownload) Module.onDownload(name, FS.readFile(p));
});
EM_JS(void, showFatal, (const char* text), {
    Module.fatal(UTF8ToString(text));
});
EM_JS(void, openFilePicker, (), {
    if (Module.openFilePicker) Module.openFilePicker();
});
// clang-format on

// "a=1&b=x" of the page's URL.
std::map<std::string, std::string> urlParameters() {
    char* raw = pageQuery();
    std::string q(raw);
    std::free(raw);
    std::map<std::string, std::string> out;
    if (!q.empty() && q[0] == '?') q.erase(0, 1);
    std::stringstream ss(q);
    for (std::string item; std::getline(ss, item, '&');) {
        const std::size_t eq = item.find('=');
        out[item.substr(0, eq)] = eq == std::string::npos ? "1" : item.substr(eq + 1);
    }
    return out;
}

// A bundled name is letters, digits, '_' and '-': never a path out of its folder.
bool plainName(const std::string& s) {
    if (s.empty() || s.size() > 100) return false;
    for (char c : s) {
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') return false;
    }
    return true;
}

// Opens a file in `folder` by its name, so that messages name the file as the user knows it.
bool openInFolder(dlab::ui::AppState& state, const std::string& folder, const std::string& name) {
    std::error_code ec;
    fs::current_path(folder, ec);
    const bool ok = dlab::ui::openFile(state, name);
    fs::current_path(kDownloads, ec);
    return ok;
}

void applyUrl(WebApp& app) {
    dlab::ui::AppState& st = app.state;
    const auto params = urlParameters();
    auto get = [&](const char* key) {
        const auto it = params.find(key);
        return it == params.end() ? std::string() : it->second;
    };
    if (get("presentation") == "1") st.presentation = true;
    if (const std::string p = get("points"); !p.empty()) {
        if (plainName(p)) {
            openInFolder(st, "/lessons/points", p + ".csv");
        } else {
            dlab::ui::fileError(st, "?points=" + p + ": not the name of a bundled point set");
        }
    }
    if (const std::string l = get("lesson"); !l.empty()) {
        if (plainName(l)) {
            openInFolder(st, "/lessons", l + ".toml");
        } else {
            dlab::ui::fileError(st, "?lesson=" + l + ": not the name of a bundled lesson");
        }
        const long stop = std::strtol(get("stop").c_str(), nullptr, 10);
        if (st.lessonPlayer.lesson && stop >= 1)
            dlab::ui::goToStop(st, static_cast<std::size_t>(stop - 1));
    }
    for (long n = std::strtol(get("step").c_str(), nullptr, 10); n > 0 && st.engine.forward();
         --n) {}
}

std::string readAll(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// Everything under /persist as one string: changed since the last sync?
std::string persistedText() {
    std::string all;
    std::error_code ec;
    for (const auto& e : fs::recursive_directory_iterator(kPersist, ec)) {
        if (e.is_regular_file(ec)) all += e.path().string() + '\n' + readAll(e.path()) + '\n';
    }
    return all;
}

void saveState(WebApp& app, bool force) {
    const double now = nowSeconds();
    if (!force && now - app.lastSync < 2.0) return;
    app.lastSync = now;
    dlab::ui::WindowOptions window;
    std::string error;
    if (!dlab::ui::saveSettings(app.settingsPath, app.state, window, error))
        app.state.log(dlab::ui::Message::Level::Warning, error);
    std::string now_text = persistedText();
    if (!force && now_text == app.persisted) return;
    app.persisted = std::move(now_text);
    syncPersist();
}

// Files the app wrote to /downloads: handed to the browser once complete (unchanged since the
// last frame, and no GIF still being rendered), then removed.
void serviceDownloads(WebApp& app) {
    std::error_code ec;
    std::map<std::string, std::uintmax_t> seen;
    for (const auto& e : fs::directory_iterator(kDownloads, ec)) {
        if (e.is_regular_file(ec)) seen[e.path().string()] = e.file_size(ec);
    }
    const bool busy = app.state.files.gif.has_value();
    for (const auto& [path, size] : seen) {
        const auto it = app.pending.find(path);
        if (busy || it == app.pending.end() || it->second != size) continue;
        offerDownload(path.c_str());
        fs::remove(path, ec);
        seen.erase(path);
        break;  // one per frame; the map changed
    }
    app.pending = std::move(seen);
}

void frame() {
    WebApp& app = *g_app;
    dlab::ui::AppState& st = app.state;
    for (const std::string& dropped : app.platform->takeDroppedFiles()) {
        const fs::path p(dropped);
        openInFolder(st, p.parent_path().string(), p.filename().string());
    }
    app.gui->frame();
    ++app.frames;
    dlab::ui::serviceCaptures(*app.gui);
    serviceDownloads(app);
    saveState(app, false);
}

// Autosaves left by earlier tabs (a closed tab never exits cleanly) become one offer: the newest
// is renamed to pid 0, which is never a running instance.
void adoptEarlierAutosaves(const std::string& folder) {
    std::error_code ec;
    fs::path newest;
    fs::file_time_type newestTime{};
    for (const auto& e : fs::directory_iterator(folder, ec)) {
        const std::string name = e.path().filename().string();
        if (name.rfind("autosave-", 0) != 0) continue;
        if (newest.empty() || e.last_write_time(ec) > newestTime) {
            if (!newest.empty()) fs::remove(newest, ec);
            newest = e.path();
            newestTime = e.last_write_time(ec);
        } else {
            fs::remove(e.path(), ec);
        }
    }
    if (!newest.empty()) fs::rename(newest, fs::path(folder) / "autosave-0.json", ec);
}

}  // namespace

extern "C" {

// Called by main's IndexedDB load: /persist holds what earlier visits saved.
EMSCRIPTEN_KEEPALIVE void dlab_web_start() {
    auto* app = new WebApp;  // lives as long as the page
    g_app = app;
    std::error_code ec;
    fs::create_directories(kDownloads, ec);
    fs::current_path(kDownloads, ec);
    dlab::ui::AppState& st = app->state;
    app->settingsPath = dlab::ui::defaultSettingsPath();
    dlab::ui::WindowOptions window;
    std::string warning, error;
    dlab::ui::loadSettings(app->settingsPath, st, window, warning);
    if (!warning.empty()) st.log(dlab::ui::Message::Level::Warning, warning);
    st.lessonPlayer.settingsPath = app->settingsPath;  // progress saved as it is made
    app->platform = dlab::ui::makeWebPlatform(pageWidth(), pageHeight(), error);
    if (!app->platform) {
        showFatal(error.c_str());
        return;
    }
    app->gui = std::make_unique<dlab::ui::Gui>(*app->platform, st);
    // File > Open is the browser's file chooser; the page then calls dlab_web_open.
    st.files.platformOpenDialog = [] { openFilePicker(); };
    st.setOptions(dlab::ui::demoOptions());
    st.loadPoints(dlab::demoPoints(), "built-in demo");
    applyUrl(*app);
    const std::string autosave = dlab::ui::defaultAutosaveFolder();
    fs::create_directories(autosave, ec);
    adoptEarlierAutosaves(autosave);
    dlab::ui::offerRecovery(st, autosave);
    dlab::ui::enableAutosave(st, autosave);
    app->persisted = persistedText();
    app->lastSync = nowSeconds();
    EM_ASM({
        if (Module.onStarted) Module.onStarted();
    });
    emscripten_set_main_loop(frame, 0, false);
}

// A file the page wrote to FOLDER/NAME (the file picker): opened like a dropped file.
EMSCRIPTEN_KEEPALIVE int dlab_web_open(const char* folder, const char* name) {
    if (!g_app) return 0;
    return openInFolder(g_app->state, folder, name) ? 1 : 0;
}

EMSCRIPTEN_KEEPALIVE void dlab_web_resize(int width, int height) {
    if (g_app && g_app->platform) g_app->platform->resize(width, height);
}

// The page is hidden or closed: settings, progress and the autosave go to IndexedDB now.
EMSCRIPTEN_KEEPALIVE void dlab_web_save_state() {
    if (g_app) saveState(*g_app, true);
}

// Table 1 on this browser's GPU: one run of `method` (0 naive, 1 idbuffer-gl, 2
// idbuffer-gl-batched, 3 idbuffer-cpu, 4 walk, 5 best) on n uniform random points in the paper's
// 1600 x 1600 box; milliseconds, or -1 when it cannot run (no WebGL2 context, a bad method).
EMSCRIPTEN_KEEPALIVE double dlab_web_table1_run(int n, int method, int seed);

// The test hooks: the run's state as JSON, and the trace line (core/teaching/trace.h) of the
// operation just performed ("" at the start).
EMSCRIPTEN_KEEPALIVE const char* dlab_web_test_info() {
    static std::string text;
    if (!g_app) return "{}";
    const dlab::ui::AppState& st = g_app->state;
    nlohmann::json j;
    j["position"] = st.engine.position();
    j["recorded"] = st.engine.recorded();
    j["points"] = st.engine.points().size();
    j["source"] = st.source;
    j["notice"] = st.files.notice;
    j["presentation"] = st.presentation;
    j["recovery"] = st.files.recoveryPath;
    j["autosaved"] = st.files.autosaved.size();  // the points the last autosave holds
    const auto& lp = st.lessonPlayer;
    j["lesson"] = lp.lesson ? lp.lesson->title : "";
    j["stop"] = lp.lesson ? static_cast<long>(lp.progress.stop) + 1 : 0;
    j["frame"] = g_app->frames;
    int width = 0, height = 0;
    if (g_app->platform) g_app->platform->framebufferSize(width, height);
    j["width"] = width;
    j["height"] = height;
    j["scale"] = st.view.scale;
    j["frameMs"] = g_app->gui ? g_app->gui->lastFrameMs() : 0.0;
    const auto gl = std::dynamic_pointer_cast<dlab::ui::GlContext>(st.engine.glContext());
    j["gl"] = gl ? gl->version() : "";
    for (const auto& [name, r] : st.itemRects) j["rects"][name] = {r[0], r[1], r[2], r[3]};
    text = j.dump();
    return text.c_str();
}

EMSCRIPTEN_KEEPALIVE const char* dlab_web_test_last_op() {
    static std::string text;
    text.clear();
    if (!g_app) return "";
    const dlab::ui::Engine& engine = g_app->state.engine;
    if (engine.journal() && engine.position() > 0) {
        text = dlab::toJsonLine(
            dlab::traceRecord(*engine.journal(), engine.position() - 1, engine.mesh()));
    }
    return text.c_str();
}

}  // extern "C"

double dlab_web_table1_run(int n, int method, int seed) {
    using dlab::LocatorKind;
    using dlab::OrderKind;
    struct Method {
        LocatorKind locator;
        OrderKind order;
    };
    static constexpr Method kMethods[] = {
        {LocatorKind::Naive, OrderKind::Input},
        {LocatorKind::IdBufferGl, OrderKind::Input},
        {LocatorKind::IdBufferGlBatched, OrderKind::Input},
        {LocatorKind::IdBufferCpu, OrderKind::Input},
        {LocatorKind::Walk, OrderKind::Input},
        {LocatorKind::Walk, OrderKind::Brio},
    };
    if (!g_app || method < 0 || method >= 6 || n < 3 || n > (1 << 22)) return -1;
    const auto gl = std::dynamic_pointer_cast<dlab::ui::GlContext>(g_app->state.engine.glContext());
    const Method m = kMethods[method];
    const bool needsGl =
        m.locator == LocatorKind::IdBufferGl || m.locator == LocatorKind::IdBufferGlBatched;
    if (needsGl && !gl) return -1;
    std::vector<dlab::Vec2> points = dlab::generatePoints(
        dlab::Generator::Uniform, static_cast<std::size_t>(n), static_cast<std::uint64_t>(seed));
    dlab::InsertOptions o;
    o.locator = m.locator;
    o.order = m.order;
    o.seed = static_cast<std::uint64_t>(seed);
    o.locatorOptions.idBufferWidth = o.locatorOptions.idBufferHeight = 1600;
    try {
        const auto t0 = std::chrono::steady_clock::now();
        std::unique_ptr<dlab::Locator> locator;
        dlab::ui::IdBufferGl* glLocator = nullptr;
        if (needsGl) {
            dlab::ui::IdBufferGlOptions g;
            g.width = g.height = 1600;
            g.batch = o.locatorOptions.idBufferBatch;
            g.readback = m.locator == LocatorKind::IdBufferGl ? dlab::ui::GlReadback::OnePixel
                                                              : dlab::ui::GlReadback::Batched;
            auto made = std::make_unique<dlab::ui::IdBufferGl>(gl, g);
            glLocator = made.get();
            locator = std::move(made);
        }
        dlab::Inserter ins(std::move(points), o, std::move(locator));
        if (glLocator) glLocator->followOrder(ins);
        ins.run();
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
            .count();
    } catch (const std::exception& e) {
        g_app->state.log(dlab::ui::Message::Level::Error, std::string("Table 1: ") + e.what());
        return -1;
    }
}

int main() {
    // Settings and the autosave live under /persist (IndexedDB), found by the desktop's rules.
    setenv("XDG_CONFIG_HOME", "/persist/config", 1);
    setenv("XDG_CACHE_HOME", "/persist/cache", 1);
    // clang-format off
    EM_ASM({
        FS.mkdir("/persist");
        FS.mount(IDBFS, {}, "/persist");
        FS.syncfs(true, function(err) {
            if (err) console.warn("IndexedDB: " + err);
            Module.ccall("dlab_web_start", null, [], []);
        });
    });
    // clang-format on
    return 0;
}
