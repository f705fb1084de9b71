// Lessons: the TOML lesson format, its loader (untrusted input: every error names file, line and
// stop), the headless planner that runs a lesson to its end and computes every stop's state and
// answer, answer checking, Markdown-light text, and the progress record the GUI persists.
//
// A lesson file (lessons/*.toml):
//
//   title = "The corner table"
//   summary = "G, V and O for two triangles."
//   kind = "lesson"                 # or "assignment": points and text only, no stops needed
//   objectives = ["Say when an edge is legal", "Run a flip cascade by hand"]   # shown first
//   minutes = 12                    # its length in class (1 to 300); a lesson in a track
//                                   # needs objectives and minutes
//   points = [[0, 0], [4, 0], [4, 3], [0, 3]]   # or points_file = "square.csv", beside the lesson
//   triangles = [[0, 1, 2], [0, 2, 3]]  # optional: a start triangulation (0-based ids into
//                                   # points, counter-clockwise, valid as checkMesh finds it);
//                                   # the run is then Lawson's flip algorithm from it, not
//                                   # insertion, and [options] does not apply
//
//   [options]                       # all optional
//   boundary = "exact"              # exact | super
//   locator = "walk"                # naive | walk | grid | idbuffer-cpu
//   order = "input"                 # input | random | brio   (default: input: read in order)
//   seed = 1
//   idbuffer_size = 64              # pixels per side of the CPU ID buffer
//
//   [[stop]]
//   run_to = "inserted:3"           # a breakpoint (teaching/breakpoint.h); omitted: stay put
//   count = 1                       # the count-th hit after the previous stop
//   panels = ["canvas", "corner-table"]          # names from kPanelNames
//   overlays = ["corner-ids", "vertex-ids"]      # names from kOverlayNames
//   select = "c.n"                  # corner expression; c = the previous stop's selection
//   text = """Markdown-light: **bold**, `code`, lists with - or 1."""
//   question = "What is O[c] for the selected corner?"
//   answer = "O[c]"                 # a quantity name (lessonQuantities) or a corner expression
//   hint = "Look across the edge opposite c."
//   expect = { located = "hit", walk_steps = 0 }  # checked against the engine at the stop
//   figure = "lifting-map"          # a drawing beside the text (kFigureNames)
//   needs = ["vertex:4", "panel:corner-table"]  # what the slide must show (see below)
//
// A track file (kind = "track") plays stops of several lessons in order: one lecture made of
// the lessons' own stops, each checked as part of its lesson.
//
//   title = "Delaunay in one lecture"
//   kind = "track"
//   summary = "..."
//   objectives = ["..."]            # required: shown on the track's first slide
//   minutes = 50                    # the lecture's length: the items' minutes add up to at most it
//
//   [[item]]
//   lesson = "04b_delaunay_foundations.toml"   # beside the track, as points_file is
//   stops = [1, 2, 4]               # 1-based stop numbers of that lesson, increasing
//   minutes = 6                     # required
//
// The answer is computed by the engine at the stop, never typed into the file. Text, question
// and hint may embed engine values: {{walk_steps}}, {{test_edge}}, {{V[c.n]}} (a quantity or a
// corner expression, as in `answer`), replaced by the value at the stop. An expectation's value
// is written as a student would type the answer ("0-2", "edge", 25, true).
//
// `dtlab lesson check` renders every stop's slide and reads it back (core/teaching/slide_check.h):
// each vertex the text or question names ("vertex 7", "vertices 2, 3 and 5", an edge "2-3") and
// each end of an edge answer must carry a legible label on the canvas, and so must each corner
// and triangle it names ("corner 4", "triangle 1"); the stop's tab and each
// panel the text refers to ("the corner table", "the statistics") must be on the slide; a stop
// about the in-circle test must draw the engine's test edge, and a count of queued edges in the
// text ("{{queue}} edges wait") must match the edges drawn. What the check cannot read from the
// text, the stop declares: needs = ["vertex:N", "corner:N", "triangle:N", "panel:NAME"] (NAME
// from kPanelNames).
#pragma once

