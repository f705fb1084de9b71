// Label placement on the canvas: vertex labels try the four sides of their point, corner labels
// slide along their bisector, each to the first spot that meets no label placed before it, so
// that crowded vertices stay readable. A label with no free spot is not drawn (a dense mesh
// shows the labels that fit, not a pile of them).
#pragma once

#include "core/engine/geometry.h"
#include "ui/app_state.h"

#include <imgui.h>

#include <array>
#include <initializer_list>
#include <vector>

namespace dlab::ui {

struct LabelBoxes {
    std::vector<std::array<float, 4>> boxes;  // x0, y0, x1, y1
    // Whether the last place* call found a free spot (else it placed the label at its first
    // candidate, over another: the caller hides it, and may take it back with dropLast()).
    bool lastFree = true;
    void add(ImVec2 centre, ImVec2 size);
    void dropLast() { boxes.pop_back(); }
    void addBox(float x0, float y0, float x1, float y1) { boxes.push_back({x0, y0, x1, y1}); }
    bool isFree(float x0, float y0, float x1, float y1) const;
};

// Where corner labels go: `anchor` is the usual spot on the bisector from `vertex`; the label
// moves along it (within the triangle `tri`) to the first spot that is free. Returns the
// label's centre and registers it.
ImVec2 placeAlong(LabelBoxes& labels, ImVec2 vertex, ImVec2 anchor, const ImVec2 (&tri)[3],
                  ImVec2 size);

// The first of the candidate centres where the label meets no other, else the first one.
// Returns the label's centre and registers it.
ImVec2 placeFirstFree(LabelBoxes& labels, std::initializer_list<ImVec2> candidates, ImVec2 size);

// Where a triangle's label goes: its centroid `centre`, else the first free spot nearer one of
// its corners or edges (the label's box inside the triangle); the centroid when none is free.
// Returns the label's centre and registers it.
ImVec2 placeInside(LabelBoxes& labels, const ImVec2 (&tri)[3], ImVec2 centre, ImVec2 size);

// The top-left corner of each point's label (top-right of the point, else top-left,
// bottom-right, bottom-left, right, left of it), registered with the points' markers; NaN for
// points off the canvas and for labels that would meet another (hidden).
std::vector<ImVec2> placeVertexLabels(LabelBoxes& labels, const View& view,
                                      const std::vector<Vec2>& points, ImFont* font, float fontSize,
                                      float radius);

}  // namespace dlab::ui
