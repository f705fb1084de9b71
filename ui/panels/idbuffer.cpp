// The ID-buffer view: the locator's colour-ID buffer (the paper's idea: every triangle painted in
// a colour that encodes its id) as false colour or as the true encoded colours, drawn as a
// texture; the pixel under the mouse decoded to its triangle id and checked against exact
// containment; and whether the last locate hit (its hint already contained the point) or had to
// walk. The buffer is read through readIdBuffer() only, so that another buffer (the GL one) plugs
// in beside the CPU one.
#include "core/engine/predicates.h"
#include "ui/gui.h"
#include "ui/lesson_player.h"
#include "ui/panels/panels.h"
#include "ui/render/renderer.h"
#include "ui/render/triangle_ids.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

namespace dlab::ui {

// The texture the view shows and what it was made from.
struct IdBufferView {
    ImageSlot image;  // the renderer's (a GL texture, freed with the context)
    int texW = 0, texH = 0;
    std::uint64_t version = ~std::uint64_t{0};
    bool trueColours = false;
    int bufW = 0, bufH = 0;
    std::vector<std::uint8_t> rgba;
    // The last hover's exact check, cached per pixel and mesh version.
    int hoverI = -1, hoverJ = -1;
    std::uint64_t hoverVersion = ~std::uint64_t{0};
    IdBufferCopy copy;  // the GL buffer's ids
};

namespace {

constexpr int kMaxTexture = 800;  // texels per side; the magnifier shows full resolution

// Up to this many triangles, a hover checks every triangle for exact containment.
constexpr std::int32_t kExactScanLimit = 2000000;

bool containsClosed(const Mesh& m, std::int32_t t, Vec2 q) {
    const Vec2 a = m.G[m.V[3 * t]], b = m.G[m.V[3 * t + 1]], c = m.G[m.V[3 * t + 2]];
    return orient2d(a, b, q) >= 0 && orient2d(b, c, q) >= 0 && orient2d(c, a, q) >= 0;
}

bool realTriangle(const Engine& e, std::int32_t t) {
    return t >= 0 && t < e.mesh().numTriangles() && (!e.showsVirtual() || !e.isVirtualTriangle(t));
}

// A buffer pixel's colour as the view shows it: false colour, or the encoded colour.
ImU32 BufferColour(std::int32_t id, bool trueColours) {
    if (!trueColours) return IdFalseColour(id);
    const auto c = encodeTriangleId(id);
    return IM_COL32(c[0], c[1], c[2], 255);
}

void rebuildTexture(Renderer* renderer, IdBufferView& v, const IdBufferFrame& f, bool trueColours) {
    const double scale =
        std::min(1.0, static_cast<double>(kMaxTexture) / std::max(f.width, f.height));
    v.texW = std::max(1, static_cast<int>(f.width * scale));
    v.texH = std::max(1, static_cast<int>(f.height * scale));
    v.rgba.resize(static_cast<std::size_t>(v.texW) * v.texH * 4);
    for (int y = 0; y < v.texH; ++y) {
        const int j =
            f.height - 1 -
            static_cast<int>(static_cast<long long>(y) * f.height / v.texH);  // texture row 0 = top
        for (int x = 0; x < v.texW; ++x) {
            const int i = static_cast<int>(static_cast<long long>(x) * f.width / v.texW);
            const std::int32_t id = f.ids[static_cast<std::size_t>(j) * f.width + i];
            std::uint8_t* px = &v.rgba[(static_cast<std::size_t>(y) * v.texW + x) * 4];
            const ImU32 c = BufferColour(id, trueColours);
            px[0] = c & 255, px[1] = (c >> 8) & 255, px[2] = (c >> 16) & 255;
            px[3] = 255;  // the encoded alpha is data, not transparency
        }
    }
    if (renderer) renderer->uploadImage(v.image, v.texW, v.texH, v.rgba.data());
    v.bufW = f.width;
    v.bufH = f.height;
}

// The last locate of the journal up to the current position: its start triangle (the hint),
// steps and result; `justDone` while nothing has happened since it ended (the buffer is still
// the one it read).
struct LocateSummary {
    bool found = false, justDone = false;
    std::int32_t vertex = kNone, start = kNone, end = kNone, steps = 0;
};

LocateSummary lastLocate(const Engine& e) {
    LocateSummary s;
    const Journal* j = e.journal();
    if (!j) return s;
    const auto& ops = j->ops();
    std::size_t k = e.position();
    while (k > 0 && ops[k - 1].type != OpType::Located) --k;
    if (k == 0) return s;
    const Op& located = ops[k - 1];
    s.found = true;
    s.justDone = k == e.position();
    s.vertex = located.vertex;
    s.end = located.a;
    std::size_t first = k - 1;
    while (first > 0 && ops[first - 1].type == OpType::LocateStep &&
           ops[first - 1].vertex == located.vertex)
        --first;
    s.steps = static_cast<std::int32_t>(k - 1 - first);
    s.start = ops[first].a;
    return s;
}

// The id the buffer holds under world point p (kNone: nothing painted), from the grid of pixel
// centres; nullopt outside the image.
std::optional<std::int32_t> idUnder(const IdBufferFrame& f, Vec2 p) {
    if (f.width < 2 || f.height < 2 || !f.centre) return std::nullopt;
    const Vec2 c0 = f.centre(0, 0), cx = f.centre(1, 0), cy = f.centre(0, 1);
    const double dx = cx.x - c0.x, dy = cy.y - c0.y;
    if (!(dx > 0) || !(dy > 0)) return std::nullopt;
    long i = std::lround((p.x - c0.x) / dx), j = std::lround((p.y - c0.y) / dy);
    if (i < -1 || j < -1 || i > f.width || j > f.height) return std::nullopt;
    i = std::clamp(i, 0L, static_cast<long>(f.width - 1));  // the image's far sides are closed
    j = std::clamp(j, 0L, static_cast<long>(f.height - 1));
    return f.ids[static_cast<std::size_t>(j) * f.width + static_cast<std::size_t>(i)];
}

// The three cases a lesson asks about, as `pixel_outcome` names them: hit (the pixel's triangle
// holds the point), miss (a walk from the pixel's triangle), empty pixel (a walk from the last
// insertion). Told apart only while the buffer is the one the locate read; otherwise "walked".
void ShowLocateCase(const Engine& e, const LocateSummary& loc, const IdBufferFrame& f) {
    std::optional<std::int32_t> pixel;
    if (loc.justDone && e.options().locator != LocatorKind::IdBufferGlBatched && loc.vertex >= 0 &&
        static_cast<std::size_t>(loc.vertex) < e.mesh().G.size())
        pixel = idUnder(f, e.mesh().G[loc.vertex]);
    const char* s = loc.steps == 1 ? "" : "s";
    if (pixel && *pixel == kNone) {
        ImGui::TextWrapped(
            "Last locate (v%d): empty pixel - nothing painted there: walked %d "
            "step%s from the last insertion's t%d to t%d",
            loc.vertex, loc.steps, s, loc.start, loc.end);
    } else if (loc.steps == 0 && (!pixel || *pixel == loc.end)) {
        ImGui::TextWrapped("Last locate (v%d): HIT - the pixel's triangle t%d contains it",
                           loc.vertex, loc.end);
    } else if (pixel) {
        ImGui::TextWrapped(
            "Last locate (v%d): miss - the pixel's t%d does not hold it: walked %d "
            "step%s from t%d to t%d",
            loc.vertex, *pixel, loc.steps, s, loc.start, loc.end);
    } else {
        ImGui::TextWrapped("Last locate (v%d): walked %d step%s from t%d to t%d", loc.vertex,
                           loc.steps, s, loc.start, loc.end);
    }
}

void hexColour(const char* label, std::int32_t id) {
    const auto c = encodeTriangleId(id);
    ImGui::Text("%sRGBA %02X %02X %02X %02X", label, c[0], c[1], c[2], c[3]);
}

}  // namespace

std::uint32_t IdFalseColour(std::int32_t id) {
    if (id == kNone) return IM_COL32(238, 238, 238, 255);
    // Golden-ratio hues: neighbouring ids get far-apart colours.
    const double h = std::fmod(static_cast<double>(id) * 0.6180339887498949, 1.0);
    float r, g, b;
    ImGui::ColorConvertHSVtoRGB(static_cast<float>(h),
                                0.55f + 0.25f * static_cast<float>((id * 7) % 3) / 2.0f, 0.95f, r,
                                g, b);
    return IM_COL32(static_cast<int>(r * 255 + 0.5f), static_cast<int>(g * 255 + 0.5f),
                    static_cast<int>(b * 255 + 0.5f), 255);
}

bool readIdBuffer(const Engine& e, IdBufferFrame& out, IdBufferCopy& copy) {
    if (GpuIdBuffer* gl = e.idBufferGl()) {
        if (!gl->ready()) return false;
        // Reading back paints what is pending first (and bumps its version): read when the run
        // moved or the buffer changed since the copy.
        if (copy.engineVersion != e.version() || copy.bufferVersion != gl->version() ||
            copy.ids.empty()) {
            copy.ids = gl->readAll();
            copy.engineVersion = e.version();
            copy.bufferVersion = gl->version();
        }
        out.kind = e.options().locator == LocatorKind::IdBufferGlBatched ? "idbuffer-gl-batched"
                                                                         : "idbuffer-gl";
        out.width = gl->width();
        out.height = gl->height();
        out.ids = std::span<const std::int32_t>(copy.ids);
        out.centre = [gl](int i, int j) { return gl->pixelCentre(i, j); };
        return copy.ids.size() == static_cast<std::size_t>(out.width) * out.height;
    }
    // The inserter owns the locator and lets the panel look (reads only): const_cast here, in
    // the one place that touches the buffer, because Inserter::locator() is not const.
    Locator* loc = const_cast<Inserter&>(e.inserter()).locator();
    if (const auto* cpu = dynamic_cast<const IdBufferCpu*>(loc)) {
        if (cpu->pixels().empty()) return false;
        out.kind = "idbuffer-cpu";
        out.width = cpu->width();
        out.height = cpu->height();
        out.ids = std::span<const std::int32_t>(cpu->pixels());
        out.centre = [cpu](int i, int j) { return cpu->pixelCentre(i, j); };
        return true;
    }
    return false;
}

namespace {

constexpr int kMagnifierRadius = 5;  // the magnifier shows (2 r + 1)^2 buffer pixels

void OfferLocator(AppState& st, const char* label, LocatorKind kind, const char* item,
                  const char* tip) {
    if (ImGui::Button(label)) {
        InsertOptions o = st.engine.options();
        o.locator = kind;
        st.setUserOptions(o);
    }
    RecordItem(st, item);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tip);
}

// The run keeps no buffer: what the buffer is, and the locators that keep one.
void ShowNoIdBuffer(AppState& st) {
    const Engine& e = st.engine;
    ImGui::TextWrapped("The run's locator is \"%s\": it keeps no ID buffer.",
                       toString(e.options().locator));
    ImGui::TextWrapped(
        "The ID-buffer locator paints every triangle in a colour that encodes its id, and "
        "reads the "
        "pixel under each new point to find where to start the walk (the paper's section 4).");
    if (e.options().locator == LocatorKind::IdBufferCpu || needsGl(e.options().locator)) {
        ImGui::TextDisabled("The buffer is made at the first triangle: take a step.");
    } else {
        OfferLocator(st, "Use idbuffer-cpu", LocatorKind::IdBufferCpu, "idbuffer-use",
                     "A software rasterizer of triangle ids: the paper's idea without GL");
        if (e.hasGl()) {
            ImGui::SameLine();
            OfferLocator(st, "Use idbuffer-gl", LocatorKind::IdBufferGl, "idbuffer-use-gl",
                         "The paper's GL colour-ID buffer: an offscreen framebuffer, one pixel "
                         "read back per insertion");
        }
    }
    ImGui::TextDisabled(
        "or choose it under Locate in the toolbar (the run restarts with the same points)");
}

// The buffer's kind and size, and the choice of false or encoded colours.
void ShowBufferHeader(IdBufferViewState& vs, const IdBufferFrame& f) {
    ImGui::Text("%s, %d x %d pixels", f.kind, f.width, f.height);
    if (ImGui::RadioButton("false colour", !vs.trueColours)) vs.trueColours = false;
    ImGui::SameLine();
    if (ImGui::RadioButton("encoded colours", vs.trueColours)) vs.trueColours = true;
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "What the buffer really holds: id = (r << 16) | (g << 8) | b (+ a << 24).\nSmall ids "
            "look black; white means no triangle.");
}

