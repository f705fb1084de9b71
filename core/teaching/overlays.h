// What the canvas draws over the mesh: one switch per overlay, and the one table of their names
// that lessons, sessions, settings, the View menu's state and `dtlab render --overlay` read, so
// that adding an overlay is one edit here.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>

namespace dlab {

struct Overlays {
    bool fill = true;  // light fill of the triangles
    bool vertexIds = true;
    bool cornerIds = true;  // corner ids inside their corners (when zoomed in enough)
    bool triangleIds = false;
    bool walk = true;            // the current locate's path and the line L
    bool flipQueue = true;       // edges still to test
    bool queueOrder = true;      // and their order (1 = tested next); lessons name it to show it
    bool queuePushed = false;    // or the order they were pushed in (1 = first; the last is next)
    bool flipped = true;         // edges flipped by the current insertion
    bool circumcircles = false;  // every triangle's circumcircle
    bool voronoi = false;
    bool idBufferGrid = false;     // the ID buffer's pixels: their borders and centres
    bool pendingPoints = true;     // points not inserted yet
    bool virtualTriangles = true;  // super-triangle (super mode) while the run is in progress
    bool violations = true;        // what validate() finds: broken rules, edges not Delaunay yet
    bool legend = false;           // what each colour and line means (L; always on slides)
};

struct OverlaySwitch {
    const char* name;  // as lessons and --overlay write it; sessions and settings use '_' for '-'
    bool Overlays::*flag;
    bool perStop;  // a lesson stop that names overlays turns the others off (not the legend)
};

inline constexpr OverlaySwitch kOverlaySwitches[] = {
    {"fill", &Overlays::fill, true},
    {"vertex-ids", &Overlays::vertexIds, true},
    {"corner-ids", &Overlays::cornerIds, true},
    {"triangle-ids", &Overlays::triangleIds, true},
    {"walk", &Overlays::walk, true},
    {"flip-queue", &Overlays::flipQueue, true},
    {"flip-queue-order", &Overlays::queueOrder, true},
    {"flip-queue-pushed", &Overlays::queuePushed, true},
    {"flipped", &Overlays::flipped, true},
    {"circumcircles", &Overlays::circumcircles, true},
    {"voronoi", &Overlays::voronoi, true},
    {"idbuffer-grid", &Overlays::idBufferGrid, true},
    {"pending-points", &Overlays::pendingPoints, true},
    {"virtual-triangles", &Overlays::virtualTriangles, true},
    {"violations", &Overlays::violations, true},
    {"legend", &Overlays::legend, false},
};

// The switch called `name` ("vertex-ids" or "vertex_ids"), nullptr when there is none.
inline bool* overlaySwitch(Overlays& o, std::string_view name) {
    for (const OverlaySwitch& s : kOverlaySwitches) {
        const std::string_view n = s.name;
        bool same = n.size() == name.size();
        for (std::size_t i = 0; same && i < n.size(); ++i)
            same = n[i] == name[i] || (n[i] == '-' && name[i] == '_');
        if (same) return &(o.*s.flag);
    }
    return nullptr;
}

// "vertex_ids": the name as sessions and settings keep it.
inline std::string overlayKey(const OverlaySwitch& s) {
    std::string k = s.name;
    for (char& c : k)
        if (c == '-') c = '_';
    return k;
}

// The names a lesson stop may list: every switch, and "idbuffer" (the ID-buffer panel's view).
inline constexpr auto kOverlayNames = [] {
    std::array<const char*, std::size(kOverlaySwitches) + 1> names{};
    for (std::size_t i = 0; i < std::size(kOverlaySwitches); ++i)
        names[i] = kOverlaySwitches[i].name;
    names.back() = "idbuffer";
    return names;
}();

}  // namespace dlab
