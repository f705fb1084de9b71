// One-line captions of recorded operations ("edge 4-9 is Delaunay: no flip"), for the CLI's
// narration, the GUI's caption bar and lessons.
#pragma once

#include "core/engine/inserter.h"

#include <string>

namespace dlab {

// Describes `op` given the mesh as it is right after the op was applied.
std::string describe(const Op& op, const Inserter& inserter);
// A vertex as the captions name it: its id, "ghost" (exact mode) or "s0".."s2" (the
// super-triangle's) while the run is in progress, "-" for kNone.
std::string vertexName(const Inserter& inserter, std::int32_t v);

}  // namespace dlab
