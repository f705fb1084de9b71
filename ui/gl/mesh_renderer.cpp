// MeshRenderer: the mesh in screen space, as GL vertex arrays (sparse) or a CPU raster (dense).
#include "ui/gl/mesh_renderer.h"

#include "ui/gl/gl_api.h"
#include "ui/gl/shaders.h"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

namespace dlab::ui {

namespace {

bool sameView(const View& a, const View& b) {
    return a.center == b.center && a.scale == b.scale && a.origin == b.origin && a.size == b.size;
}

bool sameStyle(const MeshStyle& a, const MeshStyle& b) {
    return a.fill == b.fill && a.edge == b.edge && a.virtualEdge == b.virtualEdge &&
           a.point == b.point && a.pending == b.pending && a.background == b.background &&
           a.edgeWidth == b.edgeWidth && a.pointSize == b.pointSize && a.drawFill == b.drawFill &&
           a.drawVirtual == b.drawVirtual && a.drawPoints == b.drawPoints;
}

// `colour` (ImU32, ABGR) blended over the opaque `background` as GL blends: an opaque colour.
std::uint32_t over(std::uint32_t colour, std::uint32_t background) {
    const std::uint32_t a = colour >> 24;
    std::uint32_t out = 0xFF000000u;
    for (int shift = 0; shift < 24; shift += 8) {
        const std::uint32_t c = (colour >> shift) & 0xFF, b = (background >> shift) & 0xFF;
        out |= ((c * a + b * (255 - a) + 127) / 255) << shift;
    }
    return out;
}

// 1 / steps (0 for 0), from a table for the short edges a dense mesh is made of.
float reciprocal(int steps) {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 1; i < 256; ++i) t[i] = 1.0f / static_cast<float>(i);
        return t;
    }();
    return steps < 256 ? table[steps] : 1.0f / static_cast<float>(steps);
}

// The raster covers the canvas: a fractional width or height takes one pixel more.
int rasterSize(double canvasPixels) {
    return std::max(1, static_cast<int>(std::ceil(canvasPixels)));
}

// Screen positions can be anywhere (a vertex far off the canvas at high zoom): clamp to a range
// where float arithmetic and the rasterizer's loops stay sane; culling drops what is outside.
float clampCoord(double v) { return static_cast<float>(std::clamp(v, -1e7, 1e7)); }

bool g_patching = true;

// The edges and triangles the renderer draws, over the screen positions of the last update.
struct MeshScan {
    const Mesh& m;
    const std::vector<float>& xy;
    bool ghostMode, running, drawVirtual;
    bool hideVirtual;           // virtual triangles are not drawn
    std::int32_t firstVirtual;  // vertices from here on are virtual
    float left, top, right, bottom;

    MeshScan(const Engine& engine, const std::vector<float>& screen, const View& view,
             const MeshStyle& style)
        : m(engine.mesh()),
          xy(screen),
          ghostMode(engine.inserter().options().boundary == Boundary::Exact),
          running(engine.showsVirtual()),
          drawVirtual(style.drawVirtual),
          hideVirtual(running && (ghostMode || !drawVirtual)),
          firstVirtual(engine.inserter().firstVirtual()),
          left(static_cast<float>(view.origin.x)),
          top(static_cast<float>(view.origin.y)),
          right(left + static_cast<float>(view.size.x)),
          bottom(top + static_cast<float>(view.size.y)) {}

