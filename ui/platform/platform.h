// What the UI needs from a window system: a current GL context that runs our shaders (OpenGL 3.3
// core; ui/gl/gl_api.h), frames, and input for ImGui.
//
// Four implementations, one file each, each in its own library because each brings its own GL
// provider or none: platform_glfw.cpp (a real window, libGL), platform_egl.cpp (headless, EGL
// and libOpenGL: a GPU, or Mesa's llvmpipe), platform_osmesa.cpp (headless, OSMesa: the only
// file that includes it, and optional, since Mesa 25.1 dropped it) and platform_null.cpp
// (headless, no GL at all: the null renderer). libOSMesa and libOpenGL both export the gl*
// functions, so one executable links one of them.
#pragma once

#include "ui/render/renderer.h"

#include <memory>
#include <string>
#include <vector>

namespace dlab::ui {

class Platform {
public:
    virtual ~Platform() = default;
    virtual const char* name() const = 0;
    virtual bool headless() const = 0;
    virtual void framebufferSize(int& width, int& height) const = 0;
    // Called after ImGui::CreateContext: install the ImGui platform backend (keyboard, mouse).
    virtual void initImGui() = 0;
    virtual void shutdownImGui() = 0;
    // Polls events and fills ImGui's io for the next frame. False when the window was closed.
    virtual bool newFrame() = 0;
    // Shows the rendered frame (swap buffers; headless: nothing).
    virtual void present() = 0;
    // Nothing animates: sleep until an input event arrives or `seconds` pass (headless: no-op).
    virtual void waitForEvents(double /*seconds*/) {}
    // Files dropped on the window since the last call.
    virtual std::vector<std::string> takeDroppedFiles() { return {}; }
    virtual void setTitle(const std::string& /*title*/) {}
    // Headless only: a new framebuffer size.
    virtual bool resize(int /*width*/, int /*height*/) { return false; }
    // What draws on this platform: the GL renderer on the platform's context, or the null one.
    virtual std::unique_ptr<Renderer> makeRenderer() = 0;
};

// Headless, no GL: ImGui on synthetic input, the null renderer (counts into `counts` if given).
std::unique_ptr<Platform> makeNullPlatform(int width, int height,
                                           NullRendererCounts* counts = nullptr);

// Headless, OSMesa: a core-profile context (3.3 asked for; Mesa gives 4.5). Returns nullptr and
// sets `error` when no context can be made.
std::unique_ptr<Platform> makeOsmesaPlatform(int width, int height, std::string& error);

// Headless, EGL: an OpenGL 3.3 core context on an RGBA8 pbuffer of width x height, current.
// Gpu: a GPU's EGL device only; Software: Mesa's software device or surfaceless platform
// (llvmpipe) only; Any: the GPUs first. Returns nullptr and sets `error` (every display tried and
// why it failed) when no context can be made. The EGL displays stay initialized until exit.
enum class EglDevice { Any, Gpu, Software };
std::unique_ptr<Platform> makeEglPlatform(int width, int height, EglDevice device,
                                          std::string& error);
// Whether EGL lists a device that is not Mesa's software one (a GPU's driver).
bool eglHasGpu();
// The display an EGL platform runs on ("GPU device 0", "Mesa surfaceless"); "" for others.
std::string eglDisplayName(const Platform& platform);

struct WindowOptions {
    int width = 1600, height = 1000;
    int x = -1, y = -1;  // -1: let the window manager place it
    bool maximized = false;
    std::string title = "Delaunay Lab";
};
// A GLFW window with an OpenGL 3.3 core, forward-compatible context (the only kind macOS gives).
// Returns nullptr and sets `error` when there is no display or no such context.
std::unique_ptr<Platform> makeGlfwPlatform(const WindowOptions& options, std::string& error);

// Where the GLFW window is now (to remember it between runs); false on other platforms.
bool windowPlacement(const Platform& platform, WindowOptions& out);

}  // namespace dlab::ui
