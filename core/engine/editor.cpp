// Edits of a finished triangulation as recorded operations: record, step, seek.
#include "core/engine/editor.h"

#include "core/engine/numbers.h"
#include "core/engine/text_util.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>

namespace dlab {

const char* toString(EditKind k) {
    switch (k) {
        case EditKind::RemoveVertex: return "remove vertex";
        case EditKind::Constrain: return "constrain";
        case EditKind::Unconstrain: return "unconstrain";
        case EditKind::MoveVertex: return "move vertex";
    }
    return "?";
}

std::string describe(const Edit& edit) {
    if (edit.kind == EditKind::RemoveVertex) return "remove vertex " + std::to_string(edit.a);
    if (edit.kind == EditKind::MoveVertex) {
        std::string s = "move vertex " + std::to_string(edit.a) + " to ";
        appendShortest(s, edit.to.x);
        s += ", ";
        appendShortest(s, edit.to.y);
        return s;
    }
    return std::string(toString(edit.kind)) + " " + std::to_string(edit.a) + "-" +
           std::to_string(edit.b);
}

namespace {

// A non-negative integer, the whole of `s`.
std::optional<std::int32_t> parseId(std::string_view s) {
    std::int32_t v = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc{} || end != s.data() + s.size() || v < 0) return std::nullopt;
    return v;
}

// A finite number, the whole of `s` (shortest decimals read back bit for bit).
std::optional<double> parseNumber(std::string_view s) {
    const std::string t = trimmed(s);
    double x = 0;
    const ParseResult r = parseDouble(t.data(), t.data() + t.size(), x);
    if (r.ec != std::errc{} || r.ptr != t.data() + t.size() || !std::isfinite(x))
        return std::nullopt;
    return x;
}

// "5 to 3.5, 7": the vertex and its new place.
std::optional<Edit> parseMove(std::string_view rest, Edit edit) {
    const std::size_t to = rest.find(" to ");
    const std::size_t comma = rest.find(',');
    if (to == std::string_view::npos || comma == std::string_view::npos || comma < to)
        return std::nullopt;
    const auto v = parseId(trimmed(rest.substr(0, to)));
    const auto x = parseNumber(rest.substr(to + 4, comma - to - 4));
    const auto y = parseNumber(rest.substr(comma + 1));
    if (!v || !x || !y) return std::nullopt;
    edit.a = *v;
    edit.to = {*x, *y};
    return edit;
}

Mesh closedForm(const Mesh& finished) {
    Mesh m = finished;
    addGhosts(m);
    return m;
}

}  // namespace

std::optional<Edit> parseEdit(std::string_view typed) {
    const std::string text = lowered(trimmed(typed));
    static constexpr std::pair<std::string_view, EditKind> kWords[] = {
        {"move vertex ", EditKind::MoveVertex},     {"move ", EditKind::MoveVertex},
        {"remove vertex ", EditKind::RemoveVertex}, {"remove ", EditKind::RemoveVertex},
        {"unconstrain ", EditKind::Unconstrain},    {"constrain ", EditKind::Constrain}};
    Edit edit;
    std::string rest;
    for (const auto& [word, kind] : kWords) {
        if (std::string_view(text).substr(0, word.size()) == word) {
            edit.kind = kind;
            rest = trimmed(std::string_view(text).substr(word.size()));
            break;
        }
    }
    if (rest.empty()) return std::nullopt;
    if (edit.kind == EditKind::MoveVertex) return parseMove(rest, edit);
    if (edit.kind == EditKind::RemoveVertex) {
        const auto v = parseId(rest);
        if (!v) return std::nullopt;
        edit.a = *v;
        return edit;
    }
    const std::size_t dash = rest.find('-');
    if (dash == std::string::npos) return std::nullopt;
    const auto a = parseId(trimmed(std::string_view(rest).substr(0, dash)));
    const auto b = parseId(trimmed(std::string_view(rest).substr(dash + 1)));
    if (!a || !b) return std::nullopt;
    edit.a = *a;
    edit.b = *b;
    return edit;
}

Editor::Editor(const Mesh& finished)
    : m_mesh(closedForm(finished)),
      m_firstVirtual(finished.numVertices()),
      m_boundary(Boundary::Exact),
      m_remover(m_mesh, m_firstVirtual, Boundary::Exact),
      m_constrainer(m_mesh, m_firstVirtual, Boundary::Exact) {}

