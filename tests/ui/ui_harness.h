// A headless instance of the whole GUI driven with synthetic input, as a user would:
// ImGui 1.86 has no input-event API, so the harness sets io.MousePos, io.MouseDown[],
// io.MouseWheel and io.KeysDown[] (GLFW key codes, as in the real window) between frames, and
// queues each key press for the shortcuts as the window's key callback does (ui/platform/keys.h).
#pragma once

#include "ui/gui.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

namespace dlab::ui {
class GlContext;
}

namespace dlab::test {

// A fresh folder per test, removed at the end.
struct TempDir {
    std::filesystem::path path;
    explicit TempDir(const std::string& name) {
        path = std::filesystem::temp_directory_path() /
               ("dlab_files_" + name + "_" + std::to_string(::getpid()));
        std::filesystem::remove_all(path);
        std::filesystem::create_directories(path);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    std::string operator/(const std::string& f) const { return (path / f).string(); }
};

// Same coordinates, bit for bit.
inline bool sameBits(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec2)) == 0);
}

// The platform the harness runs on: OSMesa in dlab_ui_tests (harness_osmesa.cpp), EGL on Mesa's
// llvmpipe in dlab_ui_tests_egl (harness_egl.cpp), the null platform (no GL, no pixels) in
// dlab_ui_logic_tests (harness_null.cpp).
std::unique_ptr<ui::Platform> makeTestPlatform(int width, int height, std::string& error);

// The GL tests' headless GL as dtlab's --gl flag ("--gl osmesa", "--gl egl"): the tests that run
// dtlab's GL commands run them on the same GL as the rest of their executable.
const char* dtlabGlFlag();

// A headless GL context (that platform's, 16 x 16), current, for tests of the GL layer without
// the GUI (dlab_ui_tests and dlab_ui_tests_egl only).
struct HeadlessGl {
    std::unique_ptr<ui::Platform> platform;
    std::shared_ptr<ui::GlContext> gl;
    // False and a reason when no context can be made.
    bool open(std::string& error);
};

class UiHarness {
public:
    explicit UiHarness(int width = 1400, int height = 900);
    ~UiHarness();

    ui::AppState& state() { return m_state; }
    ui::Gui& gui() { return *m_gui; }
    void frames(int n = 1);
    // Input, each followed by the frames ImGui needs to see it.
    void moveTo(float x, float y);
    void click(float x, float y, int button = 0);
    void drag(float x0, float y0, float x1, float y1, int button = 0);
    void scroll(float x, float y, float wheel);
    void press(int key, bool shift = false, bool ctrl = false);
    // Clicks the centre of a widget the UI recorded under `name` (state().itemRects).
    void clickItem(const std::string& name);
    std::array<float, 4> rect(const std::string& name);
    // The pixel (r, g, b) at screen position (x, y) of the last frame.
    std::array<int, 3> pixel(int x, int y);
    // How many pixels of exactly this colour lie inside the rectangle.
    int countColour(const std::array<float, 4>& r, std::array<int, 3> rgb);

private:
    ui::AppState m_state;
    std::unique_ptr<ui::Platform> m_platform;
    std::unique_ptr<ui::Gui> m_gui;
};

}  // namespace dlab::test
