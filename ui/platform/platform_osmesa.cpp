// The headless platform: an OSMesa context rendering into memory (software GL, llvmpipe).
// The only file that includes OSMesa: when Mesa's OSMesa goes away, an EGL pbuffer replaces it.
#include "ui/platform/platform.h"

#include <GL/osmesa.h>
#include <imgui.h>

#include <vector>

namespace dlab::ui {

namespace {

class OsmesaPlatform final : public Platform {
public:
    OsmesaPlatform(OSMesaContext ctx, int width, int height) : m_ctx(ctx) { resize(width, height); }
    ~OsmesaPlatform() override { OSMesaDestroyContext(m_ctx); }
    const char* name() const override { return "osmesa"; }
    bool headless() const override { return true; }
    void framebufferSize(int& width, int& height) const override {
        width = m_width;
        height = m_height;
    }
    void initImGui() override {
        ImGuiIO& io = ImGui::GetIO();
        io.BackendPlatformName = "dlab_headless";
        // Key indices are GLFW's key codes (ui/platform/keys.h), as in the real window.
        for (int k = 0; k < ImGuiKey_COUNT; ++k) io.KeyMap[k] = -1;
        const int map[][2] = {{ImGuiKey_Tab, 258},        {ImGuiKey_LeftArrow, 263},
                              {ImGuiKey_RightArrow, 262}, {ImGuiKey_UpArrow, 265},
                              {ImGuiKey_DownArrow, 264},  {ImGuiKey_PageUp, 266},
                              {ImGuiKey_PageDown, 267},   {ImGuiKey_Home, 268},
                              {ImGuiKey_End, 269},        {ImGuiKey_Insert, 260},
                              {ImGuiKey_Delete, 261},     {ImGuiKey_Backspace, 259},
                              {ImGuiKey_Space, 32},       {ImGuiKey_Enter, 257},
                              {ImGuiKey_Escape, 256},     {ImGuiKey_KeyPadEnter, 335},
                              {ImGuiKey_A, 'A'},          {ImGuiKey_C, 'C'},
                              {ImGuiKey_V, 'V'},          {ImGuiKey_X, 'X'},
                              {ImGuiKey_Y, 'Y'},          {ImGuiKey_Z, 'Z'}};
        for (const auto& m : map) io.KeyMap[m[0]] = m[1];
    }
    void shutdownImGui() override {}
    bool newFrame() override {
        ImGuiIO& io = ImGui::GetIO();
        io.DisplaySize = ImVec2(static_cast<float>(m_width), static_cast<float>(m_height));
        io.DisplayFramebufferScale = ImVec2(1, 1);
        if (io.DeltaTime <= 0) io.DeltaTime = 1.0f / 60.0f;
        return true;
    }
    void present() override {}
    bool resize(int width, int height) override {
        if (width < 1 || height < 1 || width > 16384 || height > 16384) return false;
        m_buffer.assign(static_cast<std::size_t>(width) * height * 4, 0);
        if (!OSMesaMakeCurrent(m_ctx, m_buffer.data(), GL_UNSIGNED_BYTE, width, height))
            return false;
        OSMesaPixelStore(OSMESA_Y_UP, 1);  // row 0 at the bottom, as glReadPixels reads
        m_width = width;
        m_height = height;
        return true;
    }

private:
    OSMesaContext m_ctx;
    std::vector<unsigned char> m_buffer;
    int m_width = 0, m_height = 0;
};

}  // namespace

std::unique_ptr<Platform> makeOsmesaPlatform(int width, int height, std::string& error) {
    // A core profile, as in the window and close to WebGL2: what runs here runs there.
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           0,
                           OSMESA_STENCIL_BITS,
                           0,
                           OSMESA_ACCUM_BITS,
                           0,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           3,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           3,
                           0};
    OSMesaContext ctx = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!ctx) {
        error = "OSMesa: cannot create a software OpenGL 3.3 core context";
        return nullptr;
    }
    auto platform = std::make_unique<OsmesaPlatform>(ctx, width, height);
    int w = 0, h = 0;
    platform->framebufferSize(w, h);
    if (w != width || h != height) {
        error = "OSMesa: cannot make a " + std::to_string(width) + "x" + std::to_string(height) +
                " buffer current";
        return nullptr;
    }
    return platform;
}

bool windowPlacement(const Platform&, WindowOptions&) { return false; }

}  // namespace dlab::ui
