// The browser's platform (the WebAssembly build): Emscripten's GLFW on the page's canvas, a
// WebGL2 context (OpenGL ES 3.0: the same shaders as OpenGL 3.3 core, ui/gl/gl_api.h), input
// from the mouse, wheel, keyboard and touch (platform_web.js turns taps and pinches into mouse
// and wheel events), and files dropped on the canvas.
#pragma once

#include "ui/platform/platform.h"

namespace dlab::ui {

// A WebGL2 context on the canvas (#canvas) of `width` x `height` pixels. Returns nullptr and sets
// `error` when the browser gives none.
std::unique_ptr<Platform> makeWebPlatform(int width, int height, std::string& error);

}  // namespace dlab::ui
