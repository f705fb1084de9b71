// The GL tests' platform in dlab_ui_tests: OSMesa, a software OpenGL core-profile context.
#include "tests/ui/ui_harness.h"
#include "ui/gl/gl_api.h"

namespace dlab::test {

std::unique_ptr<ui::Platform> makeTestPlatform(int width, int height, std::string& error) {
    return ui::makeOsmesaPlatform(width, height, error);
}

bool HeadlessGl::open(std::string& error) {
    platform = ui::makeOsmesaPlatform(16, 16, error);
    if (platform) gl = ui::GlContext::fromCurrent(error);
    return gl != nullptr;
}

const char* dtlabGlFlag() { return "--gl osmesa"; }

}  // namespace dlab::test