#include "core/engine/editor.h"
#include "core/engine/inserter.h"
#include "core/teaching/breakpoint.h"
#include "core/teaching/overlays.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace dlab {

// Names a stop may use. The GUI maps them to its panels and overlay switches.
inline constexpr const char* kPanelNames[] = {
    "canvas",      "corner-table", "vertex-table", "inspector",  "messages",
    "expressions", "predicates",   "idbuffer",     "statistics", "lesson",
};

// Drawings a stop may show beside its text (`figure = "lifting-map"`).
inline constexpr const char* kFigureNames[] = {"lifting-map"};

// A bad lesson file. what() is "FILE:LINE: stop K: message" (parts left out when unknown).
class LessonError : public std::runtime_error {
public:
    LessonError(std::string file, int line, int stop, std::string message);
    const std::string& file() const noexcept { return m_file; }
    int line() const noexcept { return m_line; }  // 0: no line
    int stop() const noexcept { return m_stop; }  // 1-based; 0: not about one stop
    const std::string& message() const noexcept { return m_message; }

private:
    std::string m_file;
    int m_line;
    int m_stop;
    std::string m_message;
};

// What the canvas shows at a stop: a world rectangle, or the box around some vertices (ids; the
// super-triangle's or the ghost follow the input points). Empty: the view stays as it is.
struct StopView {
    std::optional<std::array<double, 4>> rect;  // x0, y0, x1, y1
    std::vector<std::int32_t> fit;
    bool empty() const { return !rect && fit.empty(); }
};

// The side tabs a stop can bring to the front (`tab = "idbuffer"`); "none": a slide shows no
// side tab (its text has the column), a window keeps the tab in front.
inline constexpr const char* kTabNames[] = {
    "corner-table", "vertex-table", "expressions", "predicates", "idbuffer", "statistics", "none"};

// An expectation: at the stop, `spec` (a quantity or a corner expression) reads `value`.
struct LessonExpect {
    std::string spec, value;
    int line = 0;
};

struct LessonStop {
    int line = 0;                     // line of its [[stop]] header
    std::optional<Breakpoint> runTo;  // nullopt: stay at the previous stop's position
    int count = 1;
    std::vector<std::string> panels, overlays;
    std::string select;  // corner expression, empty: keep the previous selection
    std::string text;
    std::string question, answer, hint;
    int answerLine = 0;
    StopView view;    // view = { fit = [0, 4, 7] } or view = { rect = [x0, y0, x1, y1] }
    std::string tab;  // a side tab in front at this stop (kTabNames), empty: as it is

    // Lines of the first line of text / question / hint (for messages about their content).
    int textLine = 0, questionLine = 0, hintLine = 0;
    std::vector<LessonExpect> expect;
    std::string figure;  // a drawing beside the text: one of kFigureNames, or empty
    // What the slide must show beyond what the check reads from the text: "vertex:4",
    // "corner:7", "triangle:3" (a legible label on the canvas), "panel:corner-table".
    std::vector<std::string> needs;
    int needsLine = 0;
};

struct Lesson {
    std::string file;  // as given to loadLesson
    std::string title, summary;
    std::string text;  // the lesson's own text (an assignment's instructions), Markdown-light
    std::vector<std::string> objectives;  // what a student can do after it (shown first)
    int minutes = 0;                      // its length in class; 0: not stated
    bool assignment = false;
    InsertOptions options;
    std::vector<Vec2> points;
    std::string pointsFile;  // resolved path of points_file, empty for inline points
    // `triangles`: the run is Lawson's flip algorithm from this mesh (V from the file, O as
    // checkMesh computes it) instead of the insertion of the points. nullopt: insertion.
    std::optional<Inserter::StartMesh> start;
    std::vector<LessonStop> stops;
    // `edits = ["remove vertex 7", "constrain 2-9"]`: applied after the run's end, in order
    // (exact boundary, insertion only). Stops inside them run_to the edit targets (edit:N,
    // ear-test, sloan-flip, ...; breakpoint.h) and ask the edit quantities.
    std::vector<Edit> edits;
    int editsLine = 0;
};