    bool isVirtual(std::int32_t v) const { return v >= firstVirtual; }
    bool virtualTriangle(std::int32_t t) const {
        return isVirtual(m.V[3 * t]) || isVirtual(m.V[3 * t + 1]) || isVirtual(m.V[3 * t + 2]);
    }
    bool skipped(std::int32_t t) const { return hideVirtual && virtualTriangle(t); }
    bool visible(std::int32_t a, std::int32_t b) const {
        const float x0 = xy[2 * a], y0 = xy[2 * a + 1], x1 = xy[2 * b], y1 = xy[2 * b + 1];
        return std::max(x0, x1) >= left && std::min(x0, x1) <= right && std::max(y0, y1) >= top &&
               std::min(y0, y1) <= bottom;
    }
    // Each edge once: from its lower corner, unless the other side is not drawn. (The triangle
    // across the edge ab of a drawn triangle is virtual when its third vertex, V[o], is: a and b
    // are not.)
    template <class F>
    void forEachEdge(F&& f) const {
        const std::int32_t* V = m.V.data();
        const std::int32_t* O = m.O.data();
        for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
            if (skipped(t)) continue;
            const std::int32_t v[3] = {V[3 * t], V[3 * t + 1], V[3 * t + 2]};
            for (int k = 0; k < 3; ++k) {
                const std::int32_t c = 3 * t + k, o = O[c];
                if (o != kNone && o < c && !(hideVirtual && isVirtual(V[o]))) continue;
                const std::int32_t a = v[k == 2 ? 0 : k + 1], b = v[k == 0 ? 2 : k - 1];
                if (visible(a, b)) f(a, b, running && (isVirtual(a) || isVirtual(b)));
            }
        }
    }
    // Whether vertex v has no position on the screen (the ghost vertex).
    bool placeholder(std::int32_t v) const { return ghostMode && isVirtual(v); }
};

}  // namespace

void MeshRenderer::setPatching(bool on) { g_patching = on; }

bool MeshRenderer::update(const Engine& engine, const View& view, const MeshStyle& style) {
    // The engine's device is a GlContext wherever a MeshRenderer exists (the GL renderer made
    // both).
    m_context = std::static_pointer_cast<GlContext>(engine.glContext());
    const bool sameLook = sameView(view, m_view) && sameStyle(style, m_style);
    if (engine.version() == m_version && sameLook) return false;
    const auto t0 = std::chrono::steady_clock::now();
    const bool wasDense = m_dense;
    m_version = engine.version();
    m_view = view;
    m_style = style;
    ++m_built;
    screenPositions(engine.mesh(), view);
    const MeshScan scan(engine, m_xy, view, style);
    // Points cost llvmpipe a primitive each too: with enough of them the raster is certain, and
    // its drawing counts the visible edges.
    const std::size_t points = style.drawPoints ? engine.points().size() : 0;
    m_visibleEdges = 0;
    if (points <= kDenseEdges)
        scan.forEachEdge([&](std::int32_t, std::int32_t, bool) { ++m_visibleEdges; });
    m_dense = m_visibleEdges + points > kDenseEdges;
    m_visibleEdges = 0;
    m_patched = false;
    if (m_dense) {
        m_patched = g_patching && sameLook && wasDense && patchRaster(engine);
        if (!m_patched) drawRasterAll(engine, false);
    } else {
        buildArrays(engine);
    }
    if (!m_dense) m_visibleEdges = (m_edges.size() + m_virtualEdges.size()) / 4;
    m_run = engine.run();
    m_position = engine.position();
    m_currentVertex = engine.currentVertex();
    m_running = scan.running;
    m_buildMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return true;
}

// Screen positions of every vertex (the ghost vertex has a placeholder, never drawn).
void MeshRenderer::screenPositions(const Mesh& m, const View& view) {
    m_xy.resize(2 * static_cast<std::size_t>(m.numVertices()));
    for (std::int32_t v = 0; v < m.numVertices(); ++v) {
        const glm::dvec2 s = view.toScreen(m.G[v]);
        m_xy[2 * v] = clampCoord(s.x);
        m_xy[2 * v + 1] = clampCoord(s.y);
    }
}

