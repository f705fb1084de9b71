// The GL executables' GL pieces (dtlab-gl on EGL, dtlab-gl-osmesa on OSMesa): the process'
// headless context, what it runs on, and the GL ID-buffer locators on it. Which GL an executable
// has, and when --gl sends the command to the other one, is in dtlab_gl_egl.cpp and
// dtlab_gl_osmesa.cpp (one of them in each executable).
#include "app/dtlab_gl.h"

#include "ui/gl/gl_api.h"

#include <unistd.h>

#include <cstdlib>
#include <iostream>

namespace dlab::cli {

namespace {

bool g_needGl = false;
GlInfo g_info;

// One headless context for the whole process. The buffer it renders into is tiny: the GL
// locators draw into their own framebuffer objects.
struct HeadlessContext {
    std::unique_ptr<ui::Platform> platform;
    std::shared_ptr<ui::GlContext> gl;
};
HeadlessContext g_context;

}  // namespace

void needGl() { g_needGl = true; }

void chooseGl() {
    if (!g_needGl) return;
    try {
        settleGl(glFlag());
    } catch (const Exit& e) {  // nothing was done yet: leave now
        std::exit(e.code);
    }
}

std::unique_ptr<ui::Platform> headlessPlatform(int width, int height) {
    std::string error;
    std::unique_ptr<ui::Platform> platform = makeHeadlessPlatform(width, height, error);
    if (!platform) fail(error);
    if (g_info.api.empty()) {  // the first context: say once which GL it is
        const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
        const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
        g_info = {headlessApi(*platform), renderer ? renderer : "?", version ? version : "?"};
        // On a terminal only: piped, stderr holds the one line of an error and nothing else
        // (Table 1 names the renderer in its header, CSV and figure).
        if (isatty(STDERR_FILENO)) {
            std::cerr << "dtlab: GL: " << g_info.renderer << ", OpenGL " << g_info.version
                      << ", on " << g_info.api << " (--gl " << glFlag() << ")\n";
        }
    }
    return platform;
}

const GlInfo& glInfo() { return g_info; }

std::shared_ptr<ui::GlContext> headlessGl() {
    if (!g_context.gl) {
        g_context.platform = headlessPlatform(16, 16);
        std::string error;
        g_context.gl = ui::GlContext::fromCurrent(error);
        if (!g_context.gl) fail("--locate idbuffer-gl: " + error);
    }
    return g_context.gl;
}

void releaseGl() {
    // Mesa registers its own exit handlers (its thread queues) when the context is made, after
    // any static of ours: destroyed at exit, the context would outlive them.
    if (g_context.gl) g_context.gl->lose();
    g_context.gl.reset();
    g_context.platform.reset();
}

ui::IdBufferGlOptions EngineFlags::glOptions() const {
    const InsertOptions o = options();
    ui::IdBufferGlOptions g = ui::IdBufferGlOptions::from(o.locator, o.locatorOptions);
    if (readback == "pipelined") g.readback = ui::GlReadback::Pipelined;
    return g;
}

std::unique_ptr<Inserter> EngineFlags::makeGlInserter(std::vector<Vec2> points) const {
    auto locator = std::make_unique<ui::IdBufferGl>(headlessGl(), glOptions());
    ui::IdBufferGl* gl = locator.get();
    auto ins = std::make_unique<Inserter>(std::move(points), options(), std::move(locator));
    gl->followOrder(*ins);  // the batched readback reads ahead along the insertion order
    return ins;
}

}  // namespace dlab::cli
