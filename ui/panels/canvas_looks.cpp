// The canvas' marks with their looks and meanings (one table), and the legend drawn from it.
#include "ui/panels/canvas_looks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace dlab::ui {

namespace {

constexpr std::array<Look, kMarkCount> kLooks{{
    {Mark::WalkVisited, Shape::Fill, IM_COL32(255, 244, 190, 255), "walk: triangles visited"},
    {Mark::WalkNow, Shape::Fill, IM_COL32(255, 214, 90, 255), "walk: triangle it is in now"},
    {Mark::LineL, Shape::Arrow, IM_COL32(30, 90, 220, 255), "walk: line L to the new point"},
    {Mark::NewTriangles, Shape::Fill, IM_COL32(200, 224, 248, 255), "triangles just made"},
    {Mark::TestEdge, Shape::Line, IM_COL32(240, 120, 0, 255), "edge under test"},
    {Mark::CircleFlip, Shape::Ring, IM_COL32(215, 40, 40, 255), "circle holds the point: flip"},
    {Mark::CircleKeep, Shape::Ring, IM_COL32(30, 150, 60, 255), "circle misses the point: keep"},
    {Mark::HalfPlaneFlip, Shape::Fill, IM_COL32(215, 40, 40, 45),
     "beyond the hull edge, holds the point: flip"},
    {Mark::HalfPlaneKeep, Shape::Fill, IM_COL32(30, 150, 60, 45),
     "beyond the hull edge, misses the point: keep"},
    {Mark::FlippedEdge, Shape::Line, IM_COL32(215, 40, 40, 255), "edge made by a flip"},
    {Mark::NewEdge, Shape::Line, IM_COL32(32, 128, 32, 255), "edge the split made"},
    {Mark::QueuedEdge, Shape::Dashed, IM_COL32(135, 60, 205, 255), "edge still to test"},
    {Mark::QueueOrder, Shape::Badge, IM_COL32(135, 60, 205, 255), "order of the tests (1 = next)"},
    {Mark::QueuePushed, Shape::Badge, IM_COL32(95, 35, 160, 255), "order pushed (1 = first)"},
    {Mark::QueuedOnHull, Shape::Dashed, IM_COL32(150, 150, 160, 255),
     "on the stack, a hull edge: nothing to test"},
    {Mark::NextPoint, Shape::Diamond, IM_COL32(0, 150, 215, 255), "point being inserted, or next"},
    {Mark::QueuedPoint, Shape::Ring, IM_COL32(140, 140, 150, 255), "point not inserted yet"},
    {Mark::SkippedPoint, Shape::Cross, IM_COL32(200, 30, 30, 255), "duplicate point, skipped"},
    {Mark::SelectedCorner, Shape::Dot, IM_COL32(0, 165, 175, 255), "selected corner"},
    {Mark::HoveredCorner, Shape::Ring, IM_COL32(60, 60, 75, 255), "corner under the mouse"},
    {Mark::ChangedCorner, Shape::Badge, IM_COL32(150, 95, 0, 255), "corner this step changed"},
    {Mark::CornerMove, Shape::Arrow, IM_COL32(120, 70, 20, 255), "last corner operator"},
    {Mark::Circumcircle, Shape::Ring, IM_COL32(150, 150, 200, 160), "circumcircle"},
    {Mark::Voronoi, Shape::Line, IM_COL32(90, 160, 40, 255), "Voronoi edge"},
    {Mark::IdPixel, Shape::Dot, IM_COL32(0, 130, 120, 255), "ID-buffer pixel, a dot at its centre"},
    {Mark::IdPixelNow, Shape::Line, IM_COL32(205, 95, 0, 255), "pixel under the point to insert"},
    {Mark::GhostBand, Shape::Fill, IM_COL32(150, 155, 170, 90), "outside the hull (ghost)"},
    {Mark::NotYetDelaunay, Shape::Ring, IM_COL32(245, 110, 150, 255),
     "vertex in the circle across an edge: not Delaunay yet"},
    {Mark::Violation, Shape::Line, IM_COL32(230, 0, 0, 255), "broken rule (validate)"},
    {Mark::HullDent, Shape::Fill, IM_COL32(230, 0, 0, 90), "hull dent: triangle missing"},
    {Mark::HullEdgeMissing, Shape::Dashed, IM_COL32(230, 0, 0, 255), "hull edge the mesh lacks"},
    {Mark::ExpressionPath, Shape::Arrow, IM_COL32(214, 0, 120, 255), "expression's path"},
    {Mark::StudentTriangle, Shape::Line, IM_COL32(200, 0, 160, 255),
     "student's triangle, not ours"},
    {Mark::MeshNotDelaunay, Shape::Ring, IM_COL32(205, 30, 40, 255),
     "circle with a vertex inside (Check)"},
    {Mark::MeshProblem, Shape::Fill, IM_COL32(205, 30, 40, 110), "mesh problem (Check)"},
    {Mark::MeshPicked, Shape::Line, IM_COL32(150, 0, 160, 255), "problem picked in Check"},
    {Mark::OnlyInMesh, Shape::Line, IM_COL32(205, 30, 40, 255), "edge only in this mesh"},
    {Mark::OnlyInDelaunay, Shape::Dashed, IM_COL32(20, 140, 60, 255),
     "edge only in the Delaunay triangulation"},
    {Mark::ConstrainedEdge, Shape::Line, IM_COL32(90, 40, 150, 255),
     "constrained edge: never flipped"},
    {Mark::EditSegment, Shape::Dashed, IM_COL32(90, 40, 150, 255), "segment being constrained"},
    {Mark::CrossingEdge, Shape::Line, IM_COL32(230, 90, 20, 255),
     "edge crossing the segment: flipped out"},
    {Mark::EarTriangle, Shape::Fill, IM_COL32(205, 235, 200, 255), "ear tested (removal)"},
    {Mark::RemovedPoint, Shape::Ring, IM_COL32(160, 160, 170, 255),
     "vertex an edit removes, or removed"},
}};

constexpr bool inMarkOrder() {
    for (std::size_t i = 0; i < kLooks.size(); ++i) {
        if (static_cast<std::size_t>(kLooks[i].mark) != i) return false;
    }
    return true;
}
static_assert(inMarkOrder(), "kLooks lists the marks in Mark order");

// The sample of a look in the box [a, b].
void DrawSample(ImDrawList* dl, const Look& look, ImVec2 a, ImVec2 b) {
    const ImVec2 c((a.x + b.x) / 2, (a.y + b.y) / 2);
    const float h = b.y - a.y, r = h * 0.32f;
    const ImU32 col = look.colour;
    switch (look.shape) {
        case Shape::Fill:
            dl->AddRectFilled(ImVec2(a.x, a.y + 2), ImVec2(b.x, b.y - 2), col);
            dl->AddRect(ImVec2(a.x, a.y + 2), ImVec2(b.x, b.y - 2), IM_COL32(120, 125, 140, 255));
            break;
        case Shape::Line: dl->AddLine(ImVec2(a.x, c.y), ImVec2(b.x, c.y), col, 3.0f); break;
        case Shape::Dashed:
        case Shape::Badge:
            for (float x = a.x; x < b.x; x += 8)
                dl->AddLine(ImVec2(x, c.y), ImVec2(std::min(b.x, x + 5), c.y), col, 2.5f);
            if (look.shape == Shape::Dashed) break;
            if (look.mark == Mark::QueueOrder || look.mark == Mark::QueuePushed) {  // its disc
                dl->AddCircleFilled(c, h * 0.42f, col);
                dl->AddCircleFilled(c, h * 0.12f, IM_COL32(255, 255, 255, 255));
            } else {  // a label on a filled box
                dl->AddRectFilled(ImVec2(c.x - h * 0.5f, a.y + 2), ImVec2(c.x + h * 0.5f, b.y - 2),
                                  col, 3);
            }
            break;
        case Shape::Arrow:
            dl->AddLine(ImVec2(a.x, c.y), ImVec2(b.x - 4, c.y), col, 2.0f);
            dl->AddTriangleFilled(ImVec2(b.x, c.y), ImVec2(b.x - 8, c.y - 4),
                                  ImVec2(b.x - 8, c.y + 4), col);
            break;
        case Shape::Ring: dl->AddCircle(c, r + 1, col, 0, 2.0f); break;
        case Shape::Dot: dl->AddCircleFilled(c, r + 1, col); break;
        case Shape::Diamond:
            dl->AddQuadFilled(ImVec2(c.x, c.y - r - 2), ImVec2(c.x + r + 2, c.y),
                              ImVec2(c.x, c.y + r + 2), ImVec2(c.x - r - 2, c.y), col);
            break;
        case Shape::Cross:
            dl->AddLine(ImVec2(c.x - r, c.y - r), ImVec2(c.x + r, c.y + r), col, 2.0f);
            dl->AddLine(ImVec2(c.x - r, c.y + r), ImVec2(c.x + r, c.y - r), col, 2.0f);
            break;
    }
}

}  // namespace

