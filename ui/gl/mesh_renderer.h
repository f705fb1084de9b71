// Draws big meshes with our own GL code from inside ImGui's render pass: ImGui draws each draw
// list with 16-bit indices (at most 64k vertices), and a 100k-point mesh has 300k edges.
//
// Two modes, chosen per rebuild from how many edges are on the canvas:
//   sparse: one vertex buffer, culled to the canvas, in screen pixels computed in double (exact
//     at any zoom or offset): the fill as triangles, edges and points as instanced quads that
//     the vertex shader spans (wide lines and big points exist on every target this way);
//   dense: llvmpipe pays per primitive, so beyond kDenseEdges visible edges and points, they
//     are rasterized on the CPU into one opaque RGBA image, the canvas background included (a
//     few pixel writes per short edge), that ImGui draws as an image with blending off; the
//     fill is skipped (the edges cover it anyway). The image goes to one of two textures in
//     turn, so that an upload never waits for llvmpipe still drawing the last frame.
// Arrays and textures are rebuilt only when the mesh (engine version), the view or the style
// changed, and uploaded on the next draw, so an idle frame costs a few draws. When only a few
// operations moved the mesh along its journal, the dense raster is patched: the pixels of the
// canvas tiles that the operations' triangles cover are cleared and drawn again (the same pixels
// as a full rebuild), and only the rows of those tiles are uploaded. One shader program
// (ui/gl/gl_api.h: GLSL 3.30 core or ES 3.00) serves every target.
#pragma once

#include "ui/app_state.h"
#include "ui/render/renderer.h"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

struct ImDrawList;

namespace dlab::ui {

class GlContext;

class MeshRenderer final : public CanvasMesh {
public:
    static constexpr std::size_t kDenseEdges = 40000;

    MeshRenderer() = default;
    ~MeshRenderer() override;
    MeshRenderer(const MeshRenderer&) = delete;  // the passes point back at this object
    MeshRenderer& operator=(const MeshRenderer&) = delete;

    // Rebuilds the arrays if the mesh (engine version), the view or the style changed; returns
    // whether it did. It draws on the engine's GL context (nothing when it has none).
    bool update(const Engine& engine, const View& view, const MeshStyle& style) override;
    // Adds a GL draw (clipped to the rectangle) to the draw list; it leaves ImGui's GL state as
    // it found it. Two passes, so that highlights can go between the fill and the edges.
    void enqueue(ImDrawList* drawList, Pass pass, float clipX0, float clipY0, float clipX1,
                 float clipY1) override;
    bool dense() const override { return m_dense; }
    std::size_t visibleEdges() const override { return m_visibleEdges; }
    double lastBuildMs() const override { return m_buildMs; }
    // Whether the last update patched the raster instead of drawing it whole.
    bool lastPatched() const { return m_patched; }
    // Dense mode: the canvas' pixels (RGBA, row 0 at the top), as the next draw shows them.
    const std::vector<std::uint32_t>& raster() const { return m_raster; }
    static constexpr int kTile = 32;  // the raster is patched in tiles of kTile x kTile pixels
    // Patching on (the default) or off: every change redraws the raster whole (benchmarks).
    static void setPatching(bool on);

private:
    struct PassData {
        MeshRenderer* self;
        Pass pass;
    };
    // The GL side: objects of one context, made on the first draw on it.
    struct Gl {
        std::shared_ptr<GlContext> context;
        unsigned program = 0, vertexArray = 0, buffer = 0;
        // Dense mode: two textures, the raster going to the one the last frame did not show, so
        // that an upload never waits for a software rasterizer still drawing that frame.
        unsigned texture[2] = {0, 0};
        int textureW[2] = {0, 0}, textureH[2] = {0, 0};
        int shown = 0;  // the texture the last upload went to
        int uShape = -1, uScreen = -1, uSize = -1, uColour = -1;
        std::uint64_t uploaded = 0;  // m_built at the last upload
        bool failed = false;         // the program did not build: draw nothing
    };
    static void drawCallback(const ImDrawList* list, const void* cmd);
    bool prepareGl();
    void upload();
    void drawPass(Pass pass, const float screen[4]);
    void drawInstances(int shape, std::size_t offset, std::size_t count, std::uint32_t colour,
                       float size);
    void uploadRaster();
    void enqueueRaster(ImDrawList* drawList, float x0, float y0, float x1, float y1);
    void releaseGl();
    void screenPositions(const Mesh& m, const View& view);
    void buildArrays(const Engine& engine);
    void drawRasterAll(const Engine& engine, bool masked);
    bool patchRaster(const Engine& engine);
    bool markChanges(const Engine& engine);
    void markBox(float x0, float y0, float x1, float y1);
    bool boxDirty(float x0, float y0, float x1, float y1) const;
    void clearDirtyTiles();
    void rasterLine(float x0, float y0, float x1, float y1, std::uint32_t colour);
    void rasterDot(float x, float y, int size, std::uint32_t colour);
    void put(int px, int py, std::uint32_t colour) {
        if (px < 0 || py < 0 || px >= m_rasterW || py >= m_rasterH) return;
        if (m_masked && !m_tiles[(py / kTile) * m_tilesW + px / kTile]) return;
        m_raster[static_cast<std::size_t>(py) * m_rasterW + px] = colour;
    }

    std::vector<float> m_fill, m_edges, m_virtualEdges, m_points, m_pending;
    // Dense mode: RGBA pixels of the canvas, row 0 at the top, opaque (the canvas' background
    // where nothing is drawn); uploaded to a texture when changed.
    std::vector<std::uint32_t> m_raster;
    int m_rasterW = 0, m_rasterH = 0;
    bool m_dense = false;
    std::vector<float> m_xy;  // screen position of every vertex at the last update
    // Patching: the dirty tiles of this update.
    std::vector<std::uint8_t> m_tiles;
    std::size_t m_dirtyTiles = 0;
    int m_tilesW = 0, m_tilesH = 0;
    bool m_masked = false, m_patched = false;
    // Rows [y0, y1) of the raster that a texture has not received yet, per texture.
    struct Rows {
        int y0 = 0, y1 = 0;
        bool empty() const { return y0 >= y1; }
        void add(int a, int b) {
            y0 = empty() ? a : std::min(y0, a);
            y1 = empty() ? b : std::max(y1, b);
        }
    };
    Rows m_stale[2];
    // Where the raster was drawn: the engine's run, journal position, current vertex, and
    // whether the run was still going (virtual triangles hidden).
    std::uint64_t m_run = ~std::uint64_t{0};
    std::size_t m_position = 0;
    std::int32_t m_currentVertex = -1;
    bool m_running = false;
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
