// Corner expressions: a recursive-descent parser into a small node array, and an evaluator that
// checks every index before it reads the mesh.
#include "core/teaching/corner_expr.h"

#include "core/engine/numbers.h"

#include "core/engine/text_util.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <string>

namespace dlab {

namespace {

constexpr int kMaxDepth = 64;           // nested brackets
constexpr std::size_t kMaxNodes = 600;  // bounds the evaluator's recursion as well

bool isIdentStart(char ch) { return std::isalpha(static_cast<unsigned char>(ch)) || ch == '_'; }
bool isIdentChar(char ch) { return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_'; }
bool isCornerOp(char op) {
    return std::string_view("nplorsutv").find(op) != std::string_view::npos;
}

// Shortest text that reads back to the same double.
std::string formatDouble(double x) { return shortest(x); }

}  // namespace

const char* toString(ValueKind kind) {
    switch (kind) {
        case ValueKind::Number: return "number";
        case ValueKind::Corner: return "corner";
        case ValueKind::Vertex: return "vertex";
        case ValueKind::Triangle: return "triangle";
        case ValueKind::Point: return "point";
        case ValueKind::Truth: return "truth value";
    }
    return "?";
}

const char* toString(ExprError::Kind kind) {
    switch (kind) {
        case ExprError::Kind::Syntax: return "syntax";
        case ExprError::Kind::Type: return "type";
        case ExprError::Kind::Boundary: return "boundary";
        case ExprError::Kind::Range: return "range";
    }
    return "?";
}

std::string formatValue(const ExprValue& v) {
    switch (v.kind) {
        case ValueKind::Point:
            return "(" + formatDouble(v.point.x) + ", " + formatDouble(v.point.y) + ")";
        case ValueKind::Truth: return v.truth ? "true" : "false";
        default: return std::to_string(v.i);
    }
}

// ============================================================================================
// [SECTION] Parser
// ============================================================================================

class ExprParser {
public:
    ExprParser(std::string_view text, CornerExpr& out) : m_s(text), m_out(out) {}

    bool run(ExprError* error) {
        if (m_s.size() > CornerExpr::kMaxLength) {
            return fail(CornerExpr::kMaxLength,
                        "expression too long (at most " + std::to_string(CornerExpr::kMaxLength) +
                            " characters)",
                        error);
        }
        for (std::size_t i = 0; i < m_s.size(); ++i) {
            const unsigned char ch = static_cast<unsigned char>(m_s[i]);
            if (ch < 32 && ch != '\t' && ch != '\n' && ch != '\r')
                return fail(i, "control character in the expression", error);
            if (ch >= 128) return fail(i, "only ASCII is allowed in an expression", error);
        }
        skip();
        if (m_pos == m_s.size()) return fail(0, "empty expression: try 7.n or o(c)", error);
        m_out.m_root = expr();
        if (!m_failed) {
            skip();
            if (m_pos < m_s.size()) {
                const char ch = m_s[m_pos];
                if (ch == '=' || ch == '!') {
                    setError(m_pos, "only one comparison per expression");
                } else if (ch == ')' || ch == ']') {
                    setError(m_pos, std::string("unmatched '") + ch + "'");
                } else {
                    setError(m_pos, std::string("unexpected '") + ch + "'");
                }
            }
        }
        if (m_failed) {
            if (error) *error = m_error;
            return false;
        }
        return true;
    }

private:
    using Node = CornerExpr::Node;