Editor::Editor(const Mesh& closed, std::int32_t firstVirtual)
    : m_mesh(closed),
      m_firstVirtual(firstVirtual),
      m_boundary(Boundary::Super),
      m_remover(m_mesh, m_firstVirtual, Boundary::Super),
      m_constrainer(m_mesh, m_firstVirtual, Boundary::Super) {}

std::unique_ptr<Editor> editorAtRunEnd(Journal& journal, const Inserter& ins) {
    if (ins.options().boundary == Boundary::Exact) return std::make_unique<Editor>(ins.mesh());
    const std::size_t end = journal.position();
    journal.seek(end - 1);  // before Finalize: the super-triangle still in
    auto editor = std::make_unique<Editor>(ins.mesh(), ins.numInput());
    journal.seek(end);
    return editor;
}

std::size_t Editor::total() const { return m_ends.empty() ? 0 : m_ends.back(); }

std::size_t Editor::editStart(std::size_t k) const {
    return k == 0 ? 0 : k <= m_ends.size() ? m_ends[k - 1] : total();
}

std::size_t Editor::editsDone() const {
    return static_cast<std::size_t>(std::upper_bound(m_ends.begin(), m_ends.end(), m_pos) -
                                    m_ends.begin());
}

EditStep Editor::stepAt(std::size_t position) const {
    EditStep s;
    // The edit that holds the op: the first whose end is past it.
    const auto k = static_cast<std::size_t>(
        std::upper_bound(m_ends.begin(), m_ends.end(), position) - m_ends.begin());
    if (k >= m_edits.size()) return s;
    const Edit& e = m_edits[k];
    const std::size_t i = position - editStart(k);
    s.edit = &e;
    s.index = k;
    if (i < e.removal.ops.size())
        s.removal = &e.removal.ops[i];
    else
        s.constraint = &e.constraint.ops[i - e.removal.ops.size()];
    return s;
}

EditStep Editor::current() const { return m_pos == 0 ? EditStep{} : stepAt(m_pos - 1); }

void Editor::replay(std::size_t position, bool forward) {
    const EditStep s = stepAt(position);
    const std::size_t i = position - editStart(s.index);
    if (s.removal) {
        m_remover.replay(s.edit->removal, i, forward);
        return;
    }
    if (s.constraint->type == ConstrainOpType::MoveVertex)
        m_mesh.G[s.edit->a] = forward ? s.edit->to : s.edit->from;
    m_constrainer.replay(s.edit->constraint, i - s.edit->removal.ops.size(), forward);
}

bool Editor::forward() {
    if (m_pos >= total()) return false;
    replay(m_pos++, true);
    return true;
}

bool Editor::back() {
    if (m_pos == 0) return false;
    replay(--m_pos, false);
    return true;
}

void Editor::seek(std::size_t position) {
    position = std::min(position, total());
    while (m_pos < position) forward();
    while (m_pos > position) back();
}

std::vector<std::pair<std::int32_t, std::int32_t>> Editor::constrainedEdges() const {
    std::vector<std::pair<std::int32_t, std::int32_t>> edges;
    for (std::int32_t c = 0; c < m_mesh.numCorners(); ++c) {
        const std::int32_t o = m_mesh.O[c];
        if (!isConstrained(c) || (o != kNone && o < c)) continue;
        edges.push_back({m_mesh.V[next(c)], m_mesh.V[prev(c)]});
    }
    return edges;
}

namespace {

std::string vertexName(std::int32_t v) { return "vertex " + std::to_string(v); }

std::string edgeName(std::pair<std::int32_t, std::int32_t> e) {
    return std::to_string(e.first) + "-" + std::to_string(e.second);
}

}  // namespace