std::span<const Look> canvasLooks() { return kLooks; }

namespace {

// Whether the segment p -> q meets the box [a, b] (Liang-Barsky clipping).
bool segmentMeetsBox(ImVec2 p, ImVec2 q, ImVec2 a, ImVec2 b) {
    float t0 = 0, t1 = 1;
    const float d[2] = {q.x - p.x, q.y - p.y};
    const float from[2] = {p.x, p.y}, lo[2] = {a.x, a.y}, hi[2] = {b.x, b.y};
    for (int k = 0; k < 2; ++k) {
        if (d[k] == 0) {
            if (from[k] < lo[k] || from[k] > hi[k]) return false;
            continue;
        }
        float ta = (lo[k] - from[k]) / d[k], tb = (hi[k] - from[k]) / d[k];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 > t1) return false;
    }
    return true;
}

}  // namespace

float coveredWeight(ImVec2 a, ImVec2 b, std::span<const BusyPoint> busy, float margin) {
    const ImVec2 a2(a.x - margin, a.y - margin), b2(b.x + margin, b.y + margin);
    float covered = 0;
    for (const BusyPoint& p : busy) {
        const bool meets =
            p.edge ? segmentMeetsBox(p.at, p.to, a2, b2)
                   : std::min(p.at.x, p.to.x) <= b2.x && std::max(p.at.x, p.to.x) >= a2.x &&
                         std::min(p.at.y, p.to.y) <= b2.y && std::max(p.at.y, p.to.y) >= a2.y;
        if (meets) covered += p.weight;
    }
    return covered;
}

