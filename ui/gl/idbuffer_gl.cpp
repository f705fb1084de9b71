// IdBufferGl: the colour-ID buffer in a framebuffer object, repainted per change, read back one
// pixel at a time (the paper) or in gathered batches through a pixel-buffer object.
//
// Index:
//   [SECTION] Encoding and options
//   [SECTION] Scope: save, set and restore the GL state we touch
//   [SECTION] GL objects
//   [SECTION] Painting
//   [SECTION] Reading
//   [SECTION] Locator
#include "ui/gl/idbuffer_gl.h"

#include "core/engine/inserter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <stdexcept>

namespace dlab::ui {

// ============================================================================================
// [SECTION] Encoding and options
// ============================================================================================

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

constexpr int kGatherWidth = 256;  // the gather target: 256 ids per row
constexpr std::uint32_t kNoTriangle = 0xFFFFFFFFu;

// Pixel coordinates go to GL as floats; a super-triangle corner can lie far outside the box
// (and a point at 1e308 overflows the map to inf): clamp to a range the rasterizer handles.
// Only the part of a triangle inside the box shows, and a far corner's rounding moves it by far
// less than a pixel there.
float toPixel(double v) {
    constexpr double kFar = 1e7;
    if (!(v > -kFar)) return static_cast<float>(-kFar);
    if (!(v < kFar)) return static_cast<float>(kFar);
    return static_cast<float>(v);
}

// Draw into `fbo` (w x h pixels) with pixel coordinates: x in [0, w), y in [0, h), y up.
void drawInto(const GlApi& gl, GLuint fbo, int w, int h) {
    gl.bindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, w, h);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0, w, 0, h, -1, 1);
    glMatrixMode(GL_MODELVIEW);
}

std::uint32_t packColour(std::int32_t id) {
    const std::array<std::uint8_t, 4> c = encodeTriangleId(id);
    std::uint32_t v;
    std::memcpy(&v, c.data(), 4);  // memory order r, g, b, a: what GL reads from the array
    return v;
}

// Charges the GL state saving and restoring around a read to the painting side, so that
// readbackMs + paintMs is all the time spent in GL calls: the time of the block minus what the
// painting and reading inside it already counted.
class GlTimer {
public:
    explicit GlTimer(IdBufferGlStats& stats)
        : m_stats(stats), m_t0(Clock::now()), m_paint(stats.paintMs), m_read(stats.readbackMs) {}
    ~GlTimer() {
        const double inside = (m_stats.paintMs - m_paint) + (m_stats.readbackMs - m_read);
        m_stats.paintMs += std::max(0.0, msSince(m_t0) - inside);
    }
    GlTimer(const GlTimer&) = delete;
    GlTimer& operator=(const GlTimer&) = delete;

private:
    IdBufferGlStats& m_stats;
    Clock::time_point m_t0;
    double m_paint, m_read;
};

}  // namespace

const char* toString(GlReadback mode) {
    switch (mode) {
        case GlReadback::OnePixel: return "one";
        case GlReadback::Batched: return "batched";
        case GlReadback::Pipelined: return "pipelined";
    }
    return "?";
}

IdBufferGlOptions IdBufferGlOptions::from(LocatorKind kind, const LocatorOptions& o) {
    IdBufferGlOptions g;
    g.width = o.idBufferWidth;
    g.height = o.idBufferHeight;
    g.batch = o.idBufferBatch;
    g.readback =
        kind == LocatorKind::IdBufferGlBatched ? GlReadback::Batched : GlReadback::OnePixel;
    return g;
}

std::array<std::uint8_t, 4> encodeTriangleId(std::int32_t id) {
    const std::uint32_t v = id < 0 ? kNoTriangle : static_cast<std::uint32_t>(id);
    return {static_cast<std::uint8_t>((v >> 16) & 255), static_cast<std::uint8_t>((v >> 8) & 255),
            static_cast<std::uint8_t>(v & 255), static_cast<std::uint8_t>((v >> 24) & 255)};
}

std::int32_t decodeTriangleId(const std::uint8_t* c) {
    const std::uint32_t v = (std::uint32_t{c[3]} << 24) | (std::uint32_t{c[0]} << 16) |
                            (std::uint32_t{c[1]} << 8) | c[2];
    return v == kNoTriangle ? kNone : static_cast<std::int32_t>(v & 0x7FFFFFFFu);
}

