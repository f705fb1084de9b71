// Reading back the text of a frame from ImGui's draw lists (see drawn_text.h).
#include "ui/render/drawn_text.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>

namespace dlab::ui {

namespace {

// A glyph of one of the atlas' fonts, keyed by the top-left corner of its texture rectangle.
struct AtlasGlyph {
    const ImFontGlyph* glyph;
    float spaceAdvance;  // of its font, at the font's own size
};
using UvKey = std::pair<std::int64_t, std::int64_t>;

UvKey uvKey(float u, float v) {
    return {std::llround(static_cast<double>(u) * 1048576.0),
            std::llround(static_cast<double>(v) * 1048576.0)};
}

std::map<UvKey, AtlasGlyph> atlasGlyphs() {
    std::map<UvKey, AtlasGlyph> out;
    const ImFontAtlas* atlas = ImGui::GetIO().Fonts;
    for (const ImFont* font : atlas->Fonts) {
        const ImFontGlyph* space = font->FindGlyphNoFallback(' ');
        const float spaceAdvance = space ? space->AdvanceX : font->FontSize * 0.3f;
        for (const ImFontGlyph& g : font->Glyphs) {
            if (!g.Visible) continue;
            out.emplace(uvKey(g.U0, g.V0), AtlasGlyph{&g, spaceAdvance});
        }
    }
    return out;
}

// A glyph found on screen: its pen position and advance in screen pixels.
struct Placed {
    unsigned codepoint;
    float lineTop, penX, advance, space, height;
    int list;
};

void appendUtf8(std::string& s, unsigned cp) {
    if (cp < 0x80) {
        s += static_cast<char>(cp);
    } else if (cp < 0x800) {
        s += static_cast<char>(0xC0 | (cp >> 6));
        s += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
        s += static_cast<char>(0xE0 | (cp >> 12));
        s += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        s += static_cast<char>(0x80 | (cp & 0x3F));
    }
}

bool inside(const ImVec4& clip, float x0, float y0, float x1, float y1) {
    return x0 >= clip.x - 0.5f && y0 >= clip.y - 0.5f && x1 <= clip.z + 0.5f && y1 <= clip.w + 0.5f;
}

// The glyph quads of one draw command: indices b, b+1, b+2, b, b+2, b+3 over a rectangle whose
// corners sample a glyph's whole texture rectangle.
void readCommand(const ImDrawList& dl, const ImDrawCmd& cmd, int list,
                 const std::map<UvKey, AtlasGlyph>& glyphs, std::vector<Placed>& out) {
    const ImDrawIdx* idx = dl.IdxBuffer.Data + cmd.IdxOffset;
    const ImDrawVert* vtx = dl.VtxBuffer.Data + cmd.VtxOffset;
    const auto nv = static_cast<unsigned>(dl.VtxBuffer.Size - static_cast<int>(cmd.VtxOffset));
    for (unsigned i = 0; i + 6 <= cmd.ElemCount;) {
        const unsigned b = idx[i];
        const bool quad = b + 3 < nv && idx[i + 1] == b + 1 && idx[i + 2] == b + 2 &&
                          idx[i + 3] == b && idx[i + 4] == b + 2 && idx[i + 5] == b + 3;
        const auto it = quad ? glyphs.find(uvKey(vtx[b].uv.x, vtx[b].uv.y)) : glyphs.end();
        if (it == glyphs.end()) {
            ++i;
            continue;
        }
        const ImFontGlyph& g = *it->second.glyph;
        const ImDrawVert &a = vtx[b], &c = vtx[b + 2];
        const bool whole = uvKey(c.uv.x, c.uv.y) == uvKey(g.U1, g.V1);
        const float gh = g.Y1 - g.Y0;
        const float scale = gh > 0 ? (c.pos.y - a.pos.y) / gh : 0;
        const float penX = a.pos.x - g.X0 * scale, advance = g.AdvanceX * scale;
        // Inside the clip by its pen box: a glyph whose ink overhangs its pen position (a "T" at
        // the start of a line) is still read whole.
        if (whole && gh > 0 &&
            inside(cmd.ClipRect, std::max(a.pos.x, penX), a.pos.y,
                   std::min(c.pos.x, penX + advance), c.pos.y)) {
            out.push_back({g.Codepoint, a.pos.y - g.Y0 * scale, penX, advance,
                           it->second.spaceAdvance * scale, (c.pos.y - a.pos.y), list});
        }
        i += 6;
    }
}

}  // namespace

std::vector<DrawnText> drawnText(const ImDrawData* data) {
    std::vector<DrawnText> out;
    if (!data || !data->Valid) return out;
    const std::map<UvKey, AtlasGlyph> glyphs = atlasGlyphs();
    std::vector<Placed> placed;
    for (int l = 0; l < data->CmdListsCount; ++l) {
        const ImDrawList& dl = *data->CmdLists[l];
        for (const ImDrawCmd& cmd : dl.CmdBuffer) {
            if (cmd.UserCallback == nullptr) readCommand(dl, cmd, l, glyphs, placed);
        }
    }
    // Lines: same list, same top (to half a pixel); then left to right.
    const auto line = [](const Placed& p) { return std::lround(p.lineTop * 2); };
    std::stable_sort(placed.begin(), placed.end(), [&](const Placed& p, const Placed& q) {
        if (p.list != q.list) return p.list < q.list;
        if (line(p) != line(q)) return line(p) < line(q);
        return p.penX < q.penX;
    });
    for (std::size_t i = 0; i < placed.size(); ++i) {
        const Placed& p = placed[i];
        const bool sameLine =
            i > 0 && placed[i - 1].list == p.list && line(placed[i - 1]) == line(p);
        const float gap = sameLine ? p.penX - (placed[i - 1].penX + placed[i - 1].advance) : 1e9f;
        if (!sameLine || gap > 2.5f * p.space || gap < -p.space) {
            out.push_back({"", p.penX, p.lineTop, p.penX, p.lineTop + p.height, p.list});
        } else if (gap > 0.5f * p.space) {
            out.back().text += ' ';
        }
        appendUtf8(out.back().text, p.codepoint);
        out.back().x1 = p.penX + p.advance;
        out.back().y1 = std::max(out.back().y1, p.lineTop + p.height);
    }
    return out;
}

std::vector<std::string> drawnLines(const std::vector<DrawnText>& runs) {
    std::vector<std::string> out;
    for (std::size_t i = 0; i < runs.size(); ++i) {
        const bool join = i > 0 && runs[i - 1].list == runs[i].list &&
                          std::lround(runs[i - 1].y0 * 2) == std::lround(runs[i].y0 * 2);
        if (join) {
            out.back() += " | " + runs[i].text;
        } else {
            out.push_back(runs[i].text);
        }
    }
    return out;
}

}  // namespace dlab::ui
