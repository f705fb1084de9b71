// MeshRenderer: the mesh in screen space, as GL vertex arrays (sparse) or a CPU raster (dense).
#include "ui/gl/mesh_renderer.h"

#include <GL/gl.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace dlab::ui {

namespace {

bool sameView(const View& a, const View& b) {
    return a.center == b.center && a.scale == b.scale && a.origin == b.origin && a.size == b.size;
}

bool sameStyle(const MeshStyle& a, const MeshStyle& b) {
    return a.fill == b.fill && a.edge == b.edge && a.virtualEdge == b.virtualEdge &&
           a.point == b.point && a.pending == b.pending && a.edgeWidth == b.edgeWidth &&
           a.pointSize == b.pointSize && a.drawFill == b.drawFill &&
           a.drawVirtual == b.drawVirtual && a.drawPoints == b.drawPoints;
}

void colour(std::uint32_t c) {
    glColor4ub(static_cast<GLubyte>(c & 0xFF), static_cast<GLubyte>((c >> 8) & 0xFF),
               static_cast<GLubyte>((c >> 16) & 0xFF), static_cast<GLubyte>((c >> 24) & 0xFF));
}

// Screen positions can be anywhere (a vertex far off the canvas at high zoom): clamp to a range
// where float arithmetic and the rasterizer's loops stay sane; culling drops what is outside.
float clampCoord(double v) { return static_cast<float>(std::clamp(v, -1e7, 1e7)); }

}  // namespace

