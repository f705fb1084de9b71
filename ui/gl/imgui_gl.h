// ImGui drawn by its OpenGL3 backend on our GL, the same on every target, and the pixels of what
// was drawn (screenshots, the Table 1 plot).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

struct ImDrawData;

namespace dlab::ui {

// The backend on the current context (GLSL 3.30 core or ES 3.00), with ImGui's large-mesh mode
// off on every target (WebGL2 has no base-vertex draw): each draw list holds at most 65536
// vertices everywhere, and the canvas keeps within that budget (panels.h: canvasHasRoom).
// False and a one-line reason when the context cannot run it.
bool initImGuiGl(std::string& error);
void shutdownImGuiGl();
void newFrameImGuiGl();
// Makes the font texture again after the fonts changed.
void reloadImGuiFontsGl();
// Clears the bound framebuffer (width x height pixels) to `clear` (RGBA) and draws ImGui's frame.
void renderImGuiGl(ImDrawData* drawData, int width, int height, const float clear[4]);

// The width x height pixels of the default framebuffer as RGBA rows, top row first, after the
// drawing finished (`front`: single-buffered contexts such as OSMesa's).
void readFramebufferGl(int width, int height, bool front, std::vector<std::uint8_t>& rgba);

// Draws ImGui's frame into an offscreen width x height target cleared to `clear` and returns its
// pixels, top row first (the default framebuffer is left alone).
std::vector<std::uint8_t> renderImGuiOffscreenGl(ImDrawData* drawData, int width, int height,
                                                 const float clear[4]);

}  // namespace dlab::ui
