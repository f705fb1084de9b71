// GlRenderer: the renderer interface over our GL layer (gl_api, imgui_gl, mesh_renderer).
#include "ui/gl/gl_renderer.h"

#include "ui/gl/gl_api.h"
#include "ui/gl/imgui_gl.h"
#include "ui/gl/mesh_renderer.h"

namespace dlab::ui {

namespace {

class GlRenderer final : public Renderer {
public:
    const char* name() const override { return "gl"; }
    bool init(std::string& error) override {
        if (!initImGuiGl(error)) return false;
        m_device = GlContext::fromCurrent(error);  // nullptr: no GL locators, ImGui still draws
        return true;
    }
    void shutdown() override { shutdownImGuiGl(); }
    void newFrame() override { newFrameImGuiGl(); }
    void reloadFonts() override { reloadImGuiFontsGl(); }
    void render(ImDrawData* drawData, int width, int height, const float clear[4]) override {
        renderImGuiGl(drawData, width, height, clear);
    }
    bool readPixels(int width, int height, bool front, std::vector<std::uint8_t>& rgba) override {
        readFramebufferGl(width, height, front, rgba);
        return true;
    }
    std::shared_ptr<GpuDevice> device() override { return m_device; }
    std::unique_ptr<CanvasMesh> makeCanvasMesh() override {
        return std::make_unique<MeshRenderer>();
    }
    void uploadImage(ImageSlot& slot, int width, int height, const void* rgba) override {
        uploadRgbaTexture(slot.handle, slot.width, slot.height, width, height, rgba);
    }

private:
    std::shared_ptr<GlContext> m_device;
};

}  // namespace

std::unique_ptr<Renderer> makeGlRenderer() { return std::make_unique<GlRenderer>(); }

}  // namespace dlab::ui
