// The statistics panel: points, triangles, flips per insertion and in total, walk steps,
// in-circle tests, a plot of flips per insertion, frame times, and validate() plus an exact
// hull check of the current mesh, with every violation drawn on the canvas.
#include "core/engine/predicates.h"
#include "ui/gui.h"
#include "ui/lesson_player.h"
#include "ui/panels/canvas_looks.h"
#include "ui/panels/panels.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

namespace dlab::ui {

namespace {

bool sameOp(const Op& a, const Op& b) {
    return a.type == b.type && a.vertex == b.vertex && a.a == b.a && a.b == b.b &&
           a.firstChange == b.firstChange;
}

void countOps(RunCounts& s, const Engine& e) {
    const Journal* j = e.journal();
    if (!j) return;
    const auto& ops = j->ops();
    const std::size_t pos = e.position();
    const bool continues =
        s.position <= pos &&
        (s.position == 0 || (s.position <= ops.size() && sameOp(ops[s.position - 1], s.last)));
    if (!continues) s = RunCounts{};
    for (std::size_t k = s.position; k < pos; ++k) {
        const Op& op = ops[k];
        switch (op.type) {
            case OpType::LocateStep:
                ++s.walkSteps;
                ++s.stepsNow;
                break;
            case OpType::Located:
                ++s.locates;
                s.hits += s.stepsNow == 0;
                s.stepsNow = 0;
                break;
            case OpType::Split: ++s.splits; break;
            case OpType::SplitEdge: ++s.edgeSplits; break;
            case OpType::InCircleTest: s.inCircleTests += op.b != kNone; break;
            case OpType::Flip:
                ++s.flips;
                ++s.flipsNow;
                break;
            case OpType::Inserted:
                ++s.inserted;
                s.flipsPerInsertion.push_back(static_cast<float>(s.flipsNow));
                s.flipsNow = 0;
                break;
            case OpType::SkipDuplicate:
                ++s.duplicates;
                s.stepsNow = 0;
                s.flipsNow = 0;
                break;
            default: break;
        }
    }
    s.position = pos;
    if (pos > 0) s.last = ops[pos - 1];
}

// The boundary of the real triangles, checked exactly: every boundary vertex turns left or goes
// straight (a convex hull), and Euler's count T = 2n - h - 2 of a triangulated disc holds.
// With local Delaunay on every interior edge this makes the mesh the Delaunay triangulation.
void checkHull(const Engine& e, StatisticsState& s) {
    s.hullDents.clear();
    s.hullGaps.clear();
    s.hullReport.clear();
    const Mesh& m = e.mesh();
    const bool running = e.showsVirtual();
    auto real = [&](std::int32_t t) { return !running || !e.isVirtualTriangle(t); };
    std::unordered_map<std::int32_t, std::int32_t>
        nextOnHull;  // boundary edge a -> b (interior on the left)
    std::vector<std::uint8_t> used(static_cast<std::size_t>(m.numVertices()), 0);
    std::int64_t triangles = 0, boundary = 0;
    bool pinched = false;
    for (std::int32_t t = 0; t < m.numTriangles(); ++t) {
        if (!real(t)) continue;
        ++triangles;
        for (std::int32_t c = 3 * t; c < 3 * t + 3; ++c) {
            used[m.V[c]] = 1;
            const std::int32_t o = m.O[c];
            if (o == kNone || !real(tri(o))) {
                ++boundary;
                pinched |= !nextOnHull.emplace(m.V[next(c)], m.V[prev(c)]).second;
            }
        }
    }
    if (triangles == 0) {
        s.hullReport = "no triangles yet";
        return;
    }
    const std::int64_t n = std::count(used.begin(), used.end(), 1);
    for (const auto& [a, b] : nextOnHull) {
        const auto it = nextOnHull.find(b);
        if (it == nextOnHull.end()) continue;
        if (orient2d(m.G[a], m.G[b], m.G[it->second]) < 0) {
            s.hullDents.push_back(b);
            s.hullGaps.push_back({a, b, it->second});
        }
    }
    std::sort(s.hullDents.begin(), s.hullDents.end());
    std::sort(s.hullGaps.begin(), s.hullGaps.end(),
              [](const auto& x, const auto& y) { return x[1] < y[1]; });
    const bool euler = triangles == 2 * n - boundary - 2;
    char buf[256];
    if (pinched) {
        std::snprintf(buf, sizeof buf,
                      "boundary touches itself (a vertex with two boundary edges leaving it)");
    } else if (!s.hullDents.empty()) {
        std::snprintf(buf, sizeof buf, "hull NOT convex at %zu vertex(es), first v%d%s",
                      s.hullDents.size(), s.hullDents.front(),
                      e.options().boundary == Boundary::Super
                          ? " - the super-triangle's flaw (try boundary: exact)"
                          : "");
    } else {
        std::snprintf(buf, sizeof buf,
                      "hull convex (%lld edges); Euler %s: %lld triangles, %lld vertices",
                      static_cast<long long>(boundary), euler ? "holds" : "FAILS",
                      static_cast<long long>(triangles), static_cast<long long>(n));
    }
    s.hullReport = buf;
}

void validateNow(AppState& st) {
    StatisticsState& s = st.statistics;
    const Engine& e = st.engine;
    ValidateOptions o;
    o.maxViolations = 200;
    if (e.showsVirtual() && e.options().boundary == Boundary::Exact)
        o.firstVirtual = e.inserter().firstVirtual();
    s.violations = validate(e.mesh(), o);
    if (e.editing()) {  // a constrained edge need not be Delaunay: it is never flipped
        std::erase_if(s.violations, [&](const Violation& v) {
            return v.kind == Violation::Kind::NotDelaunay && e.editor()->isConstrained(v.corner);
        });
    }
    checkHull(e, s);
    s.validatedVersion = e.version();
}

// Between Split and Inserted the new vertex's edges are still being tested: some are not
// Delaunay yet, and that is expected.
bool midInsertion(const Engine& e) {
    if (e.editing()) {  // an edit's flips to come
        const Editor& ed = *e.editor();
        return ed.position() < ed.editEnd(ed.current().index);
    }
    const Op* op = e.current();
    if (op && e.repairs())
        return op->type != OpType::Finalize;  // the flip algorithm's tests to come
    return op && !endsInsertion(op->type) && op->type != OpType::Finalize;
}

}  // namespace

const RunCounts& UpdateRunCounts(AppState& st) {
    if (!st.engine.batch()) countOps(st.statistics.counts, st.engine);
    return st.statistics.counts;
}

namespace {

// validate() after every change: it costs about 40 ns a corner, so every frame of a running
// animation only for small meshes; larger ones when the run pauses or steps by hand.
void autoValidate(AppState& st) {
    const StatisticsState& s = st.statistics;
    constexpr std::int32_t kWhileRunning = 60000;
    const std::int32_t corners = st.engine.mesh().numCorners();
    if (s.autoValidate && s.validatedVersion != st.engine.version() &&
        corners <= StatisticsState::kAutoValidateCorners &&
        (corners <= kWhileRunning || !st.run.running)) {
        validateNow(st);
    }
}

}  // namespace

void updateStatistics(AppState& st) {
    StatisticsState& s = st.statistics;
    s.frameMs.push_back(ImGui::GetIO().DeltaTime * 1000.0f);
    if (s.frameMs.size() > StatisticsState::kFrames) s.frameMs.erase(s.frameMs.begin());
    autoValidate(st);
}

namespace {

// The edges the canvas marks as under test or still to test: mid-insertion they keep that look
// (a violation there is the test to come).
bool markedByTheCanvas(const Engine& e, std::int32_t a, std::int32_t b) {
    const Mesh& m = e.mesh();
    std::vector<VertexEdge> edges;
    for (const Engine::QueuedTest& q : e.pendingTests()) edges.push_back(q.edge);
    if (const Op* op = e.current();
        op && op->type == OpType::InCircleTest && op->a >= 0 && op->a < m.numCorners())
        edges.push_back({m.V[next(op->a)], m.V[prev(op->a)]});
    return std::any_of(edges.begin(), edges.end(), [&](const VertexEdge& q) {
        return (q.a == a && q.b == b) || (q.a == b && q.b == a);
    });
}

// A dashed segment, at most ~300 dashes however far it runs off the canvas.
void DrawDashes(ImDrawList* dl, ImVec2 a, ImVec2 b, ImU32 col, float w) {
    const float dx = b.x - a.x, dy = b.y - a.y, len = std::hypot(dx, dy);
    if (!(len > 1e-3f)) return;
    const float period = std::max(14.0f, len / 300), dash = period * 0.6f;
    for (float t = 0; t < len; t += period) {
        const float e = std::min(len, t + dash);
        dl->AddLine(ImVec2(a.x + dx * t / len, a.y + dy * t / len),
                    ImVec2(a.x + dx * e / len, a.y + dy * e / len), col, w);
    }
}

}  // namespace

void DrawViolationOverlay(AppState& st) {
    const StatisticsState& s = st.statistics;
    if (!st.overlays.violations) return;
    autoValidate(st);  // the mesh may have changed since the frame began (a lesson's stop)
    if (s.validatedVersion != st.engine.version()) return;
    if (s.violations.empty() && s.hullDents.empty()) return;
    const Mesh& m = st.engine.mesh();
    const View& view = st.view;
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->PushClipRect(toIm(view.origin), toIm(view.origin + view.size), true);
    const bool expected =
        midInsertion(st.engine) &&
        std::all_of(s.violations.begin(), s.violations.end(),
                    [](const Violation& v) { return v.kind == Violation::Kind::NotDelaunay; });
    const Mark mark = expected ? Mark::NotYetDelaunay : Mark::Violation;
    const ImU32 col = s.violations.empty() ? lookOf(mark).colour : useLook(st, mark);
    const float w = (st.presentation ? 7.0f : 5.0f) * (expected ? 0.6f : 1.0f);
    const Engine& e = st.engine;
    auto drawable = [&](std::int32_t v) {
        return v >= 0 && v < m.numVertices() &&
               (!e.showsVirtual() || !e.isVirtual(v) || e.options().boundary == Boundary::Super);
    };
    for (const Violation& v : s.violations) {
        const std::int32_t c = v.corner;
        if (c < 0 || c >= m.numCorners()) continue;
        if (!canvasHasRoom(st, dl, 120)) break;
        const std::int32_t a = m.V[next(c)], b = m.V[prev(c)];
        if (drawable(a) && drawable(b) && !(expected && markedByTheCanvas(st.engine, a, b)))
            dl->AddLine(toIm(view.toScreen(m.G[a])), toIm(view.toScreen(m.G[b])), col, w);
        float x = 0, y = 0;
        if (v.kind == Violation::Kind::NotDelaunay && drawable(m.V[c])) {
            // Around the vertex that lies inside the circle across the edge.
            dl->AddCircle(toIm(view.toScreen(m.G[m.V[c]])), st.presentation ? 13.0f : 11.0f, col, 0,
                          3);
        } else if (cornerAnchor(st, c, x, y)) {
            dl->AddCircle(ImVec2(x, y), 14, col, 0, 3);
        }
    }
    // Each dent: the triangle the mesh misses there, shaded, and the hull edge that closes it,
    // dashed (no edge of the mesh); the dent's vertex keeps its label clear.
    for (const auto& [a, b, c] : s.hullGaps) {
        if (!canvasHasRoom(st, dl, 100)) break;
        if (!drawable(a) || !drawable(b) || !drawable(c)) continue;
        const ImVec2 pa = toIm(view.toScreen(m.G[a])), pb = toIm(view.toScreen(m.G[b])),
                     pc = toIm(view.toScreen(m.G[c]));
        dl->AddTriangleFilled(pa, pb, pc, useLook(st, Mark::HullDent));
        DrawDashes(dl, pa, pc, useLook(st, Mark::HullEdgeMissing), st.presentation ? 3.0f : 2.0f);
    }
    dl->PopClipRect();
}

namespace {

// The next widget of this width on the same row when it fits in the column, else on a new row.
void SameLineIfFits(float nextWidth) {
    const float right = ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + nextWidth;
    if (right <= ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x) ImGui::SameLine();
}

float CheckboxWidth(const char* label) {
    return ImGui::GetFrameHeight() + ImGui::GetStyle().ItemInnerSpacing.x +
           ImGui::CalcTextSize(label).x;
}

void ColouredWrapped(ImVec4 colour, const char* text) {
    ImGui::PushStyleColor(ImGuiCol_Text, colour);
    ImGui::TextWrapped("%s", text);
    ImGui::PopStyleColor();
}

const ImVec4 kGood(0.05f, 0.45f, 0.15f, 1), kBad(0.8f, 0.1f, 0.1f, 1),
    kExpected(0.7f, 0.4f, 0.0f, 1);

// The check's controls: automatic or by hand, and whether the canvas shows what it found.
void CheckControls(AppState& st) {
    StatisticsState& s = st.statistics;
    ImGui::TextUnformatted("Checks of the current mesh (exact)");
    if (slideMode(st)) return;  // a slide shows what they found, not how to run them
    ImGui::Checkbox("after every change", &s.autoValidate);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("validate() after each step, for meshes up to %d corners",
                          StatisticsState::kAutoValidateCorners);
    SameLineIfFits(ImGui::CalcTextSize("Validate now").x + 2 * ImGui::GetStyle().FramePadding.x);
    if (ImGui::Button("Validate now")) validateNow(st);
    RecordItem(st, "validate-now");
    SameLineIfFits(CheckboxWidth("show on canvas"));
    ImGui::Checkbox("show on canvas", &st.overlays.violations);
}

// The violations, one line each (click: select the corner; hover: the message).
void ViolationList(AppState& st) {
    const StatisticsState& s = st.statistics;
    const float listH = ImGui::GetTextLineHeightWithSpacing() *
                        static_cast<float>(std::min<std::size_t>(s.violations.size(), 8) + 1);
    ImGui::BeginChild("##violations", ImVec2(0, listH), true);
    for (std::size_t i = 0; i < s.violations.size(); ++i) {
        const Violation& v = s.violations[i];
        ImGui::PushID(static_cast<int>(i));
        const std::string line =
            std::string(toString(v.kind)) + " at corner " + std::to_string(v.corner);
        if (ImGui::Selectable(line.c_str(), st.selection.corner == v.corner)) {
            st.select(v.corner);
            st.selection.jumpToCorner = v.corner;
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", v.message.c_str());
        ImGui::PopID();
    }
    ImGui::EndChild();
}

// validate() and the hull check, with the violations listed.
void ShowChecks(AppState& st) {
    const Engine& e = st.engine;
    const StatisticsState& s = st.statistics;
    CheckControls(st);
    if (s.validatedVersion != e.version()) {
        ImGui::PushTextWrapPos(0);
        ImGui::TextDisabled("not checked at this step%s",
                            e.mesh().numCorners() > StatisticsState::kAutoValidateCorners
                                ? " (large mesh: press Validate now)"
                                : "");
        ImGui::PopTextWrapPos();
        return;
    }
    const bool expected = midInsertion(e);
    if (s.violations.empty()) {
        ColouredWrapped(kGood,
                        "validate(): every invariant holds (O symmetric, CCW, locally "
                        "Delaunay)");
    } else {
        const bool onlyDelaunay =
            std::all_of(s.violations.begin(), s.violations.end(),
                        [](const Violation& v) { return v.kind == Violation::Kind::NotDelaunay; });
        const ImVec4 col = expected && onlyDelaunay ? kExpected : kBad;
        char buf[96];
        std::snprintf(buf, sizeof buf, "validate(): %zu violation%s%s", s.violations.size(),
                      s.violations.size() == 1 ? "" : "s",
                      s.violations.size() >= 200 ? " (first 200)" : "");
        ColouredWrapped(col, buf);
        if (expected && onlyDelaunay)
            ColouredWrapped(col, e.repairs() ? "expected while the flip algorithm runs: these "
                                               "edges are still to be tested and flipped"
                                             : "expected mid-insertion: these edges are still to "
                                               "be tested and flipped");
    }
    const bool hullBad = !s.hullDents.empty() || s.hullReport.find("FAILS") != std::string::npos ||
                         s.hullReport.find("touches") != std::string::npos;
    ColouredWrapped(hullBad ? kBad : kGood, s.hullReport.c_str());
    if (!s.violations.empty()) ViolationList(st);
}

// The run's counts, the same in a batch run (the inserter's) and a stepped one (the journal's).
struct Totals {
    std::int64_t flips, steps, tests, inserted, duplicates, virtualTriangles;
};

Totals runTotals(AppState& st) {
    const Engine& e = st.engine;
    const Inserter& ins = e.inserter();
    const bool batch = e.batch();
    const RunCounts& c = UpdateRunCounts(st);
    const InsertStats& bs = ins.stats();
    Totals t{batch ? bs.flips : c.flips,
             batch ? bs.walkSteps : c.walkSteps,
             batch ? bs.inCircleTests : c.inCircleTests,
             batch ? bs.inserted : c.inserted,
             batch ? bs.duplicates : c.duplicates,
             0};
    if (e.showsVirtual()) {
        for (std::int32_t k = 0; k < e.mesh().numTriangles(); ++k)
            t.virtualTriangles += e.isVirtualTriangle(k);
    }
    return t;
}

void CountRow(const char* name, const std::string& value) {
    ImGui::TableNextRow();
    ImGui::TableSetColumnIndex(0);
    ImGui::TextUnformatted(name);
    ImGui::TableSetColumnIndex(1);
    ImGui::TextWrapped("%s", value.c_str());  // wraps at the column: never wider than the panel
}

std::string perInsertion(std::int64_t total, std::int64_t per) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%lld  (%.2f per insertion", static_cast<long long>(total),
                  per > 0 ? static_cast<double>(total) / static_cast<double>(per) : 0.0);
    return buf;
}

// Points, triangles, flips, walk steps, in-circle tests, splits and exact fallbacks.
void CountsTable(AppState& st) {
    const Engine& e = st.engine;
    const RunCounts& c = st.statistics.counts;
    const bool batch = e.batch();
    const Totals t = runTotals(st);
    if (!ImGui::BeginTable("##counts", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV))
        return;
    ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthFixed);
    ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthStretch);
    auto num = [](std::int64_t v) { return std::to_string(v); };
    CountRow("points", pointCountsText(e));
    CountRow("triangles",
             num(e.mesh().numTriangles() - t.virtualTriangles) +
                 (t.virtualTriangles ? "  (+" + num(t.virtualTriangles) + " virtual)" : ""));
    CountRow("flips", perInsertion(t.flips, t.inserted) +
                          (!batch && c.flipsNow ? ", " + num(c.flipsNow) + " in this one)" : ")"));
    CountRow("walk steps",
             perInsertion(t.steps, t.inserted > 0 ? t.inserted + t.duplicates : 0) + ")");
    if (!batch && c.locates > 0) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "%lld of %lld (%.0f%%)", static_cast<long long>(c.hits),
                      static_cast<long long>(c.locates),
                      100.0 * static_cast<double>(c.hits) / static_cast<double>(c.locates));
        CountRow("0-step locates", buf);
    }
    CountRow("in-circle tests", num(t.tests));
    if (!batch)
        CountRow("splits", num(c.splits) + " in triangles, " + num(c.edgeSplits) + " on edges");
    const std::array<std::uint64_t, 2> exact = e.exactFallbacks();
    CountRow("exact fallbacks", num(static_cast<std::int64_t>(exact[0])) + " orient2d, " +
                                    num(static_cast<std::int64_t>(exact[1])) + " incircle");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "Predicate calls the floating-point filter could not decide, made by this run's "
            "operations up to the current one");
    ImGui::EndTable();
}

