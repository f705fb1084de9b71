// The null renderer: no GL context, no pixels; it counts what the UI asked it to draw.
#include "ui/render/renderer.h"

#include <imgui.h>

namespace dlab::ui {

namespace {

class NullCanvasMesh final : public CanvasMesh {
public:
    explicit NullCanvasMesh(NullRendererCounts* counts) : m_counts(counts ? counts : &m_own) {}
    bool update(const Engine&, const View&, const MeshStyle&) override {
        ++m_counts->meshUpdates;
        return false;
    }
    void enqueue(ImDrawList*, Pass, float, float, float, float) override { ++m_counts->meshPasses; }
    bool dense() const override { return false; }
    std::size_t visibleEdges() const override { return 0; }
    double lastBuildMs() const override { return 0; }

private:
    NullRendererCounts m_own;
    NullRendererCounts* m_counts;
};

class NullRenderer final : public Renderer {
public:
    explicit NullRenderer(NullRendererCounts* counts)
        : m_external(counts), m_counts(counts ? counts : &m_own) {}
    const char* name() const override { return "null"; }
    bool init(std::string&) override {
        reloadFonts();
        return true;
    }
    void shutdown() override {}
    void newFrame() override {}
    // ImGui needs its font atlas built to start a frame; no texture is made from it.
    void reloadFonts() override {
        unsigned char* pixels = nullptr;
        int width = 0, height = 0;
        ImGui::GetIO().Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
    }
    void render(ImDrawData*, int, int, const float*) override { ++m_counts->frames; }
    bool readPixels(int, int, bool, std::vector<std::uint8_t>& rgba) override {
        rgba.clear();
        return false;
    }
    std::shared_ptr<GpuDevice> device() override { return nullptr; }
    std::unique_ptr<CanvasMesh> makeCanvasMesh() override {
        return std::make_unique<NullCanvasMesh>(m_external);
    }
    void uploadImage(ImageSlot& slot, int width, int height, const void*) override {
        slot.width = width;
        slot.height = height;
        ++m_counts->imageUploads;
    }

private:
    NullRendererCounts m_own;
    NullRendererCounts* m_external;  // the caller's, or nullptr
    NullRendererCounts* m_counts;
};

}  // namespace

std::unique_ptr<Renderer> makeNullRenderer(NullRendererCounts* counts) {
    return std::make_unique<NullRenderer>(counts);
}

}  // namespace dlab::ui
