// ImGui's OpenGL3 renderer backend, compiled from the ImGui sources we build with against our GL
// declarations (ui/gl/gl_api.h): the packaged libimgui.a's copy loads its functions from libGL by
// name and cannot find OSMesa's. CMake names the source (DLAB_IMGUI_OPENGL3_SOURCE).
#include "ui/gl/gl_api.h"

#if DLAB_GL_ES
#define IMGUI_IMPL_OPENGL_ES3
#else
#define IMGUI_IMPL_OPENGL_LOADER_CUSTOM
#endif

#include DLAB_IMGUI_OPENGL3_SOURCE