    bool fail(std::size_t column, std::string message, ExprError* error) {
        if (error) *error = ExprError{ExprError::Kind::Syntax, column, std::move(message)};
        return false;
    }
    std::int32_t setError(std::size_t column, std::string message) {
        if (!m_failed)
            m_error = ExprError{ExprError::Kind::Syntax, column, escapeControls(message)};
        m_failed = true;
        return -1;
    }
    void skip() {
        while (m_pos < m_s.size() && std::isspace(static_cast<unsigned char>(m_s[m_pos]))) ++m_pos;
    }
    bool peek(char ch) {
        skip();
        return m_pos < m_s.size() && m_s[m_pos] == ch;
    }
    std::string_view ident() {
        const std::size_t start = m_pos;
        while (m_pos < m_s.size() && isIdentChar(m_s[m_pos])) ++m_pos;
        return m_s.substr(start, m_pos - start);
    }
    std::int32_t add(Node n) {
        if (m_failed) return -1;
        if (m_out.m_nodes.size() >= kMaxNodes) return setError(n.begin, "expression too long");
        m_out.m_nodes.push_back(std::move(n));
        return static_cast<std::int32_t>(m_out.m_nodes.size() - 1);
    }
    std::uint32_t at() const { return static_cast<std::uint32_t>(m_pos); }

    std::int32_t expr() {
        const std::uint32_t begin = (skip(), at());
        const std::int32_t left = chain();
        if (m_failed) return -1;
        skip();
        char op = 0;
        if (m_s.substr(m_pos, 2) == "==") {
            op = '=';
            m_pos += 2;
        } else if (m_s.substr(m_pos, 2) == "!=") {
            op = '!';
            m_pos += 2;
        } else if (m_s.substr(m_pos, 1) == "=") {
            op = '=';
            m_pos += 1;
        } else
            return left;
        skip();
        if (m_pos == m_s.size())
            return setError(m_pos, "nothing to compare with after the comparison");
        const std::int32_t right = chain();
        if (m_failed) return -1;
        Node n;
        n.kind = Node::Kind::Compare;
        n.op = op;
        n.a = left;
        n.b = right;
        n.begin = begin;
        n.end = at();
        return add(std::move(n));
    }

    std::int32_t chain() {
        skip();
        const std::uint32_t begin = at();
        std::int32_t x = primary();
        while (!m_failed && peek('.')) {
            const std::size_t dot = m_pos++;
            skip();
            if (m_pos < m_s.size() && std::isdigit(static_cast<unsigned char>(m_s[m_pos]))) {
                return setError(dot, "corners are whole numbers: no decimal point");
            }
            if (m_pos == m_s.size() || !isIdentStart(m_s[m_pos])) {
                return setError(m_pos, "expected an operator after '.' (n p o l r s u t v)");
            }
            const std::size_t nameAt = m_pos;
            const std::string_view name = ident();
            if (name.size() != 1 || !isCornerOp(name[0])) {
                return setError(
                    nameAt, "unknown operator '" + std::string(name) + "' (use n p o l r s u t v)");
            }
            Node n;
            n.kind = Node::Kind::Apply;
            n.op = name[0];
            n.a = x;
            n.begin = begin;
            n.end = at();
            x = add(std::move(n));
        }
        return x;
    }

    std::int32_t bracketed(char open, char close, char op, std::uint32_t begin,
                           std::string_view name) {
        ++m_pos;  // the opening bracket
        if (++m_depth > kMaxDepth) return setError(m_pos - 1, "brackets nested too deeply");
        skip();
        if (peek(close))
            return setError(m_pos, std::string(name) + open + close + " needs an argument inside");
        const std::int32_t inner = expr();
        if (m_failed) return -1;
        if (!peek(close)) {
            return setError(m_pos, m_pos == m_s.size()
                                       ? std::string("missing '") + close + "'"
                                       : std::string("expected '") + close + "' here");
        }
        ++m_pos;
        --m_depth;
        if (op == 0) return inner;  // plain parentheses
        if (m_out.m_nodes[inner].kind == Node::Kind::Compare) {
            return setError(begin, "a comparison cannot be the argument of " + std::string(name));
        }
        Node n;
        n.kind = Node::Kind::Apply;
        n.op = op;
        n.a = inner;
        n.begin = begin;
        n.end = at();
        return add(std::move(n));
    }

