// The panels: free functions ShowXxx(AppState&), one file each (ImGui's demo style). A new panel
// is one file plus one line in kSideTabs (app.cpp) or a call in ShowApplication.
#pragma once

#include "core/engine/predicates.h"
#include "ui/app_state.h"

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <imgui.h>

namespace dlab::ui {

// A screen position (View::toScreen) as ImGui's vector.
inline ImVec2 toIm(glm::dvec2 v) {
    return ImVec2(static_cast<float>(v.x), static_cast<float>(v.y));
}

void ShowMenuBar(AppState& state);  // menu.cpp: File, View, Run, Generate, Help
void ShowToolbar(AppState& state);  // toolbar.cpp: stepping, run/pause, speed, modes
void ShowCaption(AppState& state);  // toolbar.cpp: "[op 17] InCircleTest: ... is Delaunay"
// "[op 17]": the one numbering of operations the GUI shows (caption, lesson banner, messages,
// stops): op N is the N-th operation done, position N of the timeline ("op 17 of 245").
inline std::string opLabel(std::size_t position) { return "[op " + std::to_string(position) + "]"; }
// The caption's text: the current operation, why stepping is off (batch), or how to start.
std::string captionText(const AppState& state);
void ShowTimeline(AppState& state);  // toolbar.cpp: scrubber over all operations
// "op 45 of 120   |   9 of 12 points inserted, 1 duplicate skipped": the timeline's words.
std::string timelineText(const Engine& engine);
// "9 of 12 points inserted, 1 duplicate skipped": the one count of points done, everywhere
// (the flip algorithm on a given mesh inserts none and says so).
std::string pointCountsText(const Engine& engine);
struct LabelBoxes;
void ShowCanvas(AppState& state);  // canvas.cpp: the mesh and every overlay
// The side tabs' ids ("corner-table", ..., "check"), in order (app.cpp's table).
std::vector<std::string> sideTabIds();
// ghosts.cpp: exact mode's ghost triangles as grey bands beyond the hull edges (overlay
// "virtual-triangles"), labelled when triangle ids are on; true when a band was drawn.
bool DrawGhostTriangles(AppState& state, ImDrawList* dl);
// ghosts.cpp: super mode, run in progress, vertex ids on: the super-triangle's vertices named as
// the tables name them ("4 (s0)"), beside the vertex or at the canvas's edge towards it, clear of
// the labels placed before (registered in `labels`).
void LabelSuperVertices(AppState& state, ImDrawList* dl, LabelBoxes& labels);
// Exact mode, run in progress: ghost triangle t on the screen as a wedge, its hull edge a -> b
// and the sides it leaves the hull along at a and at b (da, db: along the bisectors at the hull
// vertices, so that neighbouring wedges share their sides; a depth of 1 along da and db is a
// depth of 1 from the edge). False for any other triangle.
bool ghostWedge(const AppState& state, std::int32_t t, ImVec2& a, ImVec2& b, ImVec2& da,
                ImVec2& db);
void ShowCornerTable(AppState& state);  // corner_table.cpp: c, t, V, O, n, p, l, r
void ShowVertexTable(AppState& state);  // corner_table.cpp: G (vertex coordinates)
void ShowInspector(AppState& state);    // inspector.cpp: the selected corner's operators
void ShowMessages(AppState& state);     // messages.cpp: every warning and error
// check.cpp: an opened mesh's exact check (problems listed, picked, drawn) and the check of the
// mesh at the current step.
void ShowCheck(AppState& state);
void DrawCheckOverlay(AppState& state, ImDrawList* dl);
// Opens a mesh file (.ele, .off, .obj, .corners, a corner table or Delaunator JSON), checks
// it and runs the flip algorithm on it (only shows it when it is no triangulation); on bad
// input logs one line and changes nothing.
bool openMeshFile(AppState& state, const std::string& path);
void ShowHelp(AppState& state);  // help.cpp: F1 overlay with all shortcuts
// The help's rows: keys, and what they do.
const std::vector<std::array<const char*, 2>>& helpRows();
void ShowLesson(AppState& state);  // lesson.cpp: the lesson's text and questions
// lesson.cpp: presentation mode with a lesson: canvas, the stop's text, its side tab and its
// question, sized to the window (nothing scrolls the question away), no toolbar or messages.
void ShowSlide(AppState& state);

// Loads a point file into the run; on bad input logs one line (file:line: what) and changes
// nothing (menu.cpp).
bool loadPointFile(AppState& state, const std::string& path);

// Where corner c's label sits on the canvas (screen pixels); false when its triangle is not
// drawn or too small for a label (canvas.cpp).
bool cornerAnchor(const AppState& state, std::int32_t corner, float& x, float& y);

// ImGui draws each draw list with 16-bit indices (at most 65536 vertices, on every target:
// ui/gl/imgui_gl.h): the mesh itself is our GL code, and every overlay loop on the canvas asks
// here before adding about `vertices` more. Past the budget it answers false and the canvas says
// that shapes were left out (zoom in), instead of aborting (canvas.cpp).
bool canvasHasRoom(AppState& state, const ImDrawList* drawList, unsigned vertices);
// Says so on the canvas when canvasHasRoom left shapes out this frame (after all overlays).
void ShowCanvasNotice(AppState& state);
// The legend of what the canvas and the layers over it drew this frame (after all overlays;
// View > Legend, always on slides; canvas_looks.h).
void ShowCanvasLegend(AppState& state);

// Remembers the last ImGui item's rectangle under `name` in state.itemRects (app.cpp).
void RecordItem(AppState& state, const char* name);

// Keyboard shortcuts (app.cpp); ignored while a text field has the keyboard.
void handleShortcuts(AppState& state);
// Advances a running animation by this frame's share of operations (toolbar.cpp).
void advanceRun(AppState& state, double dtSeconds);

// ---- Debugging panels (side tabs), files and sessions -----------------------------------------
void ShowExpressions(AppState& state);  // expressions.cpp: console, path on the canvas, watches
void ShowPredicates(AppState& state);   // predicates.cpp: the current test's determinant and signs
void ShowIdBuffer(AppState& state);     // idbuffer.cpp: the colour-ID buffer, pixel under the mouse
void ShowStatistics(AppState& state);   // statistics.cpp: counts, flips plot, frame times, checks
// flip_queue.cpp: the Predicates tab's "Flip queue" section: the edges still to test, next first.
void ShowFlipQueue(AppState& state);
// "1. edge 3-7 (triangles 4 | 9)": the Queue tab's row for the number-th edge to test.
std::string queueRowText(const Inserter& inserter, std::size_t number,
                         const Engine::QueuedTest& test);
void ShowTraceCompare(AppState& state);  // trace_compare.cpp: a student's trace beside our run

// A student's trace (.jsonl) compared with this run (same points and options): opens at the
// first difference. On a bad file: one fileError line, nothing changed (trace_compare.cpp).
bool openStudentTrace(AppState& state, const std::string& path);
void closeStudentTrace(AppState& state);
// True once after a trace was opened: the side column shows its tab.
bool studentTraceSelectTab(AppState& state);
// The student's triangles that are not ours, over the canvas.
void DrawTraceCompareOverlay(AppState& state);
void ShowFileDialogs(AppState& state);  // files.cpp: save/export/GIF dialogs, recovery, notices
// history.cpp: over the canvas, when the run's history would pass the op limit: BRIO order, a
// run without a history, or step anyway.
void ShowHistoryOffer(AppState& state);

// Per-frame work of those panels whichever tab is open: watches (pausing a run that breaks
// one), validate(), frame times, autosave (debug_hooks.cpp; ShowApplication calls it).
void updateDebugPanels(AppState& state);
// What they draw on the canvas, over it: the expression's path, violations (after ShowCanvas).
void DrawDebugOverlays(AppState& state);

// Expression console (expressions.cpp). Evaluates `text` with c = the selected corner,
// adds a history line and draws the path; true when it gave a value.
bool evaluateExpression(AppState& state, const std::string& text);
// Adds a watch (a comparison, e.g. o(o(c)) == c); logs why not when it cannot.
bool addWatch(AppState& state, const std::string& text);
// Checks the watches if the mesh changed; a run that broke one is stopped at the first
// operation that did, and the failure is logged with that operation and corner.
void checkWatches(AppState& state);
void DrawExpressionOverlay(AppState& state);

// Predicate inspector (predicates.cpp): the predicate calls the current operation made, as the
// engine made them (Journal::predicateCallsOf), or the user's typed points.
struct PredicateCall {
    bool inCircle = false;    // incircle(a, b, c, d); else orient2d(a, b, c)
    bool fromEngine = false;  // a call of the run (else typed)
    std::string what;         // one line: what is being asked
    std::array<Vec2, 4> p{};
    // Their vertex ids (kNone: typed, or the walk's origin q) and row labels ("v7", "q").
    std::array<std::int32_t, 4> v{kNone, kNone, kNone, kNone};
    std::array<std::string, 4> labels;
    int engineSign = 0;  // the sign the engine acted on (fromEngine)
    PredicateReport report;
};
// The current operation's calls, in the order the engine made them; none in batch mode.
std::vector<PredicateCall> currentPredicateCalls(const Engine& engine);
// "x, y" (or "(x, y)", "x y"): two finite decimal numbers, read exactly.
bool parsePointText(std::string_view text, Vec2& out);

// ID-buffer view (idbuffer.cpp). What the view shows of a locator's ID buffer, read by
// one function: the CPU buffer in place, the GL buffer read back into a copy.
struct IdBufferFrame {
    const char* kind = "";
    int width = 0, height = 0;
    std::span<const std::int32_t> ids;     // width * height, row 0 = lowest y
    std::function<Vec2(int, int)> centre;  // world position of the centre of pixel (i, j)
};
// A copy of a buffer that lives on the GPU, read back only when it may have changed.
struct IdBufferCopy {
    std::vector<std::int32_t> ids;
    std::uint64_t engineVersion = ~std::uint64_t{0}, bufferVersion = ~std::uint64_t{0};
};
// False when the run's locator keeps no ID buffer (or it has none yet).
bool readIdBuffer(const Engine& engine, IdBufferFrame& out, IdBufferCopy& copy);
// The false colour of a triangle id (kNone: light grey), as the view draws it.
std::uint32_t IdFalseColour(std::int32_t id);  // ImU32, as IM_COL32 packs it

// Statistics (statistics.cpp).
void updateStatistics(AppState& state);
// The counts over the journal up to the current position, brought up to date (stepping mode).
const RunCounts& UpdateRunCounts(AppState& state);
void DrawViolationOverlay(AppState& state);

// A side-column tab: the debugging panels slot in here.
struct SideTab {
    const char* name;  // the tab's label
    void (*show)(AppState&);
    const char* id =
        nullptr;  // the panel's name in lesson files (core/teaching/lesson.h kPanelNames)
    const char* title = nullptr;      // the full name: the tooltip, and itemRects' key
    const char* shortName = nullptr;  // the label when the labels do not all fit (1280 x 720)
};

// edits.cpp: edits after the run. The canvas tools' names (AppState::CanvasTool order); the
// constrained edges and the edit op in progress drawn as its record says; the op in words for
// the caption ("" when none); an edit made, logged and played; Delete on the selected corner's
// vertex; a click with an edit tool (false: the tool adds points, the click is not one for it).
extern const char* const kCanvasToolNames[5];
// The point in this state nearest to the mouse, within `radius` pixels (kNone when none).
std::int32_t pointAt(const AppState& state, ImVec2 mouse, Engine::PointState pointState,
                     float radius);
void DrawEditOverlay(AppState& state, ImDrawList* dl);
std::string editOpText(const Engine& engine);
void ApplyEdit(AppState& state, Edit edit);
void RemoveSelectedVertex(AppState& state);
bool EditClick(AppState& state, ImVec2 mouse, Vec2 world);

}  // namespace dlab::ui
