// What every headless platform shares (OSMesa, null): a framebuffer size, GLFW's key codes in
// ImGui's key map (ui/platform/keys.h, as in the real window) and a fixed frame step.
#pragma once

#include "ui/platform/platform.h"

#include <imgui.h>

namespace dlab::ui {

class HeadlessPlatform : public Platform {
public:
    bool headless() const override { return true; }
    void framebufferSize(int& width, int& height) const override {
        width = m_width;
        height = m_height;
    }
    void initImGui() override {
        ImGuiIO& io = ImGui::GetIO();
        io.BackendPlatformName = "dlab_headless";
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

protected:
    int m_width = 0, m_height = 0;
};

}  // namespace dlab::ui
