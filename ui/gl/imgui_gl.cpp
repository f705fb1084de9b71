// ImGui's OpenGL3 backend on our GL; framebuffer reads.
#include "ui/gl/imgui_gl.h"

#include "ui/gl/gl_api.h"

#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>

namespace dlab::ui {

namespace {

// GL rows start at the bottom: flip to top-first.
void flipRows(std::vector<std::uint8_t>& rgba, int width, int height) {
    const std::size_t row = static_cast<std::size_t>(width) * 4;
    for (int y = 0; y < height / 2; ++y) {
        std::swap_ranges(rgba.begin() + static_cast<std::ptrdiff_t>(y * row),
                         rgba.begin() + static_cast<std::ptrdiff_t>((y + 1) * row),
                         rgba.begin() + static_cast<std::ptrdiff_t>((height - 1 - y) * row));
    }
}

}  // namespace

bool initImGuiGl(std::string& error) {
    if (!GlContext::fromCurrent(error)) return false;
    if (!ImGui_ImplOpenGL3_Init(kGlslVersion)) {
        error = "ImGui's OpenGL3 renderer cannot start on this context";
        return false;
    }
    ImGui::GetIO().BackendFlags &= ~ImGuiBackendFlags_RendererHasVtxOffset;
    return true;
}

void shutdownImGuiGl() { ImGui_ImplOpenGL3_Shutdown(); }

void newFrameImGuiGl() { ImGui_ImplOpenGL3_NewFrame(); }

void reloadImGuiFontsGl() {
    ImGui_ImplOpenGL3_DestroyFontsTexture();
    ImGui_ImplOpenGL3_CreateFontsTexture();
}

void renderImGuiGl(ImDrawData* drawData, int width, int height, const float clear[4]) {
    glViewport(0, 0, width, height);
    glClearColor(clear[0], clear[1], clear[2], clear[3]);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(drawData);
    // A window's swap flushes; headless, nothing else would: llvmpipe keeps every orphaned
    // vertex buffer of the frames not yet flushed (~0.2-1 MB a frame at 20k points).
    glFlush();
}

void readFramebufferGl(int width, int height, bool front, std::vector<std::uint8_t>& rgba) {
    rgba.resize(static_cast<std::size_t>(width) * height * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(front ? GL_FRONT : GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    flipRows(rgba, width, height);
}

std::vector<std::uint8_t> renderImGuiOffscreenGl(ImDrawData* drawData, int width, int height,
                                                 const float clear[4]) {
    GLuint tex = 0, fbo = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glBindTexture(GL_TEXTURE_2D, 0);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    renderImGuiGl(drawData, width, height, clear);
    std::vector<std::uint8_t> rgba(static_cast<std::size_t>(width) * height * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
    flipRows(rgba, width, height);
    return rgba;
}

}  // namespace dlab::ui
