// The null platform: no window, no GL; ImGui runs on synthetic input and the null renderer
// draws nothing (ui/render/renderer.h). The UI's logic tests run on it.
#include "ui/platform/headless.h"

namespace dlab::ui {

namespace {

class NullPlatform final : public HeadlessPlatform {
public:
    NullPlatform(int width, int height, NullRendererCounts* counts) : m_counts(counts) {
        resize(width, height);
    }
    const char* name() const override { return "null"; }
    bool resize(int width, int height) override {
        if (width < 1 || height < 1 || width > 16384 || height > 16384) return false;
        m_width = width;
        m_height = height;
        return true;
    }
    std::unique_ptr<Renderer> makeRenderer() override { return makeNullRenderer(m_counts); }

private:
    NullRendererCounts* m_counts;
};

}  // namespace

std::unique_ptr<Platform> makeNullPlatform(int width, int height, NullRendererCounts* counts) {
    return std::make_unique<NullPlatform>(width, height, counts);
}

}  // namespace dlab::ui