bool MeshRenderer::update(const Engine& engine, const View& view, const MeshStyle& style) {
    if (engine.version() == m_version && sameView(view, m_view) && sameStyle(style, m_style))
        return false;
    const auto t0 = std::chrono::steady_clock::now();
    m_version = engine.version();
    m_view = view;
    m_style = style;
    m_fill.clear();
    m_edges.clear();
    m_virtualEdges.clear();
    m_points.clear();
    m_pending.clear();
    const Mesh& m = engine.mesh();
    const Inserter& ins = engine.inserter();
    const bool ghostMode = ins.options().boundary == Boundary::Exact;
    const bool running = !ins.done();
    const float left = static_cast<float>(view.origin.x), top = static_cast<float>(view.origin.y);
    const float right = left + static_cast<float>(view.size.x),
                bottom = top + static_cast<float>(view.size.y);

    // Screen positions of every vertex, once (the ghost vertex has a placeholder, never drawn).
    std::vector<float> xy(2 * static_cast<std::size_t>(m.numVertices()));
    for (std::int32_t v = 0; v < m.numVertices(); ++v) {
        const glm::dvec2 s = view.toScreen(m.G[v]);
        xy[2 * v] = clampCoord(s.x);
        xy[2 * v + 1] = clampCoord(s.y);
    }
    auto skipped = [&](std::int32_t t) {
        return running && ins.isVirtualTriangle(t) && (ghostMode || !style.drawVirtual);
    };
    auto visible = [&](std::int32_t a, std::int32_t b) {
        const float x0 = xy[2 * a], y0 = xy[2 * a + 1], x1 = xy[2 * b], y1 = xy[2 * b + 1];
        return std::max(x0, x1) >= left && std::min(x0, x1) <= right && std::max(y0, y1) >= top &&
               std::min(y0, y1) <= bottom;
    };
    // Each edge once: from its lower corner, unless the other side is not drawn.
    auto forEachEdge = [&](auto&& f) {
        for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
            if (skipped(t)) continue;
            for (int k = 0; k < 3; ++k) {
                const std::int32_t c = 3 * t + k, o = m.O[c];
                if (o != kNone && o < c && !skipped(tri(o))) continue;
                const std::int32_t a = m.V[next(c)], b = m.V[prev(c)];
                if (visible(a, b)) f(a, b, running && (ins.isVirtual(a) || ins.isVirtual(b)));
            }
        }
    };
    m_visibleEdges = 0;
    forEachEdge([&](std::int32_t, std::int32_t, bool) { ++m_visibleEdges; });
    // Points cost llvmpipe a primitive each too.
    m_dense = m_visibleEdges + (style.drawPoints ? engine.points().size() : 0) > kDenseEdges;

    if (m_dense) {
        m_rasterW = std::max(1, static_cast<int>(view.size.x));
        m_rasterH = std::max(1, static_cast<int>(view.size.y));
        m_raster.assign(static_cast<std::size_t>(m_rasterW) * m_rasterH, 0u);
        forEachEdge([&](std::int32_t a, std::int32_t b, bool virt) {
            rasterLine(xy[2 * a] - left, xy[2 * a + 1] - top, xy[2 * b] - left, xy[2 * b + 1] - top,
                       virt ? style.virtualEdge : style.edge);
        });
        if (style.drawPoints) {
            const auto& states = engine.pointStates();
            for (std::size_t i = 0; i < states.size(); ++i) {
                const bool pending = states[i] == Engine::PointState::Pending;
                if (pending || states[i] == Engine::PointState::Inserted) {
                    rasterDot(xy[2 * i] - left, xy[2 * i + 1] - top, 2,
                              pending ? style.pending : style.point);
                }
            }
        }
        m_rasterDirty = true;
    } else {
        auto push = [&](std::vector<float>& out, std::int32_t v) {
            out.push_back(xy[2 * v]);
            out.push_back(xy[2 * v + 1]);
        };
        if (style.drawFill) {
            for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
                if (skipped(t) || (running && ins.isVirtualTriangle(t))) continue;
                const std::int32_t a = m.V[3 * t], b = m.V[3 * t + 1], c = m.V[3 * t + 2];
                if (!visible(a, b) && !visible(b, c) && !visible(c, a)) {
                    // A triangle can cover the canvas with all its edges outside: keep it if
                    // its box overlaps the canvas.
                    const float x0 = std::min({xy[2 * a], xy[2 * b], xy[2 * c]}),
                                x1 = std::max({xy[2 * a], xy[2 * b], xy[2 * c]});
                    const float y0 = std::min({xy[2 * a + 1], xy[2 * b + 1], xy[2 * c + 1]});
                    const float y1 = std::max({xy[2 * a + 1], xy[2 * b + 1], xy[2 * c + 1]});
                    if (x1 < left || x0 > right || y1 < top || y0 > bottom) continue;
                }
                push(m_fill, a);
                push(m_fill, b);
                push(m_fill, c);
            }
        }
        forEachEdge([&](std::int32_t a, std::int32_t b, bool virt) {
            std::vector<float>& out = virt ? m_virtualEdges : m_edges;
            push(out, a);
            push(out, b);
        });
        if (style.drawPoints) {
            const auto& states = engine.pointStates();
            for (std::size_t i = 0; i < states.size(); ++i) {
                if (states[i] == Engine::PointState::Inserted)
                    push(m_points, static_cast<std::int32_t>(i));
                if (states[i] == Engine::PointState::Pending)
                    push(m_pending, static_cast<std::int32_t>(i));
            }
        }
    }
    m_buildMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return true;
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
    const float sx = steps ? dx / steps : 0, sy = steps ? dy / steps : 0;
    float x = x0, y = y0;
    for (int i = 0; i <= steps; ++i, x += sx, y += sy) {
        const int px = static_cast<int>(x), py = static_cast<int>(y);
        if (px >= 0 && py >= 0 && px < m_rasterW && py < m_rasterH)
            m_raster[static_cast<std::size_t>(py) * m_rasterW + px] = colour;
    }
}

void MeshRenderer::rasterDot(float x, float y, int size, std::uint32_t colour) {
    const int px = static_cast<int>(x) - size / 2, py = static_cast<int>(y) - size / 2;
    for (int j = std::max(0, py); j < std::min(m_rasterH, py + size); ++j) {
        for (int i = std::max(0, px); i < std::min(m_rasterW, px + size); ++i)
            m_raster[static_cast<std::size_t>(j) * m_rasterW + i] = colour;
    }
}

