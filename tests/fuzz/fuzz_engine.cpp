// Fuzz target: the engine. Bytes -> a degenerate point set and options -> recorded insertion,
// checked exactly, compared with the batch path, undone to the bit-for-bit start state.
//
// Byte layout (every byte past the end reads as 0, so any input decodes):
//   [0] options: bit 0 boundary (exact/super), bits 1-2 locator, bits 3-4 order (mod 3),
//       bit 5 round-trip ops through the trace format
//   [1] seed   [2] [3] ID-buffer width and height (1..64)   [4] position of a mid-run probe
//   [5] scale exponent e (coordinates are k * 2^e, e from about -1074 to 980)
//   [6] [7] offset (ox, oy) = small integers * 2^(e+40): far from the origin, tiny spacing
//   then commands, one byte each plus operands, until the bytes or kMaxFuzzPoints run out:
//     grid point, duplicate of an earlier point, collinear run, lattice points of a circle
//     (cocircular sets), midpoint of two points (points on edges), raw doubles (any finite
//     bits), a change of scale (huge and tiny together), a finer cloud point.
// Integer lattices scaled by powers of two keep collinear and cocircular sets exactly so.
// After the insertion checks, vertices are removed from the closed mesh (the state before
// Finalize) in an order drawn from the seed and the probe, each removal checked exactly; in the
// exact mode segments between the vertices left are then constrained (recorded), each checked
// valid and constrained Delaunay; then the constraints and the removals are undone bit for bit.
// The GUI's editor mixes removals, constraints and moves (halfway to another vertex, or beyond it
// and often out of the hull), each checked valid, constrained Delaunay with a convex hull, made
// again the same on a fresh editor and stepped back bit for bit.
#include "tests/fuzz/fuzz_common.h"

#include "core/engine/constrainer.h"
#include "core/engine/editor.h"
#include "core/engine/halves.h"
#include "core/engine/inserter.h"
#include "core/engine/predicates.h"
#include "core/engine/remover.h"
#include "core/teaching/trace.h"
#include "tests/exact_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>
#include <stdexcept>

namespace {

using namespace dlab;
using dlab::fuzz::fail;
using dlab::fuzz::require;

// Enough for long flip cascades and every degenerate shape; small enough for thousands of
// runs a second (each run is checked in GMP rationals).
constexpr std::size_t kMaxFuzzPoints = 160;

class Bytes {
public:
    Bytes(const std::uint8_t* data, std::size_t size) : m_data(data), m_size(size) {}
    bool empty() const { return m_pos >= m_size; }
    std::uint8_t u8() { return m_pos < m_size ? m_data[m_pos++] : 0; }
    int range(int lo, int hi) { return lo + u8() % (hi - lo + 1); }  // in [lo, hi], hi - lo < 256
    std::uint64_t u64() {
        std::uint64_t v = 0;
        for (int i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(u8()) << (8 * i);
        return v;
    }
    double f64() {
        const std::uint64_t bits = u64();
        double d;
        std::memcpy(&d, &bits, sizeof d);
        return d;
    }

private:
    const std::uint8_t* m_data;
    std::size_t m_size;
    std::size_t m_pos = 0;
};

// Lattice points on the circle x^2 + y^2 = r^2: 4 for r = 1, 12 for 5, 20 for 25, 36 for 65.
std::vector<std::pair<int, int>> latticeCircle(int r) {
    std::vector<std::pair<int, int>> out;
    for (int x = -r; x <= r; ++x) {
        for (int y = -r; y <= r; ++y) {
            if (x * x + y * y == r * r) out.emplace_back(x, y);
        }
    }
    return out;
}

struct Case {
    std::vector<Vec2> points;
    InsertOptions options;
    bool traceRoundTrip = false;
    std::uint8_t probe = 0;
};

class Decoder {
public:
    explicit Decoder(Bytes& in) : m_in(in) {}