// Runs the edit on the mesh with its records; false (with nothing changed) when refused.
// The removal of edit.a, recorded in the edit (the constraints kept when there are any).
VertexRemoval Editor::removeRecorded(Edit& edit, std::string& message) {
    VertexRemoval r;
    if (constrainedEdges().empty()) {  // no flag to put back, nothing but Delaunay to keep
        m_remover.meshChanged();
        r.removed = m_remover.remove(edit.a, &edit.removal);
        m_constrainer.refresh();
    } else {
        r = m_constrainer.removeVertex(m_remover, edit.a, &edit.removal, &edit.constraint);
    }
    if (r.refused) {
        message = vertexName(edit.a) + " is an end of the constrained edge " +
                  edgeName(r.constrained) + ": take that constraint away first";
    } else if (r.removed == RemoveResult::NotInMesh) {
        message = vertexName(edit.a) + " is not in the mesh (removed, or a duplicate)";
    }
    return r;
}

// Steps the recorded edit back to its start (its ops undone, the moved vertex back in place).
void Editor::unrecord(const Edit& e) {
    for (std::size_t i = e.constraint.ops.size(); i-- > 0;) {
        if (e.constraint.ops[i].type == ConstrainOpType::MoveVertex) m_mesh.G[e.a] = e.from;
        m_constrainer.replay(e.constraint, i, false);
    }
    for (std::size_t i = e.removal.ops.size(); i-- > 0;) m_remover.replay(e.removal, i, false);
}

// The op that puts the moved vertex at its new place (the editor changes G; sign 1: inside its
// star's kernel, the triangles around it follow).
void Editor::pushMoveOp(Edit& edit, bool inKernel) {
    ConstrainOp op;
    op.type = ConstrainOpType::MoveVertex;
    op.a = edit.a;
    op.sign = inKernel ? 1 : 0;
    op.trianglesBefore = op.trianglesAfter = m_mesh.numTriangles();
    op.firstChange = static_cast<std::uint32_t>(edit.constraint.changes.size());
    op.firstFlag = static_cast<std::uint32_t>(edit.constraint.flagChanges.size());
    edit.constraint.ops.push_back(op);
    m_mesh.G[edit.a] = edit.to;
}

// A move. Inside the kernel of its star, the vertex takes its new place (a MoveVertex op) and
// Lawson's flips from its star's edges follow; beyond it, the removal, the new place, then the
// insertion there (the hull grows when it is outside).
bool Editor::recordMove(Edit& edit, std::string& message) {
    const std::int32_t v = edit.a;
    if (!std::isfinite(edit.to.x) || !std::isfinite(edit.to.y)) {
        message = "a vertex moves to a point with finite coordinates";
        return false;
    }
    edit.from = m_mesh.G[v];
    if (edit.to == edit.from) {
        message = vertexName(v) + " is already there";
        return false;
    }
    for (const auto& e : constrainedEdges()) {  // a constraint ends at it: its segment would bend
        if (e.first == v || e.second == v) {
            message = vertexName(v) + " is an end of the constrained edge " + edgeName(e) +
                      ": take that constraint away first";
            return false;
        }
    }
    if (m_constrainer.inKernel(v, edit.to)) {
        pushMoveOp(edit, true);
        m_constrainer.follow(v, &edit.constraint);
        m_remover.meshChanged();
        message = "moved " + vertexName(v) +
                  " inside its star's kernel: " + std::to_string(edit.numOps()) + " operations";
        return true;
    }
    const VertexRemoval r = removeRecorded(edit, message);
    if (r.refused || r.removed == RemoveResult::NotInMesh) return false;
    pushMoveOp(edit, false);
    PlaceResult placed = PlaceResult::NoTriangle;
    if (r.removed == RemoveResult::Removed)
        placed = m_constrainer.insertVertex(v, &edit.constraint);
    else if (r.droppedConstraints == 0)  // the others are collinear: a fan with them
        placed = m_constrainer.fanOut(v, leftAfterCollapse(edit), &edit.constraint);
    if (placed == PlaceResult::Placed) {
        message = "moved " + vertexName(v) +
                  " (taken out and put in again): " + std::to_string(edit.numOps()) + " operations";
        return true;
    }
    unrecord(edit);
    m_remover.meshChanged();
    m_constrainer.refresh();
    if (placed == PlaceResult::OnVertex)
        message = vertexName(v) + " cannot move onto another vertex";
    else if (m_boundary == Boundary::Super)
        message = vertexName(v) + " cannot move outside the super-triangle";
    else if (r.droppedConstraints)
        message = vertexName(v) + " cannot move: the other points are collinear, and the " +
                  "constraints between them would be lost";
    else
        message = vertexName(v) + " cannot move onto the line of the other points: they would " +
                  "make no triangle";
    return false;
}