// The last locate: did the buffer's hint already contain the point? And the run's hits so far.
void ShowLastLocate(AppState& st, const IdBufferFrame& f) {
    const LocateSummary loc = lastLocate(st.engine);
    if (loc.found) {
        ImGui::PushStyleColor(ImGuiCol_Text, loc.steps == 0 ? ImVec4(0.05f, 0.45f, 0.15f, 1)
                                                            : ImVec4(0.7f, 0.4f, 0.0f, 1));
        ShowLocateCase(st.engine, loc, f);
        ImGui::PopStyleColor();
    } else {
        ImGui::TextDisabled("No locate yet.");
    }
    if (const RunCounts& rc = UpdateRunCounts(st); rc.locates > 0) {
        ImGui::TextDisabled("locates so far: %lld of %lld hits, %lld walk steps in all",
                            static_cast<long long>(rc.hits), static_cast<long long>(rc.locates),
                            static_cast<long long>(rc.walkSteps));
    }
}

// Where the image goes and how large it is, with the magnifier's column beside it.
struct ImageLayout {
    float cell = 0, sideW = 0;  // a magnifier cell; the column beside the image
    ImVec2 size, p0;            // the image on screen
    float sx = 0, sy = 0;       // screen px per texel
};

ImageLayout LayOutImage(const AppState& st, const IdBufferView& v) {
    constexpr int kR = kMagnifierRadius;
    ImageLayout L;
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    L.cell = std::clamp(std::floor(ImGui::GetFontSize() * 0.6f), 6.0f,
                        std::floor(avail.x * 0.3f / (2 * kR + 1)));
    L.sideW = std::max((2 * kR + 1) * L.cell + 16, ImGui::CalcTextSize("RGBA 00 00 00 00").x + 8);
    // As tall as the panel allows, but never so small it cannot be read (the panel scrolls then;
    // a slide does not scroll: there it fits).
    const float widthLeft = avail.x - L.sideW - ImGui::GetStyle().ItemSpacing.x;
    const float side =
        std::max({80.0f, std::min(widthLeft, avail.y - ImGui::GetFrameHeightWithSpacing()),
                  slideMode(st) ? 0.0f : 0.6f * widthLeft});
    const float fit = side / static_cast<float>(std::max(v.texW, v.texH));
    L.size = ImVec2(std::floor(v.texW * fit), std::floor(v.texH * fit));
    L.sx = L.size.x / static_cast<float>(v.texW);
    L.sy = L.size.y / static_cast<float>(v.texH);
    L.p0 = ImGui::GetCursorScreenPos();
    return L;
}