// ============================================================================================
// [SECTION] Scope: save, set and restore the GL state we touch
// ============================================================================================

// In the GUI the locator runs while ImGui is mid-frame (and the mesh renderer's arrays and
// ImGui's texture are set): everything changed here goes back exactly as it was. Bindings that
// the attribute stacks do not cover (framebuffers, buffers, program, vertex array, sampler) are
// saved by hand; the framebuffers are rebound before the attribute pop, because the pop restores
// the draw and read buffers of whatever framebuffer is bound then.
class IdBufferGl::Scope {
public:
    Scope(const GlApi& gl, bool texturing) : m_gl(gl), m_texturing(texturing) {
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &m_drawFbo);
        glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &m_readFbo);
        glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &m_arrayBuffer);
        glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &m_packBuffer);
        glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &m_unpackBuffer);
        glGetIntegerv(GL_CURRENT_PROGRAM, &m_program);
        glGetIntegerv(GL_SHADE_MODEL, &m_shadeModel);
        glGetIntegerv(GL_MATRIX_MODE, &m_matrixMode);
        if (m_gl.bindVertexArray) {
            // Vertex array 0 is where our client arrays go; bound before the client push, so
            // that the push and pop act on it and the caller's vertex array is never touched.
            glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &m_vertexArray);
            if (m_vertexArray != 0) m_gl.bindVertexArray(0);
        }
        if (m_texturing) {
            glGetIntegerv(GL_ACTIVE_TEXTURE, &m_activeTexture);
            glGetIntegerv(GL_CLIENT_ACTIVE_TEXTURE, &m_clientActiveTexture);
            m_gl.activeTexture(GL_TEXTURE0);
            m_gl.clientActiveTexture(GL_TEXTURE0);
            glGetIntegerv(GL_TEXTURE_BINDING_2D, &m_texture2d);
            if (m_gl.bindSampler) {
                glGetIntegerv(GL_SAMPLER_BINDING, &m_sampler);
                if (m_sampler != 0) m_gl.bindSampler(0, 0);
            }
        }
        glPushAttrib(GL_ENABLE_BIT | GL_COLOR_BUFFER_BIT | GL_CURRENT_BIT | GL_VIEWPORT_BIT |
                     GL_POLYGON_BIT | GL_PIXEL_MODE_BIT | GL_POINT_BIT |
                     (m_texturing ? GL_TEXTURE_BIT : 0));
        glPushClientAttrib(GL_CLIENT_VERTEX_ARRAY_BIT | GL_CLIENT_PIXEL_STORE_BIT);
        for (GLenum mode : {GL_PROJECTION, GL_MODELVIEW, GL_TEXTURE}) {
            if (mode == GL_TEXTURE && !m_texturing) continue;
            glMatrixMode(mode);
            glPushMatrix();
            glLoadIdentity();
        }
        m_gl.bindBuffer(GL_ARRAY_BUFFER, 0);
        m_gl.bindBuffer(GL_PIXEL_PACK_BUFFER, 0);
        m_gl.bindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
        if (m_program != 0) m_gl.useProgram(0);
        // Exact integer colours: nothing between the vertex colour and the pixel may change it.
        for (GLenum cap : {GL_BLEND,
                           GL_DITHER,
                           GL_SCISSOR_TEST,
                           GL_DEPTH_TEST,
                           GL_STENCIL_TEST,
                           GL_ALPHA_TEST,
                           GL_CULL_FACE,
                           GL_LIGHTING,
                           GL_FOG,
                           GL_TEXTURE_1D,
                           GL_TEXTURE_2D,
                           GL_TEXTURE_3D,
                           GL_TEXTURE_CUBE_MAP,
                           GL_TEXTURE_GEN_S,
                           GL_TEXTURE_GEN_T,
                           GL_TEXTURE_GEN_R,
                           GL_TEXTURE_GEN_Q,
                           GL_COLOR_LOGIC_OP,
                           GL_POLYGON_SMOOTH,
                           GL_POLYGON_STIPPLE,
                           GL_MULTISAMPLE,
                           GL_SAMPLE_ALPHA_TO_COVERAGE,
                           GL_COLOR_SUM,
                           GL_FRAMEBUFFER_SRGB,
                           GL_POINT_SMOOTH,
                           GL_POINT_SPRITE,
                           GL_VERTEX_PROGRAM_POINT_SIZE,
                           GL_CLIP_PLANE0,
                           GL_CLIP_PLANE1,
                           GL_CLIP_PLANE2,
                           GL_CLIP_PLANE3,
                           GL_CLIP_PLANE4,
                           GL_CLIP_PLANE5}) {
            glDisable(cap);
        }
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        glShadeModel(GL_FLAT);
        glPointSize(1.0f);
        glPixelTransferi(GL_MAP_COLOR, GL_FALSE);
        for (GLenum scale : {GL_RED_SCALE, GL_GREEN_SCALE, GL_BLUE_SCALE, GL_ALPHA_SCALE})
            glPixelTransferf(scale, 1.0f);
        for (GLenum bias : {GL_RED_BIAS, GL_GREEN_BIAS, GL_BLUE_BIAS, GL_ALPHA_BIAS})
            glPixelTransferf(bias, 0.0f);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glPixelStorei(GL_PACK_ROW_LENGTH, 0);
        glPixelStorei(GL_PACK_SKIP_ROWS, 0);
        glPixelStorei(GL_PACK_SKIP_PIXELS, 0);
        glPixelStorei(GL_PACK_SWAP_BYTES, GL_FALSE);
        glPixelStorei(GL_PACK_LSB_FIRST, GL_FALSE);
        for (GLenum array :
             {GL_NORMAL_ARRAY, GL_COLOR_ARRAY, GL_INDEX_ARRAY, GL_TEXTURE_COORD_ARRAY,
              GL_EDGE_FLAG_ARRAY, GL_FOG_COORD_ARRAY, GL_SECONDARY_COLOR_ARRAY}) {
            glDisableClientState(array);
        }
        glEnableClientState(GL_VERTEX_ARRAY);
    }

    void target(GLuint fbo, int w, int h) { drawInto(m_gl, fbo, w, h); }

    ~Scope() {
        for (GLenum mode : {GL_TEXTURE, GL_MODELVIEW, GL_PROJECTION}) {
            if (mode == GL_TEXTURE && !m_texturing) continue;
            glMatrixMode(mode);
            glPopMatrix();
        }
        m_gl.bindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(m_drawFbo));
        m_gl.bindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(m_readFbo));
        glPopClientAttrib();
        glPopAttrib();
        glShadeModel(static_cast<GLenum>(m_shadeModel));
        glMatrixMode(static_cast<GLenum>(m_matrixMode));
        m_gl.bindBuffer(GL_ARRAY_BUFFER, static_cast<GLuint>(m_arrayBuffer));
        m_gl.bindBuffer(GL_PIXEL_PACK_BUFFER, static_cast<GLuint>(m_packBuffer));
        m_gl.bindBuffer(GL_PIXEL_UNPACK_BUFFER, static_cast<GLuint>(m_unpackBuffer));
        if (m_program != 0) m_gl.useProgram(static_cast<GLuint>(m_program));
        if (m_vertexArray != 0) m_gl.bindVertexArray(static_cast<GLuint>(m_vertexArray));
        if (m_texturing) {
            glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(m_texture2d));
            if (m_sampler != 0) m_gl.bindSampler(0, static_cast<GLuint>(m_sampler));
            m_gl.clientActiveTexture(static_cast<GLenum>(m_clientActiveTexture));
            m_gl.activeTexture(static_cast<GLenum>(m_activeTexture));
        }
    }

    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

