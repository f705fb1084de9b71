// The GL tests' platform in dlab_ui_tests_egl: EGL on Mesa's software device or surfaceless
// platform (llvmpipe), never a GPU, so that the tests give the same pixels on every machine.
#include "tests/ui/ui_harness.h"
#include "ui/gl/gl_api.h"

namespace dlab::test {

std::unique_ptr<ui::Platform> makeTestPlatform(int width, int height, std::string& error) {
    return ui::makeEglPlatform(width, height, ui::EglDevice::Software, error);
}

bool HeadlessGl::open(std::string& error) {
    platform = ui::makeEglPlatform(16, 16, ui::EglDevice::Software, error);
    if (platform) gl = ui::GlContext::fromCurrent(error);
    return gl != nullptr;
}

const char* dtlabGlFlag() { return "--gl egl"; }

}  // namespace dlab::test
