// The GL renderer (ui/render/renderer.h) on the current context: ImGui's OpenGL3 backend, the
// mesh renderer, GL textures for images, and the context for the GL ID-buffer locators.
#pragma once

#include "ui/render/renderer.h"

#include <memory>

namespace dlab::ui {

std::unique_ptr<Renderer> makeGlRenderer();

}  // namespace dlab::ui
