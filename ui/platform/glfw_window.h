// What the desktop window and the browser's canvas share: a GLFW window with a GL context, drawn
// by the GL renderer, with ImGui's GLFW backend for input and GLFW's file drops. Header-only,
// included by platform_glfw.cpp and platform_web.cpp (each its own library).
#pragma once

#include "ui/gl/gl_renderer.h"
#include "ui/platform/keys.h"
#include "ui/platform/platform.h"

#define GLFW_INCLUDE_NONE  // GL comes from ui/gl/gl_api.h, never from here
#include <GLFW/glfw3.h>
#if __has_include(<backends/imgui_impl_glfw.h>)
#include <backends/imgui_impl_glfw.h>  // Debian's libimgui-dev
#else
#include <imgui_impl_glfw.h>  // the web build's ImGui sources
#endif

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace dlab::ui {

// The last error GLFW reported, or "" (set by the callback initGlfw installs).
inline std::string& glfwErrorText() {
    static std::string text;
    return text;
}

// glfwInit with errors collected for messages; false with `error` set when it fails.
inline bool initGlfw(std::string& error) {
    glfwSetErrorCallback([](int code, const char* text) {
        glfwErrorText() = "GLFW error " + std::to_string(code) + ": " + text;
    });
    if (glfwInit()) return true;
    error = glfwErrorText().empty() ? "GLFW could not initialise" : glfwErrorText();
    return false;
}

// The error GLFW reported, or `fallback` when it reported none.
inline std::string glfwErrorOr(const char* fallback) {
    return glfwErrorText().empty() ? fallback : glfwErrorText();
}

class GlfwWindowPlatform : public Platform {
public:
    explicit GlfwWindowPlatform(GLFWwindow* window) : m_window(window) {
        glfwSetWindowUserPointer(window, this);
        glfwSetDropCallback(window, [](GLFWwindow* w, int count, const char** paths) {
            auto* self = static_cast<GlfwWindowPlatform*>(glfwGetWindowUserPointer(w));
            for (int i = 0; i < count; ++i) self->m_dropped.emplace_back(paths[i]);
        });
    }
    ~GlfwWindowPlatform() override {
        glfwDestroyWindow(m_window);
        glfwTerminate();
    }
    bool headless() const override { return false; }
    std::unique_ptr<Renderer> makeRenderer() override { return makeGlRenderer(); }
    void framebufferSize(int& width, int& height) const override {
        glfwGetFramebufferSize(m_window, &width, &height);
    }
    // ImGui's backend first (it chains nothing of ours), then our key callback in front of it:
    // ImGui gets every event as before, and each press goes into the shortcut queue too.
    void initImGui() override {
        ImGui_ImplGlfw_InitForOpenGL(m_window, true);
        imguiKeyCallback() = glfwSetKeyCallback(m_window, [](GLFWwindow* w, int key, int scancode,
                                                             int action, int mods) {
            if (GLFWkeyfun next = imguiKeyCallback()) next(w, key, scancode, action, mods);
            if (action == GLFW_PRESS || action == GLFW_REPEAT)
                queueKeyPress(key, (mods & GLFW_MOD_SHIFT) != 0, (mods & GLFW_MOD_CONTROL) != 0);
        });
    }
    void shutdownImGui() override { ImGui_ImplGlfw_Shutdown(); }
    std::vector<std::string> takeDroppedFiles() override { return std::exchange(m_dropped, {}); }
    GLFWwindow* window() const { return m_window; }

protected:
    GLFWwindow* m_window;
    static GLFWkeyfun& imguiKeyCallback() {
        static GLFWkeyfun callback = nullptr;
        return callback;
    }

private:
    std::vector<std::string> m_dropped;
};

}  // namespace dlab::ui