// The vertices a collapsed removal left (every other vertex its Collapse op took out of the
// table), in order.
std::vector<std::int32_t> Editor::leftAfterCollapse(const Edit& edit) const {
    std::vector<std::int32_t> left;
    for (const RemoveOp& op : edit.removal.ops) {
        if (op.type != RemoveOpType::Collapse) continue;
        for (std::uint32_t i = 0; i < op.numChanges; ++i) {
            const CellChange& ch = edit.removal.changes[op.firstChange + i];
            if (!ch.isO() && ch.before >= 0 && ch.before < m_firstVirtual && ch.before != edit.a)
                left.push_back(ch.before);
        }
    }
    std::sort(left.begin(), left.end());
    left.erase(std::unique(left.begin(), left.end()), left.end());
    return left;
}

// Runs the edit on the mesh with its records; false (with nothing changed) when refused.
bool Editor::record(Edit& edit, std::string& message) {
    const std::int32_t n = m_firstVirtual;
    const auto isVertex = [&](std::int32_t v) { return v >= 0 && v < n; };
    const bool segment = edit.kind == EditKind::Constrain || edit.kind == EditKind::Unconstrain;
    if (!isVertex(edit.a) || (segment && !isVertex(edit.b))) {
        message = "no such vertex: the mesh has vertices 0 to " + std::to_string(n - 1);
        return false;
    }
    if (edit.kind == EditKind::MoveVertex) return recordMove(edit, message);
    if (edit.kind == EditKind::RemoveVertex) {
        const VertexRemoval r = removeRecorded(edit, message);
        if (r.refused || r.removed == RemoveResult::NotInMesh) return false;
        message = "removed " + vertexName(edit.a) + ": " + std::to_string(edit.removal.ops.size()) +
                  " operations";
        if (r.removed == RemoveResult::Collapsed) message += "; the points left make no triangle";
        if (r.droppedConstraints > 0)  // no triangle holds them: stepping back restores them
            message += ", and the " + std::to_string(r.droppedConstraints) +
                       (r.droppedConstraints == 1 ? " constraint" : " constraints") +
                       " between them are dropped";
        return true;
    }
    const ConstrainOutcome out = edit.kind == EditKind::Constrain
                                     ? m_constrainer.insert(edit.a, edit.b, &edit.constraint)
                                     : m_constrainer.remove(edit.a, edit.b, &edit.constraint);
    const std::string seg = "segment " + edgeName({edit.a, edit.b});
    switch (out.result) {
        case ConstrainResult::Inserted:
            message = (edit.kind == EditKind::Constrain ? "constrained " : "unconstrained ") + seg +
                      ": " + std::to_string(edit.constraint.ops.size()) + " operations";
            return true;
        case ConstrainResult::SameVertex: message = "a segment needs two different vertices"; break;
        case ConstrainResult::NotInMesh:
            message = seg + ": an end is not a vertex of the mesh (removed, or a duplicate)";
            break;
        case ConstrainResult::Crosses:
            message = seg + " crosses the constrained edge " + edgeName(out.crossed) +
                      ": constrained edges may not cross";
            break;
        case ConstrainResult::NotConstrained: message = seg + " is not a constraint"; break;
    }
    return false;
}

bool Editor::add(Edit edit, std::string& message) {
    seek(total());  // every edit before it done, one in progress finished
    edit.removal = {};
    edit.constraint = {};
    m_remover.meshChanged();  // stepping changed the mesh behind both editors' indexes
    m_constrainer.refresh();
    if (!record(edit, message)) return false;
    m_ends.push_back(total() + edit.numOps());
    m_edits.push_back(std::move(edit));
    unrecord(m_edits.back());  // back to the start of the edit: its ops are stepped from there
    return true;
}

std::optional<Edit> Editor::takeLast() {
    if (m_edits.empty()) return std::nullopt;
    const std::size_t start = editStart(m_edits.size() - 1);
    if (m_pos > start) seek(start);
    Edit last = std::move(m_edits.back());
    m_edits.pop_back();
    m_ends.pop_back();
    last.removal = {};
    last.constraint = {};
    return last;
}

}  // namespace dlab