void FlipsPlot(AppState& st) {
    const RunCounts& c = st.statistics.counts;
    if (st.engine.batch() || c.flipsPerInsertion.empty()) return;
    constexpr std::size_t kShown = 400;
    const std::size_t n = c.flipsPerInsertion.size();
    const std::size_t first = n > kShown ? n - kShown : 0;
    const float maxFlips =
        *std::max_element(c.flipsPerInsertion.begin() + static_cast<std::ptrdiff_t>(first),
                          c.flipsPerInsertion.end());
    char overlay[96];
    std::snprintf(overlay, sizeof overlay, "flips per insertion (last %zu, max %.0f)", n - first,
                  maxFlips);
    ImGui::PlotHistogram("##flips", c.flipsPerInsertion.data() + first, static_cast<int>(n - first),
                         0, overlay, 0.0f, std::max(4.0f, maxFlips * 1.15f),
                         ImVec2(ImGui::GetContentRegionAvail().x, 90));
    RecordItem(st, "flips-plot");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "Expected about 3 per insertion on average for random insertion orders (the new "
            "vertex gets about 6 edges, 3 from the split).");
}

void FrameTimes(AppState& st) {
    const StatisticsState& s = st.statistics;
    if (s.frameMs.empty()) return;
    const float mean = std::accumulate(s.frameMs.begin(), s.frameMs.end(), 0.0f) /
                       static_cast<float>(s.frameMs.size());
    const float worst = *std::max_element(s.frameMs.begin(), s.frameMs.end());
    char overlay[128];
    std::snprintf(overlay, sizeof overlay, "frame ms: mean %.1f, worst %.1f", mean, worst);
    ImGui::PlotLines("##frames", s.frameMs.data(), static_cast<int>(s.frameMs.size()), 0, overlay,
                     0.0f, std::max(40.0f, worst * 1.1f),
                     ImVec2(ImGui::GetContentRegionAvail().x, 60));
    const FrameStats& fs = st.frameStats;
    ImGui::PushTextWrapPos(0);
    ImGui::TextDisabled("mesh rebuild %.1f ms, %zu edges drawn%s, %zu ops this frame",
                        fs.meshBuildMs, fs.visibleEdges, fs.denseMesh ? " (dense raster)" : "",
                        fs.opsStepped);
    ImGui::PopTextWrapPos();
}

}  // namespace

void ShowStatistics(AppState& st) {
    ImGui::BeginChild("##statsbody", ImVec2(0, 0), false);  // scrolls when the column is short
    ImGui::BeginGroup();
    // What a debugging user looks for first: does the mesh hold its invariants at this step. A
    // slide shows the run's counts first, which its text speaks of, and the checks below them.
    if (slideMode(st)) {
        ImGui::TextUnformatted("Counts of the run");
        CountsTable(st);
        FlipsPlot(st);
        ImGui::Separator();
        ShowChecks(st);
    } else {
        ShowChecks(st);
        ImGui::Separator();
        CountsTable(st);
        FlipsPlot(st);
        FrameTimes(st);
    }
    ImGui::EndGroup();
    // Not clipped (unlike RecordItem): tests check that nothing is wider than the panel.
    const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
    const ImVec2 wp = ImGui::GetWindowPos();
    st.itemRects["statistics-content"] = {lo.x, lo.y, hi.x, hi.y};
    st.itemRects["statistics-panel"] = {wp.x, wp.y, wp.x + ImGui::GetWindowWidth(),
                                        wp.y + ImGui::GetWindowHeight()};
    ImGui::EndChild();
}

}  // namespace dlab::ui