// Sparse mode: the fill, edges and points as vertex arrays, culled to the canvas.
void MeshRenderer::buildArrays(const Engine& engine) {
    m_fill.clear();
    m_edges.clear();
    m_virtualEdges.clear();
    m_points.clear();
    m_pending.clear();
    const MeshScan scan(engine, m_xy, m_view, m_style);
    const Mesh& m = scan.m;
    const std::vector<float>& xy = m_xy;
    auto push = [&](std::vector<float>& out, std::int32_t v) {
        out.push_back(xy[2 * v]);
        out.push_back(xy[2 * v + 1]);
    };
    if (m_style.drawFill) {
        for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
            if (scan.running && scan.virtualTriangle(t)) continue;
            const std::int32_t a = m.V[3 * t], b = m.V[3 * t + 1], c = m.V[3 * t + 2];
            if (!scan.visible(a, b) && !scan.visible(b, c) && !scan.visible(c, a)) {
                // A triangle can cover the canvas with all its edges outside: keep it if its box
                // overlaps the canvas.
                const float x0 = std::min({xy[2 * a], xy[2 * b], xy[2 * c]}),
                            x1 = std::max({xy[2 * a], xy[2 * b], xy[2 * c]});
                const float y0 = std::min({xy[2 * a + 1], xy[2 * b + 1], xy[2 * c + 1]});
                const float y1 = std::max({xy[2 * a + 1], xy[2 * b + 1], xy[2 * c + 1]});
                if (x1 < scan.left || x0 > scan.right || y1 < scan.top || y0 > scan.bottom)
                    continue;
            }
            push(m_fill, a);
            push(m_fill, b);
            push(m_fill, c);
        }
    }
    scan.forEachEdge([&](std::int32_t a, std::int32_t b, bool virt) {
        std::vector<float>& out = virt ? m_virtualEdges : m_edges;
        push(out, a);
        push(out, b);
    });
    if (m_style.drawPoints) {
        const auto& states = engine.pointStates();
        for (std::size_t i = 0; i < states.size(); ++i) {
            if (states[i] == Engine::PointState::Inserted)
                push(m_points, static_cast<std::int32_t>(i));
            if (states[i] == Engine::PointState::Pending)
                push(m_pending, static_cast<std::int32_t>(i));
        }
    }
}

// Dense mode: every edge and point into the raster, in one order. `masked`: only the pixels of
// dirty tiles are written (the rest is left as it is), and only what can reach them is drawn.
void MeshRenderer::drawRasterAll(const Engine& engine, bool masked) {
    const MeshScan scan(engine, m_xy, m_view, m_style);
    const float left = scan.left, top = scan.top;
    const std::vector<float>& xy = m_xy;
    if (!masked) {
        m_rasterW = rasterSize(m_view.size.x);
        m_rasterH = rasterSize(m_view.size.y);
        m_raster.assign(static_cast<std::size_t>(m_rasterW) * m_rasterH, m_style.background);
        for (Rows& r : m_stale) r = {0, m_rasterH};
    }
    m_masked = masked;
    m_visibleEdges = 0;
    const std::uint32_t bg = m_style.background;
    const std::uint32_t edge = over(m_style.edge, bg), virtualEdge = over(m_style.virtualEdge, bg),
                        point = over(m_style.point, bg), pendingPoint = over(m_style.pending, bg);
    scan.forEachEdge([&](std::int32_t a, std::int32_t b, bool virt) {
        ++m_visibleEdges;
        const float x0 = xy[2 * a] - left, y0 = xy[2 * a + 1] - top;
        const float x1 = xy[2 * b] - left, y1 = xy[2 * b + 1] - top;
        // Two pixels of margin: the DDA's float steps may end a pixel past an endpoint.
        if (masked && !boxDirty(std::min(x0, x1) - 2, std::min(y0, y1) - 2, std::max(x0, x1) + 2,
                                std::max(y0, y1) + 2))
            return;
        rasterLine(x0, y0, x1, y1, virt ? virtualEdge : edge);
    });
    if (m_style.drawPoints) {
        const auto& states = engine.pointStates();
        for (std::size_t i = 0; i < states.size(); ++i) {
            const bool pending = states[i] == Engine::PointState::Pending;
            if (!pending && states[i] != Engine::PointState::Inserted) continue;
            const float x = xy[2 * i] - left, y = xy[2 * i + 1] - top;
            if (masked && !boxDirty(x - 2, y - 2, x + 2, y + 2)) continue;
            rasterDot(x, y, 2, pending ? pendingPoint : point);
        }
    }
    m_masked = false;
}

