// The headless platform on EGL (glvnd's libEGL and libOpenGL): a pbuffer on a GPU's EGL device,
// or on Mesa's software device or surfaceless platform (llvmpipe) when there is no GPU.
#include "ui/gl/gl_renderer.h"
#include "ui/platform/headless.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <vector>

namespace dlab::ui {

namespace {

// One display to try: an EGL device's or Mesa's surfaceless platform's, and what it is.
struct EglCandidate {
    EGLenum platform;
    void* native;
    std::string what;
};

bool hasExtension(const char* list, const char* name) {
    if (!list) return false;
    const std::size_t n = std::strlen(name);
    for (const char* p = std::strstr(list, name); p; p = std::strstr(p + n, name)) {
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    }
    return false;
}

// EGL's devices, each with whether it is a GPU (Mesa's software device says it is not).
std::vector<std::pair<EGLDeviceEXT, bool>> eglDevices() {
    std::vector<std::pair<EGLDeviceEXT, bool>> out;
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!hasExtension(client, "EGL_EXT_device_enumeration") &&
        !hasExtension(client, "EGL_EXT_device_base"))
        return out;
    auto queryDevices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto queryString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
        eglGetProcAddress("eglQueryDeviceStringEXT"));
    EGLint count = 0;
    if (!queryDevices || !queryString || !queryDevices(0, nullptr, &count) || count <= 0)
        return out;
    std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
    if (!queryDevices(count, devices.data(), &count)) return out;
    for (EGLint i = 0; i < count; ++i) {
        const char* ext = queryString(devices[i], EGL_EXTENSIONS);
        out.emplace_back(devices[i], !hasExtension(ext, "EGL_MESA_device_software"));
    }
    return out;
}

// The displays to try for `device`, in order: GPUs first, then Mesa's software device, then
// Mesa's surfaceless platform. (EGL_DEFAULT_DISPLAY needs an X server on Mesa.)
std::vector<EglCandidate> eglCandidates(EglDevice device) {
    std::vector<EglCandidate> out;
    const auto devices = eglDevices();
    for (const bool gpu : {true, false}) {
        if ((gpu && device == EglDevice::Software) || (!gpu && device == EglDevice::Gpu)) continue;
        int k = 0;
        for (const auto& [d, isGpu] : devices) {
            if (isGpu == gpu)
                out.push_back({EGL_PLATFORM_DEVICE_EXT, d,
                               (gpu ? "GPU device " : "software device ") + std::to_string(k++)});
        }
    }
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (device != EglDevice::Gpu && hasExtension(client, "EGL_MESA_platform_surfaceless"))
        out.push_back({EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, "Mesa surfaceless"});
    return out;
}

// A display once initialized stays so for the whole process (other contexts may share it):
// never eglTerminate'd.
EGLDisplay initializedDisplay(const EglCandidate& c) {
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!getPlatformDisplay) return EGL_NO_DISPLAY;
    EGLDisplay display = getPlatformDisplay(c.platform, c.native, nullptr);
    EGLint major = 0, minor = 0;
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) return EGL_NO_DISPLAY;
    return display;
}

