// UiHarness: the test platform (harness_osmesa.cpp, harness_egl.cpp, harness_null.cpp) + AppState +
// Gui on the built-in demo, and synthetic input.
#include "tests/ui/ui_harness.h"

#include "core/engine/generators.h"
#include "ui/platform/keys.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <stdexcept>

namespace dlab::test {

UiHarness::UiHarness(int width, int height) {
    std::string error;
    m_platform = makeTestPlatform(width, height, error);
    if (!m_platform) throw std::runtime_error(error);
    m_gui = std::make_unique<ui::Gui>(*m_platform, m_state);
    m_state.setOptions(ui::demoOptions());
    m_state.loadPoints(demoPoints(), "built-in demo");
    frames(3);
}

UiHarness::~UiHarness() = default;

void UiHarness::frames(int n) {
    for (int i = 0; i < n; ++i) m_gui->frame();
}

void UiHarness::moveTo(float x, float y) {
    ImGui::GetIO().MousePos = ImVec2(x, y);
    frames(2);
}

void UiHarness::click(float x, float y, int button) {
    ImGuiIO& io = ImGui::GetIO();
    io.MousePos = ImVec2(x, y);
    frames(1);  // hover first, as a real mouse does
    io.MouseDown[button] = true;
    frames(1);
    io.MouseDown[button] = false;
    frames(2);
}

void UiHarness::drag(float x0, float y0, float x1, float y1, int button) {
    ImGuiIO& io = ImGui::GetIO();
    io.MousePos = ImVec2(x0, y0);
    frames(1);
    io.MouseDown[button] = true;
    frames(1);
    for (int i = 1; i <= 8; ++i) {
        io.MousePos = ImVec2(x0 + (x1 - x0) * i / 8, y0 + (y1 - y0) * i / 8);
        frames(1);
    }
    io.MouseDown[button] = false;
    frames(2);
}

void UiHarness::scroll(float x, float y, float wheel) {
    ImGuiIO& io = ImGui::GetIO();
    io.MousePos = ImVec2(x, y);
    frames(1);
    io.MouseWheel = wheel;
    frames(1);
    io.MouseWheel = 0;
    frames(2);
}

void UiHarness::press(int key, bool shift, bool ctrl) {
    ImGuiIO& io = ImGui::GetIO();
    io.KeyShift = shift;
    io.KeyCtrl = ctrl;
    io.KeysDown[key] = true;
    ui::queueKeyPress(key, shift, ctrl);  // as the window's key callback does
    frames(1);
    io.KeysDown[key] = false;
    io.KeyShift = io.KeyCtrl = false;
    frames(1);
}

std::array<float, 4> UiHarness::rect(const std::string& name) {
    const auto it = m_state.itemRects.find(name);
    if (it == m_state.itemRects.end()) throw std::runtime_error("no widget recorded as " + name);
    return it->second;
}

void UiHarness::clickItem(const std::string& name) {
    const auto r = rect(name);
    click((r[0] + r[2]) / 2, (r[1] + r[3]) / 2);
}

std::array<int, 3> UiHarness::pixel(int x, int y) {
    int w = 0, h = 0;
    const auto& px = m_gui->lastFrame(w, h);
    if (x < 0 || y < 0 || x >= w || y >= h) return {-1, -1, -1};
    const std::size_t i = (static_cast<std::size_t>(y) * w + x) * 4;
    return {px[i], px[i + 1], px[i + 2]};
}

int UiHarness::countColour(const std::array<float, 4>& r, std::array<int, 3> rgb) {
    int count = 0;
    for (int y = static_cast<int>(r[1]); y < static_cast<int>(r[3]); ++y) {
        for (int x = static_cast<int>(r[0]); x < static_cast<int>(r[2]); ++x)
            count += pixel(x, y) == rgb;
    }
    return count;
}

}  // namespace dlab::test