    Case decode() {
        Case c;
        const std::uint8_t flags = m_in.u8();
        c.options.boundary = (flags & 1) ? Boundary::Super : Boundary::Exact;
        c.options.locator = static_cast<LocatorKind>((flags >> 1) & 3);
        c.options.order = static_cast<OrderKind>(((flags >> 3) & 3) % 3);
        c.traceRoundTrip = (flags >> 5) & 1;
        c.options.seed = m_in.u8();
        c.options.locatorOptions.idBufferWidth = 1 + m_in.u8() % 64;
        c.options.locatorOptions.idBufferHeight = 1 + m_in.u8() % 64;
        c.probe = m_in.u8();
        setExponent(static_cast<int>(static_cast<std::int8_t>(m_in.u8())) * 8);
        m_offX = m_in.range(-4, 4);
        m_offY = m_in.range(-4, 4);
        while (!m_in.empty() && m_pts.size() < kMaxFuzzPoints) command();
        c.points = std::move(m_pts);
        return c;
    }

private:
    // Coordinates k * 2^e stay finite for |k| < 2^16 + offsets; below the normal range they
    // become (exact) subnormals or round, which is still a valid input.
    void setExponent(int e) { m_exp = std::clamp(e, -1100, 980); }

    double coord(double k, int offset) const {
        const double off =
            m_exp + 40 <= 1000 ? std::ldexp(static_cast<double>(offset), m_exp + 40) : 0.0;
        return off + std::ldexp(k, m_exp);
    }
    void add(double kx, double ky) { push({coord(kx, m_offX), coord(ky, m_offY)}); }
    void push(Vec2 p) {
        if (std::isfinite(p.x) && std::isfinite(p.y) && m_pts.size() < kMaxFuzzPoints)
            m_pts.push_back(p);
    }

    void command() {
        switch (m_in.u8() % 10) {
            case 0:
            case 1: {  // grid point: tiny integer lattice, dense in cocircular quadruples
                const int x = m_in.range(-8, 8);
                add(x, m_in.range(-8, 8));
                break;
            }
            case 2:  // duplicate of an earlier point
                if (!m_pts.empty()) push(m_pts[m_in.u8() % m_pts.size()]);
                break;
            case 3: {  // collinear run
                const int x = m_in.range(-8, 8), y = m_in.range(-8, 8);
                int dx = m_in.range(-3, 3);
                const int dy = m_in.range(-3, 3);
                if (dx == 0 && dy == 0) dx = 1;
                const int count = m_in.range(3, 12);
                for (int i = 0; i < count; ++i) add(x + i * dx, y + i * dy);
                break;
            }
            case 4: {  // a subset of the lattice points of a circle: exactly cocircular
                static const std::vector<std::pair<int, int>> circles[] = {
                    latticeCircle(1), latticeCircle(5), latticeCircle(25), latticeCircle(65)};
                const auto& circle = circles[m_in.u8() % 4];
                const int cx = m_in.range(-8, 8), cy = m_in.range(-8, 8);
                const std::uint64_t mask = m_in.u64();
                for (std::size_t i = 0; i < circle.size(); ++i) {
                    if (mask >> (i % 64) & 1) add(cx + circle[i].first, cy + circle[i].second);
                }
                break;
            }
            case 5:  // midpoint of two points: a point on their segment (exactly, at lattice scale)
                if (m_pts.size() >= 2) {
                    const Vec2 a = m_pts[m_in.u8() % m_pts.size()],
                               b = m_pts[m_in.u8() % m_pts.size()];
                    push({a.x + (b.x - a.x) / 2, a.y + (b.y - a.y) / 2});
                }
                break;
            case 6: {  // any finite doubles: subnormals, DBL_MAX, wild exponent spans
                const double x = m_in.f64();
                push({x, m_in.f64()});
                break;
            }
            case 7:  // change the scale: later points are much larger or smaller
                setExponent(m_exp + m_in.range(-64, 64) * 4);
                break;
            case 8: {  // a finer cloud point
                const int x = m_in.range(0, 255) - 128;
                add(std::ldexp(x, -6), std::ldexp(m_in.range(0, 255) - 128, -6));
                break;
            }
            case 9: {  // the same grid point, repeated: a pile of duplicates
                const int x = m_in.range(-8, 8), y = m_in.range(-8, 8);
                const int count = m_in.range(2, 6);
                for (int i = 0; i < count; ++i) add(x, y);
                break;
            }
        }
    }

