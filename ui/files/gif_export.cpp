// GifWriter over giflib's encoder (per-frame palettes from GifQuantizeBuffer, the NETSCAPE2.0
// loop extension), and the export of a range of steps rendered through the GUI.
#include "ui/files/gif_export.h"

#include "core/engine/output_files.h"
#include "ui/gui.h"

#include <gif_lib.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <stdexcept>
#include <unordered_map>

namespace dlab::ui {

namespace {

std::string gifError(const std::string& path, int code) {
    const char* s = GifErrorString(code);
    return path + ": " + (s ? s : "GIF error " + std::to_string(code));
}

constexpr int kMaxFrames = 2000;

std::uint32_t rgb(GifByteType r, GifByteType g, GifByteType b) {
    return (std::uint32_t{r} << 16) | (std::uint32_t{g} << 8) | b;
}

// The palette of one frame. A flat UI has few colours that cover most pixels (background, fills,
// text) and many antialiased shades in between: the 128 most frequent colours are kept exactly,
// and the rest of the pixels are quantized to 128 more by giflib's median cut, each of those
// entries then set to the most frequent exact colour among its pixels (the cut's box mean would
// tint the flat areas). A frame of at most 256 colours keeps them all exactly.
bool quantizeFrame(const std::vector<GifByteType>& r, const std::vector<GifByteType>& g,
                   const std::vector<GifByteType>& b, std::vector<GifByteType>& index,
                   GifColorType* palette) {
    std::unordered_map<std::uint32_t, std::uint32_t> freq;
    freq.reserve(8192);
    for (std::size_t i = 0; i < r.size(); ++i) ++freq[rgb(r[i], g[i], b[i])];
    std::vector<std::pair<std::uint32_t, std::uint32_t>> byCount(freq.begin(),
                                                                 freq.end());  // (colour, count)
    const std::size_t reserved = byCount.size() <= 256 ? byCount.size() : 128;
    std::partial_sort(byCount.begin(), byCount.begin() + static_cast<std::ptrdiff_t>(reserved),
                      byCount.end(), [](const auto& x, const auto& y) {
                          return x.second > y.second || (x.second == y.second && x.first < y.first);
                      });
    std::unordered_map<std::uint32_t, GifByteType> exact;
    for (std::size_t k = 0; k < reserved; ++k) {
        const std::uint32_t c = byCount[k].first;
        palette[k] = {static_cast<GifByteType>(c >> 16), static_cast<GifByteType>(c >> 8),
                      static_cast<GifByteType>(c)};
        exact.emplace(c, static_cast<GifByteType>(k));
    }
    std::vector<GifByteType> r2, g2, b2;
    std::vector<std::size_t> where;
    for (std::size_t i = 0; i < r.size(); ++i) {
        const auto it = exact.find(rgb(r[i], g[i], b[i]));
        if (it != exact.end()) {
            index[i] = it->second;
        } else {
            r2.push_back(r[i]);
            g2.push_back(g[i]);
            b2.push_back(b[i]);
            where.push_back(i);
        }
    }
    if (where.empty()) return true;
    GifColorType* rest = palette + reserved;
    int size = static_cast<int>(256 - reserved);
    std::vector<GifByteType> idx(where.size());
    if (GifQuantizeBuffer(static_cast<unsigned>(where.size()), 1, &size, r2.data(), g2.data(),
                          b2.data(), idx.data(), rest) == GIF_ERROR) {
        return false;
    }
    std::unordered_map<std::uint64_t, std::uint32_t> count;
    for (std::size_t k = 0; k < where.size(); ++k)
        ++count[(std::uint64_t{idx[k]} << 32) | rgb(r2[k], g2[k], b2[k])];
    std::uint32_t best[256] = {};
    for (const auto& [key, n] : count) {
        const auto k = static_cast<std::size_t>(key >> 32);
        if (n <= best[k]) continue;
        best[k] = n;
        const auto c = static_cast<std::uint32_t>(key);
        rest[k] = {static_cast<GifByteType>(c >> 16), static_cast<GifByteType>(c >> 8),
                   static_cast<GifByteType>(c)};
    }
    for (std::size_t k = 0; k < where.size(); ++k)
        index[where[k]] = static_cast<GifByteType>(reserved + idx[k]);
    return true;
}

}  // namespace

struct GifWriter::File {
    GifFileType* gif = nullptr;
    std::ostream* os = nullptr;
    bool failed = false;
};

namespace {

// giflib's output: the stream (a temporary of writeTextFile); a short count is its error.
int writeToStream(GifFileType* gif, const GifByteType* bytes, int n) {
    auto* os = static_cast<std::ostream*>(gif->UserData);
    os->write(reinterpret_cast<const char*>(bytes), n);
    return *os ? n : 0;
}

}  // namespace

GifWriter::GifWriter() : m_file(std::make_unique<File>()) {}

GifWriter::~GifWriter() {
    if (m_file->gif) {
        int err = 0;
        EGifCloseFile(m_file->gif, &err);
        m_file->gif = nullptr;
    }
}

bool GifWriter::open(std::ostream& os, const std::string& path, int width, int height,
                     std::string& error) {
    if (width < 1 || height < 1 || width > 65535 || height > 65535) {
        error = path + ": a GIF frame must be 1 to 65535 pixels wide and high, not " +
                std::to_string(width) + "x" + std::to_string(height);
        return false;
    }
    int err = 0;
    GifFileType* gif = EGifOpen(&os, writeToStream, &err);
    if (!gif) {
        error = gifError(path, err);
        return false;
    }
    m_file->gif = gif;
    m_file->os = &os;
    m_path = path;
    m_width = width;
    m_height = height;
    EGifSetGifVersion(gif, true);  // GIF89a: frame delays and looping
    if (EGifPutScreenDesc(gif, width, height, 8, 0, nullptr) == GIF_ERROR) {
        error = gifError(path, gif->Error);
        m_file->failed = true;
        return false;
    }
    // Loop forever (the NETSCAPE2.0 application extension, sub-block 1, count 0).
    static const char kNetscape[] = "NETSCAPE2.0";
    const unsigned char loop[3] = {1, 0, 0};
    if (EGifPutExtensionLeader(gif, APPLICATION_EXT_FUNC_CODE) == GIF_ERROR ||
        EGifPutExtensionBlock(gif, 11, kNetscape) == GIF_ERROR ||
        EGifPutExtensionBlock(gif, 3, loop) == GIF_ERROR ||
        EGifPutExtensionTrailer(gif) == GIF_ERROR) {
        error = gifError(path, gif->Error);
        m_file->failed = true;
        return false;
    }
    return true;
}

bool GifWriter::addFrame(const std::uint8_t* rgba, int delayMs, std::string& error) {
    GifFileType* gif = m_file->gif;
    if (!gif || m_file->failed) {
        error = m_path + ": the GIF is not open";
        return false;
    }
    const std::size_t n = static_cast<std::size_t>(m_width) * m_height;
    std::vector<GifByteType> r(n), g(n), b(n), index(n);
    for (std::size_t i = 0; i < n; ++i) {
        r[i] = rgba[4 * i];
        g[i] = rgba[4 * i + 1];
        b[i] = rgba[4 * i + 2];
    }
    ColorMapObject* map = GifMakeMapObject(256, nullptr);
    if (!map) {
        error = m_path + ": out of memory";
        return false;
    }
    bool ok = quantizeFrame(r, g, b, index, map->Colors);
    GraphicsControlBlock gcb{};
    gcb.DisposalMode = DISPOSE_DO_NOT;
    gcb.UserInputFlag = false;
    gcb.DelayTime = std::clamp(delayMs / 10, 1, 65535);  // hundredths of a second
    gcb.TransparentColor = NO_TRANSPARENT_COLOR;
    GifByteType ext[4];
    const std::size_t len = EGifGCBToExtension(&gcb, ext);
    ok = ok &&
         EGifPutExtension(gif, GRAPHICS_EXT_FUNC_CODE, static_cast<int>(len), ext) != GIF_ERROR;
    ok = ok && EGifPutImageDesc(gif, 0, 0, m_width, m_height, false, map) != GIF_ERROR;
    for (int y = 0; ok && y < m_height; ++y) {
        ok = EGifPutLine(gif, index.data() + static_cast<std::size_t>(y) * m_width, m_width) !=
             GIF_ERROR;
    }
    GifFreeMapObject(map);
    if (!ok) {
        error = gifError(m_path, gif->Error);
        m_file->failed = true;
        return false;
    }
    ++m_frames;
    return true;
}

bool GifWriter::close(std::string& error) {
    GifFileType* gif = m_file->gif;
    if (!gif) {
        error = m_path + ": the GIF is not open";
        return false;
    }
    int err = 0;
    const bool closed = EGifCloseFile(gif, &err) != GIF_ERROR;
    m_file->gif = nullptr;
    if (!closed || m_file->failed || m_frames == 0) {
        if (error.empty())
            error = closed ? m_path + ": no frame was written" : gifError(m_path, err);
        return false;
    }
    return true;
}

std::vector<std::uint8_t> CaptureRegion(Gui& gui, bool wholeWindow, int& width, int& height) {
    int fw = 0, fh = 0;
    const std::vector<std::uint8_t>& px = gui.lastFrame(fw, fh);
    int x0 = 0, y0 = 0, x1 = fw, y1 = fh;
    const auto& rects = gui.state().itemRects;
    if (const auto it = rects.find("canvas"); !wholeWindow && it != rects.end()) {
        // ImGui works in display pixels; the framebuffer may be scaled (HiDPI).
        const ImVec2 s = ImGui::GetIO().DisplayFramebufferScale;
        x0 = std::clamp(static_cast<int>(std::lround(it->second[0] * s.x)), 0, fw);
        y0 = std::clamp(static_cast<int>(std::lround(it->second[1] * s.y)), 0, fh);
        x1 = std::clamp(static_cast<int>(std::lround(it->second[2] * s.x)), x0, fw);
        y1 = std::clamp(static_cast<int>(std::lround(it->second[3] * s.y)), y0, fh);
    }
    width = x1 - x0;
    height = y1 - y0;
    std::vector<std::uint8_t> out(static_cast<std::size_t>(std::max(0, width)) *
                                  std::max(0, height) * 4);
    if (px.size() < static_cast<std::size_t>(fw) * fh * 4) {
        width = height = 0;
        return {};
    }
    for (int y = 0; y < height; ++y) {
        std::copy_n(px.begin() + (static_cast<std::ptrdiff_t>(y0 + y) * fw + x0) * 4,
                    static_cast<std::ptrdiff_t>(width) * 4,
                    out.begin() + static_cast<std::ptrdiff_t>(y) * width * 4);
    }
    return out;
}

namespace {

// An RGBA frame of w x h as one of w0 x h0: its top-left part, white where it is smaller.
std::vector<std::uint8_t> fitFrame(const std::vector<std::uint8_t>& px, int w, int h, int w0,
                                   int h0) {
    if (w == w0 && h == h0) return px;
    std::vector<std::uint8_t> out(static_cast<std::size_t>(w0) * h0 * 4, 255);
    for (int y = 0; y < std::min(h, h0); ++y) {
        const auto* from = px.data() + static_cast<std::size_t>(y) * w * 4;
        std::copy(from, from + static_cast<std::size_t>(std::min(w, w0)) * 4,
                  out.data() + static_cast<std::size_t>(y) * w0 * 4);
    }
    return out;
}

// Renders steps req.from .. req.to (every `every`) into a GIF on `os`; false with `error` set.
bool renderGifFrames(Gui& gui, const GifRequest& req, std::size_t every, std::ostream& os,
                     int& frames, std::string& error) {
    Engine& e = gui.state().engine;
    GifWriter gif;
    int w0 = 0, h0 = 0;  // the first frame's size: every frame of a GIF has it
    for (std::size_t p = req.from;; p = std::min(req.to, p + every)) {
        e.seek(p);
        // Two frames: ImGui settles a layout (tables measure columns) in the first.
        gui.frame();
        gui.frame();
        int w = 0, h = 0;
        const std::vector<std::uint8_t> px = CaptureRegion(gui, req.wholeWindow, w, h);
        if (gif.frames() == 0) {
            if (!gif.open(os, req.path, w, h, error)) return false;
            w0 = w;
            h0 = h;
        }
        // A caption that wraps onto another line resizes the canvas: the frame is cut or padded
        // (white) to the first frame's size, which every frame of a GIF has.
        const bool whole = w * h * 4 == static_cast<int>(px.size());
        if (!whole || !gif.addFrame(fitFrame(px, w, h, w0, h0).data(), req.delayMs, error)) {
            if (error.empty()) error = req.path + ": the window changed size during the export";
            return false;
        }
        if (p >= req.to || e.position() < p) break;  // done, or the run ended before `to`
    }
    frames = gif.frames();
    return gif.close(error);
}

}  // namespace

int exportStepsGif(Gui& gui, const GifRequest& req, std::string& error) {
    AppState& st = gui.state();
    Engine& e = st.engine;
    if (e.batch()) {
        error = req.path + ": this run has no steps to animate (more than " +
                std::to_string(Engine::kHistoryLimit) + " points)";
        return 0;
    }
    const std::size_t every = std::max<std::size_t>(1, req.every);
    if (req.to < req.from) {
        error = req.path + ": the last step (" + std::to_string(req.to) +
                ") comes before the first (" + std::to_string(req.from) + ")";
        return 0;
    }
    if ((req.to - req.from) / every + 1 > static_cast<std::size_t>(kMaxFrames)) {
        error = req.path + ": " + std::to_string((req.to - req.from) / every + 1) +
                " frames is too many (at most " + std::to_string(kMaxFrames) +
                "): take every n-th step";
        return 0;
    }
    const std::size_t saved = e.position();
    const bool wasRunning = st.run.running;
    st.run.running = false;
    gui.captureFrames(true);
    struct GifFailed {};
    int frames = 0;
    bool ok = false;
    try {
        // Written whole to a temporary, then renamed over the old file: a failure keeps it.
        writeTextFile(req.path, [&](std::ostream& os) {
            ok = renderGifFrames(gui, req, every, os, frames, error);
            // A stream that failed to write: writeTextFile says why (the system's reason).
            if (!ok && os) throw GifFailed{};
        });
    } catch (const GifFailed&) {
        ok = false;
    } catch (const std::runtime_error& failed) {
        error = failed.what();  // "cannot write PATH: why"
        ok = false;
    }
    gui.captureFrames(false);
    e.seek(saved);
    st.run.running = wasRunning;
    return ok ? frames : 0;
}

}  // namespace dlab::ui
