// All of the GUI's state in one place (Polyscope's Context, not scattered globals): the run, the
// view, the selection, overlays, run control and the message log. Panels are free functions
// ShowXxx(AppState&) that read the core through const references and change the mesh only
// through the Engine (that is, through the Inserter and its Journal).
#pragma once

#include "core/locator.h"
#include "ui/engine.h"

#include <glm/vec2.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace dlab::ui {

struct CanvasCache;  // panel_canvas.cpp: the mesh renderer's arrays and the drag in progress

// The canvas' one world <-> screen transform: y up in the world, y down on the screen.
struct View {
    glm::dvec2 center{800, 800};  // world point at the middle of the canvas
    double scale = 0.5;           // screen pixels per world unit
    glm::dvec2 origin{0, 0};      // top-left corner of the canvas on the screen
    glm::dvec2 size{1, 1};        // canvas size in pixels

    glm::dvec2 toScreen(Vec2 p) const {
        return {origin.x + size.x / 2 + (p.x - center.x) * scale, origin.y + size.y / 2 - (p.y - center.y) * scale};
    }
    Vec2 toWorld(glm::dvec2 s) const {
        return {center.x + (s.x - origin.x - size.x / 2) / scale, center.y - (s.y - origin.y - size.y / 2) / scale};
    }
    // Shows the box [lo, hi] whole, with a margin; a degenerate box gets a sensible zoom.
    void fit(Vec2 lo, Vec2 hi);
    // Zooms by `factor`, keeping the world point under `screen` where it is.
    void zoomAt(glm::dvec2 screen, double factor);
};

struct Overlays {
    bool fill = true;            // light fill of the triangles
    bool vertexIds = true;
    bool cornerIds = true;       // corner ids inside their corners (when zoomed in enough)
    bool triangleIds = false;
    bool walk = true;            // the current locate's path and the line L
    bool flipQueue = true;       // edges still to test
    bool flipped = true;         // edges flipped by the current insertion
    bool circumcircles = false;  // every triangle's circumcircle
    bool voronoi = false;
    bool pendingPoints = true;   // points not inserted yet
    bool virtualTriangles = true;  // super-triangle (super mode) while the run is in progress
};

// A corner operator applied by the inspector (n p o l r s u).
struct CornerMove {
    std::int32_t from = kNone;
    char op = 0;
    std::int32_t to = kNone;
};

struct Selection {
    std::int32_t corner = kNone;
    std::int32_t hoveredCorner = kNone;  // on the canvas: lights its table row
    std::int32_t hoveredRow = kNone;     // in the table: lights the corner on the canvas
    CornerMove lastMove;                 // drawn as an arrow on the canvas
    std::int32_t jumpToCorner = kNone;   // the table scrolls to this row once
    bool followOp = true;                // the table scrolls to the cells each op changes
};

struct BreakpointEntry {
    Breakpoint bp;
    bool enabled = true;
};

struct RunControl {
    bool running = false;
    std::vector<BreakpointEntry> breakpoints;  // a running animation stops where one hits
    float opsPerSecond = 6.0f;  // the slider; kFullSpeed runs as many as a frame allows
    static constexpr float kFullSpeed = 1000.0f;
    double carry = 0.0;         // fractional ops owed from earlier frames
    double frameBudgetMs = 25;  // stepping time per frame at full speed
    std::string stopReason;     // why the last run stopped ("end", "breakpoint: next flip", ...)
    std::size_t stopPosition = 0;  // where it stopped (the caption shows the reason only there)
};

// What the last frame cost (the statistics panel and `dtlab render --bench-frames` show it).
struct FrameStats {
    double meshBuildMs = 0;        // the canvas' mesh rebuild (0 when nothing changed)
    std::size_t visibleEdges = 0;
    bool denseMesh = false;        // drawn as a CPU raster
    std::size_t opsStepped = 0;    // operations the run advanced this frame
};

struct Message {
    enum class Level : std::uint8_t { Info, Warning, Error };
    Level level = Level::Info;
    std::string text;
};

struct Layout {
    float rightWidth = 0.36f;  // the side column, as a fraction of the window width
    float bottomHeight = 0.2f; // the message strip, as a fraction of the window height
    float inspectorHeight = 0.42f;  // the inspector, as a fraction of the side column
};

// Text and choices of the menu's dialogs, kept between frames (ImGui is immediate-mode).
struct DialogState {
    std::string openPath;
    std::string openFolder;
    std::vector<int> generatorCounts;
    int generatorSeed = 1;
    int breakVertex = 0;
    int breakCorner = -1;
    std::string breakText;
};

struct AppState {
    Engine engine;
    std::string source = "built-in demo";  // where the points came from (shown in the title)
    View view;
    bool fitPending = true;  // fit the view to the points at the next canvas frame
    Overlays overlays;
    Selection selection;
    RunControl run;
    Layout layout;
    std::vector<Message> messages;
    bool showHelp = false;
    bool presentation = false;  // large fonts, high contrast, no clutter
    bool snapToGrid = false;
    double gridStep = 10.0;
    bool quitRequested = false;
    std::shared_ptr<CanvasCache> canvas;  // created by the canvas on its first frame
    DialogState dialogs;
    FrameStats frameStats;
    std::uint64_t tableVersion = 0;  // the engine version the corner table last showed
    // Screen rectangles of named widgets from the last frame (x0, y0, x1, y1): how tests and
    // lessons find "the step button" without hard-coding the layout.
    std::unordered_map<std::string, std::array<float, 4>> itemRects;

    // Undo/redo of edits to the point set (never lose a user's points).
    std::vector<std::vector<Vec2>> undoPoints, redoPoints;

    // ---- Actions (every change of points or options goes through these) ---------------------
    void log(Message::Level level, std::string text);
    // Replaces the points (a file, a generator, the demo) and restarts at operation 0.
    bool loadPoints(std::vector<Vec2> points, std::string sourceName);
    // An edit of the points (add, move, remove): restarts and replays to the same position;
    // undoable.
    bool editPoints(std::vector<Vec2> points);
    bool undoEdit();
    bool redoEdit();
    // New boundary / locator / order / seed: restarts with the same points at operation 0.
    bool setOptions(const InsertOptions& options);
    void select(std::int32_t corner);
    // Applies a corner operator to the selection; logs when it cannot (boundary, no selection).
    bool moveSelection(char op);
};

// The built-in demo: the demo points with options chosen for teaching (input order).
InsertOptions demoOptions();

}  // namespace dlab::ui
