// Captions of operations, written for students: vertex and corner numbers as in the tables.
#include "core/teaching/describe.h"

#include <string>

namespace dlab {

std::string vertexName(const Inserter& ins, std::int32_t v) {
    if (v == kNone) return "-";
    if (ins.isVirtual(v) && !ins.done()) {
        return ins.options().boundary == Boundary::Exact ? "ghost"
                                                         : "s" + std::to_string(v - ins.numInput());
    }
    return std::to_string(v);
}

namespace {

std::string vname(const Inserter& ins, std::int32_t v) { return vertexName(ins, v); }

std::string triName(const Inserter& ins, std::int32_t t) {
    const auto& V = ins.mesh().V;
    if (t < 0 || 3 * t + 2 >= static_cast<std::int32_t>(V.size()))
        return "triangle " + std::to_string(t);
    return "triangle " + std::to_string(t) + " (" + vname(ins, V[3 * t]) + ", " +
           vname(ins, V[3 * t + 1]) + ", " + vname(ins, V[3 * t + 2]) + ")";
}

// Exact mode while the run is on: the ghost vertex is no point, so an edge to it is named by
// its real end ("the ghost edge at 3"), and a ghost triangle by its hull edge.
bool ghostMode(const Inserter& ins) {
    return ins.options().boundary == Boundary::Exact && !ins.done();
}

std::string edgeName(const Inserter& ins, std::int32_t a, std::int32_t b) {
    if (ghostMode(ins) && ins.isVirtual(a) != ins.isVirtual(b))
        return "the ghost edge at " + vname(ins, ins.isVirtual(a) ? b : a);
    return "edge " + vname(ins, a) + "-" + vname(ins, b);
}

bool isGhostTriangle(const Inserter& ins, std::int32_t t) {
    return ghostMode(ins) && t >= 0 && t < ins.mesh().numTriangles() && ins.isVirtualTriangle(t);
}

// "hull edge 4-3" of ghost triangle t: its two real vertices, in the triangle's order.
std::string hullEdgeOf(const Inserter& ins, std::int32_t t) {
    const auto& V = ins.mesh().V;
    for (int k = 0; k < 3; ++k) {
        if (ins.isVirtual(V[3 * t + k]))
            return "hull edge " + vname(ins, V[3 * t + (k + 1) % 3]) + "-" +
                   vname(ins, V[3 * t + (k + 2) % 3]);
    }
    return "the hull";
}

// The question of an in-circle test against triangle t: a ghost triangle's "circle" is the
// open half-plane beyond its hull edge.
std::string inCircleQuestion(const Inserter& ins, const std::string& p, std::int32_t t) {
    if (isGhostTriangle(ins, t))
        return "is " + p + " beyond " + hullEdgeOf(ins, t) + " (ghost triangle " +
               std::to_string(t) + ")? ";
    return "is " + p + " inside the circle of triangle " + std::to_string(t) + "? ";
}

}  // namespace

std::string describe(const Op& op, const Inserter& ins) {
    const auto& V = ins.mesh().V;
    const std::string p = "vertex " + vname(ins, op.vertex);
    switch (op.type) {
        case OpType::Start:
            // The caption's prefix already says "Start": the text goes on from there.
            // (A caption describes the op just done: the stack is the one Start left.)
            if (ins.repairs() && ins.flipStack().empty())
                return "the given triangles in the corner table, no edge on the flip stack";
            if (ins.repairs())
                return "the given triangles in the corner table, every interior edge on the "
                       "flip stack (Lawson's flip algorithm)";
            if (op.a == kNone) return "fewer than three points not on one line, so no triangle";
            return ins.options().boundary == Boundary::Super
                       ? triName(ins, 0) + ", the super-triangle, holds every point"
                       : triName(ins, 0) +
                             ", the first triangle, and three ghost triangles around its hull";
        case OpType::LocateStep:
            return "locate " + p + ": leave triangle " + std::to_string(op.a) + " for " +
                   triName(ins, op.b);
        case OpType::Located: {
            const std::string where =
                op.where == Where::OnEdge ? "on the edge opposite corner " + std::to_string(op.b)
                : op.where == Where::OnVertex ? "on vertex " + vname(ins, V[op.b])
                : op.where == Where::Outside
                    ? "outside the hull, beyond ghost " + triName(ins, op.a)
                    : "inside " + triName(ins, op.a);
            return p + " found " + where;
        }
        case OpType::Split:
            return "split triangle " + std::to_string(op.a) + " into three around " + p +
                   " (corners " + std::to_string(3 * op.a) + ".." + std::to_string(3 * op.a + 2) +
                   " reused, triangles " + std::to_string(op.trianglesBefore) + " and " +
                   std::to_string(op.trianglesBefore + 1) + " appended)";
        case OpType::SplitEdge: {
            const std::string edge =
                "the edge opposite corner " + std::to_string(op.a) + " at " + p;
            if (op.b == kNone)
                return "split the boundary " + edge.substr(4) + " (1 -> 2 triangles)";
            // A hull edge in exact mode: one real triangle and its ghost become two of each.
            if (isGhostTriangle(ins, tri(op.a)) || isGhostTriangle(ins, tri(op.b)))
                return "split the hull " + edge.substr(4) +
                       " (1 triangle -> 2, its ghost triangle -> 2 ghost triangles)";
            return "split " + edge + " (2 -> 4 triangles)";
        }
        case OpType::InCircleTest: {
            const std::int32_t a = V[next(op.a)], b = V[prev(op.a)];
            const std::string edge = edgeName(ins, a, b);
            if (op.b == kNone) return edge + " is on the boundary: nothing to test";
            // The flip algorithm inserts no point: the vertex tested is the one at corner a.
            const std::string tested = op.vertex == kNone ? "vertex " + vname(ins, V[op.a]) : p;
            const std::string q = inCircleQuestion(ins, tested, tri(op.b));
            if (op.sign > 0) return q + "yes: " + edge + " must flip";
            if (op.sign == 0) return q + "on it (cocircular): " + edge + " stays";
            return q + "no: " + edge + " is Delaunay";
        }
        case OpType::Flip:
            return "flip " + edgeName(ins, V[next(op.a)], V[next(op.b)]) + " to " +
                   edgeName(ins, V[op.a], V[op.b]);
        case OpType::SkipDuplicate:
            return p + " duplicates vertex " + vname(ins, op.b) + ": skipped (vertex " +
                   std::to_string(std::min(op.vertex, op.b)) + ", the first occurrence, is kept)";
        case OpType::Inserted: return p + " inserted; every edge around it is Delaunay";
        case OpType::Finalize:
            if (ins.repairs() && ins.stats().inCircleTests == 0)
                return "the given triangles, as they are: no edge was tested";
            if (ins.repairs())
                return "the flip stack is empty: every edge is locally Delaunay, so the "
                       "triangulation is Delaunay";
            return std::to_string(op.a) +
                   (ins.options().boundary == Boundary::Super
                        ? " triangles touching the super-triangle"
                        : " ghost triangles") +
                   " removed, V and O compacted to " + std::to_string(op.trianglesAfter) +
                   " triangles";
    }
    return "?";
}

}  // namespace dlab
