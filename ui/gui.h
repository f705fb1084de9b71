// The GUI driver: the ImGui context, fonts and theme, one frame of the whole application, and
// screenshots. The same class runs in a real window (GLFW), headless (OSMesa) and with no GL at
// all (the null platform): tests and `dtlab render` drive it with synthetic input through
// ImGui's io. It draws through the platform's renderer (ui/render/renderer.h).
#pragma once

#include "ui/app_state.h"
#include "ui/platform/platform.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

struct ImFont;

namespace dlab::ui {

struct Fonts {
    ImFont* ui = nullptr;       // labels, buttons, text
    ImFont* mono = nullptr;     // tables and ids
    ImFont* caption = nullptr;  // the caption line
    ImFont* bold = nullptr;     // lesson text
};

// Fonts of the current frame (set by Gui before the panels run; the defaults when absent).
const Fonts& fonts();

class Gui {
public:
    Gui(Platform& platform, AppState& state);
    ~Gui();
    Gui(const Gui&) = delete;
    Gui& operator=(const Gui&) = delete;

    // One frame: input, the whole UI, render, present. False once the user closed the window
    // or chose Quit.
    bool frame();
    // The pixels of the last frame as RGBA rows, top row first (headless: any time after
    // frame(); in a window: with captureFrames on).
    const std::vector<std::uint8_t>& lastFrame(int& width, int& height);
    // Captures the next frame (or, headless, the last one) to a PNG file (writePng).
    bool saveScreenshot(const std::string& path, std::string& error);
    // The same capture as the bytes of a PNG file (empty: nothing drawn), for a set of files.
    std::string screenshotPng();
    // Requests that frame() captures its image (needed for windows: the back buffer is gone
    // after the swap).
    void captureFrames(bool on) { m_capture = on; }
    double lastFrameMs() const { return m_frameMs; }
    double lastUiMs() const { return m_uiMs; }
    Platform& platform() { return m_platform; }
    Renderer& renderer() { return *m_renderer; }
    AppState& state() { return m_state; }

private:
    void loadFonts();
    void readFramebuffer();
    void captureScreenshot();
    void applyTheme();
    float fontSize() const;  // presentation: grows with the window's height

    Platform& m_platform;
    AppState& m_state;
    std::unique_ptr<Renderer> m_renderer;
    Fonts m_fonts;
    bool m_rendererReady = false;  // the renderer draws ImGui (on the platform's context)
    bool m_presentationApplied = false;
    float m_fontSizeApplied = 0;
    bool m_capture = false;
    std::vector<std::uint8_t> m_pixels;
    int m_pixelsW = 0, m_pixelsH = 0;
    bool m_pixelsStale = true;
    double m_frameMs = 0, m_uiMs = 0;
    double m_lastTime = 0;
};

// RGBA rows (top first) as the bytes of a PNG file; empty when there is no image.
std::string encodePng(const std::vector<std::uint8_t>& rgba, int width, int height);
// Writes RGBA rows (top first) to a PNG file, whole or not at all (writeTextFile); false with
// "cannot write PATH: why" on failure, the old file left as it was.
bool writePng(const std::string& path, const std::vector<std::uint8_t>& rgba, int width, int height,
              std::string& error);

// Draws the whole application into the current ImGui frame (gui.cpp calls it; tests may too).
void ShowApplication(AppState& state);

}  // namespace dlab::ui