    std::int32_t primary() {
        skip();
        const std::uint32_t begin = at();
        if (m_pos == m_s.size()) return setError(m_pos, "expression ends too early");
        const char ch = m_s[m_pos];
        if (std::isdigit(static_cast<unsigned char>(ch)) ||
            (ch == '-' && m_pos + 1 < m_s.size() &&
             std::isdigit(static_cast<unsigned char>(m_s[m_pos + 1])))) {
            const std::size_t start = m_pos;
            if (ch == '-') ++m_pos;
            while (m_pos < m_s.size() && std::isdigit(static_cast<unsigned char>(m_s[m_pos])))
                ++m_pos;
            if (m_pos < m_s.size() && isIdentChar(m_s[m_pos])) {
                return setError(m_pos, "a number cannot run into a name: '" +
                                           std::string(m_s.substr(start, m_pos - start + 1)) + "'");
            }
            std::int64_t v = 0;
            const auto [end, ec] = std::from_chars(m_s.data() + start, m_s.data() + m_pos, v);
            if (ec != std::errc() || end != m_s.data() + m_pos || v > INT32_MAX || v < INT32_MIN) {
                return setError(start, "number too large");
            }
            Node n;
            n.kind = Node::Kind::Number;
            n.number = v;
            n.begin = begin;
            n.end = at();
            return add(std::move(n));
        }
        if (ch == '(') return bracketed('(', ')', 0, begin, "");
        if (!isIdentStart(ch)) {
            return setError(
                m_pos,
                std::string("expected a corner number, a name or '(' here, not '") + ch + "'");
        }
        const std::string_view name = ident();
        const bool op = name.size() == 1 && isCornerOp(name[0]);
        const bool table = name == "V" || name == "O" || name == "G";
        if (op && peek('(')) return bracketed('(', ')', name[0], begin, name);
        if (table && peek('['))
            return bracketed('[', ']', name == "G" ? 'G' : static_cast<char>(name[0] + 32), begin,
                             name);
        if (op && peek('[')) {
            return setError(begin, "use " + std::string(name) + "(...) or " +
                                       static_cast<char>(name[0] - 32) +
                                       "[...] (O and V take square brackets)");
        }
        if (table && peek('(')) {
            return setError(
                begin, "use " + std::string(name) + "[...] with square brackets" +
                           (name == "G"
                                ? ""
                                : std::string(" or ") + static_cast<char>(name[0] + 32) + "(...)"));
        }
        if (op || table) {
            return setError(begin,
                            std::string(name) + " needs an argument: " +
                                (table ? std::string(name) + "[7]"
                                       : std::string(name) + "(7) or 7." + std::string(name)));
        }
        Node n;
        n.kind = Node::Kind::Var;
        n.name = std::string(name);
        n.begin = begin;
        n.end = at();
        return add(std::move(n));
    }

    std::string_view m_s;
    CornerExpr& m_out;
    std::size_t m_pos = 0;
    int m_depth = 0;
    bool m_failed = false;
    ExprError m_error;
};

std::optional<CornerExpr> CornerExpr::parse(std::string_view text, ExprError* error) {
    CornerExpr e;
    e.m_text = std::string(text.substr(0, kMaxLength + 1));
    ExprParser parser(e.m_text, e);
    if (!parser.run(error)) return std::nullopt;
    return e;
}

bool CornerExpr::isComparison() const {
    return m_root >= 0 && m_nodes[m_root].kind == Node::Kind::Compare;
}

bool CornerExpr::uses(std::string_view name) const {
    return std::any_of(m_nodes.begin(), m_nodes.end(),
                       [&](const Node& n) { return n.kind == Node::Kind::Var && n.name == name; });
}

std::vector<std::string> CornerExpr::variables() const {
    std::vector<std::string> out;
    for (const Node& n : m_nodes) {
        if (n.kind == Node::Kind::Var && std::find(out.begin(), out.end(), n.name) == out.end())
            out.push_back(n.name);
    }
    return out;
}

// ============================================================================================
// [SECTION] Evaluator
// ============================================================================================

class ExprEvaluator {
public:
    ExprEvaluator(const CornerExpr& e, const Mesh& m, std::span<const ExprBinding> b,
                  const ExprContext& ctx, std::vector<PathStep>* path)
        : m_e(e), m_mesh(m), m_bindings(b), m_ctx(ctx), m_path(path) {
        const std::size_t cells = std::min(m.V.size(), m.O.size());
        m_corners = static_cast<std::int64_t>(cells - cells % 3);
    }