private:
    const GlApi& m_gl;
    bool m_texturing;
    GLint m_drawFbo = 0, m_readFbo = 0, m_arrayBuffer = 0, m_packBuffer = 0, m_unpackBuffer = 0;
    GLint m_program = 0, m_shadeModel = GL_SMOOTH, m_matrixMode = GL_MODELVIEW, m_vertexArray = 0;
    GLint m_activeTexture = GL_TEXTURE0, m_clientActiveTexture = GL_TEXTURE0, m_texture2d = 0,
          m_sampler = 0;
};

// ============================================================================================
// [SECTION] GL objects
// ============================================================================================

IdBufferGl::IdBufferGl(std::shared_ptr<GlContext> gl, const IdBufferGlOptions& options)
    : m_gl(std::move(gl)), m_opt(options) {
    if (!m_gl || !m_gl->alive()) throw std::runtime_error("idbuffer-gl: no GL context");
    m_opt.batch = std::clamp(m_opt.batch, 1, IdBufferGlOptions::kMaxBatch);
    GLint maxTexture = 0, maxViewport[2] = {0, 0};
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, maxViewport);
    const int limit = std::min({maxTexture, maxViewport[0], maxViewport[1]});
    if (m_opt.width < 1 || m_opt.height < 1 || m_opt.width > limit || m_opt.height > limit) {
        throw std::runtime_error("idbuffer-gl: a " + std::to_string(m_opt.width) + "x" +
                                 std::to_string(m_opt.height) +
                                 " buffer does not fit this GL context (at most " +
                                 std::to_string(limit) + " per side)");
    }
    while (glGetError() != GL_NO_ERROR) {}  // earlier errors are not ours
    const GlApi& a = m_gl->api();
    std::string problem;
    {
        Scope scope(a, true);
        auto makeTarget = [&](unsigned& tex, unsigned& fbo, int w, int h) {
            glGenTextures(1, &tex);
            glBindTexture(GL_TEXTURE_2D, tex);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
            glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
            a.genFramebuffers(1, &fbo);
            a.bindFramebuffer(GL_FRAMEBUFFER, fbo);
            a.framebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
            glDrawBuffer(GL_COLOR_ATTACHMENT0);  // framebuffer state: set once here
            glReadBuffer(GL_COLOR_ATTACHMENT0);
            const GLenum status = a.checkFramebufferStatus(GL_FRAMEBUFFER);
            if (status != GL_FRAMEBUFFER_COMPLETE && problem.empty()) {
                char hex[16];
                std::snprintf(hex, sizeof hex, "0x%04x", status);
                problem = std::string("framebuffer incomplete (status ") + hex + ")";
            }
            glClearColor(1, 1, 1, 1);  // the "no triangle" colour
            glClear(GL_COLOR_BUFFER_BIT);
        };
        makeTarget(m_tex, m_fbo, m_opt.width, m_opt.height);
        a.genBuffers(1, &m_vbo);
        if (m_opt.readback != GlReadback::OnePixel) {
            m_gatherRows = (m_opt.batch + kGatherWidth - 1) / kGatherWidth;
            makeTarget(m_gatherTex, m_gatherFbo, kGatherWidth, m_gatherRows);
            a.genBuffers(1, &m_pbo);
            a.bindBuffer(GL_PIXEL_PACK_BUFFER, m_pbo);
            a.bufferData(GL_PIXEL_PACK_BUFFER,
                         static_cast<GLsizeiptr>(kGatherWidth) * m_gatherRows * 4, nullptr,
                         GL_STREAM_READ);
        }
    }
    if (const GLenum err = glGetError(); err != GL_NO_ERROR && problem.empty()) {
        char hex[16];
        std::snprintf(hex, sizeof hex, "0x%04x", err);
        problem = std::string("GL error ") + hex + " while creating the buffer";
    }
    if (!problem.empty()) {
        this->~IdBufferGl();  // a throwing constructor runs no destructor: free the GL objects
        throw std::runtime_error("idbuffer-gl: " + problem);
    }
}

