// Breakpoints: parsing, the hit predicate on journal positions, budgeted runs both ways.
#include "core/teaching/breakpoint.h"

#include "core/engine/text_util.h"

#include <algorithm>
#include <cctype>
#include <charconv>

namespace dlab {

namespace {

constexpr BreakKindInfo kKinds[] = {
    {BreakKind::Op, "op", BreakParam::Required, "the journal is at operation N"},
    {BreakKind::Step, "step", BreakParam::None, "every operation"},
    {BreakKind::Walk, "walk", BreakParam::None, "a walk step of a locate"},
    {BreakKind::Located, "located", BreakParam::None, "a locate ended"},
    {BreakKind::Split, "split", BreakParam::None, "a triangle split 1->3"},
    {BreakKind::SplitEdge, "split-edge", BreakParam::None, "an edge split 2->4 (1->2 on the hull)"},
    {BreakKind::InCircle, "incircle", BreakParam::Optional,
     "an in-circle test (with result S: 1, 0, -1)"},
    {BreakKind::Flip, "flip", BreakParam::None, "an edge flipped"},
    {BreakKind::Duplicate, "duplicate", BreakParam::None, "a duplicate point skipped"},
    {BreakKind::Degenerate, "degenerate", BreakParam::None,
     "a point on an edge or on a vertex, or four cocircular points"},
    {BreakKind::Insert, "insert", BreakParam::Required, "vertex K is about to be inserted"},
    {BreakKind::Inserted, "inserted", BreakParam::Optional, "a vertex (K) is in, or was skipped"},
    {BreakKind::Insertion, "insertion", BreakParam::None, "an insertion ended"},
    {BreakKind::Corner, "corner", BreakParam::Required, "corner C changed (V[C] or O[C])"},
    {BreakKind::Finalize, "finalize", BreakParam::None, "the virtual triangles were removed"},
    {BreakKind::End, "end", BreakParam::None, "the run is finished"},
    {BreakKind::Edit, "edit", BreakParam::Optional,
     "the end of an edit (N; edit:0 the run's end, before the edits)"},
    {BreakKind::EarTest, "ear-test", BreakParam::Optional,
     "a removal tested an ear (with result S: 1 an ear, -1 none)"},
    {BreakKind::EarFlip, "ear-flip", BreakParam::None, "a removal flipped an ear off its vertex"},
    {BreakKind::Merge, "merge", BreakParam::None,
     "the removed vertex's last three triangles merged"},
    {BreakKind::SegmentWalk, "segment-walk", BreakParam::None,
     "the walk along a segment found the edges it crosses"},
    {BreakKind::SloanFlip, "sloan-flip", BreakParam::None, "an edge crossing a segment flipped"},
    {BreakKind::SloanWait, "sloan-wait", BreakParam::None,
     "an edge crossing a segment waits (its quadrilateral is not convex)"},
    {BreakKind::ConstrainMark, "constrain-mark", BreakParam::None,
     "a segment is an edge now, marked constrained"},
    {BreakKind::EditInCircle, "edit-incircle", BreakParam::Optional,
     "an in-circle test of an edit's repair (with result S: 1, 0, -1)"},
    {BreakKind::RepairFlip, "repair-flip", BreakParam::None, "an edit's repair flipped an edge"},
};

// Vertex whose insertion starts right after position p, which ends an insertion. kNone when
// none does (the run is past its last point).
std::int32_t nextVertexAfter(const Journal& journal, const Inserter& ins, std::size_t p) {
    if (p < journal.recorded()) {
        const Op& next = journal.ops()[p];
        return next.type == OpType::LocateStep || next.type == OpType::Located ? next.vertex
                                                                               : kNone;
    }
    if (journal.position() == p) return ins.currentVertex();
    // The journal sits elsewhere and the next op is not recorded: derive it from the order.
    const Op& last = journal.ops()[p - 1];
    const auto& order = ins.order();
    std::size_t rank = 0;
    if (last.type == OpType::Start) {
        rank = ins.options().boundary == Boundary::Exact ? 3 : 0;
    } else if (last.type == OpType::Inserted || last.type == OpType::SkipDuplicate) {
        rank = static_cast<std::size_t>(std::find(order.begin(), order.end(), last.vertex) -
                                        order.begin()) +
               1;
    } else {
        return kNone;
    }
    return rank < order.size() ? order[rank] : kNone;
}

bool startInserts(const Journal& journal, const Inserter& ins, const Op& start, std::int64_t v) {
    if (v < 0 || v >= ins.numInput()) return false;
    const auto& changes = journal.changes();
    for (std::uint32_t i = 0; i < start.numChanges; ++i) {
        const CellChange& ch = changes[start.firstChange + i];
        if (!ch.isO() && ch.after == v) return true;
    }
    return false;
}

}  // namespace

bool endsInsertion(OpType t) {
    return t == OpType::Start || t == OpType::Inserted || t == OpType::SkipDuplicate ||
           t == OpType::Finalize;
}

std::span<const BreakKindInfo> breakKinds() { return kKinds; }

const BreakKindInfo& info(BreakKind kind) { return kKinds[static_cast<int>(kind)]; }

std::optional<Breakpoint> parseBreakpoint(std::string_view text, std::string* error) {
    auto bad = [&](const std::string& why) -> std::optional<Breakpoint> {
        if (error) *error = why;
        return std::nullopt;
    };
    const std::string whole = trimmed(text);
    const std::size_t colon = whole.find(':');
    const std::string name = lowered(trimmed(std::string_view(whole).substr(0, colon)));
    const BreakKindInfo* kind = nullptr;
    for (const BreakKindInfo& k : kKinds) {
        if (name == k.name) kind = &k;
    }
    if (!kind) {
        std::string names;
        for (const BreakKindInfo& k : kKinds)
            names += std::string(names.empty() ? "" : ", ") + k.name;
        return bad("unknown breakpoint \"" + name + "\" (known: " + names + ")");
    }
    Breakpoint bp{kind->kind, std::nullopt};
    if (colon == std::string::npos) {
        if (kind->param == BreakParam::Required) {
            return bad(std::string("breakpoint \"") + kind->name + "\" needs a number, e.g. \"" +
                       kind->name + ":5\"");
        }
        return bp;
    }
    if (kind->param == BreakParam::None)
        return bad(std::string("breakpoint \"") + kind->name + "\" takes no number");
    std::string num = trimmed(std::string_view(whole).substr(colon + 1));
    if (!num.empty() && num[0] == '+') num.erase(0, 1);
    std::int64_t value = 0;
    const auto [end, ec] = std::from_chars(num.data(), num.data() + num.size(), value);
    if (num.empty() || ec != std::errc() || end != num.data() + num.size()) {
        return bad("\"" + trimmed(std::string_view(whole).substr(colon + 1)) +
                   "\" is not a whole number");
    }
    if (bp.kind == BreakKind::InCircle || bp.kind == BreakKind::EarTest ||
        bp.kind == BreakKind::EditInCircle) {
        if (value < -1 || value > 1) return bad("an in-circle result is 1, 0 or -1");
    } else if (value < 0) {
        return bad(std::string("the number of \"") + kind->name + "\" cannot be negative");
    }
    bp.param = value;
    return bp;
}

std::string toString(const Breakpoint& bp) {
    std::string s = info(bp.kind).name;
    if (bp.param) s += ":" + std::to_string(*bp.param);
    return s;
}

std::string explain(const Breakpoint& bp) {
    const std::string k = bp.param ? std::to_string(*bp.param) : std::string();
    switch (bp.kind) {
        case BreakKind::Op: return "after operation " + k;
        case BreakKind::InCircle:
            if (!bp.param) return "an in-circle test";
            return *bp.param > 0    ? "an in-circle test that says flip"
                   : *bp.param == 0 ? "an in-circle test on four cocircular points"
                                    : "an in-circle test that finds the edge Delaunay";
        case BreakKind::Insert: return "vertex " + k + " is about to be inserted";
        case BreakKind::Inserted: return bp.param ? "vertex " + k + " is in" : "a vertex is in";
        case BreakKind::Corner: return "corner " + k + " changes";
        case BreakKind::Edit:
            if (!bp.param) return "an edit ended";
            return *bp.param == 0 ? "the run's end, before the edits" : "edit " + k + " ended";
        case BreakKind::EarTest:
            if (!bp.param) return "an ear test";
            return *bp.param > 0 ? "an ear test that finds an ear" : "an ear test without an ear";
        default: return info(bp.kind).meaning;
    }
}

bool isEditBreak(BreakKind kind) { return kind >= BreakKind::Edit; }

namespace {

bool editEndHits(const Breakpoint& bp, const Editor& ed) {
    const std::size_t p = ed.position();
    if (bp.param) {
        const auto n = static_cast<std::size_t>(*bp.param);
        if (n == 0) return p == 0;
        return n <= ed.edits().size() && p == ed.editEnd(n - 1);
    }
    for (std::size_t k = 0; k < ed.edits().size(); ++k) {
        if (p == ed.editEnd(k)) return true;
    }
    return false;
}

bool signMatches(const Breakpoint& bp, int sign) { return !bp.param || sign == *bp.param; }

}  // namespace

bool hitsEditAt(const Breakpoint& bp, const Editor& ed) {
    if (bp.kind == BreakKind::Edit) return editEndHits(bp, ed);
    const EditStep s = ed.current();
    if (s.removal) {
        const RemoveOp& op = *s.removal;
        switch (bp.kind) {
            case BreakKind::EarTest:
                return op.type == RemoveOpType::EarTest && signMatches(bp, op.sign);
            case BreakKind::EarFlip: return op.type == RemoveOpType::Flip;
            case BreakKind::Merge: return op.type == RemoveOpType::Merge;
            default: return false;
        }
    }
    if (!s.constraint) return false;
    const ConstrainOp& op = *s.constraint;
    switch (bp.kind) {
        case BreakKind::SegmentWalk: return op.type == ConstrainOpType::Walk;
        case BreakKind::SloanFlip: return op.type == ConstrainOpType::SloanFlip;
        case BreakKind::SloanWait: return op.type == ConstrainOpType::SloanWait;
        case BreakKind::ConstrainMark: return op.type == ConstrainOpType::Mark;
        case BreakKind::EditInCircle:
            return op.type == ConstrainOpType::InCircleTest && signMatches(bp, op.sign);
        case BreakKind::RepairFlip: return op.type == ConstrainOpType::Flip;
        default: return false;
    }
}

bool hitsAt(const Breakpoint& bp, const Journal& journal, const Inserter& ins, std::size_t p) {
    if (isEditBreak(bp.kind)) return false;  // hitsEditAt
    if (bp.kind == BreakKind::Op) return bp.param && static_cast<std::int64_t>(p) == *bp.param;
    if (p == 0 || p > journal.recorded()) return false;
    const Op& op = journal.ops()[p - 1];
    switch (bp.kind) {
        case BreakKind::Op: return false;  // handled above
        case BreakKind::Step: return true;
        case BreakKind::Walk: return op.type == OpType::LocateStep;
        case BreakKind::Located: return op.type == OpType::Located;
        case BreakKind::Split: return op.type == OpType::Split;
        case BreakKind::SplitEdge: return op.type == OpType::SplitEdge;
        case BreakKind::InCircle:
            return op.type == OpType::InCircleTest && (!bp.param || op.sign == *bp.param);
        case BreakKind::Flip: return op.type == OpType::Flip;
        case BreakKind::Duplicate: return op.type == OpType::SkipDuplicate;
        case BreakKind::Degenerate:
            return (op.type == OpType::Located &&
                    (op.where == Where::OnEdge || op.where == Where::OnVertex)) ||
                   (op.type == OpType::InCircleTest && op.sign == 0 && op.b != kNone);
        case BreakKind::Insert:
            return bp.param && op.type != OpType::Finalize && endsInsertion(op.type) &&
                   nextVertexAfter(journal, ins, p) == *bp.param;
        case BreakKind::Inserted:
            if (op.type == OpType::Inserted || op.type == OpType::SkipDuplicate) {
                return !bp.param || op.vertex == *bp.param;
            }
            if (op.type == OpType::Start && op.a != kNone &&
                ins.options().boundary == Boundary::Exact) {
                return !bp.param || startInserts(journal, ins, op, *bp.param);
            }
            return false;
        case BreakKind::Insertion: return endsInsertion(op.type);
        case BreakKind::Corner: {
            if (!bp.param) return false;
            const auto& changes = journal.changes();
            for (std::uint32_t i = 0; i < op.numChanges; ++i) {
                const CellChange& ch = changes[op.firstChange + i];
                if (ch.corner() == *bp.param && ch.before != ch.after) return true;
            }
            return false;
        }
        case BreakKind::Finalize:
        case BreakKind::End: return op.type == OpType::Finalize;  // Finalize is always the last op
        default: return false;                                    // the edits' (hitsEditAt)
    }
    return false;
}

int firstHit(std::span<const Breakpoint> bps, const Journal& journal, const Inserter& ins) {
    for (std::size_t i = 0; i < bps.size(); ++i) {
        if (hits(bps[i], journal, ins)) return static_cast<int>(i);
    }
    return -1;
}

const char* toString(StopReason reason) {
    switch (reason) {
        case StopReason::Hit: return "hit";
        case StopReason::End: return "end";
        case StopReason::Start: return "start";
        case StopReason::Budget: return "budget";
    }
    return "?";
}

RunResult runUntil(Journal& journal, const Inserter& ins, std::span<const Breakpoint> bps,
                   std::size_t maxSteps) {
    RunResult r;
    while (true) {
        if (journal.atEnd()) {
            r.reason = StopReason::End;
            return r;
        }
        if (r.steps >= maxSteps) {
            r.reason = StopReason::Budget;
            return r;
        }
        if (!journal.forward()) {
            r.reason = StopReason::End;
            return r;
        }
        ++r.steps;
        r.hit = firstHit(bps, journal, ins);
        if (r.hit >= 0) {
            r.reason = StopReason::Hit;
            return r;
        }
    }
}

RunResult runBackUntil(Journal& journal, const Inserter& ins, std::span<const Breakpoint> bps,
                       std::size_t maxSteps) {
    RunResult r;
    while (true) {
        if (journal.position() == 0) {
            r.reason = StopReason::Start;
            return r;
        }
        if (r.steps >= maxSteps) {
            r.reason = StopReason::Budget;
            return r;
        }
        journal.back();
        ++r.steps;
        r.hit = firstHit(bps, journal, ins);
        if (r.hit >= 0) {
            r.reason = StopReason::Hit;
            return r;
        }
    }
}

RunResult forwardInsertion(Journal& journal, const Inserter& ins, std::size_t maxSteps) {
    const Breakpoint bp{BreakKind::Insertion, std::nullopt};
    return runUntil(journal, ins, std::span(&bp, 1), maxSteps);
}

RunResult backInsertion(Journal& journal, const Inserter& ins, std::size_t maxSteps) {
    const Breakpoint bp{BreakKind::Insertion, std::nullopt};
    return runBackUntil(journal, ins, std::span(&bp, 1), maxSteps);
}

}  // namespace dlab
