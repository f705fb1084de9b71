// Settings as JSON (nlohmann): every field optional, unknown fields ignored, ranges clamped.
#include "ui/files/settings.h"

#include "core/engine/io_read.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace dlab::ui {

namespace {

template <class T>
void read(const nlohmann::json& j, const char* key, T& out) {
    const auto it = j.find(key);
    if (it == j.end()) return;
    try {
        out = it->get<T>();
    } catch (const nlohmann::json::exception&) {
        // A wrong type keeps the default.
    }
}

}  // namespace

std::string defaultSettingsPath() {
    if (const char* x = std::getenv("XDG_CONFIG_HOME"); x && *x)
        return std::string(x) + "/delaunay-lab/settings.json";
    if (const char* h = std::getenv("HOME"); h && *h)
        return std::string(h) + "/.config/delaunay-lab/settings.json";
    return {};
}

void loadSettings(const std::string& path, AppState& st, WindowOptions& window,
                  std::string& warning) {
    if (path.empty()) return;
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return;  // no settings yet: the defaults
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(readRegularFile(path, kMaxSettingsFileBytes));
    } catch (const InputError& e) {
        warning = std::string(e.what()) + " (settings ignored)";
        return;
    } catch (const nlohmann::json::exception& e) {
        warning = path + ": damaged settings file ignored (" + e.what() + ")";
        return;
    }
    if (!j.is_object()) {
        warning = path + ": damaged settings file ignored (not a JSON object)";
        return;
    }
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
    if (const auto o = j.find("overlays"); o != j.end() && o->is_object()) {
        Overlays& ov = st.overlays;
        read(*o, "fill", ov.fill);
        read(*o, "vertex_ids", ov.vertexIds);
        read(*o, "corner_ids", ov.cornerIds);
        read(*o, "triangle_ids", ov.triangleIds);
        read(*o, "walk", ov.walk);
        read(*o, "flip_queue", ov.flipQueue);
        read(*o, "flipped", ov.flipped);
        read(*o, "circumcircles", ov.circumcircles);
        read(*o, "voronoi", ov.voronoi);
        read(*o, "pending_points", ov.pendingPoints);
        read(*o, "virtual_triangles", ov.virtualTriangles);
    }
    if (const auto ls = j.find("lessons"); ls != j.end() && ls->is_object()) {
        for (const auto& [path, v] : ls->items()) {
            if (!v.is_object()) continue;
            LessonProgress p;
            p.lesson = path;
            read(v, "title", p.title);
            read(v, "stop", p.stop);
            read(v, "furthest", p.furthest);
            read(v, "answers", p.answers);
            st.lessonPlayer.saved[path] = std::move(p);
        }
    }
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
    const Overlays& ov = userOverlays(st);  // not a lesson's
    nlohmann::json j = {
        {"window",
         {{"x", window.x},
          {"y", window.y},
          {"width", window.width},
          {"height", window.height},
          {"maximized", window.maximized}}},
        {"layout",
         {{"right_width", st.layout.rightWidth},
          {"bottom_height", st.layout.bottomHeight},
          {"inspector_height", st.layout.inspectorHeight}}},
        {"overlays",
         {{"fill", ov.fill},
          {"vertex_ids", ov.vertexIds},
          {"corner_ids", ov.cornerIds},
          {"triangle_ids", ov.triangleIds},
          {"walk", ov.walk},
          {"flip_queue", ov.flipQueue},
          {"flipped", ov.flipped},
          {"circumcircles", ov.circumcircles},
          {"voronoi", ov.voronoi},
          {"pending_points", ov.pendingPoints},
          {"virtual_triangles", ov.virtualTriangles}}},
        {"presentation", st.presentation},
        {"ops_per_second", st.run.opsPerSecond},
        {"snap_to_grid", st.snapToGrid},
        {"grid_step", st.gridStep},
    };
    nlohmann::json lessons = nlohmann::json::object();
    for (const auto& [file, p] : st.lessonPlayer.saved) {
        lessons[file] = {
            {"title", p.title}, {"stop", p.stop}, {"furthest", p.furthest}, {"answers", p.answers}};
    }
    j["lessons"] = std::move(lessons);
    std::error_code ec;
    const std::filesystem::path p(path);
    std::filesystem::create_directories(p.parent_path(), ec);
    const std::string tmp = path + ".tmp";
    {
        std::ofstream out(tmp, std::ios::trunc);
        out << j.dump(2) << "\n";
        out.flush();
        if (!out) {
            error = "cannot write " + tmp;
            return false;
        }
    }
    std::filesystem::rename(tmp, p, ec);
    if (ec) {
        error = "cannot replace " + path + ": " + ec.message();
        return false;
    }
    return true;
}

}  // namespace dlab::ui