// Where the point being inserted falls in the buffer (the pixel the locator reads).
void MarkCurrentVertex(ImDrawList* dl, const Engine& e, const IdBufferFrame& f,
                       const ImageLayout& L) {
    const std::int32_t cv = e.currentVertex();
    if (cv == kNone || cv >= e.mesh().numVertices() || f.width <= 1 || f.height <= 1) return;
    const Vec2 q = e.mesh().G[cv];
    const Vec2 lo = f.centre(0, 0), hi = f.centre(f.width - 1, f.height - 1);
    // Pixel centres span [0.5, W - 0.5] of the image's W pixel widths.
    const double fx = ((q.x - lo.x) / (hi.x - lo.x) * (f.width - 1) + 0.5) / f.width;
    const double fy = ((q.y - lo.y) / (hi.y - lo.y) * (f.height - 1) + 0.5) / f.height;
    if (std::isfinite(fx) && std::isfinite(fy) && fx >= -0.01 && fx <= 1.01 && fy >= -0.01 &&
        fy <= 1.01) {
        const ImVec2 m(L.p0.x + static_cast<float>(fx) * L.size.x,
                       L.p0.y + (1 - static_cast<float>(fy)) * L.size.y);
        dl->AddCircle(m, 7, IM_COL32(0, 0, 0, 255), 0, 2.5f);
        dl->AddCircle(m, 9, IM_COL32(255, 255, 255, 255), 0, 1.5f);
    }
}

