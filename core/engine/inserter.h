// Lawson's incremental Delaunay insertion as a resumable state machine of recorded operations.
//
// step() performs exactly one operation (one walk step, a split, one in-circle test, one flip,
// ...) and returns its Op record. A Journal keeps the records and their cell changes so that
// any prefix can be undone exactly. run() is the batch path: the same primitives (walk step,
// split, test, flip) instantiated with a recorder that does nothing, so the fast path pays
// nothing for the teaching path.
//
// Boundary modes:
//   Exact (default): one ghost vertex g = |input| joined to every hull edge. A ghost triangle
//     (x, y, g) stands for the half-plane right of the hull edge y->x; its "circumcircle" is
//     that open half-plane plus the open segment xy. The result is the Delaunay triangulation of
//     the input with its convex hull, collinear hull points included.
//   Super: the paper's finite super-triangle, its three vertices at the end of G; triangles
//     touching them are removed at the end. Near the hull the result can be non-convex and
//     non-Delaunay: that is the paper's flaw, kept on purpose for the lesson that shows it.
#pragma once

#include "core/engine/enum_names.h"
#include "core/engine/geometry.h"
#include "core/engine/locator.h"
#include "core/engine/mesh.h"
#include "core/engine/order.h"

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace dlab {

enum class Boundary : std::uint8_t { Exact, Super };
inline constexpr std::array<EnumName<Boundary>, 2> kBoundaryNames{
    {{Boundary::Exact, "exact"}, {Boundary::Super, "super"}}};
const char* toString(Boundary b);
std::optional<Boundary> parseBoundary(std::string_view name);

enum class OpType : std::uint8_t {
    Start,          // the first triangle(s): super-triangle, or first non-collinear triple + ghosts
    LocateStep,     // the walk moved from triangle a to triangle b
    Located,        // the walk ended: triangle a contains the point (where = inside/edge/vertex)
    Split,          // 1->3: triangle a split around the new vertex; 2 triangles appended
    SplitEdge,      // 2->4 (or 1->2 on a boundary): the edge opposite corner a split
    InCircleTest,   // is the new vertex inside the circle of the triangle across the edge
                    // opposite corner a (corner b)? sign in `sign`
    Flip,           // the edge opposite corner a (shared with corner b) flipped in place
    SkipDuplicate,  // the point equals vertex `b`: skipped (the lower input index is kept)
    Inserted,       // the vertex is in, every edge around it is Delaunay
    Finalize,       // virtual triangles removed, V and O compacted
};
const char* toString(OpType t);
std::optional<OpType> parseOpType(std::string_view name);

enum class Where : std::uint8_t { None, InTriangle, OnEdge, OnVertex, Outside };
const char* toString(Where w);

// One changed cell of V or O. slot = 2 * corner + (O ? 1 : 0).
struct CellChange {
    std::int32_t slot;
    std::int32_t before;
    std::int32_t after;
    bool isO() const { return slot & 1; }
    std::int32_t corner() const { return slot >> 1; }
};

enum class Phase : std::uint8_t { Start, Locate, Place, Test, Flip, Finish, Finalize, Done };

// The walk towards the point being inserted.
struct WalkState {
    std::int32_t tri = kNone;    // current triangle of the walk (kNone: not started)
    std::int32_t entry = kNone;  // corner of tri facing the edge we entered through
    std::int32_t steps = 0;
    bool straight = true;  // the paper's line walk (false: visibility-walk fallback)
    Vec2 origin{};         // q, the start of the line L = q->p of the straight walk
};

// Everything the state machine needs besides the mesh and the flip stack.
struct Control {
    Phase phase = Phase::Start;
    std::int32_t cursor = 0;  // position in the insertion order of the current point
    WalkState walk;
    Where where = Where::None;         // classification once located
    std::int32_t whereCorner = kNone;  // Located: corner facing the edge / at the vertex
    std::int32_t flipCorner = kNone;   // the edge (opposite this corner) a positive test flips
    std::int32_t lastTri = 0;          // a triangle of the last inserted vertex
};

struct Op {
    OpType type = OpType::Start;
    Where where = Where::None;
    std::int8_t sign = 0;  // InCircleTest: +1 flip, 0 cocircular, -1 Delaunay
    // How many corners the op put on the flip stack (Split 3, SplitEdge 2 or 4, Flip 2 or, in
    // the flip algorithm, up to 4), kept in order in Journal::pushes() after those of the ops
    // before it: undo and redo read them from there. kPushesInB: more than fit here (the flip
    // algorithm's Start queues every edge), the count is in b. Read it with pushCount(op).
    std::uint8_t pushes = 0;
    std::int32_t vertex = kNone;  // input index of the point being inserted
    std::int32_t a = kNone;       // see OpType
    std::int32_t b = kNone;
    std::int32_t trianglesBefore = 0;
    std::int32_t trianglesAfter = 0;
    std::int32_t verticesBefore = 0;  // |G| (Finalize drops the virtual vertices)
    std::int32_t verticesAfter = 0;
    std::uint32_t firstChange = 0;  // range in Journal::changes()
    std::uint32_t numChanges = 0;
    // The control state before the op, for exact undo (Journal::controlBefore): ops that start
    // or move a walk, end it, or place the point (hasControlSnapshot) keep a snapshot, this is
    // its index in the Journal; the in-circle tests, flips and Inserted of an insertion differ
    // from the snapshot before their Place op only in phase and flip corner, this is how many
    // ops back that Place op is.
    std::uint32_t control = 0;
};

inline constexpr std::uint8_t kPushesInB = 255;
inline std::size_t pushCount(const Op& op) {
    return op.pushes == kPushesInB ? static_cast<std::size_t>(op.b) : op.pushes;
}

// Ops whose control state before cannot be derived from an earlier op's (see Op::control).
inline bool hasControlSnapshot(OpType t) {
    return t != OpType::InCircleTest && t != OpType::Flip && t != OpType::Inserted;
}

// What one predicate call of the inserter asks: the first triangle's orientation, the walk's
// tests (start, line side, exit edge, visibility, hull edge), the classification of the point in
// the triangle the walk stopped in, and the in-circle test of an edge at the new vertex.
enum class PredicateAsk : std::uint8_t {
    FirstTriangle,   // orient2d(a, b, c): the first three points in order (exact mode's start)
    StartCentroid,   // orient2d(a, b, q): is the start triangle's centroid q left of edge a->b?
    LineSide,        // orient2d(q, p, v): is vertex v left of the walk's line L from q to p?
    ExitEdge,        // orient2d(a, b, p): is p inside the edge a->b that L leaves through?
    VisibilityEdge,  // orient2d(a, b, p): the visibility walk: is p left of the edge a->b?
    HullEdge,        // orient2d(a, b, p): in a ghost triangle: is p beyond the hull edge a->b?
    ClassifyEdge,    // orient2d(a, b, p): p against an edge of its triangle the walk left open
    ClassifyHull,    // orient2d(a, b, p): the same against a ghost triangle's hull edge
    InCircle,        // incircle(a, b, c, d): is the new vertex d inside the circle of a, b, c?
    GhostCircle,     // orient2d(a, b, d): across a hull edge a->b: is the new vertex d beyond it?
};
const char* toString(PredicateAsk ask);

// One orient2d or incircle call as the inserter made it: its arguments in order, their vertex
// ids, and the sign it used.
struct RecordedPredicateCall {
    PredicateAsk ask = PredicateAsk::FirstTriangle;
    std::int8_t sign = 0;     // the exact sign, the one the inserter acted on
    std::array<Vec2, 4> p{};  // the arguments (three for orient2d)
    // Their vertex ids; kNone for the walk's origin q (a point of no vertex). Vertices from
    // firstVirtual() on are the super-triangle's (the ghost vertex has no coordinates and is
    // never an argument: its triangles are tested through their hull edge).
    std::array<std::int32_t, 4> v{kNone, kNone, kNone, kNone};
    // The corner whose opposite edge is tested (the vertex's corner for LineSide; the corner at
    // the new vertex for InCircle / GhostCircle); kNone for FirstTriangle.
    std::int32_t corner = kNone;
    bool inCircle() const { return ask == PredicateAsk::InCircle; }
    int numArgs() const { return inCircle() ? 4 : 3; }
    bool operator==(const RecordedPredicateCall& o) const;
};
// One line: what the call asks in the inserter's terms, e.g. "is p = v7 left of the edge
// v2 -> v5 of t3?".
std::string describe(const RecordedPredicateCall& call);

struct InsertOptions {
    Boundary boundary = Boundary::Exact;
    LocatorKind locator = LocatorKind::Walk;
    OrderKind order = OrderKind::Brio;
    std::uint64_t seed = 1;
    LocatorOptions locatorOptions;
    int threads = 1;  // the insertion order's sorts may use two (the same order; the run is one)
};

// Whether two option sets make the same run, op for op (the ID buffer's size only changes how
// the locator finds triangles, not which triangle it finds).
inline bool sameRun(const InsertOptions& a, const InsertOptions& b) {
    return a.boundary == b.boundary && a.locator == b.locator && a.order == b.order &&
           a.seed == b.seed;
}

struct InsertStats {
    std::int64_t inserted = 0;
    std::int64_t duplicates = 0;
    std::int64_t flips = 0;
    std::int64_t inCircleTests = 0;
    std::int64_t walkSteps = 0;
    std::int64_t edgeSplits = 0;
    std::int64_t boundaryPops = 0;  // edges off the flip stack on the boundary: nothing to test
    InsertStats& operator+=(const InsertStats& o) {
        inserted += o.inserted;
        duplicates += o.duplicates;
        flips += o.flips;
        inCircleTests += o.inCircleTests;
        boundaryPops += o.boundaryPops;
        walkSteps += o.walkSteps;
        edgeSplits += o.edgeSplits;
        return *this;
    }
};

// The most triangles a run on n points holds at once (ghosts included): the batch reserves it.
inline constexpr std::size_t maxTriangles(std::size_t n) { return 2 * n + 8; }

class Journal;

class Inserter {
public:
    // Throws std::invalid_argument for non-finite coordinates or too many points, and
    // std::domain_error when super mode cannot build a finite super-triangle.
    Inserter(std::vector<Vec2> points, const InsertOptions& options = {},
             std::unique_ptr<Locator> locator = nullptr);
    // Lawson's flip algorithm from a given triangulation instead of insertion: Start puts the
    // triangles `V` with their opposites `O` (a valid triangulation of `points`, as checkMesh
    // finds it: counter-clockwise, O its own) in the corner table and every interior edge on the
    // flip stack, one corner each in increasing order; each InCircleTest pops one, each Flip
    // puts the four edges around the flipped one back (those inside the mesh), and Finalize
    // ends the run once the stack is empty. Every op is stepped, recorded and undone as in
    // insertion; no point is located or inserted. The boundary mode is exact (no virtual
    // triangle is made: the triangulation's outline is its own).
    struct StartMesh {
        std::vector<std::int32_t> V, O;
        bool flip = true;  // false: Start queues no edge (a mesh to show, not to repair)
    };
    Inserter(std::vector<Vec2> points, StartMesh start, const InsertOptions& options = {});
    // True for a run of the flip algorithm from a given mesh.
    bool repairs() const { return m_repair; }
    ~Inserter();
    Inserter(const Inserter&) = delete;
    Inserter& operator=(const Inserter&) = delete;

    // One recorded operation (journal may be null: then nothing is kept for undo). With `calls`,
    // every predicate call the operation makes is appended there as it is made.
    Op step(Journal* journal = nullptr, std::vector<RecordedPredicateCall>* calls = nullptr);
    // The predicate calls of `op`, made again by the same code from `before`, the control state
    // before it (Journal::controlBefore), with the locator's hint read from the op (its start
    // triangle): every orient2d and incircle call is the one the op made, in order. Only Start
    // (exact mode: the first triangle's orientation), the locate ops and the in-circle tests make
    // calls; the latter change neither V nor O, so the mesh must be the one before or after op
    // (Start's call reads only the points).
    std::vector<RecordedPredicateCall> predicateCallsOf(const Op& op, const Control& before) const;
    // Batch: run to the end with recording compiled out.
    void run();
    // Called by run() with the number of points taken so far, every kProgressEvery of them.
    static constexpr std::int32_t kProgressEvery = 1 << 14;
    void setProgress(std::function<void(std::int32_t taken)> progress) {
        m_progress = std::move(progress);
    }
    // run() for a caller that needs only the topology: the points in input order are not kept
    // aside while the batch works in insertion order (n * 16 bytes less at the peak), and G is
    // empty afterwards. V, O and skipped() are run()'s, with input point i called names[i] when
    // `names` is not empty: the caller's own ids, increasing (equal points keep the lowest name,
    // as they keep the lowest index), without a pass of its own over V and a list kept for it.
    // Only from the start: then order() gives the names in insertion order.
    void runForTopology(std::vector<std::int32_t> names = {});
    // Room in the corner table for this many triangles (run() makes room for maxTriangles(n)).
    void reserveTriangles(std::size_t count);
    bool done() const { return m_ctl.phase == Phase::Done; }

    const Mesh& mesh() const { return m_mesh; }
    // After a batch run(): the mesh itself, handed over (this inserter keeps an empty one).
    Mesh takeMesh() { return std::exchange(m_mesh, Mesh{}); }
    const InsertOptions& options() const { return m_options; }
    const std::vector<std::int32_t>& order() const { return m_order; }
    std::int32_t numInput() const { return m_numInput; }
    // Vertices >= firstVirtual() are the ghost vertex or the super-triangle's (until Finalize).
    std::int32_t firstVirtual() const { return m_numInput; }
    bool isVirtual(std::int32_t v) const { return v >= m_numInput; }
    bool isVirtualTriangle(std::int32_t t) const {
        const auto& V = m_mesh.V;
        return isVirtual(V[3 * t]) || isVirtual(V[3 * t + 1]) || isVirtual(V[3 * t + 2]);
    }
    const Control& control() const { return m_ctl; }
    const std::vector<std::int32_t>& flipStack() const { return m_stack; }
    const InsertStats& stats() const { return m_stats; }
    Locator* locator() { return m_locator.get(); }
    // Input points that ended up as no vertex of the result (duplicates), in input order.
    const std::vector<std::int32_t>& skipped() const { return m_skipped; }
    // The point currently being inserted (kNone when none).
    std::int32_t currentVertex() const;

    // Journal support: revert / re-apply one recorded op; `before` and `after` are the control
    // states around it.
    // `pushes` are the op's own flip-stack pushes as recorded (Op::pushes of them).
    void undo(const Op& op, const std::vector<CellChange>& changes,
              std::span<const std::int32_t> pushes, const Control& before);
    // Bulk mode (long seeks): undo/redo stop notifying the locator; leaving it rebuilds the
    // locator's index once from the current mesh.
    void setBulk(bool on);
    void redo(const Op& op, const std::vector<CellChange>& changes,
              std::span<const std::int32_t> pushes, const Control& after);

private:
    template <class Rec>
    Op stepImpl(Rec& rec);
    template <class Rec>
    void doStart(Rec& rec, Op& op);
    template <class Rec>
    void doPlace(Rec& rec, Op& op);
    template <class Rec>
    void doFinalize(Rec& rec, Op& op);
    void notifyReplayed(const Op& op, const std::vector<CellChange>& changes);
    template <class Rec>
    void doLocate(Rec& rec, Op& op);
    template <class Rec>
    void doTest(Rec& rec, Op& op);
    void doFinish(Op& op);
    // Exact mode's first triangle: the sign of the first three points in order (0: collinear, or
    // fewer than three points: no triangle).
    template <class Rec>
    int firstTriangleSign(Rec& rec) const;

    template <class Rec>
    void setV(Rec& rec, std::int32_t c, std::int32_t v);
    template <class Rec>
    void setO(Rec& rec, std::int32_t c, std::int32_t o);
    template <class Rec>
    void link(Rec& rec, std::int32_t c, std::int32_t d);  // O[c]=d, O[d]=c
    template <class Rec>
    std::int32_t appendTriangles(Rec& rec, int count);
    // Puts the edge opposite corner c on the flip stack, through the recorder.
    template <class Rec>
    void pushTest(Rec& rec, std::int32_t c);
    template <class Rec>
    void split(Rec& rec, std::int32_t t, std::int32_t v);
    template <class Rec>
    void splitEdge(Rec& rec, std::int32_t c, std::int32_t v);
    template <class Rec>
    void flip(Rec& rec, std::int32_t c);
    template <class Rec>
    void doStartRepair(Rec& rec, Op& op);
    template <class Rec>
    void keepFirstOccurrence(Rec& rec, std::int32_t existing, std::int32_t v);

    void collectDuplicatesWithoutMesh();  // all points collinear: report equal points anyway
    std::vector<std::int32_t> virtualTriangles() const;  // sorted ids of triangles to drop
    void beginLocate();
    struct HullEdge {
        int k;      // index of the ghost vertex's corner in its triangle
        Vec2 x, y;  // the hull edge opposite it
    };
    HullEdge hullEdgeOf(std::int32_t c0) const;
    // Signs of orient2d(edge opposite corner 3*tri+k, p) that the walk computed (or derived
    // exactly) when it stopped in tri, so that classify() does not evaluate them again.
    static constexpr std::int8_t kUnknownSide = 2;
    struct KnownSides {
        std::int32_t tri = kNone;
        std::array<std::int8_t, 3> side{};
    };
    // Where the point lies in the triangle the walk stopped in (None: nowhere, a walk error).
    struct Placement {
        Where where = Where::None;
        std::int32_t corner = kNone;  // see Control::whereCorner
    };
    // The point being inserted: its id and where it is.
    struct Query {
        std::int32_t v;
        Vec2 p;
    };
    Query currentQuery() const;
    // The walk: one step (the recorded path) or every step until found (the batch path); true
    // when m_ctl.walk.tri contains the current point, with the sides it knows in `known`.
    // Its parts are inlined into the batch loop: the attribute is on these declarations, since a
    // member template takes its attributes from its first declaration.
    template <class Rec>
    bool walk(Rec& rec, bool oneStep, KnownSides& known);
    template <class Rec>  // one step; true when w.tri contains p
    [[gnu::always_inline]] bool walkOnce(Rec& rec, WalkState& w, Query p, KnownSides& known) const;
    enum class StartStep : std::uint8_t { Found, Moved, Undecided };
    template <class Rec>  // the first step of the line walk
    [[gnu::always_inline]] StartStep walkStart(Rec& rec, WalkState& w, Query p,
                                               KnownSides& known) const;
    // The walk stops in t: the sides of p it knows (corner, sign; kNone for none) for classify().
    [[gnu::always_inline]] static bool walkFound(KnownSides& known, std::int32_t t, std::int32_t c1,
                                                 int s1, std::int32_t c2, int s2);
    template <class Rec>  // across that edge
    [[gnu::always_inline]] bool walkMove(WalkState& w, std::int32_t corner, bool keepEntry) const;
    // The walk's start in triangle t (the locator's hint), L's origin kept from `from`.
    static WalkState walkFrom(std::int32_t t, const WalkState& from) {
        return {t, kNone, 0, true, from.origin};
    }
    // Where p lies in triangle t, given the sides the walk knows.
    template <class Rec>
    Placement classify(Rec& rec, std::int32_t t, Query p, const KnownSides& known) const;
    template <class Rec>  // is V[c] inside the circle across the edge? (inlined: the flip loop's)
    [[gnu::always_inline]] int inCircleSign(Rec& rec, std::int32_t c) const;
    bool onOpenSegment(Vec2 a, Vec2 b, Vec2 p) const;
    void notifyChanged(const std::int32_t* tris, int count);
    // While run() works on points stored in insertion order, vertex ids are insertion ranks.
    std::int32_t vertexAt(std::int32_t cursor) const {
        return m_permuted ? cursor : m_order[cursor];
    }
    std::int32_t inputId(std::int32_t v) const {
        return m_permuted && v < m_numInput ? m_order[v] : v;
    }
    Vec2 currentPoint() const { return m_mesh.G[vertexAt(m_ctl.cursor)]; }
    void permuteForBatch(std::vector<std::int32_t> names);
    void unpermute();

    std::function<void(std::int32_t)> m_progress;  // run()'s ticks (setProgress)
    InsertOptions m_options;
    Mesh m_mesh;
    std::int32_t m_numInput = 0;
    std::vector<std::int32_t> m_order;
    std::vector<Vec2> m_virtualPoints;  // super-triangle vertices or the ghost placeholder
    bool m_repair = false;              // the flip algorithm from m_start (repairs())
    StartMesh m_start;
    std::unique_ptr<Locator> m_locator;
    bool m_locatorWantsChanges = false;
    bool m_permuted = false;
    std::vector<Vec2> m_byInput;  // while run() works by rank: the points in input order
    bool m_keepPoints = true;     // false: runForTopology() (m_byInput not kept)
    bool m_bulk = false;
    Bounds m_bounds{};
    Control m_ctl;
    std::vector<std::int32_t> m_stack;  // flip work-list: corners at the new vertex
    std::vector<std::int32_t> m_skipped;
    InsertStats m_stats;
};

// The most memory a Journal's history takes by default: 1 GiB (about 10 million operations
// with their cell changes). Past it the journal stops recording: forward() returns nullptr and
// budgetReached() says why; the run itself can go on unrecorded (Inserter::step(nullptr)).
inline constexpr std::size_t kHistoryBudgetBytes = std::size_t{1} << 30;

// The record of a run: ops and their cell changes, with a cursor for undo/redo.
class Journal {
public:
    explicit Journal(Inserter& inserter) : m_ins(&inserter) {}
    // Reserves room for this many ops and cell changes up front: a vector doubling at millions
    // of ops copies hundreds of megabytes in one step, a visible stall.
    Journal(Inserter& inserter, std::size_t expectedOps, std::size_t expectedChanges)
        : m_ins(&inserter) {
        m_ops.reserve(expectedOps);
        m_changes.reserve(expectedChanges);
        m_pushes.reserve(expectedOps / 2);  // BRIO: ~9 pushes a point in ~18 ops
        m_exact.reserve(expectedOps);
    }
    // Forward one op: replays a recorded op after an undo, else asks the inserter for a new one.
    // Returns nullptr at the end.
    const Op* forward();
    const Op* back();                 // undo the op before the cursor; nullptr at the start
    void seek(std::size_t position);  // forward/back until position (clamped)
    std::size_t position() const { return m_pos; }
    std::size_t recorded() const { return m_ops.size(); }
    bool atEnd() const { return m_pos == m_ops.size() && m_ins->done(); }
    const std::vector<Op>& ops() const { return m_ops; }
    const std::vector<CellChange>& changes() const { return m_changes; }
    const Op* current() const { return m_pos > 0 ? &m_ops[m_pos - 1] : nullptr; }
    // The inserter's control state before recorded op i (i < recorded()).
    Control controlBefore(std::size_t i) const;
    // The predicate calls recorded op i made, made again by the inserter from the control state
    // before it (Inserter::predicateCallsOf). Op i must be the op just done or the next one
    // (i + 1 == position() or i == position() < recorded()), whose mesh the inserter holds;
    // throws std::out_of_range for any other.
    std::vector<RecordedPredicateCall> predicateCallsOf(std::size_t i) const;
    // Predicate calls the floating-point filter could not decide (predicateCounters()) that
    // the first `position` ops made as they were recorded: orient2d, incircle.
    std::array<std::uint32_t, 2> exactFallbacksAt(std::size_t position) const {
        const std::size_t p = std::min(position, m_exact.size());
        return p == 0 ? std::array<std::uint32_t, 2>{} : m_exact[p - 1];
    }
    // Memory the record holds: ops, control snapshots and cell changes (sizes, not capacities).
    std::size_t bytesUsed() const {
        return m_ops.size() * sizeof(Op) + m_controls.size() * sizeof(Control) +
               m_changes.size() * sizeof(CellChange) + m_pushes.size() * sizeof(std::int32_t) +
               m_exact.size() * sizeof(m_exact[0]);
    }
    std::size_t controlSnapshots() const { return m_controls.size(); }
    // The history's memory budget (bytes of reserved ops, control snapshots and cell changes),
    // and whether forward() stopped at it: then the run is not done, but nothing more is
    // recorded.
    void setBudget(std::size_t bytes) { m_budget = bytes; }
    std::size_t budget() const { return m_budget; }
    std::size_t memoryBytes() const {
        return m_ops.capacity() * sizeof(Op) + m_controls.capacity() * sizeof(Control) +
               m_changes.capacity() * sizeof(CellChange) +
               m_pushes.capacity() * sizeof(std::int32_t) + m_exact.capacity() * sizeof(m_exact[0]);
    }
    bool budgetReached() const { return m_budgetReached; }

    // Used by the inserter while recording.
    void record(const CellChange& c) { m_changes.push_back(c); }
    std::uint32_t changeCount() const { return static_cast<std::uint32_t>(m_changes.size()); }
    void recordPush(std::int32_t corner) { m_pushes.push_back(corner); }
    std::size_t pushCount() const { return m_pushes.size(); }
    // Every op's flip-stack pushes in op order (Op::pushes each).
    const std::vector<std::int32_t>& pushes() const { return m_pushes; }
    void push(Op op, const Control& before);

private:
    Inserter* m_ins;
    std::vector<Op> m_ops;
    std::vector<Control> m_controls;  // snapshots, see Op::control
    std::vector<CellChange> m_changes;
    std::vector<std::int32_t> m_pushes;
    // exactFallbacksAt(i + 1) for each op i
    std::vector<std::array<std::uint32_t, 2>> m_exact;
    std::size_t m_pos = 0;
    std::size_t m_pushEnd = 0;  // pushes of the ops before m_pos
    Control m_tip;              // the inserter's control state after the last recorded op
    std::size_t m_budget = kHistoryBudgetBytes;
    bool m_budgetReached = false;
    bool fitsBudget() const;  // room for one more op without passing the budget
};

}  // namespace dlab
