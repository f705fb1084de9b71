// The run the GUI shows: the user's points and options, the Inserter and its Journal, and what
// the canvas derives from the recorded ops (the walk of the current locate, the flips so far).
// The Inserter/Journal are the only things that change the mesh; this class only drives them.
#pragma once

#include "core/engine/editor.h"
#include "core/engine/inserter.h"
#include "core/teaching/breakpoint.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace dlab::ui {

class GpuDevice;  // ui/render/renderer.h: a GL context (ui/gl/gl_api.h), or none
class GpuIdBuffer;

// An edge as two vertex ids (the canvas draws it from G).
struct VertexEdge {
    std::int32_t a = kNone, b = kNone;
};

class Engine {
public:
    // Above this many points the run has no history: it is made in one batch (Inserter::run)
    // and only the final mesh is shown. A history costs about 2 KB per point.
    static constexpr std::size_t kHistoryLimit = 200000;
    // Up to this many points the whole run is recorded at once, so the timeline spans it all
    // (up to kPrerecordOps operations).
    static constexpr std::size_t kPrerecordLimit = 20000;
    static constexpr std::size_t kPrerecordOps = 1000000;
    // A history holds at most this many operations (~100 bytes each with their cell changes):
    // BRIO order needs ~18 per point, but input or random order walk far, ~350 per point at
    // 200000 points. Past it the run is finished in one batch and stepping is off (takeNotice()).
    static constexpr std::size_t kOpLimit = 4000000;
    // The op limit of the runs reset from now on (tests use a small one).
    void setOpLimit(std::size_t ops) { m_opLimit = std::max<std::size_t>(ops, 1); }
    std::size_t opLimit() const { return m_opLimit; }
    // The operations this run will record to its end (estimateRunOps), 0 in batch mode.
    std::size_t estimatedOps() const { return m_estimatedOps; }
    // Whether recording this run to its end would pass the op limit (stepping would stop there).
    bool historyWillOverflow() const { return m_journal && m_estimatedOps > m_opLimit; }
    // Finishes the run in one batch from where it stands, without a history (stepping off
    // until the next reset), as the user asked.
    void runWithoutHistory();

    Engine();
    ~Engine();

    // Replaces the points and options and restarts at operation 0. On bad input (non-finite
    // coordinates, too many points, no finite super-triangle) returns false with a one-line
    // reason and leaves the engine as it was.
    bool reset(std::vector<Vec2> points, const InsertOptions& options, std::string& error);
    // As reset, then replays to `position` (clamped to the end): the same step after an edit.
    bool resetAt(std::vector<Vec2> points, const InsertOptions& options, std::size_t position,
                 std::string& error);
    // Lawson's flip algorithm from a given triangulation of `points` (Inserter's StartMesh),
    // stepped like insertion; with `flips` false the mesh is only shown (it is no
    // triangulation: nothing may be flipped). Restarts at operation 0 and runs to Start.
    bool resetRepair(std::vector<Vec2> points, Inserter::StartMesh start, bool flips,
                     std::string& error);
    // True while the run is the flip algorithm on an opened mesh.
    bool repairs() const { return m_ins->repairs(); }

    // The GL context that the GL ID-buffer locators and the mesh renderer draw on (the window's,
    // or OSMesa headless). Without one, idbuffer-gl is refused with a message. The owner of the
    // context detaches it before destroying the context; a GL locator still running then stops
    // drawing.
    void attachGl(std::shared_ptr<GpuDevice> gl);
    void detachGl();
    bool hasGl() const;
    const std::shared_ptr<GpuDevice>& glContext() const { return m_gl; }
    // The run's GL ID buffer when the locator is one, else nullptr (the ID-buffer view panel).
    GpuIdBuffer* idBufferGl() const { return m_idBufferGl; }

