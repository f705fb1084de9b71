// The text a frame drew, read back from its draw lists: every glyph quad that samples the font
// atlas, mapped back to its character, and grouped into runs along one line. What `lesson check`
// reads on a rendered slide: table cells, statistics, panel verdicts, banner and canvas labels
// alike, whichever code drew them.
#pragma once

#include <string>
#include <vector>

struct ImDrawData;

namespace dlab::ui {

// One run of text: glyphs on one line, a space where the pen skipped about a space's width. A
// wider gap (table columns, labels side by side) starts a new run. Screen pixels.
struct DrawnText {
    std::string text;  // UTF-8
    float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int list = 0;  // the draw list (one per window or child window)
};

// The runs of `data` (the current ImGui context's fonts decode it), in draw order of their lists,
// top to bottom and left to right within each. Glyphs outside their clip rectangle, or cut by it,
// are not read.
std::vector<DrawnText> drawnText(const ImDrawData* data);

// The runs as lines: runs of one draw list side by side on one line joined with " | " (a table
// row: "flips | 24 (3.0 per insertion)").
std::vector<std::string> drawnLines(const std::vector<DrawnText>& runs);

}  // namespace dlab::ui