// Redraws only the tiles that the operations since the last update touched: the triangles whose
// corners changed cover, before and after, the same part of the plane, and the points whose
// state changed are the operations' vertices. False (nothing done) when a full rebuild is due:
// another run, no history, the end of the run (virtual triangles go), or most tiles dirty.
bool MeshRenderer::patchRaster(const Engine& engine) {
    const Journal* journal = engine.journal();
    if (!journal || engine.editor() || engine.run() != m_run || m_running != engine.showsVirtual())
        return false;
    if (m_rasterW != rasterSize(m_view.size.x) || m_rasterH != rasterSize(m_view.size.y))
        return false;
    if (!markChanges(engine)) return false;
    int y0 = m_tilesH, y1 = -1;
    for (int ty = 0; ty < m_tilesH; ++ty) {
        for (int tx = 0; tx < m_tilesW; ++tx) {
            if (!m_tiles[ty * m_tilesW + tx]) continue;
            y0 = std::min(y0, ty);
            y1 = std::max(y1, ty);
            for (int y = ty * kTile; y < std::min(m_rasterH, (ty + 1) * kTile); ++y) {
                std::uint32_t* row = m_raster.data() + static_cast<std::size_t>(y) * m_rasterW;
                std::fill(row + tx * kTile, row + std::min(m_rasterW, (tx + 1) * kTile),
                          m_style.background);
            }
        }
    }
    drawRasterAll(engine, true);  // with no dirty tile it only counts the visible edges
    if (y1 >= 0) {
        for (Rows& r : m_stale) r.add(y0 * kTile, std::min(m_rasterH, (y1 + 1) * kTile));
    }
    return true;
}

// Marks the tiles of every triangle and point that the journal's operations between the last
// update's position and now touched. False when a full rebuild is cheaper or needed.
bool MeshRenderer::markChanges(const Engine& engine) {
    const Journal& journal = *engine.journal();
    const std::size_t lo = std::min(m_position, engine.position()),
                      hi = std::max(m_position, engine.position());
    const Mesh& m = engine.mesh();
    if (hi > journal.recorded()) return false;
    m_tilesW = (m_rasterW + kTile - 1) / kTile;
    m_tilesH = (m_rasterH + kTile - 1) / kTile;
    m_tiles.assign(static_cast<std::size_t>(m_tilesW) * m_tilesH, 0);
    m_dirtyTiles = 0;
    const MeshScan scan(engine, m_xy, m_view, m_style);
    const float left = scan.left, top = scan.top;
    auto markPoint = [&](std::int32_t v) {
        if (v < 0 || v >= m.numVertices() || scan.placeholder(v)) return;
        const float x = m_xy[2 * v] - left, y = m_xy[2 * v + 1] - top;
        markBox(x - 2, y - 2, x + 2, y + 2);
    };
    markPoint(m_currentVertex);
    markPoint(engine.currentVertex());
    std::size_t changes = 0;
    // Most of the canvas dirty: a full rebuild is cheaper (known as soon as it happens).
    auto most = [&] { return 2 * m_dirtyTiles > m_tiles.size(); };
    for (std::size_t i = lo; i < hi; ++i) {
        const Op& op = journal.ops()[i];
        if (op.type == OpType::Finalize || most()) return false;
        changes += op.numChanges;
        // The masked redraw still visits every edge: past a few changes a corner, drawing the
        // raster whole is cheaper than marking and testing tiles.
        if (8 * changes > static_cast<std::size_t>(m.numCorners())) return false;
        markPoint(op.vertex);
        for (std::uint32_t k = 0; k < op.numChanges; ++k) {
            const std::int32_t t = tri(journal.changes()[op.firstChange + k].corner());
            if (t >= m.numTriangles()) continue;  // removed by stepping back
            float x0 = 1e30f, y0 = 1e30f, x1 = -1e30f, y1 = -1e30f;
            for (int j = 0; j < 3; ++j) {
                const std::int32_t v = m.V[3 * t + j];
                if (v < 0 || scan.placeholder(v)) continue;
                x0 = std::min(x0, m_xy[2 * v] - left);
                x1 = std::max(x1, m_xy[2 * v] - left);
                y0 = std::min(y0, m_xy[2 * v + 1] - top);
                y1 = std::max(y1, m_xy[2 * v + 1] - top);
            }
            markBox(x0 - 2, y0 - 2, x1 + 2, y1 + 2);  // the DDA may end a pixel past a vertex
        }
    }
    return !most();
}