// Hard limits for untrusted lesson files.
inline constexpr std::size_t kMaxLessonPoints = 100000;
inline constexpr std::size_t kMaxLessonStops = 500;
inline constexpr std::size_t kMaxLessonFileBytes = 1 << 20;

// Reads and checks a lesson (syntax, known names, breakpoints, expressions, text, the points
// file's location). Throws LessonError.
Lesson loadLesson(const std::string& path);
// The same from text; `path` names the file in messages and anchors points_file.
Lesson parseLesson(std::string_view text, const std::string& path);

// The objectives as the first slide shows them above the stop's text (Markdown-light); empty
// when there are none.
std::string objectivesText(const std::vector<std::string>& objectives);

// ---- Tracks: one lecture made of stops of several lessons ---------------------------------------

struct TrackItem {
    std::string lesson;              // resolved path of the lesson file
    std::string written;             // as the track names it
    std::vector<std::size_t> stops;  // 0-based, increasing
    int minutes = 0;
    int line = 0;  // line of its [[item]] header
};

struct Track {
    std::string file;
    std::string title, summary;
    std::vector<std::string> objectives;
    int minutes = 0;  // the lecture's length
    std::vector<TrackItem> items;
    std::size_t slides() const;  // stops over all items
};

// Whether the file is a track (kind = "track"): valid TOML with that key. False on anything
// else (loadLesson then says what is wrong with it).
bool isTrackFile(const std::string& path);
// Reads and checks a track: its keys, each item's lesson (loaded and checked: it exists, beside
// the track, states objectives and minutes), stop numbers that exist, minutes on every item
// adding up to at most the track's. Throws LessonError naming the track's file and line.
Track loadTrack(const std::string& path);
// The track's slides in order: (item, 0-based stop of its lesson).
std::vector<std::pair<std::size_t, std::size_t>> trackSlides(const Track& track);

// Resolves a points file named in a lesson: relative, no "..", inside the lesson's folder after
// following symlinks, an existing regular file. Returns the resolved path or throws
// LessonError(lessonPath, line, 0, why).
std::string resolveLessonFile(const std::string& lessonPath, const std::string& relative, int line);

// ---- Answers ---------------------------------------------------------------------------------

struct Answer {
    enum class Kind : std::uint8_t { Integer, Edge, Text, Truth, Point };
    Kind kind = Kind::Integer;
    std::int64_t a = 0, b = 0;  // Integer: a; Edge: the two vertices
    bool corner = false;        // Integer that is a corner: -1 reads "none" too
    std::string text;           // Text
    bool truth = false;         // Truth
    Vec2 point{};               // Point
    // The canvas labels of virtual vertices ("s0", "g"): of a (a vertex) or of a and b (edge).
    std::string labelA, labelB;
    bool triangle = false;  // Integer that is a triangle: "t25" reads 25 too
    // Words that may follow the number of an Integer, singular and plural ("step", "steps"):
    // what the quantity counts ("8 steps", "32 degrees", "6 times"). Empty: a bare number.
    std::vector<std::string> units;
    std::string display() const;  // "17", "4-9", "1-s0", "Flip", "yes", "(1, 2)"
};
// Whether what a student typed means the same as `expected` (edges in either order, numbers
// with spaces or as words up to twenty, a unit the quantity allows after the number ("8 steps",
// "32°"), trailing punctuation, "split edge" for SplitEdge, British spellings, the phrases of
// the hints ("on the boundary" for an edge), yes/no for truth values...).
bool acceptsAnswer(const Answer& expected, std::string_view typed);

