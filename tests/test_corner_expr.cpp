// Corner expressions: both notations agree with core/engine/mesh.h's operators, paths are recorded,
// every kind of error is precise, watches find the first broken corner, and random strings or a
// corrupted mesh never crash the parser or the evaluator.
#include "core/engine/generators.h"
#include "core/engine/inserter.h"
#include "core/teaching/corner_expr.h"

#include <gtest/gtest.h>

#include <climits>
#include <random>

using namespace dlab;

namespace {

Mesh finishedMesh(const std::vector<Vec2>& pts) {
    Inserter ins(pts);
    ins.run();
    return ins.mesh();
}

// Two triangles sharing an edge: 6 corners, 4 of them on the boundary.
Mesh twoTriangles() { return finishedMesh({{0, 0}, {4, 0}, {4, 3}, {0, 3}}); }

CornerExpr parse(std::string_view text) {
    ExprError e;
    auto x = CornerExpr::parse(text, &e);
    EXPECT_TRUE(x) << text << ": " << e.message;
    return x.value_or(CornerExpr{});
}

ExprError syntaxError(std::string_view text) {
    ExprError e;
    EXPECT_FALSE(CornerExpr::parse(text, &e)) << text;
    EXPECT_EQ(e.kind, ExprError::Kind::Syntax) << text;
    EXPECT_FALSE(e.message.empty());
    EXPECT_LE(e.column, text.size()) << text;
    return e;
}

ExprError evalError(const Mesh& m, std::string_view text, std::int32_t c = 0) {
    const ExprResult r = parse(text).evaluateAt(m, c);
    EXPECT_FALSE(r.ok()) << text << " gave " << (r.ok() ? formatValue(*r.value) : "");
    return r.error;
}

std::int32_t apply(const Mesh& m, char op, std::int32_t c) {
    switch (op) {
        case 'n': return m.n(c);
        case 'p': return m.p(c);
        case 'o': return m.o(c);
        case 'l': return m.l(c);
        case 'r': return m.r(c);
        case 's': return m.s(c);
        case 'u': return m.u(c);
        case 't': return m.t(c);
        case 'v': return m.v(c);
    }
    return -2;
}

}  // namespace

TEST(CornerExpr, BothNotationsAgreeWithTheMeshOperators) {
    const Mesh m = finishedMesh(generatePoints(Generator::Uniform, 60, 4));
    for (char op : std::string("nplorsutv")) {
        const std::string o(1, op);
        const CornerExpr call = parse(o + "(c)"), dot = parse("c." + o);
        for (std::int32_t c = 0; c < m.numCorners(); ++c) {
            const ExprResult a = call.evaluateAt(m, c), b = dot.evaluateAt(m, c);
            ASSERT_TRUE(a.ok()) << o << " at " << c << ": " << a.error.message;
            ASSERT_TRUE(b.ok());
            EXPECT_EQ(a.value->i, apply(m, op, c)) << op << "(" << c << ")";
            EXPECT_EQ(b.value->i, a.value->i);
            EXPECT_EQ(a.value->kind, op == 't'   ? ValueKind::Triangle
                                     : op == 'v' ? ValueKind::Vertex
                                                 : ValueKind::Corner);
            ASSERT_EQ(a.path.size(), 1u);
            EXPECT_EQ(a.path[0].op, op);
            EXPECT_EQ(a.path[0].from, c);
            EXPECT_EQ(a.path[0].to, a.value->i);
        }
    }
    // Tables are the same as the operators; G gives the coordinates.
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        EXPECT_EQ(parse("V[c]").evaluateAt(m, c).value->i, m.V[c]);
        EXPECT_EQ(parse("O[ c ]").evaluateAt(m, c).value->i, m.O[c]);
        const ExprResult g = parse("G[V[c]]").evaluateAt(m, c);
        ASSERT_TRUE(g.ok());
        EXPECT_EQ(g.value->kind, ValueKind::Point);
        EXPECT_TRUE(g.value->point == m.G[m.V[c]]);
    }
}