    Bytes& m_in;
    std::vector<Vec2> m_pts;
    int m_exp = 0;
    int m_offX = 0, m_offY = 0;
};

struct Snapshot {
    std::vector<Vec2> G;
    std::vector<std::int32_t> V, O;
    bool operator==(const Snapshot& s) const {
        return V == s.V && O == s.O && G.size() == s.G.size() &&
               (G.empty() || std::memcmp(G.data(), s.G.data(), G.size() * sizeof(Vec2)) == 0);
    }
};
Snapshot snap(const Mesh& m) { return {m.G, m.V, m.O}; }

bool sameStats(const InsertStats& a, const InsertStats& b) {
    return a.inserted == b.inserted && a.duplicates == b.duplicates && a.flips == b.flips &&
           a.inCircleTests == b.inCircleTests && a.boundaryPops == b.boundaryPops &&
           a.walkSteps == b.walkSteps && a.edgeSplits == b.edgeSplits;
}

std::string describe(const Case& c) {
    std::string s = std::string("boundary ") + toString(c.options.boundary) + ", locator " +
                    toString(c.options.locator) + ", order " + toString(c.options.order) + ", " +
                    std::to_string(c.points.size()) + " points";
    return s;
}

void checkResult(const Case& c, const Inserter& ins) {
    const std::string what = describe(c);
    const Mesh& m = ins.mesh();
    const auto n = static_cast<std::int32_t>(c.points.size());
    require(m.numVertices() == n, "after the run G holds exactly the input points", what);
    const auto violations = validate(m);
    if (!violations.empty())
        fail("validate() accepts the result", what + ": " + violations[0].message);

    const auto distinct = firstOccurrences(c.points);
    require(ins.stats().duplicates == n - static_cast<std::int64_t>(distinct.size()),
            "every later copy of a point is reported as a duplicate", what);
    std::vector<std::int32_t> expectSkipped;
    std::set<std::int32_t> firsts(distinct.begin(), distinct.end());
    for (std::int32_t i = 0; i < n; ++i) {
        if (!firsts.count(i)) expectSkipped.push_back(i);
    }
    std::vector<std::int32_t> skipped = ins.skipped();
    std::sort(skipped.begin(), skipped.end());
    require(skipped == expectSkipped, "skipped() lists exactly the later copies", what);
    const std::set<std::int32_t> used(m.V.begin(), m.V.end());
    for (std::int32_t v : used)
        require(firsts.count(v) == 1, "only first occurrences are vertices", what);

    if (c.options.boundary == Boundary::Super) return;  // the paper's mode promises no more
    if (allCollinearExact(c.points)) {
        require(m.numTriangles() == 0, "collinear input gives no triangle", what);
        return;
    }
    const std::string exact = checkDelaunayExact(m, &distinct);
    require(exact.empty(), "the exact GMP check accepts the triangulation", what + ": " + exact);
}

void traceRoundTrip(const Journal& journal, const Mesh& mesh) {
    const TraceRecord r = traceRecord(journal, journal.position() - 1, mesh);
    const std::string line = toJsonLine(r);
    require(parseTraceLine(line, "fuzz", 1) == r,
            "an op's trace line reads back as the same record", line);
}

// The two-core path on the same set, split however small (both halves on this thread): where
// both halves have a triangle, the join is exactly Delaunay, with the batch's vertices, triangle
// count and duplicates.
void checkHalves(const Case& c, const Inserter& batch) {
    if (c.options.boundary != Boundary::Exact || c.options.locator != LocatorKind::Walk) return;
    const std::string what = describe(c) + ", split in two";
    std::vector<Vec2> points = c.points;
    const std::optional<Vec2> split = splitPoint(points, 2);
    if (!split) return;
    HalfTriangulation left = triangulateHalf(points, *split, true, c.options);
    HalfTriangulation right = triangulateHalf(points, *split, false, c.options);
    const bool bothHaveTriangles = left.mesh.numTriangles() > 0 && right.mesh.numTriangles() > 0;
    const auto joined = joinHalves(points, std::move(left), std::move(right));
    require(joined.has_value() == bothHaveTriangles, "two halves with triangles join", what);
    if (!joined) return;
    const auto distinct = firstOccurrences(c.points);
    const std::string exact = checkDelaunayExact(joined->mesh, &distinct);
    require(exact.empty(), "the exact GMP check accepts the joined halves", what + ": " + exact);
    require(joined->mesh.numTriangles() == batch.mesh().numTriangles(),
            "the joined halves have the batch's triangle count", what);
    std::vector<std::int32_t> skipped = batch.skipped();
    std::sort(skipped.begin(), skipped.end());
    require(joined->skipped == skipped, "the joined halves skip the batch's duplicates", what);
}

// One removal checked: the closed mesh valid (Delaunay with the super-triangle's real vertices),
// and in the exact mode the finished mesh exactly the Delaunay triangulation of the vertices left.
void checkRemoval(const Case& c, const Mesh& closed, const std::vector<std::int32_t>& left,
                  bool exactCheck) {
    const std::string what = describe(c) + ", after removals";
    const auto n = static_cast<std::int32_t>(c.points.size());
    const bool exact = c.options.boundary == Boundary::Exact;
    ValidateOptions vo;
    vo.firstVirtual = exact ? n : -1;
    const auto bad = validate(closed, vo);
    if (!bad.empty())
        fail("a removal leaves a valid Delaunay corner table", what + ": " + bad[0].message);
    if (!exact || !exactCheck) return;
    Mesh finished = closed;
    dropVirtual(finished, n);
    std::vector<Vec2> leftPoints;
    for (const std::int32_t v : left) leftPoints.push_back(c.points[v]);
    if (allCollinearExact(leftPoints)) {
        require(finished.numTriangles() == 0, "collinear points left give no triangle", what);
        return;
    }
    const std::string err = checkDelaunayExact(finished, &left);
    require(err.empty(), "the exact GMP check accepts the mesh after a removal", what + ": " + err);
}

// Constrains up to 12 drawn segments between the vertices left (exact mode's closed mesh), each
// recorded and checked: a valid corner table, every segment refused only for a constrained edge
// it crosses, every unconstrained edge between finite triangles locally Delaunay. Then all undone:
// the mesh as it was, bit for bit.
void checkConstraints(const Case& c, Mesh& closed, const std::vector<std::int32_t>& left,
                      std::uint64_t state) {
    const std::string what = describe(c) + ", constraints";
    const auto n = static_cast<std::int32_t>(c.points.size());
    if (left.size() < 3 || closed.numTriangles() == 0) return;
    const Snapshot before = snap(closed);
    Constrainer con(closed, n);
    ConstraintRecord record;
    ValidateOptions vo;
    vo.firstVirtual = n;
    vo.delaunay = false;
    for (int k = 0; k < 12; ++k) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        const std::int32_t a = left[(state >> 33) % left.size()];
        const std::int32_t b = left[(state >> 13) % left.size()];
        const ConstrainOutcome out = con.insert(a, b, &record);
        require(out.result != ConstrainResult::NotInMesh, "a vertex left can be constrained", what);
        const auto bad = validate(closed, vo);
        if (!bad.empty())
            fail("a constraint leaves a valid corner table", what + ": " + bad[0].message);
        for (std::int32_t e = 0; e < closed.numCorners(); ++e) {
            const std::int32_t o = closed.O[e];
            if (o == kNone || con.isConstrained(e)) continue;
            const std::int32_t P = closed.V[e], A = closed.V[next(e)], B = closed.V[prev(e)];
            const std::int32_t D = closed.V[o];
            if (P >= n || A >= n || B >= n || D >= n) continue;
            require(incircle(closed.G[P], closed.G[A], closed.G[B], closed.G[D]) <= 0,
                    "every unconstrained edge is locally Delaunay", what);
        }
    }
    con.undo(record);
    require(snap(closed) == before, "undoing every constraint restores the mesh bit for bit", what);
}

// Removes vertices of the closed mesh in a drawn order (about two in three), checking each
// removal, constrains segments between those left (exact mode), then undoes the constraints and
// the removals: the closed mesh again, bit for bit.
void checkRemovals(const Case& c, Mesh closed) {
    const std::string what = describe(c) + ", removals";
    const auto n = static_cast<std::int32_t>(c.points.size());
    const Snapshot start = snap(closed);
    std::vector<std::int32_t> left = firstOccurrences(c.points), order = left;
    std::uint64_t state =
        c.options.seed * 6364136223846793005ULL + c.probe + 1442695040888963407ULL;
    for (std::size_t i = order.size(); i > 1; --i) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        std::swap(order[i - 1], order[(state >> 33) % i]);
    }
    order.resize(order.size() * 2 / 3);
    Remover remover(closed, n, c.options.boundary);
    RemovalRecord record;
    for (std::size_t k = 0; k < order.size(); ++k) {
        const std::int32_t v = order[k];
        const bool hadTriangles = closed.numTriangles() > 0;
        const RemoveResult r = remover.remove(v, &record);
        left.erase(std::find(left.begin(), left.end(), v));
        require(hadTriangles ? r != RemoveResult::NotInMesh && r != RemoveResult::Virtual
                             : r == RemoveResult::NotInMesh,
                "a vertex of the mesh is removed, none other", what);
        checkRemoval(c, closed, left, left.size() <= 40 || k % 4 == 0 || k + 1 == order.size());
    }
    if (c.options.boundary == Boundary::Exact) checkConstraints(c, closed, left, state);
    remover.undo(record);
    require(snap(closed) == start, "undoing every removal restores the closed mesh bit for bit",
            what);
}