// The buffer as an image, framed, with the current point marked; returns whether it is hovered.
bool DrawBufferImage(AppState& st, const IdBufferView& v, const IdBufferFrame& f,
                     const ImageLayout& L) {
    ImGui::Image(v.image.id(), L.size);
    RecordItem(st, "idbuffer-image");
    st.itemRects["idbuffer-image-whole"] = {L.p0.x, L.p0.y, L.p0.x + L.size.x, L.p0.y + L.size.y};
    const bool hovered = ImGui::IsItemHovered();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->AddRect(ImVec2(L.p0.x - 1, L.p0.y - 1),
                ImVec2(L.p0.x + L.size.x + 1, L.p0.y + L.size.y + 1), IM_COL32(120, 120, 130, 255));
    MarkCurrentVertex(dl, st.engine, f, L);
    return hovered;
}

// The texel under the mouse (the centre of the screen pixel, as GL samples it), marked on the
// image, and the buffer pixel it shows, decoded into the hover.
void PickHoveredPixel(IdBufferViewState::Hover& h, const IdBufferView& v, const IdBufferFrame& f,
                      const ImageLayout& L) {
    const ImVec2 mouse = ImGui::GetIO().MousePos;
    const int tx =
        std::clamp(static_cast<int>(std::floor((mouse.x + 0.5f - L.p0.x) / L.sx)), 0, v.texW - 1);
    const int ty =
        std::clamp(static_cast<int>(std::floor((mouse.y + 0.5f - L.p0.y) / L.sy)), 0, v.texH - 1);
    // Mark the texel on the image (the mouse pointer is not in screenshots or on every projector).
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 t0(L.p0.x + static_cast<float>(tx) * L.sx, L.p0.y + static_cast<float>(ty) * L.sy);
    dl->AddRect(ImVec2(t0.x - 4, t0.y - 4), ImVec2(t0.x + L.sx + 4, t0.y + L.sy + 4),
                IM_COL32(0, 0, 0, 255), 0, 0, 2);
    dl->AddRect(ImVec2(t0.x - 6, t0.y - 6), ImVec2(t0.x + L.sx + 6, t0.y + L.sy + 6),
                IM_COL32(255, 255, 255, 255), 0, 0, 2);
    h.valid = true;
    h.i = static_cast<int>(static_cast<long long>(tx) * f.width / v.texW);
    h.j = f.height - 1 - static_cast<int>(static_cast<long long>(ty) * f.height / v.texH);
    h.id = f.ids[static_cast<std::size_t>(h.j) * f.width + h.i];
    h.centre = f.centre(h.i, h.j);
}

