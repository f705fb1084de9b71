// The paper's colour-ID buffer on real GL: every triangle painted in its own colour into an
// offscreen framebuffer object, one pixel (or a batch of pixels) read back to start the walk.
//
// Encoding (the paper's, section 4): triangle i is the colour r = (i >> 16) & 255,
// g = (i >> 8) & 255, b = i & 255, a = (i >> 24) & 255; all four bytes 255 mean "no triangle"
// (outside the hull: ghost triangles are never painted). No blending, no dithering, no
// multisampling, flat shading: the colours come back exactly.
//
// After each operation only the triangles that changed are repainted (the inserter reports them;
// their union covers exactly the area that changed). The painting is deferred to the next read,
// so all the changes between two reads go out in one draw call. When the covered area can shrink
// (an undo in the GUI takes a point outside the hull back out), the old footprints of the changed
// triangles are cleared first from a CPU copy of what was painted.
//
// Readback modes:
//   OnePixel   the paper: before each insertion, glReadPixels of the pixel under the point.
//   Batched    the paper's future work: the pixels under the next K points of the insertion
//              order are gathered in one draw (points sampling the ID texture) and read back in
//              one go through a pixel-buffer object. Later points of the batch get ids that are
//              up to K-1 insertions old: a stale id is a triangle near the right one, and the
//              exact walk goes the rest of the way. A batch spans at most four times as many
//              insertions as came before it (the first batches grow 12, 60, 300, ... up to K).
//   Pipelined  Batched, one batch ahead: when batch b starts, its ids (read one batch earlier)
//              are mapped, the ids of batch b+1 are gathered from the texture as it is, and only
//              then are the changes painted, so that the rasterizer (a GPU, or llvmpipe's
//              threads) draws while the CPU inserts. Ids are about 2K to 3K insertions old.
//
// The locator draws on whatever context is current when it is called: an OSMesa context in
// dtlab and the UI tests, the window's context in the GUI, WebGL2 in the browser (mid-frame:
// every piece of GL state it touches is saved and restored, GlStateScope). Shaders paint and
// gather (GLSL 3.30 core or ES 3.00); the batch comes back through glGetBufferSubData, which
// desktop GL and WebGL2 share. The id is only a hint: the inserter checks containment exactly.
#pragma once

#include "core/engine/locator.h"
#include "ui/gl/gl_api.h"
#include "ui/render/renderer.h"
#include "ui/render/triangle_ids.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace dlab {
class Inserter;
}

namespace dlab::ui {

enum class GlReadback : std::uint8_t { OnePixel, Batched, Pipelined };
const char* toString(GlReadback mode);

struct IdBufferGlOptions {
    int width = 1600, height = 1600;  // the paper's box
    GlReadback readback = GlReadback::OnePixel;
    int batch = 256;  // Batched / Pipelined: points per readback (K), 1 .. kMaxBatch
    static constexpr int kMaxBatch = 1 << 16;
    // idbuffer-gl: one pixel per insertion; idbuffer-gl-batched: Batched with
    // options.idBufferBatch.
    static IdBufferGlOptions from(LocatorKind kind, const LocatorOptions& options);
};

struct IdBufferGlStats {
    std::uint64_t reads = 0;       // readbacks that waited for the drawing (one per batch)
    std::uint64_t pixelsRead = 0;  // ids fetched for the locator
    std::uint64_t draws = 0;       // paint draw calls
    std::uint64_t trianglesPainted = 0;
    std::uint64_t trianglesCleared = 0;  // old footprints cleared (undo shrinking the hull)
    double pixelsPainted = 0;            // area of the painted triangles, in pixels (clipped: less)
    std::uint64_t fullRepaints = 0;
    double readbackMs = 0;  // in glReadPixels / gather / fence wait / map: includes the wait for
                            // the drawing that the read forces (as the paper measured it)
    double paintMs = 0;     // GL state save/restore, vertex arrays and draw submission
    // Hints by the age of their id: fresh = read after the last insertion; stale = read ahead.
    std::uint64_t freshQueries = 0, freshHits = 0, freshSteps = 0;
    std::uint64_t staleQueries = 0, staleHits = 0, staleSteps = 0, staleAgeSum = 0;
    std::uint64_t noPixel = 0;  // no triangle under the point (outside the hull) or a vanished id
};

class IdBufferGl final : public GpuIdBuffer {
public:
    // Needs the context current. Throws std::runtime_error (one line) when the context cannot
    // hold the buffer (size beyond the GL limits, incomplete framebuffer).
    IdBufferGl(std::shared_ptr<GlContext> gl, const IdBufferGlOptions& options = {});
    ~IdBufferGl() override;
    IdBufferGl(const IdBufferGl&) = delete;
    IdBufferGl& operator=(const IdBufferGl&) = delete;