TEST(CornerExpr, NestedAndChainedFormsGiveTheSameValueAndPath) {
    const Mesh m = finishedMesh(generatePoints(Generator::Uniform, 60, 4));
    std::int32_t interior = kNone;
    for (std::int32_t c = 0; c < m.numCorners() && interior == kNone; ++c) {
        if (m.O[next(c)] != kNone && m.O[prev(m.O[next(c)])] != kNone && m.O[prev(c)] != kNone)
            interior = c;
    }
    ASSERT_NE(interior, kNone);
    const std::string k = std::to_string(interior);
    // A corner whose n(c).o exists.
    for (std::int32_t c = 0; c < m.numCorners(); ++c) {
        const std::int32_t x = m.O[next(c)];
        if (x == kNone || m.O[prev(x)] == kNone) continue;
        const std::int32_t expect = m.r(m.o(m.n(c)));
        const std::string s = std::to_string(c);
        const ExprResult a = parse("r(o(n(" + s + ")))").evaluate(m),
                         b = parse(s + ".n.o.r").evaluate(m), d = parse("c.n.o.r").evaluateAt(m, c);
        ASSERT_TRUE(a.ok() && b.ok() && d.ok());
        EXPECT_EQ(a.value->i, expect);
        EXPECT_EQ(b.value->i, expect);
        EXPECT_EQ(d.value->i, expect);
        ASSERT_EQ(a.path.size(), 3u);
        EXPECT_EQ(a.path[0].from, c);
        EXPECT_EQ(a.path[0].to, next(c));
        EXPECT_EQ(a.path[1].op, 'o');
        EXPECT_EQ(a.path[1].to, x);
        EXPECT_EQ(a.path[2].op, 'r');
        EXPECT_EQ(a.path[2].to, expect);
        for (std::size_t i = 0; i < 3; ++i) {
            EXPECT_EQ(a.path[i].op, b.path[i].op);
            EXPECT_EQ(a.path[i].to, b.path[i].to);
        }
    }
    // Parentheses, spaces and mixing.
    EXPECT_EQ(parse(" ( o ( " + k + " ) ) . n ").evaluate(m).value->i, m.n(m.o(interior)));
    EXPECT_EQ(parse("n(" + k + ".o).p").evaluate(m).value->i, m.p(m.n(m.o(interior))));
    EXPECT_EQ(parse("V[O[" + k + "]]").evaluate(m).value->i, m.V[m.O[interior]]);
}

TEST(CornerExpr, ComparisonsAndIdentities) {
    const Mesh m = twoTriangles();
    ASSERT_EQ(m.numCorners(), 6);
    std::int32_t inner = kNone;
    for (std::int32_t c = 0; c < 6; ++c) {
        if (m.O[c] != kNone) inner = c;
    }
    ASSERT_NE(inner, kNone);
    const ExprResult r = parse("o(o(c)) == c").evaluateAt(m, inner);
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r.value->kind, ValueKind::Truth);
    EXPECT_TRUE(r.value->truth);
    EXPECT_EQ(formatValue(*r.value), "true");
    // Both sides' moves are in the path, marked by side.
    ASSERT_EQ(r.path.size(), 2u);
    EXPECT_EQ(r.path[0].side, 0);
    const ExprResult s = parse("V[n(o(c))] = V[p(c)]").evaluateAt(m, inner);
    ASSERT_TRUE(s.ok());
    EXPECT_TRUE(s.value->truth);
    EXPECT_EQ(s.path.back().side, 1);
    EXPECT_FALSE(parse("c.n != n(c)").evaluateAt(m, 4).value->truth);
    EXPECT_TRUE(parse("o(c) == -1").evaluateAt(m, next(inner)).value->truth)
        << "the hull corners face nothing";
    EXPECT_TRUE(parse("G[V[c]] == G[V[c.n.p]]").evaluateAt(m, 2).value->truth);
    EXPECT_TRUE(parse("t(c) == 1").evaluateAt(m, 4).value->truth);
    // A bare integer keeps its number kind and prints as such.
    const ExprResult seven = parse("7").evaluate(m);
    ASSERT_TRUE(seven.ok());
    EXPECT_EQ(seven.value->kind, ValueKind::Number);
    EXPECT_EQ(formatValue(*seven.value), "7");
    EXPECT_EQ(formatValue(*parse("G[2]").evaluate(m).value), "(4, 3)");
}

