// The browser's platform: Emscripten's GLFW (its window is the page's canvas) with a WebGL2
// context, ImGui's GLFW backend for input. The page resizes the canvas through resize().
#include "ui/platform/platform_web.h"

#include "ui/platform/glfw_window.h"

namespace dlab::ui {

namespace {

class WebPlatform final : public GlfwWindowPlatform {
public:
    using GlfwWindowPlatform::GlfwWindowPlatform;
    const char* name() const override { return "webgl2"; }
    bool newFrame() override {
        glfwPollEvents();
        ImGui_ImplGlfw_NewFrame();
        return true;  // a page is closed by the browser, never by the app
    }
    void present() override {}  // the browser shows the canvas when the frame callback returns
    bool resize(int width, int height) override {
        if (width <= 0 || height <= 0) return false;
        glfwSetWindowSize(m_window, width, height);
        return true;
    }
};

}  // namespace

std::unique_ptr<Platform> makeWebPlatform(int width, int height, std::string& error) {
    if (!initGlfw(error)) return nullptr;
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_ES_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
    GLFWwindow* window = glfwCreateWindow(width, height, "Delaunay Lab", nullptr, nullptr);
    if (!window) {
        error = glfwErrorOr("this browser gives no WebGL2 context");
        glfwTerminate();
        return nullptr;
    }
    glfwMakeContextCurrent(window);
    return std::make_unique<WebPlatform>(window);
}

}  // namespace dlab::ui
