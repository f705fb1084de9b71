// Edits of a finished Delaunay triangulation, each a sequence of recorded operations: removing a
// vertex (the Remover's ear tests, flips and merge, then the constraints put back), and adding or
// taking away a constrained segment (the Constrainer's walk, Sloan's flips, the mark and the
// repair). The edits work on the exact mode's closed mesh (addGhosts); every op is stepped
// forwards and backwards bit for bit, and an edit made in the middle of the history drops the
// edits after it, as a new edit in a text editor drops its redo.
#pragma once

#include "core/engine/constrainer.h"
#include "core/engine/mesh.h"
#include "core/engine/remover.h"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace dlab {

enum class EditKind : std::uint8_t {
    RemoveVertex,  // a: the vertex
    Constrain,     // a-b: the segment made a constrained edge (or a chain of them)
    Unconstrain,   // a-b: a constrained segment taken away
    MoveVertex,    // a to `to`: inside its star's kernel the mesh follows by flips; beyond it,
                   // taken out and put in again at its new place (the hull grows to take it in)
};
const char* toString(EditKind k);

struct Edit {
    EditKind kind = EditKind::RemoveVertex;
    std::int32_t a = kNone, b = kNone;
    Vec2 from{}, to{};            // MoveVertex: the vertex's place before and after
    RemovalRecord removal;        // RemoveVertex: the ear tests, flips and merge
    ConstraintRecord constraint;  // the constraint ops (after the removal's, for RemoveVertex)
    std::size_t numOps() const { return removal.ops.size() + constraint.ops.size(); }
};
inline Edit makeEdit(EditKind kind, std::int32_t a, std::int32_t b = kNone) {
    Edit e;
    e.kind = kind;
    e.a = a;
    e.b = b;
    return e;
}
inline Edit makeMove(std::int32_t v, Vec2 to) {
    Edit e = makeEdit(EditKind::MoveVertex, v);
    e.to = to;
    return e;
}
// "remove vertex 5", "constrain 2-7", "unconstrain 2-7", "move vertex 5 to 3.5, 7" (shortest
// decimals: bit for bit): the edit as a user says it (and as sessions and `dtlab render --edit`
// read it back).
std::string describe(const Edit& edit);
// Reads that form back (also "remove 5"); nullopt when it is none of them.
std::optional<Edit> parseEdit(std::string_view text);

// One operation of an edit: an op of its removal or of its constraint record.
struct EditStep {
    const Edit* edit = nullptr;  // null: no edit op (position 0)
    std::size_t index = 0;       // which edit
    const RemoveOp* removal = nullptr;
    const ConstrainOp* constraint = nullptr;
};

class Editor {
public:
    // `finished`: an exact-mode triangulation as the inserter's Finalize leaves it (vertices are
    // the input's indices, no ghost). Edits work on its closed form: the ghost vertex is index
    // |G| (firstVirtual()), joined to every hull edge.
    explicit Editor(const Mesh& finished);
    // The super-triangle's mode: `closed` is the inserter's mesh before Finalize, the
    // super-triangle's three vertices from `firstVirtual` on (real points every test uses, never
    // removed, moved or an end of a segment).
    Editor(const Mesh& closed, std::int32_t firstVirtual);

    // Records an edit after every edit (the edits before it are done first, one in progress is
    // finished). The mesh is then put back as it was before the new edit and position() is its
    // first op, to step through with forward(). Stepping never drops an edit; takeLast() does. A
    // refused edit (a vertex that is no vertex, a segment crossing a constraint, a vertex on a
    // constrained edge...) changes nothing and returns false; `message` says what happened
    // either way, in a user's words.
    bool add(Edit edit, std::string& message);
    // Undoes the last edit and takes it out of the history (the position goes back to its start
    // when past it); the edit as it was asked for, to add again, or nullopt when there is none.
    std::optional<Edit> takeLast();

    bool forward();  // one op; false at the end
    bool back();     // one op back; false at the start
    void seek(std::size_t position);
    std::size_t position() const { return m_pos; }
    std::size_t total() const;  // ops of every recorded edit
    // The first op of edit k, and the position after its last.
    std::size_t editStart(std::size_t k) const;
    std::size_t editEnd(std::size_t k) const { return m_ends[k]; }
    // The edits whose every op is done (position() at or past their end).
    std::size_t editsDone() const;

    const Mesh& mesh() const { return m_mesh; }
    std::int32_t firstVirtual() const { return m_firstVirtual; }
    Boundary boundary() const { return m_boundary; }
    // The exact mode's ghost vertex (firstVirtual()); in the super-triangle's mode past every
    // vertex, as it has none.
    std::int32_t ghost() const {
        return m_boundary == Boundary::Exact ? m_firstVirtual
                                             : std::numeric_limits<std::int32_t>::max();
    }
    const std::vector<Edit>& edits() const { return m_edits; }
    // The op just done (position() - 1), or none at position 0.
    EditStep current() const;
    // Is the edge opposite corner c constrained now?
    bool isConstrained(std::int32_t c) const {
        const auto& f = m_constrainer.flags();
        return c >= 0 && static_cast<std::size_t>(c) < f.size() && f[c] != 0;
    }
    // Every constrained edge now, once, as its two vertices.
    std::vector<std::pair<std::int32_t, std::int32_t>> constrainedEdges() const;

private:
    EditStep stepAt(std::size_t position) const;  // the op at 0-based position
    void replay(std::size_t position, bool forward);
    bool record(Edit& edit, std::string& message);
    VertexRemoval removeRecorded(Edit& edit, std::string& message);
    bool recordMove(Edit& edit, std::string& message);
    void pushMoveOp(Edit& edit, bool inKernel);
    std::vector<std::int32_t> leftAfterCollapse(const Edit& edit) const;
    void unrecord(const Edit& edit);

    Mesh m_mesh;
    std::int32_t m_firstVirtual;
    Boundary m_boundary;
    Remover m_remover;
    Constrainer m_constrainer;
    std::vector<Edit> m_edits;
    std::vector<std::size_t> m_ends;  // the position after each edit's last op, increasing
    std::size_t m_pos = 0;
};

// An editor of a finished run: its finished mesh (exact), or in the super-triangle's mode the
// mesh before Finalize dropped the super-triangle (the journal steps back over Finalize for it,
// then forward again).
std::unique_ptr<Editor> editorAtRunEnd(Journal& journal, const Inserter& ins);

}  // namespace dlab
