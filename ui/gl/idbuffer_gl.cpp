// IdBufferGl: the colour-ID buffer in a framebuffer object, repainted per change, read back one
// pixel at a time (the paper) or in gathered batches through a pixel-buffer object.
//
// Index:
//   [SECTION] Encoding and options
//   [SECTION] GL objects
//   [SECTION] Painting
//   [SECTION] Reading
//   [SECTION] Locator
#include "ui/gl/idbuffer_gl.h"

#include "core/engine/inserter.h"
#include "ui/gl/shaders.h"

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

// Draw into `fbo` (w x h pixels); the shaders map pixel coordinates (y up) themselves.
void drawInto(GLuint fbo, int w, int h) {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, w, h);
}

std::uint32_t packColour(std::int32_t id) {
    const std::array<std::uint8_t, 4> c = encodeTriangleId(id);
    std::uint32_t v;
    std::memcpy(&v, c.data(), 4);  // memory order r, g, b, a: what GL reads from the array
    return v;
}

// Waits until the fence's commands are done. WebGL2 cannot wait (its fences signal only between
// tasks of the page): there, reading the buffer waits for the drawing instead.
void waitFor(GLsync fence) {
#if defined(__EMSCRIPTEN__)
    (void)fence;
#else
    while (glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, 1'000'000'000) ==
           GL_TIMEOUT_EXPIRED) {}
#endif
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

// ============================================================================================
// [SECTION] GL objects
// ============================================================================================

std::unique_ptr<GpuIdBuffer> GlContext::makeIdBuffer(LocatorKind kind,
                                                     const LocatorOptions& options) {
    return std::make_unique<IdBufferGl>(shared_from_this(), IdBufferGlOptions::from(kind, options));
}

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
    std::string problem;
    {
        const GlStateScope scope;
        auto makeTarget = [&](GLuint& tex, GLuint& fbo, int w, int h) {
            glGenTextures(1, &tex);
            glBindTexture(GL_TEXTURE_2D, tex);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
            glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
            glGenFramebuffers(1, &fbo);
            glBindFramebuffer(GL_FRAMEBUFFER, fbo);
            glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
            const GLenum attachment = GL_COLOR_ATTACHMENT0;
            glDrawBuffers(1, &attachment);  // framebuffer state: set once here
            glReadBuffer(GL_COLOR_ATTACHMENT0);
            const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
            if (status != GL_FRAMEBUFFER_COMPLETE && problem.empty()) {
                char hex[16];
                std::snprintf(hex, sizeof hex, "0x%04x", status);
                problem = std::string("framebuffer incomplete (status ") + hex + ")";
            }
            glViewport(0, 0, w, h);
            glClearColor(1, 1, 1, 1);  // the "no triangle" colour
            glClear(GL_COLOR_BUFFER_BIT);
        };
        makeTarget(m_tex, m_fbo, m_opt.width, m_opt.height);
        glGenVertexArrays(1, &m_vao);
        glGenBuffers(1, &m_vbo);
        m_paintProgram =
            buildProgram(shaders::kPaintVertexShader, shaders::kFlatFragmentShader, problem);
        if (m_paintProgram) m_uPaintTarget = glGetUniformLocation(m_paintProgram, "uTarget");
        if (m_opt.readback != GlReadback::OnePixel) {
            m_gatherRows = (m_opt.batch + kGatherWidth - 1) / kGatherWidth;
            makeTarget(m_gatherTex, m_gatherFbo, kGatherWidth, m_gatherRows);
            glGenBuffers(1, &m_gatherVbo);
            glGenBuffers(1, &m_pbo);
            glBindBuffer(GL_PIXEL_PACK_BUFFER, m_pbo);
            glBufferData(GL_PIXEL_PACK_BUFFER,
                         static_cast<GLsizeiptr>(kGatherWidth) * m_gatherRows * 4, nullptr,
                         GL_STREAM_READ);
            if (problem.empty()) {
                m_gatherProgram = buildProgram(shaders::kGatherVertexShader,
                                               shaders::kFlatFragmentShader, problem);
            }
            if (m_gatherProgram) {
                m_uGatherTarget = glGetUniformLocation(m_gatherProgram, "uTarget");
                m_uGatherIds = glGetUniformLocation(m_gatherProgram, "uIds");
            }
        }
    }
    if (const GLenum err = glGetError(); err != GL_NO_ERROR && problem.empty()) {
        char hex[16];
        std::snprintf(hex, sizeof hex, "0x%04x", err);
        problem = std::string("GL error ") + hex + " while creating the buffer";
    }
    if (!problem.empty()) {
        releaseGl();  // a throwing constructor runs no destructor
        throw std::runtime_error("idbuffer-gl: " + problem);
    }
}

IdBufferGl::~IdBufferGl() { releaseGl(); }