void MeshRenderer::enqueue(ImDrawList* drawList, Pass pass, float x0, float y0, float x1,
                           float y1) {
    m_clip[0] = x0;
    m_clip[1] = y0;
    m_clip[2] = x1;
    m_clip[3] = y1;
    drawList->AddCallback(reinterpret_cast<ImDrawCallback>(&MeshRenderer::drawCallback),
                          &m_passes[pass == Pass::Fill ? 0 : 1]);
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
    // ImGui's OpenGL2 backend sets its array pointers once per draw list, so everything we
    // change must be put back exactly: push the client arrays and the server state we touch.
    glPushClientAttrib(GL_CLIENT_VERTEX_ARRAY_BIT);
    glPushAttrib(GL_ENABLE_BIT | GL_CURRENT_BIT | GL_LINE_BIT | GL_POINT_BIT | GL_SCISSOR_BIT |
                 GL_TEXTURE_BIT);
    glEnable(GL_SCISSOR_TEST);
    glScissor(static_cast<GLint>(x0), static_cast<GLint>(fbH - y1), static_cast<GLsizei>(x1 - x0),
              static_cast<GLsizei>(y1 - y0));
    glDisable(GL_TEXTURE_2D);
    glDisableClientState(GL_TEXTURE_COORD_ARRAY);
    glDisableClientState(GL_COLOR_ARRAY);
    glEnableClientState(GL_VERTEX_ARRAY);
    const MeshStyle& s = self->m_style;
    if (data->pass == Pass::Fill) {
        if (!self->m_dense && !self->m_fill.empty()) {
            colour(s.fill);
            glVertexPointer(2, GL_FLOAT, 0, self->m_fill.data());
            glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(self->m_fill.size() / 2));
        }
    } else if (self->m_dense) {
        self->drawRaster();
    } else {
        self->drawLines();
    }
    glPopAttrib();
    glPopClientAttrib();
}

void MeshRenderer::drawRaster() {
    if (m_texture == 0) glGenTextures(1, &m_texture);
    glBindTexture(GL_TEXTURE_2D, m_texture);
    if (m_rasterDirty) {
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
        if (m_textureW != m_rasterW || m_textureH != m_rasterH) {
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, m_rasterW, m_rasterH, 0, GL_RGBA,
                         GL_UNSIGNED_BYTE, m_raster.data());
            m_textureW = m_rasterW;
            m_textureH = m_rasterH;
        } else {
            glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, m_rasterW, m_rasterH, GL_RGBA, GL_UNSIGNED_BYTE,
                            m_raster.data());
        }
        m_rasterDirty = false;
    }
    glEnable(GL_TEXTURE_2D);
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    const float x = static_cast<float>(m_view.origin.x), y = static_cast<float>(m_view.origin.y);
    const float w = static_cast<float>(m_rasterW), h = static_cast<float>(m_rasterH);
    glBegin(GL_QUADS);
    glTexCoord2f(0, 0);
    glVertex2f(x, y);
    glTexCoord2f(1, 0);
    glVertex2f(x + w, y);
    glTexCoord2f(1, 1);
    glVertex2f(x + w, y + h);
    glTexCoord2f(0, 1);
    glVertex2f(x, y + h);
    glEnd();
}

void MeshRenderer::drawLines() const {
    const MeshStyle& s = m_style;
    glLineWidth(s.edgeWidth);
    if (!m_virtualEdges.empty()) {
        colour(s.virtualEdge);
        glVertexPointer(2, GL_FLOAT, 0, m_virtualEdges.data());
        glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(m_virtualEdges.size() / 2));
    }
    if (!m_edges.empty()) {
        colour(s.edge);
        glVertexPointer(2, GL_FLOAT, 0, m_edges.data());
        glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(m_edges.size() / 2));
    }
    glPointSize(s.pointSize);
    if (!m_pending.empty()) {
        colour(s.pending);
        glVertexPointer(2, GL_FLOAT, 0, m_pending.data());
        glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(m_pending.size() / 2));
    }
    if (!m_points.empty()) {
        colour(s.point);
        glVertexPointer(2, GL_FLOAT, 0, m_points.data());
        glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(m_points.size() / 2));
    }
}

}  // namespace dlab::ui