class EglPlatform final : public HeadlessPlatform {
public:
    EglPlatform(EGLDisplay display, EGLConfig config, EGLContext ctx, std::string what)
        : m_display(display), m_config(config), m_ctx(ctx), m_what(std::move(what)) {}
    ~EglPlatform() override {
        eglMakeCurrent(m_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (m_surface != EGL_NO_SURFACE) eglDestroySurface(m_display, m_surface);
        eglDestroyContext(m_display, m_ctx);
    }
    const char* name() const override { return "egl"; }
    std::unique_ptr<Renderer> makeRenderer() override { return makeGlRenderer(); }
    const std::string& what() const { return m_what; }
    // A new pbuffer of that size, current; the old one goes.
    bool resize(int width, int height) override {
        if (width < 1 || height < 1 || width > 16384 || height > 16384) return false;
        const EGLint attribs[] = {EGL_WIDTH, width, EGL_HEIGHT, height, EGL_NONE};
        EGLSurface surface = eglCreatePbufferSurface(m_display, m_config, attribs);
        if (surface == EGL_NO_SURFACE) return false;
        if (!eglMakeCurrent(m_display, surface, surface, m_ctx)) {
            eglDestroySurface(m_display, surface);
            return false;
        }
        if (m_surface != EGL_NO_SURFACE) eglDestroySurface(m_display, m_surface);
        m_surface = surface;
        m_width = width;
        m_height = height;
        return true;
    }

private:
    EGLDisplay m_display;
    EGLConfig m_config;
    EGLContext m_ctx;
    EGLSurface m_surface = EGL_NO_SURFACE;
    std::string m_what;
};

// An OpenGL 3.3 core context with an RGBA8 pbuffer of width x height on `c`'s display, current;
// nullptr and the step that failed in `error` otherwise.
std::unique_ptr<Platform> tryCandidate(const EglCandidate& c, int width, int height,
                                       std::string& error) {
    EGLDisplay display = initializedDisplay(c);
    if (display == EGL_NO_DISPLAY) {
        error = c.what + ": cannot initialize its display";
        return nullptr;
    }
    const EGLint configAttribs[] = {EGL_SURFACE_TYPE,
                                    EGL_PBUFFER_BIT,
                                    EGL_RENDERABLE_TYPE,
                                    EGL_OPENGL_BIT,
                                    EGL_RED_SIZE,
                                    8,
                                    EGL_GREEN_SIZE,
                                    8,
                                    EGL_BLUE_SIZE,
                                    8,
                                    EGL_ALPHA_SIZE,
                                    8,
                                    EGL_NONE};
    EGLConfig config = nullptr;
    EGLint n = 0;
    if (!eglBindAPI(EGL_OPENGL_API) || !eglChooseConfig(display, configAttribs, &config, 1, &n) ||
        n < 1) {
        error = c.what + ": no RGBA8 pbuffer configuration for OpenGL";
        return nullptr;
    }
    // A core profile, as in the window and close to WebGL2: what runs here runs there.
    const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                     3,
                                     EGL_CONTEXT_MINOR_VERSION,
                                     3,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_NONE};
    EGLContext ctx = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttribs);
    if (ctx == EGL_NO_CONTEXT) {
        error = c.what + ": cannot create an OpenGL 3.3 core context";
        return nullptr;
    }
    auto platform = std::make_unique<EglPlatform>(display, config, ctx, c.what);
    if (!platform->resize(width, height)) {
        error = c.what + ": cannot make a " + std::to_string(width) + "x" + std::to_string(height) +
                " pbuffer current";
        return nullptr;
    }
    return platform;
}

}  // namespace

bool eglHasGpu() {
    for (const auto& [device, gpu] : eglDevices()) {
        if (gpu) return true;
    }
    return false;
}

std::unique_ptr<Platform> makeEglPlatform(int width, int height, EglDevice device,
                                          std::string& error) {
    const std::vector<EglCandidate> candidates = eglCandidates(device);
    if (candidates.empty()) {
        error = device == EglDevice::Gpu ? "EGL: no GPU device"
                                         : "EGL: no device and no surfaceless platform";
        return nullptr;
    }
    std::string tried;
    for (const EglCandidate& c : candidates) {
        std::string why;
        if (auto platform = tryCandidate(c, width, height, why)) return platform;
        tried += (tried.empty() ? "" : "; ") + why;
    }
    error = "EGL: " + tried;
    return nullptr;
}

std::string eglDisplayName(const Platform& platform) {
    const auto* egl = dynamic_cast<const EglPlatform*>(&platform);
    return egl ? egl->what() : std::string();
}

bool windowPlacement(const Platform&, WindowOptions&) { return false; }

}  // namespace dlab::ui
