// What each GL executable defines for dtlab_gl.cpp: its GL (dtlab_gl_egl.cpp in dtlab-gl,
// dtlab_gl_osmesa.cpp in dtlab-gl-osmesa) and when --gl sends a command to the other one.
#pragma once

#include "app/dtlab_common.h"

namespace dlab::cli {

// The command needs GL and --gl says `flag`: returns when this executable has that GL (auto: the
// one auto picks), else replaces the process with the other GL executable on the same command
// line, or fail()s when that one is not built.
void settleGl(const std::string& flag);
// A headless platform of that size on this executable's GL, as settleGl settled it; nullptr and
// a one-line reason when none can be made.
std::unique_ptr<ui::Platform> makeHeadlessPlatform(int width, int height, std::string& error);
// What `platform` runs on, in words: "EGL, GPU device 0", "OSMesa".
std::string headlessApi(const ui::Platform& platform);

}  // namespace dlab::cli
