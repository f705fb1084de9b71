// The panels: free functions ShowXxx(AppState&), one file each (ImGui's demo style). A new panel
// is one file plus one line in kSideTabs (app.cpp) or a call in ShowApplication.
#pragma once

#include "ui/app_state.h"

#include <string>

namespace dlab::ui {

void ShowMenuBar(AppState& state);       // panel_menu.cpp: File, View, Run, Generate, Help
void ShowToolbar(AppState& state);       // panel_toolbar.cpp: stepping, run/pause, speed, modes
void ShowCaption(AppState& state);       // panel_toolbar.cpp: "[17/245] edge 4-9 is Delaunay"
void ShowTimeline(AppState& state);      // panel_toolbar.cpp: scrubber over all operations
void ShowCanvas(AppState& state);        // panel_canvas.cpp: the mesh and every overlay
void ShowCornerTable(AppState& state);   // panel_corner_table.cpp: c, t, V, O, n, p, l, r
void ShowVertexTable(AppState& state);   // panel_corner_table.cpp: G (vertex coordinates)
void ShowInspector(AppState& state);     // panel_inspector.cpp: the selected corner's operators
void ShowMessages(AppState& state);      // panel_messages.cpp: every warning and error
void ShowHelp(AppState& state);          // panel_help.cpp: F1 overlay with all shortcuts

// Loads a point file into the run; on bad input logs one line (file:line: what) and changes
// nothing (panel_menu.cpp).
bool LoadPointFile(AppState& state, const std::string& path);

// Where corner c's label sits on the canvas (screen pixels); false when its triangle is not
// drawn or too small for a label (panel_canvas.cpp).
bool CornerAnchor(const AppState& state, std::int32_t corner, float& x, float& y);

// Remembers the last ImGui item's rectangle under `name` in state.itemRects (app.cpp).
void RecordItem(AppState& state, const char* name);

// Keyboard shortcuts (app.cpp); ignored while a text field has the keyboard.
void HandleShortcuts(AppState& state);
// Advances a running animation by this frame's share of operations (panel_toolbar.cpp).
void AdvanceRun(AppState& state, double dtSeconds);

// A side-column tab: issue 5's debugging panels slot in here.
struct SideTab {
    const char* name;
    void (*show)(AppState&);
};

}  // namespace dlab::ui
