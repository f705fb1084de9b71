// MeshRenderer: the mesh in screen space, as GL vertex arrays (sparse) or a CPU raster (dense).
#include "ui/gl/mesh_renderer.h"

#include "ui/gl/gl_api.h"
#include "ui/gl/shaders.h"

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

// Screen positions can be anywhere (a vertex far off the canvas at high zoom): clamp to a range
// where float arithmetic and the rasterizer's loops stay sane; culling drops what is outside.
float clampCoord(double v) { return static_cast<float>(std::clamp(v, -1e7, 1e7)); }

}  // namespace

bool MeshRenderer::update(const Engine& engine, const View& view, const MeshStyle& style) {
    m_context = engine.glContext();
    if (engine.version() == m_version && sameView(view, m_view) && sameStyle(style, m_style))
        return false;
    const auto t0 = std::chrono::steady_clock::now();
    m_version = engine.version();
    m_view = view;
    m_style = style;
    ++m_built;
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

enum Shape : GLint { kTriangles = 0, kSegments = 1, kSquares = 2, kImage = 3 };

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
        if (m_gl.texture) glDeleteTextures(1, &m_gl.texture);
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
        m_gl.uRect = glGetUniformLocation(p, "uRect");
        m_gl.uColour = glGetUniformLocation(p, "uColour");
        m_gl.uImage = glGetUniformLocation(p, "uImage");
    }
    if (m_gl.failed) return false;
    glUseProgram(m_gl.program);
    glBindVertexArray(m_gl.vertexArray);
    glBindBuffer(GL_ARRAY_BUFFER, m_gl.buffer);
    if (m_gl.uploaded != m_built) upload();
    return true;
}

// The arrays of the last rebuild into the one vertex buffer (sparse), or the raster into the
// texture (dense).
void MeshRenderer::upload() {
    m_gl.uploaded = m_built;
    if (m_dense) {
        if (m_rasterDirty) {
            uploadRgbaTexture(m_gl.texture, m_gl.textureW, m_gl.textureH, m_rasterW, m_rasterH,
                              m_raster.data());
            m_rasterDirty = false;
        }
        return;
    }
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
        if (m_dense || m_fill.empty()) return;
        glUniform1i(m_gl.uShape, kTriangles);
        setColourUniform(m_gl.uColour, s.fill);
        glDisableVertexAttribArray(1);
        glEnableVertexAttribArray(0);
        glVertexAttribDivisor(0, 0);
        glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, floatOffset(0));
        glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(m_fill.size() / 2));
        return;
    }
    if (m_dense) {
        drawRaster();
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

void MeshRenderer::drawRaster() {
    if (m_gl.texture == 0) return;
    glUniform1i(m_gl.uShape, kImage);
    glUniform1i(m_gl.uImage, 0);
    const float x = static_cast<float>(m_view.origin.x), y = static_cast<float>(m_view.origin.y);
    glUniform4f(m_gl.uRect, x, y, x + static_cast<float>(m_rasterW),
                y + static_cast<float>(m_rasterH));
    glBindTexture(GL_TEXTURE_2D, m_gl.texture);
    glDisableVertexAttribArray(0);
    glDisableVertexAttribArray(1);
    glDrawArrays(GL_TRIANGLES, 0, 6);
}

}  // namespace dlab::ui