    std::optional<ExprValue> run() { return eval(m_e.m_root, 0); }
    const ExprError& error() const { return m_error; }

private:
    using Node = CornerExpr::Node;

    std::string src(const Node& n) const {
        return escapeControls(m_e.m_text.substr(n.begin, n.end - n.begin));
    }

    std::nullopt_t fail(ExprError::Kind kind, const Node& at, std::string message) {
        m_error = ExprError{kind, at.begin, std::move(message)};
        return std::nullopt;
    }

    std::string cornerRange() const {
        return m_corners == 0 ? "the mesh has no corners" : "0.." + std::to_string(m_corners - 1);
    }

    // The corner an operator applies to: a corner value or a bare number, in range.
    std::optional<std::int32_t> asCorner(const ExprValue& v, const Node& arg, char op) {
        if (v.kind != ValueKind::Corner && v.kind != ValueKind::Number) {
            return fail(ExprError::Kind::Type, arg,
                        std::string(1, op) + " needs a corner, but " + src(arg) + " is a " +
                            toString(v.kind) +
                            (v.kind == ValueKind::Vertex
                                 ? " (operators move between corners; V[c] gives c's vertex)"
                                 : ""));
        }
        if (v.i == kNone) {
            return fail(ExprError::Kind::Boundary, arg,
                        src(arg) + " is -1 (boundary): cannot apply " + std::string(1, op));
        }
        if (v.i < 0 || v.i >= m_corners) {
            return fail(ExprError::Kind::Range, arg,
                        "corner " + std::to_string(v.i) + " out of range (" + cornerRange() + ")");
        }
        return static_cast<std::int32_t>(v.i);
    }

    // A corner read from O: kNone or in range, else the mesh is broken and we say where.
    std::optional<std::int32_t> readO(std::int32_t c, const Node& at) {
        const std::int32_t x = m_mesh.O[c];
        if (x != kNone && (x < 0 || x >= m_corners)) {
            return fail(ExprError::Kind::Range, at,
                        "O[" + std::to_string(c) + "] = " + std::to_string(x) +
                            " is out of range (" + cornerRange() + ")");
        }
        return x;
    }

    void step(char op, std::int64_t from, std::int64_t to, std::uint8_t side) {
        if (m_path)
            m_path->push_back(
                {op, static_cast<std::int32_t>(from), static_cast<std::int32_t>(to), side});
    }

