// Session files: the whole state of a lab session as versioned JSON (points, options, the step,
// view, selection, overlays, breakpoints, the expression on the canvas and the watches), self-
// contained, so that a session file is also the bug report someone attaches when their mesh is
// wrong. Loading restores the same state at the same step and checks that the mesh there is the
// one that was saved (a fingerprint of G, V and O): a build that triangulates differently says so.
//
//   {"format": "delaunay-lab session", "version": 1, "source": "...",
//    "points": [[x, y], ...],                      (shortest round-trip decimals: bit-exact)
//    "options": {"boundary": "exact", "locator": "walk", "order": "input", "seed": 1,
//                "id_buffer": [1600, 1600]},
//    "position": 57,                              (operations done)
//    "view": {"center": [x, y], "scale": s}, "selection": {"corner": 7},
//    "overlays": {...}, "breakpoints": ["flip", "insert:5"],
//    "edits": ["remove vertex 5", "constrain 2-7"],  (after the run's end; "position" counts them)
//    "expressions": {"live": "c.n.o", "watches": [{"text": "o(o(c)) == c", "enabled": true}]},
//    "expect": {"position": 57, "op": "Flip", "triangles": 12, "vertices": 14,
//               "fingerprint": "0123456789abcdef"}}
//
// Everything but "format", "version" and "points" is optional; unknown keys are ignored. A file
// of a newer version is refused. Every error is one line, "FILE:LINE: points[3][1]: expected a
// number" (the line where that value starts), and a file with an error changes nothing.
#pragma once

#include "ui/app_state.h"

#include <cstdint>
#include <string>
#include <string_view>

namespace dlab::ui {

inline constexpr int kSessionVersion = 1;
inline constexpr const char* kSessionFormat = "delaunay-lab session";
// The largest session file opened. Its text is held while it is checked, its points taken out of
// the JSON as they are parsed (16 bytes each): 78 MB of 3 million points peak at 293 MB RSS,
// about kSessionMemoryPerByte times the file (measured), so the largest fits in well under 24 GB
// with its run. Past the memory there is, opening fails with one line saying which limit.
inline constexpr std::size_t kMaxSessionFileBytes = std::size_t{512} << 20;
inline constexpr int kSessionMemoryPerByte = 4;

// The session as JSON text (pretty-printed, one point per line).
std::string sessionText(const AppState& state);
// Writes the session atomically; logs; on failure false with a one-line reason in `error`.
bool saveSession(const AppState& state, const std::string& path, std::string& error);

// Parses and applies a session. On any error returns false with one line in `error` and leaves
// the state as it was. `name` names the file in messages. Warnings (a different mesh at the
// saved step, a step beyond the run's end) go to the message log.
bool loadSessionText(AppState& state, std::string_view text, const std::string& name,
                     std::string& error);
bool loadSession(AppState& state, const std::string& path, std::string& error);

// A few facts about a session file without applying it (the recovery offer).
struct SessionSummary {
    std::size_t points = 0;
    std::size_t position = 0;
    std::string source;
};
bool peekSession(const std::string& path, SessionSummary& out, std::string& error);

// FNV-1a over G (bits), V and O: equal meshes, equal fingerprints.
std::uint64_t MeshFingerprint(const Mesh& mesh);

}  // namespace dlab::ui
