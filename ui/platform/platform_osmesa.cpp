// The headless platform: an OSMesa context rendering into memory (software GL, llvmpipe).
// The only file that includes OSMesa: when Mesa's OSMesa goes away, an EGL pbuffer replaces it.
#include "ui/gl/gl_renderer.h"
#include "ui/platform/headless.h"

#include <GL/osmesa.h>

#include <vector>

namespace dlab::ui {

namespace {

class OsmesaPlatform final : public HeadlessPlatform {
public:
    OsmesaPlatform(OSMesaContext ctx, int width, int height) : m_ctx(ctx) { resize(width, height); }
    ~OsmesaPlatform() override { OSMesaDestroyContext(m_ctx); }
    const char* name() const override { return "osmesa"; }
    std::unique_ptr<Renderer> makeRenderer() override { return makeGlRenderer(); }
    bool resize(int width, int height) override {
        if (width < 1 || height < 1 || width > 16384 || height > 16384) return false;
        m_buffer.assign(static_cast<std::size_t>(width) * height * 4, 0);
        if (!OSMesaMakeCurrent(m_ctx, m_buffer.data(), GL_UNSIGNED_BYTE, width, height))
            return false;
        OSMesaPixelStore(OSMESA_Y_UP, 1);  // row 0 at the bottom, as glReadPixels reads
        m_width = width;
        m_height = height;
        return true;
    }

private:
    OSMesaContext m_ctx;
    std::vector<unsigned char> m_buffer;
};

}  // namespace

std::unique_ptr<Platform> makeOsmesaPlatform(int width, int height, std::string& error) {
    // A core profile, as in the window and close to WebGL2: what runs here runs there.
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           0,
                           OSMESA_STENCIL_BITS,
                           0,
                           OSMESA_ACCUM_BITS,
                           0,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           3,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           3,
                           0};
    OSMesaContext ctx = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!ctx) {
        error = "OSMesa: cannot create a software OpenGL 3.3 core context";
        return nullptr;
    }
    auto platform = std::make_unique<OsmesaPlatform>(ctx, width, height);
    int w = 0, h = 0;
    platform->framebufferSize(w, h);
    if (w != width || h != height) {
        error = "OSMesa: cannot make a " + std::to_string(width) + "x" + std::to_string(height) +
                " buffer current";
        return nullptr;
    }
    return platform;
}

bool windowPlacement(const Platform&, WindowOptions&) { return false; }

}  // namespace dlab::ui