    std::optional<ExprValue> eval(std::int32_t idx, std::uint8_t side) {
        const Node& n = m_e.m_nodes[idx];
        switch (n.kind) {
            case Node::Kind::Number: return ExprValue{ValueKind::Number, n.number, {}, false};
            case Node::Kind::Var: {
                for (const ExprBinding& b : m_bindings) {
                    if (b.name == n.name) return b.value;
                }
                return fail(
                    ExprError::Kind::Range, n,
                    "unknown name '" + n.name + "'" +
                        (n.name == "c" ? ": no corner is selected"
                                       : " (corners are numbers; c is the selected corner)"));
            }
            case Node::Kind::Compare: return compare(n);
            case Node::Kind::Apply: break;
        }
        const Node& arg = m_e.m_nodes[n.a];
        const auto x = eval(n.a, side);
        if (!x) return std::nullopt;
        if (n.op == 'G') {
            if (x->kind != ValueKind::Vertex && x->kind != ValueKind::Number) {
                return fail(
                    ExprError::Kind::Type, arg,
                    "G needs a vertex, but " + src(arg) + " is a " + toString(x->kind) +
                        (x->kind == ValueKind::Corner ? ": use G[V[" + src(arg) + "]]" : ""));
            }
            if (x->i < 0 || x->i >= m_mesh.numVertices()) {
                return fail(
                    ExprError::Kind::Range, arg,
                    "vertex " + std::to_string(x->i) + " out of range (" +
                        (m_mesh.G.empty() ? std::string("the mesh has no vertices")
                                          : "0.." + std::to_string(m_mesh.numVertices() - 1)) +
                        ")");
            }
            if (m_ctx.ghost && m_ctx.firstVirtual >= 0 && x->i >= m_ctx.firstVirtual) {
                return fail(ExprError::Kind::Range, arg,
                            "vertex " + std::to_string(x->i) +
                                " is the ghost vertex: it has no coordinates");
            }
            step('G', x->i, x->i, side);
            ExprValue out{ValueKind::Point, 0, m_mesh.G[x->i], false};
            return out;
        }
        const auto c = asCorner(*x, arg, n.op);
        if (!c) return std::nullopt;
        ExprValue out{ValueKind::Corner, kNone, {}, false};
        std::optional<std::int32_t> r;
        switch (n.op) {
            case 'n': r = next(*c); break;
            case 'p': r = prev(*c); break;
            case 'o': r = readO(*c, n); break;
            case 'l': r = readO(next(*c), n); break;
            case 'r': r = readO(prev(*c), n); break;
            case 's':
                r = readO(next(*c), n);
                if (r && *r != kNone) r = next(*r);
                break;
            case 'u':
                r = readO(prev(*c), n);
                if (r && *r != kNone) r = prev(*r);
                break;
            case 't':
                out.kind = ValueKind::Triangle;
                r = tri(*c);
                break;
            case 'v':
                out.kind = ValueKind::Vertex;
                r = m_mesh.V[*c];
                break;
            default: return fail(ExprError::Kind::Syntax, n, "internal: unknown operator");
        }
        if (!r) return std::nullopt;
        out.i = *r;
        step(n.op, *c, *r, side);
        return out;
    }

    std::optional<ExprValue> compare(const Node& n) {
        const auto a = eval(n.a, 0);
        if (!a) return std::nullopt;
        const auto b = eval(n.b, 1);
        if (!b) return std::nullopt;
        const Node& left = m_e.m_nodes[n.a];
        const Node& right = m_e.m_nodes[n.b];
        const bool aPoint = a->kind == ValueKind::Point;
        const auto integral = [](ValueKind k) {
            return k != ValueKind::Point && k != ValueKind::Truth;
        };
        const bool compatible =
            a->kind == b->kind || (integral(a->kind) && integral(b->kind) &&
                                   (a->kind == ValueKind::Number || b->kind == ValueKind::Number));
        if (!compatible) {
            return fail(ExprError::Kind::Type, n,
                        std::string("cannot compare a ") + toString(a->kind) + " (" + src(left) +
                            ") with a " + toString(b->kind) + " (" + src(right) + ")");
        }
        bool equal = false;
        if (aPoint) {
            equal = a->point == b->point;
        } else if (a->kind == ValueKind::Truth) {
            equal = a->truth == b->truth;
        } else {
            equal = a->i == b->i;
        }
        return ExprValue{ValueKind::Truth, 0, {}, n.op == '=' ? equal : !equal};
    }

