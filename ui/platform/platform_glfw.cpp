// The windowed platform: GLFW with an OpenGL 3.3 core context, ImGui's GLFW backend for input.
#include "ui/files/settings.h"
#include "ui/platform/glfw_window.h"

#include <cstdio>
#include <cstdlib>
#include <utility>

namespace dlab::ui {

namespace {

class GlfwPlatform final : public GlfwWindowPlatform {
public:
    using GlfwWindowPlatform::GlfwWindowPlatform;
    const char* name() const override { return "glfw"; }
    bool newFrame() override {
        glfwPollEvents();
        ImGui_ImplGlfw_NewFrame();
        return !glfwWindowShouldClose(m_window);
    }
    void present() override { glfwSwapBuffers(m_window); }
    void waitForEvents(double seconds) override { glfwWaitEventsTimeout(seconds); }
    void setTitle(const std::string& title) override {
        glfwSetWindowTitle(m_window, title.c_str());
    }
};

}  // namespace

std::unique_ptr<Platform> makeGlfwPlatform(const WindowOptions& options, std::string& error) {
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((!display || !*display) && (!wayland || !*wayland)) {
        error = "no display (DISPLAY and WAYLAND_DISPLAY are unset)";
        return nullptr;
    }
    if (!initGlfw(error)) return nullptr;
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_MAXIMIZED, options.maximized ? GLFW_TRUE : GLFW_FALSE);
    // A size remembered from a larger screen is fitted into this one's work area.
    WindowOptions placed = options;
    if (GLFWmonitor* monitor = glfwGetPrimaryMonitor()) {
        int x = 0, y = 0, w = 0, h = 0;
        glfwGetMonitorWorkarea(monitor, &x, &y, &w, &h);
        clampWindowToWorkArea(placed, x, y, w, h);
    }
    GLFWwindow* window =
        glfwCreateWindow(placed.width, placed.height, placed.title.c_str(), nullptr, nullptr);
    if (!window) {
        error = glfwErrorOr("GLFW could not open a window");
        glfwTerminate();
        return nullptr;
    }
    if (placed.x >= 0 && placed.y >= 0) glfwSetWindowPos(window, placed.x, placed.y);
    glfwMakeContextCurrent(window);
    glfwSwapInterval(1);
    return std::make_unique<GlfwPlatform>(window);
}

bool windowPlacement(const Platform& platform, WindowOptions& out) {
    const auto* p = dynamic_cast<const GlfwPlatform*>(&platform);
    if (!p) return false;
    glfwGetWindowPos(p->window(), &out.x, &out.y);
    glfwGetWindowSize(p->window(), &out.width, &out.height);
    out.maximized = glfwGetWindowAttrib(p->window(), GLFW_MAXIMIZED) != 0;
    return true;
}

}  // namespace dlab::ui
