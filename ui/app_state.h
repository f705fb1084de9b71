// All of the GUI's state in one place (Polyscope's Context, not scattered globals): the run, the
// view, the selection, overlays, run control and the message log. Panels are free functions
// ShowXxx(AppState&) that read the core through const references and change the mesh only
// through the Engine (that is, through the Inserter and its Journal).
#pragma once

#include "core/engine/locator.h"
#include "core/engine/mesh_diff.h"
#include "core/engine/triangulation_check.h"
#include "core/teaching/corner_expr.h"
#include "core/teaching/overlays.h"
#include "core/teaching/trace_diff.h"
#include "ui/engine.h"
#include "ui/lesson_player.h"

#include <glm/vec2.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace dlab::ui {

using ::dlab::Overlays;  // core/teaching/overlays.h

struct CanvasCache;  // canvas.cpp: the mesh renderer's arrays and the drag in progress
class Renderer;      // ui/render/renderer.h: what the canvas and image views draw through

// The canvas' one world <-> screen transform: y up in the world, y down on the screen.
struct View {
    glm::dvec2 center{800, 800};  // world point at the middle of the canvas
    double scale = 0.5;           // screen pixels per world unit
    glm::dvec2 origin{0, 0};      // top-left corner of the canvas on the screen
    glm::dvec2 size{1, 1};        // canvas size in pixels

    glm::dvec2 toScreen(Vec2 p) const {
        return {origin.x + size.x / 2 + (p.x - center.x) * scale,
                origin.y + size.y / 2 - (p.y - center.y) * scale};
    }
    Vec2 toWorld(glm::dvec2 s) const {
        return {center.x + (s.x - origin.x - size.x / 2) / scale,
                center.y - (s.y - origin.y - size.y / 2) / scale};
    }
    // Shows the box [lo, hi] whole, with a margin; a degenerate box gets a sensible zoom.
    void fit(Vec2 lo, Vec2 hi);
    // Zooms by `factor`, keeping the world point under `screen` where it is.
    void zoomAt(glm::dvec2 screen, double factor);
};

// A corner operator applied by the inspector (n p o l r s u).
struct CornerMove {
    std::int32_t from = kNone;
    char op = 0;
    std::int32_t to = kNone;
    std::uint64_t version = 0;  // the mesh it was made on (Engine::version())
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
    // End (and >|): this run goes to the end at full speed; the slider keeps the user's speed.
    bool toEnd = false;
    bool fullSpeed() const { return toEnd || opsPerSecond >= kFullSpeed; }
    void runToEnd() {
        running = true;
        toEnd = true;
    }
    double carry = 0.0;         // fractional ops owed from earlier frames
    double frameBudgetMs = 25;  // stepping time per frame at full speed, at most
    // At full speed the stepping gets what is left of this frame time after the rest of the
    // last frame (drawing, the mesh rebuild, the GL render): 60 frames a second with ~3 ms to
    // spare for a frame that costs more than the last.
    double targetFrameMs = 13;
    double lastStepMs = 0;         // the stepping part of the last frame
    double previousRestMs = 0;     // the rest (not stepping) of the frame before the last
    double lastAdvanceMs = -1;     // when advanceRun last ran (steady clock ms), -1: not yet
    std::string stopReason;        // why the last run stopped ("end", "breakpoint: next flip", ...)
    std::size_t stopPosition = 0;  // where it stopped (the caption shows the reason only there)
    std::uint64_t stopRun = 0;     // in which run (Engine::run())
    void stop(std::string reason, std::size_t position, std::uint64_t engineRun) {
        stopReason = std::move(reason);
        stopPosition = position;
        stopRun = engineRun;
    }
    // The reason belongs to where the run stopped: moving away (a step, a restart) drops it.
    void clearStaleStop(std::size_t position, std::uint64_t engineRun) {
        if (position != stopPosition || engineRun != stopRun) stopReason.clear();
    }
};

// What the last frame cost (the statistics panel and `dtlab render --bench-frames` show it).
struct FrameStats {
    double meshBuildMs = 0;  // the canvas' mesh rebuild (0 when nothing changed)
    std::size_t visibleEdges = 0;
    bool denseMesh = false;      // drawn as a CPU raster
    std::size_t opsStepped = 0;  // operations the run advanced this frame
    bool canvasFull = false;     // some overlay shapes were left out (canvasHasRoom)
};