namespace {

// The tile range [t0, t1] that pixels from a to b (inclusive, as float coordinates truncated)
// fall in, clamped to [0, n); false when none does.
bool tileRange(float a, float b, int pixels, int n, int& t0, int& t1) {
    if (b < 0 || a >= static_cast<float>(pixels) || a > b) return false;
    const int p0 = std::max(0, static_cast<int>(std::max(a, -1.0f)));
    const int p1 = std::min(pixels - 1, static_cast<int>(std::min(b, 1e7f)));
    t0 = std::min(n - 1, p0 / MeshRenderer::kTile);
    t1 = std::min(n - 1, p1 / MeshRenderer::kTile);
    return true;
}

}  // namespace

void MeshRenderer::markBox(float x0, float y0, float x1, float y1) {
    int tx0 = 0, tx1 = 0, ty0 = 0, ty1 = 0;
    if (!tileRange(x0, x1, m_rasterW, m_tilesW, tx0, tx1) ||
        !tileRange(y0, y1, m_rasterH, m_tilesH, ty0, ty1))
        return;
    for (int ty = ty0; ty <= ty1; ++ty) {
        for (int tx = tx0; tx <= tx1; ++tx) {
            std::uint8_t& tile = m_tiles[static_cast<std::size_t>(ty) * m_tilesW + tx];
            m_dirtyTiles += tile == 0;
            tile = 1;
        }
    }
}

bool MeshRenderer::boxDirty(float x0, float y0, float x1, float y1) const {
    int tx0 = 0, tx1 = 0, ty0 = 0, ty1 = 0;
    if (!tileRange(x0, x1, m_rasterW, m_tilesW, tx0, tx1) ||
        !tileRange(y0, y1, m_rasterH, m_tilesH, ty0, ty1))
        return false;
    for (int ty = ty0; ty <= ty1; ++ty) {
        for (int tx = tx0; tx <= tx1; ++tx) {
            if (m_tiles[ty * m_tilesW + tx]) return true;
        }
    }
    return false;
}

// Bresenham-style DDA over the longer axis; clipped to the raster.
void MeshRenderer::rasterLine(float x0, float y0, float x1, float y1, std::uint32_t colour) {
    const float dx = x1 - x0, dy = y1 - y0;
    const int steps = static_cast<int>(std::ceil(std::max(std::fabs(dx), std::fabs(dy))));
    if (steps > 4 * (m_rasterW + m_rasterH)) {
        // A long edge (mostly off the canvas): clip it to the raster first.
        const float tx0 = dx != 0 ? (0 - x0) / dx : -1e9f,
                    tx1 = dx != 0 ? (m_rasterW - x0) / dx : 1e9f;
        const float ty0 = dy != 0 ? (0 - y0) / dy : -1e9f,
                    ty1 = dy != 0 ? (m_rasterH - y0) / dy : 1e9f;
        const float t0 = std::max({0.0f, std::min(tx0, tx1), std::min(ty0, ty1)});
        const float t1 = std::min({1.0f, std::max(tx0, tx1), std::max(ty0, ty1)});
        if (t0 >= t1) return;
        rasterLine(x0 + dx * t0, y0 + dy * t0, x0 + dx * (t0 + (t1 - t0) * 0.999f),
                   y0 + dy * (t0 + (t1 - t0) * 0.999f), colour);
        return;
    }
    const float inverse = reciprocal(steps);
    const float sx = dx * inverse, sy = dy * inverse;
    float x = x0, y = y0;
    if (!m_masked && std::min(x0, x1) >= 0 && std::min(y0, y1) >= 0 &&
        std::max(x0, x1) < static_cast<float>(m_rasterW - 1) &&
        std::max(y0, y1) < static_cast<float>(m_rasterH - 1)) {
        // Inside, with a pixel of margin for the float steps: the pixels of put(), untested.
        std::uint32_t* const raster = m_raster.data();
        const std::size_t w = static_cast<std::size_t>(m_rasterW);
        for (int i = 0; i <= steps; ++i, x += sx, y += sy)
            raster[static_cast<std::size_t>(static_cast<int>(y)) * w + static_cast<int>(x)] =
                colour;
        return;
    }
    for (int i = 0; i <= steps; ++i, x += sx, y += sy) {
        put(static_cast<int>(x), static_cast<int>(y), colour);
    }
}

