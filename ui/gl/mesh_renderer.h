// Draws big meshes with our own GL code from inside ImGui's render pass: ImGui draws each draw
// list with 16-bit indices (at most 64k vertices), and a 100k-point mesh has 300k edges.
//
// Two modes, chosen per rebuild from how many edges are on the canvas:
//   sparse: one vertex buffer, culled to the canvas, in screen pixels computed in double (exact
//     at any zoom or offset): the fill as triangles, edges and points as instanced quads that
//     the vertex shader spans (wide lines and big points exist on every target this way);
//   dense: llvmpipe pays per primitive, so beyond kDenseEdges visible edges and points, they
//     are rasterized on the CPU into one RGBA texture (a few pixel writes per short edge) and
//     drawn as a single quad; the fill is skipped (the edges cover it anyway).
// Arrays and textures are rebuilt only when the mesh (engine version), the view or the style
// changed, and uploaded on the next draw, so an idle frame costs a few draws. One shader program
// (ui/gl/gl_api.h: GLSL 3.30 core or ES 3.00) serves every target.
#pragma once

#include "ui/app_state.h"

#include <cstdint>
#include <memory>
#include <vector>

struct ImDrawList;

namespace dlab::ui {

class GlContext;

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
    ~MeshRenderer();
    MeshRenderer(const MeshRenderer&) = delete;  // the passes point back at this object
    MeshRenderer& operator=(const MeshRenderer&) = delete;

    // Rebuilds the arrays if the mesh (engine version), the view or the style changed; returns
    // whether it did. It draws on the engine's GL context (nothing when it has none).
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
    // The GL side: objects of one context, made on the first draw on it.
    struct Gl {
        std::shared_ptr<GlContext> context;
        unsigned program = 0, vertexArray = 0, buffer = 0, texture = 0;
        int textureW = 0, textureH = 0;
        int uShape = -1, uScreen = -1, uSize = -1, uRect = -1, uColour = -1, uImage = -1;
        std::uint64_t uploaded = 0;  // m_built at the last upload
        bool failed = false;         // the program did not build: draw nothing
    };
    static void drawCallback(const ImDrawList* list, const void* cmd);
    bool prepareGl();
    void upload();
    void drawPass(Pass pass, const float screen[4]);
    void drawInstances(int shape, std::size_t offset, std::size_t count, std::uint32_t colour,
                       float size);
    void drawRaster();
    void releaseGl();
    void rasterLine(float x0, float y0, float x1, float y1, std::uint32_t colour);
    void rasterDot(float x, float y, int size, std::uint32_t colour);

    std::vector<float> m_fill, m_edges, m_virtualEdges, m_points, m_pending;
    // Dense mode: RGBA pixels of the canvas, row 0 at the top; uploaded to the texture when dirty.
    std::vector<std::uint32_t> m_raster;
    int m_rasterW = 0, m_rasterH = 0;
    bool m_dense = false, m_rasterDirty = false;
    std::uint64_t m_built = 0;             // rebuilds so far
    std::shared_ptr<GlContext> m_context;  // the engine's, at the last update
    Gl m_gl;
    std::size_t m_visibleEdges = 0;
    MeshStyle m_style;
    std::uint64_t m_version = ~std::uint64_t{0};
    View m_view;
    float m_clip[4] = {0, 0, 0, 0};
    PassData m_passes[2] = {{this, Pass::Fill}, {this, Pass::Lines}};
    double m_buildMs = 0;
};

}  // namespace dlab::ui