struct QuantityInfo {
    const char* name;
    const char* meaning;
};
// The named quantities an answer may use ("triangles", "next_flip", ...).
std::span<const QuantityInfo> lessonQuantities();

// Computes `spec` (a quantity name or a corner expression with c = `selected`) for the state at
// the journal's position. May step the journal to look ahead or back; it is back where it was on
// return. On failure returns nullopt and says why in `error`.
// With `edits` (a stop inside the lesson's edits), the answer is computeEditAnswer's.
std::optional<Answer> computeAnswer(std::string_view spec, Inserter& ins, Journal& journal,
                                    std::int32_t selected, std::string* error = nullptr,
                                    Editor* edits = nullptr);
// At a stop inside the edits: an edit quantity (removal_degree, ear_flips, crossed_edges, ...;
// about the edit whose op was just done, or the first edit at the run's end), "triangles", or a
// corner expression on the edited mesh. May step the editor; it is back where it was on return.
std::optional<Answer> computeEditAnswer(std::string_view spec, Editor& editor,
                                        std::string* error = nullptr);

// ---- Planning: what each stop shows, computed headlessly ---------------------------------------

struct StopState {
    std::size_t position = 0;       // journal position of the stop
    std::int32_t selected = kNone;  // the selected corner there
    std::optional<Answer> answer;   // when the stop has a question
    std::string caption;            // describe() of the last op ("" at position 0)
    std::string banner;             // the GUI's operation banner: "[op N] Type: caption"
    // The stop's text, question and hint with every {{value}} replaced by the engine's value.
    std::string text, question, hint;
};

struct LessonPlan {
    std::vector<StopState> stops;
    std::size_t totalOps = 0;  // operations of the whole run
    std::size_t editOps = 0;  // operations of the lesson's edits (their positions follow the run's)
};

// A fresh engine with the lesson's points and options (the flip algorithm from its start
// triangulation when it has one).
std::unique_ptr<Inserter> makeInserter(const Lesson& lesson);
// Runs the lesson to its end: every stop must be reached in order and every question must have
// a computable answer. Throws LessonError naming the stop.
LessonPlan planLesson(const Lesson& lesson);
// The lesson's edits recorded after the run's end (the journal is run to it); the editor is back
// at their start. A refused edit is a LessonError at the `edits` line.
std::unique_ptr<Editor> startEdits(const Lesson& lesson, Journal& journal, Inserter& ins);

// ---- The lifting-map figure ------------------------------------------------------------------

// The in-circle test the lifting-map figure draws: the triangle whose circle is tested and the
// new point, lifted onto the paraboloid z = x² + y². Its `sign` is the exact test's.
struct LiftingMap {
    Vec2 triangle[3]{};
    std::int32_t vertices[3]{};
    Vec2 point{};
    std::int32_t vertex = kNone;
    int sign = 0;  // 1: the point is inside the circle (its lift below the plane), 0 on it
};
// The test just done (the current op), else the one next on the flip stack; nullopt when there
// is none or its triangle is a ghost / super one.
std::optional<LiftingMap> liftingMapAt(const Inserter& ins, const Op* current);

// ---- Engine values in the text, and the checks of `dtlab lesson check` --------------------------

// One {{spec}} in a text: byte range [begin, end) of the whole "{{...}}", line counted from 1.
struct EmbeddedValue {
    std::string spec;
    std::size_t begin = 0, end = 0;
    int line = 1;
};
// The {{...}} in `text`. An unclosed or empty one: nullopt and, in `error`, "line N of the text:
// ...". The specs are not checked here.
std::optional<std::vector<EmbeddedValue>> findEmbeddedValues(std::string_view text,
                                                             std::string* error = nullptr);
// `text` with every {{spec}} replaced by its value at the journal's position (as computeAnswer).
std::optional<std::string> renderEmbeddedValues(std::string_view text, Inserter& ins,
                                                Journal& journal, std::int32_t selected,
                                                std::string* error = nullptr,
                                                Editor* edits = nullptr);