// The GUI's edits on the finished exact mesh: drawn removals and segments, each made after
// stepping to a drawn position (and now and then after taking the last edit out), each checked
// at its end (a valid table, every unconstrained edge locally Delaunay) and against a fresh
// editor given the same edits; then everything stepped back: the closed mesh bit for bit.
void checkEditor(const Case& c, const Mesh& finished) {
    const std::string what = describe(c) + ", editor";
    const auto n = static_cast<std::int32_t>(c.points.size());
    if (finished.numTriangles() == 0 || n < 3) return;
    Editor ed(finished);
    const Snapshot start = snap(ed.mesh());
    std::uint64_t state = c.options.seed * 2862933555777941757ULL + c.probe + 3037000493ULL;
    auto draw = [&](std::uint64_t bound) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return (state >> 33) % bound;
    };
    ValidateOptions vo;
    vo.firstVirtual = n;
    vo.delaunay = false;
    for (int k = 0; k < 10; ++k) {
        ed.seek(draw(ed.total() + 1));
        if (draw(5) == 0) ed.takeLast();
        const auto a = static_cast<std::int32_t>(draw(n)), b = static_cast<std::int32_t>(draw(n));
        const std::uint64_t which = draw(4);
        Edit edit = makeEdit(which < 2 ? EditKind::RemoveVertex : EditKind::Constrain, a, b);
        if (which == 3) {  // a move: halfway to another point, or beyond it (out of the hull)
            const Vec2 p = ed.mesh().G[a], q = ed.mesh().G[b];
            const double t = draw(2) ? 0.5 : 2.0;
            edit = makeMove(a, {p.x + (q.x - p.x) * t, p.y + (q.y - p.y) * t});
        }
        std::string message;
        ed.add(edit, message);
        ed.seek(ed.total());
        const Mesh& m = ed.mesh();
        const auto bad = validate(m, vo);
        if (!bad.empty()) fail("an edit leaves a valid corner table", what + ": " + bad[0].message);
        for (std::int32_t e = 0; e < m.numCorners(); ++e) {
            const std::int32_t o = m.O[e];
            if (o == kNone || ed.isConstrained(e)) continue;
            const std::int32_t P = m.V[e], A = m.V[next(e)], B = m.V[prev(e)], D = m.V[o];
            if (P >= n || D >= n) continue;  // a hull edge
            // Between finite triangles the in-circle test; between two ghost triangles, the hull
            // turns the right way at the edge's finite end.
            require(ghostInCircle(m.G, n, P, A, B, D) <= 0,
                    "after an edit every unconstrained edge is locally Delaunay, the hull convex",
                    what);
        }
    }
    Editor fresh(finished);
    for (const Edit& e : ed.edits()) {
        std::string message;
        require(fresh.add(e, message), "an edit kept is made again on a fresh editor", what);
        fresh.seek(fresh.total());
    }
    require(snap(fresh.mesh()) == snap(ed.mesh()), "a fresh editor makes the same mesh", what);
    ed.seek(0);
    require(snap(ed.mesh()) == start, "stepping back every edit restores the mesh bit for bit",
            what);
}