IdBufferGl::~IdBufferGl() {
    if (!m_gl || !m_gl->alive()) return;  // the context is gone, and its objects with it
    const GlApi& a = m_gl->api();
    dropPending();
    if (m_pbo) a.deleteBuffers(1, &m_pbo);
    if (m_vbo) a.deleteBuffers(1, &m_vbo);
    if (m_gatherFbo) a.deleteFramebuffers(1, &m_gatherFbo);
    if (m_fbo) a.deleteFramebuffers(1, &m_fbo);
    if (m_gatherTex) glDeleteTextures(1, &m_gatherTex);
    if (m_tex) glDeleteTextures(1, &m_tex);
    m_pbo = m_vbo = m_gatherFbo = m_fbo = m_gatherTex = m_tex = 0;
}

bool IdBufferGl::ready() const { return m_reset && m_gl && m_gl->alive(); }

std::string IdBufferGl::name() const {
    return m_opt.readback == GlReadback::OnePixel
               ? "idbuffer-gl"
               : std::string("idbuffer-gl-") + toString(m_opt.readback);
}

// ============================================================================================
// [SECTION] Painting
// ============================================================================================

bool IdBufferGl::paintable(std::int32_t t) const {
    return t < m_ctx.mesh->numTriangles() && !(m_ctx.ghost && m_ctx.isVirtualTriangle(t));
}