void MeshRenderer::rasterDot(float x, float y, int size, std::uint32_t colour) {
    const int px = static_cast<int>(x) - size / 2, py = static_cast<int>(y) - size / 2;
    if (!m_masked && px >= 0 && py >= 0 && px + size <= m_rasterW && py + size <= m_rasterH) {
        for (int j = py; j < py + size; ++j)
            std::fill_n(m_raster.data() + static_cast<std::size_t>(j) * m_rasterW + px, size,
                        colour);
        return;
    }
    for (int j = std::max(0, py); j < std::min(m_rasterH, py + size); ++j) {
        for (int i = std::max(0, px); i < std::min(m_rasterW, px + size); ++i) put(i, j, colour);
    }
}

void MeshRenderer::enqueue(ImDrawList* drawList, Pass pass, float x0, float y0, float x1,
                           float y1) {
    if (m_dense) {
        if (pass == Pass::Lines) enqueueRaster(drawList, x0, y0, x1, y1);
        return;
    }
    m_clip[0] = x0;
    m_clip[1] = y0;
    m_clip[2] = x1;
    m_clip[3] = y1;
    drawList->AddCallback(reinterpret_cast<ImDrawCallback>(&MeshRenderer::drawCallback),
                          &m_passes[pass == Pass::Fill ? 0 : 1]);
}

// Dense mode: the raster goes to a texture now (the frame's GL context is current while ImGui
// builds it) and ImGui draws it as an image, with blending off: the raster is opaque, so the
// canvas is one unblended quad for llvmpipe to fill instead of a background under a blended one.
void MeshRenderer::enqueueRaster(ImDrawList* drawList, float x0, float y0, float x1, float y1) {
    {
        const GlStateScope scope;
        if (!prepareGl()) return;
        uploadRaster();
    }
    const unsigned texture = m_gl.texture[m_gl.shown];
    drawList->PushClipRect(ImVec2(x0, y0), ImVec2(x1, y1), true);
    if (texture == 0) {  // no GL: the background at least
        drawList->AddRectFilled(ImVec2(x0, y0), ImVec2(x1, y1), m_style.background);
        drawList->PopClipRect();
        return;
    }
    const float x = static_cast<float>(m_view.origin.x), y = static_cast<float>(m_view.origin.y);
    drawList->AddCallback([](const ImDrawList*, const ImDrawCmd*) { glDisable(GL_BLEND); },
                          nullptr);
    drawList->AddImage(
        reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(texture)), ImVec2(x, y),
        ImVec2(x + static_cast<float>(m_rasterW), y + static_cast<float>(m_rasterH)));
    drawList->AddCallback(ImDrawCallback_ResetRenderState, nullptr);
    drawList->PopClipRect();
}

