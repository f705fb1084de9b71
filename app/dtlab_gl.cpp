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
    ~HeadlessContext() {
        if (gl) gl->lose();
    }
};

}  // namespace

std::shared_ptr<ui::GlContext> headlessGl() {
    static HeadlessContext context;
    if (!context.gl) {
        std::string error;
        context.platform = ui::makeOsmesaPlatform(16, 16, error);
        if (context.platform) context.gl = ui::GlContext::fromCurrent(error);
        if (!context.gl) fail("--locate idbuffer-gl: " + error);
    }
    return context.gl;
}

}  // namespace dlab::cli
