// Loading the GL entry points beyond 1.1 from the current context.
#include "ui/gl/gl_api.h"

#include "ui/platform/platform.h"

#include <type_traits>

namespace dlab::ui {

std::shared_ptr<GlContext> GlContext::load(Platform& platform, std::string& error) {
    auto ctx = std::make_shared<GlContext>();
    GlApi& a = ctx->m_api;
    std::string missing;
    auto get = [&](auto& fn, const char* name, bool required = true) {
        fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(platform.procAddress(name));
        if (!fn && required) missing += (missing.empty() ? "" : ", ") + std::string(name);
    };
    get(a.genFramebuffers, "glGenFramebuffers");
    get(a.deleteFramebuffers, "glDeleteFramebuffers");
    get(a.bindFramebuffer, "glBindFramebuffer");
    get(a.framebufferTexture2D, "glFramebufferTexture2D");
    get(a.checkFramebufferStatus, "glCheckFramebufferStatus");
    get(a.genBuffers, "glGenBuffers");
    get(a.deleteBuffers, "glDeleteBuffers");
    get(a.bindBuffer, "glBindBuffer");
    get(a.bufferData, "glBufferData");
    get(a.mapBufferRange, "glMapBufferRange");
    get(a.unmapBuffer, "glUnmapBuffer");
    get(a.fenceSync, "glFenceSync");
    get(a.clientWaitSync, "glClientWaitSync");
    get(a.deleteSync, "glDeleteSync");
    get(a.useProgram, "glUseProgram");
    get(a.activeTexture, "glActiveTexture");
    get(a.clientActiveTexture, "glClientActiveTexture");
    get(a.bindVertexArray, "glBindVertexArray", false);
    get(a.bindSampler, "glBindSampler", false);
    if (!missing.empty()) {
        error = std::string(platform.name()) + " GL context lacks " + missing +
                " (the GL ID buffer needs GL 3.2)";
        return nullptr;
    }
    return ctx;
}

}  // namespace dlab::ui
