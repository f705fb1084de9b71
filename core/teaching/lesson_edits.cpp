// Answers at the stops inside a lesson's edits: the edit quantities, read from the Editor's
// records (ear tests, flips, the segment's crossings, the repair), and corner expressions on the
// edited mesh.
#include "core/engine/predicates.h"
#include "core/engine/text_util.h"
#include "core/teaching/corner_expr.h"
#include "core/teaching/lesson.h"

#include <algorithm>
#include <functional>

namespace dlab {

namespace {

struct NotHere {
    std::string why;
};

Answer integerAnswer(std::int64_t v) {
    Answer a;
    a.kind = Answer::Kind::Integer;
    a.a = v;
    return a;
}
Answer truthAnswer(bool t) {
    Answer a;
    a.kind = Answer::Kind::Truth;
    a.truth = t;
    return a;
}

// The quantities about the edit in progress: the one whose op was just done (at an edit's end,
// that edit), or at the run's end (position 0) the first edit.
class EditQuantities {
public:
    explicit EditQuantities(Editor& editor) : m_ed(editor) {
        if (m_ed.edits().empty()) throw NotHere{"the lesson has no edits"};
        const EditStep s = m_ed.current();
        m_k = s.edit ? s.index : 0;
    }

    Answer get(std::string_view name) {
        if (name == "removal_degree") return integerAnswer(degreeAt(m_ed.editStart(m_k)));
        if (name == "degree_left") return integerAnswer(degreeAt(m_ed.position()));
        if (name == "ear_tests") return integerAnswer(countRemove(RemoveOpType::EarTest));
        if (name == "ear_flips") return integerAnswer(countRemove(RemoveOpType::Flip));
        if (name == "ear_tip" || name == "is_ear") return latestEar(name == "is_ear");
        if (name == "next_ear_tip" || name == "next_is_ear") return nextEar(name == "next_is_ear");
        if (name == "crossed_edges") return integerAnswer(crossedEdges());
        if (name == "sloan_flips") return integerAnswer(countConstrain(ConstrainOpType::SloanFlip));
        if (name == "sloan_waits") return integerAnswer(countConstrain(ConstrainOpType::SloanWait));
        if (name == "next_sloan_flips") return nextSloan(false);
        if (name == "next_crossing_edge") return nextSloan(true);
        if (name == "delaunay_violations") return integerAnswer(violations());
        if (name == "repair_tests")
            return integerAnswer(countConstrain(ConstrainOpType::InCircleTest));
        if (name == "repair_flips") return integerAnswer(countConstrain(ConstrainOpType::Flip));
        if (name == "edit_ops") return integerAnswer(static_cast<std::int64_t>(edit().numOps()));
        if (name == "triangles") return integerAnswer(realTriangles());
        throw NotHere{
            "not available inside the edits (there: the edit quantities, triangles and "
            "corner expressions)"};
    }

private:
    const Edit& edit() const { return m_ed.edits()[m_k]; }

    // Runs f with the editor at position p, then puts it back.
    template <typename F>
    auto at(std::size_t p, F f) {
        const std::size_t back = m_ed.position();
        m_ed.seek(p);
        auto r = f();
        m_ed.seek(back);
        return r;
    }

    std::int64_t degreeAt(std::size_t p) {
        if (edit().kind != EditKind::RemoveVertex) throw NotHere{"this edit removes no vertex"};
        return at(p, [&] {
            const auto& V = m_ed.mesh().V;
            return static_cast<std::int64_t>(std::count(V.begin(), V.end(), edit().a));
        });
    }

    std::int64_t countRemove(RemoveOpType t) const {
        if (edit().kind != EditKind::RemoveVertex) throw NotHere{"this edit removes no vertex"};
        const auto& ops = edit().removal.ops;
        return std::count_if(ops.begin(), ops.end(),
                             [&](const RemoveOp& o) { return o.type == t; });
    }

    std::int64_t countConstrain(ConstrainOpType t) const {
        const auto& ops = edit().constraint.ops;
        return std::count_if(ops.begin(), ops.end(),
                             [&](const ConstrainOp& o) { return o.type == t; });
    }

    std::int64_t crossedEdges() const {
        if (edit().kind != EditKind::Constrain) throw NotHere{"this edit constrains no segment"};
        std::int64_t n = 0;
        for (const ConstrainOp& o : edit().constraint.ops)
            if (o.type == ConstrainOpType::Walk) n += o.count;
        return n;
    }

