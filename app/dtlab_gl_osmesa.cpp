// dtlab-gl-osmesa's GL: OSMesa (software GL on llvmpipe); --gl egl re-runs the command in
// dtlab-gl. dtlab-gl sends here --gl osmesa, and --gl auto when there is no GPU.
#include "app/dtlab_gl.h"

namespace dlab::cli {

void settleGl(const std::string& flag) {
    if (flag == "egl") execBeside("dtlab-gl", "--gl egl needs EGL");
}

std::unique_ptr<ui::Platform> makeHeadlessPlatform(int width, int height, std::string& error) {
    return ui::makeOsmesaPlatform(width, height, error);
}

std::string headlessApi(const ui::Platform&) { return "OSMesa"; }

}  // namespace dlab::cli
