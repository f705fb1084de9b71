// The windowed platform: GLFW with an OpenGL 3.3 core context, ImGui's GLFW backend for input.
#include "ui/files/settings.h"
#include "ui/gl/gl_renderer.h"
#include "ui/platform/platform.h"

#define GLFW_INCLUDE_NONE  // GL comes from ui/gl/gl_api.h, never from here
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <imgui.h>

#include <cstdio>
#include <cstdlib>
#include <utility>

namespace dlab::ui {

namespace {

std::string g_glfwError;

class GlfwPlatform final : public Platform {
public:
    explicit GlfwPlatform(GLFWwindow* window) : m_window(window) {
        glfwSetWindowUserPointer(window, this);
        glfwSetDropCallback(window, [](GLFWwindow* w, int count, const char** paths) {
            auto* self = static_cast<GlfwPlatform*>(glfwGetWindowUserPointer(w));
            for (int i = 0; i < count; ++i) self->m_dropped.emplace_back(paths[i]);
        });
    }
    ~GlfwPlatform() override {
        glfwDestroyWindow(m_window);
        glfwTerminate();
    }
    const char* name() const override { return "glfw"; }
    bool headless() const override { return false; }
    std::unique_ptr<Renderer> makeRenderer() override { return makeGlRenderer(); }
    void framebufferSize(int& width, int& height) const override {
        glfwGetFramebufferSize(m_window, &width, &height);
    }
    void initImGui() override { ImGui_ImplGlfw_InitForOpenGL(m_window, true); }
    void shutdownImGui() override { ImGui_ImplGlfw_Shutdown(); }
    bool newFrame() override {
        glfwPollEvents();
        ImGui_ImplGlfw_NewFrame();
        return !glfwWindowShouldClose(m_window);
    }
    void present() override { glfwSwapBuffers(m_window); }
    void waitForEvents(double seconds) override { glfwWaitEventsTimeout(seconds); }
    std::vector<std::string> takeDroppedFiles() override { return std::exchange(m_dropped, {}); }
    void setTitle(const std::string& title) override {
        glfwSetWindowTitle(m_window, title.c_str());
    }
    GLFWwindow* window() const { return m_window; }

private:
    GLFWwindow* m_window;
    std::vector<std::string> m_dropped;
};

}  // namespace

std::unique_ptr<Platform> makeGlfwPlatform(const WindowOptions& options, std::string& error) {
    glfwSetErrorCallback([](int code, const char* text) {
        g_glfwError = "GLFW error " + std::to_string(code) + ": " + text;
    });
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((!display || !*display) && (!wayland || !*wayland)) {
        error = "no display (DISPLAY and WAYLAND_DISPLAY are unset)";
        return nullptr;
    }
    if (!glfwInit()) {
        error = g_glfwError.empty() ? "GLFW could not initialise" : g_glfwError;
        return nullptr;
    }
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
        error = g_glfwError.empty() ? "GLFW could not open a window" : g_glfwError;
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