    std::int64_t realTriangles() const {
        const Mesh& m = m_ed.mesh();
        std::int64_t n = 0;
        for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
            bool real = true;
            for (int i = 0; i < 3; ++i) real = real && m.V[3 * t + i] < m_ed.firstVirtual();
            n += real ? 1 : 0;
        }
        return n;
    }

    static Answer earAnswer(const RemoveOp& op, bool passes) {
        return passes ? truthAnswer(op.sign > 0) : integerAnswer(op.b);
    }

    Answer latestEar(bool passes) const {
        const EditStep s = m_ed.current();
        if (!s.removal || s.removal->type != RemoveOpType::EarTest)
            throw NotHere{"the last operation is no ear test"};
        return earAnswer(*s.removal, passes);
    }

    // The op after the position, in the same edit.
    EditStep nextStep() {
        if (m_ed.position() >= m_ed.total()) throw NotHere{"no operation is left"};
        return at(m_ed.position() + 1, [&] { return m_ed.current(); });
    }

    Answer nextEar(bool passes) {
        const EditStep s = nextStep();
        if (!s.removal || s.removal->type != RemoveOpType::EarTest)
            throw NotHere{"the next operation is no ear test"};
        return earAnswer(*s.removal, passes);
    }

    // The next Sloan op: whether it flips, or the edge it looks at (as it is now).
    Answer nextSloan(bool edge) {
        const EditStep s = nextStep();
        if (!s.constraint || (s.constraint->type != ConstrainOpType::SloanFlip &&
                              s.constraint->type != ConstrainOpType::SloanWait))
            throw NotHere{"the next operation is no flip or wait of a crossing edge"};
        if (!edge) return truthAnswer(s.constraint->type == ConstrainOpType::SloanFlip);
        const auto& V = m_ed.mesh().V;
        const std::int32_t c = s.constraint->a;
        Answer a;
        a.kind = Answer::Kind::Edge;
        a.a = std::min(V[next(c)], V[prev(c)]);
        a.b = std::max(V[next(c)], V[prev(c)]);
        return a;
    }

    // Edges between two real triangles whose opposite vertex is strictly inside the circle
    // (constrained ones too: visibility does not enter).
    std::int64_t violations() const {
        const Mesh& m = m_ed.mesh();
        const auto real = [&](std::int32_t v) { return v < m_ed.firstVirtual(); };
        std::int64_t n = 0;
        for (std::int32_t c = 0; c < m.numCorners(); ++c) {
            const std::int32_t o = m.O[c];
            if (o == kNone || o < c) continue;
            const std::int32_t a = m.V[c], b = m.V[next(c)], d = m.V[prev(c)], e = m.V[o];
            if (!real(a) || !real(b) || !real(d) || !real(e)) continue;
            n += incircle(m.G[a], m.G[b], m.G[d], m.G[e]) > 0 ? 1 : 0;
        }
        return n;
    }

    Editor& m_ed;
    std::size_t m_k = 0;
};

}  // namespace

std::optional<Answer> computeEditAnswer(std::string_view specIn, Editor& editor,
                                        std::string* error) {
    const std::string spec = trimmed(specIn);
    const auto fail = [&](const std::string& why) -> std::optional<Answer> {
        if (error) *error = why;
        return std::nullopt;
    };
    ExprError perr;
    const auto expr = CornerExpr::parse(spec, &perr);
    if (!expr || std::all_of(spec.begin(), spec.end(), [](char c) {
            return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
        })) {
        try {
            return EditQuantities(editor).get(spec);
        } catch (const NotHere& n) {
            return fail(spec + " is not available here: " + n.why);
        }
    }
    const ExprResult r =
        expr->evaluate(editor.mesh(), {}, ExprContext{editor.firstVirtual(), true});
    if (!r.ok()) return fail(spec + ": " + r.error.message);
    const ExprValue& v = *r.value;
    if (v.kind == ValueKind::Truth) return truthAnswer(v.truth);
    if (v.kind == ValueKind::Point) {
        Answer a;
        a.kind = Answer::Kind::Point;
        a.point = v.point;
        return a;
    }
    Answer a = integerAnswer(v.i);
    a.corner = v.kind == ValueKind::Corner;
    a.triangle = v.kind == ValueKind::Triangle;
    return a;
}

}  // namespace dlab
