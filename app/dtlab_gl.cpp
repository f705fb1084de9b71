// dtlab-gl's GL pieces: the process' headless OSMesa context and the GL ID-buffer locators on it.
#include "app/dtlab_common.h"

#include "ui/platform/platform.h"

namespace dlab::cli {

void needGl() {}

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

namespace {

// One OSMesa context for the whole process. The buffer it renders into is tiny: the GL
// locators draw into their own framebuffer objects.
struct HeadlessContext {
    std::unique_ptr<ui::Platform> platform;
    std::shared_ptr<ui::GlContext> gl;
};
HeadlessContext g_context;

}  // namespace

std::shared_ptr<ui::GlContext> headlessGl() {
    if (!g_context.gl) {
        std::string error;
        g_context.platform = ui::makeOsmesaPlatform(16, 16, error);
        if (g_context.platform) g_context.gl = ui::GlContext::fromCurrent(error);
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

}  // namespace dlab::cli
