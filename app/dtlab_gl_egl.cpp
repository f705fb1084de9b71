// dtlab-gl's GL: EGL and libOpenGL (glvnd), on a GPU's EGL device when there is one, else on
// Mesa's llvmpipe; --gl osmesa, and --gl auto without a GPU, re-run in dtlab-gl-osmesa when the
// build has it (DLAB_OSMESA_BUILT).
#include "app/dtlab_gl.h"

namespace dlab::cli {

namespace {
ui::EglDevice g_device = ui::EglDevice::Any;  // egl: a GPU first, else llvmpipe
constexpr bool kOsmesaBuilt = DLAB_OSMESA_BUILT;
}  // namespace

void settleGl(const std::string& flag) {
    if (flag == "egl") return;
    if (flag == "osmesa") {
        if (!kOsmesaBuilt) fail("--gl osmesa: this build has no OSMesa (use --gl egl or auto)", 2);
        execBeside("dtlab-gl-osmesa", "--gl osmesa needs OSMesa");
    }
    if (ui::eglHasGpu()) return;  // auto, with a GPU: EGL on it
    if (kOsmesaBuilt) execBeside("dtlab-gl-osmesa", "--gl auto without a GPU needs OSMesa");
    g_device = ui::EglDevice::Software;  // auto, no GPU, no OSMesa: Mesa's EGL on llvmpipe
}

std::unique_ptr<ui::Platform> makeHeadlessPlatform(int width, int height, std::string& error) {
    return ui::makeEglPlatform(width, height, g_device, error);
}

std::string headlessApi(const ui::Platform& platform) {
    return "EGL, " + ui::eglDisplayName(platform);
}

}  // namespace dlab::cli