// The exact check of the hovered pixel's centre: which triangle contains it, and whether that is
// the buffer's id (cached per pixel and mesh version).
void CheckHoverExactly(IdBufferViewState::Hover& h, IdBufferView& v, const Engine& e) {
    if (v.hoverI == h.i && v.hoverJ == h.j && v.hoverVersion == e.version()) return;
    const Mesh& m = e.mesh();
    v.hoverI = h.i;
    v.hoverJ = h.j;
    v.hoverVersion = e.version();
    h.exactTriangle = kNone;
    if (h.id != kNone && realTriangle(e, h.id) && containsClosed(m, h.id, h.centre)) {
        h.exactTriangle = h.id;
    } else if (m.numTriangles() <= kExactScanLimit) {
        for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
            if (realTriangle(e, t) && containsClosed(m, t, h.centre)) {
                h.exactTriangle = t;
                break;
            }
        }
    }
    h.agrees = h.id == kNone ? h.exactTriangle == kNone : h.exactTriangle == h.id;
}

// A magnifier: the buffer pixels around the hovered one, at full resolution.
void DrawMagnifier(const IdBufferViewState::Hover& h, const IdBufferFrame& f, bool trueColours,
                   float cell) {
    constexpr int kR = kMagnifierRadius;
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 m0 = ImGui::GetCursorScreenPos();
    for (int dy = -kR; dy <= kR; ++dy) {
        for (int dx = -kR; dx <= kR; ++dx) {
            const int i = h.i + dx, j = h.j - dy;
            ImU32 col = IM_COL32(200, 200, 200, 255);
            if (i >= 0 && j >= 0 && i < f.width && j < f.height)
                col = BufferColour(f.ids[static_cast<std::size_t>(j) * f.width + i], trueColours);
            const ImVec2 a(m0.x + (dx + kR) * cell, m0.y + (dy + kR) * cell);
            dl->AddRectFilled(a, ImVec2(a.x + cell - 1, a.y + cell - 1), col);
        }
    }
    const ImVec2 c0(m0.x + kR * cell - 1, m0.y + kR * cell - 1);
    dl->AddRect(c0, ImVec2(c0.x + cell + 1, c0.y + cell + 1), IM_COL32(0, 0, 0, 255), 0, 0, 2);
    ImGui::Dummy(ImVec2((2 * kR + 1) * cell, (2 * kR + 1) * cell));
}