    // ---- Locator -------------------------------------------------------------------------------
    std::string name() const override;
    void reset(const LocatorContext& ctx, const Bounds& bounds) override;
    std::int32_t hint(Vec2 p, std::int32_t lastTriangle) override;
    bool wantsChanges() const override { return true; }
    void trianglesChanged(const std::int32_t* tris, int count) override;
    void resync() override;
    void located(Vec2 p, std::int32_t found, std::int32_t steps) override;

    // The points in insertion order, so that the batched modes can read ahead. Call it after
    // the Inserter is built and before it runs (its order is fixed by then).
    void followOrder(const Inserter& inserter) override;
    void setInsertionOrder(std::vector<Vec2> pointsInOrder);

    // ---- Read API (the ID-buffer view panel, tests). Each read first paints what is pending, so
    // it sees the mesh as it is now; each one waits for the drawing (a sync, ~0.1 ms on llvmpipe).
    int width() const override { return m_opt.width; }
    int height() const override { return m_opt.height; }
    bool ready() const override;      // reset() happened and the context is alive
    std::int32_t idAt(int i, int j);  // pixel (i, j), row 0 = lowest y; kNone: no triangle
    std::vector<std::int32_t> readAll() override;  // width*height ids, row 0 = lowest y
    // The pixel under p; false when p lies outside the box (left of or below it).
    bool pixelOf(Vec2 p, int& i, int& j) const {
        return m_map.pixel(p, m_opt.width, m_opt.height, i, j);
    }
    Vec2 pixelCentre(int i, int j) const override { return m_map.centre(i, j); }
    const PixelMap& map() const { return m_map; }
    unsigned texture() const { return m_tex; }  // GL_RGBA8, the encoded ids (for a GL viewer)
    std::uint64_t version() const override { return m_version; }  // bumps when pixels changed
    const IdBufferGlOptions& options() const { return m_opt; }
    const IdBufferGlStats& glStats() const { return m_glStats; }

private:
    struct Batch {
        std::int32_t start = 0, count = 0;  // positions in the insertion order
        std::uint64_t readAt = 0;           // hints served before the read
        void* fence = nullptr;              // Pipelined: GLsync of the pending read
    };

    void releaseGl();
    bool paintable(std::int32_t t) const;
    void corners(std::int32_t t, float* xy) const;  // pixel coordinates, as GL gets them
    void growShadow(std::int32_t triangles);
    void paintShape(std::int32_t t);
    void appendTriangle(std::uint32_t colour, const float* xy);
    void submit();
    void paintPending();  // inside a Scope: every changed triangle
    std::int32_t batchCount(std::int32_t start) const;
    std::int32_t readOne(int i, int j);     // inside a Scope, painted
    void requestBatch(std::int32_t start);  // inside a Scope: gather + read into the PBO
    void takeBatch();                       // the PBO's ids into m_window
    void dropPending();
    bool findInOrder(Vec2 p);
    std::int32_t windowId(int& age);

    std::shared_ptr<GlContext> m_gl;
    IdBufferGlOptions m_opt;
    LocatorContext m_ctx;
    bool m_reset = false;
    PixelMap m_map;
    GLuint m_tex = 0, m_fbo = 0, m_gatherTex = 0, m_gatherFbo = 0, m_pbo = 0;
    GLuint m_vao = 0, m_vbo = 0, m_gatherVbo = 0, m_paintProgram = 0, m_gatherProgram = 0;
    GLint m_uPaintTarget = -1, m_uGatherTarget = -1, m_uGatherIds = -1;
    int m_gatherRows = 0;

    // What was painted: per triangle its pixel-space corners (6 floats) and whether it is shown.
    std::vector<float> m_shadow;
    std::vector<std::uint8_t> m_shown;
    std::int32_t m_shadowTriangles = 0;  // triangles the shadow covers
    std::vector<std::int32_t> m_dirty;   // changed since painted
    std::vector<std::uint8_t> m_isDirty;
    bool m_fullRepaint = true;
    std::int32_t m_seenVertices = 0;  // |G| at the last paint (Finalize changes it unseen)
    struct Vertex {
        float x, y;          // pixel coordinates
        std::uint32_t rgba;  // the encoded id, bytes in memory order r, g, b, a
    };
    std::vector<Vertex> m_vertices;  // the triangles of one draw

    // Read-ahead along the insertion order.
    std::vector<Vec2> m_order;
    std::int32_t m_next = 0;  // predicted position of the next hint
    Batch m_window;           // ids at hand: positions [start, start + count)
    std::vector<std::int32_t> m_windowIds;
    Batch m_pending;                       // Pipelined: issued, not mapped yet (count > 0)
    std::vector<GLint> m_gatherTexels;     // per point of a batch: its ID-buffer pixel (i, j)
    std::vector<std::uint8_t> m_readback;  // a batch's pixels as read
    std::uint64_t m_hints = 0;             // hints served since reset()
    std::uint64_t m_paintedAt = 0;         // m_hints at the last paint: the pixels' age
    int m_lastAge = -1;                    // age of the last hint's id (-1: no pixel)

    std::uint64_t m_version = 0;
    IdBufferGlStats m_glStats;
};

}  // namespace dlab::ui
