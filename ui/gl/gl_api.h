// GL entry points beyond OpenGL 1.1, loaded from the current context through the Platform
// (no GLEW or epoxy: they do not work with OSMesa), and whether that context is still alive.
#pragma once

#include <GL/gl.h>
#include <GL/glext.h>

#include <memory>
#include <string>

namespace dlab::ui {

class Platform;

// Function pointers of one context. Everything up to GL 1.1 is called directly (the executable's
// GL provider exports it); these are the framebuffer, buffer-object, sync and program calls the
// GL ID buffer needs.
struct GlApi {
    PFNGLGENFRAMEBUFFERSPROC genFramebuffers = nullptr;
    PFNGLDELETEFRAMEBUFFERSPROC deleteFramebuffers = nullptr;
    PFNGLBINDFRAMEBUFFERPROC bindFramebuffer = nullptr;
    PFNGLFRAMEBUFFERTEXTURE2DPROC framebufferTexture2D = nullptr;
    PFNGLCHECKFRAMEBUFFERSTATUSPROC checkFramebufferStatus = nullptr;
    PFNGLGENBUFFERSPROC genBuffers = nullptr;
    PFNGLDELETEBUFFERSPROC deleteBuffers = nullptr;
    PFNGLBINDBUFFERPROC bindBuffer = nullptr;
    PFNGLBUFFERDATAPROC bufferData = nullptr;
    PFNGLMAPBUFFERRANGEPROC mapBufferRange = nullptr;
    PFNGLUNMAPBUFFERPROC unmapBuffer = nullptr;
    PFNGLFENCESYNCPROC fenceSync = nullptr;
    PFNGLCLIENTWAITSYNCPROC clientWaitSync = nullptr;
    PFNGLDELETESYNCPROC deleteSync = nullptr;
    PFNGLUSEPROGRAMPROC useProgram = nullptr;
    PFNGLACTIVETEXTUREPROC activeTexture = nullptr;
    void(APIENTRYP clientActiveTexture)(GLenum) = nullptr;  // gl.h names no PFN type for it
    PFNGLBINDVERTEXARRAYPROC bindVertexArray = nullptr;     // optional (GL 3.0)
    PFNGLBINDSAMPLERPROC bindSampler = nullptr;             // optional (GL 3.3)
};

// The GL context a locator draws on: its entry points, and a flag that the owner of the context
// clears before destroying it, so that objects outliving the context never call into it.
class GlContext {
public:
    // Loads the entry points from the platform's current context; nullptr and a one-line reason
    // (the missing functions) when the context cannot run the GL ID buffer.
    static std::shared_ptr<GlContext> load(Platform& platform, std::string& error);

    const GlApi& api() const { return m_api; }
    bool alive() const { return m_alive; }
    // The context is about to go away: GL objects are leaked with it instead of deleted.
    void lose() { m_alive = false; }

private:
    GlApi m_api;
    bool m_alive = true;
};

}  // namespace dlab::ui
