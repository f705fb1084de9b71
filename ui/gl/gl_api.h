// The GL of every target from one source: OpenGL 3.3 core (the window through libGL, headless
// through EGL and libOpenGL, or OSMesa), OpenGL ES 3.0 / WebGL2 (the browser); the context
// handle, shader programs, texture upload and the scope that saves and restores the GL state our
// drawing touches.
//
// The entry points are called directly: each executable's GL provider (libGL, libOpenGL,
// libOSMesa, Emscripten's WebGL library) exports all of them, so there is no loader and no
// pointer table. Only the core subset is declared (GL/glcorearb.h): fixed-function calls do not
// compile.
#pragma once

#if defined(__EMSCRIPTEN__)
#include <GLES3/gl3.h>
#include <webgl/webgl2.h>  // glGetBufferSubData (WebGL2 has it, OpenGL ES 3.0 does not)
#define DLAB_GL_ES 1
#elif defined(__APPLE__)
#include <OpenGL/gl3.h>
#define DLAB_GL_ES 0
#else
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>
#define DLAB_GL_ES 0
#endif

#include "ui/render/renderer.h"

#include <cstdint>
#include <memory>
#include <string>

namespace dlab::ui {

// The first lines of every shader: the target's GLSL version (3.30 core or ES 3.00) and, for ES,
// full precision everywhere (uniforms shared by both stages must agree). Shader bodies are
// written in the common subset of the two languages (shaders.h).
inline constexpr const char* kGlslCorePreamble = "#version 330 core\n";
inline constexpr const char* kGlslEsPreamble =
    "#version 300 es\nprecision highp float;\nprecision highp int;\n";
#if DLAB_GL_ES
inline constexpr const char* kGlslVersion = "#version 300 es";
inline constexpr const char* kGlslPreamble = kGlslEsPreamble;
#else
inline constexpr const char* kGlslVersion = "#version 330 core";
inline constexpr const char* kGlslPreamble = kGlslCorePreamble;
#endif

// The GL context our renderers draw on, and a flag that its owner clears before destroying it,
// so that objects outliving the context never call into it. The engine sees it as a GpuDevice.
class GlContext final : public GpuDevice, public std::enable_shared_from_this<GlContext> {
public:
    // The current context if it runs our shaders (OpenGL 3.3 or OpenGL ES 3.0 and later);
    // nullptr and a one-line reason otherwise.
    static std::shared_ptr<GlContext> fromCurrent(std::string& error);

    bool alive() const override { return m_alive; }
    void lose() override { m_alive = false; }
    // ui/gl/idbuffer_gl.cpp
    std::unique_ptr<GpuIdBuffer> makeIdBuffer(LocatorKind kind,
                                              const LocatorOptions& options) override;
    const std::string& version() const { return m_version; }    // GL_VERSION
    const std::string& renderer() const { return m_renderer; }  // GL_RENDERER

private:
    bool m_alive = true;
    std::string m_version, m_renderer;
};

// A linked program from a vertex and a fragment shader body, `preamble` first (the target's, or
// the other language's in a test: desktop GL 4.3 and later also compile GLSL ES 3.00). 0 and
// the compiler's or linker's log in `error` when it fails.
GLuint buildProgram(const char* vertexBody, const char* fragmentBody, std::string& error,
                    const char* preamble = kGlslPreamble);

// Uploads RGBA pixels (rows of `width`, tightly packed) to `texture`, made on first use with
// nearest filtering; the storage is reallocated only when the size changes. Rows [rowsY0, rowsY1)
// only, when that range is not empty and the size did not change. The GL state is left as it was.
void uploadRgbaTexture(GLuint& texture, int& textureW, int& textureH, int width, int height,
                       const void* rgba, int rowsY0 = 0, int rowsY1 = 0);

// ImU32 colours (ABGR bytes) as the four floats a shader takes.
void setColourUniform(GLint location, std::uint32_t abgr);

// Saves the GL state that our drawing sets (bindings, viewport, scissor, enables, blending,
// colour mask, clear colour, pixel packing) and restores it when it ends: the GUI's frame (ImGui's
// own GL state, a caller's unusual state in tests) is left exactly as it was found. Inside, a
// neutral state for exact drawing: no blending, dithering, scissor, depth, stencil, culling or
// multisampling; all colour channels written; tight pixel packing; no buffer bound for pixels.
class GlStateScope {
public:
    GlStateScope();
    ~GlStateScope();
    GlStateScope(const GlStateScope&) = delete;
    GlStateScope& operator=(const GlStateScope&) = delete;

private:
    GLint m_bindings[10] = {};  // framebuffers, program, vertex array, buffers, texture unit 0
    GLint m_viewport[4] = {}, m_scissor[4] = {};
    GLint m_blend[6] = {};    // source and destination factors, equations
    GLint m_packing[8] = {};  // pack and unpack: alignment, row length, skipped rows and pixels
    GLint m_polygonMode = 0;  // desktop GL only
    GLfloat m_clearColour[4] = {};
    GLboolean m_enabled[16] = {}, m_colourMask[4] = {};
};
}  // namespace dlab::ui