// The code points the GUI's fonts carry (ImGui glyph ranges: pairs, then 0). Anything else is
// drawn as "?".
inline constexpr std::uint16_t kLessonGlyphRanges[] = {
    0x0020, 0x00FF, 0x2013, 0x2014, 0x2190, 0x21FF, 0x2212, 0x2212, 0x2260, 0x2265, 0,
};
// The first character of UTF-8 `text` the GUI cannot draw: its byte offset and code point
// (0xFFFD for bytes that are not UTF-8). nullopt when everything can be drawn.
std::optional<std::pair<std::size_t, char32_t>> firstUndrawable(std::string_view text);

// Whether `text` already says `answer`: the number (digits, or a word up to twelve), the edge
// (a-b either way, labels too), the phrase, or the point. Truth values are never "said".
bool answerAppearsIn(const Answer& answer, std::string_view text);

// What `dtlab lesson check` finds beyond planLesson: characters the GUI cannot draw, and stops
// whose answer is already in their own text or in the operation banner at the stop. Each names
// file, line and stop.
std::vector<LessonError> lessonProblems(const Lesson& lesson, const LessonPlan& plan);

// ---- The check of the rendered slide -----------------------------------------------------------

// The line of a rendered slide that shows `answer` in a phrasing acceptsAnswer takes: a number
// with a unit the answer allows, either way round ("6 corners", "flips  24", "walked 2 steps",
// "32°"), a phrase ("HIT", "empty pixel"), an edge, a point. A bare number is not read: ids are
// everywhere on a slide. Each line is read alone and with the next one (a phrase wrapped over
// two lines). Lines that are part of `ownText` (the stop's text and question, drawn on the slide
// too and checked on their own by lessonProblems) are skipped. nullopt when no line shows it.
std::optional<std::string> answerOnSlide(const Answer& answer,
                                         const std::vector<std::string>& lines,
                                         std::string_view ownText);

// The stops whose answer is on their rendered slide: `slides[k]` holds the lines of text drawn
// at stop k + 1 (every panel, the banner, the canvas labels). Besides answerOnSlide, a question
// that reads one cell of the corner table (`O[c]`, `V[4]`, `n(5)`, `c.l`) fails when that cell's
// row is on the slide. Each names file, line and stop.
std::vector<LessonError> slideProblems(const Lesson& lesson, const LessonPlan& plan,
                                       const std::vector<std::vector<std::string>>& slides);

// ---- Markdown-light text ------------------------------------------------------------------------

struct TextSpan {
    enum class Style : std::uint8_t { Plain, Bold, Code };
    Style style = Style::Plain;
    std::string text;
};
struct TextBlock {
    enum class Kind : std::uint8_t { Paragraph, Bullet, Numbered };
    Kind kind = Kind::Paragraph;
    int number = 0;  // Numbered: the number written
    std::vector<TextSpan> spans;
};
// Paragraphs (separated by blank lines; lines join with a space), "- " / "* " bullets, "1. "
// numbered items, **bold** and `code` inside. Unclosed ** or ` is an error: nullopt and, in
// `error`, "line N: ...", N counted from 1 within the text.
std::optional<std::vector<TextBlock>> parseLessonText(std::string_view text,
                                                      std::string* error = nullptr);

// ---- Progress (the GUI persists it) -------------------------------------------------------------

struct LessonProgress {
    std::string lesson;                 // the lesson file as opened
    std::string title;                  // to notice a different lesson at the same path
    std::size_t stop = 0;               // the stop shown
    std::size_t furthest = 0;           // the furthest stop reached
    std::vector<std::uint8_t> answers;  // per stop: 0 not answered, 1 tried and wrong, 2 right
    bool operator==(const LessonProgress&) const = default;
};

}  // namespace dlab