    const CornerExpr& m_e;
    const Mesh& m_mesh;
    std::span<const ExprBinding> m_bindings;
    const ExprContext& m_ctx;
    std::vector<PathStep>* m_path;
    std::int64_t m_corners = 0;
    ExprError m_error;
};

ExprResult CornerExpr::evaluate(const Mesh& mesh, std::span<const ExprBinding> bindings,
                                const ExprContext& context) const {
    ExprResult r;
    if (m_root < 0) {
        r.error = ExprError{ExprError::Kind::Syntax, 0, "empty expression"};
        return r;
    }
    ExprEvaluator ev(*this, mesh, bindings, context, &r.path);
    r.value = ev.run();
    if (!r.value) r.error = ev.error();
    return r;
}

ExprResult CornerExpr::evaluateAt(const Mesh& mesh, std::int32_t c,
                                  const ExprContext& context) const {
    const ExprBinding b{"c", ExprValue{ValueKind::Corner, c, {}, false}};
    return evaluate(mesh, std::span(&b, 1), context);
}

// ============================================================================================
// [SECTION] Watches
// ============================================================================================

namespace {

constexpr const char* kStandardWatches[] = {
    "o(o(c)) == c",           // O is symmetric
    "t(o(c)) != t(c)",        // the opposite corner lies in another triangle
    "V[n(o(c))] == V[p(c)]",  // the shared edge, seen from both sides, has the same ends...
    "V[p(o(c))] == V[n(c)]",  // ...in reverse order
    "n(n(n(c))) == c",        // three corners per triangle
    "u(s(c)) == c",           // swing and unswing are inverse
};

// Evaluates the watch at one corner without keeping a path (watches run over every corner after
// every step). Returns 1 pass, 0 skip (boundary), -1 fail.
int watchOne(const CornerExpr& w, const Mesh& mesh, std::int32_t c, const ExprContext& ctx) {
    const ExprBinding b{"c", ExprValue{ValueKind::Corner, c, {}, false}};
    ExprEvaluator ev(w, mesh, std::span(&b, 1), ctx, nullptr);
    const auto v = ev.run();
    if (v) return v->truth ? 1 : -1;
    return ev.error().kind == ExprError::Kind::Boundary ? 0 : -1;
}

template <class Corners>
WatchReport checkWatchOver(const CornerExpr& w, const Mesh& mesh, const Corners& corners,
                           const ExprContext& ctx) {
    WatchReport rep;
    if (!w.isComparison()) {
        rep.ok = false;
        rep.message = "a watch must be a comparison, e.g. o(o(c)) == c";
        return rep;
    }
    for (std::int32_t c : corners) {
        const int outcome = watchOne(w, mesh, c, ctx);
        if (outcome == 0) {
            ++rep.skipped;
            continue;
        }
        ++rep.checked;
        if (outcome < 0) {
            rep.ok = false;
            rep.corner = c;
            rep.failure = w.evaluateAt(mesh, c, ctx);  // again, with the path, for the report
            rep.message = "fails at c = " + std::to_string(c) + ": " + escapeControls(w.text()) +
                          (rep.failure.ok() ? " is false"
                                            : " cannot be evaluated: " + rep.failure.error.message);
            return rep;
        }
    }
    rep.message =
        "holds for " + std::to_string(rep.checked) + " corner" + (rep.checked == 1 ? "" : "s") +
        (rep.skipped ? " (" + std::to_string(rep.skipped) + " on the boundary skipped)" : "");
    return rep;
}

struct CornerRange {
    std::int32_t n;
    struct It {
        std::int32_t c;
        std::int32_t operator*() const { return c; }
        It& operator++() {
            ++c;
            return *this;
        }
        bool operator!=(const It& o) const { return c != o.c; }
    };
    It begin() const { return {0}; }
    It end() const { return {n}; }
};

}  // namespace

WatchReport checkWatch(const CornerExpr& watch, const Mesh& mesh, const ExprContext& context) {
    return checkWatchOver(watch, mesh, CornerRange{mesh.numCorners()}, context);
}

WatchReport checkWatchAt(const CornerExpr& watch, const Mesh& mesh, std::int32_t c,
                         const ExprContext& context) {
    const std::int32_t one[1] = {c};
    return checkWatchOver(watch, mesh, std::span<const std::int32_t>(one), context);
}

WatchReport checkWatchOn(const CornerExpr& watch, const Mesh& mesh,
                         std::span<const std::int32_t> corners, const ExprContext& context) {
    return checkWatchOver(watch, mesh, corners, context);
}

std::span<const char* const> standardWatches() { return kStandardWatches; }

}  // namespace dlab
