// The check of a slide as rendered: what `dtlab lesson check` reads on each stop's slide (the text
// runs drawn, with their boxes, and the canvas's marks, with their roles) against what the stop
// needs: every vertex it names labelled legibly, every panel it relies on shown, and a picture
// that agrees with the question (the edge under test, the count of queued edges).
#pragma once

#include "core/teaching/lesson.h"

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace dlab {

// A screen rectangle, pixels (y down).
struct SlideBox {
    float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    // Whether the two boxes share more than `slack` pixels each way.
    bool meets(const SlideBox& o, float slack = 1.0f) const {
        return x0 + slack < o.x1 && o.x0 + slack < x1 && y0 + slack < o.y1 && o.y0 + slack < y1;
    }
    bool within(const SlideBox& o, float slack = 0.5f) const {
        return x0 >= o.x0 - slack && y0 >= o.y0 - slack && x1 <= o.x1 + slack && y1 <= o.y1 + slack;
    }
    float cx() const { return (x0 + x1) / 2; }
    float cy() const { return (y0 + y1) / 2; }
};

// A run of text as drawn (ui/render/drawn_text.h reads them back from the draw lists).
struct SlideRun {
    std::string text;
    SlideBox box;
    int list = 0;  // the draw list: one per window or child window
};

// What the canvas drew, in the role it drew it in (ui/render/drawn_marks.h records them).
enum class SlideMarkRole : std::uint8_t {
    Canvas,         // the canvas's area
    Vertex,         // a vertex's point: a = the vertex
    VertexLabel,    // a vertex's id label: a = the vertex, box = the text's
    CornerLabel,    // a = the corner
    TriangleLabel,  // a = the triangle
    TestEdge,       // the edge under test: a, b = its vertices
    QueuedEdge,     // an edge on the flip stack: a, b
    FlippedEdge,    // a, b
    TestCircle,     // the circle (or half-plane) of the in-circle test: a = its triangle
    Legend,         // the canvas's legend box, drawn over the canvas
};

struct SlideMark {
    SlideMarkRole role = SlideMarkRole::Canvas;
    std::int32_t a = -1, b = -1;
    SlideBox box;
};

// One stop's slide as drawn.
struct RenderedSlide {
    std::vector<std::string> lines;  // the runs as lines (drawnLines)
    std::vector<SlideRun> runs;
    std::vector<SlideMark> marks;
};

// What a stop is about, as the check reads it from its text, question, answer and `needs`.
struct SlideNeeds {
    std::vector<std::int32_t> vertices, corners, triangles;
    std::vector<std::string> panels;  // names from kPanelNames
};

// The vertices a text names: "vertex 7", "vertices 2, 3 and 5", "point 4", the ends of an edge
// written "2-3" (any dash). Numbers after "corner", "triangle", "row", "op" and the like are not
// vertices; neither is a range ("corners 0-2").
std::vector<std::int32_t> verticesNamedIn(std::string_view text);

// The panels a text refers to as panels: "the corner table shows / marks / highlights", "the
// corner-table panel / tab", "in the corner table" (and so for the vertex table, the statistics,
// the ID buffer, predicates and expressions), "the inspector". The idea ("a corner table stores V
// and O") is no panel.
std::vector<std::string> panelsNamedIn(std::string_view text);

// Whether the slide shows `panel`: text that panel always draws (its header, its column names).
// Panels without such text (canvas, lesson, messages) read as shown.
bool panelOnSlide(std::string_view panel, const std::vector<std::string>& lines);

// Why vertex v's label is not legible on the slide, or nullopt when it is: a VertexLabel mark
// for v, inside the canvas, neither it nor v's point under the canvas's legend, its text read
// back there, no other run over it, and no other
// vertex drawn on the same spot (unless `points` says it is a duplicate of v: the same point).
std::optional<std::string> vertexLabelProblem(std::int32_t v, const RenderedSlide& slide,
                                              std::span<const Vec2> points = {});

// The count of queued edges a text states: "4 edges wait", "3 edges are waiting", "2 edges in the
// queue", "the queue holds 5": the number, or nullopt when it states none.
std::optional<std::int64_t> queueCountIn(std::string_view text);

// Everything the check finds on the rendered slides (slides[k]: stop k + 1), besides
// slideProblems (the answer on the slide): named vertices, corners ("corner 4") and triangles
// ("triangle 1") unlabelled or covered, panels named but
// absent, the edge drawn as under test not the engine's, a count of queued edges in the text that
// differs from the edges drawn. Each names file, line and stop.
std::vector<LessonError> renderedSlideProblems(const Lesson& lesson, const LessonPlan& plan,
                                               const std::vector<RenderedSlide>& slides);

}  // namespace dlab