    const std::vector<Vec2>& points() const { return m_points; }
    // Where each point is now: as given, or past the run its place after the edits that moved
    // it (the edited mesh's G); cached per version().
    const std::vector<Vec2>& shownPoints() const;
    const InsertOptions& options() const { return m_options; }
    const Inserter& inserter() const { return *m_ins; }
    // The mesh at the position: the run's, or past its end the edited one (editing()).
    const Mesh& mesh() const { return editing() ? m_editor->mesh() : m_ins->mesh(); }
    const Journal* journal() const { return m_journal.get(); }
    bool batch() const { return m_journal == nullptr; }
    // Why this run has no stepping, in the words of the message log ("" while it has).
    const std::string& batchReason() const { return m_batchReason; }
    // Bumps whenever the mesh or the position changes: renderers cache on it.
    std::uint64_t version() const { return m_version; }
    // Bumps on every reset (new points or options): the journal's positions belong to one run.
    std::uint64_t run() const { return m_run; }

    // ---- Stepping. Each returns whether anything moved. -------------------------------------
    bool forward();
    bool back();
    bool forwardInsertion();  // to just after the next Inserted / SkipDuplicate (or the end)
    bool backInsertion();     // to just after the previous one (or the start)
    void toStart();
    // Steps forward until the end or until `maxOps` ops were done. True at the end.
    bool toEnd(std::size_t maxOps);
    void seek(std::size_t position);
    // Positions run over the run's ops, then the edits' (recorded() counts both).
    std::size_t position() const;
    std::size_t recorded() const;
    bool atEnd() const;
    // At the run's last op (the edits, if any, follow).
    bool atRunEnd() const;
    const Op* current() const;  // the op just performed, nullptr at the start or in batch mode
    // Whether the breakpoint holds at the current position (false in batch mode).
    bool hits(const Breakpoint& bp) const;
    std::size_t insertionsDone() const;
    // Predicate calls past the floating-point filter (orient2d, incircle) that this run made up
    // to the current position; in batch mode, the whole run's.
    std::array<std::uint64_t, 2> exactFallbacks() const;

    // ---- Edits after the run (core/engine/editor.h) ------------------------------------------
    // Removes a vertex, or adds or takes away a constrained segment, as recorded ops after the
    // run's end (and after the edits kept): the position goes there and the edit's ops are
    // stepped from it like the run's, forwards and back. False, with nothing changed, when it is
    // refused or the run cannot be edited (the super-triangle, an opened mesh, no triangle);
    // `message` says what happened either way.
    bool edit(Edit edit, std::string& message);
    const Editor* editor() const { return m_editor.get(); }
    // A drag of vertex v to `to`: one move edit from where the drag started, remade as the drag
    // goes on (`continuing`: this drag made the last edit, which is taken out and made again),
    // its ops done so the mesh follows. Refused (onto another vertex...), the last place stays.
    bool dragVertex(std::int32_t v, Vec2 to, bool continuing, std::string& message);
    // Ctrl+Z / Ctrl+Y of edits: the last edit taken out of the timeline (the position goes back
    // to its start when past it), or the last one taken out made again; false when there is
    // none. A new edit forgets the ones taken out. `message` says what was done.
    bool undoEdit(std::string& message);
    bool redoEdit(std::string& message);
    // Past the run's end, into the edits: the mesh shown is the editor's (closed: its ghost
    // triangles are virtual, as while the run inserts).
    bool editing() const { return m_editor && m_editor->position() > 0; }
    // The edit op just done (no edit at the run's end or before it).
    EditStep currentEdit() const { return editing() ? m_editor->current() : EditStep{}; }
    // Whether the mesh shown has virtual triangles (the ghosts or the super-triangle's): while
    // the run inserts, and while edits are shown.
    bool showsVirtual() const { return !m_ins->done() || editing(); }
    bool isVirtual(std::int32_t v) const { return m_ins->isVirtual(v); }
    bool isVirtualTriangle(std::int32_t t) const {
        const Mesh& m = mesh();
        return isVirtual(m.V[3 * t]) || isVirtual(m.V[3 * t + 1]) || isVirtual(m.V[3 * t + 2]);
    }

