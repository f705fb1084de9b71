// Corner expressions: `r(o(n(7)))`, `c.n.o.r`, `V[n(o(c))] == V[p(c)]` parsed once and evaluated
// against a Mesh, with the path of corners visited (for drawing) or a precise error. Shared by
// the GUI's expression console and watches, and by lesson questions.
//
// Grammar (spaces anywhere between tokens):
//   expr     := chain [ ("==" | "=" | "!=") chain ]
//   chain    := primary { "." op }
//   primary  := integer | "-1" | variable | op "(" expr ")" | table "[" expr "]" | "(" expr ")"
//   op       := n p o l r s u t v               (Rossignac's operators, as in core/engine/mesh.h:
//                                                l = o(n(c)), r = o(p(c)), s = n(l(c)),
//                                                u = p(r(c)))
//   table    := V (= v) | O (= o) | G (coordinates of a vertex)
//   variable := a name bound by the caller, e.g. c (the selected corner)
//
// Types: corners (n p o l r s u take and give corners; t gives a triangle, v / V[] a vertex),
// vertices (G[] gives a point), points, truth values (comparisons). A bare
// integer takes the type its use asks for. o, l, r, s, u may give -1 on the boundary: that is a
// value, and applying a further operator to it is an error that says so. No input string can
// crash the parser or the evaluator, or make them read outside the mesh.
#pragma once

#include "core/engine/geometry.h"
#include "core/engine/mesh.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace dlab {

enum class ValueKind : std::uint8_t { Number, Corner, Vertex, Triangle, Point, Truth };
const char* toString(ValueKind kind);

struct ExprValue {
    ValueKind kind = ValueKind::Number;
    std::int64_t i = 0;  // Number, Corner, Vertex, Triangle (kNone = -1 allowed for a corner)
    Vec2 point{};        // Point
    bool truth = false;  // Truth
};
// "17", "-1", "(100, 200)", "true".
std::string formatValue(const ExprValue& value);

// One move of the evaluation: `op` applied to `from` gave `to`. op is one of n p o l r s u
// (corner -> corner), t (corner -> triangle), v (corner -> vertex, also V[...]), G (vertex ->
// point: `to` is the vertex again). side: 0 for the left of a comparison (or the whole
// expression), 1 for its right.
struct PathStep {
    char op = 'n';
    std::int32_t from = kNone;
    std::int32_t to = kNone;
    std::uint8_t side = 0;
};

struct ExprError {
    enum class Kind : std::uint8_t {
        Syntax,    // the text is not an expression
        Type,      // e.g. n applied to a vertex
        Boundary,  // an operator applied to -1 (a boundary result)
        Range,     // a corner or vertex outside the mesh, an unbound variable
    };
    Kind kind = Kind::Syntax;
    std::size_t column = 0;  // 0-based offset into the text where the culprit starts
    std::string message;     // "o(5) is -1 (boundary): cannot apply n"
};
const char* toString(ExprError::Kind kind);

struct ExprResult {
    std::optional<ExprValue> value;  // set on success
    ExprError error;                 // meaningful when !value
    std::vector<PathStep> path;      // the moves made (also up to the failure)
    bool ok() const { return value.has_value(); }
};

// Names bound for an evaluation: {"c", corner 7}. Unbound names are an error.
struct ExprBinding {
    std::string name;
    ExprValue value;
};

// Optional knowledge about the mesh for clearer messages: vertices >= firstVirtual are the
// ghost vertex (exact mode, no coordinates) or the super-triangle's.
struct ExprContext {
    std::int32_t firstVirtual = -1;
    bool ghost = false;  // exact mode: G[ghost] is an error, it has no coordinates
};

class CornerExpr {
public:
    // Parses `text` (at most kMaxLength characters). On failure returns nullopt and fills
    // `error` (column and message).
    static std::optional<CornerExpr> parse(std::string_view text, ExprError* error = nullptr);
    static constexpr std::size_t kMaxLength = 1000;

    ExprResult evaluate(const Mesh& mesh, std::span<const ExprBinding> bindings = {},
                        const ExprContext& context = {}) const;
    // Shorthand: evaluate with c bound to corner `c`.
    ExprResult evaluateAt(const Mesh& mesh, std::int32_t c, const ExprContext& context = {}) const;

    const std::string& text() const { return m_text; }
    bool isComparison() const;
    // Whether the expression mentions the variable (e.g. whether a watch depends on c).
    bool uses(std::string_view name) const;
    // The variables it mentions, each once, in order of appearance.
    std::vector<std::string> variables() const;

    struct Node {
        enum class Kind : std::uint8_t { Number, Var, Apply, Compare };
        Kind kind = Kind::Number;
        char op = 0;                       // Apply: n p o l r s u t v G; Compare: '=' or '!'
        std::int64_t number = 0;           // Number
        std::string name;                  // Var
        std::int32_t a = -1, b = -1;       // children (node indices)
        std::uint32_t begin = 0, end = 0;  // source span
    };

private:
    friend class ExprParser;
    friend class ExprEvaluator;
    std::string m_text;
    std::vector<Node> m_nodes;
    std::int32_t m_root = -1;
};

// Watches: identities such as o(o(c)) == c checked for every corner, or for one.
struct WatchReport {
    bool ok = true;               // no corner failed
    std::int64_t checked = 0;     // corners where the identity was evaluated
    std::int64_t skipped = 0;     // corners where it did not apply (it ran into the boundary)
    std::int32_t corner = kNone;  // the first failing corner
    ExprResult failure;           // its evaluation: value false, or an error
    std::string message;          // one line: "fails at c = 7: o(o(c)) == c is false (...)"
};

// The watch must be a comparison using c. Every corner c in [0, numCorners) is tried in order;
// a boundary error skips the corner, a false comparison or any other error is a failure.
WatchReport checkWatch(const CornerExpr& watch, const Mesh& mesh, const ExprContext& context = {});
WatchReport checkWatchAt(const CornerExpr& watch, const Mesh& mesh, std::int32_t c,
                         const ExprContext& context = {});
// Only these corners (e.g. those of the triangles the last operation changed), in this order.
WatchReport checkWatchOn(const CornerExpr& watch, const Mesh& mesh,
                         std::span<const std::int32_t> corners, const ExprContext& context = {});

// The identities every corner table satisfies (for the GUI's watch list and the lessons).
std::span<const char* const> standardWatches();

}  // namespace dlab
