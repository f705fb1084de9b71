// The browser's platform: Emscripten's GLFW (its window is the page's canvas) with a WebGL2
// context, ImGui's GLFW backend for input. The page resizes the canvas through resize().
#include "ui/platform/platform_web.h"

#include "ui/gl/gl_renderer.h"

#define GLFW_INCLUDE_NONE  // GL comes from ui/gl/gl_api.h, never from here
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>

#include <utility>

namespace dlab::ui {

namespace {

std::string g_glfwError;

class WebPlatform final : public Platform {
public:
    explicit WebPlatform(GLFWwindow* window) : m_window(window) {
        glfwSetWindowUserPointer(window, this);
        glfwSetDropCallback(window, [](GLFWwindow* w, int count, const char** paths) {
            auto* self = static_cast<WebPlatform*>(glfwGetWindowUserPointer(w));
            for (int i = 0; i < count; ++i) self->m_dropped.emplace_back(paths[i]);
        });
    }
    ~WebPlatform() override {
        glfwDestroyWindow(m_window);
        glfwTerminate();
    }
    const char* name() const override { return "webgl2"; }
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
        return true;  // a page is closed by the browser, never by the app
    }
    void present() override {}  // the browser shows the canvas when the frame callback returns
    std::vector<std::string> takeDroppedFiles() override { return std::exchange(m_dropped, {}); }
    bool resize(int width, int height) override {
        if (width <= 0 || height <= 0) return false;
        glfwSetWindowSize(m_window, width, height);
        return true;
    }

private:
    GLFWwindow* m_window;
    std::vector<std::string> m_dropped;
};

}  // namespace

std::unique_ptr<Platform> makeWebPlatform(int width, int height, std::string& error) {
    glfwSetErrorCallback([](int code, const char* text) {
        g_glfwError = "GLFW error " + std::to_string(code) + ": " + text;
    });
    if (!glfwInit()) {
        error = g_glfwError.empty() ? "GLFW could not initialise" : g_glfwError;
        return nullptr;
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_ES_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
    GLFWwindow* window = glfwCreateWindow(width, height, "Delaunay Lab", nullptr, nullptr);
    if (!window) {
        error = g_glfwError.empty() ? "this browser gives no WebGL2 context" : g_glfwError;
        glfwTerminate();
        return nullptr;
    }
    glfwMakeContextCurrent(window);
    return std::make_unique<WebPlatform>(window);
}

}  // namespace dlab::ui