ImVec2 placeLegend(ImVec2 lo, ImVec2 hi, ImVec2 size, std::span<const BusyPoint> busy,
                   bool anywhere) {
    const float left = lo.x + 6, right = std::max(left, hi.x - size.x - 6), top = lo.y + 6,
                bottom = std::max(top, hi.y - size.y - 6), midX = (left + right) / 2,
                midY = (top + bottom) / 2;
    std::vector<ImVec2> places = {{right, top}, {right, bottom}, {left, top},    {left, bottom},
                                  {midX, top},  {right, midY},   {midX, bottom}, {left, midY}};
    if (anywhere) {
        constexpr int kSteps = 8;
        for (int i = 0; i <= kSteps; ++i) {
            for (int j = 0; j <= kSteps; ++j)
                places.emplace_back(left + (right - left) * static_cast<float>(j) / kSteps,
                                    top + (bottom - top) * static_cast<float>(i) / kSteps);
        }
    }
    ImVec2 best = places[0];
    float least = -1;
    for (const ImVec2& c : places) {
        const float covered = coveredWeight(c, ImVec2(c.x + size.x, c.y + size.y), busy, 4);
        if (least < 0 || covered < least) {
            least = covered;
            best = c;
        }
        if (least == 0) break;
    }
    return best;
}

ImVec4 DrawCanvasLegend(ImDrawList* dl, ImVec2 lo, ImVec2 hi, const MarksDrawn& drawn,
                        float fontSize, std::span<const BusyPoint> busy, bool anywhere) {
    if (drawn.none()) return ImVec4(0, 0, 0, 0);
    ImFont* font = ImGui::GetFont();
    const float row = std::ceil(fontSize * 1.25f), sample = std::ceil(fontSize * 1.9f),
                pad = std::ceil(fontSize * 0.4f);
    float textW = 0;
    int rows = 0;
    for (const Look& look : kLooks) {
        if (!drawn[static_cast<std::size_t>(look.mark)]) continue;
        textW = std::max(textW, font->CalcTextSizeA(fontSize, 1e9f, 0, look.meaning).x);
        ++rows;
    }
    const float w = pad * 3 + sample + textW, h = pad * 2 + row * static_cast<float>(rows);
    const ImVec2 a = placeLegend(lo, hi, ImVec2(w, h), busy, anywhere);
    const ImVec2 b(a.x + w, a.y + h);
    dl->AddRectFilled(a, b, IM_COL32(255, 255, 255, 230), 4);
    dl->AddRect(a, b, IM_COL32(170, 175, 190, 255), 4);
    float y = a.y + pad;
    for (const Look& look : kLooks) {
        if (!drawn[static_cast<std::size_t>(look.mark)]) continue;
        DrawSample(dl, look, ImVec2(a.x + pad, y + 1), ImVec2(a.x + pad + sample, y + row - 1));
        dl->AddText(font, fontSize, ImVec2(a.x + pad * 2 + sample, y + (row - fontSize) / 2),
                    IM_COL32(30, 30, 40, 255), look.meaning);
        y += row;
    }
    return ImVec4(a.x, a.y, b.x, b.y);
}

}  // namespace dlab::ui