// When the texture shown last lacks rows of the raster, the other one receives what it lacks and
// is shown from now on.
void MeshRenderer::uploadRaster() {
    if (m_stale[m_gl.shown].empty() && m_gl.texture[m_gl.shown] != 0) return;
    const int k = 1 - m_gl.shown;
    uploadRgbaTexture(m_gl.texture[k], m_gl.textureW[k], m_gl.textureH[k], m_rasterW, m_rasterH,
                      m_raster.data(), m_stale[k].y0, m_stale[k].y1);
    m_stale[k] = {};
    m_gl.shown = k;
}

void MeshRenderer::drawCallback(const ImDrawList*, const void* cmdPtr) {
    const auto* cmd = static_cast<const ImDrawCmd*>(cmdPtr);
    const auto* data = static_cast<const PassData*>(cmd->UserCallbackData);
    MeshRenderer* self = data->self;
    const ImDrawData* dd = ImGui::GetDrawData();
    const float fbScaleX = dd->FramebufferScale.x, fbScaleY = dd->FramebufferScale.y;
    const float fbH = dd->DisplaySize.y * fbScaleY;
    const float x0 = (self->m_clip[0] - dd->DisplayPos.x) * fbScaleX,
                y0 = (self->m_clip[1] - dd->DisplayPos.y) * fbScaleY;
    const float x1 = (self->m_clip[2] - dd->DisplayPos.x) * fbScaleX,
                y1 = (self->m_clip[3] - dd->DisplayPos.y) * fbScaleY;
    // ImGui's OpenGL3 backend goes on with its own program, vertex array and blending after
    // the callback: everything we set is put back.
    const GlStateScope scope;
    if (!self->prepareGl()) return;
    glEnable(GL_SCISSOR_TEST);
    glScissor(static_cast<GLint>(x0), static_cast<GLint>(fbH - y1), static_cast<GLsizei>(x1 - x0),
              static_cast<GLsizei>(y1 - y0));
    glEnable(GL_BLEND);  // as ImGui blends
    glBlendEquation(GL_FUNC_ADD);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    const float screen[4] = {dd->DisplayPos.x, dd->DisplayPos.y, dd->DisplaySize.x,
                             dd->DisplaySize.y};
    self->drawPass(data->pass, screen);
}

// ============================================================================================
// The GL side
// ============================================================================================

namespace {

enum Shape : GLint { kTriangles = 0, kSegments = 1, kSquares = 2 };

// Where each array starts in the one vertex buffer, in floats.
struct BufferLayout {
    std::size_t fill, virtualEdges, edges, pending, points, total;
};

BufferLayout layoutOf(const std::vector<float>& fill, const std::vector<float>& virtualEdges,
                      const std::vector<float>& edges, const std::vector<float>& pending,
                      const std::vector<float>& points) {
    BufferLayout l{};
    l.fill = 0;
    l.virtualEdges = l.fill + fill.size();
    l.edges = l.virtualEdges + virtualEdges.size();
    l.pending = l.edges + edges.size();
    l.points = l.pending + pending.size();
    l.total = l.points + points.size();
    return l;
}

const void* floatOffset(std::size_t floats) {
    return reinterpret_cast<const void*>(floats * sizeof(float));
}

}  // namespace

MeshRenderer::~MeshRenderer() { releaseGl(); }

// Deletes the GL objects while their context lives (the renderer may outlive it: then they went
// with it).
void MeshRenderer::releaseGl() {
    if (m_gl.context && m_gl.context->alive()) {
        for (unsigned& t : m_gl.texture) {
            if (t) glDeleteTextures(1, &t);
        }
        if (m_gl.buffer) glDeleteBuffers(1, &m_gl.buffer);
        if (m_gl.vertexArray) glDeleteVertexArrays(1, &m_gl.vertexArray);
        if (m_gl.program) glDeleteProgram(m_gl.program);
    }
    m_gl = {};
}

