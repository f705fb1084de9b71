// Draws big meshes with our own GL code from inside ImGui's render pass: ImGui's OpenGL2
// backend cannot draw one ImDrawList over 64k vertices, and a 100k-point mesh has 300k edges.
//
// Two modes, chosen per rebuild from how many edges are on the canvas:
//   sparse: fixed-function vertex arrays (GL_TRIANGLES for the fill, GL_LINES, GL_POINTS),
//     culled to the canvas, in screen pixels computed in double (exact at any zoom or offset);
//   dense: llvmpipe pays per primitive, so beyond kDenseEdges visible edges and points, they
//     are rasterized on the CPU into one RGBA texture (a few pixel writes per short edge) and
//     drawn as a single quad; the fill is skipped (the edges cover it anyway).
// Arrays and textures are rebuilt only when the mesh (engine version), the view or the style
// changed, so an idle frame costs one draw.
#pragma once

#include "ui/app_state.h"

#include <cstdint>
#include <vector>

struct ImDrawList;

namespace dlab::ui {

struct MeshStyle {
    std::uint32_t fill = 0, edge = 0, virtualEdge = 0, point = 0,
                  pending = 0;  // ImU32 colours (ABGR)
    float edgeWidth = 1.0f, pointSize = 4.0f;
    bool drawFill = true, drawVirtual = true, drawPoints = true;
};

class MeshRenderer {
public:
    static constexpr std::size_t kDenseEdges = 40000;

    MeshRenderer() = default;
    MeshRenderer(const MeshRenderer&) = delete;  // the passes point back at this object
    MeshRenderer& operator=(const MeshRenderer&) = delete;

    // Rebuilds the arrays if the mesh (engine version), the view or the style changed; returns
    // whether it did.
    bool update(const Engine& engine, const View& view, const MeshStyle& style);
    // Adds a GL draw (clipped to the rectangle) to the draw list; it leaves ImGui's GL state as
    // it found it. Two passes, so that highlights can go between the fill and the edges.
    enum class Pass : std::uint8_t { Fill, Lines };
    void enqueue(ImDrawList* drawList, Pass pass, float clipX0, float clipY0, float clipX1,
                 float clipY1);
    bool dense() const { return m_dense; }
    std::size_t visibleEdges() const { return m_visibleEdges; }
    double lastBuildMs() const { return m_buildMs; }

private:
    struct PassData {
        MeshRenderer* self;
        Pass pass;
    };
    static void drawCallback(const ImDrawList* list, const void* cmd);
    void drawLines() const;
    void drawRaster();
    void rasterLine(float x0, float y0, float x1, float y1, std::uint32_t colour);
    void rasterDot(float x, float y, int size, std::uint32_t colour);

    std::vector<float> m_fill, m_edges, m_virtualEdges, m_points, m_pending;
    // Dense mode: RGBA pixels of the canvas, row 0 at the top; uploaded to m_texture when dirty.
    std::vector<std::uint32_t> m_raster;
    int m_rasterW = 0, m_rasterH = 0;
    bool m_dense = false, m_rasterDirty = false;
    unsigned m_texture = 0;  // GL name; freed with the context (the renderer may outlive it)
    int m_textureW = 0, m_textureH = 0;
    std::size_t m_visibleEdges = 0;
    MeshStyle m_style;
    std::uint64_t m_version = ~std::uint64_t{0};
    View m_view;
    float m_clip[4] = {0, 0, 0, 0};
    PassData m_passes[2] = {{this, Pass::Fill}, {this, Pass::Lines}};
    double m_buildMs = 0;
};

}  // namespace dlab::ui