void IdBufferGl::appendTriangle(std::uint32_t colour, const float* xy) {
    for (int k = 0; k < 3; ++k) m_vertices.push_back({xy[2 * k], xy[2 * k + 1], colour});
}

void IdBufferGl::trianglesChanged(const std::int32_t* tris, int count) {
    for (int k = 0; k < count; ++k) {
        const std::int32_t t = tris[k];
        if (t < 0) continue;
        if (static_cast<std::size_t>(t) >= m_isDirty.size()) {
            m_isDirty.resize(std::max<std::size_t>(t + 1, 2 * m_isDirty.size()), 0);
        }
        if (!m_isDirty[t]) {
            m_isDirty[t] = 1;
            m_dirty.push_back(t);
        }
    }
}

void IdBufferGl::resync() { m_fullRepaint = true; }

void IdBufferGl::corners(std::int32_t t, float* out) const {
    const Mesh& m = *m_ctx.mesh;
    for (int k = 0; k < 3; ++k) {
        const Vec2 g = m.G[m.V[3 * t + k]];
        out[2 * k] = toPixel(m_map.fx(g.x));
        out[2 * k + 1] = toPixel(m_map.fy(g.y));
    }
}

// Queues triangle t's current shape in its colour (or notes that it is not shown) and marks it
// clean; the shadow keeps what was painted.
void IdBufferGl::paintShape(std::int32_t t) {
    if (paintable(t)) {
        float* xy = &m_shadow[6 * static_cast<std::size_t>(t)];
        corners(t, xy);
        appendTriangle(packColour(t), xy);
        m_glStats.pixelsPainted +=
            std::abs((xy[2] - xy[0]) * (xy[5] - xy[1]) - (xy[3] - xy[1]) * (xy[4] - xy[0])) / 2;
        m_shown[t] = 1;
    } else {
        m_shown[t] = 0;
    }
    if (static_cast<std::size_t>(t) < m_isDirty.size()) m_isDirty[t] = 0;
}

void IdBufferGl::growShadow(std::int32_t triangles) {
    if (m_shown.size() < static_cast<std::size_t>(triangles)) {
        m_shown.resize(triangles, 0);
        m_shadow.resize(6 * static_cast<std::size_t>(triangles));
    }
}

// One draw call for the queued triangles, through a buffer object (llvmpipe takes client arrays
// about half as fast).
void IdBufferGl::submit() {
    if (m_vertices.empty()) return;
    const GlApi& a = m_gl->api();
    a.bindBuffer(GL_ARRAY_BUFFER, m_vbo);
    a.bufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m_vertices.size() * sizeof(Vertex)),
                 m_vertices.data(), GL_STREAM_DRAW);
    glEnableClientState(GL_COLOR_ARRAY);
    glVertexPointer(2, GL_FLOAT, sizeof(Vertex),
                    reinterpret_cast<const void*>(offsetof(Vertex, x)));
    glColorPointer(4, GL_UNSIGNED_BYTE, sizeof(Vertex),
                   reinterpret_cast<const void*>(offsetof(Vertex, rgba)));
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(m_vertices.size()));
    glDisableClientState(GL_COLOR_ARRAY);
    a.bindBuffer(GL_ARRAY_BUFFER, 0);
    ++m_glStats.draws;
    m_glStats.trianglesPainted += m_vertices.size() / 3;
    m_vertices.clear();
    ++m_version;
}