// The program, vertex array and buffer of the engine's context, made on the first draw on it;
// false when there is no live context or the program did not build.
bool MeshRenderer::prepareGl() {
    if (!m_context || !m_context->alive()) return false;
    if (m_gl.context != m_context) {
        releaseGl();
        m_gl.context = m_context;
        std::string error;
        m_gl.program =
            buildProgram(shaders::kMeshVertexShader, shaders::kMeshFragmentShader, error);
        m_gl.failed = m_gl.program == 0;
        if (m_gl.failed) return false;
        glGenVertexArrays(1, &m_gl.vertexArray);
        glGenBuffers(1, &m_gl.buffer);
        const GLuint p = m_gl.program;
        m_gl.uShape = glGetUniformLocation(p, "uShape");
        m_gl.uScreen = glGetUniformLocation(p, "uScreen");
        m_gl.uSize = glGetUniformLocation(p, "uSize");
        m_gl.uColour = glGetUniformLocation(p, "uColour");
    }
    if (m_gl.failed) return false;
    glUseProgram(m_gl.program);
    glBindVertexArray(m_gl.vertexArray);
    glBindBuffer(GL_ARRAY_BUFFER, m_gl.buffer);
    if (m_gl.uploaded != m_built) upload();
    return true;
}

// The arrays of the last rebuild into the one vertex buffer (sparse mode; the dense raster goes
// to its texture in enqueueRaster).
void MeshRenderer::upload() {
    m_gl.uploaded = m_built;
    if (m_dense) return;
    const BufferLayout l = layoutOf(m_fill, m_virtualEdges, m_edges, m_pending, m_points);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(l.total * sizeof(float)), nullptr,
                 GL_DYNAMIC_DRAW);
    auto part = [](std::size_t offset, const std::vector<float>& v) {
        if (v.empty()) return;
        glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(offset * sizeof(float)),
                        static_cast<GLsizeiptr>(v.size() * sizeof(float)), v.data());
    };
    part(l.fill, m_fill);
    part(l.virtualEdges, m_virtualEdges);
    part(l.edges, m_edges);
    part(l.pending, m_pending);
    part(l.points, m_points);
}

void MeshRenderer::drawPass(Pass pass, const float screen[4]) {
    glUniform4f(m_gl.uScreen, screen[0], screen[1], screen[2], screen[3]);
    const MeshStyle& s = m_style;
    if (pass == Pass::Fill) {
        if (m_fill.empty()) return;
        glUniform1i(m_gl.uShape, kTriangles);
        setColourUniform(m_gl.uColour, s.fill);
        glDisableVertexAttribArray(1);
        glEnableVertexAttribArray(0);
        glVertexAttribDivisor(0, 0);
        glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, floatOffset(0));
        glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(m_fill.size() / 2));
        return;
    }
    const BufferLayout l = layoutOf(m_fill, m_virtualEdges, m_edges, m_pending, m_points);
    drawInstances(kSegments, l.virtualEdges, m_virtualEdges.size() / 4, s.virtualEdge, s.edgeWidth);
    drawInstances(kSegments, l.edges, m_edges.size() / 4, s.edge, s.edgeWidth);
    drawInstances(kSquares, l.pending, m_pending.size() / 2, s.pending, s.pointSize);
    drawInstances(kSquares, l.points, m_points.size() / 2, s.point, s.pointSize);
}

// Edges (segments) or points (squares) as instanced quads: six vertices an instance, the
// instance's floats from `offset` in the vertex buffer.
void MeshRenderer::drawInstances(int shape, std::size_t offset, std::size_t count,
                                 std::uint32_t colour, float size) {
    if (count == 0) return;
    const GLuint attribute = shape == kSegments ? 1 : 0, other = 1 - attribute;
    glUniform1i(m_gl.uShape, shape);
    glUniform1f(m_gl.uSize, size);
    setColourUniform(m_gl.uColour, colour);
    glDisableVertexAttribArray(other);
    glEnableVertexAttribArray(attribute);
    glVertexAttribDivisor(attribute, 1);
    glVertexAttribPointer(attribute, shape == kSegments ? 4 : 2, GL_FLOAT, GL_FALSE, 0,
                          floatOffset(offset));
    glDrawArraysInstanced(GL_TRIANGLES, 0, 6, static_cast<GLsizei>(count));
}

}  // namespace dlab::ui