// The hovered pixel decoded (pixel, id, colour) and the exact check's verdict.
void ShowHoverVerdict(const IdBufferViewState::Hover& h, float sideW) {
    ImGui::PushFont(fonts().mono);
    ImGui::Text("pixel %d, %d", h.i, h.j);
    if (h.id == kNone)
        ImGui::TextUnformatted("id: none");
    else
        ImGui::Text("id: t%d", h.id);
    hexColour("", h.id);
    ImGui::PopFont();
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + sideW);
    if (h.agrees) {
        ImGui::TextColored(ImVec4(0.05f, 0.45f, 0.15f, 1), "%s",
                           h.id == kNone ? "exact: outside every triangle - agrees"
                                         : "exact: contains the centre - agrees");
    } else if (h.exactTriangle != kNone) {
        ImGui::TextColored(
            ImVec4(0.8f, 0.1f, 0.1f, 1),
            "exact: the centre is in t%d - a stale or rounded hint (the walk fixes it)",
            h.exactTriangle);
    } else {
        ImGui::TextColored(ImVec4(0.8f, 0.1f, 0.1f, 1),
                           "exact: in no triangle - a stale hint (the walk fixes it)");
    }
    ImGui::PopTextWrapPos();
}

void IdBufferBody(AppState& st) {
    const Engine& e = st.engine;
    IdBufferViewState& vs = st.idBuffer;
    vs.hover.valid = false;
    if (!vs.cache) vs.cache = std::make_shared<IdBufferView>();
    IdBufferView& v = *vs.cache;
    IdBufferFrame f;
    if (!readIdBuffer(e, f, v.copy)) {
        ShowNoIdBuffer(st);
        return;
    }
    if (v.version != e.version() || v.trueColours != vs.trueColours || v.bufW != f.width ||
        v.bufH != f.height) {
        rebuildTexture(st.renderer, v, f, vs.trueColours);
        v.version = e.version();
        v.trueColours = vs.trueColours;
    }
    ShowBufferHeader(vs, f);
    ShowLastLocate(st, f);

    // ---- The image, and beside it the pixel under the mouse -----------------------------------
    const ImageLayout L = LayOutImage(st, v);
    const bool hovered = DrawBufferImage(st, v, f, L);
    ImGui::SameLine();
    ImGui::BeginGroup();
    if (!hovered) {
        ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + L.sideW);
        if (!slideMode(st))  // a slide has no room to spare: its image is small
            ImGui::TextDisabled(
                "Hover the image: the pixel under the mouse is decoded and checked exactly.");
        ImGui::PopTextWrapPos();
        ImGui::EndGroup();
        return;
    }
    IdBufferViewState::Hover& h = vs.hover;
    PickHoveredPixel(h, v, f, L);
    CheckHoverExactly(h, v, e);
    DrawMagnifier(h, f, vs.trueColours, L.cell);
    ShowHoverVerdict(h, L.sideW);
    ImGui::EndGroup();
    ImGui::TextDisabled("centre of pixel (%d, %d): (%.9g, %.9g)", h.i, h.j, h.centre.x, h.centre.y);
}

}  // namespace

void ShowIdBuffer(AppState& st) {
    ImGui::BeginChild("##idbody", ImVec2(0, 0), false);  // scrolls when the column is short
    IdBufferBody(st);
    ImGui::EndChild();
}

}  // namespace dlab::ui
