// Gui: ImGui context, fonts (DejaVu when installed), light theme, frames and PNG screenshots.
#include "ui/gui.h"

#include "core/engine/output_files.h"
#include "core/teaching/lesson.h"

#include <imgui.h>
#include <stb_image_write.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <ostream>
#include <stdexcept>

namespace dlab::ui {

namespace {

Fonts g_fonts;  // the fonts of the Gui that is drawing (one ImGui context per process)

double nowMs() {
    return std::chrono::duration<double, std::milli>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

const char* firstExisting(std::initializer_list<const char*> paths) {
    std::error_code ec;
    for (const char* p : paths) {
        if (std::filesystem::is_regular_file(p, ec)) return p;
    }
    return nullptr;
}

}  // namespace

const Fonts& fonts() { return g_fonts; }

Gui::Gui(Platform& platform, AppState& state)
    : m_platform(platform), m_state(state), m_renderer(platform.makeRenderer()) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // the layout is ours (settings.json), not ImGui's window list
    io.ConfigWindowsMoveFromTitleBarOnly = true;
    m_platform.initImGui();
    // The renderer draws ImGui, the canvas' mesh and the image views; its device (the platform's
    // context that runs our shaders; none with the null renderer) runs the GL ID-buffer locators.
    std::string glError;
    m_rendererReady = m_renderer->init(glError);
    if (m_rendererReady) {
        m_state.engine.attachGl(m_renderer->device());
        m_state.renderer = m_renderer.get();
    } else {
        m_state.log(Message::Level::Error, std::string(m_platform.name()) + ": " + glError);
    }
    loadFonts();
    applyTheme();
    m_lastTime = nowMs();
}

Gui::~Gui() {
    m_state.engine.detachGl();  // the context may go away with us
    m_state.renderer = nullptr;
    m_state.canvas.reset();  // its mesh belongs to the renderer
    if (m_rendererReady) m_renderer->shutdown();
    m_platform.shutdownImGui();
    ImGui::DestroyContext();
    g_fonts = {};
}

namespace {

// Latin-1 plus the few symbols captions and lessons use (arrows, dashes, minus, ≤, ≥): the
// ranges `dtlab lesson check` holds lesson text to.
const ImWchar* glyphRanges() {
    static const auto ranges = [] {
        std::array<ImWchar, std::size(kLessonGlyphRanges)> r{};
        for (std::size_t i = 0; i < r.size(); ++i)
            r[i] = static_cast<ImWchar>(kLessonGlyphRanges[i]);
        return r;
    }();
    return ranges.data();
}

}  // namespace

void Gui::loadFonts() {
    ImGuiIO& io = ImGui::GetIO();
    const char* sans = firstExisting({"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"});
    const char* mono = firstExisting({"/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf"});
    const char* bold = firstExisting({"/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf"});
    const float base = fontSize();
    io.Fonts->Clear();
    ImFontConfig cfg;
    cfg.OversampleH = 2;
    if (sans) {
        m_fonts.ui = io.Fonts->AddFontFromFileTTF(sans, base, &cfg, glyphRanges());
        m_fonts.caption = io.Fonts->AddFontFromFileTTF(sans, base * 1.3f, &cfg, glyphRanges());
    }
    if (mono) m_fonts.mono = io.Fonts->AddFontFromFileTTF(mono, base, &cfg, glyphRanges());
    if (bold) m_fonts.bold = io.Fonts->AddFontFromFileTTF(bold, base, &cfg, glyphRanges());
    if (!m_fonts.ui) {
        ImFontConfig def;
        def.SizePixels = base;
        m_fonts.ui = io.Fonts->AddFontDefault(&def);
        m_fonts.caption = m_fonts.ui;
        m_state.log(Message::Level::Warning,
                    "DejaVu fonts not found (apt-get install fonts-dejavu-core): using ImGui's "
                    "built-in font");
    }
    if (!m_fonts.mono) m_fonts.mono = m_fonts.ui;
    if (!m_fonts.bold) m_fonts.bold = m_fonts.ui;
    io.FontDefault = m_fonts.ui;
    if (m_rendererReady) m_renderer->reloadFonts();
    m_presentationApplied = m_state.presentation;
    m_fontSizeApplied = base;
}

// Presentation mode reads from the back of a room: the text is about 1/34 of the window's
// height (21 px at 720, 32 px at 1080).
float Gui::fontSize() const {
    if (!m_state.presentation) return 16.0f;
    int w = 0, h = 0;
    m_platform.framebufferSize(w, h);
    return h > 0 ? std::clamp(std::round(static_cast<float>(h) / 34.0f), 18.0f, 40.0f) : 26.0f;
}

void Gui::applyTheme() {
    ImGuiStyle& style = ImGui::GetStyle();
    style = ImGuiStyle();
    ImGui::StyleColorsLight(&style);
    style.WindowRounding = 0;
    style.FrameRounding = 3;
    style.GrabRounding = 3;
    style.ItemSpacing = ImVec2(8, 5);
    style.FramePadding = ImVec2(6, 4);
    style.Colors[ImGuiCol_WindowBg] = ImVec4(0.95f, 0.95f, 0.96f, 1);
    style.Colors[ImGuiCol_ChildBg] = ImVec4(0, 0, 0, 0);
    if (m_state.presentation) {
        // High contrast for projectors: black text, stronger borders and highlights.
        style.Colors[ImGuiCol_Text] = ImVec4(0, 0, 0, 1);
        style.Colors[ImGuiCol_Border] = ImVec4(0.2f, 0.2f, 0.2f, 0.8f);
        style.FrameBorderSize = 1;
        style.ScaleAllSizes(1.4f);
    }
}

bool Gui::frame() {
    const double t0 = nowMs();
    if (m_presentationApplied != m_state.presentation || fontSize() != m_fontSizeApplied) {
        loadFonts();
        applyTheme();
    }
    ImGuiIO& io = ImGui::GetIO();
    if (!m_platform.headless()) {
        io.DeltaTime = static_cast<float>(std::max(1e-4, (t0 - m_lastTime) / 1000.0));
    }
    m_lastTime = t0;
    const bool open = m_platform.newFrame();
    g_fonts = m_fonts;
    if (m_rendererReady) m_renderer->newFrame();
    ImGui::NewFrame();
    ShowApplication(m_state);
    ImGui::Render();
    const double t1 = nowMs();
    int w = 0, h = 0;
    m_platform.framebufferSize(w, h);
    // The host window draws no background: the clear is its colour (one full-window fill less
    // for a software rasterizer).
    const ImVec4 bg = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
    const float clear[4] = {bg.x, bg.y, bg.z, 1.0f};
    if (m_rendererReady) m_renderer->render(ImGui::GetDrawData(), w, h, clear);
    if (m_capture) readFramebuffer();
    m_pixelsStale = !m_capture;
    m_platform.present();
    m_uiMs = t1 - t0;
    m_frameMs = nowMs() - t0;
    return open && !m_state.quitRequested;
}

void Gui::readFramebuffer() {
    int w = 0, h = 0;
    m_platform.framebufferSize(w, h);
    if (!m_rendererReady || !m_renderer->readPixels(w, h, m_platform.headless(), m_pixels)) {
        m_pixels.clear();  // nothing drawn (the null renderer)
        w = h = 0;
    }
    m_pixelsW = w;
    m_pixelsH = h;
    m_pixelsStale = false;
}

const std::vector<std::uint8_t>& Gui::lastFrame(int& width, int& height) {
    // Headless, the last frame stays in the buffer: read it when asked.
    if (m_pixelsStale && m_platform.headless()) readFramebuffer();
    width = m_pixelsW;
    height = m_pixelsH;
    return m_pixels;
}

// The pixels of a screenshot: the next frame captured (or, headless, the last one).
void Gui::captureScreenshot() {
    if (m_pixelsStale && m_platform.headless()) {
        readFramebuffer();
    } else if (m_pixels.empty() || m_pixelsStale) {
        const bool was = m_capture;
        m_capture = true;
        frame();
        m_capture = was;
    }
}

bool Gui::saveScreenshot(const std::string& path, std::string& error) {
    captureScreenshot();
    return writePng(path, m_pixels, m_pixelsW, m_pixelsH, error);
}

std::string Gui::screenshotPng() {
    captureScreenshot();
    return encodePng(m_pixels, m_pixelsW, m_pixelsH);
}

std::string encodePng(const std::vector<std::uint8_t>& rgba, int width, int height) {
    if (width <= 0 || height <= 0 || rgba.size() < static_cast<std::size_t>(width) * height * 4)
        return {};
    // Opaque output: the framebuffer's alpha is whatever blending left there.
    std::vector<std::uint8_t> opaque(
        rgba.begin(), rgba.begin() + static_cast<std::ptrdiff_t>(width) * height * 4);
    for (std::size_t i = 3; i < opaque.size(); i += 4) opaque[i] = 255;
    std::string png;
    const auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                                   static_cast<std::size_t>(size));
    };
    if (!stbi_write_png_to_func(append, &png, width, height, 4, opaque.data(), width * 4))
        return {};
    return png;
}

bool writePng(const std::string& path, const std::vector<std::uint8_t>& rgba, int width, int height,
              std::string& error) {
    const std::string png = encodePng(rgba, width, height);
    if (png.empty()) {
        error = "cannot write " + path + ": no image to write";
        return false;
    }
    try {
        writeTextFile(path, [&](std::ostream& os) { os.write(png.data(), std::ssize(png)); });
    } catch (const std::runtime_error& e) {
        error = e.what();  // "cannot write PATH: why"
        return false;
    }
    return true;
}

}  // namespace dlab::ui
