// GlContext, shader programs, texture upload and GlStateScope on the GL of every target.
#include "ui/gl/gl_api.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace dlab::ui {

namespace {

// Capabilities that change how a colour reaches the framebuffer, switched off inside a scope
// (and restored after). Desktop GL has a few more than OpenGL ES.
constexpr std::array kNeutralOff = {
    GLenum{GL_BLEND},
    GLenum{GL_DITHER},
    GLenum{GL_SCISSOR_TEST},
    GLenum{GL_DEPTH_TEST},
    GLenum{GL_STENCIL_TEST},
    GLenum{GL_CULL_FACE},
    GLenum{GL_RASTERIZER_DISCARD},
    GLenum{GL_SAMPLE_ALPHA_TO_COVERAGE},
    GLenum{GL_SAMPLE_COVERAGE},
#if !DLAB_GL_ES
    GLenum{GL_COLOR_LOGIC_OP},
    GLenum{GL_MULTISAMPLE},
    GLenum{GL_FRAMEBUFFER_SRGB},
#endif
};
#if !DLAB_GL_ES
// Points take their size from the shader (gl_PointSize), as they always do on OpenGL ES.
constexpr GLenum kNeutralOn = GL_PROGRAM_POINT_SIZE;
constexpr std::size_t kSavedCaps = kNeutralOff.size() + 1;
#else
constexpr std::size_t kSavedCaps = kNeutralOff.size();
#endif

constexpr std::array kPacking = {GLenum{GL_PACK_ALIGNMENT},   GLenum{GL_PACK_ROW_LENGTH},
                                 GLenum{GL_PACK_SKIP_ROWS},   GLenum{GL_PACK_SKIP_PIXELS},
                                 GLenum{GL_UNPACK_ALIGNMENT}, GLenum{GL_UNPACK_ROW_LENGTH},
                                 GLenum{GL_UNPACK_SKIP_ROWS}, GLenum{GL_UNPACK_SKIP_PIXELS}};

GLenum capAt(std::size_t k) {
#if !DLAB_GL_ES
    if (k == kNeutralOff.size()) return kNeutralOn;
#endif
    return kNeutralOff[k];
}

void setCap(GLenum cap, bool on) {
    if (on)
        glEnable(cap);
    else
        glDisable(cap);
}

// Whether a shader compiled (or a program linked): the status, else the log in `error`.
template <typename GetIv, typename GetLog>
bool succeeded(GLuint object, GLenum status, GetIv getIv, GetLog getLog, const char* what,
               std::string& error) {
    GLint ok = GL_FALSE;
    getIv(object, status, &ok);
    if (ok == GL_TRUE) return true;
    GLint length = 0;
    getIv(object, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    getLog(object, static_cast<GLsizei>(log.size()), nullptr, log.data());
    error = std::string(what) + ": " + log.data();
    return false;
}

GLuint compile(GLenum stage, const char* preamble, const char* body, std::string& error) {
    const GLuint shader = glCreateShader(stage);
    const char* sources[2] = {preamble, body};
    glShaderSource(shader, 2, sources, nullptr);
    glCompileShader(shader);
    const char* what = stage == GL_VERTEX_SHADER ? "vertex shader" : "fragment shader";
    if (succeeded(shader, GL_COMPILE_STATUS, glGetShaderiv, glGetShaderInfoLog, what, error))
        return shader;
    glDeleteShader(shader);
    return 0;
}

}  // namespace

static_assert(kSavedCaps <= 16, "GlStateScope::m_enabled holds every saved capability");

std::shared_ptr<GlContext> GlContext::fromCurrent(std::string& error) {
    while (glGetError() != GL_NO_ERROR) {}
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);  // GL 3.0 and ES 3.0 know these
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    const int needMajor = 3, needMinor = DLAB_GL_ES ? 0 : 3;
    if (glGetError() != GL_NO_ERROR || major < needMajor ||
        (major == needMajor && minor < needMinor)) {
        error = std::string("the GL context (") + (version ? version : "unknown version") +
                ") is older than " + (DLAB_GL_ES ? "OpenGL ES 3.0" : "OpenGL 3.3");
        return nullptr;
    }
    auto ctx = std::make_shared<GlContext>();
    ctx->m_version = version ? version : "";
    const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    ctx->m_renderer = renderer ? renderer : "";
    return ctx;
}

GLuint buildProgram(const char* vertexBody, const char* fragmentBody, std::string& error,
                    const char* preamble) {
    const GLuint vs = compile(GL_VERTEX_SHADER, preamble, vertexBody, error);
    if (!vs) return 0;
    const GLuint fs = compile(GL_FRAGMENT_SHADER, preamble, fragmentBody, error);
    if (!fs) {
        glDeleteShader(vs);
        return 0;
    }
    const GLuint program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);  // flagged: freed with the program
    glDeleteShader(fs);
    if (succeeded(program, GL_LINK_STATUS, glGetProgramiv, glGetProgramInfoLog, "shader program",
                  error))
        return program;
    glDeleteProgram(program);
    return 0;
}