// Brings every pixel up to the mesh: all changed triangles in one draw call (inside a Scope).
//
// Without a shrinking hull the new shapes of the changed triangles cover every pixel whose id
// changed, so painting them is enough. When the covered area shrinks (triangles removed, or a
// painted triangle turned into a ghost: only an undo does that), the old footprints of the
// changed triangles are painted "no triangle" first, in the same draw; no unchanged triangle's
// pixel lies in them, so only pixels that the new shapes repaint or that left the hull change.
void IdBufferGl::paintPending() {
    const Mesh& m = *m_ctx.mesh;
    const std::int32_t nt = m.numTriangles();
    if (m.numVertices() != m_seenVertices) m_fullRepaint = true;  // Finalize renumbers silently
    if (!m_fullRepaint && m_dirty.empty() && nt == m_shadowTriangles) {
        m_paintedAt = m_hints;  // nothing changed since: the pixels are current
        return;
    }
    const auto t0 = Clock::now();
    m_vertices.clear();
    growShadow(std::max(nt, m_shadowTriangles));
    bool shrink = nt < m_shadowTriangles;
    for (std::int32_t t : m_dirty) shrink |= t < m_shadowTriangles && m_shown[t] && !paintable(t);
    if (m_fullRepaint) {
        glClearColor(1, 1, 1, 1);
        glClear(GL_COLOR_BUFFER_BIT);
        for (std::int32_t t = 0; t < nt; ++t) paintShape(t);
        std::fill(m_shown.begin() + nt, m_shown.end(), 0);
        ++m_glStats.fullRepaints;
    } else {
        if (shrink) {
            const std::uint32_t none = packColour(kNone);
            auto clear = [&](std::int32_t t) {
                if (!m_shown[t]) return;
                appendTriangle(none, &m_shadow[6 * static_cast<std::size_t>(t)]);
                m_shown[t] = 0;
                ++m_glStats.trianglesCleared;
            };
            for (std::int32_t t = nt; t < m_shadowTriangles; ++t) clear(t);
            for (std::int32_t t : m_dirty) {
                if (t < nt) clear(t);
            }
        }
        for (std::int32_t t : m_dirty) {
            if (t < nt) paintShape(t);
        }
    }
    for (std::int32_t t : m_dirty) m_isDirty[t] = 0;
    m_dirty.clear();
    m_shadowTriangles = nt;
    m_seenVertices = m.numVertices();
    m_fullRepaint = false;
    submit();
    m_paintedAt = m_hints;
    m_glStats.paintMs += msSince(t0);
}

// ============================================================================================
// [SECTION] Reading
// ============================================================================================

