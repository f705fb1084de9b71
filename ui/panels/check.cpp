// The Check tab and its canvas layer: a mesh made elsewhere, opened, checked exactly
// (checkMesh), every problem listed and drawn, and Lawson's flip algorithm stepped on it by the
// engine; the check of the mesh at the current step beside the one as opened.
#include "core/engine/mesh_diff.h"
#include "core/engine/mesh_read.h"
#include "ui/panels/canvas_looks.h"
#include "ui/panels/panels.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>

namespace dlab::ui {

namespace {

using Kind = MeshProblem::Kind;

// The live check runs on every step up to this many triangles; above, on request.
constexpr std::int32_t kLiveCheckTriangles = 20000;

// The mesh at this step can be checked: a flip run on an opened mesh, or an insertion run
// after Finalize (before it, ghost or super triangles are part of the table).
bool checkableNow(const Engine& e) { return !e.batch() && (e.repairs() || e.atEnd()); }

bool nowIsCurrent(const AppState& st) { return st.meshCheck.nowVersion == st.engine.version(); }

void checkNow(AppState& st) {
    AppState::MeshCheck& mc = st.meshCheck;
    CheckOptions o;
    o.indexBase = mc.open ? mc.indexBase : 0;
    o.hasOpposites = true;  // the engine's own O, checked against its triangles
    // The check is of the triangulation of the input points: the ghost vertex's placeholder
    // (there until Finalize) is no unused point of it.
    const Mesh& m = st.engine.mesh();
    const std::size_t n = st.engine.points().size();
    if (m.G.size() > n) {
        Mesh input = m;
        input.G.resize(n);
        mc.now = checkMesh(input, o);
    } else {
        mc.now = checkMesh(m, o);
    }
    mc.nowVersion = st.engine.version();
}

// The check of the current step, computed when it is cheap or asked for; null when none.
const CheckReport* currentCheck(AppState& st) {
    const Engine& e = st.engine;
    if (!checkableNow(e)) return nullptr;
    if (!nowIsCurrent(st) && e.mesh().numTriangles() <= kLiveCheckTriangles) checkNow(st);
    return nowIsCurrent(st) ? &st.meshCheck.now : nullptr;
}

Vec2 vertexAt(const AppState& st, std::int32_t v) { return st.engine.points()[v]; }

bool validVertex(const AppState& st, std::int32_t v) {
    return v >= 0 && v < static_cast<std::int32_t>(st.engine.points().size());
}

// The triangle's three vertices as the mesh had them when it was opened.
bool openedTriangle(const AppState& st, std::int32_t t, std::int32_t out[3]) {
    const auto& V = st.meshCheck.openedV;
    if (t < 0 || 3 * static_cast<std::size_t>(t) + 2 >= V.size()) return false;
    for (int k = 0; k < 3; ++k) {
        out[k] = V[3 * t + k];
        if (!validVertex(st, out[k])) return false;
    }
    return true;
}

// The box of a problem's elements (as opened), for the view to show it.
bool problemBox(const AppState& st, const MeshProblem& p, Vec2& lo, Vec2& hi) {
    bool any = false;
    auto add = [&](std::int32_t v) {
        if (!validVertex(st, v)) return;
        const Vec2 q = vertexAt(st, v);
        lo = any ? Vec2{std::min(lo.x, q.x), std::min(lo.y, q.y)} : q;
        hi = any ? Vec2{std::max(hi.x, q.x), std::max(hi.y, q.y)} : q;
        any = true;
    };
    for (std::int32_t v : p.vertices) add(v);
    for (std::int32_t t : p.triangles) {
        std::int32_t tv[3];
        if (openedTriangle(st, t, tv))
            for (std::int32_t v : tv) add(v);
    }
    return any;
}

void pick(AppState& st, std::int32_t index) {
    st.meshCheck.picked = index;
    const MeshProblem& p = st.meshCheck.report.problems[static_cast<std::size_t>(index)];
    Vec2 lo, hi;
    if (!problemBox(st, p, lo, hi)) return;
    // A margin of the box's own size, so that the neighbourhood shows too.
    const double w = std::max(hi.x - lo.x, hi.y - lo.y) * 0.6 + 1e-9;
    st.view.fit({lo.x - w, lo.y - w}, {hi.x + w, hi.y + w});
}

void ShowProblemList(AppState& st, const CheckReport& r, bool clickable, const char* id) {
    constexpr std::size_t kListed = 500;
    ImGui::BeginChild(id, ImVec2(0, clickable ? ImGui::GetContentRegionAvail().y * 0.55f : 0),
                      true);
    for (std::size_t i = 0; i < std::min(r.problems.size(), kListed); ++i) {
        const MeshProblem& p = r.problems[i];
        const std::string line = std::string(toString(p.kind)) + ": " + p.message;
        ImGui::PushStyleColor(ImGuiCol_Text, blocksRepair(p.kind) ? ImVec4(0.75f, 0.1f, 0.1f, 1)
                                             : p.kind == Kind::NotDelaunay
                                                 ? ImVec4(0.65f, 0.3f, 0.0f, 1)
                                                 : ImVec4(0.3f, 0.3f, 0.35f, 1));
        ImGui::PushID(static_cast<int>(i));
        if (clickable) {
            if (ImGui::Selectable(line.c_str(),
                                  st.meshCheck.picked == static_cast<std::int32_t>(i)))
                pick(st, static_cast<std::int32_t>(i));
            if (i == 0) RecordItem(st, "check-first-problem");
        } else {
            ImGui::TextWrapped("%s", line.c_str());
        }
        ImGui::PopID();
        ImGui::PopStyleColor();
    }
    if (r.problems.size() > kListed)
        ImGui::TextDisabled("... and %zu more (dtlab check --all lists them all)",
                            r.problems.size() - kListed);
    ImGui::EndChild();
}

// The circle through triangle (a, b, c), in world coordinates (drawing only: the decision that
// the edge is not Delaunay was the exact test's).
bool circumcircle(Vec2 a, Vec2 b, Vec2 c, Vec2& centre, double& radius) {
    const double bx = b.x - a.x, by = b.y - a.y, cx = c.x - a.x, cy = c.y - a.y;
    const double d = 2 * (bx * cy - by * cx);
    if (d == 0) return false;
    const double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
    centre = {a.x + (cy * b2 - by * c2) / d, a.y + (bx * c2 - cx * b2) / d};
    radius = std::hypot(centre.x - a.x, centre.y - a.y);
    return std::isfinite(radius);
}

void DrawEdge(const AppState& st, ImDrawList* dl, std::int32_t a, std::int32_t b, ImU32 col,
              float w) {
    if (!validVertex(st, a) || !validVertex(st, b)) return;
    dl->AddLine(toIm(st.view.toScreen(vertexAt(st, a))), toIm(st.view.toScreen(vertexAt(st, b))),
                col, w);
}

// A triangle filled and hatched (overlaps), or only outlined.
void DrawTriangle(const AppState& st, ImDrawList* dl, const std::int32_t tv[3], ImU32 col,
                  bool hatch, ImU32 fill) {
    ImVec2 p[3];
    for (int k = 0; k < 3; ++k) p[k] = toIm(st.view.toScreen(vertexAt(st, tv[k])));
    dl->AddTriangle(p[0], p[1], p[2], col, 2.0f);
    if (!hatch) return;
    dl->AddTriangleFilled(p[0], p[1], p[2], fill);
    // Lines x + y = s across the triangle, 8 pixels apart, clipped to it.
    float lo = p[0].x + p[0].y, hi = lo;
    for (const ImVec2& q : p) {
        lo = std::min(lo, q.x + q.y);
        hi = std::max(hi, q.x + q.y);
    }
    for (float s = lo + 4; s < hi && s < lo + 4000; s += 8) {
        ImVec2 hit[2];
        int n = 0;
        for (int k = 0; k < 3 && n < 2; ++k) {
            const ImVec2 u = p[k], v = p[(k + 1) % 3];
            const float fu = u.x + u.y - s, fv = v.x + v.y - s;
            if ((fu < 0) == (fv < 0) || fu == fv) continue;
            const float t = fu / (fu - fv);
            hit[n++] = ImVec2(u.x + t * (v.x - u.x), u.y + t * (v.y - u.y));
        }
        if (n == 2) dl->AddLine(hit[0], hit[1], col, 1.0f);
    }
}

// One problem: its edge and circle (not Delaunay), its triangles (hatched where they overlap),
// its vertices ringed, its outline (holes, a non-convex outline).
void DrawProblem(AppState& st, ImDrawList* dl, const MeshProblem& p, ImU32 col, bool asOpened) {
    if (p.kind == Kind::NotDelaunay && p.vertices.size() == 3 && p.triangles.size() == 2) {
        // The circle and the vertex inside it; the edge itself only when picked (a flip's new
        // edge is drawn red too).
        if (asOpened) DrawEdge(st, dl, p.vertices[0], p.vertices[1], col, 3.0f);
        std::int32_t tv[3];
        bool have = true;
        if (asOpened) {
            have = openedTriangle(st, p.triangles[0], tv);
        } else {
            const auto& V = st.engine.mesh().V;
            for (int k = 0; k < 3; ++k) tv[k] = V[3 * p.triangles[0] + k];
        }
        Vec2 c;
        double r = 0;
        if (have &&
            circumcircle(vertexAt(st, tv[0]), vertexAt(st, tv[1]), vertexAt(st, tv[2]), c, r)) {
            dl->AddCircle(toIm(st.view.toScreen(c)), static_cast<float>(r * st.view.scale), col, 96,
                          1.5f);
        }
        if (validVertex(st, p.vertices[2]))
            dl->AddCircleFilled(toIm(st.view.toScreen(vertexAt(st, p.vertices[2]))), 5.0f, col);
        return;
    }
    if (p.kind == Kind::Hole) {  // its loop (or the hull edge no triangle has)
        const std::size_t n = p.vertices.size();
        for (std::size_t i = 0; n >= 2 && i < (n == 2 ? 1 : n); ++i)
            DrawEdge(st, dl, p.vertices[i], p.vertices[(i + 1) % n], col, 3.0f);
    }
    for (std::int32_t t : p.triangles) {
        std::int32_t tv[3];
        if (openedTriangle(st, t, tv))
            DrawTriangle(st, dl, tv, col, p.kind == Kind::Overlap, useLook(st, Mark::MeshProblem));
    }
    for (std::int32_t v : p.vertices) {
        if (validVertex(st, v))
            dl->AddCircle(toIm(st.view.toScreen(vertexAt(st, v))), 7.0f, col, 16, 2.0f);
    }
}

void ShowDiffControls(AppState& st) {
    AppState::MeshCheck& mc = st.meshCheck;
    ImGui::Checkbox("Edges that differ from the Delaunay triangulation", &mc.showDiff);
    RecordItem(st, "check-diff");
    if (!mc.showDiff) return;
    if (mc.diffVersion != st.engine.version()) {
        try {
            mc.diff = diffWithDelaunay(st.engine.mesh());
        } catch (const std::exception& e) {
            mc.diff = {};
            st.log(Message::Level::Warning, std::string("difference not computed: ") + e.what());
        }
        mc.diffVersion = st.engine.version();
    }
    ImGui::TextColored(ImVec4(0.8f, 0.12f, 0.16f, 1), "%zu edges only in this mesh",
                       mc.diff.onlyGiven.size());
    ImGui::SameLine();
    ImGui::TextColored(ImVec4(0.08f, 0.55f, 0.24f, 1), "%zu only in the Delaunay triangulation",
                       mc.diff.onlyDelaunay.size());
    if (mc.diff.cocircular > 0)
        ImGui::TextDisabled("(%lld of them across four points on one circle: either is Delaunay)",
                            static_cast<long long>(mc.diff.cocircular));
}

// The triangles whose three vertices exist, in the file's order, with O as the check finds it
// among them: what can be drawn of a mesh some of whose triangles name missing vertices.
Inserter::StartMesh drawableTriangles(const Mesh& mesh, const CheckOptions& options) {
    Mesh shown;
    shown.G = mesh.G;
    for (std::size_t t = 0; t + 2 < mesh.V.size(); t += 3) {
        bool exists = true;
        for (std::size_t k = 0; k < 3; ++k)
            exists = exists && mesh.V[t + k] >= 0 && mesh.V[t + k] < mesh.numVertices();
        if (exists) shown.V.insert(shown.V.end(), mesh.V.begin() + t, mesh.V.begin() + t + 3);
    }
    shown.O.assign(shown.V.size(), kNone);
    CheckOptions o = options;
    o.hasOpposites = false;
    CheckReport r = checkMesh(shown, o);
    return Inserter::StartMesh{std::move(shown.V), std::move(r.opposites)};
}

}  // namespace

bool openMeshFile(AppState& st, const std::string& path) {
    ImportedMesh im;
    try {
        im = readMeshFile(path);
    } catch (const std::exception& e) {
        st.log(Message::Level::Error, std::string(e.what()) + " (nothing was changed)");
        return false;
    }
    CheckOptions o;
    o.hasOpposites = im.hasOpposites;
    o.indexBase = im.indexBase;
    CheckReport report = checkMesh(im.mesh, o);
    const bool triangulation = report.isTriangulation();
    // Triangles naming vertices that do not exist cannot be drawn: the others are shown.
    const std::size_t missing = report.count(Kind::VertexRange);
    Inserter::StartMesh start;
    if (missing == 0) {
        start.V = im.mesh.V;
        start.O = report.opposites;
    } else {
        start = drawableTriangles(im.mesh, o);
    }
    const std::size_t shown = start.V.size() / 3;
    std::string error;
    std::vector<Vec2> previous = st.engine.points();
    if (!st.engine.resetRepair(im.mesh.G, std::move(start), triangulation, error)) {
        st.log(Message::Level::Error, path + ": " + error + " (nothing was changed)");
        return false;
    }
    if (!previous.empty()) {
        st.undoPoints.push_back(std::move(previous));
        st.redoPoints.clear();
    }
    AppState::MeshCheck& mc = st.meshCheck;
    mc = {};
    mc.open = true;
    mc.path = path;
    mc.format = im.format;
    mc.warnings = im.warnings;
    mc.indexBase = im.indexBase;
    mc.openedV = std::move(im.mesh.V);
    mc.report = std::move(report);
    mc.run = st.engine.run();
    st.source = path;
    st.selection = {};
    st.run.running = false;
    st.fitPending = true;
    st.pendingTab = "check";
    for (const std::string& w : mc.warnings) st.log(Message::Level::Warning, path + ": " + w);
    st.log(Message::Level::Info,
           path + " (" + mc.format + "): " + mc.report.summary() +
               (triangulation ? mc.report.isDelaunay()
                                    ? ""
                                    : "; step through Lawson's flip algorithm to repair it"
                              : "; shown as it is: these problems block a repair by flips"));
    if (missing != 0)
        st.log(
            Message::Level::Warning,
            path + ": " + std::to_string(missing) +
                (missing == 1 ? " triangle names" : " triangles name") +
                " a vertex that does not exist (listed in the Check tab, not drawn); the other " +
                std::to_string(shown) +
                " are shown, numbered in their order in the file without those");
    return true;
}

void ShowCheck(AppState& st) {
    AppState::MeshCheck& mc = st.meshCheck;
    const Engine& e = st.engine;
    if (mc.open && mc.run != e.run()) mc.open = false;  // other points or options since
    if (mc.open) {
        ImGui::TextWrapped("%s (%s), as opened:", mc.path.c_str(), mc.format.c_str());
        ImGui::TextWrapped("%s", mc.report.summary().c_str());
        RecordItem(st, "check-summary");
        ShowProblemList(st, mc.report, true, "##opened");
    } else {
        ImGui::TextWrapped(
            "Open a triangulation made by any program (File > Open: Triangle's .ele with its "
            ".node and .neigh, .off, .obj, a corner table as .corners or .json, Delaunator's "
            "JSON) to check it exactly, see every problem and repair it by flips.");
    }
    ImGui::Separator();
    const CheckReport* now = currentCheck(st);
    if (!checkableNow(e)) {
        ImGui::TextDisabled("The mesh is checked once the run has finished (Finalize).");
        return;
    }
    if (!now) {
        if (ImGui::Button("Check the mesh at this step")) checkNow(st);
        RecordItem(st, "check-now");
        now = nowIsCurrent(st) ? &mc.now : nullptr;
        if (!now) return;
    }
    ImGui::Text("At op %zu:", e.position());
    ImGui::SameLine();
    ImGui::TextWrapped("%s", now->summary().c_str());
    RecordItem(st, "check-now-summary");
    if (e.repairs() && !e.atEnd()) {
        ImGui::TextDisabled("%zu edges wait on the flip stack; %lld flips so far",
                            e.inserter().flipStack().size(),
                            static_cast<long long>(e.inserter().stats().flips));
    } else if (e.repairs()) {
        ImGui::TextDisabled("the flip algorithm made %lld flips in %lld in-circle tests",
                            static_cast<long long>(e.inserter().stats().flips),
                            static_cast<long long>(e.inserter().stats().inCircleTests));
    }
    ShowDiffControls(st);
    if (!mc.open) ShowProblemList(st, *now, false, "##now");
}

void DrawCheckOverlay(AppState& st, ImDrawList* dl) {
    AppState::MeshCheck& mc = st.meshCheck;
    if (mc.open && mc.run != st.engine.run()) mc.open = false;
    if (mc.showDiff && mc.diffVersion == st.engine.version()) {
        for (const MeshEdge& ed : mc.diff.onlyGiven)
            DrawEdge(st, dl, ed.first, ed.second, useLook(st, Mark::OnlyInMesh), 2.5f);
        for (const MeshEdge& ed : mc.diff.onlyDelaunay)
            DrawEdge(st, dl, ed.first, ed.second, useLook(st, Mark::OnlyInDelaunay), 2.5f);
    }
    // What is wrong now: each edge that is not Delaunay at this step with its circle; the
    // problems that block a repair as opened (the mesh is shown as it is).
    constexpr std::size_t kDrawn = 2000;
    std::size_t drawn = 0;
    if (nowIsCurrent(st) && checkableNow(st.engine)) {
        for (const MeshProblem& p : mc.now.problems)
            if (p.kind == Kind::NotDelaunay && drawn++ < kDrawn)
                DrawProblem(st, dl, p, useLook(st, Mark::MeshNotDelaunay), false);
    }
    if (!mc.open) return;
    for (const MeshProblem& p : mc.report.problems)
        if (blocksRepair(p.kind) && drawn++ < kDrawn)
            DrawProblem(st, dl, p, useLook(st, Mark::MeshProblem) | IM_COL32_A_MASK, true);
    if (mc.picked >= 0 && mc.picked < static_cast<std::int32_t>(mc.report.problems.size()))
        DrawProblem(st, dl, mc.report.problems[static_cast<std::size_t>(mc.picked)],
                    useLook(st, Mark::MeshPicked), true);
}

}  // namespace dlab::ui
