// Fuzz target: corner expressions (parse, evaluate, watches) on sound and corrupt meshes.
//
// Byte [0] picks the mesh (a finished exact-mode mesh, a mid-run super-mode mesh with virtual
// vertices, an empty one, and the same meshes with corrupted V/O) and the corner bound to c;
// the rest is the expression text. Either outcome is checked: an error has a message on one
// line and a column inside the text; a value is in range for its kind, and the path of corners
// stays inside the mesh unless the mesh is corrupt or c is bound outside it.
#include "tests/fuzz/fuzz_common.h"

#include "core/engine/inserter.h"
#include "core/teaching/corner_expr.h"

#include <climits>
#include <string>

namespace {

using namespace dlab;
using dlab::fuzz::require;

struct Fixture {
    Mesh mesh;
    ExprContext context;
    bool corrupt = false;
};

const std::vector<Vec2> kPoints{{0, 0}, {4, 0}, {4, 4}, {0, 4}, {2, 2},
                                {1, 3}, {3, 1}, {2, 0}, {2, 2}};

std::vector<Fixture> makeFixtures() {
    std::vector<Fixture> out;
    {
        Inserter ins(kPoints);
        ins.run();
        out.push_back({ins.mesh(), {}, false});
    }
    {
        InsertOptions opt;
        opt.boundary = Boundary::Super;
        Inserter ins(kPoints, opt);
        Journal journal(ins);
        for (int i = 0; i < 40 && journal.forward(); ++i) {}
        out.push_back({ins.mesh(), {ins.firstVirtual(), false}, false});
        Inserter ghost(kPoints);
        Journal j2(ghost);
        for (int i = 0; i < 30 && j2.forward(); ++i) {}
        out.push_back({ghost.mesh(), {ghost.firstVirtual(), true}, false});
    }
    out.push_back({Mesh{}, {}, false});
    // Corrupt copies: O pointing anywhere, V out of range, V and O of different sizes.
    const std::size_t sound = out.size();
    for (std::size_t k = 0; k < sound; ++k) {
        Fixture f = out[k];
        f.corrupt = true;
        std::int32_t x = 0;
        for (std::int32_t& o : f.mesh.O)
            o = (++x % 3 == 0) ? INT_MIN : (x % 3 == 1 ? INT_MAX : -7 * x);
        for (std::size_t i = 0; i < f.mesh.V.size(); i += 4)
            f.mesh.V[i] = -100 + static_cast<std::int32_t>(i);
        if (f.mesh.O.size() >= 2) f.mesh.O.resize(f.mesh.O.size() - 2);
        out.push_back(std::move(f));
    }
    return out;
}

bool oneLine(const std::string& s) { return s.find_first_of("\r\n") == std::string::npos; }

// boundInside: c is -1 or a corner of the mesh (a bare "c" bound outside it is the caller's value).
void checkResult(const ExprResult& r, const Fixture& f, std::size_t textSize, bool boundInside) {
    const std::int64_t corners = f.mesh.numCorners(), vertices = f.mesh.numVertices();
    if (!r.ok()) {
        require(!r.error.message.empty() && oneLine(r.error.message),
                "an evaluation error is one line", r.error.message);
        require(r.error.column <= textSize, "an evaluation error points into the text",
                r.error.message);
    } else if (!f.corrupt && boundInside) {
        const ExprValue& v = *r.value;
        if (v.kind == ValueKind::Corner)
            require(v.i >= -1 && v.i < corners, "a corner value is -1 or a corner");
        if (v.kind == ValueKind::Vertex)
            require(v.i >= 0 && v.i < vertices, "a vertex value is a vertex");
        if (v.kind == ValueKind::Triangle)
            require(v.i >= 0 && v.i < corners / 3, "a triangle value is a triangle");
        require(oneLine(formatValue(v)), "a value formats on one line", formatValue(v));
    }
    if (f.corrupt || !boundInside) return;
    for (const PathStep& s : r.path) {
        require(s.from >= kNone && s.from < std::max(corners, vertices),
                "a path step starts inside the mesh");
        require(s.to >= kNone && s.to < std::max(corners, vertices),
                "a path step ends inside the mesh");
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::vector<Fixture> fixtures = makeFixtures();
    if (size == 0) return 0;
    const Fixture& f = fixtures[data[0] % fixtures.size()];
    const std::string_view text = dlab::fuzz::asText(data + 1, size - 1);

    ExprError error;
    const auto expr = CornerExpr::parse(text, &error);
    if (!expr) {
        require(!error.message.empty() && oneLine(error.message), "a syntax error is one line",
                error.message);
        require(error.column <= text.size(), "a syntax error points into the text", error.message);
        return 0;
    }
    require(expr->text() == text, "the parsed expression keeps its text");
    // c bound to corners inside, at the ends of, and outside the mesh.
    const std::int32_t corners = f.mesh.numCorners();
    for (const std::int32_t c : {0, corners - 1, data[0] / 16 % 7, corners, kNone, INT_MAX}) {
        checkResult(expr->evaluateAt(f.mesh, c, f.context), f, text.size(),
                    c >= kNone && c < corners);
    }
    if (expr->isComparison() && expr->uses("c")) {
        const WatchReport w = checkWatch(*expr, f.mesh, f.context);
        require(oneLine(w.message), "a watch report is one line", w.message);
        require(w.ok || (w.corner >= 0 && w.corner < corners),
                "a failing watch names a corner of the mesh");
    }
    return 0;
}