void uploadRgbaTexture(GLuint& texture, int& textureW, int& textureH, int width, int height,
                       const void* rgba, int rowsY0, int rowsY1) {
    const GlStateScope scope;  // tight unpacking, no unpack buffer; the binding put back
    if (texture == 0) {
        glGenTextures(1, &texture);
        textureW = textureH = 0;
    }
    glBindTexture(GL_TEXTURE_2D, texture);
    if (textureW != width || textureH != height) {
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
        textureW = width;
        textureH = height;
    } else if (rowsY0 < rowsY1) {
        const int y0 = std::max(0, rowsY0), y1 = std::min(height, rowsY1);
        const auto* rows = static_cast<const std::uint8_t*>(rgba) + std::size_t{4} * width * y0;
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, y0, width, y1 - y0, GL_RGBA, GL_UNSIGNED_BYTE, rows);
    } else {
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    }
}

void setColourUniform(GLint location, std::uint32_t c) {
    glUniform4f(location, static_cast<float>(c & 0xFF) / 255.0f,
                static_cast<float>((c >> 8) & 0xFF) / 255.0f,
                static_cast<float>((c >> 16) & 0xFF) / 255.0f,
                static_cast<float>((c >> 24) & 0xFF) / 255.0f);
}

GlStateScope::GlStateScope() {
    GLint* b = m_bindings;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &b[0]);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &b[1]);
    glGetIntegerv(GL_CURRENT_PROGRAM, &b[2]);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &b[3]);
    glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &b[4]);
    glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &b[5]);
    glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &b[6]);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &b[7]);
    glActiveTexture(GL_TEXTURE0);  // our drawing samples from unit 0
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &b[8]);
    glGetIntegerv(GL_SAMPLER_BINDING, &b[9]);
    glGetIntegerv(GL_VIEWPORT, m_viewport);
    glGetIntegerv(GL_SCISSOR_BOX, m_scissor);
    const GLenum blend[6] = {GL_BLEND_SRC_RGB,   GL_BLEND_DST_RGB,      GL_BLEND_SRC_ALPHA,
                             GL_BLEND_DST_ALPHA, GL_BLEND_EQUATION_RGB, GL_BLEND_EQUATION_ALPHA};
    for (int k = 0; k < 6; ++k) glGetIntegerv(blend[k], &m_blend[k]);
    for (std::size_t k = 0; k < kPacking.size(); ++k) glGetIntegerv(kPacking[k], &m_packing[k]);
    glGetFloatv(GL_COLOR_CLEAR_VALUE, m_clearColour);
    glGetBooleanv(GL_COLOR_WRITEMASK, m_colourMask);
    for (std::size_t k = 0; k < kSavedCaps; ++k) m_enabled[k] = glIsEnabled(capAt(k));
#if !DLAB_GL_ES
    GLint polygonMode[2] = {GL_FILL, GL_FILL};
    glGetIntegerv(GL_POLYGON_MODE, polygonMode);
    m_polygonMode = polygonMode[0];
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glEnable(kNeutralOn);
#endif
    // The neutral state.
    for (const GLenum cap : kNeutralOff) glDisable(cap);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    for (std::size_t k = 0; k < kPacking.size(); ++k) {
        const bool alignment =
            kPacking[k] == GL_PACK_ALIGNMENT || kPacking[k] == GL_UNPACK_ALIGNMENT;
        glPixelStorei(kPacking[k], alignment ? 4 : 0);
    }
    glBindSampler(0, 0);  // a caller's sampler object would override our textures' filtering
}

GlStateScope::~GlStateScope() {
    const GLint* b = m_bindings;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(b[0]));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(b[1]));
    glUseProgram(static_cast<GLuint>(b[2]));
    glBindVertexArray(static_cast<GLuint>(b[3]));
    glBindBuffer(GL_ARRAY_BUFFER, static_cast<GLuint>(b[4]));
    glBindBuffer(GL_PIXEL_PACK_BUFFER, static_cast<GLuint>(b[5]));
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, static_cast<GLuint>(b[6]));
    glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(b[8]));  // unit 0, active since the start
    glBindSampler(0, static_cast<GLuint>(b[9]));
    glActiveTexture(static_cast<GLenum>(b[7]));
    glViewport(m_viewport[0], m_viewport[1], m_viewport[2], m_viewport[3]);
    glScissor(m_scissor[0], m_scissor[1], m_scissor[2], m_scissor[3]);
    glBlendFuncSeparate(static_cast<GLenum>(m_blend[0]), static_cast<GLenum>(m_blend[1]),
                        static_cast<GLenum>(m_blend[2]), static_cast<GLenum>(m_blend[3]));
    glBlendEquationSeparate(static_cast<GLenum>(m_blend[4]), static_cast<GLenum>(m_blend[5]));
    for (std::size_t k = 0; k < kPacking.size(); ++k) glPixelStorei(kPacking[k], m_packing[k]);
    glClearColor(m_clearColour[0], m_clearColour[1], m_clearColour[2], m_clearColour[3]);
    glColorMask(m_colourMask[0], m_colourMask[1], m_colourMask[2], m_colourMask[3]);
    for (std::size_t k = 0; k < kSavedCaps; ++k) setCap(capAt(k), m_enabled[k] == GL_TRUE);
#if !DLAB_GL_ES
    glPolygonMode(GL_FRONT_AND_BACK, static_cast<GLenum>(m_polygonMode));
#endif
}

}  // namespace dlab::ui
