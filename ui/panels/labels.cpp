#include "ui/panels/labels.h"

#include <cmath>
#include <cstdio>
#include <limits>

namespace dlab::ui {

void LabelBoxes::add(ImVec2 c, ImVec2 size) {
    addBox(c.x - size.x / 2 - 2, c.y - size.y / 2, c.x + size.x / 2 + 2, c.y + size.y / 2);
}

bool LabelBoxes::isFree(float x0, float y0, float x1, float y1) const {
    for (const auto& b : boxes) {
        if (x0 < b[2] && b[0] < x1 && y0 < b[3] && b[1] < y1) return false;
    }
    return true;
}

namespace {

float cross(ImVec2 a, ImVec2 b, ImVec2 p) {
    return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

// Inside the screen triangle, either orientation (only to keep a label near its corner).
bool insideTriangle(const ImVec2 (&t)[3], ImVec2 p) {
    const float d0 = cross(t[0], t[1], p), d1 = cross(t[1], t[2], p), d2 = cross(t[2], t[0], p);
    return (d0 >= 0 && d1 >= 0 && d2 >= 0) || (d0 <= 0 && d1 <= 0 && d2 <= 0);
}

// A label of this size centred at c overlaps no placed label (2 px of room on either side).
bool boxFree(const LabelBoxes& labels, ImVec2 c, ImVec2 size) {
    return labels.isFree(c.x - size.x / 2 - 2, c.y - size.y / 2, c.x + size.x / 2 + 2,
                         c.y + size.y / 2);
}

}  // namespace

ImVec2 placeAlong(LabelBoxes& labels, ImVec2 vertex, ImVec2 anchor, const ImVec2 (&tri)[3],
                  ImVec2 size) {
    ImVec2 best = anchor;
    labels.lastFree = false;
    for (float f : {1.0f, 1.5f, 2.0f, 2.6f, 0.75f}) {
        const ImVec2 c(vertex.x + (anchor.x - vertex.x) * f, vertex.y + (anchor.y - vertex.y) * f);
        if (f != 1.0f && !insideTriangle(tri, c)) continue;
        if (boxFree(labels, c, size)) {
            best = c;
            labels.lastFree = true;
            break;
        }
    }
    labels.add(best, size);
    return best;
}

ImVec2 placeFirstFree(LabelBoxes& labels, std::initializer_list<ImVec2> candidates, ImVec2 size) {
    ImVec2 best = *candidates.begin();
    labels.lastFree = false;
    for (const ImVec2& c : candidates) {
        if (boxFree(labels, c, size)) {
            best = c;
            labels.lastFree = true;
            break;
        }
    }
    labels.add(best, size);
    return best;
}

ImVec2 placeInside(LabelBoxes& labels, const ImVec2 (&tri)[3], ImVec2 centre, ImVec2 size) {
    const float hw = size.x / 2 + 2, hh = size.y / 2;
    // First with the whole box inside the triangle, then with its centre inside.
    auto fits = [&](ImVec2 c, bool whole) {
        const ImVec2 box[4] = {
            {c.x - hw, c.y - hh}, {c.x + hw, c.y - hh}, {c.x - hw, c.y + hh}, {c.x + hw, c.y + hh}};
        for (const ImVec2& q : box) {
            if (whole && !insideTriangle(tri, q)) return false;
        }
        return insideTriangle(tri, c) && labels.isFree(c.x - hw, c.y - hh, c.x + hw, c.y + hh);
    };
    // The centroid, then towards each corner and each edge's midpoint, a little, then further.
    ImVec2 targets[6];
    for (int k = 0; k < 3; ++k) {
        targets[k] = tri[k];
        targets[k + 3] =
            ImVec2((tri[k].x + tri[(k + 1) % 3].x) / 2, (tri[k].y + tri[(k + 1) % 3].y) / 2);
    }
    ImVec2 best = centre;
    bool found = labels.isFree(centre.x - hw, centre.y - hh, centre.x + hw, centre.y + hh);
    for (int pass = 0; pass < 2 && !found; ++pass) {
        for (float f : {0.25f, 0.45f, 0.65f}) {
            for (const ImVec2& t : targets) {
                const ImVec2 c(centre.x + (t.x - centre.x) * f, centre.y + (t.y - centre.y) * f);
                if (!found && fits(c, pass == 0)) {
                    best = c;
                    found = true;
                }
            }
        }
    }
    labels.lastFree = found;
    labels.add(best, size);
    return best;
}

std::vector<ImVec2> placeVertexLabels(LabelBoxes& labels, const View& view,
                                      const std::vector<Vec2>& points, ImFont* font, float fontSize,
                                      float r) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<ImVec2> at(points.size(), ImVec2(nan, nan));
    std::vector<ImVec2> q(points.size());
    std::vector<bool> shown(points.size(), false);
    for (std::size_t i = 0; i < points.size(); ++i) {
        const glm::dvec2 s = view.toScreen(points[i]);
        q[i] = ImVec2(static_cast<float>(s.x), static_cast<float>(s.y));
        shown[i] = s.x >= view.origin.x - 20 && s.x <= view.origin.x + view.size.x + 20 &&
                   s.y >= view.origin.y - 20 && s.y <= view.origin.y + view.size.y + 20;
        if (shown[i]) labels.addBox(q[i].x - r, q[i].y - r, q[i].x + r, q[i].y + r);
    }
    char buf[32];
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (!shown[i]) continue;
        std::snprintf(buf, sizeof buf, "%zu", i);
        const ImVec2 size = font->CalcTextSizeA(fontSize, 1e9f, 0, buf);
        const float x = q[i].x, y = q[i].y, w = size.x, h = size.y;
        const ImVec2 spots[] = {{x + r + 2, y - r - h}, {x - r - 2 - w, y - r - h},
                                {x + r + 2, y + r},     {x - r - 2 - w, y + r},
                                {x + r + 3, y - h / 2}, {x - r - 3 - w, y - h / 2}};
        for (const ImVec2& p : spots) {
            if (labels.isFree(p.x, p.y, p.x + w, p.y + h)) {
                at[i] = p;
                labels.addBox(p.x, p.y, p.x + w, p.y + h);
                break;
            }
        }
    }
    return at;
}

}  // namespace dlab::ui