struct Message {
    enum class Level : std::uint8_t { Info, Warning, Error };
    Level level = Level::Info;
    std::string text;
};

struct Layout {
    float rightWidth = 0.36f;       // the side column, as a fraction of the window width
    float bottomHeight = 0.2f;      // the message strip, as a fraction of the window height
    float inspectorHeight = 0.42f;  // the inspector, as a fraction of the side column
    float lessonHeight = 0.5f;      // the lesson panel, as a fraction of the side column
};

// Text and choices of the menu's dialogs, kept between frames (ImGui is immediate-mode).
struct DialogState {
    std::vector<int> generatorCounts;
    int generatorSeed = 1;
    std::vector<std::pair<std::string, std::string>> lessons;  // (path, title) of lessons/*.toml
    int breakVertex = 0;
    int breakCorner = -1;
    std::string breakText;
};

// ---- The debugging panels and files ----------------------------------------------------------

// One line of the expression console: what was typed and what it gave.
struct ExprLine {
    std::string text;
    std::string answer;  // "= 17 (corner)", or the error
    bool ok = false;
    std::size_t errorColumn = 0;  // where the error starts in `text`
};

// An identity checked after every step, e.g. o(o(c)) == c (expressions.cpp).
struct WatchEntry {
    std::string text;
    bool enabled = true;
    std::shared_ptr<const CornerExpr> expr;  // parsed once; null when the text does not parse
    bool failing = false;
    std::string status;  // "holds for 36 corners" / "fails at c = 7: ..."
};

struct ExpressionState {
    std::string input;  // the console's input line
    // After Enter a field takes the keyboard back; until it has it (a few frames at most), no
    // shortcut fires: the next key typed is for the field.
    static constexpr int kRefocusFrames = 4;
    int refocusInput = 0;
    std::vector<ExprLine> history;  // newest last
    std::string live;               // the expression shown on the canvas, re-evaluated each step
    std::vector<PathStep> path;     // its moves, drawn on the canvas as arrows between corners
    std::optional<ExprValue> result;
    std::uint64_t liveVersion = ~std::uint64_t{0};  // engine version `path` was computed at
    std::int32_t liveCorner = kNone;                // the c it was computed with
    std::vector<WatchEntry> watches;
    std::string watchInput;
    int refocusWatch = 0;                              // the watch field, likewise
    bool pauseOnFailure = true;                        // a failing watch pauses a running animation
    std::uint64_t watchedVersion = ~std::uint64_t{0};  // engine version the watches last saw
    std::size_t watchedPosition = 0;  // and its position (for the replay on failure)
};

struct PredicateState {
    std::array<std::string, 4> points{"0, 0", "1, 0", "0, 1",
                                      "1, 1"};  // the user's a, b, c, d as "x, y"
};

struct IdBufferView;  // idbuffer.cpp: the texture and the ids it was made from

struct IdBufferViewState {
    bool trueColours = false;  // the encoded colours instead of false colour
    std::shared_ptr<IdBufferView> cache;
    // The buffer pixel under the mouse, decoded and checked (tests read it).
    struct Hover {
        bool valid = false;
        int i = 0, j = 0;                    // pixel, row 0 = lowest y
        std::int32_t id = kNone;             // what the buffer holds there
        Vec2 centre{};                       // the pixel centre in the world
        std::int32_t exactTriangle = kNone;  // a triangle that contains the centre (exact), if any
        bool agrees = false;                 // the id's triangle contains the centre (exact)
    } hover;
};

// Counts over the journal's ops [0, position): kept up while the run goes forward, recounted
// when it goes back or restarts (statistics.cpp).
struct RunCounts {
    std::size_t position = 0;
    Op last{};  // ops[position - 1] when counted: tells a continuation from a new run
    std::vector<float> flipsPerInsertion;  // finished insertions, in order
    std::int64_t flipsNow = 0;             // flips of the insertion in progress
    std::int64_t flips = 0, walkSteps = 0, inCircleTests = 0, inserted = 0, duplicates = 0,
                 splits = 0, edgeSplits = 0;
    std::int64_t locates = 0, hits = 0, stepsNow = 0;
};