std::int32_t IdBufferGl::readOne(int i, int j) {
    std::uint8_t rgba[4] = {255, 255, 255, 255};
    glReadPixels(i, j, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    return decodeTriangleId(rgba);
}

std::int32_t IdBufferGl::idAt(int i, int j) {
    if (!ready() || i < 0 || j < 0 || i >= m_opt.width || j >= m_opt.height) return kNone;
    Scope scope(m_gl->api(), false);
    scope.target(m_fbo, m_opt.width, m_opt.height);
    paintPending();
    return readOne(i, j);
}

std::vector<std::int32_t> IdBufferGl::readAll() {
    if (!ready()) return {};
    const std::size_t n = static_cast<std::size_t>(m_opt.width) * m_opt.height;
    std::vector<std::uint8_t> rgba(4 * n);
    {
        Scope scope(m_gl->api(), false);
        scope.target(m_fbo, m_opt.width, m_opt.height);
        paintPending();
        glReadPixels(0, 0, m_opt.width, m_opt.height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    }
    std::vector<std::int32_t> ids(n);
    for (std::size_t k = 0; k < n; ++k) ids[k] = decodeTriangleId(&rgba[4 * k]);
    return ids;
}

// A batch spans at most four times as many insertions as came before it: early on, when the mesh
// is small, ids read K insertions ahead would mostly show the small old hull (no triangle under
// the point, and a long walk from the last triangle). Four, not one: every early batch repaints
// most of the box, and each costs a full read.
std::int32_t IdBufferGl::batchCount(std::int32_t start) const {
    return std::min({m_opt.batch, std::max<std::int32_t>(4 * start, 1),
                     static_cast<std::int32_t>(m_order.size()) - start});
}

// The ids under the points [start, start + count) of the insertion order, in one draw and one
// read: each point is a GL point at its own pixel of the gather target that samples the ID
// texture (nearest texel, colour replaced by the texel: exact). The read goes into the PBO; a
// fence marks it, and takeBatch() maps it when the ids are needed.
void IdBufferGl::requestBatch(std::int32_t start) {
    const auto t0 = Clock::now();
    const GlApi& a = m_gl->api();
    const std::int32_t count = batchCount(start);
    m_gatherXy.resize(2 * static_cast<std::size_t>(count));
    m_gatherUv.resize(2 * static_cast<std::size_t>(count));
    for (std::int32_t k = 0; k < count; ++k) {
        int i = 0, j = 0;
        m_map.pixel(m_order[start + k], m_opt.width, m_opt.height, i, j);  // outside: pixel (0, 0)
        m_gatherXy[2 * k] = static_cast<float>(k % kGatherWidth) + 0.5f;
        m_gatherXy[2 * k + 1] = static_cast<float>(k / kGatherWidth) + 0.5f;
        m_gatherUv[2 * k] = (static_cast<float>(i) + 0.5f) / static_cast<float>(m_opt.width);
        m_gatherUv[2 * k + 1] = (static_cast<float>(j) + 0.5f) / static_cast<float>(m_opt.height);
    }
    const int rows = (count + kGatherWidth - 1) / kGatherWidth;
    drawInto(a, m_gatherFbo, kGatherWidth, m_gatherRows);
    glEnable(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, m_tex);
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
    glEnableClientState(GL_TEXTURE_COORD_ARRAY);
    glVertexPointer(2, GL_FLOAT, 0, m_gatherXy.data());
    glTexCoordPointer(2, GL_FLOAT, 0, m_gatherUv.data());
    glDrawArrays(GL_POINTS, 0, count);
    glDisableClientState(GL_TEXTURE_COORD_ARRAY);
    glDisable(GL_TEXTURE_2D);
    a.bindBuffer(GL_PIXEL_PACK_BUFFER, m_pbo);
    glReadPixels(0, 0, kGatherWidth, rows, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    a.bindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    m_pending.start = start;
    m_pending.count = count;
    m_pending.readAt = m_paintedAt;  // the pixels show the mesh as it was then
    m_pending.fence = a.fenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    glFlush();  // the fence must reach the GPU, or a wait on it from another point never ends
    ++m_glStats.reads;
    m_glStats.readbackMs += msSince(t0);
}

void IdBufferGl::takeBatch() {
    const auto t0 = Clock::now();
    const GlApi& a = m_gl->api();
    if (m_pending.fence) {
        const auto fence = static_cast<GLsync>(m_pending.fence);
        while (a.clientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, 1'000'000'000) ==
               GL_TIMEOUT_EXPIRED) {}
        a.deleteSync(fence);
        m_pending.fence = nullptr;
    }
    a.bindBuffer(GL_PIXEL_PACK_BUFFER, m_pbo);
    const auto* p = static_cast<const std::uint8_t*>(a.mapBufferRange(
        GL_PIXEL_PACK_BUFFER, 0, static_cast<GLsizeiptr>(m_pending.count) * 4, GL_MAP_READ_BIT));
    m_windowIds.resize(static_cast<std::size_t>(m_pending.count));
    for (std::int32_t k = 0; k < m_pending.count; ++k)
        m_windowIds[k] = p ? decodeTriangleId(p + 4 * k) : kNone;
    if (p) a.unmapBuffer(GL_PIXEL_PACK_BUFFER);
    a.bindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    m_window = m_pending;
    m_pending = {};
    m_glStats.pixelsRead += static_cast<std::uint64_t>(m_window.count);
    m_glStats.readbackMs += msSince(t0);
}

void IdBufferGl::dropPending() {
    if (m_pending.fence && m_gl && m_gl->alive())
        m_gl->api().deleteSync(static_cast<GLsync>(m_pending.fence));
    m_pending = {};
}

// ============================================================================================
// [SECTION] Locator
// ============================================================================================

void IdBufferGl::reset(const LocatorContext& ctx, const Bounds& bounds) {
    m_ctx = ctx;
    m_map.init(bounds, m_opt.width, m_opt.height);
    m_reset = true;
    m_fullRepaint = true;
    for (std::int32_t t : m_dirty) m_isDirty[t] = 0;
    m_dirty.clear();
    m_shadowTriangles = 0;
    std::fill(m_shown.begin(), m_shown.end(), 0);
    m_seenVertices = ctx.mesh->numVertices();
    m_next = 0;
    m_window = {};
    dropPending();
    m_hints = 0;
    m_paintedAt = 0;
    m_lastAge = -1;
}

void IdBufferGl::followOrder(const Inserter& inserter) {
    // Before run() the mesh's G is in input order (run() permutes it while it works).
    const auto& G = inserter.mesh().G;
    std::vector<Vec2> points;
    points.reserve(inserter.order().size());
    for (const std::int32_t v : inserter.order()) points.push_back(G[v]);
    setInsertionOrder(std::move(points));
}

void IdBufferGl::setInsertionOrder(std::vector<Vec2> pointsInOrder) {
    m_order = std::move(pointsInOrder);
    m_next = 0;
    m_window = {};
    dropPending();
}

// The hints come in insertion order; a point that is not the predicted one (the first after the
// start triangle, a jump in the GUI) is looked up near the prediction.
bool IdBufferGl::findInOrder(Vec2 p) {
    const std::int32_t n = static_cast<std::int32_t>(m_order.size());
    if (m_next < n && m_order[m_next] == p) return true;
    constexpr std::int32_t kReach = 64;
    for (std::int32_t d = 1; d <= kReach; ++d) {
        for (const std::int32_t k : {m_next + d, m_next - d}) {
            if (k >= 0 && k < n && m_order[k] == p) {
                m_next = k;
                return true;
            }
        }
    }
    return false;
}

// The id of the point at m_next from the batch at hand, reading the next batch when needed.
//
// Batched: paint the changes, gather the next K ids, wait for them.
// Pipelined: take the ids gathered one batch earlier, gather the following batch from the
// texture as it is (it waits only for the paint issued one batch ago, long done by now), then
// paint this batch's changes: they are rasterized while the CPU inserts the next K points.
std::int32_t IdBufferGl::windowId(int& age) {
    if (m_next < m_window.start || m_next >= m_window.start + m_window.count) {
        const GlTimer timer(m_glStats);
        Scope scope(m_gl->api(), true);
        scope.target(m_fbo, m_opt.width, m_opt.height);
        if (m_pending.count > 0 && m_pending.start == m_next) {
            takeBatch();
        } else {
            dropPending();
            paintPending();
            requestBatch(m_next);
            takeBatch();
        }
        if (m_opt.readback == GlReadback::Pipelined) {
            const std::int32_t after = m_window.start + m_window.count;
            if (after < static_cast<std::int32_t>(m_order.size())) requestBatch(after);
            scope.target(m_fbo, m_opt.width, m_opt.height);
            paintPending();
            glFlush();  // to the rasterizer now: it draws while the CPU inserts the next K points
        }
    }
    age = static_cast<int>(std::min<std::uint64_t>(m_hints - m_window.readAt, 1u << 30));
    return m_windowIds[m_next - m_window.start];
}

std::int32_t IdBufferGl::hint(Vec2 p, std::int32_t lastTriangle) {
    const std::int32_t fallback = lastTriangle < 0 ? 0 : lastTriangle;
    m_lastAge = -1;
    if (!ready()) return fallback;
    std::int32_t id = kNone;
    int age = 0;
    if (m_opt.readback != GlReadback::OnePixel && findInOrder(p)) {
        id = windowId(age);
        ++m_next;
    } else if (int i = 0, j = 0; pixelOf(p, i, j)) {
        const GlTimer timer(m_glStats);
        Scope scope(m_gl->api(), false);
        scope.target(m_fbo, m_opt.width, m_opt.height);
        paintPending();
        const auto t0 = Clock::now();
        id = readOne(i, j);
        m_glStats.readbackMs += msSince(t0);
        ++m_glStats.reads;
        ++m_glStats.pixelsRead;
    }
    ++m_hints;
    if (id < 0 || id >= m_ctx.mesh->numTriangles()) {
        ++m_glStats.noPixel;
        return fallback;
    }
    m_lastAge = age;
    return id;
}

void IdBufferGl::located(Vec2 p, std::int32_t found, std::int32_t steps) {
    Locator::located(p, found, steps);
    if (m_lastAge < 0) return;
    const bool hit = steps == 0;
    if (m_lastAge == 0) {
        ++m_glStats.freshQueries;
        m_glStats.freshHits += hit;
        m_glStats.freshSteps += static_cast<std::uint64_t>(steps);
    } else {
        ++m_glStats.staleQueries;
        m_glStats.staleHits += hit;
        m_glStats.staleSteps += static_cast<std::uint64_t>(steps);
        m_glStats.staleAgeSum += static_cast<std::uint64_t>(m_lastAge);
    }
    m_lastAge = -1;
}

}  // namespace dlab::ui