    // ---- Derived from the ops of the insertion in progress ------------------------------------
    // Ops from the first op of the current insertion up to the current position (empty between
    // insertions and in batch mode).
    std::span<const Op> currentInsertion() const;
    // Triangles the current locate visited, in order (only while the locate is in progress or
    // just ended, before the split changes the triangles).
    std::vector<std::int32_t> walkPath() const;
    // Edges made by the flips of the current insertion so far (vertex pairs).
    std::vector<VertexEdge> flippedEdges() const;
    // Edges still to test: the edge opposite each corner on the flip stack, the next one (the
    // top of the stack) first.
    struct QueuedTest {
        std::int32_t corner = kNone;  // on the inserter's flip stack
        VertexEdge edge;              // V[next(corner)], V[prev(corner)]
        std::int32_t near = kNone;    // tri(corner): the new point's side
        std::int32_t far = kNone;     // tri(O[corner]), kNone past the hull
    };
    std::vector<QueuedTest> pendingTests() const;
    // The input point being inserted, kNone between insertions.
    std::int32_t currentVertex() const { return m_ins->currentVertex(); }
    // What each input point is now: waiting, being inserted, a vertex, or a skipped duplicate.
    // Removed: taken out of the mesh by an edit.
    enum class PointState : std::uint8_t { Pending, Current, Inserted, Skipped, Removed };
    const std::vector<PointState>& pointStates() const;  // cached per version()

    // A one-line warning the engine has for the user (the history was dropped); empty when none.
    // Reading it clears it.
    std::string takeNotice() { return std::exchange(m_notice, {}); }

private:
    void bump() { ++m_version; }
    bool resetWith(std::vector<Vec2> points, const InsertOptions& options, std::size_t position,
                   std::optional<Inserter::StartMesh> start, std::string& error);
    // At the op limit with the cursor at the tip: finish in one batch, drop the history.
    void capHistory();
    // Runs the rest of the run in one batch, counting its exact fallbacks into m_batchExact.
    void finishInBatch();
    // The run's ops (the edits' positions follow them); the journal's seek.
    std::size_t runLength() const { return m_journal ? m_journal->recorded() : 0; }
    void seekRun(std::size_t position);

    std::vector<Vec2> m_points;
    InsertOptions m_options;
    std::shared_ptr<GpuDevice> m_gl;
    GpuIdBuffer* m_idBufferGl = nullptr;  // owned by m_ins
    std::unique_ptr<Inserter> m_ins;
    std::unique_ptr<Journal> m_journal;
    std::unique_ptr<Editor> m_editor;  // the edits after the run's end, once there is one
    std::vector<Edit> m_undoneEdits;   // taken out by undoEdit, newest last
    std::vector<std::int32_t> m_rank;  // position of each input point in the insertion order
    std::uint64_t m_version = 0;
    std::uint64_t m_run = 0;
    mutable std::vector<Vec2> m_shown;  // shownPoints() while editing
    mutable std::uint64_t m_shownVersion = ~std::uint64_t{0};
    mutable std::vector<PointState> m_states;
    mutable std::uint64_t m_statesVersion = ~std::uint64_t{0};
    std::string m_notice;
    std::string m_batchReason;
    std::size_t m_opLimit = kOpLimit;
    std::size_t m_estimatedOps = 0;
    std::array<std::uint64_t, 2> m_batchExact{};  // exactFallbacks() in batch mode
};

// Every edit on the run's timeline as a user writes it ("remove vertex 5"), in order: what sessions
// and the autosave keep.
std::vector<std::string> editTexts(const Engine& engine);

// The operations a recorded run of these points in this order (input ids in insertion order)
// makes, from Start to Finalize: counted on batch runs of the first points of the order (exact
// up to kPilotPoints points), the walk extrapolated as it grows with the number of points
// (input and random order walk ~sqrt(n) triangles a point, BRIO a few). A few milliseconds.
std::size_t estimateRunOps(const std::vector<Vec2>& points, const std::vector<std::int32_t>& order,
                           const InsertOptions& options);
// The same in the order the options give.
std::size_t estimateRunOps(const std::vector<Vec2>& points, const InsertOptions& options);
inline constexpr std::size_t kPilotPoints = 8192;

}  // namespace dlab::ui