struct StatisticsState {
    static constexpr std::size_t kFrames = 240;
    std::vector<float> frameMs;  // the last kFrames frame times, oldest first
    bool autoValidate = true;  // validate() after every change (meshes up to kAutoValidateCorners)
    static constexpr std::int32_t kAutoValidateCorners = 300000;
    std::uint64_t validatedVersion = ~std::uint64_t{0};
    std::vector<Violation> violations;  // drawn on the canvas
    std::vector<std::int32_t>
        hullDents;  // boundary vertices where the hull turns right (not convex)
    // Each dent b with its boundary neighbours (a, b, c): the triangle the mesh misses there.
    std::vector<std::array<std::int32_t, 3>> hullGaps;
    std::string hullReport;  // the hull / Euler check in one line
    RunCounts counts;
};

struct GifRequest {
    std::string path;
    std::size_t from = 0, to = 0;  // journal positions, inclusive
    std::size_t every = 1;         // one frame per this many operations
    int delayMs = 250;
    bool wholeWindow = false;  // the whole window instead of the canvas
};

struct FileState {
    std::string autosavePath;                 // empty: no autosave (tests, --no-autosave)
    std::vector<Vec2> autosaved;              // the points the autosave file holds now
    std::vector<std::string> autosavedEdits;  // and the edits after the run (editTexts)
    bool autosaveTooBig = false;              // said once: too many points to autosave
    std::string recoveryPath;  // an autosave left by a session that did not exit cleanly
    std::size_t recoveryPoints = 0;
    std::string recoverySource;
    std::string notice;                // a file error, shown over the canvas until dismissed
    bool screenshotRequested = false;  // F12: main loop / tests call ServiceCaptures
    std::string screenshotFolder;      // empty: the current directory
    std::optional<GifRequest> gif;     // a GIF to render (serviceCaptures)
    enum class Dialog : std::uint8_t {
        None,
        SavePoints,
        SaveSession,
        OpenFile,
        ExportMesh,
        ExportSvg,
        ExportGif
    };
    Dialog dialog = Dialog::None;  // to open at the next frame
    std::string dialogPath;        // the path field of the open dialog
    int meshFormat = 0;            // export dialog: 0 .ele/.neigh, 1 OFF, 2 OBJ
    GifRequest gifDraft;           // the GIF dialog's fields

    // The platform's own file chooser (the browser's), used for Open instead of our dialog; it
    // opens the chosen file itself, later.
    std::function<void()> platformOpenDialog;
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
    bool presentation = false;   // large fonts, high contrast, no clutter
    bool handoutSlides = false;  // slides for a handout: no menus, buttons, answer box, side tab
    // What a click on the canvas does: queue a point, or edit the finished mesh (remove the
    // vertex clicked; constrain or free the segment between the two vertices clicked; move the
    // vertex clicked to the point clicked next).
    enum class CanvasTool : std::uint8_t {
        AddPoints,
        RemoveVertex,
        Constrain,
        Unconstrain,
        MoveVertex
    };
    CanvasTool tool = CanvasTool::AddPoints;
    std::int32_t toolFirstVertex = kNone;  // a segment's first vertex, or the vertex to move
    bool snapToGrid = false;
    double gridStep = 10.0;
    bool quitRequested = false;
    std::shared_ptr<CanvasCache> canvas;  // created by the canvas on its first frame
    Renderer* renderer = nullptr;         // the Gui's (GL or null); none: nothing is drawn
    DialogState dialogs;
    FrameStats frameStats;
    LessonState lessonPlayer;        // the lesson on show, if any (lesson_player.h)
    std::uint64_t tableVersion = 0;  // the engine version the corner table last showed
    // Screen rectangles of named widgets from the last frame (x0, y0, x1, y1): how tests and
    // lessons find "the step button" without hard-coding the layout.
    std::unordered_map<std::string, std::array<float, 4>> itemRects;

    // Undo/redo of edits to the point set (never lose a user's points).
    std::vector<std::vector<Vec2>> undoPoints, redoPoints;