TEST(CornerExpr, BoundaryRangeAndTypeErrorsArePrecise) {
    const Mesh m = twoTriangles();
    std::int32_t hull = kNone;
    for (std::int32_t c = 0; c < 6 && hull == kNone; ++c) {
        if (m.O[c] == kNone) hull = c;
    }
    const std::string h = std::to_string(hull);
    ExprError e = evalError(m, "o(" + h + ").n");
    EXPECT_EQ(e.kind, ExprError::Kind::Boundary);
    EXPECT_EQ(e.message, "o(" + h + ") is -1 (boundary): cannot apply n");
    EXPECT_EQ(e.column, 0u);
    e = evalError(m, "n(" + h + ".o)");
    EXPECT_EQ(e.message, h + ".o is -1 (boundary): cannot apply n");
    EXPECT_EQ(e.column, 2u);
    e = evalError(m, "c.o.n", hull);
    EXPECT_EQ(e.message, "c.o is -1 (boundary): cannot apply n");

    e = evalError(m, "99.n");
    EXPECT_EQ(e.kind, ExprError::Kind::Range);
    EXPECT_EQ(e.message, "corner 99 out of range (0..5)");
    EXPECT_EQ(evalError(m, "c.n", 6).message, "corner 6 out of range (0..5)");
    EXPECT_EQ(evalError(m, "-5.n").message, "corner -5 out of range (0..5)");
    EXPECT_EQ(evalError(m, "G[4]").message, "vertex 4 out of range (0..3)");
    EXPECT_EQ(evalError(Mesh{}, "0.n").message, "corner 0 out of range (the mesh has no corners)");
    e = evalError(m, "x.n");
    EXPECT_EQ(e.kind, ExprError::Kind::Range);
    EXPECT_NE(e.message.find("unknown name 'x'"), std::string::npos);
    EXPECT_NE(parse("c").evaluate(m).error.message.find("no corner is selected"),
              std::string::npos);

    e = evalError(m, "V[c].n");
    EXPECT_EQ(e.kind, ExprError::Kind::Type);
    EXPECT_NE(e.message.find("n needs a corner, but V[c] is a vertex"), std::string::npos)
        << e.message;
    e = evalError(m, "G[c]", 1);
    EXPECT_NE(e.message.find("use G[V[c]]"), std::string::npos) << e.message;
    e = evalError(m, "c == V[c]");
    EXPECT_EQ(e.message, "cannot compare a corner (c) with a vertex (V[c])");
    EXPECT_EQ(evalError(m, "G[0] == 0").kind, ExprError::Kind::Type);
    EXPECT_EQ(evalError(m, "t(c).n").kind, ExprError::Kind::Type);
    EXPECT_EQ(evalError(m, "(c == c).n").kind, ExprError::Kind::Type);
    // The path keeps the moves made before the failure (the GUI draws them in red).
    const ExprResult partial = parse("c.n.o.n").evaluateAt(m, hull == 0 ? 2 : prev(hull));
    EXPECT_FALSE(partial.ok());
    EXPECT_EQ(partial.path.size(), 2u);
}

