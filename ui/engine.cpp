// The GUI's run: restart on new points or options, step, and derive what the canvas highlights.
#include "ui/engine.h"
#include "core/engine/predicates.h"

#include "ui/render/renderer.h"

#include <algorithm>
#include <cmath>
#include <exception>

namespace dlab::ui {

namespace {

// A batch run of the first m points of the order, in that order, on a CPU locator.
InsertStats pilotRun(const std::vector<Vec2>& points, const std::vector<std::int32_t>& order,
                     InsertOptions options, std::size_t m) {
    std::vector<Vec2> prefix(m);
    for (std::size_t k = 0; k < m; ++k) prefix[k] = points[static_cast<std::size_t>(order[k])];
    options.order = OrderKind::Input;
    if (needsGl(options.locator)) options.locator = LocatorKind::IdBufferCpu;
    Inserter ins(std::move(prefix), options);
    ins.run();
    return ins.stats();
}

// The ops of a run besides its walk steps: Start and Finalize; Located, a split and Inserted per
// point placed by a walk (exact mode's Start places three without one); Located and
// SkipDuplicate per duplicate; the edges off the flip stack (tested or on the boundary) and flips.
double opsBesidesWalk(const InsertStats& s, const InsertOptions& options) {
    const std::int64_t started = options.boundary == Boundary::Exact ? 3 : 0;
    const std::int64_t placed = std::max<std::int64_t>(s.inserted - started, 0);
    return 2.0 + 3.0 * static_cast<double>(placed) + 2.0 * static_cast<double>(s.duplicates) +
           static_cast<double>(s.inCircleTests + s.boundaryPops + s.flips);
}

}  // namespace

std::size_t estimateRunOps(const std::vector<Vec2>& points, const std::vector<std::int32_t>& order,
                           const InsertOptions& options) {
    const std::size_t n = std::min(points.size(), order.size());
    const std::size_t m = std::min(n, kPilotPoints);
    try {
        const InsertStats all = pilotRun(points, order, options, m);
        const double walk = static_cast<double>(all.walkSteps);
        if (m == n) return static_cast<std::size_t>(opsBesidesWalk(all, options) + walk);
        // Walks of the second half against the first: how the walk grows (n^a a point).
        const InsertStats half = pilotRun(points, order, options, m / 2);
        const double first = std::max(1.0, static_cast<double>(half.walkSteps));
        const double a = std::clamp(std::log2(std::max(1.0, walk) / first) - 1.0, 0.0, 0.5);
        const double scale = static_cast<double>(n) / static_cast<double>(m);
        return static_cast<std::size_t>(opsBesidesWalk(all, options) * scale +
                                        walk * std::pow(scale, 1.0 + a));
    } catch (const std::exception&) {
        return 0;  // points the inserter refuses: the run itself says why
    }
}

std::vector<std::string> editTexts(const Engine& engine) {
    std::vector<std::string> out;
    if (const Editor* ed = engine.editor()) {
        for (const Edit& e : ed->edits()) out.push_back(describe(e));
    }
    return out;
}

std::size_t estimateRunOps(const std::vector<Vec2>& points, const InsertOptions& options) {
    InsertOptions cpu = options;
    if (needsGl(cpu.locator)) cpu.locator = LocatorKind::IdBufferCpu;
    try {
        const Inserter ins(points, cpu);
        return estimateRunOps(points, ins.order(), cpu);
    } catch (const std::exception&) {
        return 0;
    }
}

Engine::Engine() {
    std::string error;
    reset({}, InsertOptions{}, error);
}

Engine::~Engine() = default;

void Engine::attachGl(std::shared_ptr<GpuDevice> gl) { m_gl = std::move(gl); }

void Engine::detachGl() {
    if (m_gl) m_gl->lose();
    m_gl.reset();
}

bool Engine::hasGl() const { return m_gl && m_gl->alive(); }

bool Engine::reset(std::vector<Vec2> points, const InsertOptions& options, std::string& error) {
    return resetAt(std::move(points), options, 0, error);
}

bool Engine::resetAt(std::vector<Vec2> points, const InsertOptions& options, std::size_t position,
                     std::string& error) {
    return resetWith(std::move(points), options, position, std::nullopt, error);
}

bool Engine::resetRepair(std::vector<Vec2> points, Inserter::StartMesh start, bool flips,
                         std::string& error) {
    start.flip = flips;
    return resetWith(std::move(points), m_options, 1, std::move(start), error);
}

bool Engine::resetWith(std::vector<Vec2> points, const InsertOptions& options, std::size_t position,
                       std::optional<Inserter::StartMesh> start, std::string& error) {
    std::unique_ptr<Inserter> ins;
    GpuIdBuffer* gl = nullptr;
    try {
        std::unique_ptr<Locator> locator;
        if (needsGl(options.locator)) {
            if (!hasGl()) {
                error = std::string(toString(options.locator)) +
                        " needs a GL context, and this view has none";
                return false;
            }
            auto made = m_gl->makeIdBuffer(options.locator, options.locatorOptions);
            gl = made.get();
            locator = std::move(made);
        }
        ins = start ? std::make_unique<Inserter>(points, std::move(*start), options)
                    : std::make_unique<Inserter>(points, options, std::move(locator));
        if (gl) gl->followOrder(*ins);  // before any step: the batched readback reads ahead
    } catch (const std::exception& e) {
        error = e.what();
        return false;
    }
    m_journal.reset();
    m_editor.reset();
    m_undoneEdits.clear();
    ++m_run;
    m_ins = std::move(ins);
    m_idBufferGl = gl;
    m_points = std::move(points);
    m_options = options;
    m_batchReason.clear();
    m_estimatedOps = 0;
    m_batchExact = {};
    if (m_points.size() > kHistoryLimit) {
        finishInBatch();
        m_batchReason = "more than " + std::to_string(kHistoryLimit) +
                        " points: triangulated in one batch, stepping is off";
    } else {
        // Reserved for a BRIO-like run (~18 ops and ~42 cell changes a point).
        const std::size_t n = m_points.size();
        m_journal =
            std::make_unique<Journal>(*m_ins, std::min(m_opLimit, 20 * n + 64), 44 * n + 64);
        if (n <= kPrerecordLimit) m_journal->seek(std::min(kPrerecordOps, m_opLimit));
        seek(position);
        const auto& ops = m_journal->ops();
        const bool whole = !ops.empty() && ops.back().type == OpType::Finalize;
        m_estimatedOps = whole              ? ops.size()
                         : m_ins->repairs() ? 0
                                            : estimateRunOps(m_points, m_ins->order(), m_options);
    }
    m_rank.assign(m_points.size(), 0);
    const auto& order = m_ins->order();
    for (std::size_t k = 0; k < order.size(); ++k) m_rank[order[k]] = static_cast<std::int32_t>(k);
    bump();
    return true;
}

void Engine::capHistory() {
    if (!m_journal || m_journal->recorded() < m_opLimit ||
        m_journal->position() < m_journal->recorded() || m_ins->done()) {
        return;
    }
    finishInBatch();
    m_journal.reset();
    m_batchReason = "the history reached " + std::to_string(m_opLimit) +
                    " operations: the run was finished in one batch and stepping is off (BRIO "
                    "order walks far less)";
    m_notice = m_batchReason;
    bump();
}

void Engine::finishInBatch() {
    const PredicateCounters& c = predicateCounters();
    const std::uint64_t orient = c.orientExact, incircle = c.incircleExact;
    m_batchExact = {};
    if (m_journal) {
        const auto done = m_journal->exactFallbacksAt(m_journal->position());
        m_batchExact = {done[0], done[1]};
    }
    m_ins->run();
    m_batchExact[0] += c.orientExact - orient;
    m_batchExact[1] += c.incircleExact - incircle;
}

std::array<std::uint64_t, 2> Engine::exactFallbacks() const {
    if (!m_journal) return m_batchExact;
    const auto at = m_journal->exactFallbacksAt(m_journal->position());
    return {at[0], at[1]};
}

void Engine::runWithoutHistory() {
    if (!m_journal) return;
    finishInBatch();
    m_journal.reset();
    m_estimatedOps = 0;
    m_batchReason =
        "run without a history, as asked: stepping is off (a new order or new points "
        "record again)";
    bump();
}

bool Engine::forward() {
    if (m_journal && !m_journal->atEnd()) {
        if (!m_journal->forward()) return false;
        capHistory();
    } else if (!m_editor || !m_editor->forward()) {
        return false;
    }
    bump();
    return true;
}

bool Engine::back() {
    if (m_editor && m_editor->position() > 0) {
        m_editor->back();
    } else if (!m_journal || !m_journal->back()) {
        return false;
    }
    bump();
    return true;
}

bool Engine::forwardInsertion() {
    if (m_editor && atRunEnd()) {  // in the edits: to the end of the next one
        const std::size_t k = m_editor->editsDone();
        if (k >= m_editor->edits().size()) return false;
        m_editor->seek(m_editor->editEnd(k));
        bump();
        return true;
    }
    if (!m_journal) return false;
    const std::size_t steps =
        dlab::forwardInsertion(*m_journal, *m_ins, static_cast<std::size_t>(-1)).steps;
    capHistory();
    if (steps) bump();
    return steps > 0;
}

bool Engine::backInsertion() {
    if (editing()) {  // to the start of the edit in progress (or the last one done)
        m_editor->seek(m_editor->editStart(m_editor->current().index));
        bump();
        return true;
    }
    if (!m_journal) return false;
    const std::size_t steps =
        dlab::backInsertion(*m_journal, *m_ins, static_cast<std::size_t>(-1)).steps;
    if (steps) bump();
    return steps > 0;
}

bool Engine::edit(Edit edit, std::string& message) {
    if (!m_journal) {
        message =
            "this run has no history (" + m_batchReason + "): edits are stepped, they need one";
        return false;
    }
    if (m_ins->repairs()) {
        message = "an opened mesh cannot be edited: triangulate its points";
        return false;
    }
    if (!m_editor) {
        seekRun(static_cast<std::size_t>(-1));  // the run's end: the edits start from it
        if (!m_ins->done()) {
            message = "the run has not reached its end: run it to the end first";
            return false;
        }
        if (m_ins->mesh().numTriangles() == 0) {
            message = "no triangle to edit: the points are collinear or fewer than three";
            return false;
        }
        m_editor = editorAtRunEnd(*m_journal, *m_ins);
    }
    seekRun(runLength());
    const bool ok = m_editor->add(std::move(edit), message);
    if (ok) m_undoneEdits.clear();
    bump();
    return ok;
}

bool Engine::dragVertex(std::int32_t v, Vec2 to, bool continuing, std::string& message) {
    std::optional<Edit> before;
    if (continuing && m_editor && !m_editor->edits().empty()) {
        const Edit& last = m_editor->edits().back();
        if (last.kind == EditKind::MoveVertex && last.a == v) before = m_editor->takeLast();
    }
    const bool ok = edit(makeMove(v, to), message);
    if (!ok && before) {  // the drag's last place stays
        std::string again;
        edit(std::move(*before), again);
    }
    if (m_editor) m_editor->seek(m_editor->total());
    bump();
    return ok;
}

bool Engine::undoEdit(std::string& message) {
    std::optional<Edit> last = m_editor ? m_editor->takeLast() : std::nullopt;
    if (!last) {
        message = "no edit to undo";
        return false;
    }
    message = "undone: " + describe(*last);
    m_undoneEdits.push_back(std::move(*last));
    bump();
    return true;
}

bool Engine::redoEdit(std::string& message) {
    if (m_undoneEdits.empty()) {
        message = "no edit to redo";
        return false;
    }
    std::vector<Edit> undone = std::move(m_undoneEdits);
    Edit again = std::move(undone.back());
    undone.pop_back();
    const std::string what = describe(again);
    const bool ok = edit(std::move(again), message);
    m_undoneEdits = std::move(undone);  // the others stay to redo
    if (ok) message = "redone: " + what;
    return ok;
}

bool Engine::hits(const Breakpoint& bp) const {
    if (editing()) return isEditBreak(bp.kind) && hitsEditAt(bp, *m_editor);
    return m_journal && dlab::hits(bp, *m_journal, *m_ins);
}

void Engine::toStart() { seek(0); }

bool Engine::toEnd(std::size_t maxOps) {
    for (std::size_t i = 0; i < maxOps; ++i) {
        if (!forward()) return true;
    }
    return atEnd();
}

void Engine::seekRun(std::size_t position) {
    if (!m_journal || position == m_journal->position()) return;
    // Recording stops at the op limit; a seek beyond it (the End key) finishes the run.
    m_journal->seek(std::min(position, std::max(m_journal->recorded(), m_opLimit)));
    if (position > m_journal->position()) capHistory();
    bump();
}

void Engine::seek(std::size_t position) {
    if (m_editor) {
        const std::size_t run = runLength();
        const std::size_t edits = position > run ? position - run : 0;
        if (edits != m_editor->position()) {
            if (edits > 0) seekRun(run);
            m_editor->seek(edits);
            bump();
        }
        if (edits > 0) return;
    }
    seekRun(position);
}

bool Engine::atRunEnd() const { return m_journal ? m_journal->atEnd() : true; }
std::size_t Engine::position() const {
    return (m_journal ? m_journal->position() : 0) + (m_editor ? m_editor->position() : 0);
}
std::size_t Engine::recorded() const { return runLength() + (m_editor ? m_editor->total() : 0); }
bool Engine::atEnd() const {
    return atRunEnd() && (!m_editor || m_editor->position() == m_editor->total());
}
const Op* Engine::current() const {
    return m_journal && !editing() ? m_journal->current() : nullptr;
}

std::size_t Engine::insertionsDone() const {
    return static_cast<std::size_t>(m_ins->stats().inserted + m_ins->stats().duplicates);
}

std::span<const Op> Engine::currentInsertion() const {
    if (!m_journal || editing()) return {};
    const auto& ops = m_journal->ops();
    const std::size_t end = m_journal->position();
    std::size_t begin = end;
    while (begin > 0 && !endsInsertion(ops[begin - 1].type)) --begin;
    return {ops.data() + begin, end - begin};
}

std::vector<std::int32_t> Engine::walkPath() const {
    std::vector<std::int32_t> path;
    for (const Op& op : currentInsertion()) {
        if (op.type == OpType::LocateStep) {
            if (path.empty()) path.push_back(op.a);
            path.push_back(op.b);
        } else if (op.type == OpType::Located) {
            if (path.empty()) path.push_back(op.a);
        } else {
            return {};  // the split has changed the triangles: the path is history
        }
    }
    return path;
}

std::vector<VertexEdge> Engine::flippedEdges() const {
    std::vector<VertexEdge> edges;
    if (!m_journal) return edges;
    const auto& changes = m_journal->changes();
    for (const Op& op : currentInsertion()) {
        if (op.type != OpType::Flip) continue;
        // The flip writes V[p(a)] = D, then V[p(O[a])] = P (see Inserter::flip): the new edge
        // is P-D.
        std::int32_t after[2] = {kNone, kNone};
        int k = 0;
        for (std::uint32_t i = 0; i < op.numChanges && k < 2; ++i) {
            const CellChange& ch = changes[op.firstChange + i];
            if (!ch.isO()) after[k++] = ch.after;
        }
        // The flip algorithm may flip an edge made earlier away again: only its last flip's
        // edge is sure to be in the mesh.
        if (m_ins->repairs()) edges.clear();
        if (k == 2) edges.push_back({after[1], after[0]});
    }
    return edges;
}

std::vector<Engine::QueuedTest> Engine::pendingTests() const {
    std::vector<QueuedTest> tests;
    const Mesh& m = mesh();
    const std::vector<std::int32_t>& stack = m_ins->flipStack();
    for (auto it = stack.rbegin(); it != stack.rend(); ++it) {
        const std::int32_t c = *it;
        if (c < 0 || c >= m.numCorners()) continue;
        const std::int32_t o = m.O[c];
        tests.push_back({c, {m.V[next(c)], m.V[prev(c)]}, tri(c), o == kNone ? kNone : tri(o)});
    }
    return tests;
}

const std::vector<Vec2>& Engine::shownPoints() const {
    if (!editing()) return m_points;
    if (m_shownVersion != m_version) {
        const auto& G = m_editor->mesh().G;
        m_shown.assign(G.begin(), G.begin() + static_cast<std::ptrdiff_t>(m_points.size()));
        m_shownVersion = m_version;
    }
    return m_shown;
}

const std::vector<Engine::PointState>& Engine::pointStates() const {
    if (m_statesVersion == m_version) return m_states;
    m_statesVersion = m_version;
    const std::int32_t n = static_cast<std::int32_t>(m_points.size());
    m_states.assign(static_cast<std::size_t>(n), PointState::Pending);
    const Control& ctl = m_ins->control();
    const bool hasMesh = m_ins->mesh().numTriangles() > 0;
    for (std::int32_t i = 0; i < n; ++i) {
        PointState& s = m_states[i];
        if (m_ins->done() || m_ins->repairs()) {  // an opened mesh has every point in it
            s = hasMesh ? PointState::Inserted : PointState::Pending;
        } else if (ctl.phase == Phase::Start) {
            s = PointState::Pending;
        } else if (m_rank[i] < ctl.cursor) {
            s = hasMesh ? PointState::Inserted : PointState::Pending;
        } else if (m_rank[i] == ctl.cursor && ctl.phase != Phase::Finalize) {
            s = PointState::Current;
        }
    }
    for (std::int32_t i : m_ins->skipped()) {
        if (i >= 0 && i < n) m_states[i] = PointState::Skipped;
    }
    if (editing()) {  // the vertices the edits took out
        std::vector<char> used(static_cast<std::size_t>(n), 0);
        for (const std::int32_t v : mesh().V) {
            if (v >= 0 && v < n) used[v] = 1;
        }
        for (std::int32_t i = 0; i < n; ++i) {
            if (!used[i] && m_states[i] == PointState::Inserted) m_states[i] = PointState::Removed;
        }
    }
    return m_states;
}

}  // namespace dlab::ui
