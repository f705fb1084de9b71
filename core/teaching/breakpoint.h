// Breakpoints over the Journal: "next flip", "vertex 5 inserted", "corner 17 changes", "op 120",
// and the budgeted runs forward/back until one hits (the GUI's step controls and the lessons).
//
// A breakpoint is a predicate on a journal POSITION p (p operations done). It looks at the last
// operation done, ops[p-1], so it means the same whether we arrive at p running forward or
// running back: "flip" stops on the state right after a flip, both ways. Text forms:
//
//   op:N          position N (N operations done); forward only stops there if N is ahead
//   step          every operation
//   walk          a walk step of a locate (LocateStep)
//   located       a locate ended (Located)
//   split         a 1->3 split
//   split-edge    a 2->4 (or 1->2 on the hull) edge split
//   incircle      an in-circle test; incircle:1 / incircle:0 / incircle:-1 only with that result
//   flip          an edge flipped
//   duplicate     a duplicate point skipped
//   degenerate    a point located on an edge or on an existing vertex, or a cocircular
//                 in-circle test (sign 0 on a real edge)
//   insert:K      vertex K is about to be inserted: its first operation is the next one
//   inserted      a vertex is in or was skipped; inserted:K only vertex K (in exact mode the
//                 first three vertices come in with Start)
//   insertion     a whole insertion ended: Start, Inserted, SkipDuplicate or Finalize
//   corner:C      the last operation changed V[C] or O[C]
//   finalize      the virtual triangles were removed
//   end           the run is finished
//
// Targets inside the lesson's edits after the run's end (core/engine/editor.h); they never hit
// in the run itself (hitsEditAt reads the Editor's records):
//
//   edit:N        the end of edit N (1-based; a lesson's run_to goes there as to op:N); edit:0
//                 the run's end, before the first edit;
//                 edit alone: the end of any edit
//   ear-test      a removal tested an ear; ear-test:1 an ear, ear-test:-1 no ear
//   ear-flip      a removal flipped an ear off the vertex (its degree one less)
//   merge         the vertex's last three triangles merged into one
//   segment-walk  the walk along a segment collected the edges it crosses
//   sloan-flip    a crossed edge flipped (Sloan)
//   sloan-wait    a crossed edge whose quadrilateral is not convex waits
//   constrain-mark  the segment is an edge now, marked constrained
//   edit-incircle an in-circle test of the repair; edit-incircle:1 / :0 / :-1 with that result
//   repair-flip   the repair flipped an edge (Lawson)
#pragma once

#include "core/engine/editor.h"

#include "core/engine/inserter.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace dlab {

enum class BreakKind : std::uint8_t {
    Op,
    Step,
    Walk,
    Located,
    Split,
    SplitEdge,
    InCircle,
    Flip,
    Duplicate,
    Degenerate,
    Insert,
    Inserted,
    Insertion,
    Corner,
    Finalize,
    End,
    Edit,
    EarTest,
    EarFlip,
    Merge,
    SegmentWalk,
    SloanFlip,
    SloanWait,
    ConstrainMark,
    EditInCircle,
    RepairFlip,
};

// How a kind uses its parameter.
enum class BreakParam : std::uint8_t { None, Optional, Required };

struct BreakKindInfo {
    BreakKind kind;
    const char* name;  // the text form before ':'
    BreakParam param;
    const char* meaning;  // one line for menus and help ("an edge flipped")
};

// Every kind, in the order of BreakKind (for GUI menus and help texts).
std::span<const BreakKindInfo> breakKinds();
const BreakKindInfo& info(BreakKind kind);

struct Breakpoint {
    BreakKind kind = BreakKind::Flip;
    std::optional<std::int64_t> param;  // op number, vertex, corner or in-circle sign
    friend bool operator==(const Breakpoint&, const Breakpoint&) = default;
};

// "insert:5" -> {Insert, 5}. Case-insensitive, spaces around the parts allowed. On failure
// returns nullopt and, when `error` is given, says why ("unknown breakpoint \"flop\"...").
std::optional<Breakpoint> parseBreakpoint(std::string_view text, std::string* error = nullptr);
std::string toString(const Breakpoint& bp);  // the text form, parseBreakpoint's inverse
std::string explain(const Breakpoint& bp);   // "vertex 5 is about to be inserted"

// Whether journal position `position` (0 .. recorded()) matches bp. Reads the recorded ops; the
// inserter is asked only for what the journal cannot tell (the number of input points, and for
// insert:K the next vertex when the next op is not recorded yet).
bool hitsAt(const Breakpoint& bp, const Journal& journal, const Inserter& ins,
            std::size_t position);
// The same at the journal's current position.
inline bool hits(const Breakpoint& bp, const Journal& journal, const Inserter& ins) {
    return hitsAt(bp, journal, ins, journal.position());
}
// Whether the kind is a target inside the edits (edit, ear-test, ... repair-flip).
bool isEditBreak(BreakKind kind);
// Whether the editor's position matches an edit target (false for the run's kinds).
bool hitsEditAt(const Breakpoint& bp, const Editor& editor);

// Whether an op of this type ends an insertion (Inserted, SkipDuplicate), the start triangle's
// (Start) or the run (Finalize): the boundaries that whole-insertion steps stop at.
bool endsInsertion(OpType type);

// Index of the first breakpoint of `bps` that hits at the current position, or -1.
int firstHit(std::span<const Breakpoint> bps, const Journal& journal, const Inserter& ins);

enum class StopReason : std::uint8_t {
    Hit,     // a breakpoint hit (RunResult::hit says which)
    End,     // the run is finished (forward)
    Start,   // position 0 (back)
    Budget,  // maxSteps operations done without a hit: call again (e.g. next frame)
};
const char* toString(StopReason reason);

struct RunResult {
    StopReason reason = StopReason::Budget;
    int hit = -1;           // index into the breakpoints when reason == Hit
    std::size_t steps = 0;  // operations done (forward) or undone (back)
};

// Steps forward at least once (unless already at the end), then until a breakpoint hits, the
// run ends, or maxSteps operations were done. `journal` must belong to `ins`.
RunResult runUntil(Journal& journal, const Inserter& ins, std::span<const Breakpoint> bps,
                   std::size_t maxSteps);
// Steps back at least once (unless at the start), then until a breakpoint hits at the new
// position, position 0 is reached, or maxSteps operations were undone.
RunResult runBackUntil(Journal& journal, const Inserter& ins, std::span<const Breakpoint> bps,
                       std::size_t maxSteps);

// Forward to the end of the current (or next) insertion: just after its Inserted or
// SkipDuplicate (or Start / Finalize).
RunResult forwardInsertion(Journal& journal, const Inserter& ins, std::size_t maxSteps);
// Back to the start of the current insertion (the position right after the previous insertion
// ended); from a position where an insertion just ended, back to the start of that insertion.
RunResult backInsertion(Journal& journal, const Inserter& ins, std::size_t maxSteps);

}  // namespace dlab