TEST(CornerExpr, SyntaxErrorsNameTheColumn) {
    EXPECT_NE(syntaxError("").message.find("empty"), std::string::npos);
    EXPECT_NE(syntaxError("   ").message.find("empty"), std::string::npos);
    EXPECT_EQ(syntaxError("n(").column, 2u);
    EXPECT_NE(syntaxError("n(7").message.find("missing ')'"), std::string::npos);
    EXPECT_NE(syntaxError("V[7)").message.find("expected ']'"), std::string::npos);
    EXPECT_NE(syntaxError("7.").message.find("expected an operator"), std::string::npos);
    const ExprError q = syntaxError("7.n.q");
    EXPECT_EQ(q.column, 4u);
    EXPECT_EQ(q.message, "unknown operator 'q' (use n p o l r s u t v)");
    EXPECT_NE(syntaxError("o[7]").message.find("O[...]"), std::string::npos);
    EXPECT_NE(syntaxError("V(7)").message.find("square brackets"), std::string::npos);
    EXPECT_NE(syntaxError("n").message.find("needs an argument"), std::string::npos);
    EXPECT_NE(syntaxError("n()").message.find("needs an argument"), std::string::npos);
    EXPECT_NE(syntaxError("1 == 1 == 1").message.find("only one comparison"), std::string::npos);
    EXPECT_NE(syntaxError("7)").message.find("unmatched ')'"), std::string::npos);
    EXPECT_NE(syntaxError("7.5").message.find("whole numbers"), std::string::npos);
    EXPECT_NE(syntaxError("7n").message.find("cannot run into"), std::string::npos);
    EXPECT_NE(syntaxError("n(7 == 7)").message.find("comparison cannot be the argument"),
              std::string::npos);
    EXPECT_NE(syntaxError("99999999999").message.find("too large"), std::string::npos);
    EXPECT_NE(syntaxError("7 ==").message.find("nothing to compare"), std::string::npos);
    EXPECT_NE(syntaxError("c.n\x01").message.find("control"), std::string::npos);
    EXPECT_NE(syntaxError("c.n \xc3\xa9").message.find("ASCII"), std::string::npos);
    EXPECT_NE(
        syntaxError(std::string(200, '(') + "7" + std::string(200, ')')).message.find("nested"),
        std::string::npos);
    EXPECT_NE(syntaxError(std::string(2000, ' ')).message.find("too long"), std::string::npos);
    // The longest chains that fit evaluate fine (no deep recursion trouble).
    std::string chain = "c";
    for (int i = 0; i < 499; ++i) chain += ".n";
    ASSERT_LE(chain.size(), CornerExpr::kMaxLength);
    EXPECT_EQ(parse(chain).evaluateAt(twoTriangles(), 4).value->i, 5);  // 499 = 1 mod 3
    EXPECT_NE(syntaxError(chain + ".n").message.find("too long"), std::string::npos);
}

TEST(CornerExpr, StandardWatchesHoldOnEveryMeshTheInserterMakes) {
    for (Boundary b : {Boundary::Exact, Boundary::Super}) {
        InsertOptions opt;
        opt.boundary = b;
        const auto pts = generatePoints(Generator::Grid, 200, 3);
        Inserter ins(pts, opt);
        Journal j(ins);
        const ExprContext ctx{ins.firstVirtual(), b == Boundary::Exact};
        std::size_t k = 0;
        while (j.forward()) {
            if (++k % 37 != 0 && !ins.done())
                continue;  // mid-run meshes, ghosts included, and the end
            for (const char* w : standardWatches()) {
                const WatchReport r = checkWatch(parse(w), ins.mesh(), ctx);
                ASSERT_TRUE(r.ok) << w << " after op " << j.position() << ": " << r.message;
                EXPECT_EQ(r.checked + r.skipped, ins.mesh().numCorners());
            }
        }
        // After Finalize the hull corners face nothing: the boundary skips are counted.
        const WatchReport r = checkWatch(parse("o(o(c)) == c"), ins.mesh(), ctx);
        EXPECT_GT(r.skipped, 0);
        EXPECT_NE(r.message.find("on the boundary skipped"), std::string::npos);
    }
}

