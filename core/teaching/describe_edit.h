// The ops of edits (core/engine/editor.h) in words and in the shapes the canvas draws: what each
// op's record says, read from it, for the GUI's caption bar, its canvas and the lessons.
#pragma once

#include "core/engine/editor.h"

#include <cstdint>
#include <string>
#include <vector>

namespace dlab {

// The edit op just done (editor.current()) in words: "remove vertex 8, ear test at 5: triangle
// 10-5-3 is no ear: ..."; "" at the edits' start. The ghost vertex reads "g", the
// super-triangle's "s0" to "s2".
std::string describeEditStep(const Editor& editor);

// A flip writes two V cells: the new edge's ends after it, the old edge's before it.
struct FlipEdges {
    std::int32_t oldA = kNone, oldB = kNone, newA = kNone, newB = kNone;
};
FlipEdges flipEdges(const std::vector<CellChange>& changes, std::uint32_t first, std::uint32_t n);

// The ear of an ear test: its tip b, and the neighbours a and c of the vertex on either side of
// it (the mesh as it is at the test).
struct Ear {
    std::int32_t a = kNone, b = kNone, c = kNone;
};
Ear earOf(const Mesh& m, const RemoveOp& op);

// Triangle t's hull edge x->y (the mesh on its left) when it is a ghost triangle (`ghost` is one
// of its vertices: Editor::ghost()); false for a finite triangle or no triangle.
bool ghostHullEdge(const Mesh& m, std::int32_t ghost, std::int32_t t, std::int32_t& x,
                   std::int32_t& y);

}  // namespace dlab
