// What the UI draws through, with no GL in sight: the GL renderer (ui/gl/gl_renderer.cpp, on the
// platform's OpenGL 3.3 core / ES 3.0 context) or the null renderer (ui/render/null_renderer.cpp:
// no context, nothing drawn, draws counted), chosen by the platform. The canvas' mesh, ImGui's
// frame, the pixels of a frame and the images of the ID-buffer view all go through it, so the
// UI's logic (clicks, keys, panels, sessions, lessons) runs and is tested without a GL driver.
#pragma once

#include "core/engine/locator.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

struct ImDrawData;
struct ImDrawList;

namespace dlab {
class Inserter;
}

namespace dlab::ui {

class Engine;
struct View;

struct MeshStyle {
    std::uint32_t fill = 0, edge = 0, virtualEdge = 0, point = 0,
                  pending = 0;               // ImU32 colours (ABGR)
    std::uint32_t background = 0xFFFFFFFFu;  // opaque; a dense mesh's image has it
    float edgeWidth = 1.0f, pointSize = 4.0f;
    bool drawFill = true, drawVirtual = true, drawPoints = true;
};

// The mesh on the canvas: rebuilt (or patched) when the mesh, view or style changed, then drawn
// in two passes from inside ImGui's render, so that highlights go between the fill and edges.
class CanvasMesh {
public:
    enum class Pass : std::uint8_t { Fill, Lines };
    virtual ~CanvasMesh() = default;
    // Returns whether anything was rebuilt.
    virtual bool update(const Engine& engine, const View& view, const MeshStyle& style) = 0;
    virtual void enqueue(ImDrawList* drawList, Pass pass, float clipX0, float clipY0, float clipX1,
                         float clipY1) = 0;
    virtual bool dense() const = 0;
    virtual std::size_t visibleEdges() const = 0;
    virtual double lastBuildMs() const = 0;
};

// An RGBA image shown with ImGui::Image (the ID-buffer view): `id` is what ImGui draws.
struct ImageSlot {
    unsigned handle = 0;
    int width = 0, height = 0;
    void* id() const { return reinterpret_cast<void*>(static_cast<std::uintptr_t>(handle)); }
};

// A GL ID-buffer locator as the UI sees it (ui/gl/idbuffer_gl.h implements it).
class GpuIdBuffer : public Locator {
public:
    virtual bool ready() const = 0;                   // reset() happened and the context is alive
    virtual std::uint64_t version() const = 0;        // bumps whenever pixels changed
    virtual std::vector<std::int32_t> readAll() = 0;  // width*height ids, row 0 = lowest y
    virtual int width() const = 0;
    virtual int height() const = 0;
    virtual Vec2 pixelCentre(int i, int j) const = 0;
    // Before any step: the batched readback reads ahead in the run's insertion order.
    virtual void followOrder(const Inserter& inserter) = 0;
};

// The GL context the engine's GL locators draw on (ui/gl/gl_api.h: GlContext).
class GpuDevice {
public:
    virtual ~GpuDevice() = default;
    virtual bool alive() const = 0;
    // The context is about to go away: GL objects are leaked with it instead of deleted.
    virtual void lose() = 0;
    virtual std::unique_ptr<GpuIdBuffer> makeIdBuffer(LocatorKind kind,
                                                      const LocatorOptions& options) = 0;
};

class Renderer {
public:
    virtual ~Renderer() = default;
    virtual const char* name() const = 0;
    // After ImGui::CreateContext, on the platform's context. False and a one-line reason when
    // it cannot draw there.
    virtual bool init(std::string& error) = 0;
    virtual void shutdown() = 0;
    virtual void newFrame() = 0;
    virtual void reloadFonts() = 0;
    // Clears width x height pixels to `clear` (RGBA) and draws ImGui's frame.
    virtual void render(ImDrawData* drawData, int width, int height, const float clear[4]) = 0;
    // The pixels of the last frame, RGBA rows top first (`front`: single-buffered contexts);
    // false when the renderer keeps none (null).
    virtual bool readPixels(int width, int height, bool front, std::vector<std::uint8_t>& rgba) = 0;
    // The device the GL locators use; nullptr when there is none.
    virtual std::shared_ptr<GpuDevice> device() = 0;
    virtual std::unique_ptr<CanvasMesh> makeCanvasMesh() = 0;
    // Puts width x height RGBA pixels (rows top first) into the slot's image.
    virtual void uploadImage(ImageSlot& slot, int width, int height, const void* rgba) = 0;
};

// Draws nothing and keeps no pixels; counts what it was asked to draw.
struct NullRendererCounts {
    long long frames = 0, meshUpdates = 0, meshPasses = 0, imageUploads = 0;
};
std::unique_ptr<Renderer> makeNullRenderer(NullRendererCounts* counts = nullptr);

}  // namespace dlab::ui
