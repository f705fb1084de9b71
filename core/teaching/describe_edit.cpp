// The ops of edits in words, read from their records.
#include "core/teaching/describe_edit.h"

#include "core/engine/numbers.h"

#include <string>

namespace dlab {

FlipEdges flipEdges(const std::vector<CellChange>& changes, std::uint32_t first, std::uint32_t n) {
    FlipEdges f;
    int k = 0;
    for (std::uint32_t i = 0; i < n && k < 2; ++i) {
        const CellChange& ch = changes[first + i];
        if (ch.isO()) continue;
        (k == 0 ? f.oldA : f.oldB) = ch.before;
        (k == 0 ? f.newB : f.newA) = ch.after;
        ++k;
    }
    return f;
}

Ear earOf(const Mesh& m, const RemoveOp& op) {
    Ear ear;
    if (op.a < 0 || op.a >= m.numCorners()) return ear;
    ear.a = m.V[next(op.a)];
    ear.b = op.b;
    const std::int32_t o = m.O[next(op.a)];
    ear.c = o == kNone ? kNone : m.V[o];
    return ear;
}

bool ghostHullEdge(const Mesh& m, std::int32_t ghost, std::int32_t t, std::int32_t& x,
                   std::int32_t& y) {
    if (t < 0 || t >= m.numTriangles()) return false;
    for (std::int32_t g = 3 * t; g < 3 * t + 3; ++g) {
        if (m.V[g] < ghost) continue;
        x = m.V[prev(g)];
        y = m.V[next(g)];
        return true;
    }
    return false;
}

namespace {

// The ops that put a moved vertex in at its new place, in words.
std::string placeText(const Editor& ed, const Edit& edit, const ConstrainOp& op) {
    const std::string v = std::to_string(op.a);
    switch (op.type) {
        case ConstrainOpType::MoveVertex: {
            std::string at = "(";
            appendShortest(at, edit.to.x);
            at += ", ";
            appendShortest(at, edit.to.y);
            at += ")";
            if (op.sign > 0)
                return v + " stays inside its star's kernel: every triangle at " + v +
                       " still turns counter-clockwise, so flips alone follow";
            return v +
                   " is out of the mesh (its new place is beyond its star's kernel): it "
                   "takes its new place " +
                   at;
        }
        case ConstrainOpType::Locate: {
            std::int32_t x = kNone, y = kNone;
            if (ghostHullEdge(ed.mesh(), ed.ghost(), op.b, x, y))
                return v + " lies beyond the hull edge " + std::to_string(x) + "-" +
                       std::to_string(y) + " (ghost triangle " + std::to_string(op.b) +
                       "): the hull grows to take it in";
            return v +
                   (op.count == kNone ? " lies inside triangle "
                                      : " lies on an edge of triangle ") +
                   std::to_string(op.b);
        }
        case ConstrainOpType::Split:
            return "triangle " + std::to_string(op.b) + " split in three around " + v +
                   "; its edges wait for their in-circle tests";
        case ConstrainOpType::SplitEdge:
            return "the edge " + v + " lies on split in two (a constraint on it holds both halves)";
        case ConstrainOpType::Fan:
            return "the other points are collinear: " + v + ", off their line, makes a fan of " +
                   "triangles with them (" + std::to_string(op.count) +
                   " with the ghost triangles)";
        default: return toString(op.type);
    }
}

}  // namespace

namespace {

// Vertices as the captions name them: the ghost vertex "g" (as the canvas labels it), the
// super-triangle's "s0" to "s2".
struct Names {
    const Editor& ed;
    bool isGhost(std::int32_t v) const { return v >= ed.ghost(); }
    std::string id(std::int32_t v) const {
        return isGhost(v)               ? std::string("g")
               : v >= ed.firstVirtual() ? "s" + std::to_string(v - ed.firstVirtual())
                                        : std::to_string(v);
    }
    std::string edge(std::int32_t a, std::int32_t b) const { return id(a) + "-" + id(b); }
};

std::string removalText(const Names& n, const Edit& edit, const RemoveOp& op) {
    std::string out;
    const std::string v = std::to_string(op.vertex);
    switch (op.type) {
        case RemoveOpType::EarTest: {
            const Ear ear = earOf(n.ed.mesh(), op);
            out += "ear test at " + n.id(ear.b) + ": triangle " + n.edge(ear.a, ear.b) + "-" +
                   n.id(ear.c) +
                   (op.sign > 0 ? " has no other neighbour of " + v +
                                      " inside its circle: an ear, cut it next"
                    : op.sign == 0 ? " is flat: cut only when no other ear is left"
                                   : " is no ear: a neighbour of " + v +
                                         " is inside its circle, or it turns the wrong way");
            break;
        }
        case RemoveOpType::Flip: {
            const FlipEdges f = flipEdges(edit.removal.changes, op.firstChange, op.numChanges);
            out += "flip " + n.edge(f.oldA, f.oldB) + " to " + n.edge(f.newA, f.newB) +
                   ": the ear is a triangle of the result, " + v + " has one neighbour less";
            break;
        }
        case RemoveOpType::Merge:
            out += v + " has three neighbours left: its triangles merge into triangle " +
                   std::to_string(op.a);
            break;
        case RemoveOpType::Collapse: out += "the points left make no triangle"; break;
    }
    return out;
}

std::string constraintText(const Names& n, const Edit& edit, const ConstrainOp& op) {
    const Mesh& m = n.ed.mesh();
    std::string out;
    switch (op.type) {
        case ConstrainOpType::Walk:
            out += "walk from " + std::to_string(op.a) + " to " + std::to_string(op.b) + ": " +
                   std::to_string(op.count) + (op.count == 1 ? " edge crosses" : " edges cross") +
                   " the segment" + (op.b != op.segmentB ? " (a vertex lies on it)" : "");
            break;
        case ConstrainOpType::SloanFlip: {
            const FlipEdges f = flipEdges(edit.constraint.changes, op.firstChange, op.numChanges);
            out +=
                "flip the crossing edge " + n.edge(f.oldA, f.oldB) + " to " +
                n.edge(f.newA, f.newB) +
                (op.sign > 0 ? ": it still crosses, back in the queue" : ": it no longer crosses");
            break;
        }
        case ConstrainOpType::SloanWait:
            out += "the crossing edge " + n.edge(m.V[next(op.a)], m.V[prev(op.a)]) +
                   " has a quadrilateral that is not convex: it waits";
            break;
        case ConstrainOpType::Mark: out += n.edge(op.a, op.b) + " is now a constrained edge"; break;
        case ConstrainOpType::Unmark:
            out += n.edge(op.a, op.b) + " is held by one constraint less";
            break;
        case ConstrainOpType::Reflag:
            out += "the constrained edges are flagged again on their corners";
            break;
        case ConstrainOpType::InCircleTest: {
            const std::int32_t A = m.V[next(op.a)], B = m.V[prev(op.a)];
            if (n.isGhost(A) || n.isGhost(B)) {               // between two ghost triangles
                const std::int32_t x = n.isGhost(A) ? B : A;  // on the hull, or leaving it
                out += "is " + n.id(m.V[op.b]) + " beyond the hull edge " + n.edge(m.V[op.a], x) +
                       "? " +
                       (op.sign > 0 ? "yes: flip, " + n.id(x) + " leaves the hull"
                                    : "no: keep, " + n.id(x) + " stays on the hull");
                break;
            }
            out += "is " + n.id(m.V[op.b]) + " inside the circle across " + n.edge(A, B) + "? " +
                   (op.sign > 0 ? "yes: flip" : "no: keep");
            break;
        }
        case ConstrainOpType::Flip: {
            const FlipEdges f = flipEdges(edit.constraint.changes, op.firstChange, op.numChanges);
            out += "flip " + n.edge(f.oldA, f.oldB) + " to " + n.edge(f.newA, f.newB);
            break;
        }
        default: out += placeText(n.ed, edit, op); break;
    }
    return out;
}

}  // namespace

std::string describeEditStep(const Editor& ed) {
    const EditStep s = ed.current();
    if (!s.edit) return "";
    const Names names{ed};
    return describe(*s.edit) + ", " +
           (s.removal ? removalText(names, *s.edit, *s.removal)
                      : constraintText(names, *s.edit, *s.constraint));
}

}  // namespace dlab
