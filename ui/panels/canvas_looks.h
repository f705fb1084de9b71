// The canvas' marks, each with its one look (colour and shape) and its meaning, in one table: the
// canvas takes its colours from it and the legend lists it, so the legend names what is drawn.
#pragma once

#include <imgui.h>

#include <bitset>
#include <cstddef>
#include <cstdint>
#include <span>

namespace dlab::ui {

// Everything on the canvas that stands for something of the run (the mesh itself aside).
enum class Mark : std::uint8_t {
    WalkVisited,      // triangles the current locate visited
    WalkNow,          // the triangle (or the ghost wedge outside the hull) the walk is in now
    LineL,            // the walk's line L from q to the new point
    NewTriangles,     // the triangles a split or a flip made
    TestEdge,         // the edge under the in-circle test
    CircleFlip,       // the test's circle (or half-plane): the new point is inside, flip
    CircleKeep,       // the test's circle: the new point is not inside, keep the edge
    HalfPlaneFlip,    // a ghost triangle's test: the half-plane beyond its hull edge holds it
    HalfPlaneKeep,    // a ghost triangle's test: the half-plane does not hold it, keep the edge
    FlippedEdge,      // edges flipped by this insertion so far
    NewEdge,          // the edges a split made at the new vertex
    QueuedEdge,       // edges on the flip stack
    QueueOrder,       // their places on the stack, numbered in test order (1 = next)
    QueuePushed,      // their places on the stack, numbered in push order (1 = pushed first)
    QueuedOnHull,     // a stack entry that now names a boundary edge: nothing to test there
    NextPoint,        // the point being inserted
    QueuedPoint,      // points not inserted yet
    SkippedPoint,     // duplicates skipped
    SelectedCorner,   // the selected corner and its triangle
    HoveredCorner,    // the corner under the mouse or the table row under it
    ChangedCorner,    // corners whose cells the current operation changed
    CornerMove,       // the last corner operator applied (inspector)
    Circumcircle,     // every triangle's circumcircle (the overlay)
    Voronoi,          // the Voronoi diagram (the overlay)
    IdPixel,          // the ID buffer's pixels: borders and centres (the overlay)
    IdPixelNow,       // the ID-buffer pixel under the point being inserted
    GhostBand,        // exact mode: the half-plane beyond each hull edge (ghost triangle)
    NotYetDelaunay,   // an edge validate() finds not Delaunay mid-insertion: tests to come
    Violation,        // a broken rule validate() reports (Statistics)
    HullDent,         // the triangle the mesh misses where its hull turns right (Statistics)
    HullEdgeMissing,  // the hull edge that closes such a dent: the mesh lacks it (Statistics)
    ExpressionPath,   // the typed expression's moves between corners (Expressions)
    StudentTriangle,  // a student's triangle that is not ours (Trace)
    MeshNotDelaunay,  // an opened mesh's edge that is not Delaunay now, with its circle (Check)
    MeshProblem,      // an opened mesh's problem that blocks a repair (Check)
    MeshPicked,       // the problem picked in the Check tab
    OnlyInMesh,       // an edge the mesh has and the Delaunay triangulation has not (Check)
    OnlyInDelaunay,   // an edge the Delaunay triangulation has and the mesh has not (Check)
    ConstrainedEdge,  // an edge an edit constrained: never flipped
    EditSegment,      // the segment an edit constrains or frees
    CrossingEdge,     // an edge that crosses the segment: Sloan's flips take it out
    EarTriangle,      // vertex removal: the ear tested (a triangle of the result when it is one)
    RemovedPoint,     // a vertex an edit removed
    Count
};
inline constexpr std::size_t kMarkCount = static_cast<std::size_t>(Mark::Count);

// How the legend draws a mark's sample.
enum class Shape : std::uint8_t { Fill, Line, Dashed, Arrow, Ring, Dot, Diamond, Cross, Badge };

struct Look {
    Mark mark;
    Shape shape;
    ImU32 colour;
    const char* meaning;  // the legend's words
};

// The table, in Mark order (the legend's order).
std::span<const Look> canvasLooks();
inline const Look& lookOf(Mark m) { return canvasLooks()[static_cast<std::size_t>(m)]; }

// The marks a frame drew (the canvas records each as it takes its colour).
using MarksDrawn = std::bitset<kMarkCount>;

struct AppState;

// A mark's colour, recorded as drawn on the canvas this frame (the legend lists it): for the
// layers drawn over the canvas by other panels (violations, expressions, a student's trace).
ImU32 useLook(AppState& state, Mark mark);

// What the legend should not cover: a screen box (a point, a label) with its weight, or a drawn
// edge from `at` to `to` (when `edge`).
struct BusyPoint {
    ImVec2 at;
    float weight = 1;
    ImVec2 to = at;     // the box's other corner, or the edge's other end
    bool edge = false;  // a segment, not a box
};
// The weights the canvas gives: a vertex and its label must stay visible; other labels and the
// edges count for little.
inline constexpr float kBusyVertex = 100, kBusyLabel = 3, kBusyEdge = 2;
// The edges the step is about (under test, waiting on the flip stack): a question may name them.
inline constexpr float kBusyOpEdge = 40;

// Where a legend box of size `size` goes on the canvas [lo, hi]: the place that covers the least
// weight of `busy` (a box or an edge it meets counts whole), 6 pixels in from the edge. The four
// corners are tried first (top right first), then the middles of the sides, then, when `anywhere`,
// a grid over the whole canvas; the first place of the least cover wins. Returns its top left.
ImVec2 placeLegend(ImVec2 lo, ImVec2 hi, ImVec2 size, std::span<const BusyPoint> busy,
                   bool anywhere);

// The weight of `busy` a box [a, b] covers (each within `margin` pixels counts).
float coveredWeight(ImVec2 a, ImVec2 b, std::span<const BusyPoint> busy, float margin);

// Draws the legend of the marks drawn into dl, at placeLegend's place on the canvas [lo, hi],
// text at fontSize; returns its box (x0, y0, x1, y1), or an empty one when nothing was drawn.
ImVec4 DrawCanvasLegend(ImDrawList* dl, ImVec2 lo, ImVec2 hi, const MarksDrawn& drawn,
                        float fontSize, std::span<const BusyPoint> busy, bool anywhere);

}  // namespace dlab::ui