    // The side tabs (expression console and watches, predicate inspector, ID-buffer view,
    // statistics), files and sessions.
    ExpressionState expressions;
    PredicateState predicates;
    IdBufferViewState idBuffer;
    StatisticsState statistics;
    FileState files;
    // A student's trace compared with this run (trace_compare.cpp).
    struct TraceCompare {
        std::shared_ptr<const TraceFile> ours, student;  // null: no comparison open
        TraceDiff diff;
        std::size_t studentPos = 0;  // student ops applied so far (0 .. student->ops.size())
        std::vector<Vec2> points;    // the run they were compared on
        InsertOptions options;
        bool selectTab = false;
        // The overlay's caches: the student's triangles after studentPos ops, and ours (sorted)
        // at an engine version; rebuilt only when those change.
        std::vector<Triple> studentTriangles, ourTriangles;
        std::size_t studentTrianglesAt = static_cast<std::size_t>(-1);
        std::uint64_t ourTrianglesVersion = ~std::uint64_t{0};
    } traceCompare;
    // A mesh made elsewhere, opened and checked exactly (check.cpp): its report, and the
    // problem the user picked. The engine runs Lawson's flip algorithm on it when it is a
    // triangulation, and only shows it when it is not.
    struct MeshCheck {
        bool open = false;
        std::string path, format;
        std::vector<std::string> warnings;
        CheckReport report;  // of the mesh as opened (ids in messages in its numbering)
        int indexBase = 0;
        std::uint64_t run = 0;              // the engine run that shows it
        std::int32_t picked = -1;           // index into report.problems
        std::vector<std::int32_t> openedV;  // the triangles as opened (the problems' ids)
        // The edges that differ from the Delaunay triangulation of the same points (at a version).
        bool showDiff = false;
        DelaunayDiff diff;
        std::uint64_t diffVersion = ~std::uint64_t{0};
        // The check of the mesh at the current step (cached per engine version).
        CheckReport now;
        std::uint64_t nowVersion = ~std::uint64_t{0};
    } meshCheck;
    // A side tab to bring to the front at the next frame, by its id ("predicates", ...); "" none.
    std::string pendingTab;
    // The user's own options (the toolbar's choices; BRIO order until they choose): what a file
    // they open or generate runs with. The demo and lessons run with their own (a closed lesson
    // gives back the options from before it: lesson_player.h).
    InsertOptions userOptions;
    // A run whose history would pass the engine's op limit (found when the points or options
    // change): shown over the canvas with its choices (history.cpp).
    struct HistoryOffer {
        bool open = false;
        std::uint64_t run = 0;    // the engine run it is about
        std::size_t brioOps = 0;  // the same points in BRIO order (0: not offered)
    } historyOffer;

    // ---- Actions (every change of points or options goes through these) ---------------------
    void log(Message::Level level, std::string text);
    // Replaces the points (a file, a generator, the demo) and restarts at operation 0.
    bool loadPoints(std::vector<Vec2> points, std::string sourceName);
    // An edit of the points (add, move, remove): restarts and replays to the same position;
    // undoable.
    bool editPoints(std::vector<Vec2> points);
    bool undoEdit();
    bool redoEdit();
    // A point set the user opens or generates: runs with the user's options.
    bool loadUserPoints(std::vector<Vec2> points, std::string sourceName);
    // New boundary / locator / order / seed: restarts with the same points at operation 0.
    bool setOptions(const InsertOptions& options);
    // The user's choice of options (toolbar): as setOptions, and they become the user's own
    // unless a lesson is open (its run takes them until it closes).
    bool setUserOptions(const InsertOptions& options);
    // Opens historyOffer when the run now would pass the op limit (logs it once per run).
    void checkHistory();
    void select(std::int32_t corner);
    // Applies a corner operator to the selection; logs when it cannot (boundary, no selection).
    bool moveSelection(char op);
    // The last move while the mesh is the one it was made on; null once an operation changed it
    // (its corners may name other triangles now).
    const CornerMove* currentMove() const;

private:
    bool loadPointsWith(std::vector<Vec2> points, std::string sourceName,
                        const InsertOptions& options);
};

// "boundary exact, locate walk, order brio": the options as the message log names them.
std::string optionsText(const InsertOptions& options);
// "12,345": a count with its thousands marked.
std::string groupedCount(std::size_t n);
// "530,000" (two digits) below a million, "9.4 million" from there: a count said roughly.
std::string approximateCount(std::size_t n);
// Why historyOffer is open, in one sentence (the offer and the message log).
std::string historyOfferText(const AppState& state);

// The built-in demo: the demo points with options chosen for teaching (input order).
InsertOptions demoOptions();
// Loads the built-in demo with those options.
void loadDemo(AppState& state);
// What the program starts with: the file named on the command line (a point file, a session, a
// lesson...), or the demo when none is named. A file that cannot be opened leaves its one-line
// reason in state.files.notice and the demo, in its own order, runs instead (false).
bool openStartupInput(AppState& state, const std::string& input);

}  // namespace dlab::ui