void runCase(const Case& c) {
    const std::string what = describe(c);
    const auto n = static_cast<std::int32_t>(c.points.size());
    std::unique_ptr<Inserter> owner;
    try {
        owner = std::make_unique<Inserter>(c.points, c.options);
    } catch (const std::domain_error&) {
        // Super mode refuses coordinates without a finite super-triangle (documented).
        require(c.options.boundary == Boundary::Super, "only super mode refuses finite input",
                what);
        return;
    }
    Inserter& ins = *owner;
    const Snapshot start = snap(ins.mesh());

    // Recorded, one op at a time. The bound is far above any correct run (O(n^2) flips and
    // walk steps at most): past it the engine is looping.
    Journal journal(ins);
    const std::size_t limit =
        64 * static_cast<std::size_t>(n + 4) * static_cast<std::size_t>(n + 4) + 1024;
    std::size_t ops = 0;
    while (journal.forward()) {
        require(++ops <= limit, "insertion terminates", what);
        // A JSON round trip costs more than the op itself: the first ops (Start and the first
        // insertions hold every op type) and then one op in eight.
        if (c.traceRoundTrip && (ops <= 64 || ops % 8 == 0)) traceRoundTrip(journal, ins.mesh());
    }
    require(ins.done(), "the journal stops only when the inserter is done", what);
    require(ins.flipStack().empty(), "the flip work-list is empty at the end", what);
    checkResult(c, ins);
    const Snapshot end = snap(ins.mesh());
    const InsertStats endStats = ins.stats();

    // The batch path runs the same primitives without recording: the same result, bit for bit.
    Inserter batch(c.points, c.options);
    batch.run();
    require(batch.done(), "run() finishes", what);
    require(snap(batch.mesh()) == end, "run() gives the same G, V and O as stepping", what);
    require(sameStats(batch.stats(), endStats), "run() counts the same operations as stepping",
            what);
    require(batch.skipped() == ins.skipped(), "run() skips the same duplicates as stepping", what);
    checkHalves(c, batch);

    // A mid-run state is a valid corner table (virtual triangles included).
    journal.seek(c.probe * ops / 255);
    ValidateOptions vo;
    vo.firstVirtual = n;
    vo.delaunay = false;
    const auto mid = validate(ins.mesh(), vo);
    if (!mid.empty())
        fail("every intermediate state is a valid corner table", what + ": " + mid[0].message);

    // Undo everything: the start state, bit for bit; then redo to the same end.
    journal.seek(0);
    require(journal.position() == 0, "the journal rewinds to the start", what);
    require(snap(ins.mesh()) == start, "undoing every op restores the start state bit for bit",
            what);
    require(ins.flipStack().empty() && ins.skipped().empty(),
            "undo clears the work-list and the skips", what);
    require(sameStats(ins.stats(), InsertStats{}), "undo resets the statistics", what);
    journal.seek(ops);
    require(journal.position() == ops && ins.done(), "the journal replays to the end", what);
    require(snap(ins.mesh()) == end, "replaying every op gives the same end state", what);
    require(sameStats(ins.stats(), endStats), "replaying restores the statistics", what);
    if (c.options.boundary == Boundary::Exact) checkEditor(c, ins.mesh());

    // The state before Finalize is the closed mesh (ghosts or super-triangle) removals work on.
    journal.seek(ops - 1);
    require(ins.control().phase == Phase::Finalize, "the last op is Finalize", what);
    checkRemovals(c, ins.mesh());
}

// DLAB_FUZZ_PRINT=1: print the decoded case (hex floats, exact) before running it, to turn a
// crash into a unit test.
void printCase(const Case& c) {
    std::fprintf(stderr, "%s, seed %llu, ID buffer %dx%d, trace %d, probe %d\n",
                 describe(c).c_str(), static_cast<unsigned long long>(c.options.seed),
                 c.options.locatorOptions.idBufferWidth, c.options.locatorOptions.idBufferHeight,
                 c.traceRoundTrip ? 1 : 0, c.probe);
    for (const Vec2& p : c.points) std::fprintf(stderr, "  {%a, %a},\n", p.x, p.y);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    Bytes in(data, size);
    const Case c = Decoder(in).decode();
    static const bool print = std::getenv("DLAB_FUZZ_PRINT") != nullptr;
    if (print) printCase(c);
    runCase(c);
    return 0;
}