void IdBufferGl::releaseGl() {
    if (!m_gl || !m_gl->alive()) return;  // the context is gone, and its objects with it
    dropPending();
    for (GLuint* buffer : {&m_pbo, &m_vbo, &m_gatherVbo}) {
        if (*buffer) glDeleteBuffers(1, buffer);
    }
    for (GLuint* fbo : {&m_gatherFbo, &m_fbo}) {
        if (*fbo) glDeleteFramebuffers(1, fbo);
    }
    for (GLuint* tex : {&m_gatherTex, &m_tex}) {
        if (*tex) glDeleteTextures(1, tex);
    }
    if (m_vao) glDeleteVertexArrays(1, &m_vao);
    for (GLuint* program : {&m_paintProgram, &m_gatherProgram}) {
        if (*program) glDeleteProgram(*program);
    }
    m_pbo = m_vbo = m_gatherVbo = m_gatherFbo = m_fbo = m_gatherTex = m_tex = m_vao = 0;
    m_paintProgram = m_gatherProgram = 0;
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

// One draw call for the queued triangles, from a buffer object.
void IdBufferGl::submit() {
    if (m_vertices.empty()) return;
    glUseProgram(m_paintProgram);
    glUniform2f(m_uPaintTarget, static_cast<float>(m_opt.width), static_cast<float>(m_opt.height));
    glBindVertexArray(m_vao);
    glBindBuffer(GL_ARRAY_BUFFER, m_vbo);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m_vertices.size() * sizeof(Vertex)),
                 m_vertices.data(), GL_STREAM_DRAW);
    glEnableVertexAttribArray(0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                          reinterpret_cast<const void*>(offsetof(Vertex, x)));
    glVertexAttribPointer(1, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(Vertex),
                          reinterpret_cast<const void*>(offsetof(Vertex, rgba)));
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(m_vertices.size()));
    ++m_glStats.draws;
    m_glStats.trianglesPainted += m_vertices.size() / 3;
    m_vertices.clear();
    ++m_version;
}

// Brings every pixel up to the mesh: all changed triangles in one draw call (inside a
// GlStateScope, with the ID buffer as the target).
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
    const GlStateScope scope;
    drawInto(m_fbo, m_opt.width, m_opt.height);
    paintPending();
    return readOne(i, j);
}

std::vector<std::int32_t> IdBufferGl::readAll() {
    if (!ready()) return {};
    const std::size_t n = static_cast<std::size_t>(m_opt.width) * m_opt.height;
    std::vector<std::uint8_t> rgba(4 * n);
    {
        const GlStateScope scope;
        drawInto(m_fbo, m_opt.width, m_opt.height);
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
// read: each point is a GL point at its own pixel of the gather target that carries the ID
// texture's texel under the point (shaders::kGatherVertexShader). The read goes into the
// pixel-buffer object; a fence marks it, and takeBatch() fetches it when the ids are needed.
void IdBufferGl::requestBatch(std::int32_t start) {
    const auto t0 = Clock::now();
    const std::int32_t count = batchCount(start);
    m_gatherTexels.resize(2 * static_cast<std::size_t>(count));
    for (std::int32_t k = 0; k < count; ++k) {
        int i = 0, j = 0;
        m_map.pixel(m_order[start + k], m_opt.width, m_opt.height, i, j);  // outside: pixel (0, 0)
        m_gatherTexels[2 * k] = i;
        m_gatherTexels[2 * k + 1] = j;
    }
    const int rows = (count + kGatherWidth - 1) / kGatherWidth;
    drawInto(m_gatherFbo, kGatherWidth, m_gatherRows);
    glUseProgram(m_gatherProgram);
    glUniform2i(m_uGatherTarget, kGatherWidth, m_gatherRows);
    glUniform1i(m_uGatherIds, 0);
    glBindTexture(GL_TEXTURE_2D, m_tex);  // unit 0 (GlStateScope)
    glBindVertexArray(m_vao);
    glBindBuffer(GL_ARRAY_BUFFER, m_gatherVbo);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m_gatherTexels.size() * sizeof(GLint)),
                 m_gatherTexels.data(), GL_STREAM_DRAW);
    glDisableVertexAttribArray(1);
    glEnableVertexAttribArray(0);
    glVertexAttribIPointer(0, 2, GL_INT, 0, nullptr);
    glDrawArrays(GL_POINTS, 0, count);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, m_pbo);
    glReadPixels(0, 0, kGatherWidth, rows, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    m_pending.start = start;
    m_pending.count = count;
    m_pending.readAt = m_paintedAt;  // the pixels show the mesh as it was then
    m_pending.fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    glFlush();  // the fence must reach the GPU, or a wait on it from another point never ends
    ++m_glStats.reads;
    m_glStats.readbackMs += msSince(t0);
}

// The ids of the pending read, copied out of the pixel-buffer object (glGetBufferSubData: the
// same call on desktop GL and WebGL2, which cannot map buffers for reading).
void IdBufferGl::takeBatch() {
    const auto t0 = Clock::now();
    if (m_pending.fence) {
        const auto fence = static_cast<GLsync>(m_pending.fence);
        waitFor(fence);
        glDeleteSync(fence);
        m_pending.fence = nullptr;
    }
    m_readback.resize(4 * static_cast<std::size_t>(m_pending.count));
    glBindBuffer(GL_PIXEL_PACK_BUFFER, m_pbo);
    glGetBufferSubData(GL_PIXEL_PACK_BUFFER, 0, static_cast<GLsizeiptr>(m_readback.size()),
                       m_readback.data());
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    m_windowIds.resize(static_cast<std::size_t>(m_pending.count));
    for (std::int32_t k = 0; k < m_pending.count; ++k)
        m_windowIds[k] = decodeTriangleId(&m_readback[4 * static_cast<std::size_t>(k)]);
    m_window = m_pending;
    m_pending = {};
    m_glStats.pixelsRead += static_cast<std::uint64_t>(m_window.count);
    m_glStats.readbackMs += msSince(t0);
}

void IdBufferGl::dropPending() {
    if (m_pending.fence && m_gl && m_gl->alive())
        glDeleteSync(static_cast<GLsync>(m_pending.fence));
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
        const GlStateScope scope;
        drawInto(m_fbo, m_opt.width, m_opt.height);
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
            drawInto(m_fbo, m_opt.width, m_opt.height);
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
        const GlStateScope scope;
        drawInto(m_fbo, m_opt.width, m_opt.height);
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