TEST(CornerExpr, WatchReportsTheFirstBrokenCorner) {
    Mesh m = finishedMesh(generatePoints(Generator::Uniform, 50, 8));
    std::int32_t a = kNone;
    for (std::int32_t c = 10; c < m.numCorners() && a == kNone; ++c) {
        if (m.O[c] != kNone) a = c;
    }
    ASSERT_NE(a, kNone);
    const std::int32_t b = m.O[a];
    m.O[a] = next(b);  // break the symmetry at a (and at b's neighbours)
    const WatchReport r = checkWatch(parse("o(o(c)) == c"), m);
    EXPECT_FALSE(r.ok);
    EXPECT_LE(r.corner, std::min(a, next(b)));
    EXPECT_NE(r.message.find("fails at c = " + std::to_string(r.corner)), std::string::npos)
        << r.message;
    EXPECT_TRUE(r.failure.ok());
    EXPECT_FALSE(r.failure.value->truth);
    EXPECT_FALSE(r.failure.path.empty());
    EXPECT_FALSE(checkWatchAt(parse("o(o(c)) == c"), m, a).ok);
    const std::int32_t fine[] = {0, 1, 2};
    if (a > 2 && next(b) > 2 && b > 2) {
        EXPECT_TRUE(checkWatchOn(parse("o(o(c)) == c"), m, fine).ok);
    }
    // Out-of-range O is a failure with the reason, not a skip and not a crash.
    m.O[a] = 100000;
    const WatchReport bad = checkWatchAt(parse("o(o(c)) == c"), m, a);
    EXPECT_FALSE(bad.ok);
    EXPECT_NE(bad.message.find("O[" + std::to_string(a) + "] = 100000 is out of range"),
              std::string::npos)
        << bad.message;
    // Not a comparison: refused with a hint.
    EXPECT_NE(checkWatch(parse("c.n"), m).message.find("must be a comparison"), std::string::npos);
}

TEST(CornerExpr, GhostVertexHasNoCoordinates) {
    const std::vector<Vec2> pts{{0, 0}, {4, 0}, {4, 3}, {0, 3}, {2, 1}};
    Inserter ins(pts);
    Journal j(ins);
    j.forward();  // Start: the first triangle and three ghost triangles
    const ExprContext ctx{ins.firstVirtual(), true};
    const ExprError e = parse("G[5]").evaluate(ins.mesh(), {}, ctx).error;
    EXPECT_EQ(e.message, "vertex 5 is the ghost vertex: it has no coordinates");
}

TEST(CornerExpr, RandomStringsNeverCrash) {
    const Mesh m = finishedMesh(generatePoints(Generator::Uniform, 30, 1));
    Mesh corrupt = m;
    std::mt19937_64 rng(12345);
    for (std::int32_t& o : corrupt.O) {
        const int pick = static_cast<int>(rng() % 6);
        if (pick == 0)
            o = INT_MIN;
        else if (pick == 1)
            o = INT_MAX;
        else if (pick == 2)
            o = -7;
        else if (pick == 3)
            o = static_cast<std::int32_t>(rng() % 1000);
    }
    for (std::int32_t& v : corrupt.V) {
        if (rng() % 4 == 0) v = static_cast<std::int32_t>(rng() % 200) - 100;
    }
    corrupt.O.resize(corrupt.O.size() - 2);  // V and O of different sizes
    const std::string alphabet = "nplorsutvVOGcx()[].=!-0123456789  ";
    std::size_t parsed = 0, evaluated = 0;
    for (int i = 0; i < 60000; ++i) {
        std::string s;
        const std::size_t len = rng() % 24;
        for (std::size_t k = 0; k < len; ++k) {
            s += (i % 10 == 0) ? static_cast<char>(rng() % 256) : alphabet[rng() % alphabet.size()];
        }
        ExprError e;
        const auto x = CornerExpr::parse(s, &e);
        if (!x) {
            ASSERT_FALSE(e.message.empty()) << s;
            ASSERT_LE(e.column, s.size()) << s;
            continue;
        }
        ++parsed;
        for (const Mesh* mesh :
             {static_cast<const Mesh*>(&m), static_cast<const Mesh*>(&corrupt)}) {
            const std::int32_t c = static_cast<std::int32_t>(rng() % 120) - 10;
            const ExprResult r = x->evaluateAt(*mesh, c);
            if (r.ok()) {
                ++evaluated;
            } else {
                ASSERT_FALSE(r.error.message.empty()) << s;
                ASSERT_LE(r.error.column, s.size()) << s;
            }
        }
    }
    EXPECT_GT(parsed, 1000u);  // the generator does produce valid expressions
    EXPECT_GT(evaluated, 500u);
}
